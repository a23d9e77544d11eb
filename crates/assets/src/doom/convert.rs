//! A Doom map's pieces as a portalcast map source, checked by the map compiler itself: the
//! importer's proof that its partition and its mapping of the map meet every rule a hand-made
//! map must (docs/MAP_FORMAT.md), and its list of what does not yet.
//!
//! The mapping: each [`Piece`] a sector with its Doom sector's heights, flats (by
//! [`flat_name`]) and light ([`light_level`]), `F_SKY1` ceilings the sky; a manual door (a
//! closed sector of one piece behind a line with Doom's door specials 1, 26–28, 31–34, 117 or
//! 118) a door mover opening as Doom's does; a one-sided side a wall with its middle texture; a
//! two-sided side a portal with its upper and lower textures; an opening of the partition a
//! portal without any. Doom's y runs up the map and portalcast's down the screen's top view: y
//! is negated, so the map is not mirrored; a map reaching past portalcast's world limits but
//! fitting within them is recentred. The player stands at player 1's start (moved by a 1/256
//! step where it lies on a line). Things, remote doors and lifts are still to come
//! ([`import_report`] lists them).

use super::level::{DoomLevel, DoomSector};
use super::partition::{Piece, PieceWall};
use crate::diag::Loc;
use crate::geometry::{cross, Point};
use crate::map_build::{self, Catalog};
use crate::source::{
    CeilingSource, MoverKind, SourceLight, SourceMap, SourceMover, SourcePlace, SourceSector,
    SourceVertex, SourceWall, Spanned,
};
use portalcast_format::limits::{LIGHTS_MAX, WORLD_COORD_MAX};
use portalcast_format::{PlayerSize, LIGHT_FLICKER, LIGHT_GLOW, LIGHT_STROBE};

/// Doom's game ticks a second; portalcast's are 60.
const DOOM_TICKS_PER_SECOND: u32 = 35;

/// How a Doom door moves, in portalcast's units.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct DoorTiming {
    /// World units a portalcast tick.
    speed: u16,
    /// portalcast ticks it stays open.
    wait: u16,
}

/// Doom's door speed, 2 units a Doom tick (70 a second): 1 a portalcast tick (60 a second).
const DOOR_SPEED: u16 = 1;
/// Doom's blazing doors, 8 units a Doom tick (280 a second): 5 a portalcast tick.
const BLAZING_DOOR_SPEED: u16 = 5;
/// Doom's doors stay open 150 Doom ticks: 257 of portalcast's.
const DOOR_WAIT: u16 = (150 * 60 / DOOM_TICKS_PER_SECOND) as u16;
/// A door that opens for good waits as long as a portalcast door can.
const STAYS_OPEN: u16 = u16::MAX;

/// Doom's manual doors (opened by using the door's own line, from the side facing away from
/// it): specials 1, 26, 27 and 28 open, wait and close (the last three need a key portalcast
/// does not have: they open as plain doors); 31 to 34 open and stay; 117 and 118 are the fast
/// ("blazing") ones of each.
const MANUAL_DOORS: [(u16, DoorTiming); 10] = {
    const fn timing(speed: u16, wait: u16) -> DoorTiming {
        DoorTiming { speed, wait }
    }
    let (closes, stays) = (
        timing(DOOR_SPEED, DOOR_WAIT),
        timing(DOOR_SPEED, STAYS_OPEN),
    );
    [
        (1, closes),
        (26, closes),
        (27, closes),
        (28, closes),
        (31, stays),
        (32, stays),
        (33, stays),
        (34, stays),
        (117, timing(BLAZING_DOOR_SPEED, DOOR_WAIT)),
        (118, timing(BLAZING_DOOR_SPEED, STAYS_OPEN)),
    ]
};

/// The door Doom's sector `sector` is, if it is a manual one: closed, behind a two-sided line
/// with a manual door special, opening (as Doom's `EV_VerticalDoor`) to 4 below the lowest
/// ceiling round it. Its open ceiling and its timing.
fn manual_door(level: &DoomLevel, sector: u16) -> Option<(i16, DoorTiming)> {
    let own = &level.sectors[usize::from(sector)];
    if own.floor < own.ceiling {
        return None;
    }
    let sector_of = |side: u16| level.sidedefs[usize::from(side)].sector;
    let timing = level.linedefs.iter().find_map(|line| {
        let faces_door = line.two_sided() && sector_of(line.sides[1]) == sector;
        MANUAL_DOORS
            .iter()
            .find(|(special, _)| faces_door && *special == line.special)
            .map(|&(_, timing)| timing)
    })?;
    let lowest = neighbours(level, sector).map(|other| other.ceiling).min()?;
    let open = lowest.checked_sub(4)?;
    (open > own.floor).then_some((open, timing))
}

/// Doom's ticks as portalcast's (60 a second), rounded.
const fn from_doom_ticks(ticks: u32) -> u16 {
    ((ticks * 60 + DOOM_TICKS_PER_SECOND / 2) / DOOM_TICKS_PER_SECOND) as u16
}

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
    neighbours(level, sector)
        .map(|other| other.light)
        .fold(most, i16::min)
}

/// The sectors across the two-sided lines of Doom's sector `sector` (one a line, so a sector
/// may come more than once).
fn neighbours(level: &DoomLevel, sector: u16) -> impl Iterator<Item = &DoomSector> {
    let sector_of = |side: u16| level.sidedefs[usize::from(side)].sector;
    level
        .linedefs
        .iter()
        .filter(|line| line.two_sided())
        .filter_map(move |line| {
            let (right, left) = (sector_of(line.sides[0]), sector_of(line.sides[1]));
            match (right == sector, left == sector) {
                (true, false) => Some(left),
                (false, true) => Some(right),
                _ => None,
            }
        })
        .map(|other| &level.sectors[usize::from(other)])
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

/// Doom's thing type of player 1's start.
const PLAYER_1_START: u16 = 1;

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
pub(crate) fn source(
    level: &DoomLevel,
    pieces: &[Piece],
    stand_ins: StandIns,
) -> (SourceMap, Vec<String>) {
    let on = stand_ins == StandIns::On;
    let texture =
        |name: &str| texture(name).or_else(|| on.then(|| at(STAND_IN_TEXTURE.to_string())));
    let mut names: Vec<String> = Vec::new();
    let pieces_of = pieces_per_sector(level, pieces);
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
            // A door cut into several pieces would need them moving as one: not yet (they
            // stay shut, and the compiler says so).
            let door = manual_door(level, piece.sector)
                .filter(|_| pieces_of[usize::from(piece.sector)] == 1);
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
                    let (texture_name, portal, upper, lower, offsets) = match piece.walls[k] {
                        PieceWall::Solid { linedef, side: s } => {
                            let side = side(linedef, s);
                            (
                                texture(&side.middle),
                                None,
                                None,
                                None,
                                (side.x_offset, side.y_offset),
                            )
                        }
                        PieceWall::Portal {
                            linedef,
                            side: s,
                            piece: behind,
                        } => {
                            let side = side(linedef, s);
                            (
                                None,
                                Some(at(behind as usize)),
                                texture(&side.upper),
                                texture(&side.lower),
                                (side.x_offset, side.y_offset),
                            )
                        }
                        PieceWall::Open { piece: beside } => {
                            (None, Some(at(beside as usize)), None, None, (0, 0))
                        }
                    };
                    for name in [&texture_name, &upper, &lower].into_iter().flatten() {
                        names.push(name.value.clone());
                    }
                    SourceWall {
                        texture: texture_name,
                        portal,
                        upper,
                        lower,
                        x_offset: at(i64::from(offsets.0)),
                        y_offset: at(i64::from(offsets.1)),
                        ..SourceWall::new(Loc::START, start, end)
                    }
                })
                .collect();
            SourceSector {
                label: format!("piece {index} (sector {})", piece.sector),
                loc: Loc::START,
                floor: at(i64::from(doom.floor)),
                // A door is drawn open (docs/MAP_FORMAT.md, "Movers") and starts shut.
                ceil: at(match door {
                    Some((open, _)) => i64::from(open),
                    None if on => i64::from(doom.ceiling.max(doom.floor.saturating_add(1))),
                    None => i64::from(doom.ceiling),
                }),
                floor_texture: at(floor_flat),
                ceiling,
                light: light_level(doom.light),
                mover: door.map(|(_, timing)| SourceMover {
                    kind: MoverKind::Door,
                    loc: Loc::START,
                    height: None,
                    touch: false,
                    locked: None,
                    speed: timing.speed,
                    wait: timing.wait,
                    tag: None,
                }),
                light_effect: light_effect(level, piece.sector).filter(|_| {
                    let room = lights_left > 0;
                    lights_left = lights_left.saturating_sub(1);
                    room
                }),
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
        // Doom's angles run anticlockwise from east with y up; with y down they run clockwise.
        angle: ((-i32::from(start.angle)).rem_euclid(360) * 65536 / 360) as u16,
    };
    (
        SourceMap {
            vertices,
            sectors,
            player,
            player_size: PlayerSize::DOOM,
            things: Vec::new(),
        },
        names,
    )
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

/// `place` (Doom's axes, 24.8 units, shifted by `shift`), moved by the least 1/256 steps that
/// take it off every piece's walls and into one piece, if it lies on one: the compiler must
/// find a player's sector, and the partition's diagonals may pass through a thing's place.
fn off_the_lines(
    level: &DoomLevel,
    pieces: &[Piece],
    place: (i64, i64),
    shift: (i64, i64),
) -> (i64, i64) {
    let corner = |v: u16| {
        let v = level.vertices[usize::from(v)];
        (
            (i64::from(v.x) + shift.0) << 8,
            (i64::from(v.y) + shift.1) << 8,
        )
    };
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
    let (source, names) = source(level, pieces, stand_ins);
    let catalog = Catalog::new(names, Vec::<String>::new(), true);
    match map_build::build(&level.name, &source, &catalog) {
        Ok(_) => Vec::new(),
        Err(errors) => errors.into_iter().map(|(_, message)| message).collect(),
    }
}

/// What the mapping leaves out of `level` so far, one line each, for the importer's report
/// (issue 19: it names what it could not map and does not fail on it): closed sectors that are
/// not manual doors of one piece (they stay shut), linedef specials it does not map (by
/// special, with how many lines have it) and the things (not imported yet).
pub fn import_report(level: &DoomLevel, pieces: &[Piece]) -> Vec<String> {
    let mut report = Vec::new();
    let pieces_of = pieces_per_sector(level, pieces);
    for (index, sector) in level.sectors.iter().enumerate() {
        if sector.floor < sector.ceiling {
            continue;
        }
        let door = manual_door(level, index as u16).is_some();
        let why = if door {
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
                format!(
                    "opened by specials {} (not mapped yet)",
                    moved_by.join(", ")
                )
            }
        };
        if !door || pieces_of[index] != 1 {
            report.push(format!(
                "sector {index} is closed (floor {}, ceiling {}): {why}; it stays shut, drawn open 1 unit above its floor",
                sector.floor, sector.ceiling
            ));
        }
    }
    let mut specials: std::collections::BTreeMap<u16, usize> = std::collections::BTreeMap::new();
    for line in &level.linedefs {
        let mapped = MANUAL_DOORS
            .iter()
            .any(|(special, _)| *special == line.special);
        if line.special != 0 && !mapped {
            *specials.entry(line.special).or_default() += 1;
        }
    }
    for (special, lines) in specials {
        report.push(format!(
            "linedef special {special} on {lines} line(s) is not mapped yet"
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
    let others = level
        .things
        .iter()
        .filter(|thing| thing.kind != PLAYER_1_START)
        .count();
    if others > 0 {
        report.push(format!(
            "{others} things are not imported yet (only player 1's start is used)"
        ));
    }
    report
}
