//! A Doom map's pieces as a portalcast map source, checked by the map compiler itself: the
//! importer's proof that its partition and its mapping of the map meet every rule a hand-made
//! map must (docs/MAP_FORMAT.md), and its list of what does not yet.
//!
//! The mapping, so far: each [`Piece`] a sector with its Doom sector's heights, flats and light
//! (`F_SKY1` ceilings the sky); a one-sided side a wall with its middle texture; a two-sided side
//! a portal with its upper and lower textures; an opening of the partition a portal without
//! any. Doom's y runs up the map and portalcast's down the screen's top view: y is negated, so
//! the map is not mirrored. The player stands at player 1's start. Things, movers and textures'
//! images are still to come.

use super::level::DoomLevel;
use super::partition::{Piece, PieceWall};
use crate::diag::Loc;
use crate::map_build::{self, Catalog};
use crate::source::{
    CeilingSource, SourceMap, SourcePlace, SourceSector, SourceVertex, SourceWall, Spanned,
};

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

/// `level`'s pieces as a map source, and the catalog of the names it uses.
fn source(level: &DoomLevel, pieces: &[Piece], stand_ins: StandIns) -> (SourceMap, Catalog) {
    let on = stand_ins == StandIns::On;
    let texture =
        |name: &str| texture(name).or_else(|| on.then(|| at(STAND_IN_TEXTURE.to_string())));
    let mut names: Vec<String> = Vec::new();
    let vertices = level
        .vertices
        .iter()
        .enumerate()
        .map(|(index, v)| SourceVertex {
            label: format!("vertex {index}"),
            x: at(i64::from(v.x)),
            y: at(-i64::from(v.y)),
        })
        .collect();
    let sectors = pieces
        .iter()
        .enumerate()
        .map(|(index, piece)| {
            let doom = &level.sectors[usize::from(piece.sector)];
            names.push(doom.floor_flat.clone());
            let ceiling = if doom.ceiling_flat == SKY_FLAT {
                CeilingSource::Sky
            } else {
                names.push(doom.ceiling_flat.clone());
                CeilingSource::Texture(at(doom.ceiling_flat.clone()))
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
                        loc: Loc::START,
                        start,
                        end,
                        texture: texture_name,
                        portal,
                        upper,
                        lower,
                        x_offset: at(i64::from(offsets.0)),
                        y_offset: at(i64::from(offsets.1)),
                        middle: None,
                        blocks: None,
                        translucent: None,
                        switch: None,
                        tag: None,
                        trigger: None,
                    }
                })
                .collect();
            SourceSector {
                label: format!("piece {index} (sector {})", piece.sector),
                loc: Loc::START,
                floor: at(i64::from(doom.floor)),
                ceil: at(if on {
                    i64::from(doom.ceiling.max(doom.floor.saturating_add(1)))
                } else {
                    i64::from(doom.ceiling)
                }),
                floor_texture: at(doom.floor_flat.clone()),
                ceiling,
                light: doom.light.clamp(0, 255) as u8,
                mover: None,
                light_effect: None,
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
    let player = SourcePlace {
        loc: Loc::START,
        x_fx8: at(i64::from(start.x) << 8),
        y_fx8: at(-i64::from(start.y) << 8),
        // Doom's angles run anticlockwise from east with y up; with y down they run clockwise.
        angle: ((-i32::from(start.angle)).rem_euclid(360) * 65536 / 360) as u16,
    };
    let catalog = Catalog::new(names, Vec::<String>::new(), true);
    (
        SourceMap {
            vertices,
            sectors,
            player,
            things: Vec::new(),
        },
        catalog,
    )
}

/// What the map compiler says of `level`'s pieces as a portalcast map: nothing if it takes
/// them, else each complaint, one line each (its places are the pieces', not a file's). The
/// compiler checks in stages (values, outlines, portals, overlaps, the player's place, the
/// portal depth) and stops after the first that finds something: [`StandIns::On`] lets the
/// later ones run.
pub fn compiler_findings(level: &DoomLevel, pieces: &[Piece], stand_ins: StandIns) -> Vec<String> {
    let (source, catalog) = source(level, pieces, stand_ins);
    match map_build::build(&level.name, &source, &catalog) {
        Ok(_) => Vec::new(),
        Err(errors) => errors.into_iter().map(|(_, message)| message).collect(),
    }
}
