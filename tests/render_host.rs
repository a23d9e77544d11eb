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

/// [`RecordingCanvas`], and every batch of sprite columns checked as the GBA's canvas checks it
/// before its kernel runs (`hw::kernels::VramCanvas::sprite_columns`): each column's steps
/// within the kernel's bound.
struct StepsChecking(RecordingCanvas);

impl portalcast::raster::Canvas for StepsChecking {
    fn resolution(&self) -> Resolution {
        self.0.resolution()
    }
    fn column(
        &mut self,
        x: usize,
        row: usize,
        count: usize,
        texture: &portalcast::raster::column::ColumnTexture,
    ) {
        self.0.column(x, row, count, texture);
    }
    fn sprite_column(&mut self, x: usize, column: &portalcast::raster::sprite::SpriteColumn) {
        self.0.sprite_column(x, column);
    }
    fn sprite_columns(&mut self, batch: &portalcast::raster::sprite::SpriteBatch) {
        for record in batch.columns {
            assert!(
                portalcast::raster::sprite::steps_fit(record.y_top, record.scale, record.iscale),
                "{record:?}"
            );
        }
        self.0.sprite_columns(batch);
    }
    fn flat(
        &mut self,
        row: usize,
        x: usize,
        count: usize,
        texture: &portalcast::raster::flat::FlatTexture,
    ) {
        self.0.flat(row, x, count, texture);
    }
    fn set_halved_flats(&mut self, halved: bool) {
        self.0.set_halved_flats(halved);
    }
    fn set_surface(&mut self, surface: Surface) {
        self.0.set_surface(surface);
    }
}

/// The long soak's pose that stopped the ROM (its canvas refused a column of the gallery's
/// translucent window): flying in the gallery near the window's wall line, where the window's
/// depth, from the reciprocal of the wall's small constant, and its rows per texel disagreed
/// by 5 in 10,000, and the texels per row went past the sprite kernel's bound.
#[test]
fn a_middle_seen_from_near_its_wall_line_keeps_its_steps_in_the_kernel_s_bound() {
    use common::demos::{render_line_settings, PlayerLine, WorldLine};
    let player = PlayerLine::parse(
        "player frame=22956 vblank=48006 tick=48001 lost=0 keys=0x040 x=216977 y=-31764 \
         z=40960 angle=43264 sector=27 look=6 ground=0 crouch=0 fly=1 run=1 menu=-1 hud=1 \
         game_cycles=5557 ticks=2 tick_cycles=4888 tick_max_cycles=2444",
    );
    let world = WorldLine::parse("world frame=22956 heights=0,128 thrown=0 lights=90,168,21,60");
    let line = "render map=bench frame=22956 res=120x80 lighting=depth tex=ewram prep=off \
                floors=full things=on slp=16 page=0x06000000 cycles=285819";
    let (map, settings) = render_line_settings(line);
    let view = View::new(&player.camera(), &settings).at_tick(player.tick);
    let live = WorldLine::world_of(Some(&world), &map);
    let mut canvas = StepsChecking(RecordingCanvas::new(settings.resolution));
    let stats = Renderer::new().render(
        &live.map(&map),
        &portalcast_rom::demo::render_assets(),
        &view,
        &mut canvas,
    );
    assert_eq!(stats.middles_drawn, 3, "the three windows: {stats:?}");
    assert!(canvas.0.writes.iter().all(|&writes| writes == 1));
}

#[test]
fn host_render_pngs_show_the_slopes_map() {
    let compiled = shipped_assets();
    let host = HostAssets::of(compiled);
    let assets = host.render();
    let map = compiled.map("slopes").expect("the slopes map");
    let mut renderer = Renderer::new();
    // In the hall facing the ramp, on the ramp, on the landing facing the attic, in the hall
    // facing the bank.
    for (name, x, y, eye, angle) in [
        ("ramp", 64, 128, 32, 0u16),
        ("on-ramp", 380, 128, 32 + 32, 32768),
        ("attic", 576, 64, 96, 16384),
        ("bank", 128, 64, 32, 16384),
    ] {
        let sector = portalcast_oracle::find_sector(&map, f64::from(x), f64::from(y))
            .expect("the pose is in a sector");
        let camera = Camera {
            position: WorldPoint::new(Fx24_8::from_int(x), Fx24_8::from_int(y)),
            eye_z: Fx24_8::from_int(eye),
            angle: Angle::from_bits(angle),
            sector,
            look_lines: 0,
        };
        let resolution = Resolution::R240x160;
        let view = View::new(
            &camera,
            &Settings {
                resolution,
                ..Settings::DEFAULT
            },
        );
        let mut canvas = RecordingCanvas::new(resolution);
        renderer.render(&map, &assets, &view, &mut canvas);
        let pixels = expected_frame_rgb5(&canvas.page, resolution, compiled.palette());
        let image = image::RgbImage::from_fn(240, 160, |x, y| {
            let [r, g, b] = pixels[(y * 240 + x) as usize];
            image::Rgb([r << 3, g << 3, b << 3])
        });
        let path = screenshot_dir().join(format!("host-slopes-{name}.png"));
        image.save(&path).expect("saving the PNG");
    }
}
