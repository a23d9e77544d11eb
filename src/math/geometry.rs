//! Exact integer geometry on the map plane: side of a line, segment contact, point in a convex
//! polygon.
//!
//! Every predicate is a sign of 64-bit cross products of 24.8 coordinates, so it is exact: no
//! float, no tolerance. With coordinates within `±WORLD_COORD_MAX` (8192), differences are below
//! `2^22` in 24.8 bits, each product below `2^44` and every sum below `2^45`: far inside i64.
//! (On integer map vertices alone the same cross products fit i32: `2·(2·8192)^2 = 2^29`.)
//!
//! Orientation convention (`docs/ARCHITECTURE.md`): the map is drawn with `y` downward, sectors
//! are clockwise on that view and their inside is to the right of each wall `a → b`. "Left" and
//! "right" here are what a walker going from `a` to `b` sees on that top-down view.

use super::fixed::Fx24_8;

/// A point of the map plane, in 24.8 world units.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default, Debug)]
pub struct WorldPoint {
    /// World x.
    pub x: Fx24_8,
    /// World y (drawn downward on the top-down view).
    pub y: Fx24_8,
}

impl WorldPoint {
    /// The point `(x, y)`.
    #[inline]
    pub const fn new(x: Fx24_8, y: Fx24_8) -> WorldPoint {
        WorldPoint { x, y }
    }

    /// The point at integer world coordinates (a map vertex). Exact.
    #[inline]
    #[track_caller]
    pub const fn from_int(x: i32, y: i32) -> WorldPoint {
        WorldPoint {
            x: Fx24_8::from_int(x),
            y: Fx24_8::from_int(y),
        }
    }
}

/// Where a point lies relative to a directed line, as seen walking along it on the top-down view.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Side {
    /// To the left (outside a wall of a clockwise sector).
    Left,
    /// Exactly on the line.
    On,
    /// To the right (inside a wall of a clockwise sector).
    Right,
}

impl Side {
    /// The side given by the sign of a cross product: positive is right.
    #[inline]
    pub const fn from_cross(cross: i64) -> Side {
        if cross > 0 {
            Side::Right
        } else if cross < 0 {
            Side::Left
        } else {
            Side::On
        }
    }
}

/// Twice the signed area of the triangle `a, b, p`, in units of `2^-16` square world units:
/// `(b − a) × (p − a)`. Positive when `p` is right of `a → b` on the top-down view (y down).
/// Exact.
#[inline]
pub const fn cross(a: WorldPoint, b: WorldPoint, p: WorldPoint) -> i64 {
    let abx = b.x.to_bits() as i64 - a.x.to_bits() as i64;
    let aby = b.y.to_bits() as i64 - a.y.to_bits() as i64;
    let apx = p.x.to_bits() as i64 - a.x.to_bits() as i64;
    let apy = p.y.to_bits() as i64 - a.y.to_bits() as i64;
    abx * apy - aby * apx
}

/// Side of `p` relative to the directed line `a → b`. Exact. `a ≠ b`.
#[inline]
pub const fn side_of_line(a: WorldPoint, b: WorldPoint, p: WorldPoint) -> Side {
    Side::from_cross(cross(a, b, p))
}

/// How two closed segments meet.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum SegmentContact {
    /// No common point.
    Disjoint,
    /// They cross at one point interior to both.
    Crossing,
    /// They share exactly one point, an endpoint of at least one of them.
    Touching,
    /// They are collinear and share more than one point.
    Overlapping,
}

/// Orders collinear points along their line (x first, then y): a total order consistent with
/// the line's direction, vertical lines included.
#[inline]
const fn along(p: WorldPoint) -> (i32, i32) {
    (p.x.to_bits(), p.y.to_bits())
}

#[inline]
const fn lex_le(p: (i32, i32), q: (i32, i32)) -> bool {
    p.0 < q.0 || (p.0 == q.0 && p.1 <= q.1)
}

/// Whether `p`, known to be on the line through `a` and `b`, lies on the closed segment.
#[inline]
const fn collinear_within(a: WorldPoint, b: WorldPoint, p: WorldPoint) -> bool {
    let (a, b, p) = (along(a), along(b), along(p));
    (lex_le(a, p) && lex_le(p, b)) || (lex_le(b, p) && lex_le(p, a))
}

/// How the closed segments `a–b` and `c–d` meet. Exact; degenerate segments (a point) allowed.
///
/// Always inlined: linker.ld puts math's out-of-line functions in IWRAM, and this one's engine
/// caller (the player's walk through portals) runs from ROM, where it then belongs too.
#[inline(always)]
pub fn segment_contact(
    a: WorldPoint,
    b: WorldPoint,
    c: WorldPoint,
    d: WorldPoint,
) -> SegmentContact {
    let a_side = cross(c, d, a).signum();
    let b_side = cross(c, d, b).signum();
    let c_side = cross(a, b, c).signum();
    let d_side = cross(a, b, d).signum();

    if a_side * b_side < 0 && c_side * d_side < 0 {
        return SegmentContact::Crossing;
    }
    if a_side == 0 && b_side == 0 && c_side == 0 && d_side == 0 {
        return collinear_contact(a, b, c, d);
    }
    // Not collinear, so at most one common point, and it is an endpoint on the other segment.
    let touches = (a_side == 0 && collinear_within(c, d, a))
        || (b_side == 0 && collinear_within(c, d, b))
        || (c_side == 0 && collinear_within(a, b, c))
        || (d_side == 0 && collinear_within(a, b, d));
    if touches {
        SegmentContact::Touching
    } else {
        SegmentContact::Disjoint
    }
}

fn collinear_contact(a: WorldPoint, b: WorldPoint, c: WorldPoint, d: WorldPoint) -> SegmentContact {
    let (a, b, c, d) = (along(a), along(b), along(c), along(d));
    let (ab_low, ab_high) = if lex_le(a, b) { (a, b) } else { (b, a) };
    let (cd_low, cd_high) = if lex_le(c, d) { (c, d) } else { (d, c) };
    let low = if lex_le(ab_low, cd_low) {
        cd_low
    } else {
        ab_low
    };
    let high = if lex_le(ab_high, cd_high) {
        ab_high
    } else {
        cd_high
    };
    if !lex_le(low, high) {
        SegmentContact::Disjoint
    } else if low.0 == high.0 && low.1 == high.1 {
        SegmentContact::Touching
    } else {
        SegmentContact::Overlapping
    }
}

/// Whether the closed segments `a–b` and `c–d` have a common point. Exact.
#[inline]
pub fn segments_intersect(a: WorldPoint, b: WorldPoint, c: WorldPoint, d: WorldPoint) -> bool {
    segment_contact(a, b, c, d) != SegmentContact::Disjoint
}

/// Where a point lies relative to a closed polygon.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Containment {
    /// Strictly inside.
    Inside,
    /// On an edge or a vertex.
    OnBoundary,
    /// Outside.
    Outside,
}

/// Where `p` lies relative to the convex polygon `vertices`, stored clockwise on the top-down
/// view (y down), as the map's sectors are. Exact. The polygon needs at least 3 vertices and no
/// zero-length edge; consecutive collinear edges are fine.
pub fn point_in_convex_polygon(vertices: &[WorldPoint], p: WorldPoint) -> Containment {
    debug_assert!(vertices.len() >= 3, "a polygon needs 3 vertices");
    let mut on_an_edge = false;
    let mut previous = vertices[vertices.len() - 1];
    for &vertex in vertices {
        match side_of_line(previous, vertex, p) {
            Side::Left => return Containment::Outside,
            Side::On => on_an_edge = true,
            Side::Right => {}
        }
        previous = vertex;
    }
    if on_an_edge {
        Containment::OnBoundary
    } else {
        Containment::Inside
    }
}
