//! The benchmark's fly-through on every shipped map: every pose strictly inside the sector it
//! claims (checked with the polygon test, not the flight's own), the eye between floor and
//! ceiling, smooth motion, and a path that sees much of the map.

mod common;

use std::collections::BTreeSet;

use portalcast::math::{point_in_convex_polygon, Containment, WorldPoint};
use portalcast_rom::assets::MAPS;
use portalcast_rom::bench::FRAMES_PER_SETTING;
use portalcast_rom::flight::{Flight, MAX_TURN_PER_FRAME, SPEED};

/// Frames checked per map: many tours' worth on the shipped maps.
const CHECKED_FRAMES: usize = 20_000;

#[test]
fn every_pose_is_strictly_inside_its_sector_on_every_shipped_map() {
    for map in MAPS {
        let mut previous: Option<portalcast::render::view::Camera> = None;
        let mut seen = BTreeSet::new();
        for (frame, camera) in Flight::new(map).take(CHECKED_FRAMES).enumerate() {
            let sector = &map.sectors[usize::from(camera.sector)];
            let polygon: Vec<WorldPoint> = map
                .sector_walls(sector)
                .iter()
                .map(|wall| {
                    let v = map.vertices[usize::from(wall.start)];
                    WorldPoint::from_int(v.x, v.y)
                })
                .collect();
            assert_eq!(
                point_in_convex_polygon(&polygon, camera.position),
                Containment::Inside,
                "{} frame {frame}: {camera:?} is not strictly inside sector {}",
                map.name,
                camera.sector
            );
            let eye = camera.eye_z.to_bits();
            assert!(
                eye > sector.floor_z * 256 && eye < sector.ceil_z * 256,
                "{} frame {frame}: eye {} outside {}..{}",
                map.name,
                camera.eye_z,
                sector.floor_z,
                sector.ceil_z
            );
            if let Some(before) = previous {
                let dx = f64::from(camera.position.x.to_bits() - before.position.x.to_bits());
                let dy = f64::from(camera.position.y.to_bits() - before.position.y.to_bits());
                let moved = (dx * dx + dy * dy).sqrt() / 256.0;
                assert!(
                    moved <= f64::from(SPEED) + 1.0,
                    "{} frame {frame}: jumped {moved}",
                    map.name
                );
                let turned = camera.angle.wrapping_sub(before.angle).to_bits() as i16;
                assert!(
                    i32::from(turned).abs() <= MAX_TURN_PER_FRAME,
                    "{} frame {frame}: turned {turned}",
                    map.name
                );
            }
            if frame < FRAMES_PER_SETTING as usize {
                seen.insert(camera.sector);
            }
            previous = Some(camera);
        }
        println!(
            "{}: the first {FRAMES_PER_SETTING} frames pass through {} of {} sectors: {seen:?}",
            map.name,
            seen.len(),
            map.sectors.len()
        );
        assert!(
            seen.len() >= 4.min(map.sectors.len()),
            "{}: the benchmark's frames stay in {seen:?}",
            map.name
        );
    }
}

#[test]
fn the_flight_is_the_same_every_time() {
    for map in MAPS {
        let first: Vec<_> = Flight::new(map).take(500).collect();
        let second: Vec<_> = Flight::new(map).take(500).collect();
        assert_eq!(first, second, "{}", map.name);
        assert_eq!(
            first[0].position,
            WorldPoint::new(
                portalcast::math::Fx24_8::from_bits(map.player_start.x_fx8),
                portalcast::math::Fx24_8::from_bits(map.player_start.y_fx8)
            )
        );
    }
}

#[test]
fn the_slopes_map_s_benchmark_frames_pass_over_and_under_the_bridge() {
    let map = portalcast_rom::demo::map_named("slopes").expect("the slopes map is shipped");
    let name = |name: &str| common::player::sector_index("slopes.map", name);
    let seen: BTreeSet<u16> = Flight::new(&map)
        .take(portalcast_rom::bench::frames_for(&map) as usize)
        .map(|camera| camera.sector)
        .collect();
    for sector in [
        "deck",
        "walkway",
        "north_air",
        "north_pit",
        "attic",
        "bank",
        "ramp",
    ] {
        assert!(
            seen.contains(&name(sector)),
            "the slopes map's benchmark frames never enter {sector}: {seen:?}"
        );
    }
}
