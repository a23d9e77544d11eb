//! A Doom map as portalcast sees one: each GL subsector a convex cell, each of its segs a wall
//! (solid on a one-sided linedef; a portal into the partner's cell on a two-sided linedef or
//! along a partition line).

use super::gl::{FixedVertex, GlNodes};
use super::level::{DoomLevel, NONE};
use super::partition::PieceWall;

/// A convex cell: its outline (vertices in 16.16 units, each wall from one vertex to the next,
/// in the map's seg order) and the Doom sector it is part of. Its walls' `piece` fields name
/// cells.
#[derive(Clone, Debug)]
pub struct Cell {
    /// The Doom sector.
    pub sector: u16,
    /// Its corners in order; wall `k` runs from corner `k` to corner `k + 1`.
    pub outline: Vec<FixedVertex>,
    /// Its walls.
    pub walls: Vec<PieceWall>,
}

/// Why a subsector does not make a cell.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum CellError {
    /// Its segs do not join end to start round it.
    Open {
        /// The subsector.
        subsector: u32,
        /// The seg whose end is not the next one's start.
        seg: u32,
    },
    /// A seg's linedef or side does not exist.
    BadLinedef {
        /// The subsector.
        subsector: u32,
        /// The seg.
        seg: u32,
    },
    /// A seg on a two-sided linedef has no partner.
    NoPartner {
        /// The subsector.
        subsector: u32,
        /// The seg.
        seg: u32,
    },
    /// Its segs face more than one Doom sector, or none (only mini-segs).
    Sectors {
        /// The subsector.
        subsector: u32,
    },
}

/// The map's cells, one per GL subsector, in the node builder's order.
pub fn cells(level: &DoomLevel, nodes: &GlNodes) -> Result<Vec<Cell>, CellError> {
    let mut cell_of_seg = vec![0u32; nodes.segs.len()];
    for (index, &(first, count)) in nodes.subsectors.iter().enumerate() {
        for seg in first..first + count {
            cell_of_seg[seg as usize] = index as u32;
        }
    }
    nodes
        .subsectors
        .iter()
        .enumerate()
        .map(|(index, &(first, count))| {
            let subsector = index as u32;
            let segs = &nodes.segs[first as usize..(first + count) as usize];
            let mut sector = None;
            let mut walls = Vec::with_capacity(segs.len());
            for (offset, seg) in segs.iter().enumerate() {
                let at = first + offset as u32;
                if seg.end != segs[(offset + 1) % segs.len()].start {
                    return Err(CellError::Open { subsector, seg: at });
                }
                let wall = match seg.linedef {
                    None => PieceWall::Open {
                        piece: cell_of_seg[seg
                            .partner
                            .ok_or(CellError::NoPartner { subsector, seg: at })?
                            as usize],
                    },
                    Some(linedef) => {
                        let line = level
                            .linedefs
                            .get(usize::from(linedef))
                            .filter(|_| seg.side < 2)
                            .ok_or(CellError::BadLinedef { subsector, seg: at })?;
                        let side = line.sides[usize::from(seg.side)];
                        if side == NONE {
                            return Err(CellError::BadLinedef { subsector, seg: at });
                        }
                        let faces = level.sidedefs[usize::from(side)].sector;
                        if sector.is_some_and(|known| known != faces) {
                            return Err(CellError::Sectors { subsector });
                        }
                        sector = Some(faces);
                        if line.two_sided() {
                            let partner = seg
                                .partner
                                .ok_or(CellError::NoPartner { subsector, seg: at })?;
                            PieceWall::Portal {
                                linedef,
                                side: seg.side,
                                piece: cell_of_seg[partner as usize],
                            }
                        } else {
                            PieceWall::Solid {
                                linedef,
                                side: seg.side,
                            }
                        }
                    }
                };
                walls.push(wall);
            }
            Ok(Cell {
                sector: sector.ok_or(CellError::Sectors { subsector })?,
                outline: segs.iter().map(|seg| seg.start).collect(),
                walls,
            })
        })
        .collect()
}

/// How far `outline` is from convex with each vertex rounded to the nearest multiple of
/// `2^(16 − bits)` of its 16.16 units (`bits` fraction bits: 16 as the node builder gave it, 8
/// the 24.8 of portalcast's world, 0 whole units): the largest distance, in map units, of a
/// vertex where the outline turns against its winding from the line through its two
/// neighbours (0 if it never does). `None` if the rounding gives a wall of zero length.
pub fn reflex_depth(outline: &[FixedVertex], bits: u32) -> Option<f64> {
    let step = 1i64 << (16 - bits);
    let round = |v: i32| (i64::from(v) + step / 2).div_euclid(step) * step;
    let points: Vec<(f64, f64)> = outline
        .iter()
        .map(|v| (round(v.x) as f64 / 65536.0, round(v.y) as f64 / 65536.0))
        .collect();
    let n = points.len();
    let winding: f64 = (0..n)
        .map(|k| points[k].0 * points[(k + 1) % n].1 - points[(k + 1) % n].0 * points[k].1)
        .sum();
    let mut deepest = 0f64;
    for k in 0..n {
        let (a, b, c) = (points[k], points[(k + 1) % n], points[(k + 2) % n]);
        if a == b {
            return None;
        }
        let turn = (b.0 - a.0) * (c.1 - b.1) - (b.1 - a.1) * (c.0 - b.0);
        if turn * winding < 0.0 {
            let base = ((c.0 - a.0).powi(2) + (c.1 - a.1).powi(2)).sqrt();
            deepest = deepest.max(turn.abs() / base);
        }
    }
    Some(deepest)
}
