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
//! side-of-line tests of [`portalcast::math`], and a pose that lands on a wall line (the middle of a
//! portal, at the end of a leg) moves on by one 1/256 step until it is strictly inside.
//!
//! Like a player, the path keeps clear of solid things: a sector's centre inside a solid thing's
//! clearance (its radius and the player's) gives way to a point on the near side of the thing,
//! and a leg that would pass through one goes round it by one more waypoint.
//!
//! The camera moves [`SPEED`] along the path each frame (about Doom's running speed per tic),
//! eye [`EYE_HEIGHT`] above the floor of its sector, and turns smoothly towards the direction of
//! its leg: a quarter of the remaining angle per frame, at most [`MAX_TURN_PER_FRAME`].
//!
//! Everything is integer arithmetic on the map's own formats (24.8 positions, binary angles), so
//! a frame's pose is the same on every machine.

use portalcast_format::{MapTables, Sector, Thing, Wall, THING_SOLID};

use portalcast::math::{div_round_nearest, side_of_line, Angle, Fx24_8, Side, WorldPoint};
use portalcast::player::collide::RADIUS;
use portalcast::render::view::Camera;

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

/// The eye height at `at` in `sector` of `map`: [`EYE_HEIGHT`] above its floor there, lowered
/// to leave [`HEAD_ROOM`] under a low ceiling, and half-way up where even that would be at or
/// under the floor (the same rule as the oracle's sampled poses). On a flat sector the point
/// does not matter.
pub fn eye_z(map: &MapTables, sector: &Sector, at: WorldPoint) -> Fx24_8 {
    let (floor, ceil) = map.heights_fx8_at(sector, at.x.to_bits(), at.y.to_bits());
    let eye = (floor + EYE_HEIGHT * 256).min(ceil - HEAD_ROOM * 256);
    if eye > floor {
        Fx24_8::from_bits(eye)
    } else {
        Fx24_8::from_bits((floor + ceil) >> 1)
    }
}

/// Whether a walker passes from `from` to `to` through a portal between them at `at`: a floor
/// step of at most [`MAX_STEP`] either way and an opening of at least [`MIN_OPENING`], with the
/// heights there (a slope's vary along the portal).
pub fn passable(map: &MapTables, from: &Sector, to: &Sector, at: WorldPoint) -> bool {
    let heights = |sector: &Sector| map.heights_fx8_at(sector, at.x.to_bits(), at.y.to_bits());
    let ((from_floor, from_ceil), (to_floor, to_ceil)) = (heights(from), heights(to));
    let step = (to_floor - from_floor).abs();
    let opening = from_ceil.min(to_ceil) - from_floor.max(to_floor);
    step <= MAX_STEP * 256 && opening >= MIN_OPENING * 256
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

/// How near the eye may come to a solid thing's centre, in 24.8 bits: the thing's radius and the
/// player's, the distance a player's centre keeps (`portalcast::player::collide`).
fn clearance_bits(thing: &Thing) -> i64 {
    (i64::from(thing.radius) + i64::from(RADIUS)) << Fx24_8::FRAC_BITS
}

/// The solid things of sector `sector`.
fn solid_things<'a>(map: &MapTables<'a>, sector: u16) -> impl Iterator<Item = &'a Thing> + 'a {
    map.things_in(sector)
        .iter()
        .filter(|thing| thing.flags & THING_SOLID != 0)
}

/// `(x, y)` of a point in 24.8 bits, wide.
fn bits(p: WorldPoint) -> (i64, i64) {
    (i64::from(p.x.to_bits()), i64::from(p.y.to_bits()))
}

/// The point `length` (24.8 bits) from `centre` towards `(dx, dy)`, rounded to 24.8 bits; `None`
/// for a zero direction.
fn towards(centre: (i64, i64), (dx, dy): (i64, i64), length: i64) -> Option<WorldPoint> {
    let norm = (dx * dx + dy * dy).unsigned_abs().isqrt() as i64;
    if norm == 0 {
        return None;
    }
    let at = |c: i64, d: i64| Fx24_8::from_bits((c + div_round_nearest(d * length, norm)) as i32);
    Some(WorldPoint::new(at(centre.0, dx), at(centre.1, dy)))
}

/// Where the tour stands in `sector`, coming from `from`: its centre, or, where a solid thing
/// stands there (a statue in the middle of a room), the point a quarter of the thing's
/// clearance beyond it on the side `from` is, if that is inside the sector. A player's centre
/// never comes that near a solid thing, so neither does the benchmark's eye.
fn stand_point(map: &MapTables, sector: u16, from: WorldPoint) -> WorldPoint {
    let centre = centre(map, &map.sectors[usize::from(sector)]);
    let (cx, cy) = bits(centre);
    let Some(thing) = solid_things(map, sector).find(|thing| {
        let (dx, dy) = (cx - i64::from(thing.x_fx8), cy - i64::from(thing.y_fx8));
        let clearance = clearance_bits(thing);
        dx * dx + dy * dy < clearance * clearance
    }) else {
        return centre;
    };
    let at = (i64::from(thing.x_fx8), i64::from(thing.y_fx8));
    let (fx, fy) = bits(from);
    towards(at, (fx - at.0, fy - at.1), clearance_bits(thing) * 5 / 4)
        .filter(|&point| strictly_inside(map, sector, point))
        .unwrap_or(centre)
}

/// Units added to a solid thing's clearance when deciding whether a way passes near it: the
/// decision is taken in whole units.
const DETOUR_MARGIN: i64 = 2;

/// A point to go round by on the way from `from` to `to` in `sector`, if the straight way passes
/// nearer a solid thing's centre than its clearance: twice the clearance from the thing, square
/// to the way, on the side the way passes (the left one if it passes through the centre), or on
/// the other side if that one is outside the sector. `None` where the way is clear or no such
/// point is inside the sector. One detour a leg: `tests/live_flight.rs` checks that the shipped
/// maps' paths keep the clearance.
fn detour(map: &MapTables, sector: u16, from: WorldPoint, to: WorldPoint) -> Option<WorldPoint> {
    let ((fx, fy), (tx, ty)) = (bits(from), bits(to));
    let (dx, dy) = (tx - fx, ty - fy);
    if dx == 0 && dy == 0 {
        return None;
    }
    // Whether the way passes near: in whole units (products within 64 bits), with a margin of
    // [`DETOUR_MARGIN`] units for their rounding.
    let unit = |bits: i64| bits >> Fx24_8::FRAC_BITS;
    let (ux, uy, udx, udy) = (unit(fx), unit(fy), unit(tx) - unit(fx), unit(ty) - unit(fy));
    let length_squared = (udx * udx + udy * udy).max(1);
    let thing = solid_things(map, sector).find(|thing| {
        let (cx, cy) = (unit(i64::from(thing.x_fx8)), unit(i64::from(thing.y_fx8)));
        // The nearest point of the way to the thing, rounded to units.
        let along = ((cx - ux) * udx + (cy - uy) * udy).clamp(0, length_squared);
        let (qx, qy) = (
            ux + div_round_nearest(udx * along, length_squared),
            uy + div_round_nearest(udy * along, length_squared),
        );
        let reach = (clearance_bits(thing) >> Fx24_8::FRAC_BITS) + DETOUR_MARGIN;
        (cx - qx) * (cx - qx) + (cy - qy) * (cy - qy) < reach * reach
    })?;
    let at = (i64::from(thing.x_fx8), i64::from(thing.y_fx8));
    // Left of the way is (−dy, dx); the thing is left of it where the cross product is positive.
    let thing_left = dx * (at.1 - fy) - dy * (at.0 - fx) > 0;
    let away = if thing_left { (dy, -dx) } else { (-dy, dx) };
    let reach = clearance_bits(thing) * 2;
    [away, (-away.0, -away.1)]
        .into_iter()
        .filter_map(|direction| towards(at, direction, reach))
        .find(|&point| strictly_inside(map, sector, point))
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
                    if !self.is_open(there)
                        || !passable(map, sector, neighbour, midpoint(map, wall))
                    {
                        continue;
                    }
                    self.chain[self.depth - 1].1 = offset as u16 + 1;
                    self.chain[self.depth] = (there, 0);
                    self.depth += 1;
                    self.mark(there);
                    self.moved_since_start = true;
                    let through = midpoint(map, wall);
                    return Some([
                        Waypoint {
                            point: through,
                            sector: here,
                        },
                        Waypoint {
                            point: stand_point(map, there, through),
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
            let through = midpoint(map, entry);
            return Some([
                Waypoint {
                    point: through,
                    sector: here,
                },
                Waypoint {
                    point: stand_point(map, parent, through),
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
    /// By reference: the tables (17 slices) by value made every copy of a flight, and the
    /// bench scene's stack, 136 bytes larger.
    map: &'m MapTables<'m>,
    camera: Camera,
    leg: Option<Leg>,
    queued: Option<Waypoint>,
    /// The waypoint the path goes on to after a detour round a solid thing.
    after_detour: Option<Waypoint>,
    tour: Tour,
}

impl<'m> Flight<'m> {
    /// The fly-through of `map`, at its first frame.
    pub fn new(map: &'m MapTables<'m>) -> Flight<'m> {
        let start = map.player_start;
        let sector = &map.sectors[usize::from(start.sector)];
        let position = WorldPoint::new(
            Fx24_8::from_bits(start.x_fx8),
            Fx24_8::from_bits(start.y_fx8),
        );
        let mut flight = Flight {
            map,
            camera: Camera {
                position,
                eye_z: eye_z(map, sector, position),
                angle: Angle::from_bits(start.angle),
                sector: start.sector,
                look_lines: 0,
            },
            leg: None,
            queued: None,
            after_detour: None,
            tour: Tour::new(start.sector),
        };
        flight.leg = flight.next_leg(position);
        flight
    }

    fn next_waypoint(&mut self) -> Option<Waypoint> {
        if let Some(queued) = self.queued.take() {
            return Some(queued);
        }
        let [first, second] = self.tour.step(self.map)?;
        self.queued = Some(second);
        Some(first)
    }

    /// The leg from `from` to the next waypoint, or to a point round a solid thing on the way
    /// to it ([`detour`]), the waypoint then next.
    fn next_leg(&mut self, from: WorldPoint) -> Option<Leg> {
        if let Some(resumed) = self.after_detour.take() {
            return Some(Leg::new(from, resumed));
        }
        let to = self.next_waypoint()?;
        match detour(self.map, to.sector, from, to.point) {
            Some(round) => {
                self.after_detour = Some(to);
                Some(Leg::new(
                    from,
                    Waypoint {
                        point: round,
                        sector: to.sector,
                    },
                ))
            }
            None => Some(Leg::new(from, to)),
        }
    }

    /// Moves `distance` (24.8 bits) along the path, onto the following legs as each ends, but
    /// no further than the end of a leg after which the path goes on in another sector: every
    /// sector on the path, however thin (a door), has a frame of its own, so the live world
    /// sees the camera at its door.
    fn fly(&mut self, distance: i64) {
        let mut left = distance;
        while let Some(leg) = self.leg.as_mut() {
            let remaining = leg.length - leg.flown;
            if left <= remaining {
                leg.flown += left;
                return;
            }
            left -= remaining;
            let (end, sector) = (leg.to, leg.sector);
            self.leg = self.next_leg(end);
            if self.leg.is_some_and(|next| next.sector != sector) {
                return;
            }
        }
    }

    /// The sector strictly containing the current point of the path, if any: the leg's own, or
    /// (when rounding put the point a hair past a portal) the neighbour across a portal the
    /// point is not inside of.
    fn locate(&self, leg: &Leg, p: WorldPoint) -> Option<u16> {
        if strictly_inside(self.map, leg.sector, p) {
            return Some(leg.sector);
        }
        let sector = &self.map.sectors[usize::from(leg.sector)];
        self.map
            .sector_walls(sector)
            .iter()
            .filter(|wall| {
                side_of_line(vertex(self.map, wall.start), vertex(self.map, wall.end), p)
                    != Side::Right
            })
            .filter_map(Wall::neighbour)
            .find(|&neighbour| strictly_inside(self.map, neighbour, p))
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
                self.camera.eye_z = eye_z(self.map, &self.map.sectors[usize::from(sector)], p);
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
