//! A Doom map's own convex partition, with no new vertex: each sector's outline (its loops of
//! linedef sides, holes included) is triangulated by ear clipping with diagonals between its
//! own vertices, and the triangles are merged back into convex pieces wherever a diagonal can
//! go (Hertel and Mehlhorn's rule: at most four times the fewest pieces). Every corner is a map
//! vertex, in whole units, so every piece is exactly convex in portalcast's world, and the two
//! sides of a two-sided linedef are one edge of one piece on each side: portals pair exactly.
//! A node builder's subsectors need new vertices where its partition lines cross linedefs
//! (fractions no binary grid holds: a third of a unit, on Freedoom's E1M1), and the cells they
//! make bend a little on any grid.
//!
//! Coordinates are Doom's (y up). Loops run with their sector on the right, as a linedef's
//! right side faces its right sidedef's sector: an outer loop clockwise, a hole anticlockwise.

use std::collections::BTreeMap;

use super::level::{DoomLevel, NONE};
use crate::geometry::{cross, double_area, segments_touch, within_box, Point};

/// What a piece's (or a GL cell's) wall shows and where it leads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PieceWall {
    /// A side of a linedef whose other side is no sector's (one-sided).
    Solid {
        /// The linedef.
        linedef: u16,
        /// Its side: 0 right, 1 left.
        side: u16,
    },
    /// A side of a two-sided linedef, into the piece on its other side.
    Portal {
        /// The linedef.
        linedef: u16,
        /// Its side: 0 right, 1 left.
        side: u16,
        /// The piece behind.
        piece: u32,
    },
    /// A diagonal the partition drew through a sector, into the piece beside.
    Open {
        /// The piece beside.
        piece: u32,
    },
}

/// A convex piece of one sector: its corners (map vertex indices), its sector on the right of
/// each wall (clockwise, y up), wall `k` from corner `k` to corner `k + 1`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Piece {
    /// The Doom sector.
    pub sector: u16,
    /// Its corners.
    pub outline: Vec<u16>,
    /// Its walls.
    pub walls: Vec<PieceWall>,
}

/// Why a map does not partition.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PartitionError {
    /// A sector's sides do not close into loops: the map has a gap at this vertex.
    Unclosed {
        /// The sector.
        sector: u16,
        /// Where its boundary stops.
        vertex: u16,
    },
    /// A sector's outline could not be cut into triangles (it crosses itself, or a hole lies
    /// outside every outer loop).
    Tangled {
        /// The sector.
        sector: u16,
    },
}

impl std::fmt::Display for PartitionError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PartitionError::Unclosed { sector, vertex } => write!(
                f,
                "sector {sector}'s sides do not close at vertex {vertex}: close the gap in the editor"
            ),
            PartitionError::Tangled { sector } => write!(
                f,
                "sector {sector}'s outline crosses itself or has a hole outside it: fix its lines in the editor"
            ),
        }
    }
}

/// A directed side: from vertex `from` to `to`, its sector on the right.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Side {
    from: u16,
    to: u16,
    wall: PieceWall,
}

/// Which half-turn `v` lies in going anticlockwise from `reference`, and a key within it:
/// angles in `(0, π]` are half 0, `(π, 2π]` half 1 (so `reference` itself comes last).
fn after(reference: Point, v: Point) -> (u8, Point) {
    let c = i128::from(reference.0) * i128::from(v.1) - i128::from(reference.1) * i128::from(v.0);
    let d = i128::from(reference.0) * i128::from(v.0) + i128::from(reference.1) * i128::from(v.1);
    let half = if c > 0 || (c == 0 && d < 0) { 0 } else { 1 };
    (half, v)
}

/// Whether `a` comes before `b` going anticlockwise from `reference` (angles in `(0, 2π]`).
fn sooner(reference: Point, a: Point, b: Point) -> bool {
    let ((ha, a), (hb, b)) = (after(reference, a), after(reference, b));
    if ha != hb {
        return ha < hb;
    }
    i128::from(a.0) * i128::from(b.1) - i128::from(a.1) * i128::from(b.0) > 0
}

/// Whether `p` is inside triangle `a b c` (anticlockwise) or on its edges.
fn in_triangle(p: Point, a: Point, b: Point, c: Point) -> bool {
    cross(a, b, p) >= 0 && cross(b, c, p) >= 0 && cross(c, a, p) >= 0
}

/// The map's pieces, sector by sector.
pub fn partition(level: &DoomLevel) -> Result<Vec<Piece>, PartitionError> {
    let point = |v: u16| {
        let v = level.vertices[usize::from(v)];
        (i64::from(v.x), i64::from(v.y))
    };
    // Each sector's sides, the sector on the right; a line with the same sector on both sides
    // bounds nothing and is left out.
    let mut sides: BTreeMap<u16, Vec<Side>> = BTreeMap::new();
    for (index, line) in level.linedefs.iter().enumerate() {
        if point(line.start) == point(line.end) {
            continue;
        }
        let sector_of =
            |side: u16| (side != NONE).then(|| level.sidedefs[usize::from(side)].sector);
        let (right, left) = (sector_of(line.sides[0]), sector_of(line.sides[1]));
        if right == left {
            continue;
        }
        let linedef = index as u16;
        for (side, sector, from, to) in [
            (0u16, right, line.start, line.end),
            (1, left, line.end, line.start),
        ] {
            let Some(sector) = sector else {
                continue;
            };
            let wall = if right.is_some() && left.is_some() {
                // The piece behind is filled in once both sides are cut.
                PieceWall::Portal {
                    linedef,
                    side,
                    piece: PORTAL_UNRESOLVED,
                }
            } else {
                PieceWall::Solid { linedef, side }
            };
            sides
                .entry(sector)
                .or_default()
                .push(Side { from, to, wall });
        }
    }
    let mut pieces: Vec<Piece> = Vec::new();
    for (&sector, sector_sides) in &sides {
        for polygon in polygons(sector, sector_sides, &point)? {
            let first = pieces.len() as u32;
            let cut = cut_convex(&polygon, &point).ok_or(PartitionError::Tangled { sector })?;
            for (outline, walls) in cut {
                let walls = walls
                    .into_iter()
                    .map(|wall| match wall {
                        PieceWall::Open { piece } => PieceWall::Open {
                            piece: first + piece,
                        },
                        other => other,
                    })
                    .collect();
                pieces.push(Piece {
                    sector,
                    outline,
                    walls,
                });
            }
        }
    }
    // Each portal leads to the piece whose portal runs the other way between the same two
    // places: the same linedef's other side, or where a sector of no area lies between two
    // lines over each other, the other line's.
    let mut by_ends: BTreeMap<(Point, Point), u32> = BTreeMap::new();
    for (index, piece) in pieces.iter().enumerate() {
        let n = piece.outline.len();
        for (k, wall) in piece.walls.iter().enumerate() {
            if let PieceWall::Portal { .. } = wall {
                let ends = (point(piece.outline[k]), point(piece.outline[(k + 1) % n]));
                by_ends.insert(ends, index as u32);
            }
        }
    }
    for piece in &mut pieces {
        let n = piece.outline.len();
        for k in 0..n {
            let ends = (point(piece.outline[(k + 1) % n]), point(piece.outline[k]));
            if let PieceWall::Portal { piece: behind, .. } = &mut piece.walls[k] {
                *behind = *by_ends.get(&ends).ok_or(PartitionError::Tangled {
                    sector: piece.sector,
                })?;
            }
        }
    }
    Ok(pieces)
}

/// A polygon to cut: its outer loop and its holes, each as (corner, the side leaving it).
struct Polygon {
    outer: Vec<(u16, PieceWall)>,
    holes: Vec<Vec<(u16, PieceWall)>>,
}

/// A sector's sides chained into loops (at a vertex several sides leave, the one turning
/// furthest right of the way in: the loop that keeps the sector on its right), each hole given
/// to the smallest outer loop round it.
fn polygons(
    sector: u16,
    sides: &[Side],
    point: &impl Fn(u16) -> Point,
) -> Result<Vec<Polygon>, PartitionError> {
    let mut leaving: BTreeMap<u16, Vec<usize>> = BTreeMap::new();
    for (index, side) in sides.iter().enumerate() {
        leaving.entry(side.from).or_default().push(index);
    }
    let mut used = vec![false; sides.len()];
    let mut loops: Vec<Vec<(u16, PieceWall)>> = Vec::new();
    for start in 0..sides.len() {
        if used[start] {
            continue;
        }
        let mut chain = Vec::new();
        let mut at = start;
        loop {
            used[at] = true;
            let side = sides[at];
            chain.push((side.from, side.wall));
            if side.to == sides[start].from {
                break;
            }
            let back = (
                point(side.from).0 - point(side.to).0,
                point(side.from).1 - point(side.to).1,
            );
            let next = leaving
                .get(&side.to)
                .into_iter()
                .flatten()
                .copied()
                .filter(|&candidate| !used[candidate])
                .reduce(|best, candidate| {
                    let direction = |index: usize| {
                        let (a, b) = (point(sides[index].from), point(sides[index].to));
                        (b.0 - a.0, b.1 - a.1)
                    };
                    if sooner(back, direction(candidate), direction(best)) {
                        candidate
                    } else {
                        best
                    }
                })
                .ok_or(PartitionError::Unclosed {
                    sector,
                    vertex: side.to,
                })?;
            at = next;
        }
        loops.push(chain);
    }
    let points_of = |chain: &[(u16, PieceWall)]| -> Vec<Point> {
        chain.iter().map(|&(vertex, _)| point(vertex)).collect()
    };
    // A loop round no area (two lines over each other, a Doom mapper's trick) bounds nothing:
    // its sides' other sectors meet through it (see `partition`).
    let (mut outers, mut holes): (Vec<_>, Vec<_>) = loops
        .into_iter()
        .filter(|chain| double_area(&points_of(chain)) != 0)
        .partition(|chain| double_area(&points_of(chain)) < 0);
    outers.sort_by_key(|chain| -double_area(&points_of(chain)).abs());
    let mut polygons: Vec<Polygon> = outers
        .into_iter()
        .map(|outer| Polygon {
            outer,
            holes: Vec::new(),
        })
        .collect();
    for hole in holes.drain(..) {
        let probe = points_of(&hole);
        // The smallest outer loop round the hole: the last round it, the largest first.
        let home = polygons
            .iter()
            .rposition(|polygon| {
                let outer = points_of(&polygon.outer);
                probe.iter().all(|&p| !outside(&outer, p))
            })
            .ok_or(PartitionError::Tangled { sector })?;
        polygons[home].holes.push(hole);
    }
    Ok(polygons)
}

/// Whether `p` is strictly outside the loop `points` (on it counts as inside).
fn outside(points: &[Point], p: Point) -> bool {
    let n = points.len();
    let mut winding = 0i32;
    for k in 0..n {
        let (a, b) = (points[k], points[(k + 1) % n]);
        let c = cross(a, b, p);
        if c == 0 && within_box(a, b, p) {
            return false;
        }
        if a.1 <= p.1 {
            if b.1 > p.1 && c > 0 {
                winding += 1;
            }
        } else if b.1 <= p.1 && c < 0 {
            winding -= 1;
        }
    }
    winding == 0
}

/// A corner of the loop being cut: its map vertex, and the wall leaving it (a side, or one of a
/// bridge's two walks: [`BRIDGE`]).
type Corner = (u16, PieceWall);

/// The wall of a bridge's walk (between a hole and the loop it is cut into) while the loop is
/// cut: an opening whose piece is known only once the pieces are made.
const BRIDGE: PieceWall = PieceWall::Open { piece: u32::MAX };

/// A portal's wall while the sectors are cut: its piece behind is known only once both sides'
/// pieces are made.
const PORTAL_UNRESOLVED: u32 = u32::MAX;

/// Cuts `polygon` into convex pieces: holes bridged into the outer loop, the loop cut into
/// triangles, the triangles merged back across every diagonal both of whose ends stay convex.
/// Pieces' `Open` walls name pieces by their index in the result. `None` if it cannot.
fn cut_convex(
    polygon: &Polygon,
    point: &impl Fn(u16) -> Point,
) -> Option<Vec<(Vec<u16>, Vec<PieceWall>)>> {
    // Straight corners (a vertex in the middle of a straight run of sides) take no part in
    // the cutting: they go back into the piece whose wall passes over them.
    let mut loop_: Vec<Corner> = polygon.outer.clone();
    let hole_sides: Vec<(Point, Point)> = polygon
        .holes
        .iter()
        .flat_map(|hole| (0..hole.len()).map(move |k| (hole[k].0, hole[(k + 1) % hole.len()].0)))
        .map(|(a, b)| (point(a), point(b)))
        .collect();
    for hole in bridge_order(&polygon.holes, point) {
        loop_ = bridge(&loop_, &polygon.holes[hole], &hole_sides, point)?;
    }
    // Only a corner the loop passes once, between two sides of the map: at a bridge's end or
    // where the loop touches itself, leaving a corner out would lay two walls over each other.
    let mut passes: BTreeMap<Point, usize> = BTreeMap::new();
    for &(vertex, _) in &loop_ {
        *passes.entry(point(vertex)).or_default() += 1;
    }
    let straight: Vec<bool> = (0..loop_.len())
        .map(|k| {
            let n = loop_.len();
            let (a, b, c) = (
                point(loop_[(k + n - 1) % n].0),
                point(loop_[k].0),
                point(loop_[(k + 1) % n].0),
            );
            passes[&b] == 1
                && loop_[k].1 != BRIDGE
                && loop_[(k + n - 1) % n].1 != BRIDGE
                && cross(a, b, c) == 0
                && (b.0 - a.0) * (c.0 - b.0) + (b.1 - a.1) * (c.1 - b.1) > 0
        })
        .collect();
    // Triangles, each as three positions in `loop_`.
    let kept: Vec<usize> = (0..loop_.len()).filter(|&k| !straight[k]).collect();
    let triangles = ear_clip(&kept, &loop_, point)?;
    merge(&loop_, &straight, &triangles, point)
}

/// The holes in the order they are bridged: the one reaching furthest right first.
fn bridge_order(holes: &[Vec<Corner>], point: &impl Fn(u16) -> Point) -> Vec<usize> {
    let mut order: Vec<usize> = (0..holes.len()).collect();
    order.sort_by_key(|&hole| {
        std::cmp::Reverse(
            holes[hole]
                .iter()
                .map(|&(v, _)| point(v))
                .max()
                .unwrap_or((0, 0)),
        )
    });
    order
}

/// `loop_` with `hole` spliced in through a bridge from the hole's rightmost corner to the
/// nearest corner of the loop it sees (crossing no side of either), walked there and back.
fn bridge(
    loop_: &[Corner],
    hole: &[Corner],
    hole_sides: &[(Point, Point)],
    point: &impl Fn(u16) -> Point,
) -> Option<Vec<Corner>> {
    if let Some(spliced) = splice_touching(loop_, hole, point) {
        return Some(spliced);
    }
    let (h, &(m, _)) = hole
        .iter()
        .enumerate()
        .max_by_key(|&(_, &(v, _))| point(v))?;
    let pm = point(m);
    let mut candidates: Vec<usize> = (0..loop_.len()).collect();
    candidates.sort_by_key(|&k| {
        let p = point(loop_[k].0);
        (p.0 - pm.0).pow(2) + (p.1 - pm.1).pow(2)
    });
    let sides_of = |chain: &[Corner]| -> Vec<(Point, Point)> {
        (0..chain.len())
            .map(|k| (point(chain[k].0), point(chain[(k + 1) % chain.len()].0)))
            .collect()
    };
    let mut all_sides = sides_of(loop_);
    all_sides.extend_from_slice(hole_sides);
    let n = loop_.len();
    // The bridge leaves the hole's corner m into the sector and enters the loop's corner k from
    // it (never along a side), touches no other side, and ends at no place the hole touches.
    let (hole_prev, hole_next) = (
        point(hole[(h + hole.len() - 1) % hole.len()].0),
        point(hole[(h + 1) % hole.len()].0),
    );
    let visible = |k: usize| {
        let p = point(loop_[k].0);
        let (prev, next) = (point(loop_[(k + n - 1) % n].0), point(loop_[(k + 1) % n].0));
        p != pm
            && into_corner(hole_prev, pm, hole_next, p)
            && into_corner(prev, p, next, pm)
            && !hole.iter().any(|&(v, _)| point(v) == p)
            && all_sides.iter().all(|&(a, b)| {
                a == p || b == p || a == pm || b == pm || !segments_touch(p, pm, a, b)
            })
    };
    let k = candidates.into_iter().find(|&k| visible(k))?;
    let mut spliced = Vec::with_capacity(loop_.len() + hole.len() + 2);
    spliced.extend_from_slice(&loop_[..=k]);
    // Over the bridge and back: two walls the merge keeps, openings between the pieces on
    // either side of it.
    spliced.last_mut()?.1 = BRIDGE;
    for offset in 0..hole.len() {
        spliced.push(hole[(h + offset) % hole.len()]);
    }
    spliced.push((m, BRIDGE));
    spliced.push((loop_[k].0, loop_[k].1));
    spliced.extend_from_slice(&loop_[k + 1..]);
    Some(spliced)
}

/// Whether `x` lies strictly inside the sector's side of the corner `p` between the sides from
/// `prev` and to `next` of a loop with its sector on the right.
fn into_corner(prev: Point, p: Point, next: Point, x: Point) -> bool {
    if cross(prev, p, next) <= 0 {
        cross(prev, p, x) < 0 && cross(p, next, x) < 0
    } else {
        cross(prev, p, x) < 0 || cross(p, next, x) < 0
    }
}

/// `loop_` with `hole` spliced in at a place both have, if the hole touches the loop there
/// from inside the loop's corner: walked round from that corner and back to it, no bridge.
fn splice_touching(
    loop_: &[Corner],
    hole: &[Corner],
    point: &impl Fn(u16) -> Point,
) -> Option<Vec<Corner>> {
    let (n, m) = (loop_.len(), hole.len());
    for k in 0..n {
        let p = point(loop_[k].0);
        let (prev, next) = (point(loop_[(k + n - 1) % n].0), point(loop_[(k + 1) % n].0));
        for j in 0..m {
            if point(hole[j].0) != p {
                continue;
            }
            let (hole_prev, hole_next) =
                (point(hole[(j + m - 1) % m].0), point(hole[(j + 1) % m].0));
            if !(into_corner(prev, p, next, hole_prev) && into_corner(prev, p, next, hole_next)) {
                continue;
            }
            let mut spliced = Vec::with_capacity(n + m + 1);
            spliced.extend_from_slice(&loop_[..k]);
            for offset in 0..m {
                spliced.push(hole[(j + offset) % m]);
            }
            spliced.push(loop_[k]);
            spliced.extend_from_slice(&loop_[k + 1..]);
            return Some(spliced);
        }
    }
    None
}

/// Ear clipping of the clockwise loop `kept` (positions in `loop_`): triangles as positions,
/// each clockwise. An ear is a corner turning right whose triangle holds no other corner left
/// in the ring (a corner at the same place as one of the triangle's counts as that one; the
/// straight corners, on the loop's sides, cannot be inside without a kept one).
fn ear_clip(
    kept: &[usize],
    loop_: &[Corner],
    point: &impl Fn(u16) -> Point,
) -> Option<Vec<[usize; 3]>> {
    let mut ring: Vec<usize> = kept.to_vec();
    let mut triangles = Vec::new();
    let all: Vec<Point> = loop_.iter().map(|&(v, _)| point(v)).collect();
    while ring.len() > 3 {
        let n = ring.len();
        let ear = (0..n).find(|&k| {
            let (a, b, c) = (ring[(k + n - 1) % n], ring[k], ring[(k + 1) % n]);
            let (pa, pb, pc) = (all[a], all[b], all[c]);
            // Clockwise: a right turn is negative.
            if cross(pa, pb, pc) >= 0 {
                return false;
            }
            ring.iter().all(|&index| {
                let p = all[index];
                index == a
                    || index == b
                    || index == c
                    || p == pa
                    || p == pb
                    || p == pc
                    || !in_triangle(p, pc, pb, pa)
            })
        })?;
        triangles.push([ring[(ear + n - 1) % n], ring[ear], ring[(ear + 1) % n]]);
        ring.remove(ear);
    }
    if ring.len() == 3 {
        let (a, b, c) = (all[ring[0]], all[ring[1]], all[ring[2]]);
        if cross(a, b, c) < 0 {
            triangles.push([ring[0], ring[1], ring[2]]);
        } else if cross(a, b, c) > 0 {
            return None;
        }
    }
    Some(triangles)
}

/// The triangles merged into convex pieces, with the straight corners put back into the walls
/// that pass over them, and each piece's walls.
fn merge(
    loop_: &[Corner],
    straight: &[bool],
    triangles: &[[usize; 3]],
    point: &impl Fn(u16) -> Point,
) -> Option<Vec<(Vec<u16>, Vec<PieceWall>)>> {
    let n = loop_.len();
    // Pieces as rings of positions in `loop_` (clockwise).
    let mut pieces: Vec<Option<Vec<usize>>> = triangles.iter().map(|t| Some(t.to_vec())).collect();
    // The loop's own sides, between kept corners: a side runs from a kept position to the next
    // kept one (over straight corners).
    let next_kept = |k: usize| {
        let mut j = (k + 1) % n;
        while straight[j] {
            j = (j + 1) % n;
        }
        j
    };
    let is_side = |a: usize, b: usize| next_kept(a) == b;
    // Merge across diagonals: an edge (a, b) of one piece that is (b, a) of another.
    let mut changed = true;
    while changed {
        changed = false;
        'outer: for i in 0..pieces.len() {
            let Some(ring) = pieces[i].clone() else {
                continue;
            };
            for e in 0..ring.len() {
                let (a, b) = (ring[e], ring[(e + 1) % ring.len()]);
                if is_side(a, b) {
                    continue;
                }
                for j in 0..pieces.len() {
                    if j == i {
                        continue;
                    }
                    let Some(other) = &pieces[j] else {
                        continue;
                    };
                    let Some(f) = (0..other.len())
                        .find(|&f| other[f] == b && other[(f + 1) % other.len()] == a)
                    else {
                        continue;
                    };
                    // The merged ring: this ring from b round to a, then the other's corners
                    // strictly between a and b.
                    let mut merged = Vec::new();
                    for step in 0..ring.len() {
                        merged.push(ring[(e + 1 + step) % ring.len()]);
                    }
                    for step in 0..other.len() - 2 {
                        merged.push(other[(f + 2 + step) % other.len()]);
                    }
                    let points: Vec<Point> = merged.iter().map(|&k| point(loop_[k].0)).collect();
                    let m = points.len();
                    let convex = (0..m).all(|k| {
                        cross(points[(k + m - 1) % m], points[k], points[(k + 1) % m]) <= 0
                    });
                    if convex {
                        pieces[i] = Some(merged);
                        pieces[j] = None;
                        changed = true;
                        continue 'outer;
                    }
                }
            }
        }
    }
    let pieces: Vec<Vec<usize>> = pieces.into_iter().flatten().collect();
    // Where each diagonal leads: the piece with its reverse.
    let mut owner: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    for (index, ring) in pieces.iter().enumerate() {
        for e in 0..ring.len() {
            owner.insert((ring[e], ring[(e + 1) % ring.len()]), index);
        }
    }
    let mut result = Vec::with_capacity(pieces.len());
    for ring in &pieces {
        let (mut outline, mut walls) = (Vec::new(), Vec::new());
        for e in 0..ring.len() {
            let (a, b) = (ring[e], ring[(e + 1) % ring.len()]);
            if is_side(a, b) {
                // The loop's sides from a to b, straight corners included.
                let mut k = a;
                loop {
                    outline.push(loop_[k].0);
                    walls.push(loop_[k].1);
                    k = (k + 1) % n;
                    if k == b {
                        break;
                    }
                }
            } else {
                outline.push(loop_[a].0);
                walls.push(PieceWall::Open {
                    piece: *owner.get(&(b, a))? as u32,
                });
            }
        }
        result.push((outline, walls));
    }
    // A bridge's two walks are sides of the loop here; one made of Open walls leads to the
    // piece holding its reverse. Fill those in.
    let mut by_corners: BTreeMap<(u16, u16), usize> = BTreeMap::new();
    for (index, (outline, walls)) in result.iter().enumerate() {
        for k in 0..outline.len() {
            if let PieceWall::Open { .. } = walls[k] {
                by_corners.insert((outline[k], outline[(k + 1) % outline.len()]), index);
            }
        }
    }
    for (outline, walls) in &mut result {
        let len = outline.len();
        for k in 0..len {
            if walls[k] == BRIDGE {
                let (a, b) = (outline[k], outline[(k + 1) % len]);
                walls[k] = PieceWall::Open {
                    piece: *by_corners.get(&(b, a))? as u32,
                };
            }
        }
    }
    Some(result)
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::doom::level::{DoomSector, DoomVertex, Linedef, Sidedef};

    fn level(
        vertices: Vec<(i16, i16)>,
        lines: Vec<(u16, u16, u16, u16)>,
        sectors: u16,
    ) -> DoomLevel {
        let sidedef = |sector: u16| Sidedef {
            x_offset: 0,
            y_offset: 0,
            upper: "-".into(),
            lower: "-".into(),
            middle: "WALL".into(),
            sector,
        };
        let mut sidedefs = Vec::new();
        let linedefs = lines
            .into_iter()
            .map(|(start, end, right, left)| {
                let mut sides = [NONE; 2];
                for (slot, sector) in sides.iter_mut().zip([right, left]) {
                    if sector != NONE {
                        *slot = sidedefs.len() as u16;
                        sidedefs.push(sidedef(sector));
                    }
                }
                Linedef {
                    start,
                    end,
                    flags: 0,
                    special: 0,
                    tag: 0,
                    sides,
                }
            })
            .collect();
        DoomLevel {
            name: "TEST".into(),
            vertices: vertices
                .into_iter()
                .map(|(x, y)| DoomVertex { x, y })
                .collect(),
            linedefs,
            sidedefs,
            sectors: (0..sectors)
                .map(|_| DoomSector {
                    floor: 0,
                    ceiling: 128,
                    floor_flat: "F".into(),
                    ceiling_flat: "C".into(),
                    light: 160,
                    special: 0,
                    tag: 0,
                })
                .collect(),
            things: Vec::new(),
        }
    }

    /// Every piece turns right (clockwise, y up) or goes straight, with no wall of zero length.
    fn convex(level: &DoomLevel, piece: &Piece) -> bool {
        let p = |v: u16| {
            let v = level.vertices[usize::from(v)];
            (i64::from(v.x), i64::from(v.y))
        };
        let n = piece.outline.len();
        (0..n).all(|k| {
            let (a, b, c) = (
                p(piece.outline[(k + n - 1) % n]),
                p(piece.outline[k]),
                p(piece.outline[(k + 1) % n]),
            );
            a != b && cross(a, b, c) <= 0
        })
    }

    #[test]
    fn a_u_shaped_room_round_a_pillar_cuts_into_convex_pieces() {
        // A 4×3 room (clockwise, y up) with a notch in its top, and a square pillar (a hole:
        // its lines face the room) in its bottom half.
        let vertices = vec![
            (0, 0),
            (0, 30),
            (10, 30),
            (10, 20),
            (20, 20),
            (20, 30),
            (40, 30),
            (40, 0),
            (25, 5),
            (30, 5),
            (30, 10),
            (25, 10),
        ];
        let mut lines: Vec<(u16, u16, u16, u16)> =
            (0..8).map(|k| (k, (k + 1) % 8, 0, NONE)).collect();
        // The pillar's sides, the room on their right: anticlockwise round the pillar.
        lines.extend([
            (8, 9, 0, NONE),
            (9, 10, 0, NONE),
            (10, 11, 0, NONE),
            (11, 8, 0, NONE),
        ]);
        let level = level(vertices, lines, 1);
        let pieces = partition(&level).unwrap();
        assert!(pieces.len() >= 3, "{pieces:?}");
        assert!(pieces.iter().all(|piece| convex(&level, piece)));
        let area: i128 = pieces
            .iter()
            .map(|piece| {
                let points: Vec<Point> = piece
                    .outline
                    .iter()
                    .map(|&v| {
                        let v = level.vertices[usize::from(v)];
                        (i64::from(v.x), i64::from(v.y))
                    })
                    .collect();
                double_area(&points)
            })
            .sum();
        assert_eq!(area, -2 * (40 * 30 - 10 * 10 - 5 * 5));
    }

    #[test]
    fn a_gap_in_a_sector_s_outline_is_named() {
        let level = level(
            vec![(0, 0), (0, 10), (10, 10), (10, 0)],
            vec![(0, 1, 0, NONE), (1, 2, 0, NONE), (2, 3, 0, NONE)],
            1,
        );
        assert!(matches!(
            partition(&level),
            Err(PartitionError::Unclosed { sector: 0, .. })
        ));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]
        /// Any map, however tangled, is cut or refused, never a panic; what is cut is convex.
        #[test]
        fn any_map_is_cut_into_convex_pieces_or_refused(
            vertices in prop::collection::vec((-20i16..20, -20i16..20), 3..10),
            lines in prop::collection::vec((0u16..10, 0u16..10, 0u16..3, prop_oneof![Just(NONE), 0u16..3]), 3..14),
        ) {
            let count = vertices.len() as u16;
            let lines = lines.into_iter().map(|(a, b, r, l)| (a % count, b % count, r, l)).collect();
            let level = level(vertices, lines, 3);
            if let Ok(pieces) = partition(&level) {
                prop_assert!(pieces.iter().all(|piece| convex(&level, piece)));
            }
        }

        /// A random closed loop (clockwise or not, crossing itself or not) is cut into convex
        /// pieces covering its area exactly, or refused.
        #[test]
        fn a_random_loop_is_cut_exactly_or_refused(
            vertices in prop::collection::vec((-30i16..30, -30i16..30), 3..12),
        ) {
            let n = vertices.len() as u16;
            let lines = (0..n).map(|k| (k, (k + 1) % n, 0, NONE)).collect();
            let level = level(vertices, lines, 1);
            if let Ok(pieces) = partition(&level) {
                prop_assert!(pieces.iter().all(|piece| convex(&level, piece)));
                let points = |outline: &[u16]| -> Vec<Point> {
                    outline
                        .iter()
                        .map(|&v| {
                            let v = level.vertices[usize::from(v)];
                            (i64::from(v.x), i64::from(v.y))
                        })
                        .collect()
                };
                let covered: i128 = pieces.iter().map(|piece| double_area(&points(&piece.outline))).sum();
                let whole = double_area(&points(&(0..n).collect::<Vec<_>>()));
                // The loop's own area if it runs clockwise (the sector on its right); a loop
                // running the other way bounds the sector from outside: nothing to cut.
                prop_assert_eq!(covered, if whole < 0 { whole } else { 0 });
            }
        }
    }
}
