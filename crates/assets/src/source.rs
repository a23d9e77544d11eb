//! The parsed form of a map, shared by the `.map` and `.grid` front ends: names are resolved to
//! indices, values are not yet checked against the limits or the geometry rules.

use crate::diag::Loc;

/// A value and where it was written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Spanned<T> {
    pub value: T,
    pub loc: Loc,
}

impl<T> Spanned<T> {
    pub fn new(value: T, loc: Loc) -> Spanned<T> {
        Spanned { value, loc }
    }
}

#[derive(Clone, Debug)]
pub(crate) struct SourceMap {
    pub vertices: Vec<SourceVertex>,
    pub sectors: Vec<SourceSector>,
    pub player: SourcePlace,
    pub things: Vec<SourceThing>,
}

#[derive(Clone, Debug)]
pub(crate) struct SourceVertex {
    /// How error messages name it: "vertex 'v3'" or "corner (64, 128)".
    pub label: String,
    pub x: Spanned<i64>,
    pub y: Spanned<i64>,
}

#[derive(Clone, Debug)]
pub(crate) enum CeilingSource {
    Sky,
    Texture(Spanned<String>),
}

#[derive(Clone, Debug)]
pub(crate) struct SourceSector {
    /// How error messages name it: "sector 'hall'" or "area '.' at row 3, column 5".
    pub label: String,
    pub loc: Loc,
    pub floor: Spanned<i64>,
    pub ceil: Spanned<i64>,
    pub floor_texture: Spanned<String>,
    pub ceiling: CeilingSource,
    pub light: u8,
    pub walls: Vec<SourceWall>,
}

#[derive(Clone, Debug)]
pub(crate) struct SourceWall {
    pub loc: Loc,
    pub start: usize,
    pub end: usize,
    pub texture: Option<Spanned<String>>,
    pub portal: Option<Spanned<usize>>,
    pub upper: Option<Spanned<String>>,
    pub lower: Option<Spanned<String>>,
    pub x_offset: Spanned<i64>,
    pub y_offset: Spanned<i64>,
    /// Portal only (`.map`): the sprite set drawn in the opening (`mid=`), as written on this
    /// side; the twin wall of the neighbour shares it (`map_build::pair_middles`).
    pub middle: Option<Spanned<String>>,
    /// Where the word `blocks` is written, if it is.
    pub blocks: Option<Loc>,
    /// Where the word `translucent` is written, if it is.
    pub translucent: Option<Loc>,
}

#[derive(Clone, Debug)]
pub(crate) struct SourcePlace {
    pub loc: Loc,
    pub x_fx8: Spanned<i64>,
    pub y_fx8: Spanned<i64>,
    pub angle: u16,
}

#[derive(Clone, Debug)]
pub(crate) struct SourceThing {
    pub sprite: Spanned<String>,
    pub place: SourcePlace,
    pub options: ThingOptions,
}

/// The optional words of a `thing` line: `z=H`, `hang`, `solid`, `translucent`, `radius=R`,
/// `anim=TICKS`.
#[derive(Clone, Debug)]
pub(crate) struct ThingOptions {
    /// Units above the floor of the sprite's bottom (hanging: below the ceiling of its top).
    pub z: i64,
    pub hanging: bool,
    pub solid: bool,
    /// Drawn at 50 % over what is behind it.
    pub translucent: bool,
    /// The footprint radius written, if any (else half the sprite's width, rounded up).
    pub radius: Option<Spanned<i64>>,
    /// Game ticks each animation frame shows (`anim=`, else [`DEFAULT_FRAME_TICKS`]).
    pub frame_ticks: u16,
}

/// Game ticks (60 a second) each animation frame of a thing shows when it gives no `anim=`.
pub(crate) const DEFAULT_FRAME_TICKS: u16 = 8;

impl Default for ThingOptions {
    fn default() -> ThingOptions {
        ThingOptions {
            z: 0,
            hanging: false,
            solid: false,
            translucent: false,
            radius: None,
            frame_ticks: DEFAULT_FRAME_TICKS,
        }
    }
}
