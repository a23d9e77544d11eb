//! The camera and the per-frame view derived from it.

use crate::frame::Resolution;
use crate::math::{recip_small, Angle, EyeFrame, Fx24_8, Fx2_30, Viewport, WorldPoint};

use super::light::Lighting;

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
    /// Where the ROM reads texels from. The renderer draws whatever textures it is handed; the
    /// ROM picks them by this knob (`portalcast_rom::demo::assets_for`).
    pub textures: TexturePlacement,
    /// Whether the visits of a sector seen through neighbouring portals are merged first.
    pub preprocessing: Preprocessing,
    /// Horizontal resolution of floors and ceilings under 240-wide walls.
    pub floors: Floors,
    /// Whether things are drawn.
    pub things: ThingsShown,
    /// How often a sloped floor's or ceiling's texture position is exact along a span.
    pub slope_steps: SlopeSteps,
}

/// The map offsets of a row's pixels per unit of depth, the same for every floor and ceiling of
/// a frame (Doom's `basexscale`, `baseyscale`, and its `distscale` and `finecosine` folded into
/// one factor): a span at depth `z'` shows the map point `e + z'·centre` at the centre column's
/// pixel centre, and moves by `z'·step` per pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PlaneRays {
    /// `f + r/(2·d_x)`, with `f = (cos, sin)` the view direction and `r = (−sin, cos)` its right.
    pub centre: (Fx2_30, Fx2_30),
    /// `r/d_x`.
    pub step: (Fx2_30, Fx2_30),
}

impl PlaneRays {
    /// The rays of `eye` through `viewport`'s columns.
    pub fn new(eye: &EyeFrame, viewport: &Viewport) -> PlaneRays {
        let (sin, cos) = (
            i64::from(eye.sin().to_bits()),
            i64::from(eye.cos().to_bits()),
        );
        // sin/d_x and cos/d_x in 2.30, from the 16.16 sine and cosine and the 2.30 reciprocal of
        // 2·d_x: 16.16 × 2.30 is 18.46, 15 bits more than 2.30 of twice the product.
        let inverse_twice_focal_x = i64::from(recip_small(2 * viewport.focal_x as u32).to_bits());
        let sin_over_focal = (sin * inverse_twice_focal_x) >> 15;
        let cos_over_focal = (cos * inverse_twice_focal_x) >> 15;
        // Each is at most √(1 + 1/(4·d_x²)) in size, under 2 for every viewport (d_x ≥ 1).
        let factor = |bits: i64| {
            Fx2_30::from_bits(i32::try_from(bits).expect("a plane ray's factor is under 2 in size"))
        };
        PlaneRays {
            centre: (
                factor((cos << 14) - (sin_over_focal >> 1)),
                factor((sin << 14) + (cos_over_focal >> 1)),
            ),
            step: (factor(-sin_over_focal), factor(cos_over_focal)),
        }
    }
}

/// The things knob: things drawn or not, to measure what they cost.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ThingsShown {
    /// Every thing in view drawn (the default).
    On,
    /// No thing drawn: the scene alone.
    Off,
}

impl ThingsShown {
    /// Both settings, on first.
    pub const ALL: [ThingsShown; 2] = [ThingsShown::On, ThingsShown::Off];

    /// The label the ROM prints and the benchmarks read.
    pub const fn label(self) -> &'static str {
        match self {
            ThingsShown::On => "on",
            ThingsShown::Off => "off",
        }
    }

    /// Parses [`ThingsShown::label`].
    pub fn from_label(label: &str) -> Option<ThingsShown> {
        ThingsShown::ALL
            .into_iter()
            .find(|things| things.label() == label)
    }

    /// The other setting (the menu toggles it).
    pub const fn next(self) -> ThingsShown {
        match self {
            ThingsShown::On => ThingsShown::Off,
            ThingsShown::Off => ThingsShown::On,
        }
    }
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
    /// A copy in EWRAM (3 cycles a byte), made once at boot; at 120×80 the ROM reads the hottest
    /// mip chains from the page rows that resolution leaves free in VRAM (1 cycle a byte,
    /// `hw::memory::LentPageRows`).
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
    /// The shipped defaults: 120×80, sector + depth lighting, exact column splits, textures in
    /// EWRAM (each the faster or more exact choice by measurement: docs/BENCH.md).
    pub const DEFAULT: Settings = Settings {
        resolution: Resolution::R120x80,
        lighting: Lighting::SectorDepth,
        textures: TexturePlacement::Ewram,
        preprocessing: Preprocessing::Off,
        floors: Floors::Full,
        things: ThingsShown::On,
        slope_steps: SlopeSteps::DEFAULT,
    };
}

impl Default for Settings {
    fn default() -> Self {
        Settings::DEFAULT
    }
}

/// The floor resolution knob: floors and ceilings at the walls' horizontal resolution, or at half
/// of it under 240-wide walls (the Southpaw engine's trade in Doom II and Duke Nukem Advance on
/// the GBA: full-width walls, half-width planes). Half, each VRAM halfword of a span shows one
/// texel, its even pixel's, written to both bytes by the 120-wide span kernels with a doubled
/// step: half the texel fetches and light look-ups of a plane pixel. The 120-wide resolutions
/// already draw one texel per halfword, so there the knob changes nothing and is not offered: the
/// menu shows `-` and the benchmark measures it at 240×160 only.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Floors {
    /// One texel per pixel.
    Full,
    /// One texel per VRAM halfword (two pixels) at 240 wide.
    Half,
}

impl Floors {
    /// Both settings, full first.
    pub const ALL: [Floors; 2] = [Floors::Full, Floors::Half];

    /// The label the ROM prints and the benchmarks read.
    pub const fn label(self) -> &'static str {
        match self {
            Floors::Full => "full",
            Floors::Half => "half",
        }
    }

    /// Parses [`Floors::label`].
    pub fn from_label(label: &str) -> Option<Floors> {
        Floors::ALL
            .into_iter()
            .find(|floors| floors.label() == label)
    }

    /// The other setting (the menu toggles it).
    pub const fn next(self) -> Floors {
        match self {
            Floors::Full => Floors::Half,
            Floors::Half => Floors::Full,
        }
    }

    /// Whether `resolution` offers the half setting: only 240 wide has two pixels per halfword
    /// to share a texel.
    pub const fn offered_at(resolution: Resolution) -> bool {
        resolution.pixels_per_halfword() == 2
    }
}

/// The slope-mapping knob: a sloped floor or ceiling is texture-mapped in perspective, exact
/// every `N` pixels along a span and affine between (Quake's and Build's trade). `N = 1` is exact
/// at every pixel; a larger `N` takes one reciprocal per `N` pixels instead of per pixel, and
/// its texels drift from the exact ones between. docs/BENCH.md measures each `N`: cycles, and
/// texels off the exact mapping. Flat planes are exact per row whatever the knob.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SlopeSteps {
    /// `log2(N)`.
    pub log2: u8,
}

impl SlopeSteps {
    /// Every value offered: `N` = 1, 4, 8, 16, 32.
    pub const ALL: [SlopeSteps; 5] = [
        SlopeSteps { log2: 0 },
        SlopeSteps { log2: 2 },
        SlopeSteps { log2: 3 },
        SlopeSteps { log2: 4 },
        SlopeSteps { log2: 5 },
    ];
    /// The default: `N = 16`.
    pub const DEFAULT: SlopeSteps = SlopeSteps { log2: 4 };

    /// The label the ROM prints and the benchmarks read: `N`.
    pub const fn label(self) -> &'static str {
        match self.log2 {
            0 => "1",
            2 => "4",
            3 => "8",
            4 => "16",
            _ => "32",
        }
    }

    /// Parses [`SlopeSteps::label`].
    pub fn from_label(label: &str) -> Option<SlopeSteps> {
        SlopeSteps::ALL
            .into_iter()
            .find(|steps| steps.label() == label)
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
    /// Whether sector visits are planned and merged before drawing.
    pub preprocessing: Preprocessing,
    /// Floors and ceilings at half the horizontal resolution (only ever true at 240 wide).
    pub halved_floors: bool,
    /// The game tick (60 a second) the frame shows: it picks the things' animation frames.
    pub tick: u32,
    /// Whether things are drawn.
    pub things: ThingsShown,
    /// The rays of the floor and ceiling spans, per unit of depth.
    pub plane_rays: PlaneRays,
    /// The slope-mapping knob.
    pub slope_steps: SlopeSteps,
}

impl View {
    /// The view of `camera` at `settings`.
    pub fn new(camera: &Camera, settings: &Settings) -> View {
        let resolution = settings.resolution;
        let mut viewport = Viewport::new(resolution.width() as i32, resolution.height() as i32);
        let look = camera.look_lines.clamp(-MAX_LOOK_LINES, MAX_LOOK_LINES);
        viewport.horizon_y += look * resolution.height() as i32 / 160;
        let eye = EyeFrame::new(camera.position, camera.angle);
        View {
            plane_rays: PlaneRays::new(&eye, &viewport),
            eye,
            eye_z: camera.eye_z,
            viewport,
            sector: camera.sector,
            lighting: settings.lighting,
            preprocessing: settings.preprocessing,
            halved_floors: settings.floors == Floors::Half && Floors::offered_at(resolution),
            tick: 0,
            things: settings.things,
            slope_steps: settings.slope_steps,
        }
    }

    /// The view at game tick `tick`.
    pub const fn at_tick(self, tick: u32) -> View {
        View { tick, ..self }
    }
}
