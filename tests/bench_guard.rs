//! The regression guard: the bench map at the default settings, every resolution, along the
//! fly-through in the real mGBA core, against the committed baseline (docs/bench-baseline.txt).
//! Fails when a mean or a max rises more than 2 % above it; prints, without failing, when one
//! falls more than 2 % below (then `cargo bench-report --update-baseline` and commit).

mod common;

use common::*;
use portalcast_harness::Keys;
use portalcast_xtask::baseline::{self, Baseline, BASELINE_FILE};
use portalcast_xtask::bench_log;

/// Emulated frames the guard's runs may take at most (they take a small part of it).
const MAX_FRAMES: u32 = 30_000;
/// Frames run between looks at the log.
const CHUNK: u32 = 200;

#[test]
fn the_rom_and_the_report_agree_on_the_marker_lines() {
    assert_eq!(portalcast_rom::bench::GUARD_DONE, bench_log::GUARD_DONE);
    assert_eq!(portalcast_rom::bench::BENCH_DONE, bench_log::BENCH_DONE);
}

#[test]
fn bench_map_cycles_stay_within_the_baseline() {
    let baseline_path = baseline::baseline_path();
    let committed = std::fs::read_to_string(&baseline_path).unwrap_or_else(|error| {
        panic!(
            "{}: {error}; measure one with `cargo bench-report --update-baseline` and commit it",
            baseline_path.display()
        )
    });
    let committed = Baseline::parse(&committed)
        .unwrap_or_else(|problem| panic!("{}: {problem}", baseline_path.display()));

    let mut emulator = boot();
    emulator.set_keys(Keys::R | Keys::SELECT);
    emulator
        .run_frames(4)
        .unwrap_or_else(|error| panic!("{error}"));
    emulator.set_keys(Keys::NONE);
    let mut frames = 4;
    // The guard's runs, then the stack line and `bench done`.
    while !emulator
        .debug_lines()
        .iter()
        .any(|line| line.contains(bench_log::BENCH_DONE))
    {
        assert!(
            frames < MAX_FRAMES,
            "no {:?} after {frames} frames",
            bench_log::BENCH_DONE
        );
        emulator
            .run_frames(CHUNK)
            .unwrap_or_else(|error| panic!("{error}"));
        frames += CHUNK;
    }
    let log = emulator.debug_lines().join("\n");
    let runs = bench_log::bench_runs(&log).unwrap_or_else(|problem| panic!("{problem}"));
    assert!(!runs.is_empty(), "the guard's runs printed no bench lines");
    // The bench scene's stack (flying the bench map with its things, at every resolution, and
    // starting each run's flight) inside the linker's reserve, as every scene's must be: it was
    // 16 bytes past it while the scene built each flight in the frame under the renderer's.
    let lines = emulator.debug_lines();
    println!("guard: {}", checked_stack_line(lines, "the bench scene"));
    check_page_rows_lent(&emulator.debug_lines());
    let isa = portalcast_xtask::engine_isa().unwrap_or_else(|error| panic!("{error}"));
    let measured = Baseline::from_runs(isa.label(), &runs);
    for entry in &measured.entries {
        println!("guard: {} mean={} max={}", entry.key, entry.mean, entry.max);
    }

    let verdict = baseline::check(&committed, &measured);
    for note in &verdict.notes {
        println!("guard: {note}");
    }
    for improvement in &verdict.improvements {
        println!(
            "guard: faster than the baseline: {improvement}; record it with \
             `cargo bench-report --update-baseline` and commit {BASELINE_FILE}"
        );
    }
    assert!(
        verdict.passed(),
        "the bench map's cycles regressed by more than {} % against {BASELINE_FILE}:\n  {}\n\
         If the slowdown is intended, update the baseline with `cargo bench-report \
         --update-baseline` and commit it for review.",
        baseline::TOLERANCE_PERCENT,
        verdict.regressions.join("\n  ")
    );
}

/// The page rows a 120×80 frame leaves free hold texture chains for every 120×80 run with the
/// textures in fast memory, and for no other (`hw::memory::LentPageRows`): the ROM prints
/// `page rows lent chains=N bytes=B` after a run's unmeasured first frame, before its first
/// line.
fn check_page_rows_lent(lines: &[&str]) {
    let mut previous: Option<&str> = None;
    let mut lent_runs = 0;
    for &line in lines {
        if line.starts_with("bench map=") && field(line, "frame") == Some("0") {
            let lent = previous.filter(|line| line.starts_with("page rows lent"));
            let wanted =
                field(line, "res") == Some("120x80") && field(line, "tex") == Some("ewram");
            assert_eq!(lent.is_some(), wanted, "{line}\nafter {previous:?}");
            if let Some(lent) = lent {
                assert!(
                    number(lent, "chains") >= 1 && number(lent, "bytes") >= 1,
                    "{lent}"
                );
                lent_runs += 1;
            }
        }
        previous = Some(line);
    }
    assert!(lent_runs >= 1, "no 120x80 run lent the page rows");
}
