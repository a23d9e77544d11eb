//! `cargo bench-math`: runs the ROM's math micro-benchmark (the math scene, L held at power-on)
//! in the real mGBA core and rewrites the math section of `docs/BENCH.md` from its figures.
//!
//! [`math_section`] returns the section's Markdown for a given ROM, so a command that
//! regenerates all of `BENCH.md` can call it too; [`replace_region`] puts it between the
//! section's markers.

use crate::bench_log::field;
use crate::{
    build_rom, cargo, engine_isa, ensure_setup, workspace_root, EngineIsa, TaskError, TaskResult,
};
use std::path::Path;

/// The line before the math section in `docs/BENCH.md`.
pub const BEGIN_MARKER: &str = "<!-- math:begin -->";
/// The line after it.
pub const END_MARKER: &str = "<!-- math:end -->";

/// Frames the scene may take before the run counts as hung (it needs a few dozen).
const FRAME_LIMIT: u32 = 1200;

/// What the table says about each operation the ROM prints, by its `op=` name: what is
/// computed, and the engine function it is (or stands for).
const OPERATIONS: [(&str, &str, &str); 14] = [
    (
        "loop",
        "the loop alone: load the operand pair, add, accumulate",
        "—",
    ),
    ("mul24_8", "multiply 24.8 × 24.8 → 24.8", "`Fx24_8::mul`"),
    (
        "mul16_16",
        "multiply 16.16 × 16.16 → 16.16",
        "`Fx16_16::mul`",
    ),
    (
        "recip",
        "reciprocal `1/z'`, seed table + Newton step",
        "`Fx24_8::recip_fx2_30`",
    ),
    (
        "recip_exact",
        "reciprocal `1/z'`, 64-bit library divide (exact)",
        "`Fx24_8::recip_fx2_30_exact`",
    ),
    (
        "div_small",
        "divide by `n ≤ 511`, small-reciprocal table",
        "`Fx16_16::div_small`",
    ),
    (
        "div_table",
        "divide `a / b` (64-bit operands) by table: normalise, reciprocal, product",
        "`render::ratio::ratio`",
    ),
    (
        "div_bios",
        "divide `a / b`, BIOS `Div` (SWI 6)",
        "`hw::bios_div`",
    ),
    (
        "div_soft",
        "divide `a / b`, software (`/`: `__aeabi_idiv` in Thumb; shift-and-subtract in ARM)",
        "`i32 /`",
    ),
    ("sin_cos", "sine and cosine", "`Angle::sin_cos`"),
    (
        "to_eye",
        "map point → eye space (two rotations, four products)",
        "`EyeFrame::to_eye`",
    ),
    (
        "project_x",
        "projection: screen `x` of an eye-space point (reciprocal + product)",
        "`Viewport::projected_x_saturating`",
    ),
    (
        "column",
        "projection: exact first column (binary search over 240 columns)",
        "`Viewport::first_column_at_or_after`",
    ),
    (
        "project_y",
        "projection: screen `y` of a height at `1/z'`",
        "`Viewport::projected_y`",
    ),
];

/// `cargo bench-math`: builds the ROM, measures, prints the section and writes it into
/// `docs/BENCH.md` (for the shipped ROM only: `BENCH.md` documents that one).
pub fn run() -> TaskResult<()> {
    ensure_setup()?;
    let gba = build_rom()?;
    let section = math_section(&gba)?;
    print!("{section}");
    if engine_isa()? != EngineIsa::Arm {
        println!(
            "(the engine built as {}: docs/BENCH.md is left as it is; it documents the shipped ROM)",
            engine_isa()?.label()
        );
        return Ok(());
    }
    let path = workspace_root().join("docs").join("BENCH.md");
    let doc = std::fs::read_to_string(&path).map_err(|error| {
        TaskError(format!(
            "{}: cannot read it ({error}); restore it with `git checkout docs/BENCH.md`",
            path.display()
        ))
    })?;
    let updated = replace_region(&doc, &section)
        .map_err(|TaskError(message)| TaskError(format!("{}: {message}", path.display())))?;
    std::fs::write(&path, updated).map_err(|error| {
        TaskError(format!(
            "{}: cannot write it ({error}); check the file's permissions",
            path.display()
        ))
    })?;
    println!("wrote the math section of {}", path.display());
    Ok(())
}

/// The math section of `docs/BENCH.md` (heading included, markers excluded), measured by
/// running `rom`'s math scene in the harness.
pub fn math_section(rom: &Path) -> TaskResult<String> {
    let log = run_math_scene(rom)?;
    let results = parse(&log)?;
    Ok(render(&results))
}

/// `doc` with everything between the marker lines replaced by `section`.
pub fn replace_region(doc: &str, section: &str) -> TaskResult<String> {
    let missing = || {
        TaskError(format!(
            "no `{BEGIN_MARKER}` line followed by a `{END_MARKER}` line: put the two marker lines \
             where the math section belongs, then run `cargo bench-math` again"
        ))
    };
    let begin = doc.find(BEGIN_MARKER).ok_or_else(missing)?;
    let after_begin = begin + BEGIN_MARKER.len();
    let end = after_begin + doc[after_begin..].find(END_MARKER).ok_or_else(missing)?;
    let mut section = section.to_string();
    if !section.ends_with('\n') {
        section.push('\n');
    }
    Ok(format!("{}\n{section}{}", &doc[..after_begin], &doc[end..]))
}

/// The ROM's debug lines from a run of its math scene, up to `math done`.
fn run_math_scene(rom: &Path) -> TaskResult<String> {
    let target = workspace_root().join("target");
    let keys = target.join("math.keys");
    std::fs::create_dir_all(&target)
        .and_then(|()| std::fs::write(&keys, "0-3: L\n"))
        .map_err(|error| TaskError(format!("{}: cannot write it ({error})", keys.display())))?;
    let output = cargo()
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
        .arg(rom)
        .args(["--frames", &FRAME_LIMIT.to_string()])
        .args(["--png-every", "0", "--until", "math done", "--out"])
        .arg(target.join("math-frames"))
        .arg("--keys")
        .arg(&keys)
        .output()
        .map_err(|error| {
            TaskError(format!(
                "cannot start the harness (cargo run -p portalcast-harness): {error}"
            ))
        })?;
    let log = String::from_utf8_lossy(&output.stdout).into_owned();
    if !output.status.success() || !log.lines().any(|line| line == "math done") {
        let stderr = String::from_utf8_lossy(&output.stderr);
        let reason = stderr
            .lines()
            .rev()
            .find(|line| !line.trim().is_empty())
            .unwrap_or("no 'math done' line");
        return Err(TaskError(format!(
            "the ROM's math scene did not finish in {FRAME_LIMIT} frames ({reason}); \
             run `cargo test --test emulator_math` for details"
        )));
    }
    Ok(log)
}

/// The figures of one run.
#[derive(Debug, PartialEq)]
struct Results {
    /// `thumb` or `arm`: the instruction set the ROM's Rust code is compiled to.
    code: String,
    /// The WAITCNT value the ROM runs with, as printed (`0x4317`).
    waitcnt: String,
    pairs: u32,
    short_rounds: u32,
    long_rounds: u32,
    /// Per operation, in the ROM's order: name and cycles ×100 in ROM, IWRAM, ARM.
    rows: Vec<(String, [Option<u64>; 3])>,
}

fn parse(log: &str) -> TaskResult<Results> {
    let bad = |line: &str| {
        TaskError(format!(
            "cannot read the ROM's line `{line}`: crates/rom/src/main.rs (math_scene) and \
             crates/xtask/src/bench_math.rs disagree on its format"
        ))
    };
    let begin = log
        .lines()
        .find(|line| line.starts_with("math begin "))
        .ok_or_else(|| bad("math begin …"))?;
    let number = |line: &str, key: &str| -> TaskResult<u32> {
        field(line, key)
            .and_then(|text| text.parse().ok())
            .ok_or_else(|| bad(line))
    };
    let (short_rounds, long_rounds) = field(begin, "rounds")
        .and_then(|text| text.split_once('-'))
        .and_then(|(short, long)| Some((short.parse().ok()?, long.parse().ok()?)))
        .ok_or_else(|| bad(begin))?;
    let waitcnt = log
        .lines()
        .find(|line| line.starts_with("portalcast boot "))
        .and_then(|line| field(line, "waitcnt"))
        .unwrap_or("?")
        .to_string();
    let mut results = Results {
        code: field(begin, "code").ok_or_else(|| bad(begin))?.to_string(),
        waitcnt,
        pairs: number(begin, "pairs")?,
        short_rounds,
        long_rounds,
        rows: Vec::new(),
    };
    for line in log.lines() {
        if line.starts_with("math-check ") {
            let op = field(line, "op").ok_or_else(|| bad(line))?;
            let reference = field(line, "rom").ok_or_else(|| bad(line))?;
            for variant in ["iwram", "arm"] {
                let value = field(line, variant).ok_or_else(|| bad(line))?;
                if value != "-" && value != reference {
                    return Err(TaskError(format!(
                        "the ROM's {variant} variant of `{op}` returns other values than the Rust \
                         function ({line}); `cargo test --test emulator_math` shows which"
                    )));
                }
            }
        } else if line.starts_with("math-cycles-x100 ") {
            let op = field(line, "op").ok_or_else(|| bad(line))?;
            if !OPERATIONS.iter().any(|(name, ..)| *name == op) {
                return Err(TaskError(format!(
                    "the ROM measures an operation `{op}` this command does not know: describe it \
                     in OPERATIONS in crates/xtask/src/bench_math.rs"
                )));
            }
            let mut figures = [None; 3];
            for (slot, variant) in figures.iter_mut().zip(["rom", "iwram", "arm"]) {
                let text = field(line, variant).ok_or_else(|| bad(line))?;
                if text != "-" {
                    *slot = Some(text.parse().map_err(|_| bad(line))?);
                }
            }
            results.rows.push((op.to_string(), figures));
        }
    }
    if results.rows.is_empty() {
        return Err(bad("math-cycles-x100 …"));
    }
    Ok(results)
}

/// Line width of the document's prose.
const WIDTH: usize = 100;

/// `text` wrapped at `width` columns, continuation lines indented by `indent`, each line ended
/// by a newline (an empty `text` gives an empty line). A `code span` is never split.
fn wrap(text: &str, width: usize, indent: &str) -> String {
    let mut words: Vec<String> = Vec::new();
    let mut open_span = false;
    for word in text.split_whitespace() {
        match words.last_mut() {
            Some(last) if open_span => {
                last.push(' ');
                last.push_str(word);
            }
            _ => words.push(word.to_string()),
        }
        if word.matches('`').count() % 2 == 1 {
            open_span = !open_span;
        }
    }
    let mut out = String::new();
    let mut current = String::new();
    for word in &words {
        if !current.is_empty() && current.chars().count() + 1 + word.chars().count() > width {
            out.push_str(&current);
            out.push('\n');
            current = indent.to_string();
        } else if !current.is_empty() && current != indent {
            current.push(' ');
        }
        current.push_str(word);
    }
    out.push_str(&current);
    out.push('\n');
    out
}

/// Hundredths as a decimal: `1234` → `12.34`.
fn hundredths(value: u64) -> String {
    format!("{}.{:02}", value / 100, value % 100)
}

fn render(results: &Results) -> String {
    let (rust, rust_words) = match results.code.as_str() {
        "thumb" => ("Thumb", "compiled to Thumb, as the shipped ROM is"),
        _ => ("Rust ARM", "compiled to ARM (an `armv4t-none-eabi` ROM)"),
    };
    let added_rounds = results.long_rounds - results.short_rounds;
    let added = u64::from(added_rounds) * u64::from(results.pairs);
    let mut out = String::new();
    // Prose and list items are wrapped like the rest of the document; table rows are not.
    let mut line = |text: &str| {
        if text.starts_with('|') {
            out.push_str(text);
            out.push('\n');
        } else {
            let indent = if text.starts_with("- ") { "  " } else { "" };
            out.push_str(&wrap(text, WIDTH, indent));
        }
    };
    line("## Math: cycles per operation");
    line("");
    line(&format!(
        "Measured by the ROM's math scene (L held at power-on) in the real mGBA core. Each \
         operation runs over {} operand pairs spread over the engine's declared ranges \
         (`src/math_bench.rs`), kept in IWRAM; a figure is the difference between a {}-round and \
         a {}-round run divided by the {added} operations it adds, timed by the cycle meter with \
         interrupts masked, so the call and the timer reads cancel. Every figure includes the \
         loop around the operation (load the pair, accumulate the result, count): the first row \
         is that loop alone.",
        results.pairs, results.long_rounds, results.short_rounds
    ));
    line("");
    line(&format!(
        "- **{rust}, ROM**: the engine's Rust function, {rust_words}, inlined into a loop that \
         runs from the cartridge ROM (WAITCNT {}). The compiler's helper calls go where the ROM \
         puts them: the 64-bit product `__aeabi_lmul` (Thumb has no `SMULL`) runs from IWRAM, \
         the library divides from ROM.",
        results.waitcnt
    ));
    line(&format!(
        "- **{rust}, IWRAM**: the same loop, copied into IWRAM (where the renderer's code runs) \
         from an overlay only this scene loads."
    ));
    line(
        "- **ARM, IWRAM**: a hand-written ARM routine (`asm/mathbench.s`) from IWRAM; \
         `cargo test --test emulator_math` proves it returns the Rust function's value for every \
         pair. `—`: none written.",
    );
    line(&format!(
        "- **{rust} ROM ÷ ARM**: how many times the ARM routine is faster, loop included."
    ));
    line("");
    line(&format!(
        "| operation | engine function | {rust}, ROM | {rust}, IWRAM | ARM, IWRAM | {rust} ROM ÷ ARM |"
    ));
    line("|---|---|---|---|---|---|");
    for (name, figures) in &results.rows {
        let (_, what, function) = OPERATIONS
            .iter()
            .find(|(known, ..)| known == name)
            .copied()
            .unwrap_or((name, name, ""));
        let cell = |figure: Option<u64>| figure.map_or("—".to_string(), hundredths);
        let ratio = match (figures[0], figures[2]) {
            (Some(rom), Some(arm)) if arm > 0 => format!("{:.1}×", rom as f64 / arm as f64),
            _ => "—".to_string(),
        };
        line(&format!(
            "| {what} | {function} | {} | {} | {} | {ratio} |",
            cell(figures[0]),
            cell(figures[1]),
            cell(figures[2]),
        ));
    }
    line("");
    line(
        "The BIOS row is mGBA's model of the BIOS: the harness runs without a BIOS dump, and \
         mGBA's built-in (HLE) BIOS computes the division itself and charges an estimate of the \
         real BIOS's cycles (mGBA 0.9: \"Improve HLE BIOS timing\"). The table and Newton rows are approximations within the bounds \
         documented in `src/math/recip.rs` and `src/render/ratio.rs`; the other divides are \
         exact.",
    );
    line("");
    line(
        "Command: `cargo bench-math` (builds the ROM, runs the math scene in the harness, and \
         rewrites this section of `docs/BENCH.md` between its markers). \
         `PORTALCAST_ROM_TARGET=armv4t-none-eabi cargo bench-math` prints the same table for a \
         ROM whose Rust code is compiled to ARM, and leaves this file as it is.",
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const LOG: &str = "portalcast boot waitcnt=0x4317 iwram_used=1 stack_room=2\n\
        math begin code=thumb overlay_bytes=4872 pairs=16 rounds=1-9\n\
        math-check op=loop rom=0x1 iwram=0x1 arm=0x1\n\
        math-cycles-x100 op=loop rom=2178 iwram=1446 arm=1046\n\
        math-check op=column rom=0x2 iwram=0x2 arm=-\n\
        math-cycles-x100 op=column rom=40578 iwram=23159 arm=-\n\
        math done\n";

    #[test]
    fn parses_the_scene_and_renders_a_row_per_operation() {
        let results = parse(LOG).unwrap();
        assert_eq!(results.code, "thumb");
        assert_eq!((results.short_rounds, results.long_rounds), (1, 9));
        assert_eq!(
            results.rows,
            vec![
                ("loop".to_string(), [Some(2178), Some(1446), Some(1046)]),
                ("column".to_string(), [Some(40578), Some(23159), None]),
            ]
        );
        let section = render(&results);
        assert!(section.starts_with("## Math: cycles per operation\n"));
        assert!(
            section.contains("| 21.78 | 14.46 | 10.46 | 2.1× |"),
            "{section}"
        );
        assert!(section.contains("| 405.78 | 231.59 | — | — |"), "{section}");
        assert!(section.contains("128 operations"), "{section}");
        assert!(section
            .lines()
            .all(|line| line.starts_with('|') || line.chars().count() <= WIDTH));
    }

    #[test]
    fn wraps_prose_and_indents_list_items() {
        assert_eq!(wrap("a b c", 3, "  "), "a b\n  c\n");
        assert_eq!(wrap("", 3, ""), "\n");
        assert_eq!(wrap("- abc def", 5, "  "), "- abc\n  def\n");
        assert_eq!(wrap("a `b c` d", 3, ""), "a\n`b c`\nd\n");
    }

    #[test]
    fn a_disagreeing_variant_is_refused() {
        let log = LOG.replace("arm=0x1", "arm=0x3");
        let error = parse(&log).unwrap_err();
        assert!(error.0.contains("arm variant of `loop`"), "{error}");
    }

    #[test]
    fn replaces_only_the_marked_region() {
        let doc = format!("a\n{BEGIN_MARKER}\nold\n{END_MARKER}\nb\n");
        let new = replace_region(&doc, "new").unwrap();
        assert_eq!(new, format!("a\n{BEGIN_MARKER}\nnew\n{END_MARKER}\nb\n"));
        assert!(replace_region("no markers", "new").is_err());
    }
}
