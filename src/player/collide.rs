//! Horizontal movement: the body is a disc of radius [`RADIUS`] sliding among walls, and its
//! centre is tracked from sector to sector through the portals it crosses.
//!
//! # What blocks
//!
//! A solid wall, a solid thing (below), and a portal into a sector the [`Body`] may not enter:
//! one whose floor is more than [`STEP_UP_MAX`] above the feet, or whose ceiling leaves less
//! than [`HEADROOM`] above the eye the body would have there. Portals into sectors the body may enter are open: the disc
//! passes over them, and the walls of the sectors behind them block it too (the jambs of a
//! doorway, the far side of a corridor). These sectors are found by a walk through open portals
//! near the move (no search over all sectors), at most [`MAX_NEARBY_SECTORS`] of them.
//!
//! # One move
//!
//! [`slide`] splits a move into steps of at most half the radius, so no step can carry the disc
//! across a wall (swept motion without tunnelling). Each step goes to its target and pushes the
//! disc out of every blocking segment it overlaps, a few passes over the segments so that the
//! pushes of two walls meeting in a concave corner settle. A push along a wall's normal removes
//! the part of the motion that went into the wall and keeps the part along it: that is the
//! slide. Edges are pushed before vertices in each pass, so a wall split in two collinear
//! pieces is as smooth as one. A wall is pushed only from its front (the side its sector is
//! on): from behind, a wall of a neighbouring sector is not between the disc and that sector.
//!
//! The result must then pass two checks, or the step tries moving along x only, then y only
//! (as Doom does), and otherwise the disc stays where it was:
//! - the disc overlaps no blocking segment by more than [`OVERLAP_TOLERANCE`] (or no more than
//!   before the step, so a disc that starts overlapping, after landing beside a ledge, can
//!   still move away): in a gap narrower than the disc the pushes cannot settle, and the step
//!   is refused;
//! - [`track`] follows the centre's straight path exactly (64-bit cross products, no
//!   tolerance) from its sector through the portals it crosses: every crossed wall must be an
//!   open portal (one whose heights admit the body and whose middle image does not block:
//!   `WALL_MIDDLE_BLOCKS` makes a portal a wall to the body), and the end point must lie
//!   strictly inside the sector reached. A path that
//!   runs exactly through a vertex, or ends exactly on a wall's line, is nudged by 1/256 unit
//!   (the first of the eight neighbouring positions that tracks cleanly).
//!
//! So, whatever the pushes did, the centre never crosses a blocking wall and is always strictly
//! inside its sector: the exact checks are the guarantee, the pushes only make the motion
//! pleasant. The pushes use square roots and divisions rounded away from the wall (never short
//! of the radius by more than a rounding step).
//!
//! # Solid things
//!
//! A thing with [`THING_SOLID`] is a disc of its [`Thing::radius`] around its position, whatever
//! the heights (a jump does not clear it, a hanging one blocks too): the body may not overlap it,
//! that is come nearer its centre than [`RADIUS`] plus its radius (its reach). A step considers
//! the solid things of the sectors the walk above reached (its own and those behind open
//! portals near it) and of the sectors behind the blocking portals it kept, whose discs meet
//! the step's box. That is every one the body can touch: a body overlapping a thing's disc
//! overlaps its sector (the compiler keeps the disc inside it), so it reaches that sector
//! across the portals between the two centres, within its own disc, which the walk follows or
//! keeps as blocking (up to [`MAX_NEARBY_SECTORS`], as for walls). The walk notes whether those
//! sectors have things at all (a bounds test per sector on a map without things, two reads on
//! one with some); only then are their things read, and a list of the solid ones near is made
//! (`Discs`: room for a few, beyond which each pass reads them from the map again).
//!
//! A disc is one more obstacle of the pushes, after the segments in each pass: a radial push to
//! exactly its reach or beyond (the root rounded down, the quotients away from its centre; at its
//! very centre, along +x), the push of a wall's vertex with a larger radius. So a step whose
//! pushes settle ends clear of every disc, exactly. One whose pushes do not settle, or that a
//! nudge moves by 1/256, must also pass an exact test (64-bit squares, no tolerance): it
//! overlaps no disc, or, if the step began overlapping some (a start placed in a thing), no
//! deeper than it began (the largest `reach² − distance²`); otherwise the step tries x alone,
//! then y alone, then stays. The guarantee for things: **the body never ends a step nearer a
//! solid thing's centre than the sum of the radii**, unless it began the step so (then no
//! deeper, and a push moves it out), on top of the walls' guarantees, which hold as they did
//! (discs only add pushes and a test; the passes stay bounded). A thing behind a solid wall of
//! another sector is kept away by that wall (to its tolerance). A disc pushes the body round
//! it, so a glancing move slides round; a gap between a thing and a wall narrower than the body
//! refuses the step.

use portalcast_format::{
    MapTables, PlayerSize, Sector, SectorSlope, Thing, Vertex, Wall, NO_PORTAL, NO_SLOPE,
    NO_TEXTURE, THING_SOLID, WALL_MIDDLE_BLOCKS,
};

use crate::math::{segment_contact, Fx24_8, SegmentContact, WorldPoint};
use crate::render::ratio::leading_zeros;

/// Radius of the body's disc, in world units: Doom's player radius, half the thesis' 64-unit
/// square. Corridors of the shipped maps are at least 64 wide.
pub const RADIUS: i32 = 16;
/// The highest floor step the body climbs without jumping, above its feet, on native maps: a
/// map's own is its [`PlayerSize::step_up`] (24 on Doom's).
pub const STEP_UP_MAX: i32 = PlayerSize::NATIVE.step_up;
/// Room the eye keeps below any ceiling on native maps: a map's own is its
/// [`PlayerSize::headroom`] (15 on Doom's).
pub const HEADROOM: i32 = PlayerSize::NATIVE.headroom();
/// The longest step [`slide`] takes per axis, in 24.8 bits: half the radius, so a step never
/// jumps over more than half the disc.
pub const MAX_STEP_BITS: i32 = RADIUS * 256 / 2;
/// How far, in 24.8 bits (1/32 unit), the disc may still overlap a blocking segment after the
/// pushes settle (the length of the push that would clear it).
pub const OVERLAP_TOLERANCE: i64 = 8;
/// Most sectors the disc is checked against in one step (its own and those behind open
/// portals near it). Walls of sectors beyond are not pushed against; the exact tracking still
/// holds.
pub const MAX_NEARBY_SECTORS: usize = 16;
/// Most blocking segments near one step.
pub const MAX_SEGMENTS: usize = 48;
/// Passes of pushes per step: two settle a right-angled corner; more only help sharp wedges.
const PUSH_PASSES: usize = 4;
/// Most portals one step's path may cross.
const MAX_HOPS: usize = 8;

const RADIUS_BITS: i32 = RADIUS * 256;

/// A point in 24.8 bits. The pushes' points stay within 2^23 bits: a target is within the
/// declared world (2^21 bits) plus a step, a thing's push leaves the point within √2 times its
/// reach plus 2 bits of its centre ([`Disc::push`]), whose disc lies inside the world (its
/// sector's), so within 2^22 bits, and one settling adds at most
/// `PUSH_PASSES · 2 · MAX_SEGMENTS` segment pushes of at most `2 · RADIUS_BITS + 1` each (under
/// 2^22) after either.
/// Their differences with map vertices fit 32 bits and their products 64: every product below
/// multiplies two 32-bit values into 64 bits, one ARM instruction.
type Bits = (i32, i32);

/// `value` widened for a 64-bit product.
fn wide(value: i32) -> i64 {
    i64::from(value)
}

/// [`crate::math::geometry::cross`] of points whose differences fit 32 bits (map vertices and points within the
/// declared world: under 2^23 bits apart): two 32×32→64 products, where `cross` widens first
/// and multiplies 64×64.
fn cross_near(a: Bits, b: Bits, p: Bits) -> i64 {
    let (abx, aby) = (b.0 - a.0, b.1 - a.1);
    let (apx, apy) = (p.0 - a.0, p.1 - a.1);
    wide(abx) * wide(apy) - wide(aby) * wide(apx)
}

/// A vertex in 24.8 bits.
fn vertex_bits(map: &MapTables, index: u16) -> Bits {
    let vertex = map.vertices[usize::from(index)];
    (vertex.x * 256, vertex.y * 256)
}

/// The vertical extent of the body, which decides the sectors it may enter, and the sectors'
/// heights as they are now.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Body<'s> {
    /// Height of the feet (the floor, when standing).
    pub feet: Fx24_8,
    /// Height of the eye above the feet.
    pub eye_height: Fx24_8,
    /// The map's player body: its step and headroom decide the sectors it may enter.
    pub size: PlayerSize,
    /// The map's sectors with their heights now ([`Body::admits_sector`]): the live table of a
    /// map with movers (`crate::world`), the cartridge's otherwise. Only their heights are read
    /// here; the walls come from the map's own table.
    pub sectors: &'s [Sector],
}

/// The floor and ceiling of `sector` at the point `at` (24.8 bits), in 24.8 bits: its heights
/// where it is flat, its planes' there where it slopes (`slopes`, the map's).
#[inline(always)]
pub fn heights_at(slopes: &[SectorSlope], sector: &Sector, at: (i32, i32)) -> (i32, i32) {
    // A map without slopes asks its slice's length (in a register or on the stack), not each
    // sector's slope index (in the cartridge): the tick admits several sectors.
    if slopes.is_empty() || sector.slope == NO_SLOPE {
        (sector.floor_z * 256, sector.ceil_z * 256)
    } else {
        sloped_heights_at(slopes, sector, at)
    }
}

/// The floor and ceiling of the space a body in sector `index` of `map` may use at `at` (24.8
/// bits), in 24.8 bits: the sector's own heights ([`heights_at`]), with an open floor taken
/// down to the floor of the sectors below it and an open ceiling up to the ceiling of those
/// above (room over room, [`MapTables::layer_links`]). Out of line and in ROM: only sectors with
/// a floor or ceiling portal come here.
#[inline(never)]
pub fn open_heights_at(map: &MapTables, index: u16, at: (i32, i32)) -> (i32, i32) {
    let heights = |index: u16| heights_at(map.slopes, &map.sectors[usize::from(index)], at);
    let (mut floor, mut ceil) = heights(index);
    let (mut down, mut up) = (index, index);
    while let Some(below) = map.sector_below(down) {
        down = below;
        floor = heights(down).0;
    }
    while let Some(above) = map.sector_above(up) {
        up = above;
        ceil = heights(up).1;
    }
    (floor, ceil)
}

/// [`heights_at`] of a sector with a slope: out of line and in ROM, so flat maps' ticks carry
/// no copy of it in IWRAM.
#[inline(never)]
fn sloped_heights_at(slopes: &[SectorSlope], sector: &Sector, at: (i32, i32)) -> (i32, i32) {
    portalcast_format::sector_heights_fx8_at(slopes, sector, at.0, at.1)
}

impl Body<'_> {
    /// One step of the body's disc of at most [`MAX_STEP_BITS`] per axis.
    ///
    /// In VRAM on the GBA (IWRAM has no room): every tick takes at least one step. A method
    /// because `link_section` on a free function is refused as unsafe code.
    #[inline(never)]
    #[cfg_attr(
        target_os = "none",
        link_section = ".vram_after_pages.player_slide_step"
    )]
    fn slide_step(
        &self,
        map: &MapTables,
        sector: u16,
        from: WorldPoint,
        step: Delta,
    ) -> (WorldPoint, u16) {
        let body = self;
        debug_assert!(
            strictly_inside(map, &map.sectors[usize::from(sector)], from),
            "a step must start strictly inside its sector"
        );
        let reach = 2 * RADIUS_BITS + 256;
        let bounds = Bounds::around(from, step, reach);
        let target = (from.x.to_bits() + step.x, from.y.to_bits() + step.y);
        // Room for a few segments, which is quick to clear; more take the slower path.
        let mut few = [&NO_SEGMENT; FEW_SEGMENTS];
        let mut reached = [0; MAX_NEARBY_SECTORS];
        let Some(obstacles) =
            Obstacles::near(map, sector, &bounds, body, &mut few, &mut reached, target)
        else {
            return slide_step_among_many(map, sector, from, step, body, &bounds, target);
        };
        // Only a step near things looks for solid ones (a list of them is large: it is filled
        // only then, and stays out of `Obstacles`, which every step copies).
        if obstacles.things_near(map) {
            // By reference: bound by value, the list (136 bytes) was copied out of the option
            // with a library call.
            if let Some(discs) = &Discs::near(map, &obstacles, bounds) {
                return try_moves(map, sector, from, step, body, &obstacles, Some(discs));
            }
        }
        // Nothing to push against and the step ends strictly inside its sector: what try_moves'
        // first try finds (no push, then track's first test), without a second pass over the
        // sector's walls.
        if obstacles.ends.is_empty() && obstacles.target_inside {
            if let Some(to) = point_from_bits(target) {
                return (to, sector);
            }
        }
        try_moves(map, sector, from, step, body, &obstacles, None)
    }

    /// [`Body::admits`] of sector `index` of [`Body::sectors`]. A sector with a floor or ceiling
    /// portal admits the body by its own heights, as any other: the body moves in the layer of
    /// its feet (docs/MAP_FORMAT.md, "Room over room"). Only its vertical motion uses the open
    /// space's heights ([`open_heights_at`]): a test of each sector's links here cost the
    /// step's walk over nearby walls (IWRAM) 40 cycles a tick.
    pub fn admits_sector(&self, slopes: &[SectorSlope], index: u16, at: (i32, i32)) -> bool {
        self.admits(slopes, &self.sectors[usize::from(index)], at)
    }

    /// Whether the body may move into `sector` (of a map whose sloped planes are `slopes`,
    /// [`MapTables::slopes`]) with its centre at `at` (24.8 bits): its floor
    /// there at most the size's step above the feet ([`STEP_UP_MAX`] on native maps), and its
    /// ceiling there at least the size's headroom ([`HEADROOM`]) above the eye once the feet
    /// stand at least on its floor. A flat sector's heights are the same everywhere; a sloped
    /// one's are taken where the body would stand, so a ramp is entered at its foot and a
    /// sloped step is climbed where it is low enough.
    pub fn admits(&self, slopes: &[SectorSlope], sector: &Sector, at: (i32, i32)) -> bool {
        self.fits(heights_at(slopes, sector, at))
    }

    /// Whether the body may stand between `floor` and `ceil` (24.8): the rule of
    /// [`Body::admits`].
    #[inline(always)]
    fn fits(&self, (floor, ceil): (i32, i32)) -> bool {
        let feet = self.feet.to_bits();
        floor <= feet + self.size.step_up * 256
            && ceil >= feet.max(floor) + self.eye_height.to_bits() + self.size.headroom() * 256
    }
}

/// A move in 24.8 bits per axis.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Delta {
    /// Along x.
    pub x: i32,
    /// Along y.
    pub y: i32,
}

/// Where a straight path of the centre ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Track {
    /// Strictly inside this sector, having crossed only open portals.
    Inside(u16),
    /// The path crosses a solid wall or a portal the body may not enter.
    Blocked,
    /// The path runs through a vertex, along a wall, or ends on a wall's line.
    Degenerate,
}

/// Moves the disc centred at `from` (strictly inside `sector`) by `delta`, sliding along what
/// blocks it. Returns the new centre and its sector.
pub fn slide(
    map: &MapTables,
    sector: u16,
    from: WorldPoint,
    delta: Delta,
    body: &Body,
) -> (WorldPoint, u16) {
    let steps = delta
        .x
        .unsigned_abs()
        .max(delta.y.unsigned_abs())
        .div_ceil(MAX_STEP_BITS as u32)
        .max(1) as i32;
    if steps == 1 {
        // Every move within the speed limit of walking and running: no split, so no divide.
        return body.slide_step(map, sector, from, delta);
    }
    slide_in_steps(map, sector, from, delta, body, steps)
}

/// [`slide`] of a move split into `steps` steps. Out of line: only a push faster than running
/// takes it.
#[inline(never)]
fn slide_in_steps(
    map: &MapTables,
    sector: u16,
    from: WorldPoint,
    delta: Delta,
    body: &Body,
    steps: i32,
) -> (WorldPoint, u16) {
    let (mut position, mut sector) = (from, sector);
    for index in 0..steps {
        // The exact split: the steps add up to `delta`.
        let part = |total: i32| total * (index + 1) / steps - total * index / steps;
        let step = Delta {
            x: part(delta.x),
            y: part(delta.y),
        };
        (position, sector) = body.slide_step(map, sector, position, step);
    }
    (position, sector)
}

/// [`Body::slide_step`] when more than [`FEW_SEGMENTS`] blocking segments are near. Out of line.
#[inline(never)]
fn slide_step_among_many(
    map: &MapTables,
    sector: u16,
    from: WorldPoint,
    step: Delta,
    body: &Body,
    bounds: &Bounds,
    target: Bits,
) -> (WorldPoint, u16) {
    let mut many = [&NO_SEGMENT; MAX_SEGMENTS];
    let mut reached = [0; MAX_NEARBY_SECTORS];
    let Some(obstacles) =
        Obstacles::near(map, sector, bounds, body, &mut many, &mut reached, target)
    else {
        unreachable!("a list of MAX_SEGMENTS segments drops the rest")
    };
    let discs = if obstacles.things_near(map) {
        Discs::near(map, &obstacles, *bounds)
    } else {
        None
    };
    try_moves(map, sector, from, step, body, &obstacles, discs.as_ref())
}

/// The rest of [`Body::slide_step`]: the step, else along x alone, else along y alone, among
/// `obstacles` and `discs`.
#[inline(never)]
fn try_moves(
    map: &MapTables,
    sector: u16,
    from: WorldPoint,
    step: Delta,
    body: &Body,
    obstacles: &Obstacles,
    discs: Option<&Discs>,
) -> (WorldPoint, u16) {
    // Only needed for a target the pushes leave overlapping: most steps never compute it.
    let mut allowed_depth = None;
    let tries = [step, Delta { x: step.x, y: 0 }, Delta { x: 0, y: step.y }];
    let try_count = if step.x != 0 && step.y != 0 { 3 } else { 1 };
    for (index, attempt) in tries[..try_count].iter().enumerate() {
        let target = (from.x.to_bits() + attempt.x, from.y.to_bits() + attempt.y);
        let (settled, pushes_done) = obstacles.push_out(target, discs);
        // When the last pass pushed nothing, no segment pushes the result: its overlap is 0.
        if !pushes_done {
            if obstacles.deepens_some(point_bits(from), settled) {
                continue;
            }
            // Unsettled pushes may leave the disc in a thing: never deeper than it began.
            if let Some(discs) = discs {
                let allowed = *allowed_depth.get_or_insert_with(|| discs.depth(point_bits(from)));
                if discs.depth(settled) > allowed {
                    continue;
                }
            }
        }
        let Some(to) = point_from_bits(settled) else {
            continue;
        };
        // The whole step, not pushed: the walk over the walls has made track's first test.
        let unpushed_step = index == 0 && settled == target;
        if unpushed_step && obstacles.target_inside {
            return (to, sector);
        }
        if let Some((to, sector)) = track_nudged(map, sector, from, to, body, unpushed_step, discs)
        {
            return (to, sector);
        }
    }
    (from, sector)
}

/// [`track`], and on a degenerate path the same for the eight positions 1/256 unit around
/// `to` (toward the motion first) that overlap none of `discs` deeper than `from` does. The
/// position reached and its sector, if any tracks.
fn track_nudged(
    map: &MapTables,
    sector: u16,
    from: WorldPoint,
    to: WorldPoint,
    body: &Body,
    to_outside: bool,
    discs: Option<&Discs>,
) -> Option<(WorldPoint, u16)> {
    // `to_outside`: the caller knows `to` is not strictly inside `sector`, track's first test.
    let tracked = if to_outside {
        track_through_portals(map, sector, from, to, body)
    } else {
        track(map, sector, from, to, body)
    };
    match tracked {
        Track::Inside(sector) => Some((to, sector)),
        Track::Blocked | Track::Degenerate => track_nudges(map, sector, from, to, body, discs),
    }
}

/// The nudges of [`track_nudged`]. Out of line, since rare.
#[inline(never)]
fn track_nudges(
    map: &MapTables,
    sector: u16,
    from: WorldPoint,
    to: WorldPoint,
    body: &Body,
    discs: Option<&Discs>,
) -> Option<(WorldPoint, u16)> {
    // A nudge may not take the disc into a thing (the pushes left `to` clear of them, or no
    // deeper than `from`).
    let allowed = discs.map(|discs| discs.depth(point_bits(from)));
    let sx = if to.x >= from.x { 1 } else { -1 };
    let sy = if to.y >= from.y { 1 } else { -1 };
    let nudges = [
        (sx, sy),
        (sx, 0),
        (0, sy),
        (sx, -sy),
        (-sx, sy),
        (-sx, 0),
        (0, -sy),
        (-sx, -sy),
    ];
    nudges.into_iter().find_map(|(nx, ny)| {
        let nudged = WorldPoint::new(
            Fx24_8::from_bits(to.x.to_bits() + nx),
            Fx24_8::from_bits(to.y.to_bits() + ny),
        );
        if let (Some(discs), Some(allowed)) = (discs, allowed) {
            if discs.depth(point_bits(nudged)) > allowed {
                return None;
            }
        }
        match track(map, sector, from, nudged, body) {
            Track::Inside(sector) => Some((nudged, sector)),
            Track::Blocked | Track::Degenerate => None,
        }
    })
}

/// Follows the centre's straight path from `from`, strictly inside `sector`, to `to`, through
/// the portals it crosses. Exact for `to` within the declared world (as [`slide`]'s are; its
/// 64-bit products take 32-bit differences).
///
/// A convex sector's boundary meets the path at most where it enters and where it leaves, so
/// in each sector the wall it leaves through is the one wall (other than the one it came in
/// by) that the path properly crosses; anything else (touching a vertex, running along a wall,
/// ending on one) is [`Track::Degenerate`].
pub fn track(map: &MapTables, sector: u16, from: WorldPoint, to: WorldPoint, body: &Body) -> Track {
    // Most paths end in the sector they start in (convex: they cross nothing). This test is the
    // first of the walk below, which is out of line.
    if strictly_inside(map, &map.sectors[usize::from(sector)], to) {
        return Track::Inside(sector);
    }
    track_through_portals(map, sector, from, to, body)
}

/// [`track`] of a path that leaves `sector`, which `to` is not strictly inside.
#[inline(never)]
fn track_through_portals(
    map: &MapTables,
    sector: u16,
    from: WorldPoint,
    to: WorldPoint,
    body: &Body,
) -> Track {
    debug_assert!(
        strictly_inside(map, &map.sectors[usize::from(sector)], from),
        "track's path must start strictly inside its sector"
    );
    let start = sector;
    let mut current = sector;
    let mut came_through: Option<usize> = None;
    for hop in 0..=MAX_HOPS {
        let here = &map.sectors[usize::from(current)];
        if hop > 0 && strictly_inside(map, here, to) {
            return Track::Inside(current);
        }
        let mut exit = None;
        let first = usize::from(here.first_wall);
        let walls = map.sector_walls(here);
        let Some(last) = walls.last() else {
            return Track::Degenerate;
        };
        // Each wall starts where the one before it ends: one vertex read per wall.
        let mut a_bits = vertex_bits(map, last.end);
        let (from_bits, to_bits) = (point_bits(from), point_bits(to));
        for (index, wall) in (first..).zip(walls) {
            let b_bits = vertex_bits(map, wall.end);
            let start_bits = a_bits;
            a_bits = b_bits;
            if Some(index) == came_through {
                continue;
            }
            // Both ends strictly on one side of the wall's line: disjoint (a point of the wall
            // on the path would lie on that side too), for two of segment_contact's products.
            // In the first sector `from` is strictly inside (track's precondition): right of
            // every wall, so its side needs no product (any positive value stands for it).
            let from_side = if hop == 0 {
                1
            } else {
                cross_near(start_bits, b_bits, from_bits)
            };
            let to_side = cross_near(start_bits, b_bits, to_bits);
            if (from_side > 0 && to_side > 0) || (from_side < 0 && to_side < 0) {
                continue;
            }
            // segment_contact's four sides, two of them known: with none zero, the path and
            // the wall cross or miss each other; a zero side (touching, collinear) takes
            // segment_contact's whole test.
            let (start_side, end_side) = (
                cross_near(from_bits, to_bits, start_bits),
                cross_near(from_bits, to_bits, b_bits),
            );
            let contact = if from_side != 0 && to_side != 0 && start_side != 0 && end_side != 0 {
                // Nonzero, and the first two not on one side: opposite signs.
                if (start_side > 0) != (end_side > 0) {
                    SegmentContact::Crossing
                } else {
                    SegmentContact::Disjoint
                }
            } else {
                let (a, b) = wall_points(map, wall);
                segment_contact(from, to, a, b)
            };
            match contact {
                SegmentContact::Disjoint => {}
                SegmentContact::Crossing if exit.is_none() => exit = Some(index),
                SegmentContact::Crossing
                | SegmentContact::Touching
                | SegmentContact::Overlapping => return Track::Degenerate,
            }
        }
        let Some(exit) = exit else {
            return Track::Degenerate;
        };
        let wall = &map.walls[exit];
        let Some(next) = wall.neighbour() else {
            return Track::Blocked;
        };
        if wall.flags & WALL_MIDDLE_BLOCKS != 0
            || (next != start && !body.admits_sector(map.slopes, next, point_bits(to)))
        {
            return Track::Blocked;
        }
        let Some(twin) = map.twin(current, exit) else {
            return Track::Degenerate;
        };
        came_through = Some(twin);
        current = next;
    }
    Track::Degenerate
}

/// Whether `p` is strictly inside `sector` (right of every wall). Exact.
pub fn strictly_inside(map: &MapTables, sector: &Sector, p: WorldPoint) -> bool {
    SectorWalls { map, sector }.strictly_inside(p)
}

/// A sector's walls, for the test that pushed steps and portal crossings run over all of them.
struct SectorWalls<'a, 'm> {
    map: &'a MapTables<'m>,
    sector: &'a Sector,
}

impl SectorWalls<'_, '_> {
    /// See [`strictly_inside`]. In IWRAM on the GBA; a method because `link_section` on a free
    /// function counts as unsafe code.
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".iwram.player_strictly_inside")]
    fn strictly_inside(&self, p: WorldPoint) -> bool {
        let (map, sector) = (self.map, self.sector);
        let limit = portalcast_format::limits::WORLD_COORD_MAX.unsigned_abs() * 256;
        let p = point_bits(p);
        // Beyond the world no sector has an inside; within it, cross_near is exact.
        if p.0.unsigned_abs() > limit || p.1.unsigned_abs() > limit {
            return false;
        }
        let walls = map.sector_walls(sector);
        let Some(last) = walls.last() else {
            return true;
        };
        // Each wall starts where the one before it ends: one vertex read per wall.
        let mut a = vertex_bits(map, last.end);
        walls.iter().all(|wall| {
            let b = vertex_bits(map, wall.end);
            let side = cross_near(a, b, p);
            a = b;
            side > 0
        })
    }
}

/// The two ends of a wall, in world coordinates.
pub fn wall_points(map: &MapTables, wall: &Wall) -> (WorldPoint, WorldPoint) {
    let a = map.vertices[usize::from(wall.start)];
    let b = map.vertices[usize::from(wall.end)];
    (
        WorldPoint::from_int(a.x, a.y),
        WorldPoint::from_int(b.x, b.y),
    )
}

fn point_bits(p: WorldPoint) -> Bits {
    (p.x.to_bits(), p.y.to_bits())
}

/// The point at these 24.8 bits, if they are inside the declared world (a push cannot leave it
/// on a valid map, but the tracking below relies on the bounds of its products).
fn point_from_bits((x, y): Bits) -> Option<WorldPoint> {
    let limit = portalcast_format::limits::WORLD_COORD_MAX * 256;
    if x.abs() > limit || y.abs() > limit {
        return None;
    }
    Some(WorldPoint::new(Fx24_8::from_bits(x), Fx24_8::from_bits(y)))
}

/// An axis-aligned box in 24.8 bits.
#[derive(Clone, Copy, Debug)]
struct Bounds {
    min: (i32, i32),
    max: (i32, i32),
}

impl Bounds {
    /// The box around a step from `from` by `step`, grown by `margin` bits.
    fn around(from: WorldPoint, step: Delta, margin: i32) -> Bounds {
        let (x, y) = (from.x.to_bits(), from.y.to_bits());
        let (tx, ty) = (x + step.x, y + step.y);
        Bounds {
            min: (x.min(tx) - margin, y.min(ty) - margin),
            max: (x.max(tx) + margin, y.max(ty) + margin),
        }
    }

    /// Whether the bounding box of segment `a b` meets this box.
    fn meets(&self, (ax, ay): Bits, (bx, by): Bits) -> bool {
        ax.max(bx) >= self.min.0
            && ax.min(bx) <= self.max.0
            && ay.max(by) >= self.min.1
            && ay.min(by) <= self.max.1
    }
}

/// Whether `sector` has things ([`MapTables::things_range`] not empty): one bounds test on a map
/// without things, two reads on a map with some.
#[inline(always)]
fn has_things(map: &MapTables, sector: u16) -> bool {
    let index = usize::from(sector);
    matches!(map.sector_things.get(index..index + 2), Some(&[first, end]) if first != end)
}

/// Blocking segments a step keeps in the list it clears on every step (32 bytes); a step near
/// more takes a slower path with room for [`MAX_SEGMENTS`].
const FEW_SEGMENTS: usize = 8;

/// What fills the room of a segment list before [`Obstacles::near`] writes it.
const NO_SEGMENT: Wall = Wall {
    start: 0,
    end: 0,
    portal: NO_PORTAL,
    texture: NO_TEXTURE,
    upper_texture: NO_TEXTURE,
    lower_texture: NO_TEXTURE,
    x_offset: 0,
    y_offset: 0,
    length_fx8: 0,
    middle: NO_TEXTURE,
    flags: 0,
};

/// The blocking segments near one step, as their walls in a list the caller provides: clearing
/// room for [`MAX_SEGMENTS`] segments on every step cost more than the rest of a step without
/// pushes, and most steps find none.
struct Obstacles<'a, 'm> {
    vertices: &'m [Vertex],
    ends: &'a [&'m Wall],
    /// The sectors the walk reached, the step's own first.
    reached: &'a [u16],
    /// Whether one of them has things.
    things_near: bool,
    /// Whether the step's whole target is strictly inside the step's sector.
    target_inside: bool,
}

impl<'a, 'm> Obstacles<'a, 'm> {
    /// Walks from `sector` through the open portals that meet `bounds` and keeps every
    /// blocking segment of the sectors reached that meets `bounds`, in `ends`: the first
    /// [`MAX_SEGMENTS`] of them. `None` if they do not fit a shorter `ends`. The sectors reached
    /// go in `sectors`, `sector` first. On the way, tests whether `target` is strictly inside
    /// `sector`.
    ///
    /// In IWRAM on the GBA: every step runs it over at least a whole sector's walls.
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".iwram.player_obstacles_near")]
    fn near(
        map: &MapTables<'m>,
        sector: u16,
        bounds: &Bounds,
        body: &Body,
        ends: &'a mut [&'m Wall],
        sectors: &'a mut [u16; MAX_NEARBY_SECTORS],
        target: Bits,
    ) -> Option<Obstacles<'a, 'm>> {
        sectors[0] = sector;
        let mut target_inside = true;
        let mut things_near = false;
        let mut count = 0;
        let mut found = 1;
        let mut next_to_scan = 0;
        while next_to_scan < found {
            let first_sector = next_to_scan == 0;
            let here = sectors[next_to_scan];
            things_near |= has_things(map, here);
            let walls = map.sector_walls(&map.sectors[usize::from(here)]);
            next_to_scan += 1;
            // Each wall starts where the one before it ends (the format's rule), so one vertex
            // read per wall: they are in ROM.
            let Some(last) = walls.last() else {
                continue;
            };
            let mut a = vertex_bits(map, last.end);
            for wall in walls {
                let b = vertex_bits(map, wall.end);
                let (wall_a, wall_b) = (a, b);
                a = b;
                if !bounds.meets(wall_a, wall_b) {
                    continue;
                }
                if first_sector {
                    // strictly_inside(sector, target) (target is a step from a point of the
                    // world: cross_near is exact), on the walls near the step alone: the step
                    // starts strictly inside the convex sector, so if it ends outside, it leaves
                    // through a wall it meets, whose box meets the bounds, and ends on or beyond
                    // that wall's line.
                    target_inside &= cross_near(wall_a, wall_b, target) > 0;
                }
                match wall.neighbour() {
                    // A portal whose middle blocks is a wall to the body.
                    Some(next)
                        if wall.flags & WALL_MIDDLE_BLOCKS == 0
                            && (next == sector || body.admits_sector(map.slopes, next, target)) =>
                    {
                        if !sectors[..found].contains(&next) && found < MAX_NEARBY_SECTORS {
                            sectors[found] = next;
                            found += 1;
                        }
                    }
                    _ => {
                        if count < ends.len().min(MAX_SEGMENTS) {
                            ends[count] = wall;
                            count += 1;
                        } else if ends.len() < MAX_SEGMENTS {
                            return None;
                        }
                    }
                }
            }
        }
        Some(Obstacles {
            vertices: map.vertices,
            ends: &ends[..count],
            reached: &sectors[..found],
            things_near,
            target_inside,
        })
    }

    /// Whether a sector the walk reached, or one behind a blocking portal it kept, has things.
    /// The walk notes the first (in IWRAM, a bounds test per sector on a map without things,
    /// two reads on one with some); the second, in ROM, only matters for steps against walls
    /// on maps with things.
    #[inline(always)]
    fn things_near(&self, map: &MapTables) -> bool {
        self.things_near
            || (!self.ends.is_empty()
                && !map.sector_things.is_empty()
                && self.things_behind_blocking_portals(map))
    }

    /// The second part of [`Obstacles::things_near`]. Out of line.
    #[inline(never)]
    fn things_behind_blocking_portals(&self, map: &MapTables) -> bool {
        self.ends.iter().any(|wall| {
            wall.neighbour()
                .is_some_and(|behind| has_things(map, behind))
        })
    }

    /// The segments: their ends in 24.8 bits, and their walls' lengths.
    fn segments(&self) -> impl Iterator<Item = Segment> + '_ {
        let bits = |index: u16| {
            let vertex = self.vertices[usize::from(index)];
            (vertex.x * 256, vertex.y * 256)
        };
        self.ends.iter().map(move |wall| Segment {
            a: bits(wall.start),
            b: bits(wall.end),
            length_fx8: wall.length_fx8,
        })
    }

    /// `p` pushed out of the segments and `discs`: a few passes, edges before vertices before
    /// discs in each. And whether the last pass pushed nothing (the pushes settled before the
    /// passes ran out; then `p` is clear of every disc, exactly).
    #[inline]
    fn push_out(&self, p: Bits, discs: Option<&Discs>) -> (Bits, bool) {
        if let Some(discs) = discs {
            return self.push_out_among_discs(p, discs);
        }
        if self.ends.is_empty() {
            return (p, true);
        }
        self.push_out_of_some(p)
    }

    /// [`Obstacles::push_out`] with at least one segment and no disc. Out of line: most steps
    /// have none. In IWRAM on the GBA: the steps that slide along walls, corners above all,
    /// run it over every segment a few times, and from the cartridge it made them the slowest
    /// ticks.
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".iwram.player_push_out")]
    fn push_out_of_some(&self, p: Bits) -> (Bits, bool) {
        self.push_passes(p, None)
    }

    /// [`Obstacles::push_out`] with solid things near. In ROM: only steps near one take it.
    #[inline(never)]
    fn push_out_among_discs(&self, p: Bits, discs: &Discs) -> (Bits, bool) {
        self.push_passes(p, Some(discs))
    }

    /// The passes of [`Obstacles::push_out`]. Always inlined, so that the segments' copy has
    /// no code for discs. At most [`PUSH_PASSES`] passes over finite lists (the segments, and
    /// the discs: at most [`FEW_DISCS`], or the solid things of at most
    /// `MAX_NEARBY_SECTORS + MAX_SEGMENTS` sectors): it ends.
    #[inline(always)]
    fn push_passes(&self, mut p: Bits, discs: Option<&Discs>) -> (Bits, bool) {
        for _ in 0..PUSH_PASSES {
            let mut moved = false;
            for contact in [Contact::Edge, Contact::Vertex] {
                for segment in self.segments() {
                    if let Some(push) = push_from_segment(p, &segment, contact) {
                        p = (p.0 + push.0, p.1 + push.1);
                        moved = true;
                    }
                }
            }
            if let Some(discs) = discs {
                for disc in discs.iter() {
                    if let Some(push) = disc.push(p) {
                        p = (p.0 + push.0, p.1 + push.1);
                        moved = true;
                    }
                }
            }
            if !moved {
                return (p, true);
            }
        }
        (p, false)
    }

    /// Whether `to`'s disc is deeper than `from`'s in some segment, beyond
    /// [`OVERLAP_TOLERANCE`]: a segment would push it out further than that and further than it
    /// pushes `from`. Segment by segment: a disc deep in one blocking segment (a portal whose
    /// heights stopped admitting it as it flew up) may move out of it, but not into another
    /// (measured by the soak: pushed 18 units out of a portal, a disc ended 0.14 unit inside
    /// the solid wall beside it, which the deepest overlap alone allowed). Depth is the push's
    /// squared length, not its larger axis: a vertex pushes along a diagonal, and a step that
    /// traded an edge's push for a vertex's longer one, with a shorter larger axis, went deeper
    /// (a disc sliding past a wall's end into a portal). Out of line: only a step whose pushes
    /// did not settle asks.
    #[inline(never)]
    fn deepens_some(&self, from: Bits, to: Bits) -> bool {
        let depth = |p: Bits, segment: &Segment| {
            [Contact::Edge, Contact::Vertex]
                .into_iter()
                .filter_map(|contact| push_from_segment(p, segment, contact))
                .map(|(x, y)| wide(x) * wide(x) + wide(y) * wide(y))
                .max()
                .unwrap_or(0)
        };
        self.segments().any(|segment| {
            let after = depth(to, &segment);
            after > OVERLAP_TOLERANCE * OVERLAP_TOLERANCE && after > depth(from, &segment)
        })
    }
}

/// Solid things a step keeps in its list of [`Discs`]; when more are near one step (a cluster
/// of small ones), every pass reads them all from the map's tables instead.
const FEW_DISCS: usize = 8;

/// Where the solid things near one step are: the things of the sectors its walk reached and
/// of the sectors behind the blocking portals it kept, those solid whose discs meet the step's
/// box.
#[derive(Clone, Copy)]
struct NearbyThings<'a, 'm> {
    map: &'a MapTables<'m>,
    reached: &'a [u16],
    ends: &'a [&'m Wall],
    bounds: Bounds,
}

impl<'a, 'm> NearbyThings<'a, 'm> {
    /// Their discs, read from the map's tables. A sector behind two blocking portals gives its
    /// things twice (a second push from the same disc finds nothing to do).
    fn discs(self) -> impl Iterator<Item = Disc> + 'a {
        let NearbyThings {
            map,
            reached,
            ends,
            bounds,
        } = self;
        let behind = ends.iter().filter_map(|wall| wall.neighbour());
        reached
            .iter()
            .copied()
            .chain(behind)
            .flat_map(move |sector| {
                let things = map.things_in(sector).iter();
                things.take_while(|thing| thing.flags & THING_SOLID != 0)
            })
            .filter_map(move |thing| Disc::solid_near(thing, &bounds))
    }
}

/// The discs of the solid things near one step ([`NearbyThings`]), in a short list, or, when
/// they do not fit it, read from the map on each pass: the same discs in the same order either
/// way.
#[derive(Clone, Copy)]
struct Discs<'a, 'm> {
    few: [Disc; FEW_DISCS],
    count: usize,
    /// Set when there are more than [`FEW_DISCS`].
    many: Option<NearbyThings<'a, 'm>>,
}

impl<'a, 'm> Discs<'a, 'm> {
    /// The solid things near the step `obstacles` were found for, within `bounds`, if there
    /// is any. Out of line and in ROM: only a step near things runs it
    /// ([`Obstacles::things_near`]).
    #[inline(never)]
    fn near(
        map: &'a MapTables<'m>,
        obstacles: &Obstacles<'a, 'm>,
        bounds: Bounds,
    ) -> Option<Discs<'a, 'm>> {
        // Whether there is any, in plain loops: most steps near things find none solid.
        // A sector's solid things come first in the map's table.
        let solid_near = |sector: u16| {
            map.things_in(sector)
                .iter()
                .take_while(|thing| thing.flags & THING_SOLID != 0)
                .any(|thing| Disc::solid_near(thing, &bounds).is_some())
        };
        let behind = obstacles.ends.iter().filter_map(|wall| wall.neighbour());
        let any = obstacles.reached.iter().any(|&sector| solid_near(sector))
            || behind.into_iter().any(solid_near);
        if !any {
            return None;
        }
        Some(Discs::list(NearbyThings {
            map,
            reached: obstacles.reached,
            ends: obstacles.ends,
            bounds,
        }))
    }

    /// The discs of `things`, in the list if they fit.
    #[inline(never)]
    fn list(things: NearbyThings<'a, 'm>) -> Discs<'a, 'm> {
        let unused = Disc {
            centre: (0, 0),
            reach: 0,
        };
        let mut discs = Discs {
            few: [unused; FEW_DISCS],
            count: 0,
            many: None,
        };
        for disc in things.discs() {
            if discs.count == FEW_DISCS {
                discs.many = Some(things);
                break;
            }
            discs.few[discs.count] = disc;
            discs.count += 1;
        }
        discs
    }

    /// The discs.
    fn iter(&self) -> impl Iterator<Item = Disc> + '_ {
        let few = if self.many.is_some() {
            &[][..]
        } else {
            &self.few[..self.count]
        };
        few.iter()
            .copied()
            .chain(self.many.into_iter().flat_map(NearbyThings::discs))
    }

    /// How deep `p` is in the discs: the largest `reach² − distance²` in bits², 0 if it
    /// overlaps none. Exact.
    fn depth(&self, p: Bits) -> i64 {
        self.iter().map(|disc| disc.depth(p)).fold(0, i64::max)
    }
}

/// A solid thing's disc, grown by the body's radius: the body overlaps the thing when its centre
/// is nearer `centre` than `reach`.
#[derive(Clone, Copy)]
struct Disc {
    /// The thing's position, 24.8 bits.
    centre: Bits,
    /// [`RADIUS`] plus the thing's radius, in 24.8 bits (under 2^22: the thing's disc lies in
    /// the world).
    reach: i32,
}

impl Disc {
    /// `thing`'s disc, if it is solid and its footprint meets `bounds`.
    fn solid_near(thing: &Thing, bounds: &Bounds) -> Option<Disc> {
        if thing.flags & THING_SOLID == 0 {
            return None;
        }
        let (centre, radius) = ((thing.x_fx8, thing.y_fx8), i32::from(thing.radius) * 256);
        let corners = (
            (centre.0 - radius, centre.1 - radius),
            (centre.0 + radius, centre.1 + radius),
        );
        bounds.meets(corners.0, corners.1).then_some(Disc {
            centre,
            reach: RADIUS_BITS + radius,
        })
    }

    /// `reach² − distance²` from `p` (positive when the body at `p` overlaps the thing), at
    /// least 0. Exact: `p` within 2^23 bits, the centre within 2^21.
    fn depth(&self, p: Bits) -> i64 {
        let (ex, ey) = (
            wide(p.0) - wide(self.centre.0),
            wide(p.1) - wide(self.centre.1),
        );
        (wide(self.reach) * wide(self.reach) - (ex * ex + ey * ey)).max(0)
    }

    /// The push that moves `p` to [`Disc::reach`] from the centre, radially, if it is nearer:
    /// [`push_from_point`] with the larger radius, in 64 bits. Its root rounded down and its
    /// quotients away from the centre, each coordinate of the result is at least its share of
    /// the reach: the result is exactly clear of the disc. Beyond it by less than
    /// `reach / distance + 2` bits (the root is short by less than one): a few bits for a
    /// step that meets the disc, √2 times the reach at worst (a root of 1 for √2). At the
    /// centre itself, along +x.
    fn push(&self, p: Bits) -> Option<Bits> {
        let reach = self.reach;
        let (ex, ey) = (p.0 - self.centre.0, p.1 - self.centre.1);
        // Outside the square round the disc: no product.
        if ex.unsigned_abs() >= reach.unsigned_abs() || ey.unsigned_abs() >= reach.unsigned_abs() {
            return None;
        }
        // Below the reach (2^22) on each axis: squares under 2^45.
        let distance_squared = wide(ex) * wide(ex) + wide(ey) * wide(ey);
        if distance_squared >= wide(reach) * wide(reach) {
            return None;
        }
        if distance_squared == 0 {
            return Some((reach, 0));
        }
        let distance = isqrt_floor(distance_squared as u64) as i64;
        let gap = wide(reach) - distance;
        // distance ≥ 1, under 2^22: a 32-bit divisor.
        Some((
            div_away_from_zero_by_u32(wide(ex) * gap, distance as u32) as i32,
            div_away_from_zero_by_u32(wide(ey) * gap, distance as u32) as i32,
        ))
    }
}

/// A blocking segment: a wall's ends in 24.8 bits, `a` to `b` (its front on the right, where
/// its sector is), and the wall's [`Wall::length_fx8`].
#[derive(Clone, Copy)]
struct Segment {
    a: Bits,
    b: Bits,
    length_fx8: i32,
}

/// Which part of a segment a push comes from.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Contact {
    /// The inside of the segment, along its normal.
    Edge,
    /// An end point, radially.
    Vertex,
}

/// The push (24.8 bits) that moves `p` to [`RADIUS`] from `segment`, if the disc overlaps
/// the part of the segment `contact` names; rounded away from the segment.
fn push_from_segment(p: Bits, segment: &Segment, contact: Contact) -> Option<Bits> {
    let Segment { a, b, length_fx8 } = *segment;
    // Most segments near a step are farther than the radius from every part of it: a box
    // test rejects them before any product.
    let beyond = |p: i32, a: i32, b: i32| p < a.min(b) - RADIUS_BITS || p > a.max(b) + RADIUS_BITS;
    if beyond(p.0, a.0, b.0) || beyond(p.1, a.1, b.1) {
        return None;
    }
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (px, py) = (p.0 - a.0, p.1 - a.1);
    let along = wide(px) * wide(dx) + wide(py) * wide(dy);
    let length_squared = wide(dx) * wide(dx) + wide(dy) * wide(dy);
    if along <= 0 || along >= length_squared {
        if contact != Contact::Vertex {
            return None;
        }
        let end = if along <= 0 { a } else { b };
        return push_from_point(p, end);
    }
    if contact != Contact::Edge {
        return None;
    }
    // Twice the signed area: the distance to the line times the length; positive in front.
    let area = wide(dx) * wide(py) - wide(dy) * wide(px);
    if area <= 0 {
        return None;
    }
    // The disc reaches the segment if `area < RADIUS_BITS · ceil(√length_squared)`, that is
    // (the right side being a multiple of RADIUS_BITS) if `area / RADIUS_BITS`, rounded down,
    // is below `ceil(√length_squared)`, or its square below `length_squared`: the same test
    // without the square root, which only a push needs. A quotient of 2^23 or more squares
    // past any length_squared of the declared world (under 2^45), and could overflow.
    let quotient = area / wide(RADIUS_BITS);
    if quotient >= 1 << 23 || quotient * quotient >= length_squared {
        return None;
    }
    // The push below, for a wall along an axis, where the length is |dx| (or |dy|) and the
    // divisions are exact: with dy = 0 the area is dx·py, the depth |dx|·(RADIUS_BITS −
    // sign(dx)·py), and the push (0, dx·depth / dx²). Most walls are; no division, no root.
    if dy == 0 {
        return Some((0, dx.signum() * RADIUS_BITS - py));
    }
    if dx == 0 {
        return Some((-dy.signum() * RADIUS_BITS - px, 0));
    }
    // The segment's ends are whole units, so dx and dy are multiples of 256 and the squared
    // length 65536 times the squared length in units, which fits 32 bits (2^29 at most).
    let (units_x, units_y) = (dx >> 8, dy >> 8);
    let units_squared = (units_x * units_x + units_y * units_y) as u32;
    debug_assert!(wide(units_squared as i32) << 16 == length_squared);
    let length = ceil_length(length_fx8, units_squared);
    let reach = wide(RADIUS_BITS) * length;
    // Along the normal (-dy, dx)/length by (reach - area)/length: the area grows by exactly
    // reach - area, to the radius (times the rounded-up length).
    let depth = reach - area;
    // The depth is a multiple of 256 too (RADIUS_BITS and the area are), so each quotient
    // `−dy·depth / length_squared` is `−units_y·(depth/256) / units_squared`: the same
    // quotient and remainder over 65536, with a 32-bit divisor.
    debug_assert!(depth % 256 == 0);
    let depth_units = depth >> 8;
    Some((
        div_away_from_zero_by_u32(-wide(units_y) * depth_units, units_squared) as i32,
        div_away_from_zero_by_u32(wide(units_x) * depth_units, units_squared) as i32,
    ))
}

/// `ceil(√(65536·m))`, the length in 24.8 bits rounded up of a wall whose squared length is
/// `m` square units, from the map compiler's `floor_fx8` (`floor(√(65536·m))`, its
/// [`Wall::length_fx8`]): one more unless the root is exact. No square root per push.
fn ceil_length(floor_fx8: i32, m: u32) -> i64 {
    let floor = i64::from(floor_fx8);
    let scaled = i64::from(m) << 16;
    debug_assert!(
        floor * floor <= scaled && (floor + 1) * (floor + 1) > scaled,
        "the wall's length_fx8 {floor_fx8} is not the floor of the root of {m}·65536"
    );
    floor + i64::from(floor * floor != scaled)
}

/// `n / d` rounded away from zero, for `0 < d < 2^31`.
fn div_away_from_zero_by_u32(n: i64, d: u32) -> i64 {
    let (quotient, remainder) = divide_by_u32(n.unsigned_abs(), d);
    let magnitude = (quotient + u64::from(remainder != 0)) as i64;
    if n >= 0 {
        magnitude
    } else {
        -magnitude
    }
}

/// `(n / d, n % d)` for `0 < d < 2^31`: shift and subtract over the quotient's bits, with the
/// remainder (under 2·d) in one 32-bit word while the quotient has at most 32 bits; else
/// [`divide`].
fn divide_by_u32(n: u64, d: u32) -> (u64, u32) {
    debug_assert!(d != 0 && d < 1 << 31);
    if n < u64::from(d) {
        return (0, n as u32);
    }
    // At most this many quotient bits: n shifted down by it is below d.
    let bits = leading_zeros(u64::from(d)) - leading_zeros(n) + 1;
    if bits > 32 {
        let (quotient, remainder) = divide(n, u64::from(d));
        return (quotient, remainder as u32);
    }
    let mut remainder = (n >> bits) as u32;
    let low = n as u32;
    let mut quotient = 0u32;
    for index in (0..bits).rev() {
        remainder = (remainder << 1) | ((low >> index) & 1);
        quotient <<= 1;
        if remainder >= d {
            remainder -= d;
            quotient |= 1;
        }
    }
    (u64::from(quotient), remainder)
}

/// The push that moves `p` to [`RADIUS`] from `end`, radially, if it is closer.
fn push_from_point(p: Bits, end: Bits) -> Option<Bits> {
    let (ex, ey) = (p.0 - end.0, p.1 - end.1);
    let distance_squared = wide(ex) * wide(ex) + wide(ey) * wide(ey);
    // At the point itself there is no direction; the centre is never at a map vertex anyway
    // (vertices lie on sector boundaries, the centre strictly inside).
    if distance_squared == 0 || distance_squared >= wide(RADIUS_BITS) * wide(RADIUS_BITS) {
        return None;
    }
    // Closer than the radius: ex, ey, the distance and the gap are below 2^12, so the products
    // below 2^24 and 32-bit words hold everything.
    let distance = isqrt_floor_u32(distance_squared as u32) as i32;
    let gap = RADIUS_BITS - distance;
    Some((
        div_away_from_zero_u32(ex * gap, distance),
        div_away_from_zero_u32(ey * gap, distance),
    ))
}

/// [`div_away_from_zero_by_u32`] on 32-bit words.
fn div_away_from_zero_u32(n: i32, d: i32) -> i32 {
    let (quotient, remainder) = divide_u32(n.unsigned_abs(), d as u32);
    let magnitude = (quotient + u32::from(remainder != 0)) as i32;
    if n >= 0 {
        magnitude
    } else {
        -magnitude
    }
}

/// `(n / d, n % d)` for `d > 0`, by shift and subtract over the quotient's bits alone. A push's
/// quotient is at most about the radius in bits (13 bits), so this takes a few steps, where the
/// library's 64-bit division is generic Thumb code in ROM.
fn divide(n: u64, d: u64) -> (u64, u64) {
    if n < d {
        return (0, n);
    }
    // d shifted up to n's top bit: at most n's bit length minus d's quotient bits.
    let shift = leading_zeros(d) - leading_zeros(n);
    let mut divisor = d << shift;
    let (mut quotient, mut remainder) = (0, n);
    for _ in 0..=shift {
        quotient <<= 1;
        if remainder >= divisor {
            remainder -= divisor;
            quotient |= 1;
        }
        divisor >>= 1;
    }
    (quotient, remainder)
}

/// [`divide`] on 32-bit words.
fn divide_u32(n: u32, d: u32) -> (u32, u32) {
    if n < d {
        return (0, n);
    }
    let shift = leading_zeros(u64::from(d)) - leading_zeros(u64::from(n));
    let mut divisor = d << shift;
    let (mut quotient, mut remainder) = (0, n);
    for _ in 0..=shift {
        quotient <<= 1;
        if remainder >= divisor {
            remainder -= divisor;
            quotient |= 1;
        }
        divisor >>= 1;
    }
    (quotient, remainder)
}

/// `floor(sqrt(n))`, bit by bit (no division, no float).
pub fn isqrt_floor(n: u64) -> u64 {
    if let Ok(small) = u32::try_from(n) {
        // A vertex push's distance is under the radius (n < 2^24): 32-bit steps.
        return u64::from(isqrt_floor_u32(small));
    }
    let mut remainder = n;
    let mut root = 0u64;
    // The highest power of 4 at most n: where the loop of halvings from 4^31 would stop.
    let mut bit = 1u64 << ((63 - leading_zeros(n)) & !1);
    while bit != 0 {
        if remainder >= root + bit {
            remainder -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    root
}

/// [`isqrt_floor`] of a 32-bit `n`: the same steps on 32-bit words.
fn isqrt_floor_u32(n: u32) -> u32 {
    if n == 0 {
        return 0;
    }
    let mut remainder = n;
    let mut root = 0u32;
    let mut bit = 1u32 << ((63 - leading_zeros(u64::from(n))) & !1);
    while bit != 0 {
        if remainder >= root + bit {
            remainder -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    root
}

/// `ceil(sqrt(n))`.
pub fn isqrt_ceil(n: u64) -> u64 {
    let root = isqrt_floor(n);
    if root * root == n {
        root
    } else {
        root + 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_roots_round_as_named() {
        for n in [
            0u64,
            1,
            2,
            3,
            4,
            15,
            16,
            17,
            1 << 40,
            (1 << 46) - 1,
            u64::MAX >> 2,
            u64::from(u32::MAX),
            1 << 32,
            (1 << 24) - 1,
        ] {
            let floor = isqrt_floor(n);
            assert!(floor * floor <= n && (floor + 1) * (floor + 1) > n, "{n}");
            let ceil = isqrt_ceil(n);
            assert!(
                ceil * ceil >= n && (ceil == 0 || (ceil - 1) * (ceil - 1) < n),
                "{n}"
            );
        }
    }

    use portalcast_assets::wall_length_fx8;
    use portalcast_format::{PlayerSize, PlayerStart};

    /// A square room from −30 to 30 units on each axis, clockwise (y down), each side split
    /// into `pieces` collinear solid walls.
    fn square_room(pieces: i32) -> (Vec<Vertex>, Vec<Wall>, Vec<Sector>) {
        let corners = [(-30, -30), (30, -30), (30, 30), (-30, 30)];
        let mut vertices = Vec::new();
        for side in 0..4 {
            let (ax, ay) = corners[side];
            let (bx, by) = corners[(side + 1) % 4];
            for piece in 0..pieces {
                vertices.push(Vertex {
                    x: ax + (bx - ax) * piece / pieces,
                    y: ay + (by - ay) * piece / pieces,
                });
            }
        }
        let count = vertices.len() as u16;
        let walls = (0..count)
            .map(|index| Wall {
                start: index,
                end: (index + 1) % count,
                portal: NO_PORTAL,
                texture: 0,
                upper_texture: NO_TEXTURE,
                lower_texture: NO_TEXTURE,
                x_offset: 0,
                y_offset: 0,
                length_fx8: wall_length_fx8(
                    vertices[usize::from(index)],
                    vertices[usize::from((index + 1) % count)],
                ),
                middle: NO_TEXTURE,
                flags: 0,
            })
            .collect();
        let sectors = vec![Sector {
            first_wall: 0,
            wall_count: count,
            floor_z: 0,
            ceil_z: 128,
            floor_texture: 0,
            ceil_texture: 0,
            light: 255,
            links: 0,
            slope: portalcast_format::NO_SLOPE,
        }];
        (vertices, walls, sectors)
    }

    fn room_map<'a>(
        vertices: &'a [Vertex],
        walls: &'a [Wall],
        sectors: &'a [Sector],
    ) -> MapTables<'a> {
        MapTables {
            name: "room",
            vertices,
            walls,
            sectors,
            player_start: PlayerStart {
                x_fx8: 0,
                y_fx8: 0,
                angle: 0,
                sector: 0,
                size: PlayerSize::NATIVE,
            },
            things: &[],
            sector_things: &[],
            movers: &[],
            triggers: &[],
            lights: &[],
            wall_twins: &[],
            slopes: &[],
            layer_links: &[],
        }
    }

    /// Standing on the floor of the test rooms (every sector at heights 0..128).
    fn standing(sectors: &[Sector]) -> Body<'_> {
        Body {
            feet: Fx24_8::ZERO,
            eye_height: Fx24_8::from_int(32),
            size: PlayerSize::NATIVE,
            sectors,
        }
    }

    #[test]
    fn more_segments_than_the_short_list_holds_take_the_long_one() {
        let (vertices, walls, sectors) = square_room(4);
        let map = room_map(&vertices, &walls, &sectors);
        // From the middle, every one of the 16 walls is within the step's box.
        let bounds = Bounds::around(
            WorldPoint::from_int(0, 0),
            Delta::default(),
            2 * RADIUS_BITS + 256,
        );
        let mut few = [&NO_SEGMENT; FEW_SEGMENTS];
        let mut reached = [0; MAX_NEARBY_SECTORS];
        let near = Obstacles::near(
            &map,
            0,
            &bounds,
            &standing(map.sectors),
            &mut few,
            &mut reached,
            (0, 0),
        );
        assert!(near.is_none());
        let mut many = [&NO_SEGMENT; MAX_SEGMENTS];
        let mut reached = [0; MAX_NEARBY_SECTORS];
        let obstacles = Obstacles::near(
            &map,
            0,
            &bounds,
            &standing(map.sectors),
            &mut many,
            &mut reached,
            (0, 0),
        )
        .expect("room for every segment");
        let in_wall_order: Vec<&Wall> = walls.iter().collect();
        assert_eq!(obstacles.ends, &in_wall_order[..]);
        assert!(obstacles.target_inside);
        // A step toward the east wall (split at y = 0, in front of the disc) stops the disc at
        // the radius from it, through the long list.
        let (to, sector) = standing(map.sectors).slide_step(
            &map,
            0,
            WorldPoint::from_int(12, 0),
            Delta { x: 8 * 256, y: 0 },
        );
        assert_eq!((to, sector), (WorldPoint::from_int(30 - RADIUS, 0), 0));
    }

    #[test]
    fn the_short_and_the_long_list_move_alike() {
        // Four walls: the short list holds them; the long path must give the same moves.
        let (vertices, walls, sectors) = square_room(1);
        let map = room_map(&vertices, &walls, &sectors);
        let mut seed = 0x853c_49e6_748f_ea9bu64;
        let mut next = |range: i32| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 33) as i32 % (2 * range + 1) - range
        };
        let mut pushed = 0;
        for _ in 0..4_000 {
            let from = WorldPoint::new(
                Fx24_8::from_bits(next(29 * 256)),
                Fx24_8::from_bits(next(29 * 256)),
            );
            let step = Delta {
                x: next(MAX_STEP_BITS),
                y: next(MAX_STEP_BITS),
            };
            let bounds = Bounds::around(from, step, 2 * RADIUS_BITS + 256);
            let target = (from.x.to_bits() + step.x, from.y.to_bits() + step.y);
            let short = standing(map.sectors).slide_step(&map, 0, from, step);
            let long =
                slide_step_among_many(&map, 0, from, step, &standing(map.sectors), &bounds, target);
            assert_eq!(short, long, "from {from:?} by {step:?}");
            pushed += usize::from(short.0 != point_from_bits(target).expect("in the world"));
        }
        // The walls were reached, not only the free middle.
        assert!(pushed > 100, "only {pushed} moves were changed by a wall");
    }

    #[test]
    fn the_length_rounded_up_is_the_ceiling_of_the_square_root() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let check = |m: u32| {
            let n = u64::from(m) << 16;
            // What the map compiler stores: the same rule as its walls' (a wall from the origin
            // with m = dx² + dy² has the same length as any other of that squared length).
            let floor_fx8 = n.isqrt() as i32;
            assert_eq!(ceil_length(floor_fx8, m) as u64, isqrt_ceil(n), "m = {m}");
        };
        for m in [
            0,
            1,
            2,
            3,
            4,
            255,
            256,
            65_535,
            65_536,
            (1 << 29) - 1,
            1 << 29,
        ] {
            check(m);
        }
        for _ in 0..20_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            check((seed >> 35) as u32 >> (seed % 29));
        }
    }

    #[test]
    fn the_shift_and_subtract_division_rounds_as_the_library_s() {
        // The rounding the pushes used with the library's division, against the shift and
        // subtract divisions that replace it.
        let reference = |n: i64, d: i64| {
            if n >= 0 {
                (n + d - 1) / d
            } else {
                -((-n + d - 1) / d)
            }
        };
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..20_000 {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            // Numerators and divisors of every size up to the pushes' (2^58 and 2^46).
            let n = (seed >> 6) as i64 >> (seed % 58);
            let d = (((seed >> 20) % (1 << 46)) >> (seed % 46)).max(1) as i64;
            let (unsigned_n, unsigned_d) = (n.unsigned_abs(), d as u64);
            assert_eq!(
                divide(unsigned_n, unsigned_d),
                (unsigned_n / unsigned_d, unsigned_n % unsigned_d),
                "{n} / {d}"
            );
            // The edge pushes' form, by a divisor under 2^31 (quotients over 32 bits included);
            // with an exact multiple, which has no remainder to round.
            let divisor = (d % (1 << 31)).max(1) as u32;
            for n in [n, -n, n % (1 << 16) * i64::from(divisor)] {
                assert_eq!(
                    div_away_from_zero_by_u32(n, divisor),
                    reference(n, i64::from(divisor)),
                    "{n} / {divisor}"
                );
            }
            // The vertex pushes' 32-bit form, over their operands' range (below 2^24 / 2^12).
            let (small_n, small_d) = ((n % (1 << 24)) as i32, (d % (1 << 12)).max(1) as i32);
            for small_n in [small_n, -small_n] {
                assert_eq!(
                    i64::from(div_away_from_zero_u32(small_n, small_d)),
                    reference(i64::from(small_n), i64::from(small_d)),
                    "{small_n} / {small_d}"
                );
            }
        }
        assert_eq!(divide(0, 7), (0, 0));
        assert_eq!(divide(u64::MAX, 1), (u64::MAX, 0));
        assert_eq!(divide(u64::MAX, u64::MAX), (1, 0));
    }

    #[test]
    fn an_edge_push_lands_exactly_on_the_radius_of_a_straight_wall() {
        // Wall along +x at y = 0, front (inside) toward +y; the disc 10 units in front.
        let wall = Segment {
            a: (0, 0),
            b: (256 * 256, 0),
            length_fx8: 256 * 256,
        };
        let p = (100 * 256, 10 * 256);
        let push = push_from_segment(p, &wall, Contact::Edge).expect("overlaps");
        assert_eq!(push, (0, 6 * 256));
        // From behind, the wall does not push.
        assert_eq!(push_from_segment((p.0, -p.1), &wall, Contact::Edge), None);
    }

    #[test]
    fn a_disc_push_lands_exactly_clear_and_just_beyond_the_reach() {
        let mut seed = 0x2d35_8dcc_aa6c_78a5u64;
        let mut next = |bound: u64| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) % bound
        };
        let mut pushed = 0;
        for _ in 0..50_000 {
            // Reaches from the body's radius to a thing as wide as the world, most of them small.
            let radius = (next(8192 * 256 + 1) >> next(14)) as i32;
            let reach = RADIUS_BITS + radius;
            let limit = 8192 * 256 - radius;
            let centre = (
                next(2 * limit as u64 + 1) as i32 - limit,
                next(2 * limit as u64 + 1) as i32 - limit,
            );
            let disc = Disc { centre, reach };
            let spread = (reach as u64 + 2) >> next(12);
            let offset = |value: u64| value as i32 - spread as i32;
            let p = (
                centre.0 + offset(next(2 * spread + 1)),
                centre.1 + offset(next(2 * spread + 1)),
            );
            let Some(push) = disc.push(p) else {
                assert_eq!(disc.depth(p), 0, "{p:?} from {centre:?}, reach {reach}");
                continue;
            };
            pushed += 1;
            assert!(disc.depth(p) > 0);
            let q = (p.0 + push.0, p.1 + push.1);
            assert_eq!(
                disc.depth(q),
                0,
                "{p:?} to {q:?} from {centre:?}, reach {reach}"
            );
            let length = |(x, y): Bits| {
                let (x, y) = (f64::from(x - centre.0), f64::from(y - centre.1));
                (x * x + y * y).sqrt()
            };
            if p != centre {
                let before = length(p).floor();
                assert!(
                    length(q) < f64::from(reach) * (1.0 + 1.0 / before) + 2.0,
                    "{p:?} to {q:?} from {centre:?}, reach {reach}"
                );
            }
        }
        assert!(pushed > 10_000, "only {pushed} points were in the discs");
        let disc = Disc {
            centre: (5 * 256, -7 * 256),
            reach: 24 * 256,
        };
        assert_eq!(disc.push(disc.centre), Some((24 * 256, 0)));
        // Straight along an axis, exactly to the reach.
        assert_eq!(disc.push((5 * 256, -256)), Some((0, 18 * 256)));
        assert_eq!(disc.push((5 * 256, 17 * 256)), None);
    }

    #[test]
    fn a_vertex_push_is_radial() {
        let push = push_from_point((3 * 256, 4 * 256), (0, 0)).expect("overlaps");
        // Distance 5 to 16: the point moves from (3, 4) to (9.6, 12.8), rounded outward.
        assert_eq!(push, (1690, 2253));
    }
}
