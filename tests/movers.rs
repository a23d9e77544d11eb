//! Moving sectors on the host (issue 18): a door opens on use and lets the body through, closes
//! after its wait and turns back rather than come down on a body in it; a lift goes down on use,
//! waits, and carries a body standing on it back up; a platform and a crusher run for ever and
//! never close on the body. Every tick is checked against the live map with the exact invariants
//! of the player tests (`common::player::check_tick`), and the live heights stay between the
//! mover's two. And the light effects: a glow's and a strobe's levels through their periods, a
//! flicker's draws, a switched light turned by its tag.

mod common;

use common::player::*;
use portalcast::player::input::Intent;
use portalcast::player::Player;
use portalcast::world::{level, Phase, World};
use portalcast_format::{
    Light, MapTables, Mover, LIGHT_FLICKER, LIGHT_GLOW, LIGHT_STROBE, LIGHT_SWITCHED,
    MOVER_CRUSHER, MOVER_DOOR, MOVER_LIFT, MOVER_ON_TOUCH, MOVER_ON_USE,
};

/// West room, a door 16 deep, east room; north of the west room a lift (its floor 64 when
/// raised) and north of the lift a ledge at 64.
const MAP: &str = "
vertex a 0 0
vertex b 256 0
vertex c 256 96
vertex d 256 160
vertex e 256 256
vertex f 0 256
vertex g 272 96
vertex h 272 160
vertex i 528 0
vertex j 528 256
vertex k 272 0
vertex l 272 256
vertex m 0 -128
vertex n 256 -128
vertex o 0 -256
vertex p 256 -256
sector west floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall a b portal=lift lower=brick
  wall b c tex=brick
  wall c d portal=door upper=brick
  wall d e tex=brick
  wall e f tex=brick
  wall f a tex=brick
sector door floor=0 ceil=112 floor_tex=tiles ceil_tex=ceiling
  wall c g tex=brick
  wall g h portal=east upper=brick
  wall h d tex=brick
  wall d c portal=west upper=brick
sector east floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall k i tex=brick
  wall i j tex=brick
  wall j l tex=brick
  wall l h tex=brick
  wall h g portal=door upper=brick
  wall g k tex=brick
sector lift floor=64 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall m n portal=ledge
  wall n b tex=brick
  wall b a portal=west lower=brick
  wall a m tex=brick
sector ledge floor=64 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall o p tex=brick
  wall p n tex=brick
  wall n m portal=lift
  wall m o tex=brick
player 200.5 128.5
";

const DOOR: u16 = 1;
const LIFT: u16 = 3;

fn mover(sector: u16, kind: u8, low: i32, high: i32, start: i32) -> Mover {
    Mover {
        sector,
        kind,
        flags: if matches!(kind, MOVER_DOOR | MOVER_LIFT) {
            MOVER_ON_USE
        } else {
            0
        },
        low,
        high,
        speed: 2,
        wait: 60,
        tag: 0,
        start,
    }
}

type TestWorld = World<8, 4, 4>;

/// The map compiled, with `movers` added (in sector order).
fn compiled(movers: Vec<Mover>) -> portalcast_assets::CompiledMap {
    let mut map = compile_map("movers.map", MAP);
    map.movers = movers;
    map
}

fn standard_movers() -> Vec<Mover> {
    vec![
        mover(DOOR, MOVER_DOOR, 0, 112, 0),
        mover(LIFT, MOVER_LIFT, 0, 64, 64),
    ]
}

fn shoulders() -> Intent {
    Intent {
        activate: true,
        ..Intent::default()
    }
}

/// Runs `intent` for `ticks` ticks with the world, checking every tick on the live map and the
/// movers' heights.
fn play(world: &mut TestWorld, map: &MapTables, player: &mut Player, intent: Intent, ticks: u32) {
    for tick in 0..ticks {
        let before = *player;
        world.tick_with_player(map, player, &intent);
        let live = world.map(map);
        if let Err(problem) = check_tick(&live, &before, player) {
            panic!("tick {tick} of {intent:?}: {problem}");
        }
        for (state, mover) in world.movers().iter().zip(map.movers) {
            assert!(
                (mover.low..=mover.high).contains(&state.height),
                "tick {tick}: {state:?} outside {mover:?}"
            );
        }
        let sector = &live.sectors[usize::from(player.sector)];
        assert!(
            player.eye_z().to_bits() + player.size.headroom() * 256 <= sector.ceil_z * 256,
            "tick {tick}: the eye {} is within the headroom of the ceiling {}",
            player.eye_z().to_bits(),
            sector.ceil_z
        );
    }
}

fn door_height(world: &TestWorld) -> i32 {
    world.movers()[0].height
}

#[test]
fn a_closed_door_blocks_and_opens_on_use_and_lets_the_body_through() {
    let map = compiled(standard_movers());
    let map = map.tables();
    let mut world = TestWorld::start(&map);
    assert_eq!(world.map(&map).sectors[usize::from(DOOR)].ceil_z, 0);
    let mut player = at(&map, 0, 200.5, 128.5, EAST);
    // Closed: walking east stops at the door's line, one radius short of it.
    play(&mut world, &map, &mut player, walk(1, 0, 0), 120);
    assert_eq!(player.sector, 0);
    assert!(units(player.position.x.to_bits()) <= 256.0 - 16.0);
    // Use within reach: the door goes up 2 a tick to 112.
    play(&mut world, &map, &mut player, shoulders(), 1);
    play(&mut world, &map, &mut player, Intent::default(), 60);
    assert_eq!(door_height(&world), 112);
    assert_eq!(world.movers()[0].phase, Phase::WaitingAway);
    // Through the door into the east room.
    play(&mut world, &map, &mut player, walk(1, 0, 0), 40);
    assert_eq!(player.sector, 2, "{:?}", position(&player));
}

#[test]
fn a_touch_door_opens_when_the_body_comes_within_reach_and_not_before() {
    let touch_door = Mover {
        flags: MOVER_ON_TOUCH,
        ..mover(DOOR, MOVER_DOOR, 0, 112, 0)
    };
    let map = compiled(vec![touch_door]);
    let map = map.tables();
    let reach = f64::from(portalcast::player::collide::RADIUS + portalcast::world::TOUCH_REACH);
    // The door's line is x = 256, between y = 96 and 160. Standing still: out of reach (in
    // front of it, and beyond its ends), then just within it. (Nearer than a radius, the
    // closed door would turn back at once: the body would overlap its sector.)
    for (x, y, opens) in [
        (256.0 - reach - 2.5, 128.5, false),
        (256.0 - reach - 0.5, 128.5, false),
        (238.5, 96.0 - reach - 2.5, false),
        (238.5, 160.0 + reach + 2.5, false),
        (256.0 - reach + 0.5, 128.5, true),
        (238.5, 100.5, true),
    ] {
        let mut world = TestWorld::start(&map);
        let mut player = at(&map, 0, x, y, EAST);
        play(&mut world, &map, &mut player, Intent::default(), 2);
        assert_eq!(
            world.movers()[0].phase != Phase::Resting,
            opens,
            "body at ({x}, {y}): {:?}",
            world.movers()[0]
        );
    }
    // Walking into it from the middle of the room opens it; the use button is not needed.
    let mut world = TestWorld::start(&map);
    let mut player = at(&map, 0, 128.5, 128.5, EAST);
    play(&mut world, &map, &mut player, walk(1, 0, 0), 240);
    assert_eq!(player.sector, 2, "{:?}", position(&player));
}

#[test]
fn a_closing_door_turns_back_rather_than_come_down_on_the_body() {
    let map = compiled(standard_movers());
    let map = map.tables();
    let mut world = TestWorld::start(&map);
    let mut player = at(&map, 0, 230.5, 128.5, EAST);
    play(&mut world, &map, &mut player, shoulders(), 1);
    assert_eq!(world.movers()[0].phase, Phase::Away);
    play(&mut world, &map, &mut player, Intent::default(), 56);
    assert_eq!(door_height(&world), 112);
    // Stand in the doorway while the door's wait runs out.
    let mut player = at(&world.map(&map), DOOR, 264.5, 128.5, EAST);
    let mut turned_back = false;
    for _ in 0..200 {
        let before = world.movers()[0].phase;
        play(&mut world, &map, &mut player, Intent::default(), 1);
        turned_back |= before == Phase::Back && world.movers()[0].phase == Phase::Away;
    }
    assert!(turned_back, "the door never turned back");
    // Never lower than the standing body needs: feet 0, eye 32, headroom 16.
    assert!(door_height(&world) >= 48);
    // Once the body leaves, the door closes.
    play(&mut world, &map, &mut player, walk(-1, 0, 0), 40);
    assert_eq!(player.sector, 0, "{:?}", position(&player));
    play(&mut world, &map, &mut player, Intent::default(), 200);
    assert_eq!(door_height(&world), 0);
}

#[test]
fn a_lift_goes_down_on_use_and_carries_the_body_up_to_the_ledge_height() {
    let map = compiled(standard_movers());
    let map = map.tables();
    let mut world = TestWorld::start(&map);
    // In the west room facing north, in front of the lift (its floor 64 up: a wall to the body).
    let mut player = at(&map, 0, 128.5, 40.5, NORTH);
    play(&mut world, &map, &mut player, walk(1, 0, 0), 60);
    assert_eq!(player.sector, 0, "the raised lift is a step too high");
    play(&mut world, &map, &mut player, shoulders(), 1);
    play(&mut world, &map, &mut player, Intent::default(), 32);
    assert_eq!(world.movers()[1].height, 0);
    // Onto the lowered lift, and wait there: it comes back up with the body on it.
    play(&mut world, &map, &mut player, walk(1, 0, 0), 20);
    assert_eq!(player.sector, LIFT, "{:?}", position(&player));
    play(&mut world, &map, &mut player, Intent::default(), 120);
    assert_eq!(world.movers()[1].height, 64);
    assert_eq!(player.feet_z.to_bits(), 64 * 256);
    assert!(player.on_ground);
    // And on to the ledge at the same height.
    play(&mut world, &map, &mut player, walk(1, 0, 0), 60);
    assert_eq!(player.sector, 4, "{:?}", position(&player));
}

#[test]
fn a_crusher_never_closes_on_the_body_and_a_platform_runs_for_ever() {
    let movers = vec![
        mover(DOOR, MOVER_CRUSHER, 8, 112, 112),
        mover(LIFT, portalcast_format::MOVER_PLATFORM, 0, 64, 64),
    ];
    let map = compiled(movers);
    let map = map.tables();
    let mut world = TestWorld::start(&map);
    // Stand in the crusher's sector.
    let mut player = at(&map, DOOR, 264.5, 128.5, NORTH);
    let (mut lowest, mut platform_low, mut platform_high) = (i32::MAX, false, false);
    for _ in 0..2000 {
        play(&mut world, &map, &mut player, Intent::default(), 1);
        lowest = lowest.min(world.movers()[0].height);
        platform_low |= world.movers()[1].height == 0;
        platform_high |= world.movers()[1].height == 64;
    }
    assert!(lowest >= 48, "the crusher came down to {lowest}");
    assert!(platform_low && platform_high);
    // Out of the way, the crusher closes down to its low height.
    let mut player = at(&map, 0, 100.5, 128.5, NORTH);
    let mut reached = false;
    for _ in 0..2000 {
        play(&mut world, &map, &mut player, Intent::default(), 1);
        reached |= world.movers()[0].height == 8;
    }
    assert!(reached);
}

fn light(sector: u16, kind: u8, low: u8, period: u16, tag: u16) -> Light {
    Light {
        sector,
        kind,
        low,
        period,
        tag,
    }
}

#[test]
fn a_glow_falls_to_its_low_level_and_back_each_period_and_a_strobe_flashes() {
    let glow = light(0, LIGHT_GLOW, 40, 120, 0);
    let levels: Vec<u8> = (0..=240).map(|tick| level(&glow, 200, tick)).collect();
    assert_eq!(
        (levels[0], levels[60], levels[120], levels[180]),
        (200, 40, 200, 40)
    );
    assert!(levels[..=60].windows(2).all(|w| w[1] <= w[0]));
    assert!(levels[60..=120].windows(2).all(|w| w[1] >= w[0]));
    // Evenly: no step larger than the range over the half period, rounded up.
    assert!(levels.windows(2).all(|w| w[0].abs_diff(w[1]) <= 3));
    let strobe = light(0, LIGHT_STROBE, 10, 40, 0);
    let flashes: Vec<bool> = (0..80)
        .map(|tick| level(&strobe, 180, tick) == 180)
        .collect();
    assert!(flashes[..5].iter().all(|&f| f) && flashes[5..40].iter().all(|&f| !f));
    assert_eq!(flashes[..40], flashes[40..]);
    assert!((0..80).all(|tick| [10, 180].contains(&level(&strobe, 180, tick))));
}

#[test]
fn a_flicker_is_low_about_one_slot_in_four_the_same_on_every_run_and_unlike_its_neighbour() {
    let flicker = light(3, LIGHT_FLICKER, 20, 4, 0);
    let slots: Vec<bool> = (0..4000)
        .step_by(4)
        .map(|tick| level(&flicker, 150, tick) == 20)
        .collect();
    let low = slots.iter().filter(|&&l| l).count();
    assert!((180..=320).contains(&low), "{low} of 1000 slots low");
    // Constant within a slot, only the two levels.
    assert!((0..4000).all(|tick| level(&flicker, 150, tick) == level(&flicker, 150, tick / 4 * 4)));
    assert!((0..4000).all(|tick| [20, 150].contains(&level(&flicker, 150, tick))));
    let neighbour = light(4, LIGHT_FLICKER, 20, 4, 0);
    let same = (0..4000)
        .step_by(4)
        .filter(|&tick| level(&flicker, 150, tick) == level(&neighbour, 150, tick))
        .count();
    assert!(
        same < 900,
        "two sectors flicker together in {same} of 1000 slots"
    );
}

#[test]
fn a_switched_light_turns_low_and_back_by_its_tag_and_the_others_follow_the_tick() {
    let mut map = compiled(vec![Mover {
        tag: 7,
        ..mover(DOOR, MOVER_DOOR, 0, 112, 0)
    }]);
    map.lights = vec![
        light(0, LIGHT_SWITCHED, 30, 0, 7),
        light(2, LIGHT_GLOW, 50, 60, 0),
    ];
    let map = map.tables();
    let high = |sector: usize| map.sectors[sector].light;
    let mut world = TestWorld::start(&map);
    assert!(world.is_live());
    assert_eq!(world.lights(&map).collect::<Vec<_>>(), [high(0), high(2)]);
    world.start_tag(&map, 7);
    assert_eq!(world.map(&map).sectors[0].light, 30);
    assert_eq!(
        world.movers()[0].phase,
        Phase::Away,
        "the tag starts the door too"
    );
    world.show(&map, 30);
    assert_eq!(world.lights(&map).collect::<Vec<_>>(), [30, 50]);
    world.start_tag(&map, 7);
    world.show(&map, 60);
    assert_eq!(world.lights(&map).collect::<Vec<_>>(), [high(0), high(2)]);
    // The cartridge's table keeps the drawn levels.
    assert_eq!(map.sectors[0].light, high(0));
}
