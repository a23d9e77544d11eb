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

use portalcast_harness::symbols::FunctionSymbols;
use portalcast_harness::{Emulator, KeyScript};

const USAGE: &str =
    "usage: pc-profile ELF [--keys SCRIPTFILE] [--skip N] [--frames N] [--period CYCLES] [--top K] [--math-overlay]";

const HELP: &str = "\
Profiles a GBA ELF (it needs the symbols; the .gba has none) headless in mGBA.

  --keys FILE       key script, as for pc-run (e.g. `0-3: R` starts the bench scene)
  --skip N          frames to run before sampling starts (default 60)
  --frames N        frames to sample (default 120)
  --period CYCLES   cycles between samples (default 97, a prime)
  --top K           rows to print (default 40)
  --addresses K     also print the K most sampled instruction addresses (for llvm-addr2line)
  --math-overlay    name IWRAM addresses by the math benchmark's overlay (the L scene), whose
                    code shares its addresses with the renderer's: without it, by the renderer's";

struct Options {
    elf: PathBuf,
    keys: Option<PathBuf>,
    skip: u32,
    frames: u32,
    period: u32,
    top: usize,
    addresses: usize,
    math_overlay: bool,
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
            flag if flag.starts_with("--") => return Err(format!("unknown option {flag}")),
            path if elf.is_none() => elf = Some(PathBuf::from(path)),
            extra => return Err(format!("unexpected argument `{extra}`")),
        }
    }
    options.elf = elf.ok_or("no ELF given")?;
    Ok(options)
}

fn run(options: &Options) -> Result<(), String> {
    let symbols = FunctionSymbols::load(&options.elf, options.math_overlay)?;
    let script = match &options.keys {
        Some(path) => KeyScript::load(path).map_err(|error| error.to_string())?,
        None => KeyScript::new(),
    };
    let mut emulator = Emulator::load(&options.elf).map_err(|error| error.to_string())?;
    emulator
        .run_script(&script, options.skip)
        .map_err(|error| error.to_string())?;
    emulator.profile_start(options.period);
    for frame in options.skip..options.skip + options.frames {
        emulator.set_keys(script.keys_at(frame));
        emulator.run_frame().map_err(|error| error.to_string())?;
    }
    emulator.profile_stop();
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
                ("EWRAM", _) => "EWRAM",
                ("BIOS", _) => "BIOS",
                _ => "other",
            })
            .or_default() += 1;
    }
    let cycles_per_frame =
        samples.len() as f64 * f64::from(options.period) / f64::from(options.frames.max(1));
    println!(
        "{} samples every {} cycles over {} frames (~{:.0} cycles a frame sampled)",
        samples.len(),
        options.period,
        options.frames,
        cycles_per_frame
    );
    let print = |title: &str, table: &HashMap<&str, usize>| {
        let mut rows: Vec<(&&str, &usize)> = table.iter().collect();
        rows.sort_by(|a, b| b.1.cmp(a.1).then(a.0.cmp(b.0)));
        println!("\n{title}");
        for (name, count) in rows.into_iter().take(options.top) {
            println!(
                "{:6.2}% {:>9.0}/frame  {name}",
                *count as f64 * 100.0 / total,
                *count as f64 * f64::from(options.period) / f64::from(options.frames.max(1))
            );
        }
    };
    print("where the CPU runs:", &by_region);
    print("own cycles:", &own);
    print(
        "cycles with compiler helpers charged to their caller:",
        &with_leaf_helpers,
    );
    if options.addresses > 0 {
        let mut by_address: HashMap<u32, usize> = HashMap::new();
        for &(pc, _) in &samples {
            *by_address.entry(pc & !1).or_default() += 1;
        }
        let mut rows: Vec<(u32, usize)> = by_address.into_iter().collect();
        rows.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
        println!("\ninstruction addresses:");
        for (address, count) in rows.into_iter().take(options.addresses) {
            println!(
                "{:6.2}% 0x{address:08x}  {}",
                count as f64 * 100.0 / total,
                symbols.lookup(address).unwrap_or("?")
            );
        }
    }
    Ok(())
}
