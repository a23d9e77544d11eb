//! User map directories built into a ROM, in the real mGBA core (issue 8): the extreme maps of
//! `portalcast_xtask::extreme_maps`, generated into a directory outside the repository, built
//! into a ROM with `build_rom_with_assets` (what `PORTALCAST_ASSETS=/dir cargo rom` does), and
//! flown through by the ROM's bench scene (R held at power-on): every map of the directory at
//! every resolution, and the knobs on the first map (`chain`, the bench map of a directory
//! without a `bench` map). No frame may panic, every map must have its lines, and every frame's
//! cycles must stay under [`BENCH_WORST_FRAME_MULTIPLE`] times the bench map's slowest frame. And a broken user map must stop the
//! build with the compiler's `file:line:col:` line and leave the old `.gba` as it was.
//!
//! The ROM is built once per test process, in its own target directory (`target/rom-extreme`;
//! the broken build in `target/rom-extreme-broken`), so neither invalidates the normal ROM's
//! build; the first run builds `core` for each, later runs reuse it.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use common::*;
use portalcast_xtask::baseline::{self, Baseline};
use portalcast_xtask::bench_log::{self, Run};
use portalcast_xtask::extreme_maps;

/// How many times the bench map's slowest frame (the largest `max=` of docs/bench-baseline.txt,
/// the regression guard's baseline: 2,631,308 cycles at 240×160 when this was written) a frame
/// of an extreme map may take. Measured first: the slowest extreme frame was 7.4 times it (the
/// `star` map's first frame at 240×160, next to the vertex its 128 sectors share, looking across
/// it: 129 visits and 13,326 wall columns); 10 leaves a third of headroom over that. The bound
/// is a guard against runaway cost, not a frame-rate target: a walk that loops, a chain past
/// its depth limit or a per-column cost blown up by a far, long or thin wall goes far past it,
/// while the extreme maps' honest worst cases stay under it.
const BENCH_WORST_FRAME_MULTIPLE: u64 = 10;

/// The extreme maps' asset directory, outside the repository (the system's temporary
/// directory), written once per test process. Files keep their bytes and times when unchanged,
/// so a second run does not rebuild the ROM.
fn extreme_dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join("portalcast-extreme-assets");
        let repo = portalcast_xtask::workspace_root();
        assert!(
            !dir.starts_with(&repo),
            "{} is inside the repository",
            dir.display()
        );
        extreme_maps::write_extreme_assets(&dir, &repo.join("assets"))
            .unwrap_or_else(|error| panic!("{error}"));
        dir
    })
}

/// The ROM built from [`extreme_dir`], once per test process.
fn extreme_rom() -> &'static Path {
    static ROM: OnceLock<PathBuf> = OnceLock::new();
    ROM.get_or_init(|| {
        let target = portalcast_xtask::workspace_root()
            .join("target")
            .join("rom-extreme");
        std::fs::create_dir_all(&target).expect("creating target/rom-extreme");
        let gba = target.join("extreme.gba");
        portalcast_xtask::build_rom_with_assets(extreme_dir(), &target, &gba)
            .unwrap_or_else(|error| panic!("{error}"));
        gba
    })
}

/// The bench map's slowest frame in the committed baseline, in cycles.
fn bench_map_worst_frame() -> u64 {
    let path = baseline::baseline_path();
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|error| panic!("{}: {error}", path.display()));
    let committed =
        Baseline::parse(&text).unwrap_or_else(|problem| panic!("{}: {problem}", path.display()));
    committed
        .entries
        .iter()
        .map(|entry| entry.max)
        .max()
        .expect("the baseline has entries")
}

#[test]
fn extreme_maps_fly_through_in_the_rom_within_the_cycle_bound() {
    let bench_worst = bench_map_worst_frame();
    let bound = BENCH_WORST_FRAME_MULTIPLE * bench_worst;
    let log = bench_scene_log(extreme_rom());
    let runs: Vec<Run> =
        bench_log::bench_runs(&log.join("\n")).unwrap_or_else(|problem| panic!("{problem}"));

    // Per map: runs, frames, the slowest frame and its run and stages.
    let mut per_map: BTreeMap<&str, (usize, usize, u64, String)> = BTreeMap::new();
    for run in &runs {
        let entry = per_map
            .entry(run.map.as_str())
            .or_insert((0, 0, 0, String::new()));
        entry.0 += 1;
        entry.1 += run.frames.len();
        for frame in &run.frames {
            if frame.cycles > entry.2 {
                let stages: Vec<String> = frame
                    .stages
                    .iter()
                    .map(|(stage, cycles)| format!("{stage}={cycles}"))
                    .collect();
                entry.2 = frame.cycles;
                entry.3 = format!("{} frame={} {}", run.label(), frame.index, stages.join(" "));
            }
        }
    }
    println!(
        "bound: {BENCH_WORST_FRAME_MULTIPLE} x the bench map's slowest frame ({bench_worst}) = {bound} cycles"
    );
    println!("map       runs  frames  max cycles  x bench worst  slowest frame");
    for (map, (count, frames, max, slowest)) in &per_map {
        println!(
            "{map:<9} {count:>4}  {frames:>6}  {max:>10}  {:>13.2}  {slowest}",
            *max as f64 / bench_worst as f64
        );
    }

    // The stack's high-water mark: the deepest portal chain is the walk's worst case. It must
    // stay inside the linker script's STACK_RESERVE (printed as `reserve=`), which keeps IWRAM
    // code from growing into the stack's room.
    let line = checked_stack_line(log.iter().map(String::as_str), "the extreme maps' bench");
    println!("{line}");

    for map in extreme_maps::extreme_maps() {
        let frames = per_map.get(map.name).map_or(0, |entry| entry.1);
        assert!(
            frames >= portalcast_rom::bench::FRAMES_PER_SETTING as usize,
            "{}: {frames} bench frames (expected a run at every resolution)",
            map.name
        );
    }
    let too_slow: Vec<String> = runs
        .iter()
        .flat_map(|run| {
            run.frames
                .iter()
                .filter(|frame| frame.cycles > bound)
                .map(move |frame| format!("{} frame={}: {}", run.key(), frame.index, frame.cycles))
        })
        .collect();
    assert!(
        too_slow.is_empty(),
        "frames over {bound} cycles:\n{}",
        too_slow.join("\n")
    );
}

/// A broken user map stops the build with the compiler's `file:line:col:` line naming it, and
/// the `.gba` already at the output path keeps its bytes.
#[test]
fn a_broken_user_map_stops_the_build_and_leaves_the_old_rom() {
    let dir = std::env::temp_dir().join("portalcast-extreme-broken");
    let repo = portalcast_xtask::workspace_root();
    extreme_maps::write_extreme_assets(&dir, &repo.join("assets"))
        .unwrap_or_else(|error| panic!("{error}"));
    // The `thin` map with a vertex of its first room's east wall pushed in: that room is no
    // longer convex.
    let thin = extreme_maps::extreme_maps()
        .into_iter()
        .find(|map| map.name == "thin")
        .expect("the thin map");
    let (pushed, replacement) = ("vertex v2 256 96\n", "vertex v2 200 96\n");
    assert!(thin.text.contains(pushed), "the thin map's vertex v2 moved");
    let broken = dir.join("maps").join("broken.map");
    extreme_maps::write_if_changed(&broken, thin.text.replace(pushed, replacement).as_bytes())
        .unwrap_or_else(|error| panic!("{error}"));

    let target = repo.join("target").join("rom-extreme-broken");
    std::fs::create_dir_all(&target).expect("creating target/rom-extreme-broken");
    let gba = target.join("broken.gba");
    let old_rom = b"an older ROM that a failed build must leave alone".to_vec();
    std::fs::write(&gba, &old_rom).expect("writing the old ROM");

    let error = portalcast_xtask::build_rom_with_assets(&dir, &target, &gba)
        .expect_err("a map with a non-convex sector must not build");
    println!("{error}");
    let named = format!("{}:", broken.display());
    let line = error
        .0
        .lines()
        .find(|line| line.starts_with(&named))
        .unwrap_or_else(|| panic!("no line naming {}: in\n{error}", broken.display()));
    let mut position = line[named.len()..].splitn(3, ':');
    for what in ["line", "column"] {
        let number = position.next().unwrap_or_default();
        assert!(
            number.parse::<u32>().is_ok_and(|n| n > 0),
            "no {what} in {line:?}"
        );
    }
    assert!(
        line.contains("convex"),
        "the message does not say what is wrong: {line:?}"
    );
    // The compiler's lines end the error, after cargo's (issue 16: they were buried above it).
    assert_eq!(
        error.0.lines().last(),
        Some(line),
        "the located error is not last:\n{error}"
    );
    assert_eq!(
        std::fs::read(&gba).expect("the old ROM is still there"),
        old_rom,
        "the failed build touched {}",
        gba.display()
    );
    assert!(
        !gba.with_extension("gba.partial").exists(),
        "a half-written ROM was left next to it"
    );
}
