//! Mode 4 with two pages, BG2's affine step per resolution, the palette, and VBlank waits through
//! the VBlank interrupt and the BIOS `IntrWait`.
//!
//! The display owns only its bits of DISPCNT (the mode, BG2 and the page shown): a flip leaves
//! the others as they are, so a game may show hardware sprites or windows over the 3D view
//! ([`Display::with_control`]).

use crate::frame::Resolution;
use gba::bios::VBlankIntrWait;
use gba::fixed::{i16fx8, i32fx8};
use gba::interrupts::IrqBits;
use gba::mmio::{BG2PA, BG2PB, BG2PC, BG2PD, BG2X, BG2Y, BG_PALETTE, DISPCNT, DISPSTAT, IE, IME};
use gba::prelude::{Color, DisplayControl, DisplayStatus, VideoMode};

/// Owns the display: which page is shown and at which resolution.
pub struct Display {
    shown_page: usize,
    shown_resolution: Resolution,
}

impl Display {
    /// Turns on Mode 4 with page 0 current, the VBlank interrupt armed, and `resolution`'s
    /// affine step, but BG2 hidden behind a black backdrop until the first flip: at power-on
    /// VRAM and the palette hold whatever the chips woke up with, and the first frame takes
    /// several display frames to draw.
    pub fn start(resolution: Resolution) -> Display {
        DISPSTAT.write(DisplayStatus::new().with_irq_vblank(true));
        IE.write(IrqBits::VBLANK);
        IME.write(true);
        // The backdrop is BG palette entry 0; the scenes load their palettes later.
        BG_PALETTE.index(0).write(Color(0));
        let display = Display {
            shown_page: 0,
            shown_resolution: resolution,
        };
        // The whole register once: at power-on it may hold anything (forced blank included);
        // from here on only the display's own bits change.
        DISPCNT.write(DisplayControl::new());
        display.show(resolution, false);
        display
    }

    /// The page on screen (0 at 0x0600_0000, 1 at 0x0600_A000).
    pub fn shown_page(&self) -> usize {
        self.shown_page
    }

    /// The resolution BG2 shows the page at.
    pub fn shown_resolution(&self) -> Resolution {
        self.shown_resolution
    }

    /// Loads all 256 BG palette entries.
    pub fn set_palette(&self, palette: &[u16; 256]) {
        for (index, colour) in palette.iter().enumerate() {
            BG_PALETTE.index(index).write(Color(*colour));
        }
    }

    /// Sleeps until the next VBlank starts, then shows the back page at `resolution`. The affine
    /// registers and DISPCNT are written inside VBlank, so the new page and its scale appear
    /// together on the next frame.
    pub fn flip_at_vblank(&mut self, resolution: Resolution) {
        VBlankIntrWait();
        self.shown_page ^= 1;
        self.shown_resolution = resolution;
        self.show(resolution, true);
    }

    /// Changes DISPCNT's bits that are not the display's (the OBJ layer and its VRAM mapping,
    /// windows, forced blank) by `change`, applied to the register as it is now; the mode, BG2
    /// and the page shown stay the display's. Every later flip keeps the game's bits. To show
    /// hardware sprites over the view: `display.with_control(|c|
    /// c.with_show_obj(true).with_obj_vram_1d(true))`; in Mode 4 their tiles are those from
    /// 0x0601_4000 (`hw::memory` says which of them the engine leaves free).
    pub fn with_control(&mut self, change: impl FnOnce(DisplayControl) -> DisplayControl) {
        let now = DISPCNT.read();
        let changed = change(now);
        DISPCNT.write(
            changed
                .with_video_mode(VideoMode::_4)
                .with_show_bg2(now.show_bg2())
                .with_show_frame1(self.shown_page == 1),
        );
    }

    /// DISPCNT as it is now.
    pub fn control(&self) -> DisplayControl {
        DISPCNT.read()
    }

    /// Sleeps until the next VBlank starts, changing nothing.
    pub fn wait_vblank(&self) {
        VBlankIntrWait();
    }

    fn show(&self, resolution: Resolution, with_bg2: bool) {
        BG2PA.write(i16fx8::from_bits(resolution.bg2_pa()));
        BG2PB.write(i16fx8::from_bits(0));
        BG2PC.write(i16fx8::from_bits(0));
        BG2PD.write(i16fx8::from_bits(resolution.bg2_pd()));
        BG2X.write(i32fx8::from_bits(0));
        BG2Y.write(i32fx8::from_bits(0));
        DISPCNT.write(
            DISPCNT
                .read()
                .with_video_mode(VideoMode::_4)
                .with_show_bg2(with_bg2)
                .with_show_frame1(self.shown_page == 1),
        );
    }
}
