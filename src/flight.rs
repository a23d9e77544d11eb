//! A fixed fly-through of a map: the camera path of the benchmark and of the accuracy report.
//!
//! The path is derived from the map alone, so every map, shipped or not, has one, and the ROM
//! and the host replay exactly the same poses. It is a depth-first tour of the sectors a walker
//! could pass between (see [`passable`]): from the player start, through the middle of a portal,
//! to the next sector's centre (the average of its vertices), on to an unvisited neighbour of
//! that one, and back out the way it came when a sector has none left; after the whole tour it
//! starts again from the start sector. Each leg, from a sector's centre (or the player start) to
//! the middle of one of its portals or back, lies inside that one convex sector, so the path never
//! leaves the map and the sector of every pose is known; it is still checked exactly, with the
//! side-of-line tests of [`crate::math`], and a pose that lands on a wall line (the middle of a
//! portal, at the end of a leg) moves on by one 1/256 step until it is strictly inside.
//!
//! The camera moves [`SPEED`] along the path each frame (about Doom's running speed per tic),
//! eye [`EYE_HEIGHT`] above the floor of its sector, and turns smoothly towards the direction of
//! its leg: a quarter of the remaining angle per frame, at most [`MAX_TURN_PER_FRAME`].
//!
//! Everything is integer arithmetic on the map's own formats (24.8 positions, binary angles), so
//! a frame's pose is the same on every machine.

use portalcast_format::{MapTables, Sector, Wall};

use crate::math::{div_round_nearest, side_of_line, Angle, Fx24_8, Side, WorldPoint};
use crate::render::view::Camera;

/// Distance flown per frame, in world units.
pub const SPEED: i32 = 24;
/// Eye height above the floor of the eye's sector.
pub const EYE_HEIGHT: i32 = 32;
/// Least room kept between the eye and a low ceiling.
pub const HEAD_ROOM: i32 = 16;
/// Highest floor step the tour walks up or down.
pub const MAX_STEP: i32 = 24;
/// Lowest opening (lower ceiling less higher floor) the tour walks through.
pub const MIN_OPENING: i32 = 56;
/// Fastest turn, in binary-angle units per frame (about 8.4°).
pub const MAX_TURN_PER_FRAME: i32 = 1536;
/// The turn each frame is the remaining angle divided by `2^TURN_EASE_SHIFT`.
const TURN_EASE_SHIFT: u32 = 2;
/// Remaining angle under which the camera snaps to its leg's direction.
const TURN_SNAP: i32 = 4;
/// Sectors the tour keeps track of; sectors with a higher index are never entered.
pub const MAX_TOUR_SECTORS: usize = 1024;
/// Deepest chain of sectors the tour follows before it turns back.
pub const MAX_TOUR_DEPTH: usize = 64;
/// Most 1/256 steps taken to move a pose off a wall line (a handful ever happen).
const MAX_NUDGES: u32 = 1024;

/// The eye height in `sector`: [`EYE_HEIGHT`] above its floor, lowered to leave [`HEAD_ROOM`]
/// under a low ceiling, and half-way up where even that would be at or under the floor (the same
/// rule as the oracle's sampled poses).
pub fn eye_z(sector: &Sector) -> Fx24_8 {
    let eye = (sector.floor_z + EYE_HEIGHT).min(sector.ceil_z - HEAD_ROOM);
    if eye > sector.floor_z {
        Fx24_8::from_int(eye)
    } else {
        Fx24_8::from_bits((sector.floor_z + sector.ceil_z) * 128)
    }
}

/// Whether a walker passes from `from` to `to` through a portal between them: a floor step of at
/// most [`MAX_STEP`] either way and an opening of at least [`MIN_OPENING`].
pub fn passable(from: &Sector, to: &Sector) -> bool {
    let step = (to.floor_z - from.floor_z).abs();
    let opening = from.ceil_z.min(to.ceil_z) - from.floor_z.max(to.floor_z);
    step <= MAX_STEP && opening >= MIN_OPENING
}

/// Whether `p` is strictly inside sector `index` of `map` (on a wall line is not inside).
/// Exact: one side-of-line test per wall.
pub fn strictly_inside(map: &MapTables, index: u16, p: WorldPoint) -> bool {
    let sector = &map.sectors[usize::from(index)];
    let walls = map.sector_walls(sector);
    !walls.is_empty()
        && walls.iter().all(|wall| {
            side_of_line(vertex(map, wall.start), vertex(map, wall.end), p) == Side::Right
        })
}

fn vertex(map: &MapTables, index: u16) -> WorldPoint {
    let v = map.vertices[usize::from(index)];
    WorldPoint::from_int(v.x, v.y)
}

/// The middle of a wall (exact in 24.8: a half-unit at most).
fn midpoint(map: &MapTables, wall: &Wall) -> WorldPoint {
    let (a, b) = (vertex(map, wall.start), vertex(map, wall.end));
    WorldPoint::new(
        Fx24_8::from_bits((a.x.to_bits() + b.x.to_bits()) / 2),
        Fx24_8::from_bits((a.y.to_bits() + b.y.to_bits()) / 2),
    )
}

/// The average of a sector's wall start vertices, rounded to 24.8: inside a convex sector.
fn centre(map: &MapTables, sector: &Sector) -> WorldPoint {
    let walls = map.sector_walls(sector);
    let count = walls.len().max(1) as i64;
    let (mut x, mut y) = (0i64, 0i64);
    for wall in walls {
        let v = vertex(map, wall.start);
        x += i64::from(v.x.to_bits());
        y += i64::from(v.y.to_bits());
    }
    WorldPoint::new(
        Fx24_8::from_bits(div_round_nearest(x, count) as i32),
        Fx24_8::from_bits(div_round_nearest(y, count) as i32),
    )
}

/// The binary angle of the direction `(dx, dy)` (24.8 bits), rounded down to a unit; 0 for a
/// zero vector. Found bit by bit: the first bit from the sign of `dy` (which half-turn), each
/// further one from the sign of `sin(θ − candidate)`, exact as a cross product with the table's
/// cosine and sine, since the remaining range is at most a half-turn wide.
pub fn heading(dx: i32, dy: i32) -> Angle {
    if dx == 0 && dy == 0 {
        return Angle::ZERO;
    }
    let mut bits: u16 = if dy < 0 || (dy == 0 && dx < 0) {
        1 << 15
    } else {
        0
    };
    for bit in (0..15).rev() {
        let candidate = bits | (1 << bit);
        let (sin, cos) = Angle::from_bits(candidate).sin_cos();
        let across =
            i64::from(cos.to_bits()) * i64::from(dy) - i64::from(sin.to_bits()) * i64::from(dx);
        if across >= 0 {
            bits = candidate;
        }
    }
    Angle::from_bits(bits)
}

/// A point the path goes to, and the sector the leg ending there lies in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Waypoint {
    point: WorldPoint,
    sector: u16,
}

/// The depth-first tour: the chain of sectors from the start and, for each, the next wall to
/// try.
#[derive(Clone, Debug)]
struct Tour {
    root: u16,
    chain: [(u16, u16); MAX_TOUR_DEPTH],
    depth: usize,
    visited: [u32; MAX_TOUR_SECTORS / 32],
    moved_since_start: bool,
}

impl Tour {
    fn new(root: u16) -> Tour {
        let mut tour = Tour {
            root,
            chain: [(0, 0); MAX_TOUR_DEPTH],
            depth: 0,
            visited: [0; MAX_TOUR_SECTORS / 32],
            moved_since_start: false,
        };
        tour.start();
        tour
    }

    fn start(&mut self) {
        self.visited = [0; MAX_TOUR_SECTORS / 32];
        self.chain[0] = (self.root, 0);
        self.depth = 1;
        self.mark(self.root);
        self.moved_since_start = false;
    }

    fn mark(&mut self, sector: u16) {
        let index = usize::from(sector);
        if index < MAX_TOUR_SECTORS {
            self.visited[index / 32] |= 1 << (index % 32);
        }
    }

    fn is_open(&self, sector: u16) -> bool {
        let index = usize::from(sector);
        index < MAX_TOUR_SECTORS && self.visited[index / 32] & (1 << (index % 32)) == 0
    }

    /// The next two waypoints: through a portal's middle to a sector's centre. `None` when the
    /// start sector has no passable portal at all.
    fn step(&mut self, map: &MapTables) -> Option<[Waypoint; 2]> {
        loop {
            let (here, next_wall) = self.chain[self.depth - 1];
            let sector = &map.sectors[usize::from(here)];
            let walls = map.sector_walls(sector);
            if self.depth < MAX_TOUR_DEPTH {
                for (offset, wall) in walls.iter().enumerate().skip(usize::from(next_wall)) {
                    let Some(there) = wall.neighbour() else {
                        continue;
                    };
                    let neighbour = &map.sectors[usize::from(there)];
                    if !self.is_open(there) || !passable(sector, neighbour) {
                        continue;
                    }
                    self.chain[self.depth - 1].1 = offset as u16 + 1;
                    self.chain[self.depth] = (there, 0);
                    self.depth += 1;
                    self.mark(there);
                    self.moved_since_start = true;
                    return Some([
                        Waypoint {
                            point: midpoint(map, wall),
                            sector: here,
                        },
                        Waypoint {
                            point: centre(map, neighbour),
                            sector: there,
                        },
                    ]);
                }
            }
            // Nothing left to see from here: back out through the portal we came in by.
            self.depth -= 1;
            if self.depth == 0 {
                if !self.moved_since_start {
                    return None;
                }
                self.start();
                continue;
            }
            let (parent, after_entry) = self.chain[self.depth - 1];
            let parent_sector = &map.sectors[usize::from(parent)];
            let entry = &map.sector_walls(parent_sector)[usize::from(after_entry - 1)];
            return Some([
                Waypoint {
                    point: midpoint(map, entry),
                    sector: here,
                },
                Waypoint {
                    point: centre(map, parent_sector),
                    sector: parent,
                },
            ]);
        }
    }
}

/// One straight piece of the path, inside one sector.
#[derive(Clone, Copy, Debug)]
struct Leg {
    from: WorldPoint,
    to: WorldPoint,
    sector: u16,
    /// Length in 24.8 bits.
    length: i64,
    /// Distance flown along it so far, in 24.8 bits.
    flown: i64,
}

impl Leg {
    fn new(from: WorldPoint, to: Waypoint) -> Leg {
        let dx = i64::from(to.point.x.to_bits() - from.x.to_bits());
        let dy = i64::from(to.point.y.to_bits() - from.y.to_bits());
        Leg {
            from,
            to: to.point,
            sector: to.sector,
            length: (dx * dx + dy * dy).unsigned_abs().isqrt() as i64,
            flown: 0,
        }
    }

    fn point(&self) -> WorldPoint {
        let along = |from: Fx24_8, to: Fx24_8| {
            let delta = i64::from(to.to_bits() - from.to_bits());
            let offset = if self.length == 0 {
                0
            } else {
                div_round_nearest(delta * self.flown, self.length)
            };
            Fx24_8::from_bits(from.to_bits() + offset as i32)
        };
        WorldPoint::new(along(self.from.x, self.to.x), along(self.from.y, self.to.y))
    }

    fn heading(&self) -> Angle {
        heading(
            self.to.x.to_bits() - self.from.x.to_bits(),
            self.to.y.to_bits() - self.from.y.to_bits(),
        )
    }
}

/// The fly-through of one map: an iterator of cameras, one per frame, endless (the tour
/// repeats). Frame 0 is the player start, looking the start's way.
#[derive(Clone, Debug)]
pub struct Flight<'m> {
    map: MapTables<'m>,
    camera: Camera,
    leg: Option<Leg>,
    queued: Option<Waypoint>,
    tour: Tour,
}

impl<'m> Flight<'m> {
    /// The fly-through of `map`, at its first frame.
    pub fn new(map: &MapTables<'m>) -> Flight<'m> {
        let start = map.player_start;
        let sector = &map.sectors[usize::from(start.sector)];
        let position = WorldPoint::new(
            Fx24_8::from_bits(start.x_fx8),
            Fx24_8::from_bits(start.y_fx8),
        );
        let mut flight = Flight {
            map: *map,
            camera: Camera {
                position,
                eye_z: eye_z(sector),
                angle: Angle::from_bits(start.angle),
                sector: start.sector,
                look_lines: 0,
            },
            leg: None,
            queued: None,
            tour: Tour::new(start.sector),
        };
        flight.leg = flight.next_waypoint().map(|to| Leg::new(position, to));
        flight
    }

    fn next_waypoint(&mut self) -> Option<Waypoint> {
        if let Some(queued) = self.queued.take() {
            return Some(queued);
        }
        let [first, second] = self.tour.step(&self.map)?;
        self.queued = Some(second);
        Some(first)
    }

    /// Moves `distance` (24.8 bits) along the path, onto the following legs as each ends.
    fn fly(&mut self, distance: i64) {
        let mut left = distance;
        while let Some(leg) = self.leg.as_mut() {
            let remaining = leg.length - leg.flown;
            if left <= remaining {
                leg.flown += left;
                return;
            }
            left -= remaining;
            let end = leg.to;
            self.leg = self.next_waypoint().map(|to| Leg::new(end, to));
        }
    }

    /// The sector strictly containing the current point of the path, if any: the leg's own, or
    /// (when rounding put the point a hair past a portal) the neighbour across a portal the
    /// point is not inside of.
    fn locate(&self, leg: &Leg, p: WorldPoint) -> Option<u16> {
        if strictly_inside(&self.map, leg.sector, p) {
            return Some(leg.sector);
        }
        let sector = &self.map.sectors[usize::from(leg.sector)];
        self.map
            .sector_walls(sector)
            .iter()
            .filter(|wall| {
                side_of_line(
                    vertex(&self.map, wall.start),
                    vertex(&self.map, wall.end),
                    p,
                ) != Side::Right
            })
            .filter_map(Wall::neighbour)
            .find(|&neighbour| strictly_inside(&self.map, neighbour, p))
    }

    /// Advances one frame: flies [`SPEED`], moves off any wall line, and turns towards the leg.
    fn advance(&mut self) {
        self.fly(i64::from(SPEED) << Fx24_8::FRAC_BITS);
        let Some(mut leg) = self.leg else {
            // No passable portal from the start: turn on the spot.
            self.camera.angle = self.camera.angle.wrapping_add(Angle::from_bits(256));
            return;
        };
        let mut nudges = 0;
        loop {
            let p = leg.point();
            if let Some(sector) = self.locate(&leg, p) {
                self.camera.position = p;
                self.camera.sector = sector;
                self.camera.eye_z = eye_z(&self.map.sectors[usize::from(sector)]);
                break;
            }
            nudges += 1;
            assert!(nudges <= MAX_NUDGES, "the flight left the map");
            self.fly(1);
            leg = self.leg.expect("a path with legs keeps them");
        }
        let remaining = i32::from(leg.heading().wrapping_sub(self.camera.angle).to_bits() as i16);
        let turn = if remaining.abs() <= TURN_SNAP {
            remaining
        } else {
            (remaining >> TURN_EASE_SHIFT).clamp(-MAX_TURN_PER_FRAME, MAX_TURN_PER_FRAME)
        };
        self.camera.angle = self
            .camera
            .angle
            .wrapping_add(Angle::from_bits(turn as u16));
    }
}

impl Iterator for Flight<'_> {
    type Item = Camera;

    fn next(&mut self) -> Option<Camera> {
        let camera = self.camera;
        self.advance();
        Some(camera)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heading_recovers_table_directions() {
        for bits in (0..=u16::MAX).step_by(97) {
            let (sin, cos) = Angle::from_bits(bits).sin_cos();
            let found = heading(cos.to_bits(), sin.to_bits()).to_bits();
            let error = found.wrapping_sub(bits) as i16;
            assert!(error.abs() <= 1, "{bits}: {found}");
        }
        assert_eq!(heading(256, 0), Angle::ZERO);
        assert_eq!(heading(0, 256), Angle::QUARTER);
        assert_eq!(heading(-256, 0), Angle::HALF);
        assert_eq!(heading(0, -256), Angle::THREE_QUARTERS);
    }
}
