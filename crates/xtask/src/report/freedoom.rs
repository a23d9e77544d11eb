//! docs/BENCH.md's "Freedoom" section (issue 19): Freedoom's maps imported from their WAD
//! (`portalcast_xtask::freedoom`), their bench fly-throughs at every resolution, their accuracy
//! against the oracle (`tests/doom_maps.rs`), and the frame rate at E1M1's start beside
//! GBADoom's, measured as `../shared/anchors/gbadoom/bench.sh` measures it.

use std::fmt::Write as _;
use std::path::Path;

use portalcast_xtask::bench_log::{self, field, group_digits, Run};
use portalcast_xtask::{freedoom, play_keys, rom_target_dir, TaskError, TaskResult};

use super::markdown::{fps, resolution_name};
use super::{cargo, run_rom, write_file, BENCH_DONE};

/// Emulator frames by which the script below has opened the Start menu, moved its first entry
/// (the resolution) from 120×80 to 120×160 and closed it: each scenario starts here.
const SCENARIO_START: u32 = 120;

/// GBADoom's scenarios at E1M1's start, as its anchor runs them (`keys/*.txt`): the keys held
/// and for how many emulator frames, and GBADoom's rendered frames per 60 VBlanks there (the
/// anchor's README: as shipped, and without sound).
const SCENARIOS: [(&str, &str, u32, f64, f64); 3] = [
    ("standing still", "", 1200, 16.7, 20.2),
    ("turning left in place", "LEFT", 600, 29.5, 30.9),
    ("walking forward", "UP", 300, 22.9, 26.9),
];

/// The key script of one scenario: per-frame lines on at power-on, the resolution set to
/// 120×160 through the Start menu, then `held` (nothing if empty) from [`SCENARIO_START`].
fn scenario_script(held: &str) -> String {
    let mut script = String::from("0-3: START\n60-62: START\n68-70: RIGHT\n76-78: START\n");
    if !held.is_empty() {
        let _ = writeln!(script, "{SCENARIO_START}-: {held}");
    }
    script
}

/// The `render` lines of the ROM's debug output.
fn render_lines(log: &str) -> Vec<&str> {
    log.lines()
        .filter(|line| line.starts_with("render "))
        .collect()
}

/// One scenario on `rom`: frames drawn in its `frames` emulator frames from [`SCENARIO_START`]
/// (the difference between two runs of the same script, one stopped at the start) and their
/// mean cycles.
fn scenario(rom: &Path, name: &str, held: &str, frames: u32) -> TaskResult<(f64, u64)> {
    let keys = rom_target_dir().join(format!("freedoom-{}.keys", name.replace(' ', "-")));
    write_file(&keys, scenario_script(held).as_bytes())?;
    let out = rom_target_dir().join("freedoom-frames");
    let before = play_keys(rom, &keys, SCENARIO_START, &out, name)?;
    let after = play_keys(rom, &keys, SCENARIO_START + frames, &out, name)?;
    let (before, after) = (render_lines(&before), render_lines(&after));
    let window = &after[before.len().min(after.len())..];
    for line in window {
        if field(line, "map") != Some("E1M1") || field(line, "res") != Some("120x160") {
            return Err(TaskError(format!(
                "{name}: the ROM drew `{line}`, not E1M1 at 120x160: the scenario's menu keys missed"
            )));
        }
    }
    let cycles: Vec<u64> = window
        .iter()
        .filter_map(|line| field(line, "cycles")?.parse().ok())
        .collect();
    let mean = cycles.iter().sum::<u64>() / cycles.len().max(1) as u64;
    Ok((window.len() as f64 * 60.0 / f64::from(frames), mean))
}

/// The `doom-accuracy` lines `tests/doom_maps.rs` prints.
fn accuracy_lines() -> TaskResult<Vec<String>> {
    eprintln!("== Freedoom's maps against the f64 oracle (host, tests/doom_maps.rs)");
    let output = cargo()
        .args([
            "test",
            "--quiet",
            "--test",
            "doom_maps",
            "--",
            "--nocapture",
            "--exact",
            ORACLE_TEST,
        ])
        .output()
        .map_err(|error| TaskError(format!("running tests/doom_maps.rs: {error}")))?;
    let stdout = String::from_utf8_lossy(&output.stdout);
    if !output.status.success() {
        return Err(TaskError(format!(
            "tests/doom_maps.rs failed: {}{}",
            stdout.trim(),
            String::from_utf8_lossy(&output.stderr).trim()
        )));
    }
    // The test harness's progress dot may share a line with the first.
    let lines: Vec<String> = stdout
        .lines()
        .filter_map(|line| line.find("doom-accuracy ").map(|at| line[at..].to_string()))
        .collect();
    for map in freedoom::MAPS {
        if !lines.iter().any(|line| field(line, "map") == Some(map)) {
            return Err(TaskError(format!(
                "tests/doom_maps.rs printed no doom-accuracy line for {map}: {}",
                stdout.trim()
            )));
        }
    }
    Ok(lines)
}

/// The test of `tests/doom_maps.rs` that prints the `doom-accuracy` lines.
const ORACLE_TEST: &str = "freedoom_maps_match_the_oracle_from_their_starts_and_sampled_poses";

/// The section, heading included.
pub fn section() -> TaskResult<String> {
    let rom = freedoom::build_freedoom_rom()?;
    let log = run_rom(&rom, "R", BENCH_DONE)?;
    let runs = bench_log::bench_runs(&log).map_err(TaskError)?;
    let mut scenarios = Vec::new();
    for (name, held, frames, shipped, silent) in SCENARIOS {
        let (rate, mean) = scenario(&rom, name, held, frames)?;
        scenarios.push((name, frames, rate, mean, shipped, silent));
    }
    Ok(render(&runs, &scenarios, &accuracy_lines()?))
}

/// Whether `run` is at the default settings (the knobs' other values are the bench map's
/// business).
fn defaults(run: &Run) -> bool {
    [
        ("lighting", "depth"),
        ("tex", "ewram"),
        ("prep", "off"),
        ("floors", "full"),
        ("things", "on"),
    ]
    .iter()
    .all(|(key, value)| run.setting(key) == Some(value))
}

fn render(
    runs: &[Run],
    scenarios: &[(&str, u32, f64, u64, f64, f64)],
    accuracy: &[String],
) -> String {
    let mut doc = String::new();
    let _ = writeln!(
        doc,
        "## Freedoom's maps\n\n\
         Doom maps imported from Freedoom Phase 1's WAD (issue 19; `{}/{}`), built into a ROM of \
         their own as `PORTALCAST_ASSETS=/usr/share/games/doom/freedoom1.wad \
         PORTALCAST_MAPS={} cargo rom` builds them (`crates/xtask/src/freedoom.rs`), each \
         flown by the bench scene at the default settings. Doom's sectors are cut into convex \
         pieces (E1M1: 133 sectors, 434 pieces), so a view visits many more sectors than on \
         the shipped maps.\n\n\
         | map | resolution | mean | p95 | max | fps (mean) |\n|---|---|---|---|---|---|",
        freedoom::FREEDOOM_DIR,
        freedoom::FREEDOOM1,
        freedoom::MAPS.join(",")
    );
    for run in runs.iter().filter(|run| defaults(run)) {
        let summary = run.summary();
        let _ = writeln!(
            doc,
            "| {} | {} | {} | {} | {} | {:.1} |",
            run.map,
            resolution_name(run.setting("res").unwrap_or("?")),
            group_digits(summary.mean),
            group_digits(summary.p95),
            group_digits(summary.max),
            fps(summary.mean)
        );
    }
    let _ = writeln!(
        doc,
        "\nAgainst the f64 oracle on the host (`tests/doom_maps.rs`: each map's start and 12 \
         sampled poses, every resolution, the same tables the ROM holds):\n\n\
         | map | frames | surface mismatch, worst | mean | holes | frames missing a sector |\n\
         |---|---|---|---|---|---|"
    );
    for line in accuracy {
        let value = |key| field(line, key).unwrap_or("?");
        let _ = writeln!(
            doc,
            "| {} | {} | {} % | {} % | {} | {} |",
            value("map"),
            value("frames"),
            value("worst"),
            value("mean"),
            value("holes"),
            value("missed")
        );
    }
    let _ = writeln!(
        doc,
        "\n### Beside GBADoom at E1M1's start\n\n\
         GBADoom (a prBoom port, the strongest GBA peer) at Freedoom E1M1's start, as \
         `../shared/anchors/gbadoom/bench.sh` measures it in the same libmgba: rendered frames \
         per 60 VBlanks, its 3D view 120×128 with each pixel doubled (figures from the anchor's \
         README, measured on these machines; this report does not rebuild GBADoom). portalcast \
         at 120×160, the nearest of its modes, from E1M1's start with the same keys held for \
         the same time (`SCENARIOS` in `crates/xtask/src/report/freedoom.rs`; frames counted \
         from the ROM's `render` lines, which come one a drawn frame). GBADoom caps at 35 fps, \
         portalcast at 60; the issue's goal is twice GBADoom's frame rate.\n\n\
         | at E1M1's start | emulator frames | portalcast 120×160, fps | its mean cycles a frame | GBADoom, fps (with sound) | GBADoom, fps (silent) | portalcast ÷ GBADoom (silent) |\n\
         |---|---|---|---|---|---|---|"
    );
    for &(name, frames, rate, mean, shipped, silent) in scenarios {
        let _ = writeln!(
            doc,
            "| {name} | {frames} | {rate:.1} | {} | {shipped:.1} | {silent:.1} | {:.2}× |",
            group_digits(mean),
            rate / silent
        );
    }
    // How far each scenario is from the goal, twice GBADoom's silent rate.
    let short: Vec<String> = scenarios
        .iter()
        .map(|&(name, _, rate, _, _, silent)| {
            let goal = GOAL_OVER_GBADOOM * silent;
            if rate >= goal {
                format!("{name} meets it ({rate:.1} of {goal:.1} fps)")
            } else {
                format!(
                    "{name} is short by {:.1}× ({rate:.1} of {goal:.1} fps)",
                    goal / rate
                )
            }
        })
        .collect();
    let _ = writeln!(
        doc,
        "\nThe goal, {GOAL_OVER_GBADOOM}× GBADoom's silent frame rate: {}.",
        short.join("; ")
    );
    doc
}

/// The goal: portalcast's frame rate over GBADoom's (silent) at the same scenario.
const GOAL_OVER_GBADOOM: f64 = 2.0;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scenario_script_sets_the_resolution_then_holds_its_keys() {
        let script = scenario_script("LEFT");
        assert!(script.starts_with("0-3: START\n"));
        assert!(script.ends_with(&format!("{SCENARIO_START}-: LEFT\n")));
        assert!(!scenario_script("").contains(&format!("{SCENARIO_START}-")));
    }
}
