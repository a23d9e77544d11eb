//! Headless runner: runs a ROM in mGBA for a number of frames, writes PNG frames, prints the ROM's
//! debug lines and, on request, a summary of the cycle counts it printed. `cargo play` falls back
//! to it when there is no display.
//!
//! Exit status: 0 when every frame ran, 1 when the ROM failed (panic print, fatal mGBA line) or
//! could not be loaded, 2 on bad arguments.

#![forbid(unsafe_code)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use portalcast_harness::{Emulator, HarnessError, KeyScript, LogLevel};

const USAGE: &str =
    "usage: pc-run ROM [--frames N] [--keys SCRIPTFILE] [--png-every K] [--out DIR] [--summary] [--until TEXT]";

const HELP: &str = "\
Runs a GBA ROM (or ELF) headless in mGBA.

  --frames N        frames to run (default 600, ten seconds)
  --keys FILE       key script: lines `FRAMES: KEYS`, e.g. `10: A`, `20-30: UP+L`, `40-: START`
  --png-every K     write every K-th frame as a PNG; 0 = only the last (default 60)
  --out DIR         where the PNGs go (default target/frames/)
  --until TEXT      stop after the frame in which a debug print contains TEXT
  --summary         at the end, print frames and CPU cycles run, the frame rate the ROM's
                    `rate` lines add up to, and min/mean/max of every `NAME=NUMBER` field
                    whose name ends in `cycles` in the debug lines

The ROM's debug prints (mGBA \"GBA Debug\" lines) go to stdout; mGBA errors to stderr.
The last frame is always written, also when the ROM fails.";

struct Options {
    rom: PathBuf,
    frames: u32,
    keys: Option<PathBuf>,
    png_every: u32,
    out: PathBuf,
    summary: bool,
    until: Option<String>,
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.iter().any(|arg| arg == "--help" || arg == "-h") {
        println!("{USAGE}\n\n{HELP}");
        return ExitCode::SUCCESS;
    }
    let options = match parse_args(&args) {
        Ok(options) => options,
        Err(problem) => {
            eprintln!("pc-run: {problem}\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    match run(&options) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("pc-run: {error}");
            ExitCode::FAILURE
        }
    }
}

fn parse_args(args: &[String]) -> Result<Options, String> {
    let mut rom = None;
    let mut options = Options {
        rom: PathBuf::new(),
        frames: 600,
        keys: None,
        png_every: 60,
        out: PathBuf::from("target/frames"),
        summary: false,
        until: None,
    };
    let mut args = args.iter();
    while let Some(arg) = args.next() {
        let mut value = |flag: &str| {
            args.next()
                .cloned()
                .ok_or_else(|| format!("{flag} needs a value"))
        };
        match arg.as_str() {
            "--frames" => options.frames = parse_count("--frames", &value("--frames")?)?,
            "--until" => options.until = Some(value("--until")?.to_string()),
            "--png-every" => {
                options.png_every = parse_count("--png-every", &value("--png-every")?)?
            }
            "--keys" => options.keys = Some(PathBuf::from(value("--keys")?)),
            "--out" => options.out = PathBuf::from(value("--out")?),
            "--summary" => options.summary = true,
            flag if flag.starts_with("--") => return Err(format!("unknown option {flag}")),
            path if rom.is_none() => rom = Some(PathBuf::from(path)),
            extra => return Err(format!("unexpected argument {extra} (only one ROM)")),
        }
    }
    options.rom = rom.ok_or("no ROM given")?;
    Ok(options)
}

fn parse_count(flag: &str, text: &str) -> Result<u32, String> {
    text.parse()
        .map_err(|_| format!("{flag} wants a whole number, not `{text}`"))
}

fn run(options: &Options) -> Result<(), HarnessError> {
    let script = match &options.keys {
        Some(path) => KeyScript::load(path)?,
        None => KeyScript::new(),
    };
    let mut emulator = Emulator::load(&options.rom)?;
    std::fs::create_dir_all(&options.out).map_err(|source| HarnessError::Io {
        path: options.out.clone(),
        action: "create the frame directory",
        source,
    })?;

    let mut cycle_fields = CycleFields::default();
    let mut outcome = Ok(());
    for frame in 0..options.frames {
        emulator.set_keys(script.keys_at(frame));
        outcome = emulator.run_frame();
        let stop = print_log(&mut emulator, &mut cycle_fields, options.until.as_deref());
        let done = emulator.frames_run();
        let last = outcome.is_err() || stop || frame + 1 == options.frames;
        if last || (options.png_every != 0 && done % u64::from(options.png_every) == 0) {
            save_frame(&emulator, &options.out, done)?;
        }
        if outcome.is_err() || stop {
            break;
        }
    }
    if options.summary {
        // Also after a failure: the figures up to it are still worth seeing.
        cycle_fields.print(&emulator);
    }
    outcome
}

/// Debug prints to stdout as they happen; mGBA's own errors to stderr; the rest is noise here.
/// True if a debug print contains `until`.
fn print_log(emulator: &mut Emulator, cycle_fields: &mut CycleFields, until: Option<&str>) -> bool {
    let mut seen = false;
    for line in emulator.drain_log() {
        if line.is_debug_print() {
            println!("{}", line.text);
            cycle_fields.record(&line.text);
            seen |= until.is_some_and(|text| line.text.contains(text));
        } else if matches!(line.level, LogLevel::Fatal | LogLevel::Error) {
            eprintln!("mgba: {line}");
        }
    }
    seen
}

fn save_frame(emulator: &Emulator, dir: &Path, frame: u64) -> Result<(), HarnessError> {
    emulator.save_frame_png(&dir.join(format!("frame-{frame:06}.png")))
}

/// Running min/mean/max of each `NAME=NUMBER` field named `...cycles` in the debug prints, e.g.
/// `draw_cycles=51234`: the ROM measures, the runner only aggregates.
#[derive(Default)]
struct CycleFields {
    by_name: BTreeMap<String, FieldStats>,
    /// The portalcast game's `rate` lines (one about every second): frames drawn and VBlanks
    /// passed, added up, for the frame rate a player gets.
    rate_frames: u64,
    rate_vblanks: u64,
    rate_lines: u64,
    /// `frame_lines=` of the game's `play start` line: whether its per-frame lines were on.
    frame_lines: Option<bool>,
}

struct FieldStats {
    samples: u64,
    min: u64,
    max: u64,
    sum: u128,
}

impl CycleFields {
    fn record(&mut self, text: &str) {
        let number = |key: &str| {
            text.split_whitespace()
                .find_map(|word| word.strip_prefix(key)?.strip_prefix('='))
                .and_then(|value| value.parse::<u64>().ok())
        };
        if text.starts_with("rate ") {
            if let (Some(frames), Some(vblanks)) = (number("frames"), number("vblanks")) {
                self.rate_frames += frames;
                self.rate_vblanks += vblanks;
                self.rate_lines += 1;
            }
        } else if text.starts_with("play start ") {
            self.frame_lines = number("frame_lines").map(|on| on != 0);
        }
        for token in text.split_whitespace() {
            let Some((name, value)) = token.split_once('=') else {
                continue;
            };
            let Ok(value) = value.trim_end_matches([',', ';']).parse::<u64>() else {
                continue;
            };
            if !name.ends_with("cycles") {
                continue;
            }
            let stats = self.by_name.entry(name.to_owned()).or_insert(FieldStats {
                samples: 0,
                min: u64::MAX,
                max: 0,
                sum: 0,
            });
            stats.samples += 1;
            stats.min = stats.min.min(value);
            stats.max = stats.max.max(value);
            stats.sum += u128::from(value);
        }
    }

    fn print(&self, emulator: &Emulator) {
        /// A GBA frame: 228 lines of 1232 cycles.
        const FRAME_CYCLES: f64 = 280_896.0;
        println!(
            "summary: {} frames, {} CPU cycles",
            emulator.frames_run(),
            emulator.cycles()
        );
        if self.rate_vblanks > 0 {
            // The GBA shows 2^24 / 280,896 = 59.73 frames a second.
            let seconds = self.rate_vblanks as f64 * FRAME_CYCLES / 16_777_216.0;
            let lines = match self.frame_lines {
                Some(true) => ", per-frame log lines on (Start held at power-on)",
                Some(false) => ", per-frame log lines off (as a player runs it)",
                None => "",
            };
            println!(
                "  frame rate: {:.2} fps ({} frames drawn in {} VBlanks, {} `rate` lines{lines})",
                self.rate_frames as f64 / seconds,
                self.rate_frames,
                self.rate_vblanks,
                self.rate_lines
            );
        }
        if self.by_name.is_empty() {
            println!("  no `...cycles=N` fields in the debug output");
        }
        for (name, stats) in &self.by_name {
            let mean = stats.sum as f64 / stats.samples as f64;
            println!(
                "  {name}: {} samples, min {}, mean {:.0}, max {} (mean {:.1}% of a frame)",
                stats.samples,
                stats.min,
                mean,
                stats.max,
                100.0 * mean / FRAME_CYCLES
            );
        }
    }
}
