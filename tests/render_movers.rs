//! The bench map's movers mid-motion against the f64 oracle (issue 18): the corridor's door
//! half open and the lift half way down, seen from the sides a player sees them from, at every
//! resolution. The engine and the oracle draw the same live tables (`World::map`); the bounds are
//! the accuracy targets: at most 0.5 % of pixels on another surface and no missed sector. And the
//! bench's switch, thrown, shows its used texture in both.

use portalcast::frame::Resolution;
use portalcast::math::{Angle, Fx24_8, WorldPoint};
use portalcast::player::Player;
use portalcast::render::surface::Surface;
use portalcast::render::view::{Camera, Settings};
use portalcast::render::walk::Renderer;
use portalcast::world::Phase;
use portalcast_format::{MapTables, MOVER_DOOR, MOVER_LIFT, TRIGGER_SWITCH};
use portalcast_oracle::compare_with_engine;
use portalcast_rom::assets;
use portalcast_rom::demo::render_assets;
use portalcast_rom::game::GameWorld;

const SURFACE_MISMATCH_MAX_PERCENT: f64 = 0.5;

fn bench() -> &'static MapTables<'static> {
    assets::MAPS
        .iter()
        .find(|map| map.name == "bench")
        .expect("the bench map")
}

/// Index of the sector that strictly contains `(x, y)`.
fn sector_at(map: &MapTables, x: i32, y: i32) -> u16 {
    let p = WorldPoint::from_int(x, y);
    (0..map.sectors.len() as u16)
        .find(|&s| {
            portalcast::player::collide::strictly_inside(map, &map.sectors[usize::from(s)], p)
        })
        .unwrap_or_else(|| panic!("no sector at ({x}, {y})"))
}

/// The bench's world with its door (`kind`) started and run until the moving plane is half
/// way, the player far off (at the start).
fn half_way(map: &MapTables, kind: u8) -> GameWorld {
    let index = map
        .movers
        .iter()
        .position(|m| m.kind == kind)
        .expect("the bench has this mover");
    let mover = map.movers[index];
    let mut world = GameWorld::start(map);
    let player = Player::spawn(map);
    match kind {
        MOVER_DOOR => world.start_tag(map, mover.tag),
        _ => world.use_mover(map, index),
    }
    let middle = (mover.low + mover.high) / 2;
    for _ in 0..1000 {
        if world.movers()[index].height == middle {
            break;
        }
        world.tick(map, &player);
    }
    assert_eq!(world.movers()[index].height, middle);
    assert_eq!(world.movers()[index].phase, Phase::Away);
    world
}

fn check(map: &MapTables, world: &GameWorld, views: &[(i32, i32, u16)]) {
    let live = world.map(map);
    let render_assets = render_assets();
    let mut renderer = Renderer::new();
    for &(x, y, angle) in views {
        let sector = sector_at(&live, x, y);
        let camera = Camera {
            position: WorldPoint::from_int(x, y),
            eye_z: Fx24_8::from_int(live.sectors[usize::from(sector)].floor_z + 32),
            angle: Angle::from_bits(angle),
            sector,
            look_lines: 0,
        };
        for resolution in Resolution::ALL {
            let settings = Settings {
                resolution,
                ..Settings::DEFAULT
            };
            let run =
                compare_with_engine(&mut renderer, &live, &render_assets, &camera, &settings, 0);
            let percent = run.comparison.surface_mismatch_percent();
            assert!(
                percent <= SURFACE_MISMATCH_MAX_PERCENT,
                "({x}, {y}) angle {angle} at {resolution:?}: {percent:.3} % of pixels on another surface"
            );
            assert!(
                run.comparison.missed_sectors.is_empty(),
                "({x}, {y}) angle {angle} at {resolution:?}: missed {:?}",
                run.comparison.missed_sectors
            );
        }
    }
}

#[test]
fn a_half_open_door_matches_the_oracle() {
    let map = bench();
    let world = half_way(map, MOVER_DOOR);
    // From the hall, square on and at an angle; from the corridor, looking back.
    check(
        map,
        &world,
        &[
            (700, 384, 0),
            (640, 300, 3000),
            (900, 384, 32768),
            (1000, 370, 31000),
        ],
    );
}

#[test]
fn a_lift_half_way_down_matches_the_oracle() {
    let map = bench();
    let world = half_way(map, MOVER_LIFT);
    // From the lower landing looking east at it, from the upper landing looking down on it,
    // from on the stairs.
    check(
        map,
        &world,
        &[
            (1850, 400, 0),
            (1850, 0, 4000),
            (1850, 200, 60000),
            (2000, 200, 32768),
        ],
    );
}

#[test]
fn a_thrown_switch_shows_its_used_texture_in_the_engine_and_the_oracle() {
    let map = bench();
    let switch = map
        .triggers
        .iter()
        .find(|t| t.kind == TRIGGER_SWITCH)
        .expect("the bench has a switch");
    let wall = &map.walls[usize::from(switch.wall)];
    assert_ne!(wall.texture, switch.used_texture);
    let render_assets = render_assets();
    let mut renderer = Renderer::new();
    // In the hall, facing the switch on its east wall.
    let camera = Camera {
        position: WorldPoint::from_int(700, 304),
        eye_z: Fx24_8::from_int(map.sectors[usize::from(sector_at(map, 700, 304))].floor_z + 32),
        angle: Angle::from_bits(0),
        sector: sector_at(map, 700, 304),
        look_lines: 0,
    };
    let settings = Settings::DEFAULT;
    let mut world = GameWorld::start(map);
    let mut frame = |thrown: bool| {
        world.set_thrown(&[thrown]);
        let live = world.map(map);
        assert_eq!(
            live.solid_texture(switch.wall, wall),
            if thrown {
                switch.used_texture
            } else {
                wall.texture
            }
        );
        compare_with_engine(&mut renderer, &live, &render_assets, &camera, &settings, 0)
    };
    let at_rest = frame(false);
    let thrown = frame(true);
    let on_switch = Surface::Wall(switch.wall);
    let switch_pixels = thrown
        .engine
        .surfaces
        .iter()
        .filter(|&&s| s == on_switch)
        .count();
    assert!(
        switch_pixels > 1000,
        "the switch covers {switch_pixels} pixels"
    );
    // The two frames differ on the switch, and only there.
    let changed: Vec<usize> = (0..thrown.engine.indices.len())
        .filter(|&i| thrown.engine.indices[i] != at_rest.engine.indices[i])
        .collect();
    assert!(
        changed.len() * 2 > switch_pixels,
        "{} pixels changed",
        changed.len()
    );
    assert!(changed
        .iter()
        .all(|&i| thrown.engine.surfaces[i] == on_switch));
    // The oracle draws the used texture too: the texels agree as well as they do at rest.
    for run in [&at_rest, &thrown] {
        let percent = run.comparison.texel_mismatches as f64 * 100.0 / run.comparison.pixels as f64;
        assert!(percent < 2.0, "{percent:.2} % of pixels with another texel");
    }
}
