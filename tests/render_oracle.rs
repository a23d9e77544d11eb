//! The fixed-point renderer against the f64 oracle on every shipped map: sampled poses, every
//! resolution. Bounds: at most 0.5 % of pixels on a different surface, no hole, no missed
//! sector. Texel mismatches are printed (mip-level and rounding differences), not bounded here.

mod common;

use common::*;
use portalcast::bench::default_settings;
use portalcast::frame::Resolution;
use portalcast::math::{Angle, Fx24_8, WorldPoint};
use portalcast::render::view::Camera;
use portalcast::render::walk::Renderer;
use portalcast::render::RenderAssets;
use portalcast_format::Texture;
use portalcast_oracle::{compare_with_engine, EngineComparison};

const POSES_PER_MAP: usize = 12;
const SURFACE_MISMATCH_MAX_PERCENT: f64 = 0.5;

#[test]
fn engine_matches_the_oracle_on_every_shipped_map() {
    let compiled = shipped_assets();
    let textures: Vec<Texture> = compiled.textures().iter().map(|t| t.texture()).collect();
    let sky = compiled.sky().expect("a sky").sky();
    let assets = RenderAssets {
        textures: &textures,
        sky,
        colormap: compiled.colormap(),
    };
    let mut renderer = Renderer::new();
    let mut worst = 0.0f64;
    let mut texel_total = 0.0f64;
    let mut frames = 0usize;
    for compiled_map in compiled.maps() {
        let map = compiled_map.tables();
        let poses = portalcast_oracle::sample_poses(&map, POSES_PER_MAP, 7);
        assert!(
            poses.len() >= POSES_PER_MAP / 2,
            "{}: too few poses",
            map.name
        );
        for (index, pose) in poses.iter().enumerate() {
            let sector = pose.sector.expect("sampled poses know their sector");
            let camera = Camera {
                position: WorldPoint::new(
                    Fx24_8::from_bits((pose.x * 256.0) as i32),
                    Fx24_8::from_bits((pose.y * 256.0) as i32),
                ),
                eye_z: Fx24_8::from_bits((pose.eye_z * 256.0) as i32),
                angle: Angle::from_bits(pose.angle_bits()),
                sector,
                look_lines: 0,
            };
            for resolution in Resolution::ALL {
                let settings = default_settings(resolution);
                let EngineComparison {
                    engine,
                    oracle,
                    comparison,
                    ..
                } = compare_with_engine(&mut renderer, &map, &assets, &camera, &settings);
                let percent = comparison.surface_mismatch_percent();
                worst = worst.max(percent);
                texel_total += comparison.texel_mismatch_percent();
                frames += 1;
                let ok = percent <= SURFACE_MISMATCH_MAX_PERCENT
                    && comparison.holes == 0
                    && comparison.missed_sectors.is_empty();
                if !ok {
                    let png = screenshot_dir().join(format!(
                        "oracle-diff-{}-{index}-{}.png",
                        map.name,
                        resolution.label()
                    ));
                    portalcast_oracle::write_diff_png(&engine.surfaces, &oracle, &png)
                        .expect("writing the diff");
                    panic!("{} pose {index} {resolution:?}: {comparison:?} ({percent:.3} % surfaces differ; diff in {})", map.name, png.display());
                }
            }
        }
    }
    println!(
        "oracle: {frames} frames, worst surface mismatch {worst:.3} %, mean texel mismatch {:.2} %",
        texel_total / frames as f64
    );
}
