//! The renderer on the host, through the rasterizer twins: every shipped map, every resolution,
//! from several poses; every pixel written exactly once (no hole, no double draw).

mod common;

use common::*;
use portalcast::frame::Resolution;
use portalcast::math::{Angle, Fx24_8, WorldPoint};
use portalcast::render::light::Lighting;
use portalcast::render::surface::Surface;
use portalcast::render::view::{Camera, Floors, Settings, View};
use portalcast::render::walk::Renderer;
use portalcast_format::MapTables;
use portalcast_oracle::RecordingCanvas;

fn start_camera(map: &MapTables) -> Camera {
    let start = map.player_start;
    let sector = map.sectors[usize::from(start.sector)];
    Camera {
        position: WorldPoint::new(
            Fx24_8::from_bits(start.x_fx8),
            Fx24_8::from_bits(start.y_fx8),
        ),
        eye_z: Fx24_8::from_int(sector.floor_z + 32),
        angle: Angle::from_bits(start.angle),
        sector: start.sector,
        look_lines: 0,
    }
}

#[test]
fn every_pixel_is_drawn_exactly_once_on_every_shipped_map() {
    let compiled = shipped_assets();
    let host = HostAssets::of(compiled);
    let assets = host.render();
    let mut renderer = Renderer::new();
    for compiled_map in compiled.maps() {
        let map = compiled_map.tables();
        for turn in 0..8u16 {
            let mut camera = start_camera(&map);
            camera.angle = Angle::from_bits(camera.angle.to_bits().wrapping_add(turn * 8192 + 123));
            for resolution in Resolution::ALL {
                let knobs = [
                    (Lighting::Off, Floors::Full),
                    (Lighting::SectorDepth, Floors::Full),
                    // Half-width floors change which texel a pixel shows, not which pixels
                    // a span covers: still each pixel once (the value is ignored at 120 wide).
                    (Lighting::SectorDepth, Floors::Half),
                ];
                for (lighting, floors) in knobs {
                    let view = View::new(
                        &camera,
                        &Settings {
                            resolution,
                            lighting,
                            floors,
                            ..Settings::DEFAULT
                        },
                    );
                    let mut canvas = RecordingCanvas::new(resolution);
                    let stats = renderer.render(&map, &assets, &view, &mut canvas);
                    let faults = canvas.coverage_faults();
                    assert!(
                        faults.is_empty(),
                        "{} turn {turn} {resolution:?} {lighting:?} {floors:?}: {} pixels not drawn exactly once, first {:?}; {stats:?}",
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

#[test]
fn host_render_pngs_show_the_bench_map() {
    let compiled = shipped_assets();
    let host = HostAssets::of(compiled);
    let assets = host.render();
    let map = compiled.map("bench").expect("the bench map");
    let mut renderer = Renderer::new();
    for (turn, resolution) in [
        (0u16, Resolution::R240x160),
        (3, Resolution::R120x80),
        (5, Resolution::R240x160),
    ] {
        let mut camera = start_camera(&map);
        camera.angle = Angle::from_bits(camera.angle.to_bits().wrapping_add(turn * 8192));
        let view = View::new(
            &camera,
            &Settings {
                resolution,
                lighting: Lighting::SectorDepth,
                ..Settings::DEFAULT
            },
        );
        let mut canvas = RecordingCanvas::new(resolution);
        let stats = renderer.render(&map, &assets, &view, &mut canvas);
        assert!(stats.sector_visits >= 2, "{stats:?}");
        let pixels = expected_frame_rgb5(&canvas.page, resolution, compiled.palette());
        let image = image::RgbImage::from_fn(240, 160, |x, y| {
            let [r, g, b] = pixels[(y * 240 + x) as usize];
            image::Rgb([r << 3, g << 3, b << 3])
        });
        let path =
            screenshot_dir().join(format!("host-bench-turn{turn}-{}.png", resolution.label()));
        image.save(&path).expect("saving the PNG");
        println!("{} {stats:?}", path.display());
    }
}
