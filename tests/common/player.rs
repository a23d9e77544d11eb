//! Shared pieces of the player tests: sector names, driving the player, and the invariants every
//! tick must keep, checked with exact geometry independent of the player's own code.

use portalcast::math::{
    point_in_convex_polygon, segment_contact, Containment, SegmentContact, WorldPoint,
};
use portalcast::player::collide::{Body, RADIUS};
use portalcast::player::input::Intent;
use portalcast::player::vertical::CROUCH_EYE;
use portalcast::player::Player;
use portalcast_format::MapTables;

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

/// A compiled map's tables, from map text (the shipped texture and sprite names).
pub fn compile_map(file_name: &str, text: &str) -> portalcast_assets::CompiledMap {
    let catalog = portalcast_assets::Catalog::new(
        [
            "brick", "ceiling", "dirt", "grass", "marble", "metal", "step", "stone", "tiles",
            "trim", "water", "wood",
        ],
        ["torch"],
        true,
    );
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

/// Every solid wall of the map, as segments.
pub fn solid_walls(map: &MapTables) -> Vec<(WorldPoint, WorldPoint)> {
    map.walls
        .iter()
        .filter(|wall| wall.neighbour().is_none())
        .map(|wall| {
            let (a, b) = (
                map.vertices[usize::from(wall.start)],
                map.vertices[usize::from(wall.end)],
            );
            (
                WorldPoint::from_int(a.x, a.y),
                WorldPoint::from_int(b.x, b.y),
            )
        })
        .collect()
}

/// How far the disc overlaps the nearest solid wall, in world units (0 if clear).
pub fn solid_overlap(map: &MapTables, p: WorldPoint) -> f64 {
    let p = point_f64(p);
    solid_walls(map)
        .iter()
        .map(|&(a, b)| f64::from(RADIUS) - distance_to_segment(p, point_f64(a), point_f64(b)))
        .fold(0.0, f64::max)
}

/// Checks what one tick from `before` to `after` must keep:
/// - the centre strictly inside the tracked sector (exact);
/// - the centre's path crossing or touching no solid wall, and crossing only portals into
///   sectors the body could enter (exact);
/// - the eye at least 16 above the floor and, where the sector is tall enough, 16 below the
///   ceiling;
/// - the disc overlapping solid walls by no more than 1/16 unit, or no more than before.
pub fn check_tick(map: &MapTables, before: &Player, after: &Player) -> Result<(), String> {
    let polygon = sector_polygon(map, after.sector);
    if point_in_convex_polygon(&polygon, after.position) != Containment::Inside {
        return Err(format!(
            "centre {:?} not strictly inside its sector {}",
            after.position, after.sector
        ));
    }
    if before.position != after.position {
        for (a, b) in solid_walls(map) {
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
        };
        for wall in map.walls {
            let Some(next) = wall.neighbour() else {
                continue;
            };
            let (a, b) = (
                map.vertices[usize::from(wall.start)],
                map.vertices[usize::from(wall.end)],
            );
            let (a, b) = (
                WorldPoint::from_int(a.x, a.y),
                WorldPoint::from_int(b.x, b.y),
            );
            let crosses =
                segment_contact(before.position, after.position, a, b) == SegmentContact::Crossing;
            let into = portalcast::math::cross(a, b, after.position) < 0;
            if crosses && into && !body.admits(&map.sectors[usize::from(next)]) {
                return Err(format!(
                    "path {:?} -> {:?} crossed into sector {next}, which the body {body:?} may not enter",
                    before.position, after.position
                ));
            }
        }
    }
    let sector = &map.sectors[usize::from(after.sector)];
    let eye = after.eye_z().to_bits();
    if eye < (sector.floor_z + CROUCH_EYE) * 256 {
        return Err(format!(
            "eye {eye} less than 16 above the floor of {}",
            after.sector
        ));
    }
    if sector.ceil_z - sector.floor_z >= 2 * CROUCH_EYE && eye > (sector.ceil_z - 16) * 256 {
        return Err(format!(
            "eye {eye} less than 16 below the ceiling of {}",
            after.sector
        ));
    }
    let overlap = solid_overlap(map, after.position);
    if overlap > 1.0 / 16.0 && overlap > solid_overlap(map, before.position) + 1e-9 {
        return Err(format!(
            "disc at {:?} overlaps a solid wall by {overlap} (before: {})",
            after.position,
            solid_overlap(map, before.position)
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
