//! The fixed-point engine's side of a comparison: render a pose with the engine on the host
//! (through the rasterizer twins, recording which surface each pixel shows), render it with the
//! oracle, and compare. The accuracy test and the benchmark report both go through here.

use portalcast::frame::Resolution;
use portalcast::raster::column::ColumnTexture;
use portalcast::raster::flat::FlatTexture;
use portalcast::raster::{Canvas, HostCanvas, HostPage};
use portalcast::render::surface::Surface;
use portalcast::render::view::{self, Settings, View};
use portalcast::render::walk::{FrameStats, Renderer};
use portalcast::render::RenderAssets;
use portalcast_format::MapTables;

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
        }
        .column(x, row, count, texture);
    }

    fn flat(&mut self, row: usize, x: usize, count: usize, texture: &FlatTexture) {
        let indices: Vec<u8> = texture.indices(count).collect();
        for (offset, index) in indices.into_iter().enumerate() {
            self.record(x + offset, row, index);
        }
        HostCanvas {
            page: &mut self.page,
            resolution: self.resolution,
        }
        .flat(row, x, count, texture);
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

/// Renders `camera`'s view of `map` at `settings` with the engine (`renderer`, on the host) and
/// with the oracle (same viewport and lighting rule; the oracle is exact, so the engine's
/// quality knobs only change the engine's side), and compares them.
pub fn compare_with_engine(
    renderer: &mut Renderer,
    map: &MapTables,
    assets: &RenderAssets,
    camera: &view::Camera,
    settings: &Settings,
) -> EngineComparison {
    let view = View::new(camera, settings);
    let mut engine = RecordingCanvas::new(settings.resolution);
    let stats = renderer.render(map, assets, &view, &mut engine);
    let oracle_assets = Assets {
        textures: assets.textures,
        sky: &assets.sky,
        colormap: assets.colormap,
    };
    let oracle_view = crate::View::from_viewport(&view.viewport, view.lighting);
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
