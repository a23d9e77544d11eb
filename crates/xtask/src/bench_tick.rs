//! `cargo bench-tick`: the game tick's cycles (`Game::tick`: the buttons, the player's move with
//! its collisions, the jump), measured in the ROM along a scripted walk in the real mGBA core,
//! against the targets of issue 15: a mean of at most [`TARGET_MEAN`] cycles per tick and at
//! most [`TARGET_WORST`] for any tick.
//!
//! The ROM times each tick alone and prints, on every frame's `player` line, how many ticks ran
//! before that frame (`ticks=`), their cycles added up (`tick_cycles=`) and the longest
//! (`tick_max_cycles=`); what the two timer reads cost with nothing between them
//! (`timer_cycles=` on the `play start` line) is taken off each tick. [`tick_section`] plays [`KEYS_FILE`] and turns the lines into the
//! "Game tick" section of docs/BENCH.md, which `cargo bench-report` writes; `cargo bench-tick`
//! only prints it (the quick loop while optimising). mGBA's cycle counts are deterministic, so
//! the same ROM gives the same figures.

use crate::bench_log::{field, group_digits};
use crate::{
    build_rom_for, engine_isa, ensure_setup, play_keys, rom_target_dir, workspace_root, TaskError,
    TaskResult,
};
use std::path::Path;

/// The walk, relative to the workspace root: it turns, strafes, jumps and slides along walls.
pub const KEYS_FILE: &str = "assets/demo/tick.keys";
/// Emulator frames the walk is played for: the script's last press ends before this.
pub const FRAMES: u32 = 960;
/// The target for the mean tick, in CPU cycles (issue 15).
pub const TARGET_MEAN: u64 = 4_000;
/// The target for the longest tick, in CPU cycles (issue 15).
pub const TARGET_WORST: u64 = 10_000;

/// What the walk measured.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TickFigures {
    /// Ticks timed.
    pub ticks: u64,
    /// Their cycles added up.
    pub cycles: u64,
    /// The longest tick.
    pub worst: u64,
    /// Frames whose `player` line was read.
    pub frames: u64,
}

impl TickFigures {
    /// Cycles per tick on average, rounded to the nearest.
    pub fn mean(&self) -> u64 {
        (self.cycles + self.ticks / 2)
            .checked_div(self.ticks)
            .unwrap_or(0)
    }
}

/// `cargo bench-tick`: builds the ROM (the engine in `PORTALCAST_ENGINE_ISA`'s instruction set),
/// plays the walk and prints the section. Writes no file.
pub fn run() -> TaskResult<()> {
    ensure_setup()?;
    let isa = engine_isa()?;
    let gba = rom_target_dir().join(format!("portalcast-engine-{}.gba", isa.label()));
    build_rom_for(isa, &gba)?;
    print!("{}", tick_section(&gba)?);
    Ok(())
}

/// The "Game tick" section of docs/BENCH.md (heading included), measured by playing
/// [`KEYS_FILE`] on `rom` in the harness.
pub fn tick_section(rom: &Path) -> TaskResult<String> {
    let figures = parse(&run_walk(rom)?)?;
    Ok(render(&figures))
}

/// The ROM's debug lines over the walk.
fn run_walk(rom: &Path) -> TaskResult<String> {
    let keys = workspace_root().join(KEYS_FILE);
    eprintln!(
        "== {} playing {KEYS_FILE} for {FRAMES} frames",
        rom.display()
    );
    play_keys(
        rom,
        &keys,
        FRAMES,
        &rom_target_dir().join("tick-frames"),
        KEYS_FILE,
    )
}

/// Adds up the `player` lines' tick fields.
fn parse(log: &str) -> TaskResult<TickFigures> {
    let mut figures = TickFigures::default();
    for line in log.lines().filter(|line| line.starts_with("player ")) {
        let number = |key: &str| -> TaskResult<u64> {
            field(line, key)
                .and_then(|text| text.parse().ok())
                .ok_or_else(|| {
                    TaskError(format!(
                        "no {key}= in the ROM's line `{line}`: crates/rom/src/main.rs (play_scene) and \
                         crates/xtask/src/bench_tick.rs disagree on its format"
                    ))
                })
        };
        figures.frames += 1;
        figures.ticks += number("ticks")?;
        figures.cycles += number("tick_cycles")?;
        figures.worst = figures.worst.max(number("tick_max_cycles")?);
    }
    if figures.ticks == 0 {
        return Err(TaskError(format!(
            "the ROM ran no game tick over {KEYS_FILE} (no `player` line with ticks above 0)"
        )));
    }
    Ok(figures)
}

/// Whether `cycles` is within `target`, as the table says it.
fn verdict(cycles: u64, target: u64) -> String {
    if cycles <= target {
        "**met**".to_string()
    } else {
        format!("**{:.1}× over**", cycles as f64 / target as f64)
    }
}

fn render(figures: &TickFigures) -> String {
    let mean = figures.mean();
    format!(
        "## Game tick: cycles per tick\n\n\
         One tick of the game (`Game::tick`: the buttons, the player's move with its collisions, \
         the jump) runs 60 times a second whatever the frame rate, before the frame is drawn. The \
         ROM times each tick alone (less the timer reads' own cost, measured once at the start) \
         and prints the count, the sum and the longest on every frame's `player` line; the walk `{KEYS_FILE}` (run on, on the bench map) turns, strafes, jumps \
         and slides along walls and into corners for {frames} frames, {ticks} ticks.\n\n\
         | ticks | per tick | measured | target | |\n\
         |---|---|---|---|---|\n\
         | {ticks} | mean | {mean} | {target_mean} | {mean_verdict} |\n\
         | {ticks} | worst | {worst} | {target_worst} | {worst_verdict} |\n\n\
         Command: `cargo bench-tick` (builds the ROM, plays the walk in the harness and prints \
         this section); `cargo bench-report` writes it here.\n",
        frames = group_digits(figures.frames),
        ticks = group_digits(figures.ticks),
        mean = group_digits(mean),
        worst = group_digits(figures.worst),
        target_mean = group_digits(TARGET_MEAN),
        target_worst = group_digits(TARGET_WORST),
        mean_verdict = verdict(mean, TARGET_MEAN),
        worst_verdict = verdict(figures.worst, TARGET_WORST),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const LOG: &str = "portalcast boot waitcnt=0x4317\n\
        play start vblank=3\n\
        player frame=0 tick=1 ticks=1 tick_cycles=900 tick_max_cycles=900\n\
        render map=bench frame=0 cycles=200000\n\
        input vblank=5 keys=0x040\n\
        player frame=1 tick=3 ticks=2 tick_cycles=20100 tick_max_cycles=12000\n\
        player frame=2 tick=3 ticks=0 tick_cycles=0 tick_max_cycles=0\n";

    #[test]
    fn adds_up_every_frame_s_ticks() {
        let figures = parse(LOG).unwrap();
        assert_eq!(
            figures,
            TickFigures {
                ticks: 3,
                cycles: 21_000,
                worst: 12_000,
                frames: 3,
            }
        );
        assert_eq!(figures.mean(), 7_000);
        let section = render(&figures);
        assert!(section.starts_with("## Game tick: cycles per tick\n"));
        assert!(
            section.contains("| 3 | mean | 7,000 | 4,000 | **1.8× over** |"),
            "{section}"
        );
        assert!(
            section.contains("| 3 | worst | 12,000 | 10,000 | **1.2× over** |"),
            "{section}"
        );
    }

    #[test]
    fn a_rom_without_the_tick_fields_is_refused() {
        let error = parse("player frame=0 tick=1 game_cycles=5\n").unwrap_err();
        assert!(error.0.contains("ticks"), "{error}");
        assert!(parse("render map=bench\n").is_err());
    }

    #[test]
    fn the_walk_is_shipped_and_ends_within_the_frames_played() {
        let script = std::fs::read_to_string(workspace_root().join(KEYS_FILE)).unwrap();
        let last = script
            .lines()
            .filter_map(|line| line.split('#').next()?.split_once(':'))
            .filter_map(|(frames, _)| frames.trim().rsplit('-').next()?.parse::<u32>().ok())
            .max()
            .expect("the walk presses something");
        assert!(
            last < FRAMES,
            "the walk's last press, frame {last}, is not played"
        );
    }
}
