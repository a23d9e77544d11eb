//! Cycle-weighted profile of a ROM in the real mGBA core: every `--period` CPU cycles the
//! emulator records where the CPU is; the samples are attributed to the ELF's function symbols
//! and printed as a table of cycle shares. Leaf helpers (64-bit multiplies, divides) are also
//! charged to their caller through the link register, so a line shows who pays for them.
//!
//! Exit status: 0 on success, 1 when the ROM failed or could not be loaded, 2 on bad arguments.

#![forbid(unsafe_code)]

use std::collections::HashMap;
use std::path::PathBuf;
use std::process::ExitCode;

use portalcast_harness::symbols::{FunctionSymbols, Overlays};
use portalcast_harness::{Emulator, KeyScript};

const USAGE: &str =
    "usage: pc-profile ELF [--keys SCRIPTFILE] [--skip N] [--frames N] [--from TEXT] \
[--until TEXT] [--per-line TEXT] [--period CYCLES] [--top K] [--math-overlay] [--unlit-kernels] \
[--pair-kernels]";

const HELP: &str = "\
Profiles a GBA ELF (it needs the symbols; the .gba has none) headless in mGBA.

  --keys FILE       key script, as for pc-run (e.g. `0-3: R` starts the bench scene)
  --skip N          frames to run before sampling starts (default 60)
  --frames N        frames to sample (default 120; with --until, the most to sample)
  --from TEXT       start sampling after the frame in which a debug print contains TEXT
                    (instead of after --skip frames)
  --until TEXT      stop sampling after the frame in which a debug print contains TEXT
  --per-line TEXT   give cycles per debug print that contains TEXT (e.g. one per frame the
                    ROM draws) instead of per emulated frame
  --period CYCLES   cycles between samples (default 97, a prime)
  --top K           rows to print (default 40)
  --addresses K     also print the K most sampled instruction addresses (for llvm-addr2line)
  --math-overlay    name IWRAM addresses by the math benchmark's overlay (the L scene), whose
                    code shares its addresses with the renderer's: without it, by the renderer's
  --unlit-kernels   name the kernel banks' addresses by the unlit kernels (frames drawn with
                    lighting=off), which share them with the lit ones: without it, by the lit
  --pair-kernels    name the column kernel banks' addresses by the pair kernels (frames drawn
                    240 wide), which share them with the doubled ones: without it, by those";

struct Options {
    elf: PathBuf,
    keys: Option<PathBuf>,
    skip: u32,
    frames: u32,
    period: u32,
    top: usize,
    addresses: usize,
    math_overlay: bool,
    unlit_kernels: bool,
    pair_kernels: bool,
    from: Option<String>,
    until: Option<String>,
    per_line: Option<String>,
}

/// Frames `--from` runs at most before giving up: minutes of emulated time.
const MAX_FRAMES_TO_FROM: u32 = 200_000;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.iter().any(|arg| arg == "--help" || arg == "-h") {
        println!("{USAGE}\n\n{HELP}");
        return ExitCode::SUCCESS;
    }
    let options = match parse_args(&args) {
        Ok(options) => options,
        Err(problem) => {
            eprintln!("pc-profile: {problem}\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    match run(&options) {
        Ok(()) => ExitCode::SUCCESS,
        Err(problem) => {
            eprintln!("pc-profile: {problem}");
            ExitCode::FAILURE
        }
    }
}

fn parse_args(args: &[String]) -> Result<Options, String> {
    let mut options = Options {
        elf: PathBuf::new(),
        keys: None,
        skip: 60,
        frames: 120,
        period: 97,
        top: 40,
        addresses: 0,
        math_overlay: false,
        unlit_kernels: false,
        pair_kernels: false,
        from: None,
        until: None,
        per_line: None,
    };
    let mut elf = None;
    let mut args = args.iter();
    while let Some(arg) = args.next() {
        let mut value = |flag: &str| {
            args.next()
                .cloned()
                .ok_or_else(|| format!("{flag} needs a value"))
        };
        let number = |flag: &str, text: String| {
            text.parse::<u32>()
                .map_err(|_| format!("{flag}: `{text}` is not a whole number"))
        };
        match arg.as_str() {
            "--keys" => options.keys = Some(PathBuf::from(value("--keys")?)),
            "--skip" => options.skip = number("--skip", value("--skip")?)?,
            "--frames" => options.frames = number("--frames", value("--frames")?)?,
            "--period" => options.period = number("--period", value("--period")?)?.max(1),
            "--top" => options.top = number("--top", value("--top")?)? as usize,
            "--addresses" => {
                options.addresses = number("--addresses", value("--addresses")?)? as usize
            }
            "--math-overlay" => options.math_overlay = true,
            "--unlit-kernels" => options.unlit_kernels = true,
            "--pair-kernels" => options.pair_kernels = true,
            "--from" => options.from = Some(value("--from")?),
            "--until" => options.until = Some(value("--until")?),
            "--per-line" => options.per_line = Some(value("--per-line")?),
            flag if flag.starts_with("--") => return Err(format!("unknown option {flag}")),
            path if elf.is_none() => elf = Some(PathBuf::from(path)),
            extra => return Err(format!("unexpected argument `{extra}`")),
        }
    }
    options.elf = elf.ok_or("no ELF given")?;
    Ok(options)
}

fn run(options: &Options) -> Result<(), String> {
    let symbols = FunctionSymbols::load(
        &options.elf,
        Overlays {
            math: options.math_overlay,
            unlit_kernels: options.unlit_kernels,
            pair_kernels: options.pair_kernels,
        },
    )?;
    let script = match &options.keys {
        Some(path) => KeyScript::load(path).map_err(|error| error.to_string())?,
        None => KeyScript::new(),
    };
    let mut emulator = Emulator::load(&options.elf).map_err(|error| error.to_string())?;
    let mut frame = 0;
    let step = |emulator: &mut Emulator, frame: &mut u32| -> Result<Vec<String>, String> {
        emulator.set_keys(script.keys_at(*frame));
        emulator.run_frame().map_err(|error| error.to_string())?;
        *frame += 1;
        Ok(emulator
            .drain_log()
            .into_iter()
            .map(|line| line.text)
            .collect())
    };
    match &options.from {
        Some(text) => loop {
            if step(&mut emulator, &mut frame)?
                .iter()
                .any(|line| line.contains(text))
            {
                break;
            }
            if frame >= MAX_FRAMES_TO_FROM {
                return Err(format!(
                    "no debug print contained {text:?} in {frame} frames"
                ));
            }
        },
        None => {
            while frame < options.skip {
                step(&mut emulator, &mut frame)?;
            }
        }
    }
    emulator.profile_start(options.period);
    let (first_sampled, mut counted_lines) = (frame, 0usize);
    while frame - first_sampled < options.frames {
        let lines = step(&mut emulator, &mut frame)?;
        if let Some(text) = &options.per_line {
            counted_lines += lines.iter().filter(|line| line.contains(text)).count();
        }
        if let Some(text) = &options.until {
            if lines.iter().any(|line| line.contains(text)) {
                break;
            }
        }
    }
    emulator.profile_stop();
    let sampled_frames = frame - first_sampled;
    let samples = emulator.profile_take();
    let total = samples.len().max(1) as f64;
    let mut own: HashMap<&str, usize> = HashMap::new();
    let mut with_leaf_helpers: HashMap<&str, usize> = HashMap::new();
    let mut by_region: HashMap<&str, usize> = HashMap::new();
    for &(pc, lr) in &samples {
        let name = symbols.lookup(pc).unwrap_or("?");
        *own.entry(name).or_default() += 1;
        // Compiler helpers are leaves: the sample's cost belongs to whoever called them.
        let payer = if name.starts_with("__aeabi") || name.starts_with("__") {
            symbols.lookup(lr).unwrap_or(name)
        } else {
            name
        };
        *with_leaf_helpers.entry(payer).or_default() += 1;
        let region = match pc >> 24 {
            0x02 => "EWRAM",
            0x03 => "IWRAM",
            0x06 => "VRAM",
            0x08..=0x0D => "ROM",
            0x00 => "BIOS",
            _ => "other",
        };
        let state = if pc & 1 == 1 { "Thumb" } else { "ARM" };
        *by_region
            .entry(match (region, state) {
                ("IWRAM", "ARM") => "IWRAM ARM",
                ("IWRAM", _) => "IWRAM Thumb",
                ("ROM", "ARM") => "ROM ARM",
                ("ROM", _) => "ROM Thumb",
                ("VRAM", "ARM") => "VRAM ARM",
                ("VRAM", _) => "VRAM Thumb",
                ("EWRAM", _) => "EWRAM",
                ("BIOS", _) => "BIOS",
                _ => "other",
            })
            .or_default() += 1;
    }
    // What one row's cycles are counted per: an emulated frame, or a matching print.
    let (per, unit) = match &options.per_line {
        Some(text) if counted_lines == 0 => {
            return Err(format!("no debug print contained {text:?} while sampling"))
        }
        Some(_) => (counted_lines as f64, "line"),
        None => (f64::from(sampled_frames.max(1)), "frame"),
    };
    println!(
        "{} samples every {} cycles over {} frames (~{:.0} cycles a {unit} sampled)",
        samples.len(),
        options.period,
        sampled_frames,
        samples.len() as f64 * f64::from(options.period) / per
    );
    if options.per_line.is_some() {
        println!("{counted_lines} matching lines");
    }
    let print = |title: &str, table: &HashMap<&str, usize>| {
        let mut rows: Vec<(&&str, &usize)> = table.iter().collect();
        rows.sort_by(|a, b| b.1.cmp(a.1).then(a.0.cmp(b.0)));
        println!("\n{title}");
        for (name, count) in rows.into_iter().take(options.top) {
            println!(
                "{:6.2}% {:>9.0}/{unit}  {name}",
                *count as f64 * 100.0 / total,
                *count as f64 * f64::from(options.period) / per
            );
        }
    };
    print("where the CPU runs:", &by_region);
    print("own cycles:", &own);
    print(
        "cycles with compiler helpers charged to their caller:",
        &with_leaf_helpers,
    );
    // Every function in fast memory (IWRAM, VRAM), sampled or not, and every sampled one in
    // the cartridge: what its bytes buy, for the choice of what runs where.
    println!("\ncode by memory (own cycles, bytes, memory, name):");
    let mut placed: Vec<(f64, u32, &str, &str)> = symbols
        .all()
        .iter()
        .filter_map(|(start, end, name)| {
            let memory = match start >> 24 {
                0x03 => "IWRAM",
                0x06 => "VRAM",
                0x08..=0x0D => "ROM",
                _ => return None,
            };
            let count = own.get(name.as_str()).copied().unwrap_or(0);
            if memory == "ROM" && count == 0 {
                return None;
            }
            let cycles = count as f64 * f64::from(options.period) / per;
            Some((cycles, end - start, memory, name.as_str()))
        })
        .collect();
    placed.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.3.cmp(b.3)));
    for (cycles, bytes, memory, name) in placed {
        println!("{cycles:>9.0}/{unit} {bytes:>6} {memory:<5} {name}");
    }
    if options.addresses > 0 {
        let mut by_address: HashMap<u32, usize> = HashMap::new();
        for &(pc, _) in &samples {
            *by_address.entry(pc & !1).or_default() += 1;
        }
        let mut rows: Vec<(u32, usize)> = by_address.into_iter().collect();
        rows.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
        println!("\ninstruction addresses (share, samples, address):");
        for (address, count) in rows.into_iter().take(options.addresses) {
            println!(
                "{:6.2}% {count:8} 0x{address:08x}  {}",
                count as f64 * 100.0 / total,
                symbols.lookup(address).unwrap_or("?")
            );
        }
    }
    Ok(())
}
