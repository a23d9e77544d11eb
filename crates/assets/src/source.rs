//! The parsed form of a map, shared by the `.map` and `.grid` front ends: names are resolved to
//! indices, values are not yet checked against the limits or the geometry rules.

use portalcast_format::PlayerSize;

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
    /// The player's body (`player … eye= height= step=`, [`PlayerSize::NATIVE`] by default).
    pub player_size: PlayerSize,
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
    /// The floor's height; where `floor_slope` is given, its lowest height at the sector's
    /// vertices (rounded down), set once the slope is resolved ([`crate::slopes`]).
    pub floor: Spanned<i64>,
    /// The ceiling's height; where `ceil_slope` is given, its highest (rounded up).
    pub ceil: Spanned<i64>,
    /// `floor_slope=`: the floor's heights at some of the sector's vertices.
    pub floor_slope: Option<SourceSlope>,
    /// `ceil_slope=`: the ceiling's heights at some of the sector's vertices.
    pub ceil_slope: Option<SourceSlope>,
    pub floor_texture: Spanned<String>,
    pub ceiling: CeilingSource,
    pub light: u8,
    /// The sector's mover word and its settings, if it moves (`door`, `lift=`, `platform=`,
    /// `crusher=`).
    pub mover: Option<SourceMover>,
    /// The sector's light effect, if its light changes (`glow=`, `strobe=`, `flicker=`,
    /// `switched=`).
    pub light_effect: Option<SourceLight>,
    /// `layer=`: sectors on different layers may overlap (room over room); 0 unless given.
    pub layer: Spanned<i64>,
    /// `ceil_portal=`: the sector above, into which the ceiling opens (index into
    /// [`SourceMap::sectors`]).
    pub above: Option<Spanned<usize>>,
    /// `floor_portal=`: the sector below, into which the floor opens.
    pub below: Option<Spanned<usize>>,
    pub walls: Vec<SourceWall>,
}

/// A sloped floor or ceiling as a map gives it: its heights at three or more of the sector's
/// vertices, which must lie on one plane.
#[derive(Clone, Debug)]
pub(crate) struct SourceSlope {
    /// Where the `floor_slope=` or `ceil_slope=` value is written.
    pub loc: Loc,
    /// Each vertex (index into [`SourceMap::vertices`]) with its height, as written.
    pub points: Vec<(Spanned<usize>, Spanned<i64>)>,
}

/// How a sector moves: its mover word.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum MoverKind {
    /// `door`: the ceiling opens from the floor up to the ceiling drawn.
    Door,
    /// `lift=LOW`: the floor goes down from the floor drawn to LOW.
    Lift,
    /// `platform=OTHER`: the floor moves for ever between the floor drawn and OTHER.
    Platform,
    /// `crusher=LOW`: the ceiling moves for ever between the ceiling drawn and LOW.
    Crusher,
}

impl MoverKind {
    /// How messages name it: "door", "lift", ...
    pub fn name(self) -> &'static str {
        match self {
            MoverKind::Door => "door",
            MoverKind::Lift => "lift",
            MoverKind::Platform => "platform",
            MoverKind::Crusher => "crusher",
        }
    }

    /// Whether it moves the sector's ceiling (doors, crushers) rather than its floor.
    pub fn moves_ceiling(self) -> bool {
        matches!(self, MoverKind::Door | MoverKind::Crusher)
    }

    /// `speed=` and `wait=` when the sector gives none: world units a tick, ticks at the far
    /// end (60 ticks a second).
    pub fn defaults(self) -> (u16, u16) {
        match self {
            MoverKind::Door => (2, 150),
            MoverKind::Lift => (2, 120),
            MoverKind::Platform => (1, 60),
            MoverKind::Crusher => (1, 30),
        }
    }
}

/// A sector's light effect as written, checked for syntax and ranges by the parser; its low
/// level is checked against the sector's `light=` by `map_build`.
#[derive(Clone, Debug)]
pub(crate) struct SourceLight {
    /// `portalcast_format::LIGHT_GLOW`, `LIGHT_STROBE`, `LIGHT_FLICKER` or `LIGHT_SWITCHED`.
    pub kind: u8,
    /// The word as written (`glow=`, ...), for messages.
    pub word: &'static str,
    /// The low level written after the word.
    pub low: Spanned<u8>,
    /// Ticks a cycle (`period=`, else the kind's default; 0 for a switched light).
    pub period: u16,
    /// A switched light's `tag=N`.
    pub tag: Option<Spanned<u16>>,
}

/// A sector's mover as written: its word and settings, checked for syntax and ranges by the
/// parser; the heights are checked against the sector's by `map_build`.
#[derive(Clone, Debug)]
pub(crate) struct SourceMover {
    pub kind: MoverKind,
    /// Where the mover word is written (`door`; the value of `lift=`, `platform=`, `crusher=`).
    pub loc: Loc,
    /// The height written with `lift=`, `platform=` or `crusher=` (none for a door).
    pub height: Option<Spanned<i64>>,
    /// The word `touch` (doors: also opens when the player walks into it).
    pub touch: bool,
    /// Where the word `locked` is written, if it is (doors and lifts: only a trigger starts it).
    pub locked: Option<Loc>,
    /// World units a tick (`speed=`, else the kind's default).
    pub speed: u16,
    /// Ticks at the far end (`wait=`, else the kind's default).
    pub wait: u16,
    /// `tag=N`, if written.
    pub tag: Option<Spanned<u16>>,
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
    /// Solid only (`.map`): `switch=TEX`, the texture the wall shows once used; the wall starts
    /// the movers of its `tag=`.
    pub switch: Option<Spanned<String>>,
    /// `tag=N` of a switch.
    pub tag: Option<Spanned<u16>>,
    /// Portal only (`.map`): `trigger=N`, crossing the portal from this side starts the movers
    /// tagged N.
    pub trigger: Option<Spanned<u16>>,
}

impl SourceWall {
    /// A wall at `loc` from vertex `start` to `end` with none of the optional words: no
    /// texture, no portal, offsets 0. The grid compiler and the Doom importer fill in the rest.
    pub fn new(loc: Loc, start: usize, end: usize) -> SourceWall {
        SourceWall {
            loc,
            start,
            end,
            texture: None,
            portal: None,
            upper: None,
            lower: None,
            x_offset: Spanned::new(0, loc),
            y_offset: Spanned::new(0, loc),
            middle: None,
            blocks: None,
            translucent: None,
            switch: None,
            tag: None,
            trigger: None,
        }
    }
}

#[derive(Clone, Debug)]
pub(crate) struct SourcePlace {
    pub loc: Loc,
    pub x_fx8: Spanned<i64>,
    pub y_fx8: Spanned<i64>,
    pub angle: u16,
    /// `layer=`: which of the overlapping sectors of several layers holds the place (0 unless
    /// given).
    pub layer: Option<Spanned<i64>>,
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
