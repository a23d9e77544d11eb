//! The generated maps of issue 16 (`portalcast_xtask::generated_maps`: cave cells, a 48×48
//! maze, a castle of slanted corridors with long sightlines) built into a ROM from a directory
//! of their own (what `PORTALCAST_ASSETS=/dir cargo rom` does) and flown through by
//! the ROM's bench scene (R held at power-on): every map at every resolution. No frame may panic,
//! and no frame may take longer than the soak's bound, [`FRAME_CYCLES_BOUND`] (16 display
//! frames): the stall these maps once showed (4.5 million cycles).
//!
//! The ROM is built once per test process in its own target directory (`target/rom-generated`,
//! from `target/generated-maps`).

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use portalcast_xtask::bench_log::{self, Run};
use portalcast_xtask::generated_maps;

/// The soak's bound on one frame (`tests/emulator_soak.rs`): 16 display frames.
const FRAME_CYCLES_BOUND: u64 = 16 * 280_896;

/// The ROM of the generated maps, built once per test process (in `target/rom-generated`,
/// which `cargo bench-report` builds too).
fn generated_rom() -> &'static Path {
    static ROM: OnceLock<PathBuf> = OnceLock::new();
    ROM.get_or_init(|| {
        generated_maps::build_generated_rom().unwrap_or_else(|error| panic!("{error}"))
    })
}

#[test]
fn generated_maps_fly_through_in_the_rom_within_the_soak_bound() {
    let log = common::bench_scene_log(generated_rom());
    let runs: Vec<Run> =
        bench_log::bench_runs(&log.join("\n")).unwrap_or_else(|problem| panic!("{problem}"));
    let mut worst: BTreeMap<(&str, String), (u64, u32)> = BTreeMap::new();
    for run in &runs {
        for frame in &run.frames {
            let entry = worst
                .entry((run.map.as_str(), run.label()))
                .or_insert((0, 0));
            if frame.cycles > entry.0 {
                *entry = (frame.cycles, frame.index);
            }
        }
    }
    println!("map     settings  worst cycles  frame");
    for ((map, resolution), (cycles, frame)) in &worst {
        println!("{map:<7} {resolution}  {cycles:>12}  {frame}");
    }
    for map in generated_maps::generated_maps() {
        assert!(
            worst.keys().any(|(name, _)| *name == map.name),
            "{}: no bench frames",
            map.name
        );
    }
    let over: Vec<String> = worst
        .iter()
        .filter(|(_, (cycles, _))| *cycles > FRAME_CYCLES_BOUND)
        .map(|((map, resolution), (cycles, frame))| {
            format!("{map} {resolution} frame {frame}: {cycles}")
        })
        .collect();
    assert!(
        over.is_empty(),
        "frames over {FRAME_CYCLES_BOUND} cycles:\n{}",
        over.join("\n")
    );
}
