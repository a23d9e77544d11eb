//! Freedoom's maps imported from their WADs (issue 19: `portalcast_assets::doom::compile_wad`,
//! what `PORTALCAST_ASSETS=….wad cargo rom` builds) rendered by the engine against the f64
//! oracle: the start pose and sampled poses, every resolution. Bounds as for the shipped maps
//! (`tests/render_oracle.rs`): at most 0.5 % of pixels on a different surface, no hole, no
//! missed sector.

mod common;

use std::collections::BTreeMap;

use portalcast::flight::eye_z;
use portalcast::frame::Resolution;
use portalcast::math::{Angle, Fx24_8, WorldPoint};
use portalcast::render::view::{Camera, Settings};
use portalcast::render::walk::Renderer;
use portalcast_oracle::compare_with_engine;

use portalcast_xtask::freedoom::MAPS;
/// Sampled poses a map (besides the start).
const POSES_PER_MAP: usize = 12;
const SURFACE_MISMATCH_MAX_PERCENT: f64 = 0.5;

#[test]
fn freedoom_maps_match_the_oracle_from_their_starts_and_sampled_poses() {
    let compiled = common::freedoom_assets();
    let host = common::HostAssets::of(compiled);
    let assets = host.render();
    let mut renderer = Renderer::new();
    let mut failures = Vec::new();
    // Per map: frames, worst and summed surface mismatch %, holes, frames missing a sector.
    let mut figures: BTreeMap<&str, (usize, f64, f64, usize, usize)> = BTreeMap::new();
    for name in MAPS {
        let map = compiled.map(name).expect("the map was built");
        let start = map.player_start;
        let mut cameras = vec![Camera {
            position: WorldPoint::new(
                Fx24_8::from_bits(start.x_fx8),
                Fx24_8::from_bits(start.y_fx8),
            ),
            eye_z: eye_z(&map.sectors[usize::from(start.sector)]),
            angle: Angle::from_bits(start.angle),
            sector: start.sector,
            look_lines: 0,
        }];
        cameras.extend(
            portalcast_oracle::sample_poses(&map, POSES_PER_MAP, 19)
                .iter()
                .map(common::cameras_of_pose)
                .map(|(camera, _)| camera),
        );
        for (index, camera) in cameras.iter().enumerate() {
            for resolution in Resolution::ALL {
                let settings = Settings {
                    resolution,
                    ..Settings::DEFAULT
                };
                let run = compare_with_engine(&mut renderer, &map, &assets, camera, &settings, 0);
                let percent = run.comparison.surface_mismatch_percent();
                let missed = &run.comparison.missed_sectors;
                let entry = figures.entry(name).or_default();
                entry.0 += 1;
                entry.1 = entry.1.max(percent);
                entry.2 += percent;
                entry.3 += run.comparison.holes;
                entry.4 += usize::from(!missed.is_empty());
                if percent > SURFACE_MISMATCH_MAX_PERCENT
                    || run.comparison.holes > 0
                    || !missed.is_empty()
                {
                    let png = common::screenshot_dir()
                        .join(format!("doom-{name}-{index}-{}.png", resolution.label()));
                    portalcast_oracle::write_diff_png(&run.engine.surfaces, &run.oracle, &png)
                        .expect("writing the diff");
                    failures.push(format!(
                        "{name} pose {index} {} ({camera:?}): {:?}; diff: {}",
                        resolution.label(),
                        run.comparison,
                        png.display()
                    ));
                }
            }
        }
    }
    // The lines `cargo bench-report` reads for docs/BENCH.md's Freedoom section.
    for (name, (frames, worst, sum, holes, missed)) in &figures {
        println!(
            "doom-accuracy map={name} frames={frames} worst={worst:.3} mean={:.3} holes={holes} missed={missed}",
            sum / *frames as f64
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
