//! The game's logging in the real mGBA core: as a player runs it (no key held at power-on) it
//! writes no per-frame `player` or `render` line, only the recording's `input` lines and a
//! `rate` line about every second; with Start held at power-on it writes both per-frame lines
//! for every frame drawn, which the other emulator tests, the soak and `cargo bench-tick` read.

mod common;

use common::*;
use portalcast_harness::{Emulator, KeyScript};

/// Long enough for a few `rate` lines (one per 60 VBlanks) and some drawn frames.
const FRAMES: u32 = 200;

/// Plays `assets/demo/play.keys` (what `cargo play` presses) for [`FRAMES`] frames.
fn play_demo(script: &KeyScript) -> Emulator {
    let mut emulator = boot();
    for frame in 0..FRAMES {
        emulator.set_keys(script.keys_at(frame));
        emulator
            .run_frame()
            .unwrap_or_else(|error| panic!("frame {frame}: {error}"));
    }
    emulator
}

fn demo_script() -> KeyScript {
    KeyScript::load(&portalcast_xtask::workspace_root().join("assets/demo/play.keys"))
        .unwrap_or_else(|error| panic!("{error}"))
}

/// Frames drawn, added up over the `rate` lines.
fn frames_in_rate_lines(emulator: &Emulator) -> u64 {
    lines_starting(emulator, "rate ")
        .iter()
        .map(|line| number(line, "frames"))
        .sum()
}

#[test]
fn by_default_the_game_writes_no_per_frame_lines() {
    let emulator = play_demo(&demo_script());
    let per_frame: Vec<String> = emulator
        .debug_lines()
        .into_iter()
        .filter(|line| line.starts_with("player ") || line.starts_with("render "))
        .map(str::to_owned)
        .collect();
    assert!(
        per_frame.is_empty(),
        "the default game wrote per-frame lines, e.g. {:?}",
        per_frame.first()
    );
    let start = lines_starting(&emulator, "play start ");
    assert_eq!(number(&start[0], "frame_lines"), 0, "{}", start[0]);
    // It still draws, records the buttons and reports its frame rate.
    let rates = lines_starting(&emulator, "rate ");
    assert!(rates.len() >= 2, "{rates:?}");
    assert!(frames_in_rate_lines(&emulator) >= 10, "{rates:?}");
    for line in &rates {
        assert_eq!(number(line, "mean_frame_lines_cycles"), 0, "{line}");
        assert!(field(line, "fps").is_some(), "{line}");
    }
    assert!(!lines_starting(&emulator, "input vblank=").is_empty());
}

#[test]
fn start_held_at_power_on_switches_the_per_frame_lines_on() {
    let emulator = play_demo(&with_frame_lines(&demo_script()));
    let start = lines_starting(&emulator, "play start ");
    assert_eq!(number(&start[0], "frame_lines"), 1, "{}", start[0]);
    let boot = lines_starting(&emulator, "input boot ");
    assert_eq!(boot.len(), 1, "the boot keys are recorded once");
    assert_eq!(number(&boot[0], "keys"), u64::from(FRAME_LINES_KEY.bits()));
    // One `player` and one `render` line for every frame drawn, numbered from 0.
    let players = lines_starting(&emulator, "player ");
    let renders = lines_starting(&emulator, "render ");
    assert!(players.len() >= 10, "only {} player lines", players.len());
    assert!(renders.len() + 1 >= players.len() && renders.len() <= players.len());
    for (index, line) in renders.iter().enumerate() {
        assert_eq!(number(line, "frame"), index as u64, "{line}");
    }
    // The rate lines count the same frames and what writing them cost.
    let rates = lines_starting(&emulator, "rate ");
    assert!(frames_in_rate_lines(&emulator) <= renders.len() as u64);
    assert!(rates
        .iter()
        .all(|line| number(line, "mean_frame_lines_cycles") > 0));
    // The game saw no Start: the ROM waited for it to be let go, so the menu never opened.
    assert!(players.iter().all(|line| field(line, "menu") == Some("-1")));
}
