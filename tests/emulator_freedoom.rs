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
use portalcast::frame::{Resolution, PAGE_ROW_HALFWORDS};
use portalcast::render::view::Settings;
use portalcast::render::walk::Renderer;
use portalcast_harness::Keys;
use portalcast_oracle::compare_with_engine;
use portalcast_xtask::bench_log::{self, Run};
use portalcast_xtask::freedoom;

/// The soak's bound on one frame (`tests/emulator_soak.rs`): 16 display frames.
const FRAME_CYCLES_BOUND: u64 = 16 * 280_896;
const SURFACE_MISMATCH_MAX_PERCENT: f64 = 0.5;
/// Room in the host's live world for any imported map's sectors, movers and triggers (the
/// ROM's is sized by its own maps).
type HostWorld = portalcast::world::World<4096, 64, 256>;

fn freedoom_rom() -> &'static Path {
    static ROM: OnceLock<PathBuf> = OnceLock::new();
    ROM.get_or_init(|| freedoom::build_freedoom_rom().unwrap_or_else(|error| panic!("{error}")))
}

/// The settings a `render …` line names (its map is looked up by the caller).
fn settings_of(render_line: &str) -> Settings {
    use portalcast::render::demo::lighting_from_label;
    use portalcast::render::view::{Floors, Preprocessing, TexturePlacement, ThingsShown};
    let label =
        |key| field(render_line, key).unwrap_or_else(|| panic!("no {key}= in {render_line}"));
    Settings {
        resolution: Resolution::from_label(label("res")).unwrap(),
        lighting: lighting_from_label(label("lighting")).unwrap(),
        textures: TexturePlacement::from_label(label("tex")).unwrap(),
        preprocessing: Preprocessing::from_label(label("prep")).unwrap(),
        floors: Floors::from_label(label("floors")).unwrap(),
        things: ThingsShown::from_label(label("things")).unwrap(),
    }
}

/// Walks from E1M1's start: forward through the start room, a turn, forward again; compares
/// every frame with the host's and the host's with the oracle.
#[test]
fn a_walk_into_e1m1_matches_the_host_and_the_oracle() {
    let compiled = common::freedoom_assets();
    let host = common::HostAssets::of(compiled);
    let assets = host.render();
    let mut renderer = Renderer::new();
    let mut emulator = boot_rom_until_playing(freedoom_rom());
    let mut keys = Vec::new();
    for (frames, held) in [
        (90, Keys::UP),
        (24, Keys::RIGHT),
        (120, Keys::UP),
        (48, Keys::LEFT),
        (120, Keys::UP),
    ] {
        keys.extend(std::iter::repeat_n(held, frames));
    }
    let (mut compared, mut worst, mut sectors) =
        (0usize, 0.0f64, std::collections::BTreeSet::new());
    let mut failures = Vec::new();
    play_frames(
        &mut emulator,
        &keys,
        |emulator, (player, world): (&PlayerLine, Option<&WorldLine>), render_line| {
            let name = field(render_line, "map").expect("a map= field");
            assert_eq!(name, "E1M1", "{render_line}");
            let map = compiled.map(name).expect("the ROM's map is the host's");
            let settings = settings_of(render_line);
            let mut live = Box::new(HostWorld::start(&map));
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
            worst = worst.max(comparison.surface_mismatch_percent());
            if comparison.surface_mismatch_percent() > SURFACE_MISMATCH_MAX_PERCENT
                || comparison.holes > 0
                || !comparison.missed_sectors.is_empty()
            {
                failures.push(format!("{render_line}: {comparison:?}"));
            }
            sectors.insert(player.sector);
            compared += 1;
        },
    );
    println!(
        "{compared} frames compared, worst surface mismatch {worst:.3} %, sectors walked {}",
        sectors.len()
    );
    assert!(compared > 100, "{compared} frames compared");
    assert!(sectors.len() > 5, "the walk stayed in {sectors:?}");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
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
