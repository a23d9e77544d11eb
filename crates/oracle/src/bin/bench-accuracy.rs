//! The accuracy half of `cargo bench-report`: for every run of the ROM's bench scene (same maps,
//! settings and fly-through, from `portalcast_rom::bench` and `portalcast_rom::flight`), renders every
//! `ACCURACY_FRAME_STEP`-th frame with the engine on the host and with the oracle, and prints one
//! line per run:
//!
//! `accuracy map=NAME <settings> frames=N pixels=N surface_mismatches=N texel_mismatches=N
//! wall_edge_px=N missed_sectors=N missed_things=N holes=N`
//!
//! where the mismatch counts, missed sectors and missed things are summed over the frames and `wall_edge_px`
//! is the largest over them. The engine's frames on the host are the ROM's frames: the emulator
//! test `emulator_render` proves them identical pixel for pixel.

use portalcast::render::walk::Renderer;
use portalcast_oracle::bench_run_accuracy;
use portalcast_rom::bench::{all_runs, SettingsLabel};
use portalcast_rom::demo::render_assets;

fn main() {
    let assets = render_assets();
    let mut renderer = Renderer::new();
    for (map, settings) in all_runs() {
        let accuracy = bench_run_accuracy(&mut renderer, map, &assets, &settings);
        println!(
            "accuracy map={} {} frames={} pixels={} surface_mismatches={} texel_mismatches={} \
             wall_edge_px={} missed_sectors={} missed_things={} holes={}",
            map.name,
            SettingsLabel(&settings),
            accuracy.frames,
            accuracy.pixels,
            accuracy.surface_mismatches,
            accuracy.texel_mismatches,
            accuracy.wall_edge_px,
            accuracy.missed_sectors,
            accuracy.missed_things,
            accuracy.holes,
        );
    }
}
