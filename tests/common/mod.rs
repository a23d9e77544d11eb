//! Shared pieces of the emulator tests: the ROM under test, log-line fields, pages and frames;
//! and, in `player`, of the player tests.
#![allow(dead_code)]

pub mod demos;
pub mod player;
pub mod rom_frames;

use portalcast::frame::{shown_index, Resolution, PAGE_HALFWORDS, PAGE_HEIGHT, PAGE_WIDTH};
use portalcast::raster::HostPage;
use portalcast_harness::{Emulator, KeyScript, Keys};
use std::ops::RangeInclusive;
use std::path::PathBuf;

/// Held at power-on, the key that switches on the game's per-frame `player` and `render` lines
/// (crates/rom/src/main.rs): without it the ROM writes none, as a player runs it. The ROM waits for it to
/// be let go before the game starts, so it never reaches the game.
pub const FRAME_LINES_KEY: Keys = Keys::START;

/// The emulator frames, from power-on, a test holds [`FRAME_LINES_KEY`] on: the ROM reads the
/// keys held at boot within them (the bench scene's tests hold R on the same frames).
pub const FRAME_LINES_HOLD: RangeInclusive<u32> = 0..=3;

/// `script` with the game's per-frame lines switched on at power-on.
pub fn with_frame_lines(script: &KeyScript) -> KeyScript {
    script.clone().hold(FRAME_LINES_HOLD, FRAME_LINES_KEY)
}

/// The ROM, loaded in a fresh mGBA core (built first if the test command did not).
pub fn boot() -> Emulator {
    let rom = portalcast_xtask::rom_for_tests();
    Emulator::load(&rom).unwrap_or_else(|error| panic!("{error}"))
}

/// The value of `key=value` in a ROM log line.
pub fn field<'a>(line: &'a str, key: &str) -> Option<&'a str> {
    line.split_whitespace()
        .find_map(|word| word.strip_prefix(key)?.strip_prefix('='))
}

/// A numeric `key=value` field; panics with the line if missing or malformed.
pub fn number(line: &str, key: &str) -> u64 {
    let text = field(line, key).unwrap_or_else(|| panic!("no {key}= in {line:?}"));
    let parsed = match text.strip_prefix("0x") {
        Some(hex) => u64::from_str_radix(hex, 16),
        None => text.parse(),
    };
    parsed.unwrap_or_else(|_| panic!("{key}={text} is not a number in {line:?}"))
}

/// The `stack used=U room=R reserve=S` line among a scene's `lines`, checked as every scene's
/// stack must be: it went some way, and stayed below the linker script's `STACK_RESERVE` (S),
/// which is within the room the code left it (R). Returns the line, to print.
pub fn checked_stack_line<'a>(lines: impl IntoIterator<Item = &'a str>, scene: &str) -> &'a str {
    let line = lines
        .into_iter()
        .find(|line| line.starts_with("stack "))
        .unwrap_or_else(|| panic!("{scene}: no `stack used=… room=… reserve=…` line"));
    let (used, room, reserve) = (
        number(line, "used"),
        number(line, "room"),
        number(line, "reserve"),
    );
    assert!(
        used > 0 && used < reserve && reserve <= room,
        "{scene}: the stack reached the linker's reserve or its room: {line}"
    );
    line
}

/// The ROM's debug lines that start with `prefix`.
pub fn lines_starting(emulator: &Emulator, prefix: &str) -> Vec<String> {
    emulator
        .debug_lines()
        .into_iter()
        .filter(|line| line.starts_with(prefix))
        .map(str::to_owned)
        .collect()
}

/// A Mode 4 page read out of the emulator's VRAM.
pub fn read_page(emulator: &Emulator, address: u32) -> HostPage {
    let bytes = emulator.read_bytes(address, PAGE_HALFWORDS * 2);
    let mut page = HostPage::new();
    for (halfword, pair) in page.halfwords.iter_mut().zip(bytes.chunks_exact(2)) {
        *halfword = u16::from_le_bytes([pair[0], pair[1]]);
    }
    page
}

/// The 240×160 frame BG2 shows of `page` at `resolution`, through `palette`, as 5-bit channels.
pub fn expected_frame_rgb5(
    page: &HostPage,
    resolution: Resolution,
    palette: &[u16; 256],
) -> Vec<[u8; 3]> {
    let mut pixels = Vec::with_capacity(PAGE_WIDTH * PAGE_HEIGHT);
    for y in 0..PAGE_HEIGHT {
        for x in 0..PAGE_WIDTH {
            let colour = palette[usize::from(shown_index(&page.halfwords, resolution, x, y))];
            pixels.push([
                (colour & 31) as u8,
                ((colour >> 5) & 31) as u8,
                ((colour >> 10) & 31) as u8,
            ]);
        }
    }
    pixels
}

/// The emulator's current frame as 5-bit channels (mGBA expands BGR555 to 8 bits per channel).
pub fn shown_frame_rgb5(emulator: &Emulator) -> Vec<[u8; 3]> {
    emulator
        .frame_rgb()
        .pixels()
        .map(|pixel| [pixel[0] >> 3, pixel[1] >> 3, pixel[2] >> 3])
        .collect()
}

/// Where tests leave PNGs for people (and the README) to look at.
pub fn screenshot_dir() -> PathBuf {
    let dir = portalcast_xtask::workspace_root()
        .join("target")
        .join("screenshots");
    std::fs::create_dir_all(&dir).expect("creating target/screenshots");
    dir
}

/// The shipped assets, compiled once per test process by the same compiler build.rs runs.
pub fn shipped_assets() -> &'static portalcast_assets::Compiled {
    static COMPILED: std::sync::OnceLock<portalcast_assets::Compiled> = std::sync::OnceLock::new();
    COMPILED.get_or_init(|| {
        let dir = portalcast_xtask::workspace_root().join("assets");
        portalcast_assets::compile_dir(&dir).unwrap_or_else(|errors| panic!("{errors}"))
    })
}

/// A live world on the host with room for any map's sectors, movers and triggers, Freedoom's
/// included (the ROM's own, `portalcast_rom::game::GameWorld`, is sized by the maps it holds).
pub type HostWorld = portalcast::world::World<4096, 64, 256>;

/// Freedoom Phase 1's maps the tests build (`portalcast_xtask::freedoom::MAPS`), compiled once
/// per test process by the compiler build.rs runs on a WAD: the tables the Freedoom ROM holds.
pub fn freedoom_assets() -> &'static portalcast_assets::Compiled {
    static COMPILED: std::sync::OnceLock<portalcast_assets::Compiled> = std::sync::OnceLock::new();
    COMPILED.get_or_init(|| {
        use portalcast_xtask::freedoom;
        let request = portalcast_assets::doom::WadRequest {
            wad: freedoom::freedoom1_wad().unwrap_or_else(|error| panic!("{error}")),
            iwad: None,
            maps: Some(freedoom::MAPS.iter().map(|map| map.to_string()).collect()),
        };
        portalcast_assets::doom::compile_wad(&request).unwrap_or_else(|errors| {
            let lines: Vec<String> = errors.iter().map(ToString::to_string).collect();
            panic!("{}", lines.join("\n"))
        })
    })
}

/// Emulated frames the bench scene may take at most (it takes far fewer).
pub const BENCH_SCENE_MAX_FRAMES: u32 = 60_000;
/// Frames run between looks at the log while the bench scene runs.
const BENCH_SCENE_CHUNK: u32 = 300;

/// Runs the bench scene of `rom` (R held at power-on) to its end and returns the ROM's debug
/// lines. Fails on a `panic` line, a line mGBA grades fatal, or a dropped log line.
pub fn bench_scene_log(rom: &std::path::Path) -> Vec<String> {
    let done = portalcast_xtask::bench_log::BENCH_DONE;
    let mut emulator = Emulator::load(rom).unwrap_or_else(|error| panic!("{error}"));
    emulator.set_keys(Keys::R);
    emulator
        .run_frames(4)
        .unwrap_or_else(|error| panic!("{error}"));
    emulator.set_keys(Keys::NONE);
    let mut frames = 4;
    while !emulator.debug_lines().contains(&done) {
        assert!(
            frames < BENCH_SCENE_MAX_FRAMES,
            "no {done:?} after {frames} frames"
        );
        emulator
            .run_frames(BENCH_SCENE_CHUNK)
            .unwrap_or_else(|error| panic!("frame {frames}: {error}"));
        frames += BENCH_SCENE_CHUNK;
    }
    assert_eq!(emulator.dropped_log_lines(), 0, "mGBA dropped log lines");
    println!("bench scene: {frames} emulated frames");
    emulator
        .debug_lines()
        .into_iter()
        .map(str::to_owned)
        .collect()
}

/// The engine's camera at an oracle pose (sampled poses are whole 24.8 and binary angles), and
/// the oracle's camera at that engine pose.
pub fn cameras_of_pose(
    pose: &portalcast_oracle::Camera,
) -> (portalcast::render::view::Camera, portalcast_oracle::Camera) {
    use portalcast::math::{Angle, Fx24_8, WorldPoint};
    let sector = pose.sector.expect("sampled poses know their sector");
    let camera = portalcast::render::view::Camera {
        position: WorldPoint::new(
            Fx24_8::from_bits((pose.x * 256.0) as i32),
            Fx24_8::from_bits((pose.y * 256.0) as i32),
        ),
        eye_z: Fx24_8::from_bits((pose.eye_z * 256.0) as i32),
        angle: Angle::from_bits(pose.angle_bits()),
        sector,
        look_lines: 0,
    };
    let oracle = portalcast_oracle::Camera::from_fixed(
        camera.position.x.to_bits(),
        camera.position.y.to_bits(),
        camera.eye_z.to_bits(),
        camera.angle.to_bits(),
        Some(sector),
    );
    (camera, oracle)
}

/// A compiled asset set's textures as the engine's table, with its sky and colormap: what a host
/// test renders with ([`HostAssets::render`]) and compares with the oracle's
/// ([`HostAssets::oracle`]). The asset set must have a sky.
pub struct HostAssets<'c> {
    textures: Vec<portalcast_format::Texture<'c>>,
    sky: portalcast_format::Sky<'c>,
    colormap: &'c portalcast_format::Colormap,
    sprites: Vec<portalcast_format::Sprite<'c>>,
    sprite_sets: Vec<portalcast_format::SpriteSet<'c>>,
    blend: Option<&'c portalcast_format::BlendTable>,
}

impl<'c> HostAssets<'c> {
    /// The tables of `compiled`.
    pub fn of(compiled: &'c portalcast_assets::Compiled) -> HostAssets<'c> {
        HostAssets {
            textures: compiled.textures().iter().map(|t| t.texture()).collect(),
            sky: compiled.sky().expect("an asset set with a sky").sky(),
            colormap: compiled.colormap(),
            sprites: compiled.sprites().iter().map(|s| s.sprite()).collect(),
            sprite_sets: compiled.sprite_sets().iter().map(|s| s.set()).collect(),
            blend: compiled.blend(),
        }
    }

    /// What the engine renders with.
    pub fn render(&self) -> portalcast::render::RenderAssets<'_> {
        portalcast::render::RenderAssets {
            textures: &self.textures,
            sky: self.sky,
            colormap: self.colormap,
            sprites: &self.sprites,
            sprite_sets: &self.sprite_sets,
            blend: self.blend,
        }
    }

    /// What the oracle renders with.
    pub fn oracle(&self) -> portalcast_oracle::Assets<'_> {
        portalcast_oracle::Assets {
            textures: &self.textures,
            sky: &self.sky,
            colormap: self.colormap,
            sprites: &self.sprites,
            sprite_sets: &self.sprite_sets,
            blend: self.blend,
        }
    }
}

/// Renders `camera` on `map` at `settings` with `renderer` (the shipped assets) and with the
/// oracle, checking that the engine drew every pixel once; the comparison of the two. With
/// `row_tolerance`, a sector or thing the oracle shows only within
/// [`portalcast_oracle::ROW_TOLERANCE_PX`] of a row centre does not count as missed
/// ([`portalcast_oracle::compare_with_row_tolerance`], for sampled poses, where such near-ties
/// turn up).
pub fn engine_against_oracle(
    map: &portalcast_format::MapTables,
    camera: &portalcast::render::view::Camera,
    settings: &portalcast::render::view::Settings,
    renderer: &mut portalcast::render::walk::Renderer,
    row_tolerance: bool,
) -> portalcast_oracle::Comparison {
    let host = HostAssets::of(shipped_assets());
    let view = portalcast::render::view::View::new(camera, settings);
    let mut canvas = portalcast_oracle::RecordingCanvas::new(settings.resolution);
    renderer.render(map, &host.render(), &view, &mut canvas);
    assert!(
        canvas.coverage_faults().is_empty(),
        "{}: {camera:?} {:?}: pixels not drawn exactly once",
        map.name,
        settings.resolution
    );
    let oracle_view = portalcast_oracle::View::from_viewport(
        &view.viewport,
        portalcast::render::light::Lighting::SectorDepth,
    );
    let oracle_camera = portalcast_oracle::Camera::from_fixed(
        camera.position.x.to_bits(),
        camera.position.y.to_bits(),
        camera.eye_z.to_bits(),
        camera.angle.to_bits(),
        Some(camera.sector),
    );
    if row_tolerance {
        let (oracle, moved) = portalcast_oracle::render_with_row_tolerance(
            map,
            &host.oracle(),
            &oracle_camera,
            &oracle_view,
        );
        return portalcast_oracle::compare_with_row_tolerance(
            &canvas.surfaces,
            &canvas.indices,
            &oracle,
            [&moved[0], &moved[1]],
        );
    }
    let oracle = portalcast_oracle::render(map, &host.oracle(), &oracle_camera, &oracle_view);
    portalcast_oracle::compare(&canvas.surfaces, &canvas.indices, &oracle)
}
