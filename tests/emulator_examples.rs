//! The examples (`examples/*`, each a game crate of its own, as a game outside this repository
//! is) build into `.gba` files that run in the real mGBA core: the minimal one draws its room,
//! and the HUD one shows its hardware sprites over the 3D view while its game logic runs (a
//! scripted walk takes the key, which leaves the map, and opens the gate with it).

mod common;

use common::*;
use portalcast::frame::{PAGE_HEIGHT, PAGE_WIDTH};
use portalcast::text::glyph_lit;
use portalcast_harness::{Emulator, KeyScript, Keys};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Builds `examples/NAME` (release, for the GBA, as `cargo run --release` in it does) and
/// returns its `.gba`. The examples share one target directory, under this repository's, so
/// `core` is built once for all of them.
fn build_example(name: &str) -> PathBuf {
    let root = portalcast_xtask::workspace_root();
    let target = root.join("target").join("examples");
    let status = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()))
        .args(["build", "--release", "--target-dir"])
        .arg(&target)
        .current_dir(root.join("examples").join(name))
        .env_remove("CARGO_BUILD_TARGET")
        .env_remove("RUSTFLAGS")
        .env_remove("CARGO_ENCODED_RUSTFLAGS")
        .status()
        .unwrap_or_else(|error| panic!("building examples/{name}: {error}"));
    assert!(
        status.success(),
        "building examples/{name} failed ({status})"
    );
    let elf = target
        .join(portalcast_xtask::ROM_TARGET)
        .join("release")
        .join(name);
    let gba = elf.with_extension("gba");
    portalcast_xtask::elf_to_gba(&elf, &gba).unwrap_or_else(|error| panic!("{error}"));
    gba
}

fn load(gba: &Path) -> Emulator {
    Emulator::load(gba).unwrap_or_else(|error| panic!("{error}"))
}

/// The lines of the example's log that start with `prefix`.
fn lines_starting<'e>(emulator: &'e Emulator, prefix: &str) -> Vec<&'e str> {
    emulator
        .debug_lines()
        .into_iter()
        .filter(|line| line.starts_with(prefix))
        .collect()
}

#[test]
fn the_minimal_example_draws_its_room() {
    let mut emulator = load(&build_example("minimal"));
    emulator
        .run_frames(240)
        .unwrap_or_else(|error| panic!("{error}"));
    let lines = lines_starting(&emulator, "game frame=");
    assert!(lines.len() >= 3, "{:?}", emulator.debug_lines());
    assert!(
        lines.iter().all(|line| number(line, "columns") == 120),
        "every column of the 120-wide view shows a wall: {lines:?}"
    );
    emulator
        .save_frame_png(&screenshot_dir().join("example-minimal.png"))
        .unwrap_or_else(|error| panic!("{error}"));
}

/// Where the HUD's sprites light a pixel for `text`: (x, y, shadow) for each, as the example
/// draws its characters (src/main.rs: the font doubled from (1, 2) in an 8×16 sprite at
/// (4 + 8·i, 4), its shadow a pixel down and right).
fn hud_pixels(text: &[u8]) -> Vec<(usize, usize, bool)> {
    let mut pixels = Vec::new();
    for (slot, &character) in text.iter().enumerate() {
        for y in 0..16 {
            for x in 0..8 {
                let lit = |dx: usize, dy: usize| {
                    x >= dx && y >= dy && glyph_lit(character, (x - dx) / 2, (y - dy) / 2)
                };
                let (screen_x, screen_y) = (4 + 8 * slot + x, 4 + y);
                if lit(1, 2) {
                    pixels.push((screen_x, screen_y, false));
                } else if lit(2, 3) {
                    pixels.push((screen_x, screen_y, true));
                }
            }
        }
    }
    pixels
}

/// How many of the pixels `text`'s HUD would light show the HUD's colours (white text, black
/// shadow), and how many it lights.
fn hud_shown(emulator: &Emulator, text: &[u8]) -> (usize, usize) {
    let frame = shown_frame_rgb5(emulator);
    let pixels = hud_pixels(text);
    let matching = pixels
        .iter()
        .filter(|&&(x, y, shadow)| {
            assert!(x < PAGE_WIDTH && y < PAGE_HEIGHT);
            frame[y * PAGE_WIDTH + x] == if shadow { [0, 0, 0] } else { [31, 31, 31] }
        })
        .count();
    (matching, pixels.len())
}

#[test]
fn the_hud_example_shows_sprites_over_the_view_and_the_key_opens_the_gate() {
    let mut emulator = load(&build_example("hud"));
    emulator
        .run_frames(60)
        .unwrap_or_else(|error| panic!("{error}"));
    let (matching, lit) = hud_shown(&emulator, b"KEY 0");
    assert_eq!(matching, lit, "the HUD's `KEY 0` sprites over the view");
    emulator
        .save_frame_png(&screenshot_dir().join("example-hud-start.png"))
        .unwrap_or_else(|error| panic!("{error}"));

    // Straight ahead: over the key, to the gate, which opens, and into the vault.
    let walk = KeyScript::new().hold(0..=400, Keys::UP);
    emulator
        .run_script(&walk, 420)
        .unwrap_or_else(|error| panic!("{error}"));
    let lines = lines_starting(&emulator, "hud frame=");
    let first = |key: &str| {
        lines
            .iter()
            .position(|line| number(line, key) == 1)
            .unwrap_or_else(|| panic!("no line with {key}=1: {lines:?}"))
    };
    assert!(
        first("key") <= first("gate"),
        "the key before the gate: {lines:?}"
    );
    let last = lines.last().expect("the example's lines");
    assert_eq!(
        number(last, "sector"),
        2,
        "the walk ends in the vault: {last}"
    );
    let (matching, lit) = hud_shown(&emulator, b"OPEN");
    assert_eq!(matching, lit, "the HUD's `OPEN`");
    let (old, _) = hud_shown(&emulator, b"KEY 0");
    assert!(old < lit, "the HUD changed");
    emulator
        .save_frame_png(&screenshot_dir().join("example-hud-vault.png"))
        .unwrap_or_else(|error| panic!("{error}"));
}
