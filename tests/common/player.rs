//! Shared pieces of the player tests: sector names, driving the player, and the invariants every
//! tick must keep, checked with exact geometry independent of the player's own code.

use portalcast::math::{
    point_in_convex_polygon, segment_contact, Angle, Containment, Fx24_8, SegmentContact,
    WorldPoint,
};
use portalcast::player::collide::{Body, RADIUS};
use portalcast::player::input::Intent;
use portalcast::player::vertical::CROUCH_EYE;
use portalcast::player::Player;
use portalcast_format::{MapTables, THING_SOLID};

/// Index of the sector called `name` in a shipped text map (sectors keep file order).
pub fn sector_index(map_file: &str, name: &str) -> u16 {
    let path = portalcast_xtask::workspace_root()
        .join("assets")
        .join("maps")
        .join(map_file);
    let text = std::fs::read_to_string(&path).expect("a shipped map");
    sector_index_in(&text, name)
}

/// Index of the sector called `name` in map text.
pub fn sector_index_in(text: &str, name: &str) -> u16 {
    text.lines()
        .filter_map(|line| line.trim().strip_prefix("sector "))
        .position(|rest| rest.split_whitespace().next() == Some(name))
        .unwrap_or_else(|| panic!("no sector {name}")) as u16
}

/// A compiled map's tables, from map text (the shipped texture and sprite names; a torch is
/// 16 wide and 48 tall, so a thing's default radius is 8 and the compiler checks footprints).
pub fn compile_map(file_name: &str, text: &str) -> portalcast_assets::CompiledMap {
    let catalog = portalcast_assets::Catalog::new(
        [
            "brick", "ceiling", "dirt", "grass", "marble", "metal", "step", "stone", "tiles",
            "trim", "water", "wood",
        ],
        ["grate", "torch"],
        true,
    )
    .with_sprite_size("torch", 16, 48)
    .with_sprite_size("grate", 32, 64);
    portalcast_assets::compile_map_str(file_name, text, &catalog)
        .unwrap_or_else(|errors| panic!("{errors}"))
}

/// An intent with these parts, the rest idle.
pub fn walk(forward: i8, strafe: i8, turn: i8) -> Intent {
    Intent {
        forward,
        strafe,
        turn,
        ..Intent::default()
    }
}

/// World units as f64, from 24.8 bits.
pub fn units(bits: i32) -> f64 {
    f64::from(bits) / 256.0
}

fn point_f64(p: WorldPoint) -> (f64, f64) {
    (units(p.x.to_bits()), units(p.y.to_bits()))
}

/// Distance from `p` to segment `a b`, in f64 (for clearance only; the safety checks are exact).
pub fn distance_to_segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let t = (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
    let (cx, cy) = (a.0 + t * dx, a.1 + t * dy);
    ((p.0 - cx).powi(2) + (p.1 - cy).powi(2)).sqrt()
}

/// The corners of sector `sector`, clockwise.
pub fn sector_polygon(map: &MapTables, sector: u16) -> Vec<WorldPoint> {
    let sector = &map.sectors[usize::from(sector)];
    map.sector_walls(sector)
        .iter()
        .map(|wall| {
            let v = map.vertices[usize::from(wall.start)];
            WorldPoint::from_int(v.x, v.y)
        })
        .collect()
}

/// Wall `wall` of `map` as a segment.
fn segment_of(map: &MapTables, wall: &portalcast_format::Wall) -> (WorldPoint, WorldPoint) {
    let (a, b) = (
        map.vertices[usize::from(wall.start)],
        map.vertices[usize::from(wall.end)],
    );
    (
        WorldPoint::from_int(a.x, a.y),
        WorldPoint::from_int(b.x, b.y),
    )
}

/// Every solid wall of the map, as segments.
pub fn solid_walls(map: &MapTables) -> Vec<(WorldPoint, WorldPoint)> {
    map.walls
        .iter()
        .filter(|wall| wall.neighbour().is_none())
        .map(|wall| segment_of(map, wall))
        .collect()
}

/// The walls that bound a body with its feet at `feet` (24.8) and `height` units tall: on a
/// map with room over room, those of the sectors whose heights meet the body's (a pit's walls
/// do not stop a body in the air over it, nor the deck's edges one on the pit's floor under
/// it); on any other map, all of them.
fn walls_meeting<'m>(
    map: &'m MapTables,
    feet: i32,
    height: i32,
) -> impl Iterator<Item = &'m portalcast_format::Wall> + 'm {
    let top = feet + height * 256;
    let layered = !map.layer_links.is_empty();
    map.sectors
        .iter()
        .filter(move |sector| !layered || sector.floor_z * 256 < top && feet < sector.ceil_z * 256)
        .flat_map(|sector| map.sector_walls(sector))
}

/// The solid walls that can stop a body with its feet at `feet` (24.8) ([`walls_meeting`]).
pub fn solid_walls_at(map: &MapTables, feet: i32, height: i32) -> Vec<(WorldPoint, WorldPoint)> {
    walls_meeting(map, feet, height)
        .filter(|wall| wall.neighbour().is_none())
        .map(|wall| segment_of(map, wall))
        .collect()
}

/// How far the disc overlaps the nearest solid wall, in world units (0 if clear).
pub fn solid_overlap(map: &MapTables, p: WorldPoint) -> f64 {
    overlap_of(&solid_walls(map), p)
}

/// How far the disc at `p` overlaps the nearest of `walls`, in world units (0 if clear).
fn overlap_of(walls: &[(WorldPoint, WorldPoint)], p: WorldPoint) -> f64 {
    let p = point_f64(p);
    walls
        .iter()
        .map(|&(a, b)| f64::from(RADIUS) - distance_to_segment(p, point_f64(a), point_f64(b)))
        .fold(0.0, f64::max)
}

/// How deep the disc centred at `p` is in the map's solid things: the largest
/// `(RADIUS + radius)² − distance²`, in 24.8 bits squared (exact), or 0 if it overlaps none.
pub fn solid_thing_depth(map: &MapTables, p: WorldPoint) -> i64 {
    map.things
        .iter()
        .filter(|thing| thing.flags & THING_SOLID != 0)
        .map(|thing| {
            let reach = i64::from(RADIUS + i32::from(thing.radius)) * 256;
            let dx = i64::from(p.x.to_bits()) - i64::from(thing.x_fx8);
            let dy = i64::from(p.y.to_bits()) - i64::from(thing.y_fx8);
            reach * reach - (dx * dx + dy * dy)
        })
        .fold(0, i64::max)
}

/// Checks what one tick from `before` to `after` must keep:
/// - the centre strictly inside the tracked sector (exact);
/// - the centre's path crossing or touching no solid wall, and crossing only portals into
///   sectors the body could enter (exact);
/// - the eye at least 16 above the floor and, where the sector is tall enough, the body's
///   headroom below the ceiling;
/// - the disc overlapping solid walls by no more than 1/16 unit, or no more than before;
/// - the disc overlapping no solid thing (its centre at least the sum of the radii from the
///   thing's, exact), or, if it did before, no deeper ([`solid_thing_depth`]).
pub fn check_tick(map: &MapTables, before: &Player, after: &Player) -> Result<(), String> {
    let polygon = sector_polygon(map, after.sector);
    if point_in_convex_polygon(&polygon, after.position) != Containment::Inside {
        return Err(format!(
            "centre {:?} not strictly inside its sector {}",
            after.position, after.sector
        ));
    }
    let walls = solid_walls_at(map, before.feet_z.to_bits(), before.size.height);
    if before.position != after.position {
        for &(a, b) in &walls {
            if segment_contact(before.position, after.position, a, b) != SegmentContact::Disjoint {
                return Err(format!(
                    "path {:?} -> {:?} meets the solid wall {a:?}-{b:?}",
                    before.position, after.position
                ));
            }
        }
        let body = Body {
            feet: before.feet_z,
            eye_height: before.eye_height,
            size: before.size,
            sectors: map.sectors,
        };
        let at = (after.position.x.to_bits(), after.position.y.to_bits());
        for wall in walls_meeting(map, before.feet_z.to_bits(), before.size.height) {
            let Some(next) = wall.neighbour() else {
                continue;
            };
            let (a, b) = segment_of(map, wall);
            let crosses =
                segment_contact(before.position, after.position, a, b) == SegmentContact::Crossing;
            let into = portalcast::math::cross(a, b, after.position) < 0;
            if crosses && into && !body.admits_sector(map.slopes, next, at) {
                return Err(format!(
                    "path {:?} -> {:?} crossed into sector {next}, which the body {body:?} may not enter",
                    before.position, after.position
                ));
            }
        }
    }
    // The floor and ceiling under the centre (a slope's there; an open floor's or ceiling's
    // beyond it).
    let (floor, ceil) = portalcast::player::collide::open_heights_at(
        map,
        after.sector,
        (after.position.x.to_bits(), after.position.y.to_bits()),
    );
    let eye = after.eye_z().to_bits();
    if eye < floor + CROUCH_EYE * 256 {
        return Err(format!(
            "eye {eye} less than 16 above the floor of {}",
            after.sector
        ));
    }
    let headroom = after.size.headroom();
    if ceil - floor >= (CROUCH_EYE + headroom) * 256 && eye > ceil - headroom * 256 {
        return Err(format!(
            "eye {eye} less than {headroom} below the ceiling of {}",
            after.sector
        ));
    }
    let overlap = overlap_of(&walls, after.position);
    if overlap > 1.0 / 16.0 && overlap > overlap_of(&walls, before.position) + 1e-9 {
        return Err(format!(
            "disc at {:?} overlaps a solid wall by {overlap} (before: {})",
            after.position,
            overlap_of(&walls, before.position)
        ));
    }
    let depth = solid_thing_depth(map, after.position);
    if depth > 0 && depth > solid_thing_depth(map, before.position) {
        return Err(format!(
            "disc at {:?} overlaps a solid thing (depth {depth} bits², before: {})",
            after.position,
            solid_thing_depth(map, before.position)
        ));
    }
    Ok(())
}

/// Runs `intent` for `ticks` ticks, checking every tick.
pub fn run(player: &mut Player, map: &MapTables, intent: Intent, ticks: u32) {
    for tick in 0..ticks {
        let before = *player;
        player.tick(&intent, map);
        if let Err(problem) = check_tick(map, &before, player) {
            panic!("tick {tick} of {intent:?}: {problem}");
        }
    }
}

/// A room with solid things (torches: 16 wide, a default radius of 8): one in the middle of
/// the north half, two in corners touching both walls, one touching the east wall 16 from the
/// north wall (a wedge the body cannot enter), one behind an open portal touching its line
/// (the annex, west), one behind a portal the body may not pass (the ledge, 48 up, east) touching
/// its line; and a torch that is not solid.
pub const THINGS_MAP: &str = "
vertex a 0 0
vertex b 256 0
vertex c 256 256
vertex d 0 256
vertex e 256 96
vertex f 256 160
vertex g 320 96
vertex h 320 160
vertex p 0 160
vertex q 0 96
vertex r -96 96
vertex s -96 160
sector room floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall a b tex=brick
  wall b e tex=brick
  wall e f portal=ledge lower=step
  wall f c tex=brick
  wall c d tex=brick
  wall d p tex=brick
  wall p q portal=annex
  wall q a tex=brick
sector ledge floor=48 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall e g tex=brick
  wall g h tex=brick
  wall h f tex=brick
  wall f e portal=room
sector annex floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall r q tex=brick
  wall q p portal=room
  wall p s tex=brick
  wall s r tex=brick
player 128.5 200.5
thing torch 128 64 solid
thing torch 24 232 solid radius=24
thing torch 224 224 solid radius=32
thing torch 232 40 solid radius=24
thing torch -12 128 solid radius=12
thing torch 268 128 solid radius=12
thing torch 64 160
";

/// A room with a cluster of twelve solid torches (radius 8) 10 units apart, more than the
/// collision keeps in its short list of things near a step.
pub const CLUSTER_MAP: &str = "
vertex a 0 0
vertex b 256 0
vertex c 256 256
vertex d 0 256
sector room floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall a b tex=brick
  wall b c tex=brick
  wall c d tex=brick
  wall d a tex=brick
player 40.5 40.5
thing torch 100 100 solid
thing torch 110 100 solid
thing torch 120 100 solid
thing torch 130 100 solid
thing torch 100 110 solid
thing torch 110 110 solid
thing torch 120 110 solid
thing torch 130 110 solid
thing torch 100 120 solid
thing torch 110 120 solid
thing torch 120 120 solid
thing torch 130 120 solid
";

// Binary angles: 0 along +x (east), growing toward +y (south on the top-down view).
pub const EAST: u16 = 0;
pub const SOUTH_EAST: u16 = 8192;
pub const SOUTH: u16 = 2 * 8192;
pub const SOUTH_WEST: u16 = 3 * 8192;
pub const WEST: u16 = 4 * 8192;
pub const NORTH_WEST: u16 = 5 * 8192;
pub const NORTH: u16 = 6 * 8192;
pub const NORTH_EAST: u16 = 7 * 8192;

/// The player standing at `(x, y)` (units) in `sector`, facing `angle` (binary).
pub fn at(map: &MapTables, sector: u16, x: f64, y: f64, angle: u16) -> Player {
    let p = WorldPoint::new(
        Fx24_8::from_bits((x * 256.0) as i32),
        Fx24_8::from_bits((y * 256.0) as i32),
    );
    Player::standing_at(map, sector, p, Angle::from_bits(angle))
}

/// [`walk`] with run on.
pub fn run_intent(forward: i8, strafe: i8) -> Intent {
    Intent {
        run: true,
        ..walk(forward, strafe, 0)
    }
}

/// The player's position in units.
pub fn position(player: &Player) -> (f64, f64) {
    (
        units(player.position.x.to_bits()),
        units(player.position.y.to_bits()),
    )
}
