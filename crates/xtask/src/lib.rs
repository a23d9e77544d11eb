//! portalcast's build commands as a library: the `cargo rom` / `cargo play` / `cargo xtest`
//! aliases run the binary, and emulator tests call [`rom_for_tests`] to get a fresh `.gba`.
//!
//! This crate must build before any setup has run, so it depends on nothing that needs a system
//! library (the mGBA harness is started as a separate process once setup has installed libmgba).

pub mod baseline;
pub mod bench_log;
pub mod bench_logging;
pub mod bench_math;
pub mod bench_tick;
pub mod extreme_maps;
pub mod freedoom;
pub mod generated_maps;
mod map_builder;
pub mod overlay;
pub mod player;

use std::fmt;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

/// The GBA target the ROM is built for.
pub const ROM_TARGET: &str = "thumbv4t-none-eabi";
/// The environment variable that selects the instruction set of the engine's own code.
pub const ENGINE_ISA_ENV: &str = "PORTALCAST_ENGINE_ISA";

/// The instruction set the `portalcast` package (engine and ROM binary) is compiled to; the rest
/// of the ROM (core, compiler-builtins, the gba runtime) is Thumb either way, and the asm kernels
/// ARM.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EngineIsa {
    /// ARM code (the default): Cargo.toml's `rom` profile, `-Ctarget-feature=-thumb-mode`.
    Arm,
    /// Thumb code, the target's default: the `release` profile. A benchmark knob.
    Thumb,
}

impl EngineIsa {
    /// The cargo profile that builds this choice.
    pub fn profile(self) -> &'static str {
        match self {
            EngineIsa::Arm => "rom",
            EngineIsa::Thumb => "release",
        }
    }

    /// The label benchmarks print.
    pub fn label(self) -> &'static str {
        match self {
            EngineIsa::Arm => "arm",
            EngineIsa::Thumb => "thumb",
        }
    }
}

/// The engine's instruction set: ARM unless `PORTALCAST_ENGINE_ISA=thumb`.
pub fn engine_isa() -> TaskResult<EngineIsa> {
    match std::env::var(ENGINE_ISA_ENV).as_deref() {
        Err(_) | Ok("") | Ok("arm") => Ok(EngineIsa::Arm),
        Ok("thumb") => Ok(EngineIsa::Thumb),
        Ok(other) => fail(format!(
            "{ENGINE_ISA_ENV}={other} is not an instruction set: use arm (the default) or thumb"
        )),
    }
}
/// Debian packages the harness (libmgba), the play command (an mGBA window) and the Doom
/// importer's tests (Freedoom's WADs, and glbsp, the node builder that cuts their maps into
/// convex subsectors) need.
pub const DEBIAN_PACKAGES: [&str; 4] = ["libmgba-dev", "mgba-sdl", "freedoom", "glbsp"];

/// A failed step, with the one line that says what to do.
#[derive(Debug)]
pub struct TaskError(pub String);

impl fmt::Display for TaskError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for TaskError {}

/// Shorthand for results of the tasks.
pub type TaskResult<T> = Result<T, TaskError>;

fn fail<T>(message: impl Into<String>) -> TaskResult<T> {
    Err(TaskError(message.into()))
}

/// The workspace root (where the top-level Cargo.toml is).
pub fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .ancestors()
        .nth(2)
        .expect("crates/xtask sits two levels below the workspace root")
        .to_path_buf()
}

/// Where `cargo rom` writes the ROM: `target/portalcast.gba` under the workspace root.
pub fn gba_path() -> PathBuf {
    workspace_root().join("target").join("portalcast.gba")
}

/// The ROM build's own target directory. Separate from the host one so that a test can build
/// the ROM while `cargo test` holds the host build directory.
pub fn rom_target_dir() -> PathBuf {
    workspace_root().join("target").join("rom")
}

/// The linked ROM ELF.
pub fn elf_path() -> PathBuf {
    elf_path_for(engine_isa().unwrap_or(EngineIsa::Arm))
}

/// The linked ROM ELF with the engine compiled to `isa`.
pub fn elf_path_for(isa: EngineIsa) -> PathBuf {
    elf_path_in(&rom_target_dir(), isa)
}

/// Plays `rom` in the real mGBA core (`pc-run`) for `frames` frames with the key script at
/// `keys`, writing no frame but the last to `out`, and returns the ROM's debug lines. `what`
/// names the run in the error.
pub fn play_keys(
    rom: &Path,
    keys: &Path,
    frames: u32,
    out: &Path,
    what: &str,
) -> TaskResult<String> {
    let output = cargo()
        .args(["run", "--quiet", "--release", "-p", "portalcast-harness"])
        .args(["--bin", "pc-run", "--"])
        .arg(rom)
        .args(["--frames", &frames.to_string(), "--png-every", "0", "--out"])
        .arg(out)
        .arg("--keys")
        .arg(keys)
        .output()
        .map_err(|error| TaskError(format!("running pc-run: {error}")))?;
    if !output.status.success() {
        return Err(TaskError(format!(
            "{} failed on {what}: {}",
            rom.display(),
            String::from_utf8_lossy(&output.stderr).trim()
        )));
    }
    Ok(String::from_utf8_lossy(&output.stdout).into_owned())
}

fn cargo() -> Command {
    let mut command = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()));
    command.current_dir(workspace_root());
    command
}

fn run(command: &mut Command, what: &str) -> TaskResult<()> {
    let status = command
        .status()
        .map_err(|error| TaskError(format!("{what}: could not start {command:?}: {error}")))?;
    if status.success() {
        Ok(())
    } else {
        fail(format!("{what} failed ({status})"))
    }
}

fn tool_exists(tool: &str) -> bool {
    Command::new("sh")
        .arg("-c")
        .arg(format!("command -v {tool} >/dev/null 2>&1"))
        .status()
        .is_ok_and(|status| status.success())
}

/// Installs the nightly `rust-src` component if it is missing (the ROM builds `core` from it).
/// Never updates the toolchain.
pub fn ensure_rust_src() -> TaskResult<()> {
    if !tool_exists("rustup") {
        return fail(
            "rustup is not installed: install it (https://rustup.rs), then run this command again",
        );
    }
    let installed = Command::new("rustup")
        .args(["component", "list", "--toolchain", "nightly", "--installed"])
        .output()
        .map_err(|error| TaskError(format!("rustup component list: {error}")))?;
    if !installed.status.success() {
        return fail("the nightly toolchain is missing: run `rustup toolchain install nightly`, then this command again");
    }
    if String::from_utf8_lossy(&installed.stdout)
        .lines()
        .any(|line| line.starts_with("rust-src"))
    {
        return Ok(());
    }
    eprintln!("setup: rustup component add rust-src --toolchain nightly");
    run(
        Command::new("rustup").args(["component", "add", "rust-src", "--toolchain", "nightly"]),
        "installing rust-src (rustup component add rust-src --toolchain nightly)",
    )
}

fn debian_package_installed(package: &str) -> bool {
    Command::new("dpkg-query")
        .args(["-W", "-f=${Status}", package])
        .output()
        .is_ok_and(|out| String::from_utf8_lossy(&out.stdout).contains("install ok installed"))
}

/// Installs [`DEBIAN_PACKAGES`] with apt-get if any is missing (apt-get update first).
pub fn ensure_debian_packages() -> TaskResult<()> {
    let missing: Vec<&str> = DEBIAN_PACKAGES
        .iter()
        .copied()
        .filter(|package| !debian_package_installed(package))
        .collect();
    if missing.is_empty() {
        return Ok(());
    }
    let list = missing.join(" ");
    if !tool_exists("apt-get") {
        return fail(format!("missing {list} and no apt-get here: install them ({list}: mGBA's library and player, Freedoom's WADs, the glbsp node builder) with your package manager"));
    }
    let is_root = Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|out| out.stdout.starts_with(b"0"));
    let sudo: &[&str] = if is_root {
        &[]
    } else if tool_exists("sudo") {
        &["sudo"]
    } else {
        return fail(format!(
            "missing {list}: run `apt-get update && apt-get install -y {list}` as root"
        ));
    };
    let apt = |args: &[&str]| {
        let mut full: Vec<&str> = sudo.to_vec();
        full.push("apt-get");
        full.extend_from_slice(args);
        let mut command = Command::new(full[0]);
        command
            .args(&full[1..])
            .env("DEBIAN_FRONTEND", "noninteractive");
        command
    };
    eprintln!("setup: apt-get update && apt-get install -y {list}");
    run(&mut apt(&["update", "-q"]), "apt-get update")?;
    let mut install_args = vec!["install", "-y", "-q", "--no-install-recommends"];
    install_args.extend(missing.iter().copied());
    run(&mut apt(&install_args), &format!("apt-get install {list}"))
}

/// Everything the test and play commands need, installed if missing.
pub fn ensure_setup() -> TaskResult<()> {
    ensure_rust_src()?;
    ensure_debian_packages()
}

/// Builds the ROM ELF (release, Thumb, `core` from source) and converts it into
/// `target/portalcast.gba` with agb-gbafix. Returns the `.gba` path.
pub fn build_rom() -> TaskResult<PathBuf> {
    let gba = gba_path();
    build_rom_for(engine_isa()?, &gba)?;
    Ok(gba)
}

/// Builds the ROM ELF with the engine compiled to `isa` and converts it into `gba`, whatever
/// `PORTALCAST_ENGINE_ISA` says (the benchmark report builds both).
pub fn build_rom_for(isa: EngineIsa, gba: &Path) -> TaskResult<()> {
    ensure_rust_src()?;
    // The asset compiler's `file:line:col` lines end the error, after cargo's output, so a
    // broken map (in `assets/` or `PORTALCAST_ASSETS`) is the last thing `cargo rom` prints.
    run_keeping_build_script_errors(
        &mut rom_build_command(isa, &rom_target_dir()),
        "building the ROM",
    )?;
    elf_to_gba(&elf_path_for(isa), gba)
}

/// The environment variable that names the asset directory a ROM is built from (build.rs;
/// `assets/` when unset).
pub const ASSETS_ENV: &str = "PORTALCAST_ASSETS";
/// The environment variable picking maps by name (`E1M1,E1M3`) from a WAD or an asset
/// directory.
pub const MAPS_ENV: &str = "PORTALCAST_MAPS";

/// Builds a ROM from the asset directory `assets_dir` (same layout as `assets/`, anywhere on
/// disk) into `gba`, with the engine compiled as `PORTALCAST_ENGINE_ISA` says. It builds in
/// `target_dir`, its own cargo target directory: build.rs reruns whenever the asset directory
/// changes, so sharing [`rom_target_dir`] would rebuild the normal ROM after every user build.
///
/// A map or image that does not compile fails the build with the asset compiler's
/// `file:line:col: what is wrong, what to do` lines in the error (cargo's output is also shown
/// as it runs), and `gba` is left as it was: nothing is converted or written.
pub fn build_rom_with_assets(assets_dir: &Path, target_dir: &Path, gba: &Path) -> TaskResult<()> {
    build_rom_with_maps(assets_dir, None, target_dir, gba)
}

/// [`build_rom_with_assets`] from an asset directory or a Doom WAD (`assets`), with only the
/// maps `maps` names (comma-separated, as `PORTALCAST_MAPS` takes them) if it names any.
pub fn build_rom_with_maps(
    assets: &Path,
    maps: Option<&str>,
    target_dir: &Path,
    gba: &Path,
) -> TaskResult<()> {
    ensure_rust_src()?;
    let isa = engine_isa()?;
    let assets_dir = std::path::absolute(assets)
        .map_err(|error| TaskError(format!("{}: {error}", assets.display())))?;
    let mut command = rom_build_command(isa, target_dir);
    command.env(ASSETS_ENV, &assets_dir);
    match maps {
        Some(maps) => command.env(MAPS_ENV, maps),
        None => command.env_remove(MAPS_ENV),
    };
    run_keeping_build_script_errors(
        &mut command,
        &format!("building the ROM from {}", assets_dir.display()),
    )?;
    elf_to_gba(&elf_path_in(target_dir, isa), gba)
}

/// The cargo command that builds the ROM ELF with the engine compiled to `isa` into
/// `target_dir` (the ELF lands at [`elf_path_in`]).
fn rom_build_command(isa: EngineIsa, target_dir: &Path) -> Command {
    let mut command = cargo();
    command
        .args([
            "build",
            "--profile",
            isa.profile(),
            "--target",
            ROM_TARGET,
            "-Zbuild-std=core",
        ])
        .args([
            "-p",
            "portalcast-rom",
            "--bin",
            "portalcast",
            "--target-dir",
        ])
        .arg(target_dir);
    command
}

/// The linked ROM ELF of a build into `target_dir` with the engine compiled to `isa`.
pub fn elf_path_in(target_dir: &Path, isa: EngineIsa) -> PathBuf {
    target_dir
        .join(ROM_TARGET)
        .join(isa.profile())
        .join("portalcast")
}

/// Runs `command` with its standard error passed through as it comes and also kept; on failure
/// the error holds the lines a failed build script printed (cargo shows them indented after
/// `--- stderr`: for build.rs, the asset compiler's diagnostics), or the last lines of the
/// output if there are none.
/// Recognises the warnings that the ROM profile's `-Ctarget-feature=-thumb-mode` (Cargo.toml,
/// `[profile.rom.package.portalcast]`: the engine compiled as ARM while the target stays Thumb)
/// makes rustc and LLVM print on every build of the engine, and its build script: expected, the
/// same each time, and saying nothing about the code. The ROM builds (`cargo rom`) show
/// every other line.
#[derive(Default)]
pub struct ArmProfileNoise {
    /// Inside one of those warnings, whose note lines run to a blank line.
    in_warning: bool,
}

impl ArmProfileNoise {
    /// Whether `line`, the next line of cargo's output, is worth showing.
    pub fn keep(&mut self, line: &str) -> bool {
        if self.in_warning {
            self.in_warning = !line.trim().is_empty();
            return false;
        }
        if line.starts_with("warning: ") && line.ends_with("`-Ctarget-feature`: `thumb-mode`") {
            self.in_warning = true;
            return false;
        }
        let llvm =
            line == "'-thumb-mode' is not a recognized feature for this target (ignoring feature)";
        // Each of the engine's units has that one warning; a count above one has others too.
        let count = (line.starts_with("warning: `portalcast` (")
            || line.starts_with("warning: `portalcast-rom` ("))
            && (line.ends_with(") generated 1 warning")
                || line.ends_with(") generated 1 warning (1 duplicate)"));
        !(llvm || count)
    }
}

fn run_keeping_build_script_errors(command: &mut Command, what: &str) -> TaskResult<()> {
    use std::io::BufRead;
    let mut child = command
        .stderr(std::process::Stdio::piped())
        .spawn()
        .map_err(|error| TaskError(format!("{what}: could not start {command:?}: {error}")))?;
    let mut lines = Vec::new();
    let mut noise = ArmProfileNoise::default();
    if let Some(stderr) = child.stderr.take() {
        for line in std::io::BufReader::new(stderr).lines() {
            let line = line.map_err(|error| TaskError(format!("{what}: {error}")))?;
            if noise.keep(&line) {
                eprintln!("{line}");
            }
            lines.push(line);
        }
    }
    let status = child
        .wait()
        .map_err(|error| TaskError(format!("{what}: {error}")))?;
    if status.success() {
        return Ok(());
    }
    let script_errors: Vec<&str> = lines
        .iter()
        .skip_while(|line| line.trim() != "--- stderr")
        .skip(1)
        // Cargo indents the script's lines; its own (`warning: build failed, waiting for other
        // jobs to finish...` when other crates still build) follow unindented, without a blank.
        .take_while(|line| line.starts_with(' ') && !line.trim().is_empty())
        .map(|line| line.trim())
        .collect();
    let shown = if script_errors.is_empty() {
        lines[lines.len().saturating_sub(20)..]
            .iter()
            .map(String::as_str)
            .collect()
    } else {
        script_errors
    };
    fail(format!("{what} failed ({status}):\n{}", shown.join("\n")))
}

/// Converts a linked ELF into a `.gba` with a valid header (logo, complement check, title, game
/// code). Writes a temporary file and renames it, so a failure leaves no half-written ROM.
/// Refuses an ELF whose math benchmark overlay would run code it replaces ([`overlay::check`]).
pub fn elf_to_gba(elf: &Path, gba: &Path) -> TaskResult<()> {
    let elf_bytes = std::fs::read(elf).map_err(|error| {
        TaskError(format!(
            "{}: cannot read the ROM ELF ({error}); build it with `cargo rom`",
            elf.display()
        ))
    })?;
    overlay::check(&elf_bytes)
        .map_err(|problem| TaskError(format!("{}: {problem}", elf.display())))?;
    let header = agb_gbafix::GbaHeader {
        start_code: [0; 4],
        game_title: *b"PORTALCAST\0\0",
        game_code: *b"BPCE",
        maker_code: *b"PC",
        software_version: 0,
    };
    let mut rom = Vec::new();
    agb_gbafix::write_gba_file(
        &elf_bytes,
        header,
        agb_gbafix::PaddingBehaviour::DoNotPad,
        false,
        &mut rom,
    )
    .map_err(|error| {
        TaskError(format!(
            "{}: cannot convert to .gba: {error}",
            elf.display()
        ))
    })?;
    let partial = gba.with_extension("gba.partial");
    std::fs::write(&partial, &rom)
        .and_then(|()| std::fs::rename(&partial, gba))
        .map_err(|error| TaskError(format!("{}: cannot write the ROM: {error}", gba.display())))
}

/// The `.gba` emulator tests run: `$PORTALCAST_GBA` if set (the test command builds the ROM
/// first and sets it), otherwise a fresh build, made once per test process.
pub fn rom_for_tests() -> PathBuf {
    static ROM: OnceLock<PathBuf> = OnceLock::new();
    ROM.get_or_init(|| match std::env::var_os("PORTALCAST_GBA") {
        Some(path) => PathBuf::from(path),
        None => build_rom().unwrap_or_else(|error| panic!("{error}")),
    })
    .clone()
}
