//! The fixed-point precision knob (`Projection`, issue 7): its labels, its default's frames, the
//! coverage of its rounded values on every shipped map, and (printed, not bounded) their
//! accuracy against the f64 oracle next to the exact default's.
//!
//! `cargo test --release --test projection_knob -- --nocapture` prints the accuracy lines.

use portalcast::assets;
use portalcast::bench::{default_settings, FRAMES_PER_SETTING};
use portalcast::flight::Flight;
use portalcast::frame::Resolution;
use portalcast::math::Angle;
use portalcast::render::demo::render_assets;
use portalcast::render::surface::Surface;
use portalcast::render::view::{Camera, Projection, Settings, View};
use portalcast::render::walk::Renderer;
use portalcast_format::MapTables;
use portalcast_oracle::{bench_run_accuracy, RecordingCanvas};

/// The poses sampled on `map`: every frame of its fly-through, and its first pose turned
/// by eighths of a turn (a vertex behind the eye on most of them).
fn poses(map: &MapTables) -> Vec<Camera> {
    let flight: Vec<Camera> = Flight::new(map).take(FRAMES_PER_SETTING as usize).collect();
    let turns = (0..8u16).map(|turn| {
        let mut camera = flight[0];
        camera.angle = Angle::from_bits(camera.angle.to_bits().wrapping_add(turn * 8192 + 123));
        camera
    });
    flight.iter().copied().chain(turns).collect()
}

fn settings(resolution: Resolution, projection: Projection) -> Settings {
    Settings {
        projection,
        ..default_settings(resolution)
    }
}

#[test]
fn every_value_round_trips_through_its_label() {
    for projection in Projection::ALL {
        assert_eq!(Projection::from_label(projection.label()), Some(projection));
    }
    assert_eq!(Projection::from_label("fx8_24"), None);
    assert_eq!(Settings::DEFAULT.projection, Projection::Exact);
}

/// FNV-1a over the frames the default settings draw at the sampled poses of every shipped map:
/// the value below was first measured on the engine before the knob existed (commit e53fb17), so
/// the `exact` default draws the same pixels as before, bit for bit. It was measured again when
/// floor and ceiling spans started stepping from the row's centre column instead of their own
/// first pixel (so that merging sector visits changes no texel; tests/scene_preprocessing.rs),
/// a change of plane texels only, and of no surface (the oracle figures in docs/BENCH.md).
#[test]
fn exact_draws_the_same_frames_as_before_the_knob() {
    let assets = render_assets();
    let mut renderer = Renderer::new();
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for map in assets::MAPS {
        // The poses the value below was measured at: every 4th frame, then the turns.
        let poses = poses(map);
        let (flight, turns) = poses.split_at(FRAMES_PER_SETTING as usize);
        for &camera in flight.iter().step_by(4).chain(turns) {
            for resolution in Resolution::ALL {
                let view = View::new(&camera, &default_settings(resolution));
                let mut canvas = RecordingCanvas::new(resolution);
                renderer.render(map, &assets, &view, &mut canvas);
                for byte in canvas
                    .page
                    .halfwords
                    .iter()
                    .flat_map(|half| half.to_le_bytes())
                {
                    hash = (hash ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3);
                }
            }
        }
    }
    println!("exact frames hash {hash:#018x}");
    assert_eq!(hash, EXACT_FRAMES_HASH, "{hash:#018x}");
}

const EXACT_FRAMES_HASH: u64 = 0x68e6_d21c_c241_01eb;

#[test]
fn every_value_draws_every_pixel_exactly_once_on_every_shipped_map() {
    let assets = render_assets();
    let mut renderer = Renderer::new();
    for map in assets::MAPS {
        for (pose, camera) in poses(map).into_iter().enumerate() {
            for resolution in Resolution::ALL {
                for projection in Projection::ALL {
                    let view = View::new(&camera, &settings(resolution, projection));
                    let mut canvas = RecordingCanvas::new(resolution);
                    let stats = renderer.render(map, &assets, &view, &mut canvas);
                    let faults = canvas.coverage_faults();
                    assert!(
                        faults.is_empty(),
                        "{} pose {pose} {resolution:?} {projection:?}: {} pixels not drawn \
                         exactly once, first {:?}; {stats:?}",
                        map.name,
                        faults.len(),
                        &faults[..faults.len().min(8)]
                    );
                    assert!(canvas.surfaces.iter().all(|s| *s != Surface::None));
                }
            }
        }
    }
}

/// Prints, per map, resolution and value, the oracle comparison summed over the bench's
/// accuracy frames (every `ACCURACY_FRAME_STEP`-th frame of the fly-through, as
/// `bench-accuracy` does): surface and texel mismatches in per cent, the worst wall edge,
/// missed sectors and holes; and, over every frame of the fly-through, the pixels whose surface
/// differs from the exact value's frame. Not bounded: the figures are what the knob measures.
#[test]
fn rounded_projections_against_the_oracle() {
    let assets = render_assets();
    let mut renderer = Renderer::new();
    for map in assets::MAPS {
        for resolution in Resolution::ALL {
            for projection in Projection::ALL {
                let settings = settings(resolution, projection);
                let accuracy = bench_run_accuracy(&mut renderer, map, &assets, &settings);
                let mut differ = 0u64;
                for camera in Flight::new(map).take(FRAMES_PER_SETTING as usize) {
                    differ += surfaces_differing_from_exact(&mut renderer, map, &camera, &settings);
                }
                println!(
                    "projection map={} res={} proj={} surface%={:.3} texel%={:.2} \
                     wall_edge_px={} missed_sectors={} holes={} px_differing_from_exact={differ}",
                    map.name,
                    resolution.label(),
                    projection.label(),
                    accuracy.percent(accuracy.surface_mismatches),
                    accuracy.percent(accuracy.texel_mismatches),
                    accuracy.wall_edge_px,
                    accuracy.missed_sectors,
                    accuracy.holes,
                );
                assert!(accuracy.pixels > 0);
            }
        }
    }
}

/// Pixels of the frame `settings` draw at `camera` whose surface differs from the frame of the
/// exact projection at the same pose.
fn surfaces_differing_from_exact(
    renderer: &mut Renderer,
    map: &MapTables,
    camera: &Camera,
    settings: &Settings,
) -> u64 {
    let assets = render_assets();
    let mut draw = |settings: &Settings| {
        let mut canvas = RecordingCanvas::new(settings.resolution);
        renderer.render(map, &assets, &View::new(camera, settings), &mut canvas);
        canvas.surfaces
    };
    let exact = draw(&Settings {
        projection: Projection::Exact,
        ..*settings
    });
    let rounded = draw(settings);
    exact.iter().zip(&rounded).filter(|(a, b)| a != b).count() as u64
}
