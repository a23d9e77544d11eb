//! Freedoom's maps imported from their WADs (issue 19: `portalcast_assets::doom::compile_wad`,
//! what `PORTALCAST_ASSETS=….wad cargo rom` builds) rendered by the engine against the f64
//! oracle: the start pose and sampled poses, every resolution. Bounds as for the shipped maps
//! (`tests/render_oracle.rs`): at most 0.5 % of pixels on a different surface, no hole, no
//! missed sector.

mod common;

use std::collections::BTreeMap;

use portalcast::frame::Resolution;
use portalcast::math::{Angle, Fx24_8, WorldPoint};
use portalcast::render::view::{Camera, Settings};
use portalcast::render::walk::Renderer;
use portalcast_oracle::compare_with_engine;
use portalcast_rom::flight::eye_z;

use portalcast_xtask::freedoom::MAPS;
/// Sampled poses a map (besides the start).
const POSES_PER_MAP: usize = 12;
const SURFACE_MISMATCH_MAX_PERCENT: f64 = 0.5;

#[test]
fn freedoom_maps_match_the_oracle_from_their_starts_and_sampled_poses() {
    let compiled = common::freedoom_assets();
    let host = common::HostAssets::of(compiled);
    let assets = host.render();
    let mut renderer = Renderer::new();
    let mut failures = Vec::new();
    // Per map: frames, worst and summed surface mismatch %, holes, frames missing a sector.
    let mut figures: BTreeMap<&str, (usize, f64, f64, usize, usize)> = BTreeMap::new();
    for name in MAPS {
        let map = compiled.map(name).expect("the map was built");
        let start = map.player_start;
        let position = WorldPoint::new(
            Fx24_8::from_bits(start.x_fx8),
            Fx24_8::from_bits(start.y_fx8),
        );
        let mut cameras = vec![Camera {
            position,
            eye_z: eye_z(&map, &map.sectors[usize::from(start.sector)], position),
            angle: Angle::from_bits(start.angle),
            sector: start.sector,
            look_lines: 0,
        }];
        cameras.extend(
            portalcast_oracle::sample_poses(&map, POSES_PER_MAP, 19)
                .iter()
                .map(common::cameras_of_pose)
                .map(|(camera, _)| camera),
        );
        for (index, camera) in cameras.iter().enumerate() {
            for resolution in Resolution::ALL {
                let settings = Settings {
                    resolution,
                    ..Settings::DEFAULT
                };
                let run = compare_with_engine(&mut renderer, &map, &assets, camera, &settings, 0);
                let percent = run.comparison.surface_mismatch_percent();
                let missed = &run.comparison.missed_sectors;
                let entry = figures.entry(name).or_default();
                entry.0 += 1;
                entry.1 = entry.1.max(percent);
                entry.2 += percent;
                entry.3 += run.comparison.holes;
                entry.4 += usize::from(!missed.is_empty());
                if percent > SURFACE_MISMATCH_MAX_PERCENT
                    || run.comparison.holes > 0
                    || !missed.is_empty()
                {
                    let png = common::screenshot_dir()
                        .join(format!("doom-{name}-{index}-{}.png", resolution.label()));
                    portalcast_oracle::write_diff_png(&run.engine.surfaces, &run.oracle, &png)
                        .expect("writing the diff");
                    failures.push(format!(
                        "{name} pose {index} {} ({camera:?}): {:?}; diff: {}",
                        resolution.label(),
                        run.comparison,
                        png.display()
                    ));
                }
            }
        }
    }
    // The lines `cargo bench-report` reads for docs/BENCH.md's Freedoom section.
    for (name, (frames, worst, sum, holes, missed)) in &figures {
        println!(
            "doom-accuracy map={name} frames={frames} worst={worst:.3} mean={:.3} holes={holes} missed={missed}",
            sum / *frames as f64
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Doom's remote doors and lifts (issue 19): each walk-over line crossed starts every mover of
/// its tag (a door opens, a lift goes down), each switch's tag names movers and a switch
/// whose texture has an `SW1`/`SW2` twin shows the twin once used; movers that no line here
/// starts are left to the use button.
#[test]
fn freedoom_s_remote_doors_and_lifts_start_from_their_lines_and_switches() {
    use portalcast_format::{MOVER_DOOR, MOVER_LIFT, MOVER_ON_USE, TRIGGER_LINE, TRIGGER_SWITCH};
    let compiled = common::freedoom_assets();
    let (mut lines_crossed, mut switches_swapping) = (0, 0);
    for name in MAPS {
        let map = compiled.map(name).expect("the map was built");
        let count = |kind: u8, by_use: bool| {
            map.movers
                .iter()
                .filter(|m| m.kind == kind && (m.flags & MOVER_ON_USE != 0) == by_use)
                .count()
        };
        let triggers = |kind: u8| map.triggers.iter().filter(|t| t.kind == kind).count();
        println!(
            "{name}: doors {} by use, {} by lines; lifts {} by use, {} by lines; {} switches, {} walk-over lines",
            count(MOVER_DOOR, true),
            count(MOVER_DOOR, false),
            count(MOVER_LIFT, true),
            count(MOVER_LIFT, false),
            triggers(TRIGGER_SWITCH),
            triggers(TRIGGER_LINE)
        );
        for trigger in map.triggers {
            let tagged: Vec<usize> = (0..map.movers.len())
                .filter(|&index| map.movers[index].tag == trigger.tag)
                .collect();
            assert!(!tagged.is_empty(), "{name}: {trigger:?} starts nothing");
            for &index in &tagged {
                assert_eq!(
                    map.movers[index].flags & MOVER_ON_USE,
                    0,
                    "{name}: a mover some line starts is locked"
                );
            }
            let wall = &map.walls[usize::from(trigger.wall)];
            if trigger.kind == TRIGGER_SWITCH {
                assert!(wall.neighbour().is_none(), "{name}: a switch on a portal");
                switches_swapping += usize::from(trigger.used_texture != wall.texture);
                continue;
            }
            let sector = map
                .sectors
                .iter()
                .position(|s| {
                    (usize::from(s.first_wall)..usize::from(s.first_wall + s.wall_count))
                        .contains(&usize::from(trigger.wall))
                })
                .expect("the line's sector") as u16;
            let mut world = Box::new(common::HostWorld::start(&map));
            let player = portalcast::player::Player::spawn(&map);
            world.crossed(&map, sector, wall.portal);
            for _ in 0..20 {
                world.tick(&map, &player);
            }
            for &index in &tagged {
                let mover = &map.movers[index];
                assert_ne!(
                    world.movers()[index].height,
                    mover.start,
                    "{name}: crossing {trigger:?} left mover {index} ({mover:?}) at rest"
                );
            }
            lines_crossed += 1;
        }
    }
    println!("{lines_crossed} walk-over lines crossed, {switches_swapping} switches swap texture");
    assert!(lines_crossed > 0 && switches_swapping > 0);
}

/// Doom's things (issue 19): each map's things of medium skill that portalcast knows and that
/// fit their piece (moved by up to 16 units to fit it), with sprite sets composed from the WAD's sprite lumps: a monster still in
/// eight rotations, an item's frames in Doom's order, decorations solid as Doom's block. And
/// the middle textures of two-sided lines (grates, bars) as portal middles, composed from the
/// WAD's wall textures (transparent where no patch draws), blocking where Doom's line blocks.
#[test]
fn freedoom_s_things_come_with_their_sprites_from_the_wad() {
    use portalcast_format::{NO_TEXTURE, THING_HANGING, THING_SOLID, WALL_MIDDLE_BLOCKS};
    let compiled = common::freedoom_assets();
    let sets = compiled.sprite_sets();
    let set = |name: &str| {
        sets.iter()
            .position(|set| set.name == name)
            .unwrap_or_else(|| panic!("no set {name}"))
    };
    let zombie = &sets[set("poss_a")];
    assert_eq!((zombie.frames, zombie.rotations), (1, 8));
    let image = &compiled.sprites()[usize::from(zombie.first)];
    assert!(
        (30..=64).contains(&image.width) && (50..=64).contains(&image.height),
        "a zombieman's canvas is {}x{}",
        image.width,
        image.height
    );
    let barrel = set("bar1_ab");
    assert_eq!((sets[barrel].frames, sets[barrel].rotations), (2, 1));
    for name in MAPS {
        let map = compiled.map(name).expect("the map was built");
        let of = |index: usize| {
            map.things
                .iter()
                .filter(move |t| usize::from(t.sprite) == index)
        };
        println!(
            "{name}: {} things, {} solid, {} hanging",
            map.things.len(),
            map.things
                .iter()
                .filter(|t| t.flags & THING_SOLID != 0)
                .count(),
            map.things
                .iter()
                .filter(|t| t.flags & THING_HANGING != 0)
                .count()
        );
        let middles = map.walls.iter().filter(|w| w.middle != NO_TEXTURE);
        println!(
            "{name}: {} walls with a middle texture ({} blocking)",
            middles.clone().count(),
            middles
                .filter(|w| w.flags & WALL_MIDDLE_BLOCKS != 0)
                .count()
        );
        assert!(
            map.things.len() >= 100,
            "{name}: {} things",
            map.things.len()
        );
        assert!(of(barrel).all(|t| t.flags & THING_SOLID != 0));
    }
    assert!(compiled
        .import_report()
        .iter()
        .any(|line| line.contains("things do not fit their piece")));
    // Most of those near a cut are moved to fit rather than left out.
    assert!(compiled
        .import_report()
        .iter()
        .any(|line| line.starts_with("E1M1: ") && line.contains("things moved by up to 16 units")));
    let bars = &sets[set("mid_midbars3")];
    assert_eq!((bars.frames, bars.rotations), (1, 1));
    let image = &compiled.sprites()[usize::from(bars.first)];
    assert_eq!((image.width, image.height), (64, 72));
}

/// Every portal middle of the Freedoom maps (Doom's grates and bars), seen from 60 units in
/// front of it on each side, at 240×160: none is left out for want of room and every frame
/// meets the oracle's bounds. E1M1's cage of bars puts two full-width layers of middles in one
/// view, which `MIDDLE_COLUMNS_MAX`'s 240 columns used to drop (0.82 % of the pixels).
#[test]
fn freedoom_s_grates_and_bars_are_drawn_where_the_oracle_draws_them() {
    use portalcast::math::{point_in_convex_polygon, Containment};
    use portalcast_format::NO_TEXTURE;
    let compiled = common::freedoom_assets();
    let host = common::HostAssets::of(compiled);
    let assets = host.render();
    let mut renderer = Renderer::new();
    let settings = Settings {
        resolution: Resolution::from_label("240x160").unwrap(),
        ..Settings::default()
    };
    let (mut poses, mut failures) = (0, Vec::new());
    for name in MAPS {
        let map = compiled.map(name).expect("the map was built");
        for (index, sector) in map.sectors.iter().enumerate() {
            let walls =
                usize::from(sector.first_wall)..usize::from(sector.first_wall + sector.wall_count);
            for wall in &map.walls[walls] {
                if wall.middle == NO_TEXTURE {
                    continue;
                }
                let (a, b) = (
                    map.vertices[usize::from(wall.start)],
                    map.vertices[usize::from(wall.end)],
                );
                let (dx, dy) = (f64::from(b.x - a.x), f64::from(b.y - a.y));
                let length = dx.hypot(dy);
                // Into the sector: the walls run with their sector on one side; try both.
                for sign in [1.0, -1.0] {
                    let (nx, ny) = (-dy / length * sign, dx / length * sign);
                    let x = f64::from(a.x + b.x) / 2.0 + 60.0 * nx;
                    let y = f64::from(a.y + b.y) / 2.0 + 60.0 * ny;
                    let position = WorldPoint::new(
                        Fx24_8::from_bits((x * 256.0) as i32),
                        Fx24_8::from_bits((y * 256.0) as i32),
                    );
                    let outline = common::player::sector_polygon(&map, index as u16);
                    if point_in_convex_polygon(&outline, position) != Containment::Inside {
                        continue;
                    }
                    let facing = (-ny).atan2(-nx).rem_euclid(std::f64::consts::TAU);
                    let camera = Camera {
                        position,
                        eye_z: Fx24_8::from_int(sector.floor_z + 41),
                        angle: Angle::from_bits(
                            (facing / std::f64::consts::TAU * 65536.0) as u32 as u16,
                        ),
                        sector: index as u16,
                        look_lines: 0,
                    };
                    let run =
                        compare_with_engine(&mut renderer, &map, &assets, &camera, &settings, 0);
                    let comparison = &run.comparison;
                    poses += 1;
                    if run.stats.things_dropped > 0
                        || comparison.surface_mismatch_percent() > SURFACE_MISMATCH_MAX_PERCENT
                        || comparison.holes > 0
                        || !comparison.missed_sectors.is_empty()
                    {
                        failures.push(format!(
                            "{name} {camera:?}: {} dropped, {comparison:?}",
                            run.stats.things_dropped
                        ));
                    }
                }
            }
        }
    }
    println!("{poses} poses facing a grate or bars");
    assert!(poses >= 20, "{poses} poses");
    assert!(failures.is_empty(), "{failures:#?}");
}
