//! The report's profile: where the bench map's default 120×80 frames spend their cycles, by
//! function, as `pc-profile` samples them in the real mGBA core. It is the "what is left" of
//! the speed targets, measured rather than estimated.

use std::path::Path;

use portalcast_xtask::bench_log::group_digits;
use portalcast_xtask::{rom_target_dir, TaskError, TaskResult};

use super::{cargo, write_file};

/// Where sampling starts: the first frame line of the bench map's default 120×80 run (the
/// regression guard's first run).
pub const FROM: &str = "bench map=bench res=120x80 lighting=depth tex=ewram prep=off floors=full";
/// Where it stops: the next run's first line.
const UNTIL: &str = "res=120x160";
/// Rows of the function table.
const ROWS: usize = 16;

/// One row of `pc-profile`'s tables: a name and its cycles per drawn frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// Function (or memory region) name; `?` is an address outside every symbol.
    pub name: String,
    /// Cycles per frame the ROM drew.
    pub cycles: f64,
}

/// One row of `pc-profile`'s "code by memory" table: a function, where it runs, its bytes and
/// its own cycles per drawn frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Placed {
    /// Function name.
    pub name: String,
    /// `IWRAM`, `VRAM` or `ROM`.
    pub memory: String,
    /// Bytes of code.
    pub bytes: u32,
    /// Own cycles per frame the ROM drew.
    pub cycles: f64,
}

/// A parsed `pc-profile --per-line` output.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    /// Frames drawn while sampling.
    pub frames: u64,
    /// "where the CPU runs": memory region and instruction set.
    pub regions: Vec<Row>,
    /// "own cycles": each function's own samples.
    pub functions: Vec<Row>,
    /// "code by memory": every function in IWRAM and VRAM, and every sampled one in the
    /// cartridge.
    pub placed: Vec<Placed>,
}

/// The title of `pc-profile`'s table of code by memory.
const PLACED_TITLE: &str = "code by memory (own cycles, bytes, memory, name):";

/// Reads `pc-profile`'s output (run with `--per-line`).
pub fn parse(output: &str) -> Result<Profile, String> {
    let frames = output
        .lines()
        .find_map(|line| line.strip_suffix(" matching lines"))
        .and_then(|count| count.trim().parse().ok())
        .ok_or("pc-profile printed no count of matching lines")?;
    let table = |title: &str| -> Result<Vec<Row>, String> {
        let mut lines = output.lines().skip_while(|line| *line != title).skip(1);
        let mut rows = Vec::new();
        for line in lines.by_ref().take_while(|line| !line.trim().is_empty()) {
            // `  12.34%    123456/line  name`
            let mut fields = line.split_whitespace();
            let (_share, cycles) = (fields.next(), fields.next());
            let name = fields.collect::<Vec<_>>().join(" ");
            let cycles = cycles
                .and_then(|field| field.strip_suffix("/line"))
                .and_then(|field| field.parse().ok())
                .ok_or_else(|| format!("pc-profile: unreadable row {line:?}"))?;
            rows.push(Row { name, cycles });
        }
        if rows.is_empty() {
            return Err(format!("pc-profile printed no {title:?} table"));
        }
        Ok(rows)
    };
    let mut placed = Vec::new();
    for line in output
        .lines()
        .skip_while(|line| *line != PLACED_TITLE)
        .skip(1)
        .take_while(|line| !line.trim().is_empty())
    {
        // `   123456/line   1400 IWRAM name`
        let mut fields = line.split_whitespace();
        let row = (|| {
            let cycles = fields.next()?.split_once('/')?.0.parse().ok()?;
            let bytes = fields.next()?.parse().ok()?;
            let memory = fields.next()?.to_string();
            let name = fields.collect::<Vec<_>>().join(" ");
            Some(Placed {
                name,
                memory,
                bytes,
                cycles,
            })
        })()
        .ok_or_else(|| format!("pc-profile: unreadable row {line:?}"))?;
        placed.push(row);
    }
    if placed.is_empty() {
        return Err(format!("pc-profile printed no {PLACED_TITLE:?} table"));
    }
    Ok(Profile {
        frames,
        regions: table("where the CPU runs:")?,
        functions: table("own cycles:")?,
        placed,
    })
}

/// What a memory for code holds and leaves: its name, bytes used and bytes left.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CodeRoom {
    /// As the report names it.
    pub name: String,
    /// Bytes its sections take.
    pub used: u32,
    /// Bytes left (for IWRAM: above the stack's reserve).
    pub left: u32,
}

/// Functions of at least this many bytes are listed in the fast-memory table (smaller ones
/// are the linker's veneers and the kernels' variants).
const PLACED_BYTES_MIN: u32 = 200;
/// Rows of the table of the cartridge's hottest code.
const ROM_ROWS: usize = 10;

/// The subsection on what the fast memories hold: `rooms` (IWRAM and the VRAM regions for
/// code), every function of them with its bytes and what they buy per frame, and the hottest
/// code left in the cartridge.
pub fn placement_section(profile: &Profile, rooms: &[CodeRoom]) -> String {
    let mut doc = String::new();
    doc.push_str(
        "\n### What the fast memories hold, and what their bytes buy\n\n\
         IWRAM fetches an ARM instruction in 1 cycle, the VRAM Mode 4 leaves free in 2 and the \
         cartridge in about 4, and the first two are full: code moved into one means other code \
         moved out (docs/ARCHITECTURE.md). The room left, from the ELF's sections, linker.ld's \
         regions and the boot line's stack room:\n\n\
         | memory | bytes of code and data | left |\n|---|---|---|\n",
    );
    for room in rooms {
        doc.push_str(&format!(
            "| {} | {} | {} |\n",
            room.name,
            group_digits(u64::from(room.used)),
            group_digits(u64::from(room.left))
        ));
    }
    let mut fast: Vec<&Placed> = profile
        .placed
        .iter()
        .filter(|row| row.memory != "ROM" && row.bytes >= PLACED_BYTES_MIN)
        .collect();
    let per_100_bytes = |row: &Placed| row.cycles * 100.0 / f64::from(row.bytes.max(1));
    fast.sort_by(|a, b| {
        per_100_bytes(a)
            .total_cmp(&per_100_bytes(b))
            .then(a.name.cmp(&b.name))
    });
    doc.push_str(&format!(
        "\nThe functions of at least {PLACED_BYTES_MIN} bytes in them, by the cycles per frame each \
         100 of their bytes take in the profile above (the least first: what fast memory holds \
         for the least). The profile draws 120×80 frames and runs no game tick, so the 240-wide \
         kernels, the half-width floors' and the tick's code read 0 here; they earn their room \
         at 240×160 and in `cargo bench-tick`:\n\n\
         | function | memory | bytes | cycles per frame | per 100 bytes |\n|---|---|---|---|---|\n"
    ));
    for row in fast {
        doc.push_str(&format!(
            "| `{}` | {} | {} | {} | {} |\n",
            row.name.replace('|', "\\|"),
            row.memory,
            group_digits(u64::from(row.bytes)),
            thousands(row.cycles),
            thousands(per_100_bytes(row))
        ));
    }
    doc.push_str(&format!(
        "\nThe {ROM_ROWS} hottest functions in the cartridge (the bench scene's own log lines and \
         flight among them, outside `Renderer::render`):\n\n\
         | function | bytes | cycles per frame |\n|---|---|---|\n"
    ));
    for row in profile
        .placed
        .iter()
        .filter(|row| row.memory == "ROM")
        .take(ROM_ROWS)
    {
        doc.push_str(&format!(
            "| `{}` | {} | {} |\n",
            row.name.replace('|', "\\|"),
            group_digits(u64::from(row.bytes)),
            thousands(row.cycles)
        ));
    }
    doc
}

/// Profiles the shipped ROM's ELF `elf` over the bench map's default 120×80 run.
pub fn measure(elf: &Path) -> TaskResult<Profile> {
    eprintln!(
        "== profile of the bench map's default 120x80 run ({})",
        elf.display()
    );
    let script = rom_target_dir().join("bench-profile.keys");
    write_file(&script, b"0-3: R\n")?;
    let output = cargo()
        .args(["run", "--quiet", "--release", "-p", "portalcast-harness"])
        .args(["--bin", "pc-profile", "--"])
        .arg(elf)
        .arg("--keys")
        .arg(&script)
        .args(["--from", FROM, "--until", UNTIL, "--per-line", FROM])
        .args(["--frames", "100000", "--top", "1000"])
        .output()
        .map_err(|error| TaskError(format!("running pc-profile: {error}")))?;
    if !output.status.success() {
        return Err(TaskError(format!(
            "pc-profile failed: {}",
            String::from_utf8_lossy(&output.stderr).trim()
        )));
    }
    parse(&String::from_utf8_lossy(&output.stdout)).map_err(TaskError)
}

/// The stage a function belongs to, for the summary line: by the module path in its name.
fn stage(name: &str) -> &'static str {
    if name.starts_with("pc_col")
        || name.starts_with("pc_flat")
        || name.starts_with("pc_span")
        || name.starts_with("pc_sprite")
    {
        "kernels"
    } else if name == "pc_wall_run"
        || name.contains("raster::wall_run")
        || name == "pc_middle_columns"
    {
        // The ARM wall loop (asm/wall.s): the columns' set-up; its kernels are their own. The
        // portal middles' column loop (asm/middle.s), like the rest of the things stage that
        // the walk runs.
        "wall set-up and the portal walk"
    } else if name == "pc_plane_run"
        || name.contains("raster::plane_run")
        || name.contains("render::planes")
        || name.contains("render::spans")
        || name.contains("as portalcast::raster::Canvas>::flat")
    {
        // The ARM span loop (asm/plane.s) too: the spans' set-up; its kernels are their own.
        "plane set-up"
    } else if name.contains("render::") || name.contains("as portalcast::raster::Canvas>::column") {
        "wall set-up and the portal walk"
    } else if name == "?" {
        "BIOS (the wait for VBlank)"
    } else {
        "the bench scene, its log lines and the rest"
    }
}

/// The section of docs/BENCH.md.
pub fn section(profile: &Profile) -> String {
    let mut doc = String::new();
    doc.push_str("## Where the cycles go: a profile of the default 120×80 frames\n\n");
    let total: f64 = profile.regions.iter().map(|row| row.cycles).sum();
    doc.push_str(&format!(
        "`pc-profile` (crates/harness) samples the CPU every 97 cycles in the same mGBA core while the bench scene draws the bench map at 120×80 with the default settings ({} frames, from the run's first frame line to the next run's), and names each sample by the ELF's function symbols. Cycles are per frame drawn, {} in all with the wait for VBlank and the scene's own work around `Renderer::render` (its log line, the flight path). `cargo bench-report` runs it; by hand: `cargo run --release -p portalcast-harness --bin pc-profile -- target/rom/thumbv4t-none-eabi/rom/portalcast --keys FILE --from '{FROM}' --until {UNTIL} --per-line '{FROM}'` with `0-3: R` in FILE.\n\n",
        profile.frames,
        thousands(total)
    ));
    let mut stages: Vec<(&str, f64)> = Vec::new();
    for row in &profile.functions {
        let name = stage(&row.name);
        match stages.iter_mut().find(|(stage, _)| *stage == name) {
            Some((_, cycles)) => *cycles += row.cycles,
            None => stages.push((name, row.cycles)),
        }
    }
    stages.sort_by(|a, b| b.1.total_cmp(&a.1));
    doc.push_str("| stage | cycles per frame | share |\n|---|---|---|\n");
    for (name, cycles) in &stages {
        doc.push_str(&format!(
            "| {name} | {} | {:.1} % |\n",
            thousands(*cycles),
            cycles * 100.0 / total
        ));
    }
    doc.push_str(&format!(
        "\nThe {ROWS} functions with the most cycles of their own (inlined code counts where it was inlined; the wall columns' loop is `pc_wall_run`, asm/wall.s, and the per-wall set-up around it is in `draw_walls`):\n\n| function | cycles per frame | share |\n|---|---|---|\n"
    ));
    for row in profile.functions.iter().take(ROWS) {
        doc.push_str(&format!(
            "| {} | {} | {:.1} % |\n",
            if row.name == "?" {
                "outside every symbol: the BIOS's wait for VBlank".to_string()
            } else {
                format!("`{}`", row.name.replace('|', "\\|"))
            },
            thousands(row.cycles),
            row.cycles * 100.0 / total
        ));
    }
    doc
}

/// `1234567.8` as `1,234,568`.
fn thousands(value: f64) -> String {
    group_digits(value.max(0.0).round() as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    const OUTPUT: &str = "\
1000 samples every 97 cycles over 163 frames (~1000 cycles a line sampled)
63 matching lines

where the CPU runs:
 74.05%    538164/line  IWRAM ARM
 21.04%    152929/line  BIOS

own cycles:
 34.70%    252182/line  <portalcast::render::walk::Renderer<W>>::draw_walls::<C>
 21.11%    153408/line  ?
 14.00%    100000/line  pc_wall_run
  5.58%     40569/line  pc_flat_dbl_lit_k6
  3.00%     20000/line  pc_plane_run
  1.00%      7000/line  pc_sprite_columns

cycles with compiler helpers charged to their caller:
 34.70%    252182/line  x

code by memory (own cycles, bytes, memory, name):
   252182/line   6000 IWRAM <portalcast::render::walk::Renderer<W>>::draw_walls::<C>
   100000/line   1400 IWRAM pc_wall_run
    20000/line   4000 ROM   slow::thing
     7000/line    260 IWRAM pc_sprite_columns
        0/line   1500 IWRAM tick
";

    #[test]
    fn reads_the_tables_and_the_frame_count() {
        let profile = parse(OUTPUT).unwrap();
        assert_eq!(profile.frames, 63);
        assert_eq!(profile.regions.len(), 2);
        assert_eq!(profile.functions[0].cycles, 252_182.0);
        assert_eq!(profile.functions[1].name, "?");
        assert_eq!(profile.functions.len(), 6);
    }

    #[test]
    fn the_section_groups_functions_by_stage() {
        let section = section(&parse(OUTPUT).unwrap());
        assert!(
            section.contains("| wall set-up and the portal walk | 352,182 |"),
            "{section}"
        );
        assert!(section.contains("| kernels | 47,569 |"), "{section}");
        assert!(section.contains("| plane set-up | 20,000 |"), "{section}");
        assert!(
            section.contains("| BIOS (the wait for VBlank) | 153,408 |"),
            "{section}"
        );
    }

    #[test]
    fn the_placement_lists_fast_code_by_what_its_bytes_buy() {
        let profile = parse(OUTPUT).unwrap();
        assert_eq!(profile.placed.len(), 5);
        assert_eq!(profile.placed[1].bytes, 1400);
        let rooms = [CodeRoom {
            name: "IWRAM".to_string(),
            used: 28_388,
            left: 28,
        }];
        let section = placement_section(&profile, &rooms);
        assert!(section.contains("| IWRAM | 28,388 | 28 |"), "{section}");
        // The least per byte first: the tick (0), the sprite columns (2,692 per 100 bytes),
        // the walls (4,203), the wall loop (7,143); the cartridge's code apart.
        let order: Vec<usize> = [
            "`tick`",
            "`pc_sprite_columns`",
            "draw_walls",
            "`pc_wall_run`",
        ]
        .iter()
        .map(|name| section.find(name).unwrap())
        .collect();
        assert!(order.windows(2).all(|pair| pair[0] < pair[1]), "{section}");
        assert!(
            section.contains("| `slow::thing` | 4,000 | 20,000 |"),
            "{section}"
        );
    }

    #[test]
    fn output_without_a_line_count_is_refused() {
        assert!(parse("own cycles:\n 1.0% 5/line f\n").is_err());
    }
}
