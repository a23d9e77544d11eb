use portalcast::frame::Resolution;
use portalcast::math::{Angle, Fx24_8, WorldPoint};
use portalcast::render::light::Lighting;
use portalcast::render::view::{Camera, Settings, View};
use portalcast::render::walk::Renderer;
use portalcast::render::RenderAssets;
use portalcast_format::Texture;
use portalcast_oracle::RecordingCanvas;
#[test]
fn debug_pose() {
    let dir = std::env::temp_dir().join("portalcast-generated-debug");
    portalcast_xtask::generated_maps::write_generated_assets(
        &dir,
        &portalcast_xtask::workspace_root().join("assets"),
    )
    .unwrap();
    let compiled = portalcast_assets::compile_dir(&dir).unwrap();
    let textures: Vec<Texture> = compiled.textures().iter().map(|t| t.texture()).collect();
    let sky = compiled.sky().unwrap().sky();
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
    let map = compiled
        .maps()
        .iter()
        .find(|m| m.name == "castle")
        .unwrap()
        .tables();
    let camera = Camera {
        position: WorldPoint::new(
            Fx24_8::from_bits((-844.3984375f64 * 256.0) as i32),
            Fx24_8::from_bits((749.68359375f64 * 256.0) as i32),
        ),
        eye_z: Fx24_8::from_bits(80 * 256),
        angle: Angle::from_bits(2942),
        sector: 36,
        look_lines: 0,
    };
    let view = View::new(
        &camera,
        &Settings {
            resolution: Resolution::R120x80,
            ..Settings::DEFAULT
        },
    );
    let ov = portalcast_oracle::View::from_viewport(&view.viewport, Lighting::SectorDepth);
    let oc = portalcast_oracle::Camera::from_fixed(
        camera.position.x.to_bits(),
        camera.position.y.to_bits(),
        camera.eye_z.to_bits(),
        camera.angle.to_bits(),
        Some(36),
    );
    let oracle = portalcast_oracle::render(&map, &oracle_assets, &oc, &ov);
    let mut canvas = RecordingCanvas::new(Resolution::R120x80);
    Renderer::new().render(&map, &assets, &view, &mut canvas);
    for i in 0..canvas.surfaces.len() {
        if canvas.surfaces[i] != oracle.surfaces[i] {
            println!(
                "x={} y={} engine {:?} oracle {:?} depth {}",
                i % 120,
                i / 120,
                canvas.surfaces[i],
                oracle.surfaces[i],
                oracle.depths[i]
            );
        }
    }
    for delta in [-0.01f64, -0.001, -0.0001, 0.0001, 0.001, 0.01] {
        let mut ov2 = ov;
        ov2.horizon_y += delta;
        let o2 = portalcast_oracle::render(&map, &oracle_assets, &oc, &ov2);
        println!(
            "horizon {delta}: pixel(0,43) {:?} (42) {:?} (44) {:?}",
            o2.surfaces[43 * 120],
            o2.surfaces[42 * 120],
            o2.surfaces[44 * 120]
        );
    }
    let col = (0..canvas.surfaces.len())
        .find(|&i| canvas.surfaces[i] != oracle.surfaces[i])
        .unwrap()
        % 120;
    for y in 0..80 {
        println!(
            "{y}: e {:?} o {:?}",
            canvas.surfaces[y * 120 + col],
            oracle.surfaces[y * 120 + col]
        );
    }
}
