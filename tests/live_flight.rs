//! The fly-through through the live world (`portalcast_rom::live_flight`, issue 18): on every shipped
//! map the camera's eye stays strictly between its sector's live floor and ceiling (a slope's
//! under it), the camera never gives up waiting, and the world it flies through is the game's
//! (its movers within their ranges, and moving where the map has any); on the bench map it opens the corridor's door and waits for it, and rides the
//! lift down with its eye on the lift's floor.

use portalcast::player::collide::RADIUS;
use portalcast::world::Phase;
use portalcast_format::{MOVER_DOOR, MOVER_LIFT, THING_SOLID};
use portalcast_rom::assets;
use portalcast_rom::flight::EYE_HEIGHT;
use portalcast_rom::game::GameWorld;
use portalcast_rom::live_flight::{LiveFlight, MAX_WAIT_FRAMES};

/// Frames flown on each map: well past one tour of the bench map.
const FRAMES: u32 = 2000;

#[test]
fn the_camera_stays_inside_the_live_heights_and_never_gives_up_waiting() {
    for map in assets::MAPS {
        let mut world = GameWorld::new();
        let mut flight = LiveFlight::new(map, &mut world);
        let mut moved = 0;
        let mut still = 0u32;
        let mut last = flight.camera().position;
        for frame in 0..FRAMES {
            let camera = flight.camera();
            let live = world.map(map);
            let sector = &live.sectors[usize::from(camera.sector)];
            let eye = camera.eye_z.to_bits();
            // The heights under the camera: a slope's there.
            let (floor, ceil) = live.heights_fx8_at(
                sector,
                camera.position.x.to_bits(),
                camera.position.y.to_bits(),
            );
            assert!(
                floor < eye && eye < ceil,
                "{} frame {frame}: eye {eye} outside sector {} ({floor}..{ceil}, 24.8)",
                map.name,
                camera.sector,
            );
            for (state, mover) in world.movers().iter().zip(map.movers) {
                assert!((mover.low..=mover.high).contains(&state.height));
            }
            moved += usize::from(world.movers().iter().any(|m| m.phase != Phase::Resting));
            still = if camera.position == last {
                still + 1
            } else {
                0
            };
            assert!(
                still < MAX_WAIT_FRAMES / 2,
                "{} frame {frame}: the camera waited {still} frames",
                map.name
            );
            last = camera.position;
            flight.advance(&mut world);
        }
        assert!(
            map.movers.is_empty() || moved > 0,
            "{}: no mover moved in the fly-through",
            map.name
        );
    }
}

#[test]
fn on_the_bench_map_the_camera_opens_the_door_and_rides_the_lift() {
    let map = assets::MAPS.iter().find(|m| m.name == "bench").unwrap();
    let door = map
        .movers
        .iter()
        .position(|m| m.kind == MOVER_DOOR)
        .unwrap();
    let lift = map
        .movers
        .iter()
        .position(|m| m.kind == MOVER_LIFT)
        .unwrap();
    let door_sector = map.movers[door].sector;
    let lift_sector = map.movers[lift].sector;
    // The door sector is thin: the camera may cross it between two frames, from one of its
    // neighbours straight into another.
    let door_neighbours: Vec<u16> = map
        .sector_walls(&map.sectors[usize::from(door_sector)])
        .iter()
        .filter_map(|wall| wall.neighbour())
        .collect();
    let mut world = GameWorld::new();
    let mut flight = LiveFlight::new(map, &mut world);
    let (mut through_door, mut rode_down) = (None, false);
    let mut previous = flight.camera().sector;
    for frame in 0..portalcast_rom::bench::BENCH_MAP_FRAMES {
        let camera = flight.camera();
        let crossed = camera.sector != previous
            && door_neighbours.contains(&previous)
            && door_neighbours.contains(&camera.sector);
        if (camera.sector == door_sector || crossed) && through_door.is_none() {
            through_door = Some((frame, world.movers()[door].height));
        }
        previous = camera.sector;
        if camera.sector == lift_sector {
            let floor = world.movers()[lift].height;
            assert_eq!(camera.eye_z.to_bits(), (floor + EYE_HEIGHT) * 256);
            rode_down |= floor < map.movers[lift].high - 32;
        }
        flight.advance(&mut world);
    }
    let (frame, height) = through_door.expect("the camera went through the door");
    assert!(height >= 56, "frame {frame}: through the door at {height}");
    assert!(
        rode_down,
        "the camera did not ride the lift down within the bench's frames"
    );
}

/// Like a player's body, the camera keeps clear of solid things: its centre never nearer a solid
/// thing's centre than the two radii (the bench map's statue stands at its dais' centre, where
/// the tour used to stand inside it and draw a screen-filling sprite no player can see).
#[test]
fn the_camera_keeps_a_players_clearance_from_solid_things() {
    for map in assets::MAPS {
        let mut world = GameWorld::new();
        let mut flight = LiveFlight::new(map, &mut world);
        for frame in 0..FRAMES {
            let camera = flight.camera();
            for thing in map.things.iter().filter(|t| t.flags & THING_SOLID != 0) {
                let dx = i64::from(camera.position.x.to_bits() - thing.x_fx8);
                let dy = i64::from(camera.position.y.to_bits() - thing.y_fx8);
                let clearance = (i64::from(thing.radius) + i64::from(RADIUS)) * 256;
                assert!(
                    dx * dx + dy * dy >= clearance * clearance,
                    "{} frame {frame}: the camera at {:?} is within {} units of the solid thing at ({}, {})",
                    map.name,
                    camera.position,
                    clearance / 256,
                    thing.x_fx8 / 256,
                    thing.y_fx8 / 256
                );
            }
            flight.advance(&mut world);
        }
    }
}
