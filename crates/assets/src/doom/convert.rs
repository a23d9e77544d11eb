//! A Doom map's pieces as a portalcast map source, checked by the map compiler itself: the
//! importer's proof that its partition and its mapping of the map meet every rule a hand-made
//! map must (docs/MAP_FORMAT.md), and its list of what does not yet.
//!
//! The mapping: each [`Piece`] a sector with its Doom sector's heights, flats (by
//! [`flat_name`]) and light ([`light_level`]), `F_SKY1` ceilings the sky; Doom's doors and lifts
//! movers, and the lines that start them switches and walk-over lines (`super::movers`); a
//! one-sided side a wall with its middle texture; a two-sided side a portal with its upper and
//! lower textures; an opening of the partition a portal without any (with stand-in strips
//! where a mover's pieces meet). Doom's y runs up the map and portalcast's down the screen's top view: y
//! is negated, so the map is not mirrored; a map reaching past portalcast's world limits but
//! fitting within them is recentred. The player stands at player 1's start (moved by a 1/256
//! step where it lies on a line) with Doom's body; its things as things (`super::things`:
//! [`import_report`] lists those left out).

use super::level::DoomLevel;
use super::movers::{from_doom_ticks, thrown_switch_texture, LineTrigger, Motion, Movers};
use super::partition::{Piece, PieceWall};
use super::things;
use crate::diag::Loc;
use crate::geometry::{cross, Point};
use crate::map_build::{self, Catalog};
use crate::source::{
    CeilingSource, MoverKind, SourceLight, SourceMap, SourceMover, SourcePlace, SourceSector,
    SourceThing, SourceVertex, SourceWall, Spanned, ThingOptions,
};
use portalcast_format::limits::{LIGHTS_MAX, WORLD_COORD_MAX};
use portalcast_format::{PlayerSize, LIGHT_FLICKER, LIGHT_GLOW, LIGHT_STROBE};

/// Doom's strobes (`p_lights.c`): lit `STROBEBRIGHT` (5) Doom ticks of each cycle, dark
/// `FASTDARK` (15) or `SLOWDARK` (35); portalcast's strobe is lit `STROBE_FLASH_TICKS` (5 of its
/// ticks) of each period.
const FAST_STROBE_PERIOD: u16 = from_doom_ticks(5 + 15);
const SLOW_STROBE_PERIOD: u16 = from_doom_ticks(5 + 35);
/// Doom's random flash (special 1) changes level every few ticks and its fire flicker (17)
/// every 4 Doom ticks: portalcast's flicker draws a level each period.
const FLASH_PERIOD: u16 = from_doom_ticks(4);
/// Doom's glow (special 8) moves 8 light levels a Doom tick (`GLOWSPEED`).
const GLOW_SPEED: u32 = 8;

/// The least light of the sectors round Doom's sector `sector`, if below `most`
/// (`P_FindMinSurroundingLight`: `most` itself if none is darker).
fn min_surrounding_light(level: &DoomLevel, sector: u16, most: i16) -> i16 {
    level
        .neighbours(sector)
        .map(|other| other.light)
        .fold(most, i16::min)
}

/// Doom's light special of sector `sector` (`P_SpawnSpecials`) as a portalcast light effect:
/// 1 (random flash) and 17 (fire flicker) a flicker, 2, 4 and 13 (fast strobes) and 3 and 12
/// (slow ones) a strobe, 8 a glow, down to the darkest light round it as Doom's; none where
/// the sector has none of these, or where the low level would not be below its own.
fn light_effect(level: &DoomLevel, sector: u16) -> Option<SourceLight> {
    let own = &level.sectors[usize::from(sector)];
    let darkest = min_surrounding_light(level, sector, own.light);
    let (kind, word, low, period) = match own.special {
        1 => (LIGHT_FLICKER, "flicker=", darkest, FLASH_PERIOD),
        17 => (
            LIGHT_FLICKER,
            "flicker=",
            darkest.saturating_add(16),
            FLASH_PERIOD,
        ),
        // A strobe with nothing darker round it goes black (`P_SpawnStrobeFlash`).
        2 | 4 | 13 => (
            LIGHT_STROBE,
            "strobe=",
            if darkest == own.light { 0 } else { darkest },
            FAST_STROBE_PERIOD,
        ),
        3 | 12 => (
            LIGHT_STROBE,
            "strobe=",
            if darkest == own.light { 0 } else { darkest },
            SLOW_STROBE_PERIOD,
        ),
        8 => {
            let swing = u32::try_from(own.light - darkest).unwrap_or(0);
            let period = from_doom_ticks(2 * swing.div_ceil(GLOW_SPEED)).max(2);
            (LIGHT_GLOW, "glow=", darkest, period)
        }
        _ => return None,
    };
    let (high, low) = (light_level(own.light), light_level(low));
    (low < high).then(|| SourceLight {
        kind,
        word,
        low: at(low),
        period,
        tag: None,
    })
}

/// How many pieces each of `level`'s sectors is cut into.
fn pieces_per_sector(level: &DoomLevel, pieces: &[Piece]) -> Vec<usize> {
    let mut counts = vec![0usize; level.sectors.len()];
    for piece in pieces {
        counts[usize::from(piece.sector)] += 1;
    }
    counts
}

/// Doom's linedef flag: the line blocks players and monsters.
const BLOCKING: u16 = 1;

/// What [`middle_set_name`] puts before a texture's name.
pub(crate) const MIDDLE_PREFIX: &str = "mid_";

/// The sprite set a two-sided line's middle texture `texture` becomes (a grate, bars: a portal
/// middle, docs/MAP_FORMAT.md "Portal middles"): `mid_` and its name.
pub(crate) fn middle_set_name(texture: &str) -> String {
    format!("{MIDDLE_PREFIX}{}", texture.to_ascii_lowercase())
}

/// The middle texture two-sided `line` shows: its right side's, else its left side's.
fn line_middle<'l>(level: &'l DoomLevel, line: &super::level::Linedef) -> Option<&'l str> {
    line.sides
        .iter()
        .map(|&side| level.sidedefs[usize::from(side)].middle.as_str())
        .find(|name| *name != "-" && !name.is_empty())
}

/// Doom's linedef flag "lower unpegged": a two-sided line's middle texture stands on the
/// higher floor instead of hanging from the lower ceiling.
const LOWER_UNPEGGED: u16 = 16;

/// How far a side's middle texture `middle` of size `texture_size` is raised above hanging
/// from the opening's top (portalcast's rule, `y_offset` up) to stand where Doom draws it on a
/// lower unpegged line: its bottom on the higher floor. Only on a side with no upper or lower
/// texture, whose offset moves nothing else.
fn standing_middle(
    level: &DoomLevel,
    line: &super::level::Linedef,
    side: &super::level::Sidedef,
    middle: &str,
    texture_size: &dyn Fn(&str) -> Option<(u16, u16)>,
) -> Option<i16> {
    if line.flags & LOWER_UNPEGGED == 0 || side.upper != "-" || side.lower != "-" {
        return None;
    }
    let (_, height) = texture_size(middle)?;
    let sectors = line
        .sides
        .map(|s| &level.sectors[usize::from(level.sidedefs[usize::from(s)].sector)]);
    let floor = sectors[0].floor.max(sectors[1].floor);
    let ceiling = sectors[0].ceiling.min(sectors[1].ceiling);
    i16::try_from(i32::from(floor) + i32::from(height) - i32::from(ceiling)).ok()
}

/// Doom's thing type of player 1's start.
const PLAYER_1_START: u16 = 1;
/// Doom's thing types that mark places rather than show something: the players' starts (1–4,
/// deathmatch 11), teleport destinations (14), the boss brain's targets (87) and spawner (89).
const NOT_DRAWN: [u16; 8] = [1, 2, 3, 4, 11, 14, 87, 89];

/// Doom's name of the sky's ceiling flat.
const SKY_FLAT: &str = "F_SKY1";

fn at<T>(value: T) -> Spanned<T> {
    Spanned::new(value, Loc::START)
}

/// A texture name as the source takes it (`-`: none).
fn texture(name: &str) -> Option<Spanned<String>> {
    (name != "-" && !name.is_empty()).then(|| at(name.to_string()))
}

/// What the mapping does where the map compiler would refuse what Doom draws, until the
/// importer maps it for real.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StandIns {
    /// None: the compiler says what it refuses.
    Off,
    /// A sector closed (floor at or above ceiling: a shut door, a lowered lift) is opened to a
    /// ceiling one unit above its floor, and a wall or step strip without a texture takes
    /// [`STAND_IN_TEXTURE`], so the compiler's later checks run on the rest.
    On,
}

/// The texture name a missing texture stands in as.
pub const STAND_IN_TEXTURE: &str = "MISSING";

/// The catalog name of Doom's flat `name`: flats and wall textures are two namespaces in Doom
/// (a flat and a texture may share a name) and one in portalcast's catalog.
pub(crate) fn flat_name(name: &str) -> String {
    format!("{FLAT_PREFIX}{name}")
}

/// What [`flat_name`] puts before a flat's name.
pub(crate) const FLAT_PREFIX: &str = "flat:";

/// Doom's sector light (0..=255, 255 full) as portalcast's light level: half of it, rounded
/// up, so Doom's full light is portalcast's neutral (`LIGHT_NEUTRAL`, 128, textures as they
/// are) and each portalcast colormap row below it is two of Doom's `COLORMAP` rows
/// (`super::import`'s colormap).
pub(crate) fn light_level(doom_light: i16) -> u8 {
    ((doom_light.clamp(0, 255) + 1) / 2) as u8
}

/// `level`'s pieces as a map source, and the names of the textures it uses (flats by
/// [`flat_name`]).
///
/// `texture_size` gives the size of a wall texture the WAD has: a switch shows its `SW1`/`SW2`
/// twin once used only if it has it, and a middle texture Doom stands on the floor ("lower
/// unpegged") is placed by its height.
pub(crate) fn source(
    level: &DoomLevel,
    pieces: &[Piece],
    stand_ins: StandIns,
    texture_size: &dyn Fn(&str) -> Option<(u16, u16)>,
) -> (SourceMap, Vec<String>) {
    let on = stand_ins == StandIns::On;
    let texture =
        |name: &str| texture(name).or_else(|| on.then(|| at(STAND_IN_TEXTURE.to_string())));
    let mut names: Vec<String> = Vec::new();
    let pieces_of = pieces_per_sector(level, pieces);
    let movers = Movers::of(level, &pieces_of);
    let moves = |piece: u32| movers.sectors[usize::from(pieces[piece as usize].sector)].is_some();
    let (shift_x, shift_y) = recentring(level);
    // Light effects a map may hold (`LIGHTS_MAX`): the pieces after are lit steadily.
    let mut lights_left = LIGHTS_MAX as usize;
    let vertices = level
        .vertices
        .iter()
        .enumerate()
        .map(|(index, v)| SourceVertex {
            label: format!("vertex {index}"),
            x: at(i64::from(v.x) + shift_x),
            y: at(-(i64::from(v.y) + shift_y)),
        })
        .collect();
    let sectors = pieces
        .iter()
        .enumerate()
        .map(|(index, piece)| {
            let doom = &level.sectors[usize::from(piece.sector)];
            let mover = movers.sectors[usize::from(piece.sector)];
            let floor_flat = flat_name(&doom.floor_flat);
            names.push(floor_flat.clone());
            let ceiling = if doom.ceiling_flat == SKY_FLAT {
                CeilingSource::Sky
            } else {
                let ceiling_flat = flat_name(&doom.ceiling_flat);
                names.push(ceiling_flat.clone());
                CeilingSource::Texture(at(ceiling_flat))
            };
            let n = piece.outline.len();
            let walls = (0..n)
                .map(|k| {
                    let (start, end) = (
                        usize::from(piece.outline[k]),
                        usize::from(piece.outline[(k + 1) % n]),
                    );
                    let side = |linedef: u16, side: u16| {
                        let line = &level.linedefs[usize::from(linedef)];
                        &level.sidedefs[usize::from(line.sides[usize::from(side)])]
                    };
                    let mut wall = SourceWall::new(Loc::START, start, end);
                    let offsets = match piece.walls[k] {
                        PieceWall::Solid { linedef, side: s } => {
                            let side = side(linedef, s);
                            wall.texture = texture(&side.middle);
                            if let (Some(LineTrigger::Switch { tag }), Some(shown)) =
                                (movers.lines[usize::from(linedef)], &wall.texture)
                            {
                                let thrown = thrown_switch_texture(&shown.value, |name| {
                                    texture_size(name).is_some()
                                });
                                wall.switch = Some(at(thrown));
                                wall.tag = Some(at(tag));
                            }
                            (side.x_offset, side.y_offset)
                        }
                        PieceWall::Portal {
                            linedef,
                            side: s,
                            piece: behind,
                        } => {
                            let side = side(linedef, s);
                            wall.portal = Some(at(behind as usize));
                            wall.upper = texture(&side.upper);
                            wall.lower = texture(&side.lower);
                            if let Some(LineTrigger::Walk { tag }) =
                                movers.lines[usize::from(linedef)]
                            {
                                wall.trigger = Some(at(tag));
                            }
                            // The line's middle texture, given on its right side's wall (the
                            // twin shares it).
                            let line = &level.linedefs[usize::from(linedef)];
                            let middle = line_middle(level, line);
                            if let (0, Some(middle)) = (s, middle) {
                                wall.middle = Some(at(middle_set_name(middle)));
                                if line.flags & BLOCKING != 0 {
                                    wall.blocks = Some(Loc::START);
                                }
                            }
                            let raise = middle
                                .and_then(|middle| {
                                    standing_middle(level, line, side, middle, texture_size)
                                })
                                .unwrap_or(0);
                            (side.x_offset, side.y_offset.saturating_add(raise))
                        }
                        PieceWall::Open { piece: beside } => {
                            wall.portal = Some(at(beside as usize));
                            // Pieces of one mover move as one, so the strips between them
                            // show only if one is held back (a door coming down on the
                            // player goes back up alone): the compiler wants them anyway.
                            if mover.is_some() || moves(beside) {
                                wall.upper = Some(at(STAND_IN_TEXTURE.to_string()));
                                wall.lower = Some(at(STAND_IN_TEXTURE.to_string()));
                            }
                            (0, 0)
                        }
                    };
                    wall.x_offset = at(i64::from(offsets.0));
                    wall.y_offset = at(i64::from(offsets.1));
                    let strips = [&wall.texture, &wall.upper, &wall.lower, &wall.switch];
                    for name in strips.into_iter().flatten() {
                        names.push(name.value.clone());
                    }
                    wall
                })
                .collect();
            SourceSector {
                label: format!("piece {index} (sector {})", piece.sector),
                loc: Loc::START,
                floor: at(i64::from(doom.floor)),
                floor_slope: None,
                ceil_slope: None,
                // A door is drawn open (docs/MAP_FORMAT.md, "Movers") and starts shut; a lift
                // is drawn raised, as Doom's is.
                ceil: at(match mover.map(|mover| mover.motion) {
                    Some(Motion::Door { open }) => i64::from(open),
                    _ if on => i64::from(doom.ceiling.max(doom.floor.saturating_add(1))),
                    _ => i64::from(doom.ceiling),
                }),
                floor_texture: at(floor_flat),
                ceiling,
                light: light_level(doom.light),
                mover: mover.map(|mover| {
                    let (kind, height) = match mover.motion {
                        Motion::Door { .. } => (MoverKind::Door, None),
                        Motion::Lift { low } => (MoverKind::Lift, Some(at(i64::from(low)))),
                    };
                    SourceMover {
                        kind,
                        loc: Loc::START,
                        height,
                        touch: false,
                        locked: mover.locked.then_some(Loc::START),
                        speed: mover.timing.speed,
                        wait: mover.timing.wait,
                        tag: mover.tag.map(at),
                    }
                }),
                light_effect: light_effect(level, piece.sector).filter(|_| {
                    let room = lights_left > 0;
                    lights_left = lights_left.saturating_sub(1);
                    room
                }),
                layer: at(0),
                above: None,
                below: None,
                walls,
            }
        })
        .collect();
    let start = level
        .things
        .iter()
        .find(|thing| thing.kind == PLAYER_1_START)
        .copied()
        .unwrap_or_default();
    let (x_fx8, y_fx8) = off_the_lines(
        level,
        pieces,
        (
            (i64::from(start.x) + shift_x) << 8,
            (i64::from(start.y) + shift_y) << 8,
        ),
        (shift_x, shift_y),
    );
    let player = SourcePlace {
        loc: Loc::START,
        x_fx8: at(x_fx8),
        y_fx8: at(-y_fx8),
        angle: portalcast_angle(start.angle),
        layer: None,
    };
    let things = thing_places(level, pieces, &movers, (shift_x, shift_y))
        .into_iter()
        .filter_map(|(index, place)| match place {
            ThingPlace::Piece(place) => Some((index, place)),
            ThingPlace::Door | ThingPlace::Nowhere => None,
        })
        .filter_map(|(index, (x_fx8, y_fx8))| {
            let thing = &level.things[index];
            let kind = things::kind_of(thing.kind)?;
            Some(SourceThing {
                sprite: at(kind.set_name()),
                place: SourcePlace {
                    loc: thing_loc(index),
                    x_fx8: at(x_fx8),
                    y_fx8: at(-y_fx8),
                    angle: portalcast_angle(thing.angle),
                    layer: None,
                },
                options: ThingOptions {
                    hanging: kind.hanging,
                    solid: kind.solid,
                    ..ThingOptions::default()
                },
            })
        })
        .collect();
    (
        SourceMap {
            vertices,
            sectors,
            player,
            player_size: PlayerSize::DOOM,
            things,
        },
        names,
    )
}

/// Where a source made from Doom's thing `index` says it is: its line is the thing's number
/// plus one, so that the compiler's findings about it lead back to the thing
/// ([`thing_of_loc`]).
fn thing_loc(index: usize) -> Loc {
    Loc {
        line: u32::try_from(index + 1).unwrap_or(u32::MAX),
        col: 1,
    }
}

/// The Doom thing a source thing's [`thing_loc`] names.
pub(crate) fn thing_of_loc(loc: Loc) -> usize {
    (loc.line as usize).saturating_sub(1)
}

/// Doom's angle in degrees (anticlockwise from east, y up) as portalcast's binary angle (y
/// down, so clockwise).
fn portalcast_angle(degrees: i16) -> u16 {
    ((-i32::from(degrees)).rem_euclid(360) * 65536 / 360) as u16
}

/// The whole-unit shift that centres `level` on the origin where it reaches past portalcast's
/// world limits (`±WORLD_COORD_MAX`) but fits within them: Doom's maps may lie anywhere in
/// ±32,767. No shift for a map already inside.
fn recentring(level: &DoomLevel) -> (i64, i64) {
    let limit = i64::from(WORLD_COORD_MAX);
    let axis = |coordinate: fn(&super::level::DoomVertex) -> i16| {
        let values = level.vertices.iter().map(|v| i64::from(coordinate(v)));
        let (low, high) = (values.clone().min().unwrap_or(0), values.max().unwrap_or(0));
        if low >= -limit && high <= limit {
            0
        } else {
            -(low + high).div_euclid(2)
        }
    };
    (axis(|v| v.x), axis(|v| v.y))
}

/// Map vertex `v` in Doom's axes, 24.8 units, shifted by `shift`.
fn corner_fx8(level: &DoomLevel, v: u16, shift: (i64, i64)) -> Point {
    let v = level.vertices[usize::from(v)];
    (
        (i64::from(v.x) + shift.0) << 8,
        (i64::from(v.y) + shift.1) << 8,
    )
}

/// The piece `place` (Doom's axes, 24.8 units, shifted by `shift`) lies strictly inside, if
/// one.
fn piece_at(level: &DoomLevel, pieces: &[Piece], place: Point, shift: (i64, i64)) -> Option<usize> {
    let corner = |v: u16| corner_fx8(level, v, shift);
    pieces.iter().position(|piece| {
        let n = piece.outline.len();
        (0..n).all(|k| {
            cross(
                corner(piece.outline[k]),
                corner(piece.outline[(k + 1) % n]),
                place,
            ) < 0
        })
    })
}

/// Where a Doom thing the import would take stands, if it can be taken.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum ThingPlace {
    /// Strictly inside a piece that is no door: its place (24.8, Doom's axes).
    Piece(Point),
    /// In a door's piece: portalcast's doors are shut when a map starts, and the compiler
    /// refuses a thing in one.
    Door,
    /// In no piece (outside the map, or on a line no 1/256 step takes it off).
    Nowhere,
}

/// The places of `level`'s things the import would take (of medium skill, of kinds it knows),
/// by thing index.
fn thing_places(
    level: &DoomLevel,
    pieces: &[Piece],
    movers: &Movers,
    shift: (i64, i64),
) -> Vec<(usize, ThingPlace)> {
    level
        .things
        .iter()
        .enumerate()
        .filter(|(_, thing)| things::in_the_game(thing) && things::kind_of(thing.kind).is_some())
        .map(|(index, thing)| {
            let place = (
                (i64::from(thing.x) + shift.0) << 8,
                (i64::from(thing.y) + shift.1) << 8,
            );
            let place = off_the_lines(level, pieces, place, shift);
            let at = match piece_at(level, pieces, place, shift) {
                None => ThingPlace::Nowhere,
                Some(piece) => match movers.sectors[usize::from(pieces[piece].sector)] {
                    Some(mover) if matches!(mover.motion, Motion::Door { .. }) => ThingPlace::Door,
                    _ => ThingPlace::Piece(place),
                },
            };
            (index, at)
        })
        .collect()
}

/// `place` (Doom's axes, 24.8 units, shifted by `shift`), moved by the least 1/256 steps that
/// take it off every piece's walls and into one piece, if it lies on one: the compiler must
/// find a player's sector, and the partition's diagonals may pass through a thing's place.
fn off_the_lines(
    level: &DoomLevel,
    pieces: &[Piece],
    place: (i64, i64),
    shift: (i64, i64),
) -> (i64, i64) {
    let corner = |v: u16| corner_fx8(level, v, shift);
    // Pieces run clockwise with y up: inside is right of every wall.
    let sides = |p: Point| {
        pieces.iter().map(move |piece| {
            let n = piece.outline.len();
            (0..n).map(move |k| {
                cross(
                    corner(piece.outline[k]),
                    corner(piece.outline[(k + 1) % n]),
                    p,
                )
            })
        })
    };
    // Strictly inside one piece, and on no wall line of a piece it touches (the compiler's
    // rule for finding a place's sector).
    let strictly_in_one = |p: Point| {
        let mut inside = 0;
        for piece in sides(p) {
            let sides: Vec<i128> = piece.collect();
            if sides.iter().all(|&side| side < 0) {
                inside += 1;
            } else if sides.iter().all(|&side| side <= 0) {
                return false;
            }
        }
        inside == 1
    };
    [
        (0, 0),
        (1, 0),
        (0, 1),
        (-1, 0),
        (0, -1),
        (1, 1),
        (-1, -1),
        (1, -1),
        (-1, 1),
    ]
    .into_iter()
    .map(|(dx, dy)| (place.0 + dx, place.1 + dy))
    .find(|&p| strictly_in_one(p))
    .unwrap_or(place)
}

/// What the map compiler says of `level`'s pieces as a portalcast map: nothing if it takes
/// them, else each complaint, one line each (its places are the pieces', not a file's). The
/// compiler checks in stages (values, outlines, portals, overlaps, the player's place, the
/// portal depth) and stops after the first that finds something: [`StandIns::On`] lets the
/// later ones run.
pub fn compiler_findings(level: &DoomLevel, pieces: &[Piece], stand_ins: StandIns) -> Vec<String> {
    let (source, names) = source(level, pieces, stand_ins, &|_| None);
    let things = source.things.iter().map(|thing| thing.sprite.value.clone());
    let middles = source
        .sectors
        .iter()
        .flat_map(|sector| &sector.walls)
        .filter_map(|wall| wall.middle.as_ref().map(|middle| middle.value.clone()));
    let mut sets: Vec<String> = things.chain(middles).collect();
    sets.sort();
    sets.dedup();
    let catalog = Catalog::new(names, sets, true);
    match map_build::build(&level.name, &source, &catalog) {
        Ok(_) => Vec::new(),
        Err(errors) => errors.into_iter().map(|(_, message)| message).collect(),
    }
}

/// What the mapping leaves out of `level` so far, one line each, for the importer's report
/// (issue 19: it names what it could not map and does not fail on it): closed sectors that do
/// not move (they stay shut), the doors and lifts it could not map and why, linedef specials it
/// does not map (by special, with how many lines have it) and the things it leaves out.
pub fn import_report(level: &DoomLevel, pieces: &[Piece]) -> Vec<String> {
    let mut report = Vec::new();
    let pieces_of = pieces_per_sector(level, pieces);
    let movers = Movers::of(level, &pieces_of);
    for (index, sector) in level.sectors.iter().enumerate() {
        if sector.floor < sector.ceiling || movers.sectors[index].is_some() {
            continue;
        }
        let why = if super::movers::manual_door(level, index as u16).is_some() {
            format!("a manual door cut into {} pieces", pieces_of[index])
        } else {
            let moved_by: Vec<String> = level
                .linedefs
                .iter()
                .filter(|line| sector.tag != 0 && line.tag == sector.tag && line.special != 0)
                .map(|line| line.special.to_string())
                .collect();
            if moved_by.is_empty() {
                "no special opens it".to_string()
            } else {
                format!("opened by specials {}", moved_by.join(", "))
            }
        };
        report.push(format!(
            "sector {index} is closed (floor {}, ceiling {}): {why}; it stays shut, drawn open 1 unit above its floor",
            sector.floor, sector.ceiling
        ));
    }
    report.extend(movers.left_out.iter().cloned());
    let mut specials: std::collections::BTreeMap<u16, usize> = std::collections::BTreeMap::new();
    for (index, line) in level.linedefs.iter().enumerate() {
        if line.special != 0 && !movers.maps_special_of(level, index) {
            *specials.entry(line.special).or_default() += 1;
        }
    }
    for (special, lines) in specials {
        report.push(format!(
            "linedef special {special} on {lines} line(s) is not mapped"
        ));
    }
    // Sector specials: the lights are mapped (`light_effect`), but not damage, secrets, timed
    // doors or the exit's damage; a map may hold `LIGHTS_MAX` light effects.
    let mut sector_specials: std::collections::BTreeMap<u16, usize> =
        std::collections::BTreeMap::new();
    for sector in &level.sectors {
        if sector.special != 0 && !matches!(sector.special, 1 | 2 | 3 | 8 | 12 | 13 | 17) {
            *sector_specials.entry(sector.special).or_default() += 1;
        }
    }
    for (special, sectors) in sector_specials {
        let what = if special == 4 {
            " (its strobe is mapped, its damage is not)"
        } else {
            ""
        };
        report.push(format!(
            "sector special {special} on {sectors} sector(s) is not mapped yet{what}"
        ));
    }
    let lit = pieces
        .iter()
        .filter(|piece| light_effect(level, piece.sector).is_some())
        .count();
    if lit > LIGHTS_MAX as usize {
        report.push(format!(
            "{lit} pieces have a light effect, more than the {LIGHTS_MAX} a map holds: the last {} are lit steadily",
            lit - LIGHTS_MAX as usize
        ));
    }
    let mut unknown: std::collections::BTreeMap<u16, usize> = std::collections::BTreeMap::new();
    let mut other_games = 0;
    for thing in &level.things {
        if NOT_DRAWN.contains(&thing.kind) {
            continue;
        }
        if !things::in_the_game(thing) {
            other_games += 1;
        } else if things::kind_of(thing.kind).is_none() {
            *unknown.entry(thing.kind).or_default() += 1;
        }
    }
    let places = thing_places(level, pieces, &movers, recentring(level));
    for (kind, what) in [
        (
            ThingPlace::Door,
            "stand in doors, which are shut when the map starts",
        ),
        (ThingPlace::Nowhere, "stand in no piece of the map"),
    ] {
        let count = places.iter().filter(|(_, place)| *place == kind).count();
        if count > 0 {
            report.push(format!("{count} things {what}: left out"));
        }
    }
    if other_games > 0 {
        report.push(format!(
            "{other_games} things are only in other skills or in multiplayer games: left out (the import takes medium skill's)"
        ));
    }
    for (kind, count) in unknown {
        report.push(format!(
            "thing type {kind} on {count} thing(s) is not a kind the import knows: left out"
        ));
    }
    report
}
