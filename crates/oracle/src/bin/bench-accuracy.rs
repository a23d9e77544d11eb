//! The accuracy half of `cargo bench-report`: for every run of the ROM's bench scene (same maps,
//! settings and fly-through, from `portalcast::bench` and `portalcast::flight`), renders every
//! `ACCURACY_FRAME_STEP`-th frame with the engine on the host and with the oracle, and prints one
//! line per run:
//!
//! `accuracy map=NAME <settings> frames=N pixels=N surface_mismatches=N texel_mismatches=N
//! wall_edge_px=N missed_sectors=N holes=N`
//!
//! where the mismatch counts and missed sectors are summed over the frames and `wall_edge_px`
//! is the largest over them. The engine's frames on the host are the ROM's frames: the emulator
//! test `emulator_render` proves them identical pixel for pixel.

use portalcast::bench::{all_runs, SettingsLabel, ACCURACY_FRAME_STEP, FRAMES_PER_SETTING};
use portalcast::flight::Flight;
use portalcast::render::demo::render_assets;
use portalcast::render::walk::Renderer;
use portalcast_oracle::compare_with_engine;

fn main() {
    let assets = render_assets();
    let mut renderer = Renderer::new();
    for (map, settings) in all_runs() {
        let (mut frames, mut pixels, mut surface, mut texel) = (0u64, 0u64, 0u64, 0u64);
        let (mut wall_edge, mut missed, mut holes) = (0u32, 0u64, 0u64);
        let poses = Flight::new(map)
            .take(FRAMES_PER_SETTING as usize)
            .step_by(ACCURACY_FRAME_STEP as usize);
        for camera in poses {
            let result = compare_with_engine(&mut renderer, map, &assets, &camera, &settings);
            let comparison = result.comparison;
            frames += 1;
            pixels += comparison.pixels as u64;
            surface += comparison.surface_mismatches as u64;
            texel += comparison.texel_mismatches as u64;
            wall_edge = wall_edge.max(comparison.max_wall_edge_error_px);
            missed += comparison.missed_sectors.len() as u64;
            holes += comparison.holes as u64;
        }
        println!(
            "accuracy map={} {} frames={frames} pixels={pixels} surface_mismatches={surface} \
             texel_mismatches={texel} wall_edge_px={wall_edge} missed_sectors={missed} holes={holes}",
            map.name,
            SettingsLabel(&settings),
        );
    }
}
