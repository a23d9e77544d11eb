//! `cargo bench-logging`: what the game's log lines cost, measured in the ROM in the real mGBA
//! core. The game writes its per-frame `player` and `render` lines only when Start is held at
//! power-on (the tests, the soak and `cargo bench-tick` switch them on); as a player runs it, it
//! writes the recording's `input` lines (one per change of the buttons) and a `rate` line about
//! every second. The ROM times each kind of line and prints, on every `rate` line, the frames
//! drawn and the VBlanks passed since the last one and the mean cycles per frame of each kind.
//!
//! [`logging_section`] plays [`KEYS_FILE`] (what `cargo play` presses) twice, without and with
//! the switch, and turns the `rate` lines into the "Logging" section of docs/BENCH.md, which
//! `cargo bench-report` writes; `cargo bench-logging` only prints it. mGBA's cycle counts are
//! deterministic, so the same ROM gives the same figures.

use crate::bench_log::{field, group_digits};
use crate::{
    build_rom_for, engine_isa, ensure_setup, play_keys, rom_target_dir, workspace_root, TaskError,
    TaskResult,
};
use std::path::Path;

/// The demo both runs play, relative to the workspace root.
pub const KEYS_FILE: &str = "assets/demo/play.keys";
/// Emulator frames each run lasts (as `cargo play` headless).
pub const FRAMES: u32 = 600;
/// The key held at power-on that switches the per-frame lines on, in key-script syntax, and
/// the frames it is held on (the ROM reads the boot keys within them).
pub const SWITCH_RULE: &str = "0-3: START";
/// CPU cycles per displayed frame (228 lines of 1232 cycles), and per second (2^24).
const CYCLES_PER_VBLANK: u64 = 280_896;
const CPU_HZ: u64 = 16_777_216;

/// One run's `rate` lines, added up.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RateFigures {
    /// `rate` lines read.
    pub lines: u64,
    /// Frames drawn over them.
    pub frames: u64,
    /// VBlanks passed over them.
    pub vblanks: u64,
    /// Cycles spent on the per-frame lines (the per-frame means times the frames).
    pub frame_lines_cycles: u64,
    /// Cycles spent on the recording's `input` lines.
    pub input_lines_cycles: u64,
    /// Cycles the `rate` lines cost, over the lines that report their predecessor's.
    pub rate_line_cycles: u64,
    /// How many lines report a predecessor's cost (all but the first).
    pub rate_lines_timed: u64,
    /// Mean render cycles per frame, times the frames.
    pub render_cycles: u64,
}

impl RateFigures {
    /// Frames per second as the player sees them, in hundredths.
    pub fn fps_x100(&self) -> u64 {
        (self.frames * 100 * CPU_HZ)
            .checked_div(self.vblanks * CYCLES_PER_VBLANK)
            .unwrap_or(0)
    }

    fn per_frame(&self, cycles: u64) -> u64 {
        (cycles + self.frames / 2)
            .checked_div(self.frames)
            .unwrap_or(0)
    }

    /// Cycles per drawn frame spent on the per-frame lines.
    pub fn frame_lines_per_frame(&self) -> u64 {
        self.per_frame(self.frame_lines_cycles)
    }

    /// Cycles per drawn frame spent on the `input` lines.
    pub fn input_lines_per_frame(&self) -> u64 {
        self.per_frame(self.input_lines_cycles)
    }

    /// Mean render cycles per drawn frame.
    pub fn render_per_frame(&self) -> u64 {
        self.per_frame(self.render_cycles)
    }

    /// Mean cycles of one `rate` line.
    pub fn rate_line(&self) -> u64 {
        (self.rate_line_cycles + self.rate_lines_timed / 2)
            .checked_div(self.rate_lines_timed)
            .unwrap_or(0)
    }
}

/// `cargo bench-logging`: builds the ROM (the engine in `PORTALCAST_ENGINE_ISA`'s instruction
/// set), plays the demo twice and prints the section. Writes no file.
pub fn run() -> TaskResult<()> {
    ensure_setup()?;
    let isa = engine_isa()?;
    let gba = rom_target_dir().join(format!("portalcast-engine-{}.gba", isa.label()));
    build_rom_for(isa, &gba)?;
    print!("{}", logging_section(&gba)?);
    Ok(())
}

/// The "Logging" section of docs/BENCH.md (heading included), measured by playing
/// [`KEYS_FILE`] on `rom` without and with the per-frame lines.
pub fn logging_section(rom: &Path) -> TaskResult<String> {
    let demo = std::fs::read_to_string(workspace_root().join(KEYS_FILE))
        .map_err(|error| TaskError(format!("{KEYS_FILE}: {error}")))?;
    let off = parse(&run_demo(rom, "off", &demo)?)?;
    let on = parse(&run_demo(rom, "on", &format!("{SWITCH_RULE}\n{demo}"))?)?;
    Ok(render(&off, &on))
}

/// The ROM's debug lines over [`FRAMES`] frames of `script`.
fn run_demo(rom: &Path, label: &str, script: &str) -> TaskResult<String> {
    let keys = rom_target_dir().join(format!("logging-{label}.keys"));
    std::fs::create_dir_all(rom_target_dir())
        .and_then(|()| std::fs::write(&keys, script))
        .map_err(|error| TaskError(format!("{}: {error}", keys.display())))?;
    eprintln!(
        "== {} playing {KEYS_FILE} for {FRAMES} frames, per-frame lines {label}",
        rom.display()
    );
    play_keys(
        rom,
        &keys,
        FRAMES,
        &rom_target_dir().join("logging-frames"),
        KEYS_FILE,
    )
}

/// Adds up the `rate` lines.
fn parse(log: &str) -> TaskResult<RateFigures> {
    let mut figures = RateFigures::default();
    for line in log.lines().filter(|line| line.starts_with("rate ")) {
        let number = |key: &str| -> TaskResult<u64> {
            field(line, key)
                .and_then(|text| text.parse().ok())
                .ok_or_else(|| {
                    TaskError(format!(
                        "no {key}= in the ROM's line `{line}`: crates/rom/src/main.rs (RateWindow) and \
                         crates/xtask/src/bench_logging.rs disagree on its format"
                    ))
                })
        };
        let frames = number("frames")?;
        figures.lines += 1;
        figures.frames += frames;
        figures.vblanks += number("vblanks")?;
        figures.frame_lines_cycles += number("mean_frame_lines_cycles")? * frames;
        figures.input_lines_cycles += number("mean_input_lines_cycles")? * frames;
        figures.render_cycles += number("mean_render_cycles")? * frames;
        if figures.lines > 1 {
            figures.rate_line_cycles += number("rate_line_cycles")?;
            figures.rate_lines_timed += 1;
        }
    }
    if figures.frames == 0 {
        return Err(TaskError(format!(
            "the ROM printed no `rate` line with frames over {KEYS_FILE}"
        )));
    }
    Ok(figures)
}

fn fps(figures: &RateFigures) -> String {
    let x100 = figures.fps_x100();
    format!("{}.{:02}", x100 / 100, x100 % 100)
}

fn row(label: &str, figures: &RateFigures) -> String {
    format!(
        "| {label} | {frames} | {vblanks} | {fps} | {render} | {frame_lines} | {input_lines} | {rate_line} |\n",
        frames = group_digits(figures.frames),
        vblanks = group_digits(figures.vblanks),
        fps = fps(figures),
        render = group_digits(figures.render_per_frame()),
        frame_lines = group_digits(figures.frame_lines_per_frame()),
        input_lines = group_digits(figures.input_lines_per_frame()),
        rate_line = group_digits(figures.rate_line()),
    )
}

fn render(off: &RateFigures, on: &RateFigures) -> String {
    let cost = on.frame_lines_per_frame();
    format!(
        "## Logging: what the log lines cost\n\n\
         As a player runs it, the game writes no per-frame line: only the recording's `input` \
         lines (one per change of the buttons, so a game can be replayed) and one `rate` line \
         about every second (frames drawn, VBlanks passed, the frame rate, and these costs). \
         Start held at power-on switches on the `player` and `render` lines of every frame, which \
         the emulator tests, the soak and `cargo bench-tick` read. The ROM times each kind of \
         line and prints the figures on its `rate` lines; both runs play `{KEYS_FILE}` (what \
         `cargo play` presses) for {frames} frames, the second with `{SWITCH_RULE}` added. The \
         figures add up the {off_lines} and {on_lines} `rate` lines' windows.\n\n\
         | per-frame lines | frames drawn | VBlanks | frame rate (fps) | render, cycles per frame | per-frame lines, cycles per frame | `input` lines, cycles per frame | `rate` line, cycles each |\n\
         |---|---|---|---|---|---|---|---|\n\
         {off_row}{on_row}\n\
         The per-frame lines cost {cost} cycles per drawn frame when on ({percent:.1} % of a \
         60 fps frame's {budget} cycles) and nothing when off: they are not formatted. Over the \
         same demo the player gets {fps_off} fps without them and {fps_on} with them (the \
         render's mean differs too, because the frames drawn are not the same ones). The `rate` \
         line costs its cycles once a second ({rate_share:.2} % of the CPU's {cpu_hz} cycles a \
         second).\n\n\
         Command: `cargo bench-logging` (builds the ROM, plays the demo twice in the harness and \
         prints this section); `cargo bench-report` writes it here.\n",
        frames = group_digits(u64::from(FRAMES)),
        off_lines = off.lines,
        on_lines = on.lines,
        off_row = row("off (default)", off),
        on_row = row("on (Start held at power-on)", on),
        cost = group_digits(cost),
        percent = 100.0 * cost as f64 / CYCLES_PER_VBLANK as f64,
        budget = group_digits(CYCLES_PER_VBLANK),
        fps_off = fps(off),
        fps_on = fps(on),
        rate_share = 100.0 * off.rate_line() as f64 / CPU_HZ as f64,
        cpu_hz = group_digits(CPU_HZ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    const LOG: &str = "play start vblank=3 frame_lines=1\n\
        player frame=0\n\
        rate vblank=63 vblanks=60 frames=20 fps=19.90 mean_render_cycles=600000 mean_game_cycles=7000 mean_frame_lines_cycles=50000 mean_input_lines_cycles=1000 rate_line_cycles=0\n\
        input vblank=70 keys=0x040\n\
        rate vblank=123 vblanks=60 frames=30 fps=29.86 mean_render_cycles=250000 mean_game_cycles=7000 mean_frame_lines_cycles=52000 mean_input_lines_cycles=0 rate_line_cycles=22000\n";

    #[test]
    fn adds_up_the_rate_lines() {
        let figures = parse(LOG).unwrap();
        assert_eq!(figures.lines, 2);
        assert_eq!(figures.frames, 50);
        assert_eq!(figures.vblanks, 120);
        assert_eq!(figures.frame_lines_per_frame(), 51_200);
        assert_eq!(figures.input_lines_per_frame(), 400);
        assert_eq!(figures.render_per_frame(), 390_000);
        assert_eq!(figures.rate_line(), 22_000);
        // 50 frames in 120 VBlanks of 59.73 Hz.
        assert_eq!(figures.fps_x100(), 2488);
        let section = render(&RateFigures::default(), &figures);
        assert!(section.starts_with("## Logging: what the log lines cost\n"));
        assert!(
            section.contains("| on (Start held at power-on) | 50 | 120 | 24.88 | 390,000 | 51,200 | 400 | 22,000 |"),
            "{section}"
        );
        assert!(
            section.contains("cost 51,200 cycles per drawn frame"),
            "{section}"
        );
    }

    #[test]
    fn a_log_without_rate_lines_is_refused() {
        assert!(parse("player frame=0\n").is_err());
        let error = parse("rate vblank=60 frames=3\n").unwrap_err();
        assert!(error.0.contains("vblanks"), "{error}");
    }
}
