//! 10,000 random moves on every shipped map, from random places: the player never leaves the
//! map. After every tick (`common::player::check_tick`, exact geometry): the centre is strictly
//! inside the sector the player tracks, its path crossed no solid wall and no portal the body
//! could not enter, the eye keeps its room to floor and ceiling, and the disc does not sink
//! into solid walls or enter a solid thing's disc. The same on test maps of solid things set
//! in corners, against walls and by portals, and of a cluster of them. The maps' movers run
//! throughout (issue 18): each case starts them all, the moves' use button starts them again,
//! and every tick is checked on the live map.

mod common;

use common::player::check_tick;
use portalcast::math::{point_in_convex_polygon, Angle, Containment, Fx24_8, WorldPoint};
use portalcast::player::input::Intent;
use portalcast::player::Player;
use portalcast_format::{MapTables, PlayerSize};
use proptest::prelude::*;

/// Moves per case and cases per map: 40 × 256 = 10,240 moves on each map.
const MOVES_PER_CASE: usize = 256;
const CASES: u32 = 40;

/// One random move: an intent held for 1 to 8 ticks.
#[derive(Clone, Debug)]
struct Move {
    intent: Intent,
    ticks: u32,
}

fn axis() -> impl Strategy<Value = i8> {
    prop_oneof![Just(-1i8), Just(0), Just(1)]
}

fn a_move() -> impl Strategy<Value = Move> {
    (
        (axis(), axis(), axis(), axis()),
        (any::<bool>(), any::<bool>(), any::<bool>()),
        (0u8..40, 1u32..=8),
    )
        .prop_map(
            |((forward, strafe, turn, look), (run, jump, crouch), (rare, ticks))| Move {
                intent: Intent {
                    forward,
                    strafe,
                    turn,
                    look,
                    run,
                    jump,
                    crouch,
                    recentre: rare == 1,
                    toggle_fly: rare == 0,
                    activate: rare == 2,
                },
                ticks,
            },
        )
}

/// A start: a sector, weights for a point inside it (a convex combination of its corners),
/// a view angle.
fn a_start() -> impl Strategy<Value = (usize, Vec<u32>, u16)> {
    (
        any::<usize>(),
        prop::collection::vec(1u32..1000, 8),
        any::<u16>(),
    )
}

/// The player standing at the weighted mean of the sector's corners (strictly inside: all
/// weights are positive), or `None` if rounding put it on a wall.
fn place(map: &MapTables, sector_pick: usize, weights: &[u32], angle: u16) -> Option<Player> {
    let sector = (sector_pick % map.sectors.len()) as u16;
    let corners = common::player::sector_polygon(map, sector);
    let (mut x, mut y, mut total) = (0i64, 0i64, 0i64);
    for (corner, &weight) in corners.iter().zip(weights.iter().cycle()) {
        x += i64::from(corner.x.to_bits()) * i64::from(weight);
        y += i64::from(corner.y.to_bits()) * i64::from(weight);
        total += i64::from(weight);
    }
    let p = WorldPoint::new(
        Fx24_8::from_bits((x / total) as i32),
        Fx24_8::from_bits((y / total) as i32),
    );
    (point_in_convex_polygon(&corners, p) == Containment::Inside)
        .then(|| Player::standing_at(map, sector, p, Angle::from_bits(angle)))
}

fn random_moves_keep_the_invariants(map_name: &str) {
    let map = portalcast_rom::demo::map_named(map_name).expect("a shipped map");
    random_moves_keep_the_invariants_on(&map, CASES);
}

fn random_moves_keep_the_invariants_on(map: &MapTables, cases: u32) {
    let config = ProptestConfig {
        cases,
        ..ProptestConfig::default()
    };
    proptest!(config, |(
        start in a_start(),
        from_the_start in any::<bool>(),
        moves in prop::collection::vec(a_move(), MOVES_PER_CASE),
    )| {
        let player = if from_the_start {
            Some(Player::spawn(map))
        } else {
            place(map, start.0, &start.1, start.2)
        };
        prop_assume!(player.is_some());
        let mut player = player.unwrap();
        // The map's movers running (issue 18): every door opens, every lift goes down, as the
        // use button would start them, for a second before the moves (the player standing
        // where it starts, in a door or on a lift as often as anywhere); the use button
        // (`activate`) in the moves starts them again. Doors then close on the body at their
        // time, lifts carry it.
        let mut world = Box::new(common::HostWorld::start(map));
        for index in 0..map.movers.len() {
            world.use_mover(map, index);
        }
        for _ in 0..60 {
            world.tick(map, &player);
        }
        let live = world.map(map);
        let at = (player.position.x.to_bits(), player.position.y.to_bits());
        prop_assume!(player
            .body(live.sectors)
            .admits_sector(live.slopes, player.sector, at));
        player.feet_z = Fx24_8::from_bits(
            live.heights_fx8_at(&live.sectors[usize::from(player.sector)], at.0, at.1).0,
        );
        for (index, step) in moves.iter().enumerate() {
            for tick in 0..step.ticks {
                let before = player;
                world.tick_with_player(map, &mut player, &step.intent);
                let live = world.map(map);
                if let Err(problem) = check_tick(&live, &before, &player) {
                    prop_assert!(false, "move {index} tick {tick} ({:?}): {problem}", step.intent);
                }
                // Never crushed: a ceiling that came down keeps the headroom over the eye (a
                // sloped one's, over the centre; an open one's, the ceiling above it).
                let (_, ceiling) = portalcast::player::collide::open_heights_at(
                    &live,
                    player.sector,
                    (player.position.x.to_bits(), player.position.y.to_bits()),
                );
                prop_assert!(
                    player.eye_z().to_bits() + player.size.headroom() * 256 <= ceiling,
                    "move {index} tick {tick}: the eye {} under the ceiling {ceiling}",
                    player.eye_z().to_bits()
                );
            }
        }
    });
}

#[test]
fn random_moves_never_leave_the_bench_map() {
    random_moves_keep_the_invariants("bench");
}

#[test]
fn random_moves_never_leave_the_grid_map() {
    random_moves_keep_the_invariants("grid");
}

#[test]
fn random_moves_never_leave_the_tiny_map() {
    random_moves_keep_the_invariants("tiny");
}

#[test]
fn random_moves_never_leave_the_slopes_map() {
    random_moves_keep_the_invariants("slopes");
}

#[test]
fn random_moves_never_enter_solid_things() {
    let compiled = common::player::compile_map("things.map", common::player::THINGS_MAP);
    // Small and quick: five times the shipped maps' cases.
    random_moves_keep_the_invariants_on(&compiled.tables(), 5 * CASES);
}

#[test]
fn random_moves_never_enter_a_cluster_of_solid_things() {
    let compiled = common::player::compile_map("cluster.map", common::player::CLUSTER_MAP);
    random_moves_keep_the_invariants_on(&compiled.tables(), 5 * CASES);
}

#[test]
fn every_shipped_map_is_covered() {
    let names: Vec<&str> = portalcast_rom::assets::MAPS
        .iter()
        .map(|m| m.name)
        .collect();
    assert_eq!(
        names,
        ["bench", "grid", "slopes", "tiny"],
        "add a test above for a new map"
    );
}

#[test]
fn random_moves_never_leave_freedoom_maps_with_dooms_body() {
    // Doom's body (eye 41, height 56, steps of 24) on the maps cut from Freedoom's: thousands
    // of small convex pieces, doors, and steps of 24 the native body could not climb.
    for compiled in common::freedoom_assets().maps() {
        let map = compiled.tables();
        assert_eq!(map.player_start.size, PlayerSize::DOOM, "{}", map.name);
        random_moves_keep_the_invariants_on(&map, CASES);
    }
}
