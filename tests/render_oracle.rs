//! The fixed-point renderer against the f64 oracle on every shipped map: sampled poses, every
//! resolution. Bounds: at most 0.5 % of pixels on a different surface, no hole, no missed
//! sector. Texel mismatches are printed (mip-level and rounding differences), not bounded here.

mod common;

use common::*;
use portalcast::frame::Resolution;
use portalcast::math::{Angle, Fx24_8, WorldPoint};
use portalcast::render::light::Lighting;
use portalcast::render::view::{Camera, Perspective, Settings, View};
use portalcast::render::walk::Renderer;
use portalcast::render::RenderAssets;
use portalcast_format::Texture;

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
    let oracle_assets = portalcast_oracle::Assets {
        textures: &textures,
        sky: &sky,
        colormap: compiled.colormap(),
    };
    let mut renderer = Renderer::new();
    // Per perspective setting: worst surface mismatch, summed texel mismatch.
    let mut worst = [0.0f64; Perspective::ALL.len()];
    let mut texel_total = [0.0f64; Perspective::ALL.len()];
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
                let exact_view = View::new(
                    &camera,
                    &Settings {
                        resolution,
                        ..Settings::DEFAULT
                    },
                );
                let oracle_view = portalcast_oracle::View::from_viewport(
                    &exact_view.viewport,
                    Lighting::SectorDepth,
                );
                let oracle_camera = portalcast_oracle::Camera::from_fixed(
                    camera.position.x.to_bits(),
                    camera.position.y.to_bits(),
                    camera.eye_z.to_bits(),
                    camera.angle.to_bits(),
                    Some(sector),
                );
                let oracle =
                    portalcast_oracle::render(&map, &oracle_assets, &oracle_camera, &oracle_view);
                frames += 1;
                for (knob, perspective) in Perspective::ALL.into_iter().enumerate() {
                    let view = View::new(
                        &camera,
                        &Settings {
                            resolution,
                            perspective,
                            ..Settings::DEFAULT
                        },
                    );
                    let mut canvas = RecordingCanvas::new(resolution);
                    renderer.render(&map, &assets, &view, &mut canvas);
                    let comparison =
                        portalcast_oracle::compare(&canvas.surfaces, &canvas.indices, &oracle);
                    let percent = comparison.surface_mismatch_percent();
                    worst[knob] = worst[knob].max(percent);
                    texel_total[knob] += comparison.texel_mismatch_percent();
                    let ok = percent <= SURFACE_MISMATCH_MAX_PERCENT
                        && comparison.holes == 0
                        && comparison.missed_sectors.is_empty();
                    if !ok {
                        let png = screenshot_dir().join(format!(
                            "oracle-diff-{}-{index}-{}-{}.png",
                            map.name,
                            resolution.label(),
                            perspective.label()
                        ));
                        portalcast_oracle::write_diff_png(&canvas.surfaces, &oracle, &png)
                            .expect("writing the diff");
                        panic!("{} pose {index} {resolution:?} {perspective:?}: {comparison:?} ({percent:.3} % surfaces differ; diff in {})", map.name, png.display());
                    }
                }
            }
        }
    }
    for (knob, perspective) in Perspective::ALL.into_iter().enumerate() {
        println!(
            "oracle, perspective {}: {frames} frames, worst surface mismatch {:.3} %, mean texel mismatch {:.2} %",
            perspective.label(),
            worst[knob],
            texel_total[knob] / frames as f64
        );
    }
}
