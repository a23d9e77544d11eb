//! Exact geometry against independent i128 references: orientation, segment contact (by solving
//! the parametric intersection with rationals) and point in convex polygon (by ray-crossing
//! parity), over the whole declared world with 1/256 resolution and on a small grid where
//! collinear and touching cases are frequent.

use portalcast::math::{
    cross, point_in_convex_polygon, segment_contact, segments_intersect, side_of_line, Containment,
    Fx24_8, SegmentContact, Side, WorldPoint,
};
use portalcast_format::limits::WORLD_COORD_MAX;
use proptest::prelude::*;

const WORLD_BITS: i32 = WORLD_COORD_MAX << 8;

fn point(x: i32, y: i32) -> WorldPoint {
    WorldPoint::new(Fx24_8::from_bits(x), Fx24_8::from_bits(y))
}

fn world_point() -> impl Strategy<Value = WorldPoint> {
    (-WORLD_BITS..=WORLD_BITS, -WORLD_BITS..=WORLD_BITS).prop_map(|(x, y)| point(x, y))
}

/// A point of a 7×7 grid of integer vertices: collinear and shared points are common.
fn grid_point() -> impl Strategy<Value = WorldPoint> {
    (-3i32..=3, -3i32..=3).prop_map(|(x, y)| WorldPoint::from_int(x, y))
}

fn coords(p: WorldPoint) -> (i128, i128) {
    (p.x.to_bits() as i128, p.y.to_bits() as i128)
}

fn cross_i128(a: WorldPoint, b: WorldPoint, p: WorldPoint) -> i128 {
    let (a, b, p) = (coords(a), coords(b), coords(p));
    (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0)
}

/// Reference contact: solve `a + s(b − a) = c + t(d − c)` with exact rationals.
fn reference_contact(a: WorldPoint, b: WorldPoint, c: WorldPoint, d: WorldPoint) -> SegmentContact {
    let (a, b, c, d) = (coords(a), coords(b), coords(c), coords(d));
    let r = (b.0 - a.0, b.1 - a.1);
    let q = (d.0 - c.0, d.1 - c.1);
    let w = (c.0 - a.0, c.1 - a.1);
    let denominator = r.0 * q.1 - r.1 * q.0;
    if denominator != 0 {
        let (mut s, mut t, mut den) = (w.0 * q.1 - w.1 * q.0, w.0 * r.1 - w.1 * r.0, denominator);
        if den < 0 {
            (s, t, den) = (-s, -t, -den);
        }
        if s < 0 || s > den || t < 0 || t > den {
            return SegmentContact::Disjoint;
        }
        return if s > 0 && s < den && t > 0 && t < den {
            SegmentContact::Crossing
        } else {
            SegmentContact::Touching
        };
    }
    if w.0 * r.1 - w.1 * r.0 != 0 {
        return SegmentContact::Disjoint; // parallel, distinct lines
    }
    // Collinear: positions along r (non-zero for the non-degenerate segments generated here).
    let along = |p: (i128, i128)| (p.0 - a.0) * r.0 + (p.1 - a.1) * r.1;
    let (c_at, d_at) = (along(c), along(d));
    let low = c_at.min(d_at).max(0);
    let high = c_at.max(d_at).min(r.0 * r.0 + r.1 * r.1);
    if low > high {
        SegmentContact::Disjoint
    } else if low == high {
        SegmentContact::Touching
    } else {
        SegmentContact::Overlapping
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10000))]

    #[test]
    fn side_of_line_is_the_sign_of_the_exact_cross_product(a in world_point(), b in world_point(), p in world_point()) {
        let exact = cross_i128(a, b, p);
        prop_assert_eq!(cross(a, b, p) as i128, exact);
        let expected = match exact.signum() { 1 => Side::Right, -1 => Side::Left, _ => Side::On };
        prop_assert_eq!(side_of_line(a, b, p), expected);
        // Reversing the line swaps the sides.
        let reversed = match expected { Side::Right => Side::Left, Side::Left => Side::Right, Side::On => Side::On };
        prop_assert_eq!(side_of_line(b, a, p), reversed);
    }

    #[test]
    fn segment_contact_matches_the_rational_solution(a in world_point(), b in world_point(), c in world_point(), d in world_point()) {
        prop_assume!(a != b && c != d);
        prop_assert_eq!(segment_contact(a, b, c, d), reference_contact(a, b, c, d));
    }

    #[test]
    fn segment_contact_on_a_grid(a in grid_point(), b in grid_point(), c in grid_point(), d in grid_point()) {
        prop_assume!(a != b && c != d);
        let contact = segment_contact(a, b, c, d);
        prop_assert_eq!(contact, reference_contact(a, b, c, d));
        // Symmetric in the two segments and in their directions.
        prop_assert_eq!(segment_contact(c, d, a, b), contact);
        prop_assert_eq!(segment_contact(b, a, d, c), contact);
        prop_assert_eq!(segments_intersect(a, b, c, d), contact != SegmentContact::Disjoint);
    }

    #[test]
    fn points_against_convex_polygons(
        centre in (-7000i32..7000, -7000i32..7000),
        radius in 2i32..1000,
        angles in prop::collection::btree_set(0u16..360, 3..12),
        p in (-1100i32..1100, -1100i32..1100),
        fraction in (0i32..256, 0i32..256),
    ) {
        // Integer vertices near a circle, in increasing angle: clockwise with y down.
        let vertices: Vec<WorldPoint> = angles
            .iter()
            .map(|&degrees| {
                let radians = (degrees as f64).to_radians();
                WorldPoint::from_int(
                    centre.0 + (radius as f64 * radians.cos()).round() as i32,
                    centre.1 + (radius as f64 * radians.sin()).round() as i32,
                )
            })
            .collect();
        prop_assume!(is_strictly_convex_clockwise(&vertices));
        let query = point(((centre.0 + p.0) << 8) + fraction.0, ((centre.1 + p.1) << 8) + fraction.1);
        prop_assert_eq!(point_in_convex_polygon(&vertices, query), reference_containment(&vertices, query));
        for (i, &vertex) in vertices.iter().enumerate() {
            prop_assert_eq!(point_in_convex_polygon(&vertices, vertex), Containment::OnBoundary);
            let next = vertices[(i + 1) % vertices.len()];
            let (x, y) = ((vertex.x + next.x).to_bits(), (vertex.y + next.y).to_bits());
            if x % 2 == 0 && y % 2 == 0 {
                prop_assert_eq!(point_in_convex_polygon(&vertices, point(x / 2, y / 2)), Containment::OnBoundary);
            }
        }
    }
}

fn is_strictly_convex_clockwise(vertices: &[WorldPoint]) -> bool {
    let n = vertices.len();
    n >= 3
        && (0..n).all(|i| cross_i128(vertices[i], vertices[(i + 1) % n], vertices[(i + 2) % n]) > 0)
}

/// Reference: on an edge (collinear and between its ends), else crossing parity of a ray
/// toward +x (half-open rule on y, so vertices are counted once).
fn reference_containment(vertices: &[WorldPoint], p: WorldPoint) -> Containment {
    let n = vertices.len();
    let (px, py) = coords(p);
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (vertices[i], vertices[(i + 1) % n]);
        let ((ax, ay), (bx, by)) = (coords(a), coords(b));
        if cross_i128(a, b, p) == 0
            && px >= ax.min(bx)
            && px <= ax.max(bx)
            && py >= ay.min(by)
            && py <= ay.max(by)
        {
            return Containment::OnBoundary;
        }
        if (ay > py) != (by > py) {
            // x of the edge at height py, compared with px without dividing.
            let lhs = (px - ax) * (by - ay);
            let rhs = (bx - ax) * (py - ay);
            if (by > ay && lhs < rhs) || (by < ay && lhs > rhs) {
                inside = !inside;
            }
        }
    }
    if inside {
        Containment::Inside
    } else {
        Containment::Outside
    }
}

#[test]
fn a_point_one_unit_in_the_last_place_from_a_line() {
    // A wall across the whole world, and points 1/256 unit to either side of its middle.
    let a = WorldPoint::from_int(-WORLD_COORD_MAX, -WORLD_COORD_MAX);
    let b = WorldPoint::from_int(WORLD_COORD_MAX, WORLD_COORD_MAX);
    let on = WorldPoint::from_int(17, 17);
    assert_eq!(side_of_line(a, b, on), Side::On);
    // One ulp toward +y (down on the map) is right of a wall going down-right.
    assert_eq!(
        side_of_line(a, b, point(17 << 8, (17 << 8) + 1)),
        Side::Right
    );
    assert_eq!(
        side_of_line(a, b, point(17 << 8, (17 << 8) - 1)),
        Side::Left
    );
    assert_eq!(
        cross(a, b, point(17 << 8, (17 << 8) + 1)),
        (2 * WORLD_COORD_MAX as i64) << 8
    );
    // A near-parallel wall one ulp off at one end only.
    let c = point(WORLD_BITS, WORLD_BITS + 1);
    assert_eq!(side_of_line(a, c, on), Side::Left);
    assert_eq!(side_of_line(a, b, c), Side::Right);
}

#[test]
fn vertices_collinear_points_and_the_square() {
    // Clockwise with y down: top-left, top-right, bottom-right, bottom-left.
    let square = [
        WorldPoint::from_int(0, 0),
        WorldPoint::from_int(64, 0),
        WorldPoint::from_int(64, 64),
        WorldPoint::from_int(0, 64),
    ];
    let inside = |x, y| point_in_convex_polygon(&square, point(x, y));
    assert_eq!(inside(32 << 8, 32 << 8), Containment::Inside);
    assert_eq!(inside(1, 1), Containment::Inside);
    assert_eq!(inside(0, 0), Containment::OnBoundary); // on a vertex
    assert_eq!(inside(64 << 8, 64 << 8), Containment::OnBoundary);
    assert_eq!(inside(0, 32 << 8), Containment::OnBoundary); // on an edge
    assert_eq!(inside(-1, 32 << 8), Containment::Outside); // 1/256 outside an edge
    assert_eq!(inside(-1, -1), Containment::Outside); // 1/256 off a vertex, diagonally
                                                      // On an edge's line, past its end.
    assert_eq!(inside(100 << 8, 0), Containment::Outside);
    // Counter-clockwise storage puts the inside on the left: the interior reads as outside.
    let mut reversed = square;
    reversed.reverse();
    assert_eq!(
        point_in_convex_polygon(&reversed, point(32 << 8, 32 << 8)),
        Containment::Outside
    );

    // Collinear segments: overlapping, touching end to end, apart; a segment on a vertex.
    let p = WorldPoint::from_int;
    assert_eq!(
        segment_contact(p(0, 0), p(4, 4), p(2, 2), p(6, 6)),
        SegmentContact::Overlapping
    );
    assert_eq!(
        segment_contact(p(0, 0), p(4, 4), p(4, 4), p(6, 6)),
        SegmentContact::Touching
    );
    assert_eq!(
        segment_contact(p(0, 0), p(4, 4), p(5, 5), p(6, 6)),
        SegmentContact::Disjoint
    );
    assert_eq!(
        segment_contact(p(0, 0), p(0, 4), p(0, 1), p(0, 2)),
        SegmentContact::Overlapping
    );
    assert_eq!(
        segment_contact(p(0, 0), p(4, 0), p(2, 0), p(2, 5)),
        SegmentContact::Touching
    ); // T
    assert_eq!(
        segment_contact(p(0, 0), p(4, 0), p(2, -1), p(2, 5)),
        SegmentContact::Crossing
    );
    assert_eq!(
        segment_contact(p(0, 0), p(4, 0), p(4, 0), p(9, 3)),
        SegmentContact::Touching
    ); // shared vertex
       // One ulp short of touching, and one ulp across.
    assert_eq!(
        segment_contact(p(0, 0), p(4, 0), point(2 << 8, 1), p(2, 5)),
        SegmentContact::Disjoint
    );
    assert_eq!(
        segment_contact(p(0, 0), p(4, 0), point(2 << 8, -1), p(2, 5)),
        SegmentContact::Crossing
    );
    // Degenerate segments: a point on a segment touches it, a point elsewhere does not.
    assert_eq!(
        segment_contact(p(2, 0), p(2, 0), p(0, 0), p(4, 0)),
        SegmentContact::Touching
    );
    assert_eq!(
        segment_contact(p(2, 1), p(2, 1), p(0, 0), p(4, 0)),
        SegmentContact::Disjoint
    );
    // Extremes of the world: the two diagonals cross at the origin.
    let w = WORLD_COORD_MAX;
    assert_eq!(
        segment_contact(p(-w, -w), p(w, w), p(-w, w), p(w, -w)),
        SegmentContact::Crossing
    );
}
