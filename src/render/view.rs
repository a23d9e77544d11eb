//! The camera and the per-frame view derived from it.

use crate::frame::Resolution;
use crate::math::{Angle, EyeFrame, EyePoint, Fx24_8, Viewport, WorldPoint, NEAR_DEPTH};

use super::light::Lighting;
use super::walls::VertexSplit;

/// Where the eye is and where it looks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Camera {
    /// Position on the map plane.
    pub position: WorldPoint,
    /// Eye height.
    pub eye_z: Fx24_8,
    /// View direction.
    pub angle: Angle,
    /// The sector the eye is in (the player code tracks it).
    pub sector: u16,
    /// Look up/down as a horizon shift, in screen lines (160-line units) from the centre;
    /// clamped to ±[`MAX_LOOK_LINES`].
    pub look_lines: i32,
}

/// How far the horizon may move from the centre, in screen lines: a quarter screen each way,
/// which keeps the two-screen-tall sky panorama covering every row.
pub const MAX_LOOK_LINES: i32 = 40;

/// Quality knobs that change what is drawn or how exactly.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Settings {
    /// Render resolution.
    pub resolution: Resolution,
    /// Lighting rule.
    pub lighting: Lighting,
    /// How walls find their depth and texture column.
    pub perspective: Perspective,
    /// How exactly vertices are projected to the columns that split walls.
    pub projection: Projection,
    /// Where the ROM reads texels from. The renderer draws whatever textures it is handed; the
    /// ROM picks them by this knob ([`crate::render::demo::assets_for`]).
    pub textures: TexturePlacement,
    /// Whether the visits of a sector seen through neighbouring portals are merged first.
    pub preprocessing: Preprocessing,
}

/// The thesis' scene preprocessing knob (its §3.4, ×1.7 on its scenes): a first pass over the
/// portals that merges the visits of a sector seen through neighbouring portals, so that each
/// run of its columns is drawn once ([`crate::render::visits`]). Off, the walk draws each visit as
/// it reaches it. Either way each column's pixels are drawn once: merging saves the per-visit
/// work (the ownership tests of the sector's walls, the span set-up of its planes) and costs the
/// first pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Preprocessing {
    /// One pass: each visit drawn as the walk reaches it.
    Off,
    /// Two passes: plan and merge the visits, then draw each group once.
    On,
}

impl Preprocessing {
    /// Both settings, off first.
    pub const ALL: [Preprocessing; 2] = [Preprocessing::Off, Preprocessing::On];

    /// The label the ROM prints and the benchmarks read.
    pub const fn label(self) -> &'static str {
        match self {
            Preprocessing::Off => "off",
            Preprocessing::On => "on",
        }
    }

    /// Parses [`Preprocessing::label`].
    pub fn from_label(label: &str) -> Option<Preprocessing> {
        Preprocessing::ALL
            .into_iter()
            .find(|setting| setting.label() == label)
    }

    /// The other setting (the menu toggles it).
    pub const fn next(self) -> Preprocessing {
        match self {
            Preprocessing::Off => Preprocessing::On,
            Preprocessing::On => Preprocessing::Off,
        }
    }
}

/// The texture placement knob: which memory the kernels read texels from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TexturePlacement {
    /// The cartridge (5 cycles a random byte at WAITCNT 0x4317).
    Rom,
    /// A copy in EWRAM (3 cycles a byte), made once at boot.
    Ewram,
}

impl TexturePlacement {
    /// Parses [`TexturePlacement::label`].
    pub fn from_label(label: &str) -> Option<TexturePlacement> {
        [TexturePlacement::Rom, TexturePlacement::Ewram]
            .into_iter()
            .find(|placement| placement.label() == label)
    }

    /// The label the ROM prints and the benchmarks read.
    pub const fn label(self) -> &'static str {
        match self {
            TexturePlacement::Rom => "rom",
            TexturePlacement::Ewram => "ewram",
        }
    }
}

impl Settings {
    /// The shipped defaults: 120×80, sector + depth lighting, exact perspective, exact
    /// column splits, textures in EWRAM (each the faster or more exact choice by measurement: docs/BENCH.md).
    pub const DEFAULT: Settings = Settings {
        resolution: Resolution::R120x80,
        lighting: Lighting::SectorDepth,
        perspective: Perspective::Exact,
        projection: Projection::Exact,
        textures: TexturePlacement::Ewram,
        preprocessing: Preprocessing::Off,
    };
}

impl Default for Settings {
    fn default() -> Self {
        Settings::DEFAULT
    }
}

/// The wall perspective knob: how often a wall's depth and texture column come from the exact
/// reciprocal. The thesis computed them exactly every 16 columns and interpolated linearly
/// between; that is the cheap end here. Rows (the wall's top and bottom on screen) stay exact at
/// every setting, so no setting opens a hole or moves an edge; only texture columns, mip levels,
/// light and the vertical texture step drift between the exact columns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Perspective {
    /// Exact at every column (one reciprocal per column).
    Exact,
    /// Exact every 8 columns, linear between.
    Every8,
    /// Exact every 16 columns, linear between (the thesis' choice).
    Every16,
}

impl Perspective {
    /// Every setting, exact first.
    pub const ALL: [Perspective; 3] = [
        Perspective::Exact,
        Perspective::Every8,
        Perspective::Every16,
    ];

    /// Columns between exact evaluations (1 for exact).
    pub const fn interval(self) -> i32 {
        match self {
            Perspective::Exact => 1,
            Perspective::Every8 => 8,
            Perspective::Every16 => 16,
        }
    }

    /// The label the ROM prints and the benchmarks read.
    pub const fn label(self) -> &'static str {
        match self {
            Perspective::Exact => "exact",
            Perspective::Every8 => "every8",
            Perspective::Every16 => "every16",
        }
    }

    /// Parses [`Perspective::label`].
    pub fn from_label(label: &str) -> Option<Perspective> {
        Perspective::ALL
            .into_iter()
            .find(|perspective| perspective.label() == label)
    }

    /// The setting after this one (the menu cycles through them).
    pub const fn next(self) -> Perspective {
        match self {
            Perspective::Exact => Perspective::Every8,
            Perspective::Every8 => Perspective::Every16,
            Perspective::Every16 => Perspective::Exact,
        }
    }
}

/// The fixed-point precision knob: how a wall's end vertex is placed among the columns (which
/// wall owns which column). The thesis projected vertices to a screen `x` in 24.8 and took the
/// column from it, which put portals on the wrong column and missed sectors; the engine decides
/// ownership exactly instead, from 64-bit cross products of each vertex against each column's
/// ray. The rounded values project `x` through the reciprocal of `z'` (a table and a Newton
/// step, as the thesis multiplied by a reciprocal), with no divide and no bisection over the
/// columns, and measure what that saves and costs in accuracy. At every value the two walls
/// meeting at a vertex share its split, so every column stays owned once.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Projection {
    /// Exact: the column rays' cross products ([`crate::math::Viewport::side_of_column_ray`]).
    Exact,
    /// The vertex's `x = cx + d·x'/z'` in 16.16 through the reciprocal of `z'` (within 0.0026
    /// pixel, [`crate::math::Viewport::projected_x_saturating`]), then the column rule.
    Fx16_16,
    /// The same, rounded to 24.8 (1/256 pixel): the thesis' format.
    Fx24_8,
    /// The thesis' own order of operations: the ray's slope `x'/z'` truncated to 24.8, then
    /// `x = cx + d·(x'/z')`, so `x` keeps only `d/256` of a pixel (about a quarter of a pixel at
    /// 120 columns, half at 240). The thesis lost portals this way (its Fig 5.18).
    Thesis24_8,
}

impl Projection {
    /// Every value, exact first.
    pub const ALL: [Projection; 4] = [
        Projection::Exact,
        Projection::Fx16_16,
        Projection::Fx24_8,
        Projection::Thesis24_8,
    ];

    /// The label the ROM prints and the benchmarks read.
    pub const fn label(self) -> &'static str {
        match self {
            Projection::Exact => "exact",
            Projection::Fx16_16 => "fx16_16",
            Projection::Fx24_8 => "fx24_8",
            Projection::Thesis24_8 => "thesis",
        }
    }

    /// Parses [`Projection::label`].
    pub fn from_label(label: &str) -> Option<Projection> {
        Projection::ALL
            .into_iter()
            .find(|projection| projection.label() == label)
    }

    /// The value after this one (the menu cycles through them).
    pub const fn next(self) -> Projection {
        match self {
            Projection::Exact => Projection::Fx16_16,
            Projection::Fx16_16 => Projection::Fx24_8,
            Projection::Fx24_8 => Projection::Thesis24_8,
            Projection::Thesis24_8 => Projection::Exact,
        }
    }

    /// The first column of the eye-space vertex `p` at this precision: from its screen `x`
    /// rounded to the format (16.16 or 24.8) by the column rule of
    /// [`Viewport::first_column_at_or_after`]. `None` for [`Projection::Exact`] and for a vertex
    /// at or behind the near plane (a projection is undefined there): the exact
    /// [`VertexSplit::new`] splits the columns then. Computed once per vertex and frame (the
    /// renderer caches it), so it stays out of line and in ROM: in IWRAM it made the rounded
    /// projections as cheap as the exact bisection it replaces and no cheaper (docs/BENCH.md),
    /// and IWRAM is short.
    #[inline(never)]
    pub fn first_column(self, viewport: &Viewport, p: EyePoint) -> Option<i32> {
        if self == Projection::Exact || p.z <= NEAR_DEPTH {
            return None;
        }
        let inverse_depth = p.z.recip_fx2_30();
        Some(match self {
            Projection::Fx16_16 => viewport
                .first_column_at_or_after_x(viewport.projected_x_saturating_with(p, inverse_depth)),
            Projection::Fx24_8 => viewport.first_column_at_or_after_x_fx24_8(
                viewport.projected_x_fx24_8_with(p, inverse_depth),
            ),
            _ => viewport.first_column_at_or_after_x_fx24_8(
                viewport.projected_x_thesis_fx24_8_with(p, inverse_depth),
            ),
        })
    }

    /// The split of the columns `[first, end)` by the eye-space vertex `p` at this precision:
    /// from [`Projection::first_column`], or the exact [`VertexSplit::new`] where it has none.
    pub fn split(self, viewport: &Viewport, p: EyePoint, first: i32, end: i32) -> VertexSplit {
        match self.first_column(viewport, p) {
            Some(column) => VertexSplit::from_first_column(column, first, end),
            None => VertexSplit::new(viewport, p, first, end),
        }
    }
}

/// Everything per frame that follows from the camera and the settings.
#[derive(Clone, Copy, Debug)]
pub struct View {
    /// Eye position and orientation with its sine and cosine.
    pub eye: EyeFrame,
    /// Eye height.
    pub eye_z: Fx24_8,
    /// Screen size, focal lengths and horizon row.
    pub viewport: Viewport,
    /// The eye's sector.
    pub sector: u16,
    /// Lighting rule.
    pub lighting: Lighting,
    /// Wall perspective rule.
    pub perspective: Perspective,
    /// How vertices split the columns.
    pub projection: Projection,
    /// Whether sector visits are planned and merged before drawing.
    pub preprocessing: Preprocessing,
}

impl View {
    /// The view of `camera` at `settings`.
    pub fn new(camera: &Camera, settings: &Settings) -> View {
        let resolution = settings.resolution;
        let mut viewport = Viewport::new(resolution.width() as i32, resolution.height() as i32);
        let look = camera.look_lines.clamp(-MAX_LOOK_LINES, MAX_LOOK_LINES);
        viewport.horizon_y += look * resolution.height() as i32 / 160;
        View {
            eye: EyeFrame::new(camera.position, camera.angle),
            eye_z: camera.eye_z,
            viewport,
            sector: camera.sector,
            lighting: settings.lighting,
            perspective: settings.perspective,
            projection: settings.projection,
            preprocessing: settings.preprocessing,
        }
    }
}
