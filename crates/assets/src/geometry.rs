//! Exact integer predicates on map points (no rounding anywhere).

/// A point with integer coordinates (world units, or 24.8 fixed point scaled alike).
pub(crate) type Point = (i64, i64);

/// Cross product of `a - o` and `b - o`. Positive when `o → a → b` turns clockwise on a
/// top-down view with y down (a right turn), i.e. `b` lies to the right of `o → a`.
pub(crate) fn cross(o: Point, a: Point, b: Point) -> i128 {
    let (ax, ay) = (i128::from(a.0 - o.0), i128::from(a.1 - o.1));
    let (bx, by) = (i128::from(b.0 - o.0), i128::from(b.1 - o.1));
    ax * by - ay * bx
}

/// Dot product of `a - o` and `b - o`.
pub(crate) fn dot(o: Point, a: Point, b: Point) -> i128 {
    let (ax, ay) = (i128::from(a.0 - o.0), i128::from(a.1 - o.1));
    let (bx, by) = (i128::from(b.0 - o.0), i128::from(b.1 - o.1));
    ax * bx + ay * by
}

/// Twice the signed area of a polygon: positive when it runs clockwise on a y-down view.
pub(crate) fn double_area(points: &[Point]) -> i128 {
    let mut sum = 0i128;
    for (i, &a) in points.iter().enumerate() {
        let b = points[(i + 1) % points.len()];
        sum += i128::from(a.0) * i128::from(b.1) - i128::from(b.0) * i128::from(a.1);
    }
    sum
}

/// Whether `p`, known to be collinear with segment `a b`, lies on the closed segment.
pub(crate) fn within_box(a: Point, b: Point, p: Point) -> bool {
    p.0 >= a.0.min(b.0) && p.0 <= a.0.max(b.0) && p.1 >= a.1.min(b.1) && p.1 <= a.1.max(b.1)
}

/// Whether closed segments `a b` and `c d` share at least one point (touching counts).
pub(crate) fn segments_touch(a: Point, b: Point, c: Point, d: Point) -> bool {
    let d1 = cross(a, b, c).signum();
    let d2 = cross(a, b, d).signum();
    let d3 = cross(c, d, a).signum();
    let d4 = cross(c, d, b).signum();
    if d1 * d2 < 0 && d3 * d4 < 0 {
        return true;
    }
    (d1 == 0 && within_box(a, b, c))
        || (d2 == 0 && within_box(a, b, d))
        || (d3 == 0 && within_box(c, d, a))
        || (d4 == 0 && within_box(c, d, b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clockwise_square_on_y_down_view_has_positive_area_and_right_turns() {
        let square = [(0, 0), (10, 0), (10, 10), (0, 10)];
        assert!(double_area(&square) > 0);
        assert!(cross(square[0], square[1], square[2]) > 0);
        // The inside is to the right of each wall.
        assert!(cross(square[0], square[1], (5, 5)) > 0);
    }

    #[test]
    fn touching_and_crossing_segments() {
        assert!(segments_touch((0, 0), (10, 10), (0, 10), (10, 0)));
        assert!(segments_touch((0, 0), (10, 0), (10, 0), (20, 5)));
        assert!(segments_touch((0, 0), (10, 0), (5, 0), (20, 0)));
        assert!(!segments_touch((0, 0), (10, 0), (11, 0), (20, 0)));
        assert!(!segments_touch((0, 0), (10, 0), (0, 1), (10, 1)));
    }
}
