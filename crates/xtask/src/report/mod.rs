//! `cargo bench-report`: measures everything docs/BENCH.md shows and writes it, with the chart,
//! from nothing. `--check` regenerates both in memory and fails if they differ from the
//! committed files; `--update-baseline` also rewrites the regression guard's baseline.
//!
//! The steps: build the ROM (Thumb, and the ARM knob), run its bench scene, profile its default
//! 120×80 frames (`pc-profile`), run its kernel check, the
//! game tick's walk and the play demo (the log lines' cost) in the real mGBA core through `pc-run`, run the host's accuracy comparison (`bench-accuracy`
//! in crates/oracle), read the sizes from the ELF, then draw and write. The engine is not a
//! dependency of this crate (its commands must build before any setup, and must not rebuild
//! whenever the engine changes), so the ROM and the accuracy pass run as separate programs and
//! their lines are read generically (see `portalcast_xtask::bench_log`).

mod chart;
mod cost_model;
mod freedoom;
mod markdown;
mod profile;
mod sizes;

use std::path::{Path, PathBuf};
use std::process::Command;

use portalcast_xtask::baseline::{self, Baseline};
use portalcast_xtask::bench_log::{self, Accuracy, Run};
use portalcast_xtask::{
    build_rom_for, elf_path_for, ensure_setup, rom_target_dir, workspace_root, EngineIsa,
    TaskError, TaskResult,
};

pub use sizes::Sizes;

/// CPU cycles per second of the GBA (2^24).
pub const CPU_HZ: u64 = 16_777_216;
/// CPU cycles per displayed frame (228 lines of 1232 cycles): the 60 fps budget.
pub const CYCLES_PER_FRAME: u64 = 280_896;
/// The font family name the chart registers and uses.
pub const FONT: &str = "sans-serif";
/// The report, relative to the workspace root.
pub const DOC_FILE: &str = "docs/BENCH.md";
/// The chart, relative to the workspace root.
pub const CHART_FILE: &str = "docs/bench-cycles.png";
/// What the ROM prints after the guard's runs and at the end of its bench scene (the same
/// words as `portalcast_rom::bench::GUARD_DONE` and `BENCH_DONE`; the guard test checks they agree).
pub const GUARD_DONE: &str = bench_log::GUARD_DONE;
const BENCH_DONE: &str = bench_log::BENCH_DONE;
/// The kernel check's line of cycles per pixel.
const KERNEL_LINE: &str = "kernel-cycles-x100";
/// The ROM's boot line.
const BOOT_LINE: &str = "portalcast boot";
/// Marks around the math micro-benchmark section in docs/BENCH.md.
pub const MATH_BEGIN: &str = portalcast_xtask::bench_math::BEGIN_MARKER;
/// See [`MATH_BEGIN`].
pub const MATH_END: &str = portalcast_xtask::bench_math::END_MARKER;

/// Everything the report shows.
pub struct Measurements {
    /// The bench scene's runs on the shipped (Thumb) ROM, in the order the ROM ran them.
    pub runs: Vec<Run>,
    /// How many of `runs`, from the first, are the regression guard's.
    pub guard_runs: usize,
    /// The guard's runs again, drawn without kernels (`portalcast_rom::bench::setup_runs`).
    pub setup_runs: Vec<Run>,
    /// The host's accuracy lines, one per run.
    pub accuracy: Vec<Accuracy>,
    /// The kernel check's cycles per pixel, in hundredths.
    pub kernels: Vec<(String, u64)>,
    /// The boot line's figures (`iwram_used`, `stack_room`).
    pub boot: Vec<(String, u64)>,
    /// ROM, IWRAM and EWRAM sizes.
    pub sizes: Sizes,
    /// The guard's runs with the engine compiled as Thumb (the instruction-set knob).
    pub thumb_engine_runs: Vec<Run>,
    /// The committed regression baseline, if there is one.
    pub baseline: Option<Baseline>,
    /// The math micro-benchmark section, markers included.
    pub math_section: String,
    /// The game tick's section (`cargo bench-tick` prints the same).
    pub tick_section: String,
    /// The log lines' section (`cargo bench-logging` prints the same).
    pub logging_section: String,
    /// Where the default 120×80 frames' cycles go (`pc-profile`).
    pub profile_section: String,
    /// The bench scene's runs on the ROM of the generated maps
    /// (`portalcast_xtask::generated_maps`).
    pub generated_runs: Vec<Run>,
    /// Freedoom's maps' section (`report::freedoom`), heading included.
    pub freedoom_section: String,
}

impl Measurements {
    /// The regression guard's runs: the bench map at the default settings, per resolution.
    pub fn guard(&self) -> &[Run] {
        &self.runs[..self.guard_runs]
    }

    /// The accuracy line of `run`.
    pub fn accuracy_of(&self, run: &Run) -> Option<&Accuracy> {
        let key = run.key();
        self.accuracy.iter().find(|line| line.key == key)
    }
}

struct Options {
    check: bool,
    update_baseline: bool,
}

const USAGE: &str = "usage: cargo bench-report [--check] [--update-baseline]";

fn parse_options(args: &[String]) -> TaskResult<Options> {
    let mut options = Options {
        check: false,
        update_baseline: false,
    };
    for arg in args {
        match arg.as_str() {
            "--check" => options.check = true,
            "--update-baseline" => options.update_baseline = true,
            other => return Err(TaskError(format!("unknown option {other}\n{USAGE}"))),
        }
    }
    if options.check && options.update_baseline {
        return Err(TaskError(format!(
            "--check and --update-baseline exclude each other\n{USAGE}"
        )));
    }
    Ok(options)
}

/// `cargo bench-report [--check] [--update-baseline]`.
pub fn bench_report(args: &[String]) -> TaskResult<()> {
    let options = parse_options(args)?;
    let started = std::time::Instant::now();
    ensure_setup()?;
    let root = workspace_root();
    let doc_path = root.join(DOC_FILE);
    let chart_path = root.join(CHART_FILE);
    let current_doc = std::fs::read_to_string(&doc_path).unwrap_or_default();

    let gba = rom_path(EngineIsa::Arm);
    build_rom_for(EngineIsa::Arm, &gba)?;
    let bench_log = run_rom(&gba, "R", BENCH_DONE)?;
    let (guard_log, _) = bench_log
        .split_once(GUARD_DONE)
        .ok_or_else(|| TaskError(format!("the bench scene printed no {GUARD_DONE:?}")))?;
    let guard_runs = bench_log::bench_runs(guard_log).map_err(TaskError)?.len();
    let runs = bench_log::bench_runs(&bench_log).map_err(TaskError)?;
    let setup_runs = bench_log::setup_runs(&bench_log).map_err(TaskError)?;
    let kernel_log = run_rom(&gba, "L+R", KERNEL_LINE)?;
    let kernels = bench_log::numbers_of_line(&kernel_log, KERNEL_LINE)
        .ok_or_else(|| TaskError("the kernel check printed no cycles".to_string()))?;
    let boot = bench_log::numbers_of_line(&bench_log, BOOT_LINE).unwrap_or_default();
    let sizes = sizes::measure(&elf_path_for(EngineIsa::Arm), &gba)?;
    let profile = profile::measure(&elf_path_for(EngineIsa::Arm))?;
    let profile_section = profile::section(&profile)
        + &profile::placement_section(&profile, &code_rooms(&sizes, &boot)?);

    let thumb_gba = rom_path(EngineIsa::Thumb);
    build_rom_for(EngineIsa::Thumb, &thumb_gba)?;
    let thumb_log = run_rom(&thumb_gba, "R+SELECT", GUARD_DONE)?;
    let thumb_engine_runs = bench_log::bench_runs(&thumb_log).map_err(TaskError)?;

    let accuracy = bench_log::accuracy_lines(&run_accuracy()?).map_err(TaskError)?;
    let generated_runs = generated_runs()?;
    let freedoom_section = freedoom::section()?;

    let measured_baseline = Baseline::from_runs(EngineIsa::Arm.label(), &runs[..guard_runs]);
    let baseline = if options.update_baseline {
        let path = baseline::baseline_path();
        write_file(&path, measured_baseline.to_text().as_bytes())?;
        eprintln!("== wrote {}: commit it for review", path.display());
        Some(measured_baseline)
    } else {
        read_baseline()?
    };
    let measurements = Measurements {
        runs,
        guard_runs,
        setup_runs,
        accuracy,
        kernels,
        boot,
        sizes,
        thumb_engine_runs,
        baseline,
        math_section: math_section(&gba)?,
        tick_section: portalcast_xtask::bench_tick::tick_section(&gba)?,
        logging_section: portalcast_xtask::bench_logging::logging_section(&gba)?,
        profile_section,
        generated_runs,
        freedoom_section,
    };
    let doc = markdown::write(&measurements);
    let chart = chart::draw(&chart_panels(&measurements))?;
    if options.check {
        let committed_chart = std::fs::read(&chart_path).unwrap_or_default();
        let mut problems = Vec::new();
        if doc != current_doc {
            problems.push(format!(
                "{DOC_FILE} differs from a fresh report ({})",
                first_difference(&current_doc, &doc)
            ));
        }
        if chart != committed_chart {
            problems.push(format!("{CHART_FILE} differs from a fresh chart"));
        }
        if !problems.is_empty() {
            return Err(TaskError(format!(
                "{}; run `cargo bench-report` and commit the result",
                problems.join("; ")
            )));
        }
        eprintln!(
            "== {DOC_FILE} and {CHART_FILE} match a fresh report ({:.0} s)",
            started.elapsed().as_secs_f64()
        );
    } else {
        write_file(&doc_path, doc.as_bytes())?;
        write_file(&chart_path, &chart)?;
        eprintln!(
            "== wrote {DOC_FILE} and {CHART_FILE} ({:.0} s)",
            started.elapsed().as_secs_f64()
        );
    }
    Ok(())
}

/// Builds the ROM of the generated maps (`portalcast_xtask::generated_maps`) and runs its bench
/// scene: every generated map at every resolution at the default settings (and the knobs on the
/// first).
fn generated_runs() -> TaskResult<Vec<Run>> {
    let gba = portalcast_xtask::generated_maps::build_generated_rom()?;
    let log = run_rom(&gba, "R", BENCH_DONE)?;
    bench_log::bench_runs(&log).map_err(TaskError)
}

/// `cargo bench-rom`: the bench scene's cycle tables only, printed (no accuracy pass, no file
/// written): the quick loop while optimising.
pub fn bench_rom() -> TaskResult<()> {
    ensure_setup()?;
    let isa = portalcast_xtask::engine_isa()?;
    let gba = rom_path(isa);
    build_rom_for(isa, &gba)?;
    let log = run_rom(&gba, "R", BENCH_DONE)?;
    let runs = bench_log::bench_runs(&log).map_err(TaskError)?;
    print!("{}", markdown::cycle_table(&runs));
    let setup_runs = bench_log::setup_runs(&log).map_err(TaskError)?;
    print!("\n{}", markdown::set_up_table(&runs, &setup_runs));
    Ok(())
}

/// Where the report keeps the `.gba` with the engine in `isa` (apart from
/// `target/portalcast.gba`, which stays the shipped ROM).
fn rom_path(isa: EngineIsa) -> PathBuf {
    rom_target_dir().join(format!("portalcast-engine-{}.gba", isa.label()))
}

fn cargo() -> Command {
    let mut command = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()));
    command.current_dir(workspace_root());
    command
}

/// Runs `gba` in the real mGBA core with `keys` held from power-on until a debug line contains
/// `until`, and returns its debug lines.
fn run_rom(gba: &Path, keys: &str, until: &str) -> TaskResult<String> {
    eprintln!("== {} with {keys} held, until {until:?}", gba.display());
    let script = rom_target_dir().join(format!("bench-{}.keys", keys.replace('+', "-")));
    write_file(&script, format!("0-3: {keys}\n").as_bytes())?;
    let output = cargo()
        .args(["run", "--quiet", "--release", "-p", "portalcast-harness"])
        .args(["--bin", "pc-run", "--"])
        .arg(gba)
        .args(["--frames", "1000000", "--png-every", "0", "--until", until])
        .arg("--out")
        .arg(rom_target_dir().join("bench-frames"))
        .arg("--keys")
        .arg(&script)
        .output()
        .map_err(|error| TaskError(format!("running pc-run: {error}")))?;
    let log = String::from_utf8_lossy(&output.stdout).into_owned();
    if !output.status.success() || !log.contains(until) {
        return Err(TaskError(format!(
            "{} stopped before {until:?}: {}",
            gba.display(),
            String::from_utf8_lossy(&output.stderr).trim()
        )));
    }
    Ok(log)
}

/// What IWRAM and linker.ld's VRAM regions for code hold and leave: IWRAM's use from the
/// ELF's sections and what the stack's room at boot (`boot`) leaves above linker.ld's
/// `STACK_RESERVE`; each VRAM region's from the sections inside it.
fn code_rooms(sizes: &Sizes, boot: &[(String, u64)]) -> TaskResult<Vec<profile::CodeRoom>> {
    let path = workspace_root().join("linker.ld");
    let script = std::fs::read_to_string(&path)
        .map_err(|error| TaskError(format!("{}: {error}", path.display())))?;
    let reserve = sizes::stack_reserve(&script)
        .ok_or_else(|| TaskError(format!("{}: no STACK_RESERVE", path.display())))?;
    let room = boot
        .iter()
        .find(|(name, _)| name == "stack_room")
        .map(|(_, value)| *value as u32)
        .ok_or_else(|| TaskError("the boot line printed no stack_room".to_string()))?;
    let mut rooms = vec![profile::CodeRoom {
        name: "IWRAM".to_string(),
        used: sizes.used(sizes::IWRAM),
        left: room.saturating_sub(reserve),
    }];
    for region in sizes::linker_regions(&script)
        .into_iter()
        .filter(|region| region.name.starts_with("vram"))
    {
        let end = region.origin + region.length;
        let used: u32 = sizes
            .sections
            .iter()
            .filter(|section| (region.origin..end).contains(&section.address))
            .map(|section| section.size)
            .sum();
        rooms.push(profile::CodeRoom {
            name: format!(
                "VRAM, linker.ld's `{}` (0x{:08x}..0x{end:08x})",
                region.name, region.origin
            ),
            used,
            left: region.length.saturating_sub(used),
        });
    }
    Ok(rooms)
}

/// Runs the host's accuracy pass and returns its lines. The dev profile, which the tests build
/// too, is fast enough for it and saves a release build of the engine.
fn run_accuracy() -> TaskResult<String> {
    eprintln!("== the engine against the f64 oracle along the fly-through (host)");
    let output = cargo()
        .args([
            "run",
            "--quiet",
            "-p",
            "portalcast-oracle",
            "--bin",
            "bench-accuracy",
        ])
        .output()
        .map_err(|error| TaskError(format!("running bench-accuracy: {error}")))?;
    if !output.status.success() {
        return Err(TaskError(format!(
            "bench-accuracy failed: {}",
            String::from_utf8_lossy(&output.stderr).trim()
        )));
    }
    Ok(String::from_utf8_lossy(&output.stdout).into_owned())
}

fn read_baseline() -> TaskResult<Option<Baseline>> {
    let path = baseline::baseline_path();
    match std::fs::read_to_string(&path) {
        Ok(text) => Baseline::parse(&text)
            .map(Some)
            .map_err(|problem| TaskError(format!("{}: {problem}", path.display()))),
        Err(_) => Ok(None),
    }
}

/// The math micro-benchmark section (`cargo bench-math` writes the same), markers included.
fn math_section(rom: &Path) -> TaskResult<String> {
    let section = portalcast_xtask::bench_math::math_section(rom)?;
    Ok(format!("{MATH_BEGIN}\n{section}{MATH_END}"))
}

/// The chart's panels: per resolution, every run at it.
fn chart_panels(measurements: &Measurements) -> Vec<chart::Panel<'_>> {
    let mut resolutions: Vec<&str> = Vec::new();
    for run in &measurements.runs {
        let resolution = run.setting("res").unwrap_or("?");
        if !resolutions.contains(&resolution) {
            resolutions.push(resolution);
        }
    }
    resolutions
        .into_iter()
        .map(|resolution| {
            let runs: Vec<&Run> = measurements
                .runs
                .iter()
                .filter(|run| run.setting("res") == Some(resolution))
                .collect();
            let highlighted = runs.iter().position(|run| {
                measurements
                    .guard()
                    .iter()
                    .any(|guard| guard.key() == run.key())
            });
            chart::Panel {
                title: format!(
                    "{} — cycles per frame along the fly-through",
                    markdown::resolution_name(resolution)
                ),
                runs: runs
                    .into_iter()
                    .map(|run| (markdown::short_label(measurements, run), run))
                    .collect(),
                highlighted,
            }
        })
        .collect()
}

fn write_file(path: &Path, bytes: &[u8]) -> TaskResult<()> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)
            .map_err(|error| TaskError(format!("{}: {error}", dir.display())))?;
    }
    std::fs::write(path, bytes).map_err(|error| TaskError(format!("{}: {error}", path.display())))
}

/// Where two texts first differ, as `line N: "old" → "new"`.
fn first_difference(old: &str, new: &str) -> String {
    let mut old_lines = old.lines();
    let mut new_lines = new.lines();
    let mut number = 1;
    loop {
        match (old_lines.next(), new_lines.next()) {
            (Some(a), Some(b)) if a == b => number += 1,
            (None, None) => return "line endings differ".to_string(),
            (a, b) => {
                return format!(
                    "line {number}: {:?} → {:?}",
                    a.unwrap_or("(end)"),
                    b.unwrap_or("(end)")
                )
            }
        }
    }
}
