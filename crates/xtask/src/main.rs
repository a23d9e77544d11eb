//! `cargo rom`, `cargo play`, `cargo xtest`, `cargo bench-rom`, `cargo bench-report`,
//! `cargo bench-math`, `cargo bench-tick`, `cargo bench-logging` and `cargo generated-maps` (aliases in
//! .cargo/config.toml).
use portalcast_xtask::{build_rom, ensure_setup, workspace_root, TaskError, TaskResult};
use std::process::{Command, ExitCode};

mod report;

/// Frames `cargo play` runs the demo headless: its walk through the bench map's door and its
/// lift ride (assets/demo/play.keys).
const PLAY_FRAMES: &str = "1200";

const USAGE: &str = "usage: cargo rom | cargo play | cargo xtest | cargo bench-rom | cargo bench-report [--check] [--update-baseline] | cargo bench-math | cargo bench-tick | cargo bench-logging | cargo generated-maps DIR | run-rom ELF (a game's cargo runner: crates/xtask/run-rom)";

/// The environment variable setting how many frames `run-rom` runs a game headless.
const RUN_FRAMES_ENV: &str = "PORTALCAST_RUN_FRAMES";
/// Frames `run-rom` runs a game headless unless `PORTALCAST_RUN_FRAMES` says otherwise.
const RUN_FRAMES_DEFAULT: &str = "600";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("rom") => rom(),
        Some("play") => play(),
        Some("test") => test(),
        Some("bench") => report::bench_rom(),
        Some("report") => report::bench_report(&args[1..]),
        Some("bench-math") => portalcast_xtask::bench_math::run(),
        Some("bench-tick") => portalcast_xtask::bench_tick::run(),
        Some("bench-logging") => portalcast_xtask::bench_logging::run(),
        Some("generated-maps") => generated_maps(&args[1..]),
        Some("run-rom") => run_rom(&args[1..]),
        _ => Err(TaskError(USAGE.to_string())),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            ExitCode::FAILURE
        }
    }
}

/// `run-rom ELF`, the cargo runner of a game built on the engine (`crates/xtask/run-rom`, named
/// in the game's `.cargo/config.toml`; docs/GUIDE.md): turns the ELF cargo built into a `.gba`
/// beside it, then opens that in mGBA if there is a display, or runs it headless in the mGBA core
/// for `PORTALCAST_RUN_FRAMES` frames (600), printing its log and writing its last frame as a PNG
/// into `frames/` beside it.
fn run_rom(args: &[String]) -> TaskResult<()> {
    let [elf] = args else {
        return Err(TaskError(
            "usage: run-rom ELF (cargo passes the game's ELF to its runner)".to_string(),
        ));
    };
    let elf = std::path::absolute(elf).map_err(|error| TaskError(format!("{elf}: {error}")))?;
    let gba = elf.with_extension("gba");
    portalcast_xtask::elf_to_gba(&elf, &gba)?;
    println!("ROM: {}", gba.display());
    if let Some(player) = has_display()
        .then(portalcast_xtask::player::find_installed_player)
        .flatten()
    {
        return run(
            Command::new(&player).args(portalcast_xtask::player::player_args(&gba)),
            &format!("{} {}", player.display(), gba.display()),
        );
    }
    let frames = std::env::var(RUN_FRAMES_ENV).unwrap_or_else(|_| RUN_FRAMES_DEFAULT.to_string());
    println!(
        "no display or no mGBA player: running it headless in the mGBA core for {frames} frames"
    );
    let out = elf.with_file_name("frames");
    run(
        cargo()
            .args(["run", "--quiet", "--release", "-p", "portalcast-harness"])
            .args(["--bin", "pc-run", "--"])
            .arg(&gba)
            .args(["--frames", &frames, "--png-every", "0", "--out"])
            .arg(&out),
        "the headless run",
    )?;
    println!("last frame: {}", out.display());
    Ok(())
}

/// `cargo generated-maps DIR`: writes the generated maps (caves, a maze, a castle) with the
/// shipped textures, sky and sprites into DIR, an asset directory for `PORTALCAST_ASSETS`.
fn generated_maps(args: &[String]) -> TaskResult<()> {
    let [dir] = args else {
        return Err(TaskError(
            "usage: cargo generated-maps DIR (the asset directory to write)".to_string(),
        ));
    };
    let dir = std::path::Path::new(dir);
    let files = portalcast_xtask::generated_maps::write_generated_assets(
        dir,
        &workspace_root().join("assets"),
    )?;
    for file in files {
        println!("{}", file.display());
    }
    println!(
        "now, for example: PORTALCAST_ASSETS={} cargo bench-rom",
        dir.display()
    );
    Ok(())
}

fn rom() -> TaskResult<()> {
    let gba = build_rom()?;
    let size = std::fs::metadata(&gba).map(|meta| meta.len()).unwrap_or(0);
    println!("ROM: {} ({size} bytes)", gba.display());
    if let Some(report) = newest_build_file("size_report.txt") {
        print!("{report}");
    }
    // What a Doom WAD's import could not map (empty for an asset directory).
    if let Some(report) = newest_build_file("import_report.txt").filter(|r| !r.trim().is_empty()) {
        println!("What the import left out or fitted (docs/MAP_FORMAT.md, \"Doom maps\"):");
        print!("{report}");
    }
    Ok(())
}

/// A file build.rs writes to OUT_DIR (the size report, the import report), from the newest ROM
/// build.
fn newest_build_file(name: &str) -> Option<String> {
    let build_dir = portalcast_xtask::rom_target_dir()
        .join(portalcast_xtask::ROM_TARGET)
        .join(
            portalcast_xtask::engine_isa()
                .unwrap_or(portalcast_xtask::EngineIsa::Arm)
                .profile(),
        )
        .join("build");
    let newest = std::fs::read_dir(build_dir)
        .ok()?
        .filter_map(Result::ok)
        .map(|entry| entry.path().join("out").join(name))
        .filter(|path| path.is_file())
        .max_by_key(|path| path.metadata().and_then(|meta| meta.modified()).ok())?;
    std::fs::read_to_string(newest).ok()
}

fn cargo() -> Command {
    let mut command = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()));
    command.current_dir(workspace_root());
    command
}

fn run(command: &mut Command, what: &str) -> TaskResult<()> {
    eprintln!("== {what}");
    let status = command
        .status()
        .map_err(|error| TaskError(format!("{what}: could not start: {error}")))?;
    if status.success() {
        Ok(())
    } else {
        Err(TaskError(format!("{what} failed ({status})")))
    }
}

fn has_display() -> bool {
    ["DISPLAY", "WAYLAND_DISPLAY"]
        .iter()
        .any(|var| std::env::var_os(var).is_some_and(|value| !value.is_empty()))
}

fn play() -> TaskResult<()> {
    ensure_setup()?;
    let gba = build_rom()?;
    println!("ROM: {}", gba.display());
    use portalcast_xtask::player;
    let why_headless = if has_display() {
        match player::find_installed_player() {
            Some(found) => {
                println!(
                    "starting {} (the ROM's log lines follow here)",
                    found.display()
                );
                return run(
                    Command::new(&found).args(player::player_args(&gba)),
                    &format!("{} {}", found.display(), gba.display()),
                );
            }
            None => player::no_player_message(),
        }
    } else {
        "no display (DISPLAY and WAYLAND_DISPLAY are unset)".to_string()
    };
    println!("{why_headless}: running the demo headless in the real mGBA core");
    let out = workspace_root().join("target").join("play");
    let script = workspace_root()
        .join("assets")
        .join("demo")
        .join("play.keys");
    let mut headless = cargo();
    headless
        .args([
            "run",
            "--quiet",
            "--release",
            "-p",
            "portalcast-harness",
            "--bin",
            "pc-run",
            "--",
        ])
        .arg(&gba)
        .args(["--frames", PLAY_FRAMES])
        .args(["--png-every", "60", "--summary", "--out"])
        .arg(&out)
        .arg("--keys")
        .arg(&script);
    run(&mut headless, "the headless demo")?;
    println!("PNG frames: {}", out.display());
    Ok(())
}

fn test() -> TaskResult<()> {
    ensure_setup()?;
    run(
        cargo().args(["fmt", "--all", "--", "--check"]),
        "cargo fmt --check",
    )?;
    run(
        cargo().args([
            "clippy",
            "--workspace",
            "--all-targets",
            "--",
            "-D",
            "warnings",
        ]),
        "cargo clippy (host)",
    )?;
    let rom_target_dir = portalcast_xtask::rom_target_dir();
    // The engine's library (its host launcher, src/play.rs, needs std), then the ROM: one run
    // each, as a target filter would apply to both packages.
    for (packages, what) in [
        (
            &["-p", "portalcast", "--lib"][..],
            "cargo clippy (GBA, the engine)",
        ),
        (&["-p", "portalcast-rom"][..], "cargo clippy (GBA, the ROM)"),
    ] {
        run(
            cargo()
                .args([
                    "clippy",
                    "--profile",
                    portalcast_xtask::EngineIsa::Arm.profile(),
                    "--target",
                    portalcast_xtask::ROM_TARGET,
                    "-Zbuild-std=core",
                ])
                .args(packages)
                .arg("--target-dir")
                .arg(&rom_target_dir)
                .args(["--", "-D", "warnings"]),
            what,
        )?;
    }
    // The examples, each a workspace of its own as a game outside this one is: for the GBA, as
    // their `.cargo/config.toml` builds them.
    for example in ["minimal", "hud"] {
        run(
            cargo()
                .current_dir(workspace_root().join("examples").join(example))
                .args(["fmt", "--", "--check"]),
            &format!("cargo fmt (examples/{example})"),
        )?;
        run(
            cargo()
                .current_dir(workspace_root().join("examples").join(example))
                .args(["clippy", "--release", "--target-dir"])
                .arg(workspace_root().join("target").join("examples"))
                .args(["--", "-D", "warnings"]),
            &format!("cargo clippy (examples/{example})"),
        )?;
    }
    // Dead intra-doc links and malformed doc comments fail here, not in a reader's browser.
    run(
        cargo()
            .args([
                "doc",
                "--workspace",
                "--no-deps",
                "--document-private-items",
            ])
            .env("RUSTDOCFLAGS", "-D warnings"),
        "cargo doc (warnings denied)",
    )?;
    let gba = build_rom()?;
    run_tests_and_count(
        cargo()
            .args(["test", "--workspace"])
            .env("PORTALCAST_GBA", &gba),
        "cargo test --workspace",
    )?;
    // The soak on imported maps (issue 19): the test built with Freedoom's maps as its assets,
    // as a user soaks their own (`PORTALCAST_ASSETS`), against the ROM of the same maps, in a
    // target directory of its own so that neither build undoes the other.
    let freedoom_gba = portalcast_xtask::freedoom::build_freedoom_rom()?;
    let wad = portalcast_xtask::freedoom::freedoom1_wad()?;
    run_tests_and_count(
        cargo()
            .args(["test", "--test", "emulator_soak"])
            .env(portalcast_xtask::ASSETS_ENV, &wad)
            .env(
                portalcast_xtask::MAPS_ENV,
                portalcast_xtask::freedoom::MAPS.join(","),
            )
            .env("PORTALCAST_GBA", &freedoom_gba)
            .env(
                "CARGO_TARGET_DIR",
                workspace_root().join("target").join("freedoom-host"),
            ),
        "the soak on Freedoom's maps",
    )
}

/// Runs `cargo test`, passing its output through, and closes with one line that adds up every
/// test binary's `test result:` line, so the run ends on the total rather than on the last
/// (often empty) doc-test binary.
fn run_tests_and_count(command: &mut Command, what: &str) -> TaskResult<()> {
    use std::io::{BufRead, BufReader};
    eprintln!("== {what}");
    let mut child = command
        .stdout(std::process::Stdio::piped())
        .spawn()
        .map_err(|error| TaskError(format!("cargo test: could not start: {error}")))?;
    let (mut passed, mut failed) = (0u64, 0u64);
    if let Some(stdout) = child.stdout.take() {
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            println!("{line}");
            if let Some(result) = line.strip_prefix("test result: ") {
                passed += count_before(result, "passed");
                failed += count_before(result, "failed");
            }
        }
    }
    let status = child
        .wait()
        .map_err(|error| TaskError(format!("cargo test: {error}")))?;
    println!("{passed} passed, {failed} failed");
    if status.success() {
        Ok(())
    } else {
        Err(TaskError(format!("{what} failed ({status})")))
    }
}

/// The number before `word` in a `test result:` line such as `ok. 3 passed; 0 failed; …`.
fn count_before(result: &str, word: &str) -> u64 {
    result
        .split(';')
        .filter_map(|part| part.trim().strip_suffix(word))
        .filter_map(|number| number.trim().rsplit(' ').next()?.parse::<u64>().ok())
        .sum()
}
