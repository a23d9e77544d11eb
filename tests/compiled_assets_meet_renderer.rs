//! The map compiler's *accepted* output against the renderer's preconditions (issue 16, defect
//! 1). The fuzzer (`tests/fuzz_map_compiler.rs`) mangles maps against the shipped textures, all
//! 64×64; this test varies what it cannot: the images. Each case is an asset directory with a
//! grid map whose walls, floors and ceilings use textures of random sides (square or not, in
//! range or not) and a sky of random size. It goes through [`compile_dir`] as the build does.
//! When the compiler refuses the set, that is fine (its messages are the other tests' subject);
//! when it accepts it, every value the renderer will meet must be one it handles:
//!
//! - every texture a sector uses as a floor or ceiling is square, and at every mip level the
//!   span code can pick (`render::walk::mip_level` with the plane code's floor of
//!   `side − 6`) its side is in the flat kernels' range ([`FLAT_LOG2_SIDES`]) and its row-major
//!   level holds `side²` texels;
//! - every texture a wall uses has, at every mip level the wall code can pick, a height in the
//!   column kernels' range ([`COLUMN_LOG2_HEIGHTS`]) and `width × height` texels column-major;
//! - the sky's height is a power of two in the column kernels' range;
//! - and the host renderer draws the first frame at every resolution without a panic (the dev
//!   profile keeps the kernels' debug assertions), every pixel exactly once.
//!
//! Before defect 1's fix, a non-square floor compiled and this test failed on the first such
//! case (the flat twin's `texels.len() == side²` assertion).

use std::panic::AssertUnwindSafe;
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

use image::{Rgba, RgbaImage};
use portalcast::frame::Resolution;
use portalcast::math::Fx24_8;
use portalcast::player::Player;
use portalcast::raster::column::COLUMN_LOG2_HEIGHTS;
use portalcast::raster::flat::FLAT_LOG2_SIDES;
use portalcast::render::view::{Settings, View};
use portalcast::render::walk::{mip_level, Renderer};
use portalcast::render::RenderAssets;
use portalcast_assets::{compile_dir, Compiled};
use portalcast_format::limits::{FOCAL_LENGTH_MAX, FOCAL_LENGTH_MIN};
use portalcast_format::{MapTables, Sky, Texture, NO_TEXTURE, SKY};
use portalcast_oracle::RecordingCanvas;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestCaseError, TestRunner};

/// Cases per run: each encodes and quantises a handful of PNGs, well under a second.
const CASES: u32 = 48;

/// A scratch asset directory under the system temp dir, removed on drop.
struct Scratch(PathBuf);

impl Scratch {
    fn new() -> Scratch {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let dir = std::env::temp_dir().join(format!(
            "portalcast-preconditions-{}-{}",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        let _ = std::fs::remove_dir_all(&dir);
        for folder in ["maps", "textures", "sky"] {
            std::fs::create_dir_all(dir.join(folder)).expect("create scratch folder");
        }
        Scratch(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// An opaque image with a pattern, so the quantiser sees a few colours.
fn image(width: u32, height: u32) -> RgbaImage {
    RgbaImage::from_fn(width, height, |x, y| {
        let on = (x / 4 + y / 4) % 2 == 0;
        Rgba(if on {
            [200, 60, 30, 255]
        } else {
            [30, 60, 200, 255]
        })
    })
}

/// Texture sides: mostly powers of two in 8..=256, now and then one the compiler must refuse.
fn side() -> impl Strategy<Value = u32> {
    prop_oneof![
        16 => prop::sample::select(vec![8u32, 16, 32, 64, 128, 256]),
        1 => prop::sample::select(vec![4u32, 48, 512]),
    ]
}

/// A texture's width and height: mostly square, so that many sets compile.
fn texture_size() -> impl Strategy<Value = (u32, u32)> {
    prop_oneof![
        3 => side().prop_map(|side| (side, side)),
        1 => (side(), side()),
    ]
}

/// One case: four textures' sizes, the sky's, which texture each use takes, and a layout.
#[derive(Clone, Debug)]
struct Case {
    textures: Vec<(u32, u32)>,
    sky: (u32, u32),
    /// Texture of the solid walls, the two open kinds' floors, ceilings and step sides.
    walls: usize,
    floors: [usize; 2],
    ceilings: [Option<usize>; 2],
    side: usize,
    /// Interior cells of a 6×6 grid: which open kind each is.
    cells: Vec<bool>,
}

fn case() -> impl Strategy<Value = Case> {
    (
        prop::collection::vec(texture_size(), 4),
        (
            prop::sample::select(vec![64u32, 256, 512, 1024, 32]),
            prop::sample::select(vec![16u32, 64, 128, 256, 24]),
        ),
        0..4usize,
        [0..4usize, 0..4usize],
        [prop::option::of(0..4usize), prop::option::of(0..4usize)],
        0..4usize,
        prop::collection::vec(any::<bool>(), 16),
    )
        .prop_map(
            |(textures, sky, walls, floors, ceilings, side, cells)| Case {
                textures,
                sky,
                walls,
                floors,
                ceilings,
                side,
                cells,
            },
        )
}

impl Case {
    fn grid(&self) -> String {
        let ceiling = |kind: usize| match self.ceilings[kind] {
            Some(texture) => format!("t{texture}"),
            None => "sky".to_string(),
        };
        let mut text = format!("cell 64\nsolid # tex=t{}\n", self.walls);
        for (kind, symbol) in ['.', '-'].into_iter().enumerate() {
            text += &format!(
                "open {symbol} floor={} ceil={} floor_tex=t{} ceil_tex={} side=t{}\n",
                16 * kind,
                128 - 16 * kind,
                self.floors[kind],
                ceiling(kind),
                self.side
            );
        }
        text += "player @ on=. angle=30\ngrid\n######\n";
        for row in 0..4 {
            text.push('#');
            for column in 0..4 {
                text.push(match (row, column) {
                    (0, 0) => '@',
                    _ if self.cells[row * 4 + column] => '-',
                    _ => '.',
                });
            }
            text += "#\n";
        }
        text + "######\n"
    }
}

/// Mip levels the renderer can pick for a texture: `mip_level` over every depth from the near
/// plane to far beyond the world, at both ends of the focal lengths.
fn reachable_levels(texture: &Texture, width_log2: u8, height_log2: u8) -> Vec<u8> {
    let mut levels = Vec::new();
    for focal in [FOCAL_LENGTH_MIN, FOCAL_LENGTH_MAX] {
        for shift in 0..24 {
            let depth = Fx24_8::from_bits(1 << (8 + shift).min(30));
            levels.push(mip_level(
                depth,
                focal,
                texture.mip_count,
                width_log2,
                height_log2,
            ));
        }
    }
    levels.sort_unstable();
    levels.dedup();
    levels
}

/// Checks the compiled set against the kernels' and the plane and wall code's preconditions.
fn check_preconditions(compiled: &Compiled) -> Result<(), String> {
    let textures: Vec<Texture> = compiled.textures().iter().map(|t| t.texture()).collect();
    let mut flats = vec![false; textures.len()];
    let mut walls = vec![false; textures.len()];
    for map in compiled.maps() {
        for sector in &map.sectors {
            for texture in [sector.floor_texture, sector.ceil_texture] {
                if texture != SKY {
                    flats[usize::from(texture)] = true;
                }
            }
        }
        for wall in &map.walls {
            for texture in [wall.texture, wall.upper_texture, wall.lower_texture] {
                if texture != NO_TEXTURE {
                    walls[usize::from(texture)] = true;
                }
            }
        }
    }
    for (index, texture) in textures.iter().enumerate() {
        let name = texture.name;
        let (w, h) = (texture.width_log2, texture.height_log2);
        if flats[index] {
            if w != h {
                return Err(format!("flat '{name}' is 2^{w} x 2^{h}, not square"));
            }
            // planes.rs: the distance's level, at least `side − 6` (the kernels' largest).
            let floor = w.saturating_sub(*FLAT_LOG2_SIDES.end() as u8);
            for level in reachable_levels(texture, w, h) {
                let level = level.max(floor);
                if level >= texture.mip_count {
                    return Err(format!("flat '{name}': level {level} has no mip"));
                }
                let side = u32::from(texture.level_width_log2(level));
                if !FLAT_LOG2_SIDES.contains(&side) {
                    return Err(format!("flat '{name}': level {level} side 2^{side}"));
                }
                if texture.flat_level(level).len() != 1 << (2 * side) {
                    return Err(format!("flat '{name}': level {level} has the wrong size"));
                }
            }
        }
        if walls[index] {
            for level in reachable_levels(texture, w, h) {
                let height = u32::from(texture.level_height_log2(level));
                if !COLUMN_LOG2_HEIGHTS.contains(&height) {
                    return Err(format!("wall '{name}': level {level} height 2^{height}"));
                }
                let width = u32::from(texture.level_width_log2(level));
                if texture.wall_level(level).len() != 1 << (width + height) {
                    return Err(format!("wall '{name}': level {level} has the wrong size"));
                }
            }
        }
    }
    if let Some(sky) = compiled.sky() {
        let height = u32::from(sky.height);
        if !height.is_power_of_two() || !COLUMN_LOG2_HEIGHTS.contains(&height.trailing_zeros()) {
            return Err(format!("sky height {height} is outside the column kernels"));
        }
    }
    Ok(())
}

/// The first frame of every map at every resolution: no panic, every pixel once.
fn render_first_frames(compiled: &Compiled) -> Result<(), String> {
    static PLACEHOLDER: [u8; 64 * 16] = [1; 64 * 16];
    let textures: Vec<Texture> = compiled.textures().iter().map(|t| t.texture()).collect();
    let sprites: Vec<_> = compiled.sprites().iter().map(|s| s.sprite()).collect();
    let sprite_sets: Vec<_> = compiled.sprite_sets().iter().map(|s| s.set()).collect();
    let assets = RenderAssets {
        sprites: &sprites,
        sprite_sets: &sprite_sets,
        blend: compiled.blend(),
        textures: &textures,
        sky: compiled.sky().map_or(
            Sky {
                width_log2: 6,
                height: 16,
                texels: &PLACEHOLDER,
            },
            |sky| sky.sky(),
        ),
        colormap: compiled.colormap(),
    };
    for map in compiled.maps() {
        let tables: MapTables = map.tables();
        let camera = Player::spawn(&tables).camera();
        for resolution in Resolution::ALL {
            let settings = Settings {
                resolution,
                ..Settings::DEFAULT
            };
            let view = View::new(&camera, &settings);
            let faults = std::panic::catch_unwind(AssertUnwindSafe(|| {
                let mut canvas = RecordingCanvas::new(resolution);
                Renderer::new().render(&tables, &assets, &view, &mut canvas);
                canvas.coverage_faults().len()
            }))
            .map_err(|_| format!("{resolution:?}: the renderer panicked"))?;
            if faults > 0 {
                return Err(format!("{resolution:?}: {faults} pixels not drawn once"));
            }
        }
    }
    Ok(())
}

#[test]
fn accepted_textures_meet_the_kernels_preconditions() {
    // A fixed seed: the same sets every run (PROPTEST_RNG_SEED is not read here).
    let mut runner = TestRunner::new(Config {
        cases: CASES,
        failure_persistence: None,
        rng_seed: RngSeed::Fixed(16),
        ..Config::default()
    });
    let accepted = std::cell::Cell::new(0u32);
    let refused = std::cell::Cell::new(0u32);
    runner
        .run(&case(), |case| {
            let scratch = Scratch::new();
            for (index, &(width, height)) in case.textures.iter().enumerate() {
                image(width, height)
                    .save(scratch.0.join(format!("textures/t{index}.png")))
                    .expect("write texture");
            }
            image(case.sky.0, case.sky.1)
                .save(scratch.0.join("sky/sky.png"))
                .expect("write sky");
            std::fs::write(scratch.0.join("maps/cells.grid"), case.grid()).expect("write map");
            match compile_dir(&scratch.0) {
                Err(errors) => {
                    if refused.get() == 0 {
                        println!("first refusal: {errors}");
                    }
                    refused.set(refused.get() + 1);
                }
                Ok(compiled) => {
                    accepted.set(accepted.get() + 1);
                    check_preconditions(&compiled)
                        .and_then(|()| render_first_frames(&compiled))
                        .map_err(|e| TestCaseError::fail(format!("{e}\n{}", case.grid())))?;
                }
            }
            Ok(())
        })
        .unwrap_or_else(|e| panic!("{e}"));
    println!(
        "{} sets accepted, {} refused",
        accepted.get(),
        refused.get()
    );
    // Both sides must be exercised for the property to mean anything.
    assert!(accepted.get() >= CASES / 8, "too few accepted sets");
    assert!(refused.get() >= CASES / 8, "too few refused sets");
}
