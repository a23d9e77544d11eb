//! Sloped floors and ceilings: a sector's heights at three or more of its vertices become a
//! [`Plane`], checked exactly (the points lie on one plane, the plane is not too steep, the floor
//! stays below the ceiling and the player's body fits between them at every vertex) and stored
//! in the format's fixed point, whose error bound is [`portalcast_format::PLANE_ERROR_BOUND_FX8`].

use portalcast_format::limits::{HEIGHT_MAX, HEIGHT_MIN, SLOPE_GRADIENT_MAX};
use portalcast_format::{Plane, PlayerSize, SectorSlope};

use crate::diag::Located;
use crate::source::{SourceMap, SourceSector, SourceSlope};

/// The exact plane `A·(x − x0) + B·(y − y0) + C·(z − z0) = 0` through a slope's points, `C ≠ 0`.
#[derive(Clone, Copy, Debug)]
struct ExactPlane {
    a: i128,
    b: i128,
    c: i128,
    origin: (i128, i128, i128),
}

impl ExactPlane {
    /// `round(256·z(x, y))`, from the rational height `z0 − (A(x−x0) + B(y−y0))/C`.
    fn stored(&self) -> Plane {
        let (x0, y0, z0) = self.origin;
        Plane {
            // z(0, 0) = z0 + (A·x0 + B·y0)/C.
            base_fx8: round_div(256 * (z0 * self.c + self.a * x0 + self.b * y0), self.c) as i32,
            gradient_x_fx24: round_div(-self.a << 24, self.c) as i32,
            gradient_y_fx24: round_div(-self.b << 24, self.c) as i32,
        }
    }

    /// Whether `(x, y, z)` lies on the plane, exactly.
    fn contains(&self, (x, y, z): (i128, i128, i128)) -> bool {
        let (x0, y0, z0) = self.origin;
        self.a * (x - x0) + self.b * (y - y0) + self.c * (z - z0) == 0
    }
}

/// `n / d` rounded to nearest, ties away from zero.
fn round_div(n: i128, d: i128) -> i128 {
    let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
    if n >= 0 {
        (n + d / 2) / d
    } else {
        -((-n + d / 2) / d)
    }
}

/// A height in 24.8 as map makers read it: `37.5`, `-12`.
fn units(fx8: i64) -> String {
    if fx8 % 256 == 0 {
        (fx8 / 256).to_string()
    } else {
        format!("{:.2}", fx8 as f64 / 256.0)
    }
}

/// The planes of sector `sector` of `source`, whose outline's corners (vertex indices, in
/// order) are `corners`, where its floor or ceiling slopes; `None` where both are flat. Every
/// error is reported at the slope's or the point's place. On success the sector's `floor` and
/// `ceil` are set to the lowest floor and highest ceiling at its corners (rounded down and up).
pub(crate) fn resolve(
    source: &SourceMap,
    sector: &mut SourceSector,
    corners: &[usize],
    body: PlayerSize,
    errors: &mut Vec<Located>,
) -> Option<SectorSlope> {
    if sector.floor_slope.is_none() && sector.ceil_slope.is_none() {
        return None;
    }
    let before = errors.len();
    let point = |vertex: usize| {
        let v = &source.vertices[vertex];
        (i128::from(v.x.value), i128::from(v.y.value))
    };
    let mut plane_of = |slope: &Option<SourceSlope>, flat: i64, what: &str| match slope {
        None => Some(Plane::flat(flat as i32)),
        Some(slope) => exact_plane(source, &sector.label, slope, corners, point, what, errors)
            .map(|plane| plane.stored()),
    };
    let floor = plane_of(&sector.floor_slope, sector.floor.value, "floor");
    let ceiling = plane_of(&sector.ceil_slope, sector.ceil.value, "ceiling");
    let (Some(floor), Some(ceiling)) = (floor, ceiling) else {
        return None;
    };
    let at = |plane: &Plane, vertex: usize| {
        let (x, y) = point(vertex);
        i64::from(plane.height_fx8_at((x * 256) as i32, (y * 256) as i32))
    };
    let (mut lowest_floor, mut highest_ceiling) = (i64::MAX, i64::MIN);
    let loc = sector
        .floor_slope
        .as_ref()
        .or(sector.ceil_slope.as_ref())
        .map_or(sector.loc, |slope| slope.loc);
    for &vertex in corners {
        let (f, c) = (at(&floor, vertex), at(&ceiling, vertex));
        let name = &source.vertices[vertex].label;
        for (what, h) in [("floor", f), ("ceiling", c)] {
            if !(i64::from(HEIGHT_MIN) * 256..=i64::from(HEIGHT_MAX) * 256).contains(&h) {
                errors.push((
                    loc,
                    format!(
                        "{}: the sloped {what} reaches {} at {name}, outside the limits {HEIGHT_MIN}..={HEIGHT_MAX}; make the slope gentler",
                        sector.label,
                        units(h)
                    ),
                ));
            }
        }
        let room = i64::from(body.height) * 256;
        if c - f < room {
            errors.push((
                loc,
                format!(
                    "{}: at {name} the floor is at {} and the ceiling at {}, less than the player's height ({}) apart; in a sector with a slope the body must fit standing everywhere, so raise the ceiling or lower the floor there",
                    sector.label,
                    units(f),
                    units(c),
                    body.height
                ),
            ));
        }
        lowest_floor = lowest_floor.min(f);
        highest_ceiling = highest_ceiling.max(c);
    }
    if let Some(mover) = &sector.mover {
        errors.push((
            mover.loc,
            format!(
                "{} slopes and moves; a sector with a slope cannot be a {} yet: make its floor and ceiling flat, or drop the mover",
                sector.label,
                mover.kind.name()
            ),
        ));
    }
    if errors.len() > before {
        return None;
    }
    sector.floor.value = lowest_floor.div_euclid(256);
    sector.ceil.value = (highest_ceiling + 255).div_euclid(256);
    Some(SectorSlope { floor, ceiling })
}

/// The exact plane through `slope`'s points, after checking them: each a corner of the
/// sector and listed once, at least three, not all on one line, all on one plane, and the plane
/// no steeper than [`SLOPE_GRADIENT_MAX`] along either axis.
fn exact_plane(
    source: &SourceMap,
    label: &str,
    slope: &SourceSlope,
    corners: &[usize],
    point: impl Fn(usize) -> (i128, i128),
    what: &str,
    errors: &mut Vec<Located>,
) -> Option<ExactPlane> {
    let name = |vertex: usize| source.vertices[vertex].label.as_str();
    let before = errors.len();
    for (index, (vertex, _)) in slope.points.iter().enumerate() {
        if !corners.contains(&vertex.value) {
            errors.push((
                vertex.loc,
                format!(
                    "{} is not a corner of {label}; give the {what} slope's heights at the sector's own corners",
                    name(vertex.value)
                ),
            ));
        } else if slope.points[..index]
            .iter()
            .any(|(other, _)| other.value == vertex.value)
        {
            errors.push((
                vertex.loc,
                format!(
                    "{} is listed twice in the {what} slope; give each corner one height",
                    name(vertex.value)
                ),
            ));
        }
    }
    if slope.points.len() < 3 {
        errors.push((
            slope.loc,
            format!(
                "a {what} slope needs heights at three or more corners of {label} (VERTEX:HEIGHT,VERTEX:HEIGHT,VERTEX:HEIGHT); it has {}",
                slope.points.len()
            ),
        ));
    }
    if errors.len() > before {
        return None;
    }
    let points: Vec<(i128, i128, i128)> = slope
        .points
        .iter()
        .map(|(vertex, height)| {
            let (x, y) = point(vertex.value);
            (x, y, i128::from(height.value))
        })
        .collect();
    // The first point with the two others that span the largest triangle: any with a non-zero
    // area gives the same plane when all points lie on one.
    let p0 = points[0];
    let mut best: Option<ExactPlane> = None;
    for (i, &p1) in points.iter().enumerate().skip(1) {
        for &p2 in &points[i + 1..] {
            let u = (p1.0 - p0.0, p1.1 - p0.1, p1.2 - p0.2);
            let v = (p2.0 - p0.0, p2.1 - p0.1, p2.2 - p0.2);
            let plane = ExactPlane {
                a: u.1 * v.2 - u.2 * v.1,
                b: u.2 * v.0 - u.0 * v.2,
                c: u.0 * v.1 - u.1 * v.0,
                origin: p0,
            };
            if best.is_none_or(|b| plane.c.abs() > b.c.abs()) {
                best = Some(plane);
            }
        }
    }
    let Some(plane) = best.filter(|plane| plane.c != 0) else {
        errors.push((
            slope.loc,
            format!(
                "the {what} slope's corners all lie on one line, which does not fix a plane; add a height at a corner off that line"
            ),
        ));
        return None;
    };
    for ((vertex, height), &p) in slope.points.iter().zip(&points) {
        if !plane.contains(p) {
            let (x0, y0, z0) = plane.origin;
            let on_plane = round_div(
                256 * (z0 * plane.c - plane.a * (p.0 - x0) - plane.b * (p.1 - y0)),
                plane.c,
            );
            errors.push((
                height.loc,
                format!(
                    "the {what} slope's heights do not lie on one plane: the others put {} at {}, not {}; change it, or split the sector where the slope bends",
                    name(vertex.value),
                    units(on_plane as i64),
                    height.value
                ),
            ));
        }
    }
    let steepest = i128::from(SLOPE_GRADIENT_MAX) * plane.c.abs();
    if plane.a.abs() > steepest || plane.b.abs() > steepest {
        let rise = |n: i128| (n as f64 / plane.c as f64).abs();
        errors.push((
            slope.loc,
            format!(
                "the {what} slope is too steep for the renderer's fixed point: it rises {:.2} per unit along x and {:.2} along y, at most {SLOPE_GRADIENT_MAX} each; spread the heights over a longer run",
                rise(plane.a),
                rise(plane.b)
            ),
        ));
    }
    (errors.len() == before).then_some(plane)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_division_is_to_nearest_both_ways() {
        assert_eq!(round_div(7, 2), 4);
        assert_eq!(round_div(-7, 2), -4);
        assert_eq!(round_div(5, 3), 2);
        assert_eq!(round_div(-5, -3), 2);
        assert_eq!(round_div(5, -3), -2);
    }

    #[test]
    fn a_stored_plane_gives_the_exact_heights_within_its_bound() {
        // Through (0,0,0), (100,0,10), (0,300,-7): z = x/10 − 7y/300.
        let u = (100i128, 0i128, 10i128);
        let v = (0i128, 300i128, -7i128);
        let plane = ExactPlane {
            a: u.1 * v.2 - u.2 * v.1,
            b: u.2 * v.0 - u.0 * v.2,
            c: u.0 * v.1 - u.1 * v.0,
            origin: (0, 0, 0),
        };
        let stored = plane.stored();
        for (x, y) in [(0, 0), (8192, 8192), (-8192, 8192), (100, 300), (-5000, 77)] {
            let exact = 256.0 * (f64::from(x) / 10.0 - 7.0 * f64::from(y) / 300.0);
            let got = f64::from(stored.height_fx8_at(x * 256, y * 256));
            assert!(
                (got - exact).abs() <= f64::from(portalcast_format::PLANE_ERROR_BOUND_FX8),
                "{x},{y}: {got} vs {exact}"
            );
        }
    }
}
