//! What a panic shows: its message on screen, white on dark red, readable on hardware, and at
//! level Fatal in mGBA's log. A game's `#[panic_handler]` calls [`show`].

use core::fmt::Write;
use core::panic::PanicInfo;

use gba::fixed::{i16fx8, i32fx8};
use gba::mmio::{BG2PA, BG2PB, BG2PC, BG2PD, BG2X, BG2Y, BG_PALETTE, DISPCNT, IME};
use gba::prelude::{Color, DisplayControl, GbaCell, VideoMode};

use super::log;
use crate::frame::{PAGE_HEIGHT, PAGE_WIDTH};
use crate::text::{TextScreen, PANIC_BACKGROUND, PANIC_TEXT, PANIC_TITLE};

/// Set by the first panic: a panic while showing one only logs.
static PANICKING: GbaCell<bool> = GbaCell::new(false);

/// Shows `info` on the whole screen (Mode 4, page 0 at 240×160, over whatever the game showed),
/// then logs it at level Fatal, and stops: interrupts off, the CPU spinning. The screen comes
/// first because mGBA's frontends stop the game on the Fatal line.
pub fn show(info: &PanicInfo) -> ! {
    IME.write(false);
    if !PANICKING.read() {
        PANICKING.write(true);
        let mut screen = TextScreen::new();
        let _ = write!(screen, "{PANIC_TITLE}\n\n{info}");
        draw(&screen);
    }
    log::fatal(format_args!("panic: {info}"));
    loop {
        core::hint::spin_loop();
    }
}

fn draw(screen: &TextScreen) {
    BG_PALETTE.index(0).write(Color(PANIC_BACKGROUND));
    BG_PALETTE.index(1).write(Color(PANIC_TEXT));
    let page = 0x0600_0000 as *mut u16;
    for y in 0..PAGE_HEIGHT {
        for pair in 0..PAGE_WIDTH / 2 {
            let low = u16::from(screen.lit(2 * pair, y));
            let high = u16::from(screen.lit(2 * pair + 1, y));
            // SAFETY: page 0 of Mode 4 is 0x0600_0000..0x0600_9600, 240×160 bytes written here
            // as halfwords (VRAM takes no byte stores); nothing else runs any more.
            unsafe {
                page.add(y * PAGE_WIDTH / 2 + pair)
                    .write_volatile(low | high << 8)
            };
        }
    }
    BG2PA.write(i16fx8::from_bits(1 << 8));
    BG2PB.write(i16fx8::from_bits(0));
    BG2PC.write(i16fx8::from_bits(0));
    BG2PD.write(i16fx8::from_bits(1 << 8));
    BG2X.write(i32fx8::from_bits(0));
    BG2Y.write(i32fx8::from_bits(0));
    DISPCNT.write(
        DisplayControl::new()
            .with_video_mode(VideoMode::_4)
            .with_show_bg2(true),
    );
}
