//! The player on the host at the extremes: corners, vertices, portal edges, wedges, steps,
//! ceilings, the jump, crouching, flying and falling. Every tick of every case is checked with
//! exact geometry (`common::player::check_tick`): the centre strictly inside its sector, its
//! path crossing no solid wall and no portal the body may not enter, the eye's room to floor
//! and ceiling, and the disc's clearance from solid walls.

mod common;

use common::player::*;
use portalcast::math::Fx24_8;
use portalcast::player::collide::RADIUS;
use portalcast::player::input::Intent;
use portalcast::player::vertical::{CROUCH_EYE, JUMP_RISE, JUMP_TICKS, STAND_EYE};
use portalcast::player::Player;
use portalcast_format::{MapTables, PlayerSize};
use portalcast_rom::demo;

fn bench() -> MapTables<'static> {
    demo::map_named("bench").expect("the bench map is shipped")
}

const BOX: &str = "
vertex a 0 0
vertex b 256 0
vertex c 256 256
vertex d 0 256
sector room floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall a b tex=brick
  wall b c tex=brick
  wall c d tex=brick
  wall d a tex=brick
player 128.5 128.5
";

#[test]
fn running_into_a_corner_stops_one_radius_from_both_walls() {
    let compiled = compile_map("box.map", BOX);
    let map = compiled.tables();
    // North-west at full speed, for long enough to press into the corner (0, 0).
    let mut player = at(&map, 0, 128.5, 128.5, NORTH_WEST);
    run(&mut player, &map, run_intent(1, 0), 200);
    let r = RADIUS * 256;
    assert_eq!(
        (player.position.x.to_bits(), player.position.y.to_bits()),
        (r, r),
        "the disc rests against both walls"
    );
    assert_eq!(player.velocity, (0, 0));
}

/// A 14° wedge: a triangle whose sharp corner the disc cannot reach.
const WEDGE: &str = "
vertex a 0 0
vertex b 512 0
vertex c 512 128
sector wedge floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall a b tex=brick
  wall b c tex=brick
  wall c a tex=brick
player 400.5 40.5
";

#[test]
fn full_speed_into_a_sharp_concave_corner_never_leaves_the_wedge() {
    let compiled = compile_map("wedge.map", WEDGE);
    let map = compiled.tables();
    // Along the wedge's bisector toward its tip (angle 180° + 7°).
    let toward_tip = 32768 + 1274;
    let mut player = at(&map, 0, 400.5, 50.0, toward_tip);
    run(&mut player, &map, run_intent(1, 0), 300);
    let (x, y) = position(&player);
    let clearance = [
        distance_to_segment((x, y), (0.0, 0.0), (512.0, 0.0)),
        distance_to_segment((x, y), (0.0, 0.0), (512.0, 128.0)),
    ];
    for d in clearance {
        assert!(
            d >= f64::from(RADIUS) - 1.0 / 16.0,
            "{clearance:?} at {x}, {y}"
        );
    }
    // Where the disc touches both walls: 16 / sin(7°) = 131 units from the tip.
    assert!((120.0..140.0).contains(&x), "stopped at {x}, {y}");
    // Sliding along one wall into the corner from off the bisector ends in the same place.
    let mut sliding = at(&map, 0, 300.5, 20.5, 32768 + 3000);
    run(&mut sliding, &map, run_intent(1, 0), 300);
    assert!(
        (position(&sliding).0 - x).abs() < 8.0,
        "{:?}",
        position(&sliding)
    );
}

/// A square room around a square pillar, in four convex sectors.
const PILLAR: &str = "
vertex a 0 0
vertex b 384 0
vertex c 384 384
vertex d 0 384
vertex e 128 128
vertex f 256 128
vertex g 256 256
vertex h 128 256
vertex i 0 128
vertex j 384 128
vertex k 384 256
vertex l 0 256
sector north floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall a b tex=brick
  wall b j tex=brick
  wall j f portal=east
  wall f e tex=stone
  wall e i portal=west
  wall i a tex=brick
sector east floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall f j portal=north
  wall j k tex=brick
  wall k g portal=south
  wall g f tex=stone
sector south floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall l h portal=west
  wall h g tex=stone
  wall g k portal=east
  wall k c tex=brick
  wall c d tex=brick
  wall d l tex=brick
sector west floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall i e portal=north
  wall e h tex=stone
  wall h l portal=south
  wall l i tex=brick
player 64.5 64.5
";

#[test]
fn head_on_into_a_vertex_stops_one_radius_from_it() {
    let compiled = compile_map("pillar.map", PILLAR);
    let map = compiled.tables();
    // Exactly along the diagonal through the pillar's corner (128, 128).
    let mut player = at(&map, 0, 64.5, 64.5, SOUTH_EAST);
    run(&mut player, &map, run_intent(1, 0), 200);
    let (x, y) = position(&player);
    let to_corner = ((128.0 - x).powi(2) + (128.0 - y).powi(2)).sqrt();
    assert!(
        (f64::from(RADIUS) - 1.0 / 16.0..f64::from(RADIUS) + 0.5).contains(&to_corner),
        "{to_corner} from the corner at {x}, {y}"
    );
}

#[test]
fn off_centre_onto_a_vertex_slides_around_the_pillar() {
    let compiled = compile_map("pillar.map", PILLAR);
    let map = compiled.tables();
    let east = sector_index_in(PILLAR, "east");
    let south = sector_index_in(PILLAR, "south");
    // Four units north of the diagonal through the corner: the disc glances off the vertex,
    // slides east along the pillar's north face and round its far corner.
    let mut player = at(&map, 0, 64.5, 60.5, SOUTH_EAST);
    run(&mut player, &map, run_intent(1, 0), 400);
    assert!(
        player.sector == east || player.sector == south,
        "ended in sector {} at {:?}",
        player.sector,
        position(&player)
    );
}

/// Two rooms with a 64-wide doorway in the wall between them.
const DOORWAY: &str = "
vertex a 0 0
vertex b 256 0
vertex c 256 96
vertex d 256 160
vertex e 256 256
vertex f 0 256
vertex g 512 0
vertex h 512 256
sector left floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall a b tex=brick
  wall b c tex=brick
  wall c d portal=right
  wall d e tex=brick
  wall e f tex=brick
  wall f a tex=brick
sector right floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall b g tex=brick
  wall g h tex=brick
  wall h e tex=brick
  wall e d tex=brick
  wall d c portal=left
  wall c b tex=brick
player 128.5 128.5
";

#[test]
fn sliding_along_a_wall_past_a_doorway_and_through_its_jamb() {
    let compiled = compile_map("doorway.map", DOORWAY);
    let map = compiled.tables();
    let right = sector_index_in(DOORWAY, "right");
    // North along the dividing wall, pressed against it (strafing right into it): the disc
    // slides along the wall, past the doorway's south jamb, and the strafe carries it through.
    let mut player = at(&map, 0, 200.5, 240.5, NORTH);
    let mut track = Vec::new();
    for _ in 0..120 {
        run(&mut player, &map, run_intent(1, 1), 1);
        track.push(position(&player));
    }
    let below_door: Vec<f64> = track
        .iter()
        .filter(|(_, y)| *y > 176.0)
        .map(|(x, _)| *x)
        .collect();
    assert!(below_door.iter().all(|&x| x <= 240.0), "{track:?}");
    assert!(below_door.contains(&240.0), "{track:?}");
    assert_eq!(player.sector, right, "{track:?}");
    // Diagonally at the doorway's north jamb (256, 96) from the north-west: the disc glances
    // off the wall and the jamb's vertex into the doorway and through.
    let mut jamb = at(&map, 0, 196.5, 36.5, SOUTH_EAST);
    run(&mut jamb, &map, walk(1, 0, 0), 200);
    assert_eq!(jamb.sector, right, "{:?}", position(&jamb));
    // East along y = 112: the disc just touches the north jamb (exactly one radius) and
    // passes undeflected. Half a unit further north it overlaps the jamb and is pushed south.
    let mut tangent = at(&map, 0, 100.5, 112.0, EAST);
    run(&mut tangent, &map, walk(1, 0, 0), 150);
    assert_eq!(tangent.sector, right);
    assert_eq!(position(&tangent).1, 112.0);
    let mut grazing = at(&map, 0, 100.5, 111.5, EAST);
    run(&mut grazing, &map, walk(1, 0, 0), 150);
    assert_eq!(grazing.sector, right);
    assert!(position(&grazing).1 > 111.5, "{:?}", position(&grazing));
}

#[test]
fn a_path_exactly_through_a_four_sector_vertex_is_tracked() {
    let map = bench();
    let hall_w = sector_index("bench.map", "hall_w");
    let hall_n = sector_index("bench.map", "hall_n");
    // (200, 312) to the north-east passes exactly through (256, 256), where hall_nw, hall_n,
    // the dais and hall_w meet.
    let mut player = at(&map, hall_w, 200.0, 312.0, NORTH_EAST);
    run(&mut player, &map, walk(1, 0, 0), 40);
    let (x, y) = position(&player);
    assert!(x > 256.0 && y < 256.0, "at {x}, {y}");
    assert_eq!(player.sector, hall_n);
}

#[test]
fn a_step_of_16_is_climbed_and_24_is_not() {
    let map = bench();
    let hall_s = sector_index("bench.map", "hall_s");
    let dais = sector_index("bench.map", "dais");
    // The dais is 16 up: walking north from the start climbs it.
    let mut player = Player::spawn(&map);
    run(&mut player, &map, walk(1, 0, 0), 90);
    assert_eq!(player.sector, dais);
    assert_eq!(player.eye_z(), Fx24_8::from_int(16 + STAND_EYE));
    // The ledge alcove is 24 up: walking back into it from under it stops at its edge.
    let mut blocked = at(&map, hall_s, 464.5, 700.5, NORTH);
    run(&mut blocked, &map, walk(-1, 0, 0), 120);
    assert_eq!(blocked.sector, hall_s);
    assert_eq!(blocked.position.y.to_bits(), (768 - RADIUS) * 256);
    assert_eq!(blocked.eye_z(), Fx24_8::from_int(STAND_EYE));
}

#[test]
fn a_jump_onto_the_24_ledge_lands_on_it_and_walking_off_falls_back() {
    let map = bench();
    let hall_s = sector_index("bench.map", "hall_s");
    let ledge = sector_index("bench.map", "ledge");
    let mut player = at(&map, hall_s, 464.5, 700.5, NORTH);
    run(&mut player, &map, walk(-1, 0, 0), 120);
    let jump_back = Intent {
        jump: true,
        ..walk(-1, 0, 0)
    };
    run(&mut player, &map, jump_back, 40);
    assert_eq!(player.sector, ledge);
    assert!(player.on_ground);
    assert_eq!(player.eye_z(), Fx24_8::from_int(24 + STAND_EYE));
    // Forward off the ledge: a drop of 24 is a fall, not a step.
    let mut airborne = false;
    for _ in 0..60 {
        run(&mut player, &map, walk(1, 0, 0), 1);
        airborne |= !player.on_ground;
    }
    assert!(airborne, "stepping off a 24 ledge falls");
    assert_eq!(player.sector, hall_s);
    assert!(player.on_ground);
    assert_eq!(player.eye_z(), Fx24_8::from_int(STAND_EYE));
}

#[test]
fn stepping_down_16_follows_the_floor_without_falling() {
    let map = bench();
    let dais = sector_index("bench.map", "dais");
    let hall_n = sector_index("bench.map", "hall_n");
    let mut player = at(&map, dais, 384.5, 300.5, NORTH);
    for _ in 0..60 {
        run(&mut player, &map, walk(1, 0, 0), 1);
        assert!(player.on_ground, "a 16 step down is not a fall");
    }
    assert_eq!(player.sector, hall_n);
    assert_eq!(player.eye_z(), Fx24_8::from_int(STAND_EYE));
}

#[test]
fn a_ceiling_too_low_blocks_standing_and_admits_crouching() {
    let map = bench();
    let hall_s = sector_index("bench.map", "hall_s");
    let crawl = sector_index("bench.map", "crawl");
    let den = sector_index("bench.map", "den");
    let mut player = at(&map, hall_s, 304.5, 700.5, NORTH);
    run(&mut player, &map, walk(-1, 0, 0), 120);
    assert_eq!(
        player.sector, hall_s,
        "standing, the eye would be 8 under the ceiling"
    );
    assert_eq!(player.position.y.to_bits(), (768 - RADIUS) * 256);
    let crouch_back = Intent {
        crouch: true,
        ..walk(-1, 0, 0)
    };
    run(&mut player, &map, crouch_back, 60);
    assert_eq!(player.sector, crawl);
    assert_eq!(player.eye_z(), Fx24_8::from_int(CROUCH_EYE));
    assert!(player.crouched());
    // Letting go of crouch under the 40-high ceiling: the eye rises only to 16 below it.
    run(&mut player, &map, Intent::default(), 30);
    assert_eq!(player.sector, crawl);
    assert_eq!(player.eye_z(), Fx24_8::from_int(40 - 16));
    // Crouched again, on through the crawl into the den, where the player stands up.
    run(&mut player, &map, crouch_back, 150);
    assert_eq!(player.sector, den);
    run(&mut player, &map, Intent::default(), 30);
    assert_eq!(player.eye_z(), Fx24_8::from_int(STAND_EYE));
}

#[test]
fn the_jump_is_a_parabola_whose_apex_is_exactly_48_above_the_floor() {
    let map = bench();
    let mut player = Player::spawn(&map);
    let floor = player.feet_z;
    let jump = Intent {
        jump: true,
        ..Intent::default()
    };
    let mut heights = Vec::new();
    for _ in 0..2 * JUMP_TICKS + 8 {
        run(&mut player, &map, jump, 1);
        heights.push((player.eye_z() - floor).to_bits());
    }
    let apex = (STAND_EYE + JUMP_RISE) * 256;
    assert_eq!(*heights.iter().max().unwrap(), apex);
    assert_eq!(heights[JUMP_TICKS as usize - 1], apex, "apex on tick 16");
    assert_eq!(
        heights.iter().filter(|&&h| h == apex).count(),
        1,
        "one apex tick"
    );
    // Constant second difference: the heights are a parabola.
    let rising: Vec<i32> = heights[..2 * JUMP_TICKS as usize].to_vec();
    let mut with_take_off = vec![STAND_EYE * 256];
    with_take_off.extend(&rising);
    let second: Vec<i32> = with_take_off
        .windows(3)
        .map(|w| w[2] - 2 * w[1] + w[0])
        .collect();
    assert!(second.windows(2).all(|w| w[0] == w[1]), "{second:?}");
    assert!(second[0] < 0);
    // Back on the floor on tick 32, and holding A does not jump again.
    assert_eq!(heights[2 * JUMP_TICKS as usize - 1], STAND_EYE * 256);
    assert!(heights[2 * JUMP_TICKS as usize..]
        .iter()
        .all(|&h| h == STAND_EYE * 256));
    assert!(player.on_ground);
}

#[test]
fn crouching_puts_the_eye_16_above_the_floor() {
    let map = bench();
    let mut player = Player::spawn(&map);
    let crouch = Intent {
        crouch: true,
        ..Intent::default()
    };
    run(&mut player, &map, crouch, 20);
    assert_eq!(player.eye_z() - player.feet_z, Fx24_8::from_int(CROUCH_EYE));
    run(&mut player, &map, Intent::default(), 20);
    assert_eq!(player.eye_z() - player.feet_z, Fx24_8::from_int(STAND_EYE));
}

#[test]
fn flying_keeps_the_eye_between_floor_and_ceiling_and_ends_in_a_fall() {
    let map = bench();
    let yard_s = sector_index("bench.map", "yard_s");
    let mut player = at(&map, yard_s, 384.5, -200.5, NORTH);
    run(
        &mut player,
        &map,
        Intent {
            toggle_fly: true,
            ..Intent::default()
        },
        1,
    );
    assert!(player.fly);
    let rise = Intent {
        jump: true,
        ..Intent::default()
    };
    run(&mut player, &map, rise, 200);
    let ceil = map.sectors[usize::from(yard_s)].ceil_z;
    assert_eq!(player.eye_z(), Fx24_8::from_int(ceil - 16));
    let sink = Intent {
        crouch: true,
        ..Intent::default()
    };
    run(&mut player, &map, sink, 200);
    assert_eq!(player.eye_z(), Fx24_8::from_int(STAND_EYE));
    run(&mut player, &map, rise, 20);
    assert!(player.eye_z() > Fx24_8::from_int(STAND_EYE + 32));
    run(
        &mut player,
        &map,
        Intent {
            toggle_fly: true,
            ..Intent::default()
        },
        1,
    );
    assert!(!player.fly && !player.on_ground);
    run(&mut player, &map, Intent::default(), 60);
    assert!(player.on_ground);
    assert_eq!(player.eye_z(), Fx24_8::from_int(STAND_EYE));
}

#[test]
fn looking_up_and_down_stays_within_the_limits_and_recentres() {
    let map = bench();
    let mut player = Player::spawn(&map);
    let look = |direction: i8| Intent {
        look: direction,
        ..Intent::default()
    };
    run(&mut player, &map, look(1), 100);
    assert_eq!(player.look_lines, portalcast::render::view::MAX_LOOK_LINES);
    run(&mut player, &map, look(-1), 200);
    assert_eq!(player.look_lines, -portalcast::render::view::MAX_LOOK_LINES);
    run(
        &mut player,
        &map,
        Intent {
            recentre: true,
            ..Intent::default()
        },
        1,
    );
    assert_eq!(player.look_lines, 0);
}

#[test]
fn turning_for_36_ticks_is_exactly_a_right_angle() {
    let map = bench();
    let mut player = Player::spawn(&map);
    let start = player.angle;
    run(&mut player, &map, walk(0, 0, 1), 36);
    assert_eq!(player.angle.to_bits(), start.to_bits().wrapping_add(16384));
}

/// Two cave cells of the generated `caves` map (issue 16), where the long soak found a disc
/// flying up beside a wall: the cell beyond the portal (ceiling 160) stops admitting the body
/// once its feet pass 112, and the disc, 0.3 unit from the portal's line, is 15.7 deep in it.
const CAVE_CORNER: &str = "
vertex a 1076 -8
vertex b 1176 -13
vertex c 1129 76
vertex d 1076 115
vertex e 1242 -2
vertex f 1248 77
sector cell floor=16 ceil=168 floor_tex=tiles ceil_tex=ceiling
  wall a b tex=brick
  wall b c portal=beyond lower=step upper=brick
  wall c d tex=brick
  wall d a tex=brick
sector beyond floor=24 ceil=160 floor_tex=tiles ceil_tex=ceiling
  wall b e tex=brick
  wall e f tex=brick
  wall f c tex=brick
  wall c b portal=cell
player 1100.5 50.5
";

#[test]
fn a_disc_pushed_out_of_a_portal_it_no_longer_fits_is_not_pushed_into_a_wall() {
    let compiled = compile_map("cave_corner.map", CAVE_CORNER);
    let map = compiled.tables();
    let cell = sector_index_in(CAVE_CORNER, "cell");
    let mut player = Player::spawn(&map);
    player.position = portalcast::math::WorldPoint::new(
        Fx24_8::from_bits(298_742), // 1166.9609375
        Fx24_8::from_bits(889),     // 3.47265625
    );
    player.sector = cell;
    player.velocity = (-128, 6);
    player.angle = portalcast::math::Angle::from_bits(48128);
    player.feet_z = Fx24_8::from_int(114);
    player.fly = true;
    player.on_ground = false;
    let before = player;
    // Forward, into the wall, and up: every push out of the portal pushes into the wall.
    player.tick(
        &Intent {
            forward: 1,
            jump: true,
            ..Intent::default()
        },
        &map,
    );
    check_tick(&map, &before, &player).unwrap_or_else(|problem| panic!("{problem}"));
    assert!(
        solid_overlap(&map, player.position) <= 1.0 / 32.0,
        "{player:?}"
    );
}

/// A room, a ledge 24 up under a ceiling 56 above it (Doom's body just fits), and beyond it a
/// nook one unit lower. `{size}` is the player line's body keys.
const LEDGE_AND_NOOK: &str = "
vertex a 0 0
vertex b 256 0
vertex c 256 256
vertex d 0 256
vertex e 384 0
vertex f 384 256
vertex g 512 0
vertex h 512 256
sector room floor=0 ceil=128 floor_tex=tiles ceil_tex=ceiling
  wall a b tex=brick
  wall b c portal=ledge lower=brick upper=brick
  wall c d tex=brick
  wall d a tex=brick
sector ledge floor=24 ceil=80 floor_tex=tiles ceil_tex=ceiling
  wall b e tex=brick
  wall e f portal=nook upper=brick
  wall f c tex=brick
  wall c b portal=room
sector nook floor=24 ceil=79 floor_tex=tiles ceil_tex=ceiling
  wall e g tex=brick
  wall g h tex=brick
  wall h f tex=brick
  wall f e portal=ledge upper=brick
player 128.5 128.5 {size}
";

fn ledge_and_nook(size: &str) -> portalcast_assets::CompiledMap {
    compile_map("ledge.map", &LEDGE_AND_NOOK.replace("{size}", size))
}

#[test]
fn the_maps_body_decides_the_step_and_the_headroom() {
    // The native body (eye 32, height 48, step 16) stops at the ledge's 24 step.
    let native = ledge_and_nook("");
    let map = native.tables();
    assert_eq!(map.player_start.size, PlayerSize::NATIVE);
    let mut player = Player::spawn(&map);
    assert_eq!(player.eye_z(), Fx24_8::from_int(STAND_EYE));
    run(&mut player, &map, walk(1, 0, 0), 120);
    assert_eq!(player.sector, 0);
    assert_eq!(player.position.x.to_bits(), (256 - RADIUS) * 256);

    // Doom's body (eye 41, height 56, step 24) climbs it, stands at full height under the
    // ceiling 56 above the ledge, and stops at the nook, whose 55 leave its eye 14 of the 15
    // it keeps.
    let doom = ledge_and_nook("eye=41 height=56 step=24");
    let map = doom.tables();
    assert_eq!(map.player_start.size, PlayerSize::DOOM);
    let mut player = Player::spawn(&map);
    assert_eq!(player.eye_z(), Fx24_8::from_int(41));
    run(&mut player, &map, walk(1, 0, 0), 120);
    assert_eq!(player.sector, 1);
    assert_eq!(player.eye_z(), Fx24_8::from_int(24 + 41));
    assert!(!player.crouched());
    assert_eq!(player.position.x.to_bits(), (384 - RADIUS) * 256);

    // Crouched, it fits under the nook's ceiling and goes in.
    let crouch = Intent {
        crouch: true,
        ..walk(1, 0, 0)
    };
    run(&mut player, &map, crouch, 120);
    assert_eq!(player.sector, 2);
    assert!(player.crouched());

    // The body's height counts, not only its eye: eye 32 in a body of 57 may climb the step
    // but does not fit the ledge's 56, standing (it enters only by walking, not crouched).
    let tall = ledge_and_nook("height=57 step=24");
    let map = tall.tables();
    let mut player = Player::spawn(&map);
    run(&mut player, &map, walk(1, 0, 0), 120);
    assert_eq!(player.sector, 0);
    assert_eq!(player.position.x.to_bits(), (256 - RADIUS) * 256);
}

fn slopes() -> MapTables<'static> {
    demo::map_named("slopes").expect("the slopes map is shipped")
}

/// The floor under the player, in 24.8 bits.
fn floor_under(map: &MapTables, player: &Player) -> i32 {
    map.heights_fx8_at(
        &map.sectors[usize::from(player.sector)],
        player.position.x.to_bits(),
        player.position.y.to_bits(),
    )
    .0
}

#[test]
fn walking_up_and_down_the_ramp_stays_on_its_floor_every_tick() {
    let map = slopes();
    let hall = sector_index("slopes.map", "hall");
    let ramp = sector_index("slopes.map", "ramp");
    let landing = sector_index("slopes.map", "landing");
    // From the hall east up the ramp (64 over 256 units) onto the landing: on the ground every
    // tick, the feet on the floor under the centre, never lower than the tick before.
    let mut player = at(&map, hall, 128.5, 128.5, EAST);
    let mut sectors = Vec::new();
    // Until well onto the landing (the bridge lies beyond it).
    while player.position.x < Fx24_8::from_int(560) {
        assert!(sectors.len() <= 3);
        let before = player.feet_z;
        run(&mut player, &map, walk(1, 0, 0), 1);
        assert!(player.on_ground, "walking up a ramp is not a jump");
        assert_eq!(player.feet_z.to_bits(), floor_under(&map, &player));
        assert!(player.feet_z >= before, "the feet only rise going up");
        if sectors.last() != Some(&player.sector) {
            sectors.push(player.sector);
        }
    }
    assert_eq!(sectors, [hall, ramp, landing]);
    assert_eq!(player.feet_z, Fx24_8::from_int(64));
    // And back down: no fall, no jitter (the feet never rise), down to the hall's floor.
    player.angle = portalcast::math::Angle::from_bits(WEST);
    for _ in 0..200 {
        let before = player.feet_z;
        run(&mut player, &map, walk(1, 0, 0), 1);
        assert!(player.on_ground, "walking down a ramp is not a fall");
        assert_eq!(player.feet_z.to_bits(), floor_under(&map, &player));
        assert!(player.feet_z <= before, "the feet only fall going down");
    }
    assert_eq!(player.sector, hall);
    assert_eq!(player.feet_z, Fx24_8::ZERO);
}

/// A flat room beside a sloped one whose floor along their shared portal rises from 0 at the
/// south end to 32 at the north end: the native body (step 16) crosses where the edge is low
/// and is stopped where it is high.
const SLOPED_STEP: &str = "
vertex a 0 0
vertex b 256 0
vertex c 256 256
vertex d 0 256
vertex e 512 0
vertex f 512 256
sector flat floor=0 ceil=192 floor_tex=tiles ceil_tex=ceiling
  wall a b tex=brick
  wall b c portal=bank lower=step
  wall c d tex=brick
  wall d a tex=brick
sector bank floor_slope=b:32,c:0,f:0 ceil=192 floor_tex=grass ceil_tex=ceiling
  wall b e tex=brick
  wall e f tex=brick
  wall f c tex=brick
  wall c b portal=flat
player 128.5 128.5
";

#[test]
fn a_sloped_step_is_climbed_where_it_is_at_most_16_and_blocks_where_higher() {
    let compiled = compile_map("sloped_step.map", SLOPED_STEP);
    let map = compiled.tables();
    // Near the south end the edge is 4 high: walking east crosses onto the bank.
    let mut low = at(&map, 0, 200.5, 224.5, EAST);
    run(&mut low, &map, walk(1, 0, 0), 60);
    assert_eq!(low.sector, 1, "the low end of the sloped step is climbed");
    assert_eq!(low.feet_z.to_bits(), floor_under(&map, &low));
    // Near the north end it is 28 high: walking east stops at the portal.
    let mut high = at(&map, 0, 200.5, 32.5, EAST);
    run(&mut high, &map, walk(1, 0, 0), 60);
    assert_eq!(high.sector, 0, "the high end of the sloped step blocks");
    assert_eq!(high.feet_z, Fx24_8::ZERO);
}

/// Runs `intent` until the player's sector is `target` or `ticks` pass, checking every tick
/// and noting each sector entered, in order.
fn run_until(
    player: &mut Player,
    map: &MapTables,
    intent: Intent,
    target: u16,
    ticks: u32,
    sectors: &mut Vec<u16>,
) {
    for _ in 0..ticks {
        run(player, map, intent, 1);
        if sectors.last() != Some(&player.sector) {
            sectors.push(player.sector);
        }
        if player.sector == target {
            return;
        }
    }
    panic!("never reached sector {target}: went through {sectors:?}");
}

#[test]
fn crossing_the_bridge_then_walking_down_and_under_it_tracks_both_layers() {
    let map = slopes();
    let name = |name: &str| sector_index("slopes.map", name);
    let (landing, deck, east_ledge) = (name("landing"), name("deck"), name("east_ledge"));
    let (step8, tunnel, south_pit) = (name("step8"), name("tunnel"), name("south_pit"));
    let (walkway, north_pit) = (name("walkway"), name("north_pit"));
    // Over the bridge: from the landing east across the deck (layer 1) onto the east ledge,
    // on the ground at the deck's height every tick (the pit's open ceiling under the deck's
    // sides is never fallen through).
    let mut player = at(&map, landing, 600.5, 128.5, EAST);
    let mut sectors = vec![landing];
    while player.sector != east_ledge {
        assert!(sectors.len() <= 3 && player.position.x < Fx24_8::from_int(900));
        run(&mut player, &map, walk(1, 0, 0), 1);
        assert!(player.on_ground);
        assert_eq!(
            player.feet_z,
            Fx24_8::from_int(64),
            "the deck holds the body"
        );
        if sectors.last() != Some(&player.sector) {
            sectors.push(player.sector);
        }
    }
    assert_eq!(sectors, [landing, deck, east_ledge]);
    run(&mut player, &map, walk(1, 0, 0), 8);
    // Down the stairs south to the wide bottom step, then west into the tunnel.
    player.angle = portalcast::math::Angle::from_bits(SOUTH);
    player.velocity = (0, 0);
    run_until(&mut player, &map, walk(1, 0, 0), step8, 400, &mut sectors);
    assert_eq!(player.feet_z, Fx24_8::from_int(-64));
    run(&mut player, &map, walk(1, 0, 0), 40);
    player.angle = portalcast::math::Angle::from_bits(WEST);
    run_until(&mut player, &map, walk(1, 0, 0), tunnel, 400, &mut sectors);
    // North along the canyon's floor, under the deck and out the other side.
    run(&mut player, &map, walk(1, 0, 0), 24);
    player.angle = portalcast::math::Angle::from_bits(NORTH);
    player.velocity = (0, 0);
    run_until(&mut player, &map, walk(1, 0, 0), walkway, 400, &mut sectors);
    // Under the bridge: the deck's outline holds the body too, a layer up.
    let deck_outline = sector_polygon(&map, deck);
    assert_eq!(
        portalcast::math::point_in_convex_polygon(&deck_outline, player.position),
        portalcast::math::Containment::Inside
    );
    assert_eq!((player.sector, player.eye_sector()), (walkway, walkway));
    assert_eq!(player.feet_z, Fx24_8::from_int(-64));
    run_until(
        &mut player,
        &map,
        walk(1, 0, 0),
        north_pit,
        200,
        &mut sectors,
    );
    assert!(sectors.contains(&south_pit));
    assert!(sectors.ends_with(&[tunnel, south_pit, walkway, north_pit]));
}

#[test]
fn walking_off_the_landing_falls_through_the_open_floor_and_flying_rises_through_the_ceiling() {
    let map = slopes();
    let name = |name: &str| sector_index("slopes.map", name);
    let (landing, north_air, north_pit) = (name("landing"), name("north_air"), name("north_pit"));
    // East off the landing into the air over the pit: the air's floor is open, so the body
    // falls; its sector is the pit once the feet pass the link at 64, the air before.
    let mut player = at(&map, landing, 600.5, 48.5, EAST);
    let mut sectors = vec![landing];
    let mut fell = false;
    for _ in 0..120 {
        run(&mut player, &map, walk(1, 0, 0), 1);
        let expected = if player.position.x.to_bits() < 640 * 256 {
            landing
        } else if player.feet_z >= Fx24_8::from_int(64) {
            north_air
        } else {
            north_pit
        };
        assert_eq!(player.sector, expected, "{player:?}");
        fell |= !player.on_ground;
        if sectors.last() != Some(&player.sector) {
            sectors.push(player.sector);
        }
    }
    assert!(fell, "stepping into the open air is a fall");
    assert_eq!(sectors, [landing, north_air, north_pit]);
    assert!(player.on_ground);
    assert_eq!(player.feet_z, Fx24_8::from_int(-64), "on the pit's floor");
    assert_eq!(player.eye_sector(), north_pit);
    // Flying straight up: the eye passes the link first, then the feet.
    player.toggle_fly();
    let rise = Intent {
        jump: true,
        ..Intent::default()
    };
    let mut eye_crossed_first = false;
    for _ in 0..200 {
        run(&mut player, &map, rise, 1);
        let eye_above = player.eye_z() >= Fx24_8::from_int(64);
        let feet_above = player.feet_z >= Fx24_8::from_int(64);
        assert_eq!(player.eye_sector() == north_air, eye_above, "{player:?}");
        assert_eq!(player.sector == north_air, feet_above, "{player:?}");
        eye_crossed_first |= eye_above && !feet_above;
    }
    assert!(eye_crossed_first);
    assert_eq!(
        player.sector, north_air,
        "flown up through the open ceiling"
    );
    assert!(player.feet_z > Fx24_8::from_int(64));
}
