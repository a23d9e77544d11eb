//! Solid things against the player on the host: a solid thing's disc blocks the body like a
//! wall (head on it stops at contact distance, at a glance it slides round), a thing that is not
//! solid does not block, and things next to walls never let the body through the walls or into
//! their discs. Every tick of every case is checked with exact geometry
//! (`common::player::check_tick`), which includes the solid things' discs. Maps:
//! `common::player::THINGS_MAP` and `CLUSTER_MAP`.

mod common;

use common::player::*;
use portalcast::player::collide::RADIUS;
use portalcast::player::input::Intent;
use portalcast::player::Player;

fn bits(player: &Player) -> (i32, i32) {
    (player.position.x.to_bits(), player.position.y.to_bits())
}

/// The distance from the player's centre to (x, y), in units.
fn distance(player: &Player, (x, y): (f64, f64)) -> f64 {
    let (px, py) = position(player);
    ((px - x).powi(2) + (py - y).powi(2)).sqrt()
}

fn room() -> u16 {
    sector_index_in(THINGS_MAP, "room")
}

#[test]
fn walking_straight_into_a_solid_thing_stops_at_contact_distance() {
    let compiled = compile_map("things.map", THINGS_MAP);
    let map = compiled.tables();
    // North into the torch at (128, 64), radius 8: the centres end exactly 16 + 8 apart.
    for intent in [walk(1, 0, 0), run_intent(1, 0)] {
        let mut player = at(&map, room(), 128.0, 200.0, NORTH);
        run(&mut player, &map, intent, 300);
        assert_eq!(bits(&player), (128 * 256, (64 + RADIUS + 8) * 256));
        assert_eq!(player.velocity, (0, 0));
        assert_eq!(solid_thing_depth(&map, player.position), 0);
    }
}

#[test]
fn walking_past_a_solid_thing_at_an_angle_slides_round_it() {
    let compiled = compile_map("things.map", THINGS_MAP);
    let map = compiled.tables();
    // 18 units off the torch's centre line (less than the 24 of the two radii), on either side.
    for x in [110.0, 146.0] {
        let mut player = at(&map, room(), x, 200.0, NORTH);
        let intent = walk(1, 0, 0);
        let mut touched = false;
        for tick in 0..300 {
            let before = player;
            player.tick(&intent, &map);
            if let Err(problem) = check_tick(&map, &before, &player) {
                panic!("tick {tick}: {problem}");
            }
            touched |= distance(&player, (128.0, 64.0)) < 24.1;
            // Never stuck on the disc: every tick until the north wall gains ground northward.
            let (_, y) = position(&player);
            if y > f64::from(RADIUS) + 0.5 && tick > 0 {
                assert!(
                    player.position.y < before.position.y,
                    "stuck at {:?} on tick {tick}",
                    position(&player)
                );
            }
        }
        assert!(touched, "from x = {x} the disc never met the torch");
        // Round the torch, on the side it came from, up against the north wall.
        let (end_x, end_y) = position(&player);
        assert_eq!(
            player.position.y.to_bits(),
            RADIUS * 256,
            "ended at {end_x}, {end_y}"
        );
        assert!(
            (end_x < 128.0) == (x < 128.0),
            "from {x} ended at {end_x}, {end_y}"
        );
    }
}

#[test]
fn a_thing_that_is_not_solid_does_not_block() {
    let compiled = compile_map("things.map", THINGS_MAP);
    let map = compiled.tables();
    // Straight through the torch at (64, 160), which is not solid, to the north wall.
    let mut player = at(&map, room(), 64.0, 220.0, NORTH);
    run(&mut player, &map, walk(1, 0, 0), 300);
    assert_eq!(bits(&player), (64 * 256, RADIUS * 256));
}

#[test]
fn a_solid_thing_behind_an_open_portal_blocks_before_its_sector() {
    let compiled = compile_map("things.map", THINGS_MAP);
    let map = compiled.tables();
    // West toward the annex: its torch (radius 12) touches the portal line x = 0 at y = 128,
    // so the body stops in the room, 16 + 12 from its centre.
    let mut player = at(&map, room(), 128.0, 128.0, WEST);
    run(&mut player, &map, run_intent(1, 0), 200);
    assert_eq!(bits(&player), ((-12 + RADIUS + 12) * 256, 128 * 256));
    assert_eq!(player.sector, room());
}

#[test]
fn a_solid_thing_behind_a_portal_the_body_may_not_pass_stays_clear() {
    let compiled = compile_map("things.map", THINGS_MAP);
    let map = compiled.tables();
    // East into the ledge's portal (48 up): the portal stops the body 16 from its line, where
    // the ledge's torch (radius 12, touching the line) is exactly 16 + 12 away.
    let mut player = at(&map, room(), 200.0, 128.0, EAST);
    run(&mut player, &map, run_intent(1, 0), 200);
    assert_eq!(bits(&player), ((256 - RADIUS) * 256, 128 * 256));
    assert_eq!(solid_thing_depth(&map, player.position), 0);
}

#[test]
fn solid_things_in_corners_never_let_the_body_through_the_walls() {
    let compiled = compile_map("things.map", THINGS_MAP);
    let map = compiled.tables();
    // Into the wedges between a torch and the walls it touches: south along the east wall into
    // the south-east torch, east along the north wall into the north-east one, diagonally into
    // both corner torches; `run` checks every tick (walls and discs).
    let cases = [
        (240.0, 150.0, SOUTH, run_intent(1, 0)),
        (150.0, 16.5, EAST, run_intent(1, 0)),
        (128.0, 128.0, SOUTH_EAST, run_intent(1, 0)),
        (128.0, 128.0, SOUTH_WEST, run_intent(1, 0)),
        // Strafing along the south wall into either corner torch.
        (128.0, 239.5, NORTH, run_intent(0, 1)),
        (128.0, 239.5, NORTH, run_intent(0, -1)),
    ];
    for (x, y, angle, intent) in cases {
        let mut player = at(&map, room(), x, y, angle);
        run(&mut player, &map, intent, 300);
        let (px, py) = position(&player);
        let clear = RADIUS as f64 - 1.0 / 16.0;
        assert!(
            px >= clear && px <= 256.0 - clear && py >= clear && py <= 256.0 - clear,
            "from {x}, {y}: at {px}, {py}"
        );
        assert_eq!(player.sector, room(), "from {x}, {y}: at {px}, {py}");
    }
    // And from every direction at full speed, from a ring of places round the room.
    for start in 0..16u16 {
        let turn = f64::from(start) * std::f64::consts::TAU / 16.0;
        let (x, y) = (128.0 + 70.0 * turn.cos(), 128.0 + 70.0 * turn.sin());
        for heading in 0..32u16 {
            let mut player = at(&map, room(), x, y, heading * 2048);
            run(&mut player, &map, run_intent(1, 0), 90);
        }
    }
}

#[test]
fn a_body_placed_in_a_solid_thing_is_pushed_out() {
    let compiled = compile_map("things.map", THINGS_MAP);
    let map = compiled.tables();
    // Six units from the torch's centre: standing still, one tick pushes it out radially to
    // exactly the sum of the radii.
    let mut player = at(&map, room(), 128.0, 70.0, NORTH);
    run(&mut player, &map, Intent::default(), 1);
    assert_eq!(bits(&player), (128 * 256, (64 + RADIUS + 8) * 256));
    // At the very centre: along +x.
    let mut player = at(&map, room(), 128.0, 64.0, NORTH);
    run(&mut player, &map, Intent::default(), 1);
    assert_eq!(bits(&player), ((128 + RADIUS + 8) * 256, 64 * 256));
    // Walking into it from the east stops at the contact distance.
    let mut player = at(&map, room(), 200.0, 64.0, WEST);
    run(&mut player, &map, run_intent(1, 0), 200);
    assert_eq!(bits(&player), ((128 + RADIUS + 8) * 256, 64 * 256));
}

#[test]
fn a_cluster_of_more_solid_things_than_the_short_list_blocks_alike() {
    let compiled = compile_map("cluster.map", CLUSTER_MAP);
    let map = compiled.tables();
    // East along the cluster's middle row, into its west column (a bumpy wall of discs): it
    // ends against the column, in contact with a torch, clear of all.
    let column = [(100.0, 100.0), (100.0, 110.0), (100.0, 120.0)];
    for y in [110.0, 112.5, 115.0] {
        let mut player = at(&map, 0, 40.0, y, EAST);
        run(&mut player, &map, run_intent(1, 0), 200);
        let nearest = column
            .iter()
            .map(|&centre| distance(&player, centre))
            .fold(f64::MAX, f64::min);
        assert!(
            (24.0..24.1).contains(&nearest),
            "from y = {y} ended at {:?}",
            position(&player)
        );
        assert_eq!(solid_thing_depth(&map, player.position), 0);
    }
    // South into the cluster's north row, 5 units off a torch's centre line: slides west round
    // the row's end or stops on it, never inside.
    for x in [95.0, 105.0, 115.0, 125.0, 135.0] {
        let mut player = at(&map, 0, x, 40.0, SOUTH);
        run(&mut player, &map, walk(1, 0, 0), 300);
        assert_eq!(solid_thing_depth(&map, player.position), 0);
    }
    // And from every direction round it.
    for start in 0..16u16 {
        let turn = f64::from(start) * std::f64::consts::TAU / 16.0;
        let (x, y) = (115.0 + 60.0 * turn.cos(), 110.0 + 60.0 * turn.sin());
        for heading in 0..16u16 {
            let mut player = at(&map, 0, x, y, heading * 4096);
            run(&mut player, &map, run_intent(1, 0), 60);
        }
    }
}

/// Two rooms joined by a portal with a grate in it: `blocks` makes the portal a wall to the
/// body; without it the body walks through.
#[test]
fn a_blocking_middle_stops_the_player_and_a_plain_one_does_not() {
    let text = |words: &str| {
        format!(
            "vertex a 0 0\nvertex b 128 0\nvertex c 256 0\nvertex d 256 128\nvertex e 128 128\n\
             vertex f 0 128\n\
             sector west floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling light=160\n\
             \x20 wall a b tex=brick\n  wall b e portal=east mid=grate {words}\n\
             \x20 wall e f tex=brick\n  wall f a tex=brick\n\
             sector east floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling light=160\n\
             \x20 wall b c tex=brick\n  wall c d tex=brick\n  wall d e tex=brick\n\
             \x20 wall e b portal=west\n\
             player 64 64 angle=0\n"
        )
    };
    for (words, passes) in [("blocks", false), ("", true)] {
        let compiled = compile_map("grate.map", &text(words));
        let map = compiled.tables();
        let west = sector_index_in(&text(words), "west");
        let mut player = at(&map, west, 64.0, 64.0, EAST);
        for tick in 0..200 {
            let before = player;
            player.tick(&run_intent(1, 0), &map);
            if let Err(problem) = check_tick(&map, &before, &player) {
                panic!("{words:?} tick {tick}: {problem}");
            }
        }
        let (x, _) = position(&player);
        if passes {
            assert!(x > 128.0 + f64::from(RADIUS), "{words:?}: at x = {x}");
        } else {
            assert!(x <= 128.0 - f64::from(RADIUS), "{words:?}: at x = {x}");
            assert_eq!(player.sector, west);
        }
    }
}
