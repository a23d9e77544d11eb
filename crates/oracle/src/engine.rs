//! The fixed-point engine's side of a comparison: render a pose with the engine on the host
//! (through the rasterizer twins, recording which surface each pixel shows), render it with the
//! oracle, and compare. The accuracy test and the benchmark report both go through here.

use portalcast::frame::Resolution;
use portalcast::raster::column::ColumnTexture;
use portalcast::raster::flat::FlatTexture;
use portalcast::raster::sprite::SpriteColumn;
use portalcast::raster::{Canvas, HostCanvas, HostPage};
use portalcast::render::surface::Surface;
use portalcast::render::view::{self, Settings, View};
use portalcast::render::walk::{FrameStats, Renderer};
use portalcast::render::RenderAssets;
use portalcast_format::MapTables;
use portalcast_rom::bench::{frames_for, ACCURACY_FRAME_STEP};
use portalcast_rom::game::GameWorld;
use portalcast_rom::live_flight::LiveFlight;

use crate::{compare, render, Assets, Camera, Comparison, Frame};

/// A host canvas that also records, per logical pixel, the surface drawn and how many times it
/// was written: the debug coverage buffer of the renderer tests.
pub struct RecordingCanvas {
    /// The page the twins draw.
    pub page: HostPage,
    /// Resolution drawn at.
    pub resolution: Resolution,
    /// Surface per logical pixel, row-major.
    pub surfaces: Vec<Surface>,
    /// Writes per logical pixel.
    pub writes: Vec<u32>,
    /// Palette index per logical pixel.
    pub indices: Vec<u8>,
    current: Surface,
    halved_flats: bool,
}

impl RecordingCanvas {
    /// An empty canvas at `resolution`.
    pub fn new(resolution: Resolution) -> RecordingCanvas {
        let pixels = resolution.width() * resolution.height();
        RecordingCanvas {
            page: HostPage::new(),
            resolution,
            surfaces: vec![Surface::None; pixels],
            writes: vec![0; pixels],
            indices: vec![0; pixels],
            current: Surface::None,
            halved_flats: false,
        }
    }

    fn record(&mut self, x: usize, row: usize, index: u8) {
        let at = row * self.resolution.width() + x;
        self.surfaces[at] = self.current;
        self.writes[at] += 1;
        self.indices[at] = index;
    }

    /// Pixels written other than exactly once: (x, row, writes).
    pub fn coverage_faults(&self) -> Vec<(usize, usize, u32)> {
        let width = self.resolution.width();
        self.writes
            .iter()
            .enumerate()
            .filter(|(_, &writes)| writes != 1)
            .map(|(at, &writes)| (at % width, at / width, writes))
            .collect()
    }
}

impl Canvas for RecordingCanvas {
    fn resolution(&self) -> Resolution {
        self.resolution
    }

    fn column(&mut self, x: usize, row: usize, count: usize, texture: &ColumnTexture) {
        let indices: Vec<u8> = texture.indices(count).collect();
        for (offset, index) in indices.into_iter().enumerate() {
            self.record(x, row + offset, index);
        }
        HostCanvas {
            page: &mut self.page,
            resolution: self.resolution,
            halved_flats: false,
        }
        .column(x, row, count, texture);
    }

    /// Sprites draw over the scene: their pixels take the thing's surface and index without
    /// counting as writes, which [`RecordingCanvas::coverage_faults`] checks for the scene.
    fn sprite_column(&mut self, x: usize, column: &SpriteColumn) {
        for run in column.runs() {
            for (offset, index) in column.indices(run).enumerate() {
                let at = (run.row + offset) * self.resolution.width() + x;
                self.surfaces[at] = self.current;
                self.indices[at] = column.over(self.indices[at], index);
            }
        }
        HostCanvas {
            page: &mut self.page,
            resolution: self.resolution,
            halved_flats: false,
        }
        .sprite_column(x, column);
    }

    fn flat(&mut self, row: usize, x: usize, count: usize, texture: &FlatTexture) {
        let halved = self.halved_flats && self.resolution.pixels_per_halfword() == 2;
        let indices: Vec<u8> = texture.indices_from(x, count, halved).collect();
        for (offset, index) in indices.into_iter().enumerate() {
            self.record(x + offset, row, index);
        }
        HostCanvas {
            page: &mut self.page,
            resolution: self.resolution,
            halved_flats: self.halved_flats,
        }
        .flat(row, x, count, texture);
    }

    fn set_halved_flats(&mut self, halved: bool) {
        self.halved_flats = halved;
    }

    fn set_surface(&mut self, surface: Surface) {
        self.current = surface;
    }
}

impl Camera {
    /// The oracle's camera at an engine camera's pose (exactly: every engine pose is
    /// representable), in the engine camera's sector.
    pub fn from_engine(camera: &view::Camera) -> Camera {
        Camera::from_fixed(
            camera.position.x.to_bits(),
            camera.position.y.to_bits(),
            camera.eye_z.to_bits(),
            camera.angle.to_bits(),
            Some(camera.sector),
        )
    }
}

/// One pose rendered by the engine and by the oracle, and how they differ.
pub struct EngineComparison {
    /// The engine's frame, with the surface of every pixel.
    pub engine: RecordingCanvas,
    /// The engine's counters for the frame.
    pub stats: FrameStats,
    /// The oracle's frame.
    pub oracle: Frame,
    /// How they differ.
    pub comparison: Comparison,
}

/// Renders `camera`'s view of `map` at `settings` and game tick `tick` with the engine
/// (`renderer`, on the host) and with the oracle (same viewport, lighting rule and tick; the
/// oracle is exact, so the engine's quality knobs only change the engine's side), and compares
/// them.
pub fn compare_with_engine(
    renderer: &mut Renderer,
    map: &MapTables,
    assets: &RenderAssets,
    camera: &view::Camera,
    settings: &Settings,
    tick: u32,
) -> EngineComparison {
    let view = View::new(camera, settings).at_tick(tick);
    let mut engine = RecordingCanvas::new(settings.resolution);
    let stats = renderer.render(map, assets, &view, &mut engine);
    let oracle_assets = Assets {
        textures: assets.textures,
        sky: &assets.sky,
        colormap: assets.colormap,
        sprites: assets.sprites,
        sprite_sets: assets.sprite_sets,
        blend: assets.blend,
    };
    let oracle_view = crate::View {
        tick,
        ..crate::View::from_viewport(&view.viewport, view.lighting)
    };
    let oracle = render(
        map,
        &oracle_assets,
        &Camera::from_engine(camera),
        &oracle_view,
    );
    let comparison = compare(&engine.surfaces, &engine.indices, &oracle);
    EngineComparison {
        engine,
        stats,
        oracle,
        comparison,
    }
}

/// A bench run's accuracy against the oracle, summed over its compared frames: what the
/// benchmark report prints per run (`bench-accuracy`) and the knob tests print.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RunAccuracy {
    /// Frames compared.
    pub frames: u64,
    /// Pixels compared.
    pub pixels: u64,
    /// Pixels on another surface than the oracle's (holes included).
    pub surface_mismatches: u64,
    /// Pixels on the oracle's surface with another palette index.
    pub texel_mismatches: u64,
    /// The largest vertical wall-edge error of any frame, in rows.
    pub wall_edge_px: u32,
    /// Sectors the oracle shows and the engine misses, summed over the frames.
    pub missed_sectors: u64,
    /// Things the oracle shows and the engine misses, summed over the frames.
    pub missed_things: u64,
    /// Pixels left unwritten.
    pub holes: u64,
}

impl RunAccuracy {
    /// Adds one frame's comparison.
    pub fn add(&mut self, comparison: &Comparison) {
        self.frames += 1;
        self.pixels += comparison.pixels as u64;
        self.surface_mismatches += comparison.surface_mismatches as u64;
        self.texel_mismatches += comparison.texel_mismatches as u64;
        self.wall_edge_px = self.wall_edge_px.max(comparison.max_wall_edge_error_px);
        self.missed_sectors += comparison.missed_sectors.len() as u64;
        self.missed_things += comparison.missed_things.len() as u64;
        self.holes += comparison.holes as u64;
    }

    /// `count` in per cent of the pixels compared.
    pub fn percent(&self, count: u64) -> f64 {
        100.0 * count as f64 / self.pixels as f64
    }
}

/// The accuracy of the bench run `(map, settings)`: every [`ACCURACY_FRAME_STEP`]-th frame of the
/// map's fly-through through its live world (the frames the ROM's bench scene times) rendered by
/// the engine and by the oracle and compared.
pub fn bench_run_accuracy(
    renderer: &mut Renderer,
    map: &MapTables,
    assets: &RenderAssets,
    settings: &Settings,
) -> RunAccuracy {
    let mut accuracy = RunAccuracy::default();
    let mut world = GameWorld::new();
    let mut flight = LiveFlight::new(map, &mut world);
    // The fly-through's clock is a tick a frame, as in the ROM's bench scene; the engine and
    // the oracle draw the same live world.
    for frame in 0..frames_for(map) {
        if frame % ACCURACY_FRAME_STEP == 0 {
            let live = world.map(map);
            accuracy.add(
                &compare_with_engine(renderer, &live, assets, &flight.camera(), settings, frame)
                    .comparison,
            );
        }
        flight.advance(&mut world);
    }
    accuracy
}
