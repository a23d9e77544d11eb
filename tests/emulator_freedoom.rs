//! Freedoom's maps imported from `freedoom1.wad` into a ROM of their own
//! (`portalcast_xtask::freedoom`: what `PORTALCAST_ASSETS=…/freedoom1.wad PORTALCAST_MAPS=…
//! cargo rom` builds), run in mGBA (issue 19's done-when).
//!
//! - A walk from E1M1's start into its first rooms: every frame the ROM draws is rendered on the
//!   host from the pose and live world the ROM logged, with the same compiler's tables of the
//!   same WAD, and must be identical in VRAM; and the host's frame is compared with the f64
//!   oracle (at most 0.5 % of pixels on another surface, no hole, no missed sector).
//! - The bench scene's fly-through of every imported map at every resolution: no frame over the
//!   soak's bound, and its frames for docs/BENCH.md's Freedoom section.
//!
//! The ROM is built once per test process (in `target/rom-freedoom`).

mod common;

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use common::demos::{PlayerLine, WorldLine};
use common::rom_frames::{boot_rom_until_playing, play_frames};
use common::{field, number, read_page};
use portalcast::frame::PAGE_ROW_HALFWORDS;
use portalcast::render::walk::Renderer;
use portalcast_harness::Keys;
use portalcast_oracle::compare_with_engine;
use portalcast_xtask::bench_log::{self, Run};
use portalcast_xtask::freedoom;

/// The soak's bound on one frame (`tests/emulator_soak.rs`): 16 display frames.
const FRAME_CYCLES_BOUND: u64 = 16 * 280_896;
const SURFACE_MISMATCH_MAX_PERCENT: f64 = 0.5;

fn freedoom_rom() -> &'static Path {
    static ROM: OnceLock<PathBuf> = OnceLock::new();
    ROM.get_or_init(|| freedoom::build_freedoom_rom().unwrap_or_else(|error| panic!("{error}")))
}

/// What a walk in the ROM showed: frames compared, the worst surface mismatch, the sectors
/// walked and the last pose.
struct Walk {
    compared: usize,
    worst: f64,
    sectors: std::collections::BTreeSet<u16>,
    last: Option<PlayerLine>,
}

/// Plays `keys` in `rom` (built from `compiled`'s map `map_name`) and compares every frame it
/// draws with the host's render of the pose and live world the ROM logged (identical in VRAM),
/// and the host's with the oracle (within the bound, no hole, no missed sector).
fn walk_matches_the_host_and_the_oracle(
    rom: &Path,
    compiled: &portalcast_assets::Compiled,
    map_name: &str,
    keys: &[Keys],
) -> Walk {
    let host = common::HostAssets::of(compiled);
    let assets = host.render();
    let mut renderer = Renderer::new();
    let mut emulator = boot_rom_until_playing(rom);
    let mut walk = Walk {
        compared: 0,
        worst: 0.0,
        sectors: std::collections::BTreeSet::new(),
        last: None,
    };
    let mut failures = Vec::new();
    play_frames(
        &mut emulator,
        keys,
        |emulator, (player, world): (&PlayerLine, Option<&WorldLine>), render_line| {
            let name = field(render_line, "map").expect("a map= field");
            assert_eq!(name, map_name, "{render_line}");
            let map = compiled.map(name).expect("the ROM's map is the host's");
            let settings = common::demos::line_settings(render_line);
            let mut live = Box::new(common::HostWorld::start(&map));
            if let Some(world) = world {
                live.set_heights(&map, &world.heights);
                live.set_thrown(&world.thrown);
                live.set_lights(&map, &world.lights);
            }
            let live_map = live.map(&map);
            let run = compare_with_engine(
                &mut renderer,
                &live_map,
                &assets,
                &player.camera(),
                &settings,
                player.tick,
            );
            let vram = read_page(emulator, number(render_line, "page") as u32);
            let halfwords = settings.resolution.height() * PAGE_ROW_HALFWORDS;
            let differing = vram.halfwords[..halfwords]
                .iter()
                .zip(&run.engine.page.halfwords[..halfwords])
                .filter(|(a, b)| a != b)
                .count();
            assert_eq!(
                differing, 0,
                "{render_line}: halfwords differ from the host"
            );
            let comparison = run.comparison;
            walk.worst = walk.worst.max(comparison.surface_mismatch_percent());
            if comparison.surface_mismatch_percent() > SURFACE_MISMATCH_MAX_PERCENT
                || comparison.holes > 0
                || !comparison.missed_sectors.is_empty()
            {
                failures.push(format!("{render_line}: {comparison:?}"));
            }
            walk.sectors.insert(player.sector);
            walk.last = Some(player.clone());
            walk.compared += 1;
        },
    );
    println!(
        "{map_name}: {} frames compared, worst surface mismatch {:.3} %, sectors walked {}",
        walk.compared,
        walk.worst,
        walk.sectors.len()
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    walk
}

/// `frames` of each held key in turn.
fn held(script: &[(usize, Keys)]) -> Vec<Keys> {
    script
        .iter()
        .flat_map(|&(frames, keys)| std::iter::repeat_n(keys, frames))
        .collect()
}

/// Walks from E1M1's start: forward through the start room, a turn, forward again; compares
/// every frame with the host's and the host's with the oracle.
#[test]
fn a_walk_into_e1m1_matches_the_host_and_the_oracle() {
    let keys = held(&[
        (90, Keys::UP),
        (24, Keys::RIGHT),
        (120, Keys::UP),
        (48, Keys::LEFT),
        (120, Keys::UP),
    ]);
    let walk = walk_matches_the_host_and_the_oracle(
        freedoom_rom(),
        common::freedoom_assets(),
        "E1M1",
        &keys,
    );
    assert!(walk.compared > 100, "{} frames compared", walk.compared);
    assert!(
        walk.sectors.len() > 5,
        "the walk stayed in {:?}",
        walk.sectors
    );
}

/// The map drawn in Eureka (`assets/eureka/`): built from its PWAD with Freedoom 2's textures,
/// the player walks from room A up the corridor's 16 step and the 24 step into the sky-lit
/// room B, which only Doom's body climbs; every frame matches the host's and the oracle.
///
/// The walk turns a little in the corridor. Straight along the axis, one frame (the eye 57
/// high, 407.76 from room B's far wall) puts that wall's bottom edge 0.0015 row from a row of
/// pixel centres, and the engine's 24.8 rows draw the whole row as floor: 56 pixels, 0.58 %,
/// the rows' near-tie class of docs/RELIABILITY.md ("What the failures are").
#[test]
fn the_map_drawn_in_eureka_builds_and_its_walk_climbs_dooms_step() {
    let rom = freedoom::build_eureka_rom().unwrap_or_else(|error| panic!("{error}"));
    let request = portalcast_assets::doom::WadRequest {
        wad: portalcast_xtask::workspace_root().join(freedoom::EUREKA_WAD),
        iwad: None,
        maps: None,
    };
    let compiled = portalcast_assets::doom::compile_wad(&request).unwrap_or_else(|errors| {
        let lines: Vec<String> = errors.iter().map(ToString::to_string).collect();
        panic!("{}", lines.join("\n"))
    });
    let map = compiled.map("MAP01").expect("the PWAD's map");
    assert_eq!(map.player_start.size, portalcast_format::PlayerSize::DOOM);
    let walk = walk_matches_the_host_and_the_oracle(
        &rom,
        &compiled,
        "MAP01",
        &held(&[(100, Keys::UP), (6, Keys::LEFT), (254, Keys::UP)]),
    );
    let last = walk.last.expect("frames were drawn");
    let floors: std::collections::BTreeSet<i32> = walk
        .sectors
        .iter()
        .map(|&sector| map.sectors[usize::from(sector)].floor_z)
        .collect();
    assert_eq!(
        floors,
        [0, 16, 40].into(),
        "the walk crosses room A (floor 0), the corridor (16) and room B (40)"
    );
    let room_b = &map.sectors[usize::from(last.sector)];
    assert_eq!(room_b.floor_z, 40, "the walk ends in room B");
    assert_eq!(
        last.z,
        (40 + 41) * 256,
        "Doom's eye, 41 above room B's floor"
    );
}

#[test]
fn freedoom_maps_fly_through_in_the_rom_within_the_soak_bound() {
    let log = common::bench_scene_log(freedoom_rom());
    let runs: Vec<Run> =
        bench_log::bench_runs(&log.join("\n")).unwrap_or_else(|problem| panic!("{problem}"));
    for map in freedoom::MAPS {
        assert!(
            runs.iter().any(|run| run.map == map),
            "{map}: no bench frames"
        );
    }
    let mut over = Vec::new();
    for run in &runs {
        let cycles: Vec<u64> = run.frames.iter().map(|frame| frame.cycles).collect();
        let worst = cycles.iter().max().copied().unwrap_or(0);
        let mean = cycles.iter().sum::<u64>() / cycles.len().max(1) as u64;
        println!(
            "{} {}: {} frames, mean {mean}, worst {worst}",
            run.map,
            run.label(),
            cycles.len()
        );
        if worst > FRAME_CYCLES_BOUND {
            over.push(format!("{} {}: {worst}", run.map, run.label()));
        }
    }
    assert!(
        over.is_empty(),
        "frames over {FRAME_CYCLES_BOUND} cycles: {over:?}"
    );
}
