//! Cold boot: a real GBA powers on with arbitrary contents in EWRAM, IWRAM, VRAM, the palette
//! and OAM, where mGBA starts with zeros. The ROM must not depend on either: the play demo
//! (`assets/demo/play.keys`), started on mGBA's zeroed memory, on memory filled with random
//! bytes and on memory filled with ones, must print the same lines (poses and cycle counts
//! included) and show the same frames, from the first frame the ROM runs in on: until its first picture is ready it shows a
//! black backdrop, never the power-on contents of VRAM. The game's per-frame lines are switched
//! on (Start held at power-on), so the poses of every frame are compared too.

mod common;

use common::{boot, with_frame_lines};
use portalcast_harness::{Emulator, KeyScript};
use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};

/// Ten seconds of the demo: the hall, the courtyard, the menu.
const FRAMES: u32 = 600;

/// Memory a cold boot leaves undefined, as (what, address, bytes). The top 256 bytes of IWRAM
/// are left out: the BIOS sets them up (interrupt vector, flags, its stacks) before the
/// cartridge runs.
const UNDEFINED_AT_POWER_ON: [(&str, u32, usize); 5] = [
    ("EWRAM", 0x0200_0000, 0x4_0000),
    ("IWRAM", 0x0300_0000, 0x7F00),
    ("palette", 0x0500_0000, 0x400),
    ("VRAM", 0x0600_0000, 0x1_8000),
    ("OAM", 0x0700_0000, 0x400),
];

/// What a run shows: the ROM's lines, and a hash of every frame after the BIOS's.
struct Run {
    lines: Vec<String>,
    frames: Vec<u64>,
}

fn play_demo(mut emulator: Emulator) -> Run {
    let script = with_frame_lines(
        &KeyScript::load(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/demo/play.keys"),
        )
        .unwrap_or_else(|error| panic!("{error}")),
    );
    let mut frames = Vec::new();
    for frame in 0..FRAMES {
        emulator.set_keys(script.keys_at(frame));
        emulator
            .run_frame()
            .unwrap_or_else(|error| panic!("frame {frame}: {error}"));
        // Frame 0 is the BIOS handing over (mGBA's starts the cartridge at line 126); the
        // ROM's own display starts with frame 1.
        if frame > 0 {
            let mut hasher = DefaultHasher::new();
            emulator.frame_rgb().into_raw().hash(&mut hasher);
            frames.push(hasher.finish());
        }
    }
    Run {
        lines: emulator
            .debug_lines()
            .into_iter()
            .map(str::to_owned)
            .collect(),
        frames,
    }
}

/// The emulator booted with every undefined byte set by `fill` (its index in the region).
fn boot_on(mut fill: impl FnMut() -> u8) -> Emulator {
    let mut emulator = boot();
    for (_, address, bytes) in UNDEFINED_AT_POWER_ON {
        let noise: Vec<u8> = (0..bytes).map(|_| fill()).collect();
        emulator.write_bytes(address, &noise);
    }
    for (what, address, bytes) in UNDEFINED_AT_POWER_ON {
        let sample = emulator.read_bytes(address + bytes as u32 / 2, 16);
        assert!(
            sample.iter().any(|&byte| byte != 0),
            "{what} still reads zeros after the fill: the harness did not write it"
        );
    }
    emulator
}

#[test]
fn the_rom_behaves_the_same_on_zeroed_and_on_random_memory() {
    let zeroed = play_demo(boot());
    let mut state = 0x1234_5678_9ABC_DEF0u64;
    let random = play_demo(boot_on(|| {
        // xorshift64: cheap noise, different in every byte.
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 24) as u8
    }));
    compare(&zeroed, &random, "random");
    // Every byte 1: every flag a cleared `.bss` would hold as false reads true (the noise
    // above reads most of them as some other non-zero byte, which a flag's code may take
    // either way). The page rows' lent flag once sat in EWRAM, which the runtime does not
    // clear: on this memory the game never lent them, and its cycles differed.
    let ones = play_demo(boot_on(|| 1));
    compare(&zeroed, &ones, "all-ones");
}

/// `filled`, the demo on memory filled one way, prints the same lines and shows the same frames
/// as `zeroed`.
fn compare(zeroed: &Run, random: &Run, fill: &str) {
    assert!(
        zeroed
            .lines
            .iter()
            .filter(|l| l.starts_with("render "))
            .count()
            >= 10,
        "the demo hardly drew anything"
    );
    if let Some(index) = (0..zeroed.lines.len().max(random.lines.len()))
        .find(|&index| zeroed.lines.get(index) != random.lines.get(index))
    {
        panic!(
            "line {index} differs:\n  zeroed memory: {:?}\n  {fill} memory: {:?}",
            zeroed.lines.get(index),
            random.lines.get(index)
        );
    }
    assert_eq!(zeroed.frames.len(), random.frames.len());
    if let Some(index) = zeroed
        .frames
        .iter()
        .zip(&random.frames)
        .position(|(a, b)| a != b)
    {
        panic!(
            "frame {} differs between zeroed and {fill} memory",
            index + 1
        );
    }
    println!(
        "cold boot: {} lines and {} frames identical on zeroed and {fill} memory",
        zeroed.lines.len(),
        zeroed.frames.len()
    );
}
