//! A game shares the machine with the engine, in the real mGBA core (the ROM's machine check:
//! L, R and A held at power-on, crates/rom/src/main.rs): its own interrupt handler runs after the engine's
//! on every interrupt, the OBJ-layer bits it sets in DISPCNT survive the display's flips, and a
//! panic shows its message on the screen and logs it at level Fatal.

mod common;

use common::*;
use portalcast::frame::{PAGE_HEIGHT, PAGE_WIDTH};
use portalcast::text::{TextScreen, PANIC_BACKGROUND, PANIC_TEXT, PANIC_TITLE};
use portalcast_harness::{HarnessError, Keys, LogLevel};
use std::fmt::Write;

/// Frames the check may take to panic (it flips 30 times, one flip a VBlank).
const FRAME_LIMIT: u32 = 300;

#[test]
fn a_game_chains_interrupts_keeps_its_display_bits_and_sees_its_panic() {
    let mut emulator = boot();
    emulator.set_keys(Keys::L | Keys::R | Keys::A);
    let mut frames = 0;
    let panic = loop {
        assert!(frames < FRAME_LIMIT, "no panic after {FRAME_LIMIT} frames");
        match emulator.run_frame() {
            Ok(()) => frames += 1,
            Err(HarnessError::RomPanicked { message, .. }) => break message,
            Err(error) => panic!("{error}"),
        }
    };

    let lines = emulator.debug_lines();
    let machine = lines
        .iter()
        .find(|line| line.starts_with("machine "))
        .unwrap_or_else(|| panic!("no `machine` line before the panic: {lines:?}"));
    for bit in ["mode4", "bg2", "obj", "obj_1d"] {
        assert_eq!(
            number(machine, bit),
            1,
            "DISPCNT's {bit} after the flips: {machine}"
        );
    }
    let flips = number(machine, "flips");
    let chained = number(machine, "chained_vblanks");
    assert_eq!(
        chained,
        number(machine, "sampled_vblanks"),
        "the game's handler saw every VBlank the engine's did: {machine}"
    );
    assert!(
        chained >= flips,
        "{flips} flips need as many VBlanks: {machine}"
    );

    let message = panic.trim_start_matches(':').trim_start();
    let panic_line = emulator
        .log_lines()
        .iter()
        .find(|line| line.is_debug_print() && line.text.starts_with("panic: "))
        .expect("the panic's log line");
    assert_eq!(panic_line.level, LogLevel::Fatal, "{panic_line:?}");
    assert!(
        message.starts_with("panicked at crates/rom/src/main.rs:")
            && message.ends_with("the machine check's deliberate panic, after 30 flips"),
        "{message}"
    );

    // The screen is drawn before the Fatal line: the next frame shows all of it.
    emulator
        .run_frame()
        .unwrap_or_else(|error| panic!("{error}"));
    let mut screen = TextScreen::new();
    write!(screen, "{PANIC_TITLE}\n\n{message}").unwrap();
    let rgb5 = |colour: u16| {
        [
            (colour & 31) as u8,
            (colour >> 5 & 31) as u8,
            (colour >> 10 & 31) as u8,
        ]
    };
    let expected: Vec<[u8; 3]> = (0..PAGE_HEIGHT)
        .flat_map(|y| (0..PAGE_WIDTH).map(move |x| (x, y)))
        .map(|(x, y)| {
            rgb5(if screen.lit(x, y) {
                PANIC_TEXT
            } else {
                PANIC_BACKGROUND
            })
        })
        .collect();
    let shown = shown_frame_rgb5(&emulator);
    emulator
        .save_frame_png(&screenshot_dir().join("panic-screen.png"))
        .unwrap_or_else(|error| panic!("{error}"));
    let differing = shown.iter().zip(&expected).filter(|(a, b)| a != b).count();
    assert_eq!(
        differing, 0,
        "{differing} pixels of the panic screen differ from its host rendering (target/screenshots/panic-screen.png)"
    );
    assert!(
        expected
            .iter()
            .filter(|&&pixel| pixel == rgb5(PANIC_TEXT))
            .count()
            > 1000,
        "the message shows as text"
    );
}
