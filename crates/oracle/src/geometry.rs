//! Exact-as-f64 map geometry: point in sector, where a ray leaves a sector, distance to a wall.

use portalcast_format::{MapTables, Sector};

/// A point or vector of the map plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Vec2 {
    pub x: f64,
    pub y: f64,
}

impl Vec2 {
    pub(crate) const fn new(x: f64, y: f64) -> Vec2 {
        Vec2 { x, y }
    }

    fn sub(self, other: Vec2) -> Vec2 {
        Vec2::new(self.x - other.x, self.y - other.y)
    }

    /// `self × other`: positive when `other` points to the right of `self` on the y-down
    /// top-down view, i.e. to the inside of a wall along `self`.
    fn cross(self, other: Vec2) -> f64 {
        self.x * other.y - self.y * other.x
    }

    fn dot(self, other: Vec2) -> f64 {
        self.x * other.x + self.y * other.y
    }
}

/// Vertex `index` of the map, in f64.
pub(crate) fn vertex(map: &MapTables, index: u16) -> Vec2 {
    let v = map.vertices[usize::from(index)];
    Vec2::new(f64::from(v.x), f64::from(v.y))
}

/// The sector whose interior strictly contains `(x, y)`: a point on a wall line (a shared
/// portal, a vertex) belongs to no sector and gives `None`, as does a point outside the map.
/// Sectors are convex, so "strictly right of every wall" is the whole test.
pub fn find_sector(map: &MapTables, x: f64, y: f64) -> Option<u16> {
    let p = Vec2::new(x, y);
    map.sectors
        .iter()
        .position(|sector| strictly_inside(map, sector, p))
        .map(|i| i as u16)
}

/// Every sector whose interior strictly contains `(x, y)`: one, or on a map with room over
/// room, one a layer.
pub fn find_sectors(map: &MapTables, x: f64, y: f64) -> Vec<u16> {
    let p = Vec2::new(x, y);
    (0..map.sectors.len() as u16)
        .filter(|&i| strictly_inside(map, &map.sectors[usize::from(i)], p))
        .collect()
}

fn strictly_inside(map: &MapTables, sector: &Sector, p: Vec2) -> bool {
    let walls = map.sector_walls(sector);
    !walls.is_empty()
        && walls.iter().all(|wall| {
            let a = vertex(map, wall.start);
            let b = vertex(map, wall.end);
            b.sub(a).cross(p.sub(a)) > 0.0
        })
}

/// Where a 2D ray leaves a sector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Exit {
    /// Global wall index.
    pub wall: u16,
    /// Ray parameter (eye-space depth) of the crossing.
    pub t: f64,
    /// Position along the wall, 0 at its start vertex, 1 at its end.
    pub s: f64,
}

/// Relative tolerance under which two walls are crossed at the same `t` (a ray through a
/// vertex, or collinear consecutive walls): far below a pixel, far above f64 rounding.
const TIE_RELATIVE: f64 = 1e-9;
/// Tolerance on `s` for "at the start vertex" (counts as on the wall) and "at the end vertex"
/// (counts as off it).
const S_EPSILON: f64 = 1e-9;

/// How far `s` is from `[0, 1)`, with a crossing within [`S_EPSILON`] of the start vertex
/// counted as on the wall and one within it of the end vertex counted as off.
fn off_wall(s: f64) -> f64 {
    if s < -S_EPSILON {
        -s
    } else if s < 1.0 - S_EPSILON {
        0.0
    } else {
        s - 1.0 + 2.0 * S_EPSILON
    }
}

/// The wall through which the ray `p + t·d` leaves `sector`, from a point inside it.
///
/// The exit of a convex polygon is the nearest crossing among the walls the ray crosses
/// outward (Cyrus–Beck), whatever `t_in` is, so this never depends on the march's
/// accumulated state. Near-ties (a vertex, collinear walls) go to the wall with `s ∈ [0, 1)`.
/// `None` only for a degenerate ray (`d = 0`) or sector.
pub(crate) fn exit_wall(map: &MapTables, sector: &Sector, p: Vec2, d: Vec2) -> Option<Exit> {
    let first = sector.first_wall;
    let crossings = map
        .sector_walls(sector)
        .iter()
        .enumerate()
        .filter_map(|(offset, wall)| {
            let a = vertex(map, wall.start);
            let e = vertex(map, wall.end).sub(a);
            let outward = e.cross(d);
            if outward >= 0.0 {
                return None;
            }
            let pa = p.sub(a);
            Some(Exit {
                wall: first + offset as u16,
                t: -e.cross(pa) / outward,
                s: pa.cross(d) / outward,
            })
        });
    let nearest = crossings
        .clone()
        .map(|exit| exit.t)
        .min_by(f64::total_cmp)?;
    let tolerance = TIE_RELATIVE * nearest.abs().max(1.0);
    crossings
        .filter(|exit| exit.t <= nearest + tolerance)
        .min_by(|x, y| off_wall(x.s).total_cmp(&off_wall(y.s)))
}

/// Distance from `p` to the segment `a → b`.
pub(crate) fn distance_to_segment(p: Vec2, a: Vec2, b: Vec2) -> f64 {
    let e = b.sub(a);
    let along = (p.sub(a).dot(e) / e.dot(e)).clamp(0.0, 1.0);
    let closest = Vec2::new(a.x + along * e.x, a.y + along * e.y);
    let offset = p.sub(closest);
    offset.dot(offset).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn off_wall_prefers_start_vertex_over_end_vertex() {
        assert_eq!(off_wall(0.0), 0.0);
        assert_eq!(off_wall(-1e-12), 0.0);
        assert_eq!(off_wall(0.5), 0.0);
        assert!(off_wall(1.0) > 0.0);
        assert!(off_wall(1.0 - 1e-12) > 0.0);
        assert_eq!(off_wall(-0.25), 0.25);
    }

    #[test]
    fn distance_to_segment_clamps_to_the_ends() {
        let a = Vec2::new(0.0, 0.0);
        let b = Vec2::new(10.0, 0.0);
        assert_eq!(distance_to_segment(Vec2::new(5.0, 3.0), a, b), 3.0);
        assert_eq!(distance_to_segment(Vec2::new(13.0, 4.0), a, b), 5.0);
        assert_eq!(distance_to_segment(Vec2::new(-3.0, -4.0), a, b), 5.0);
    }
}
