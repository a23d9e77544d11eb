//! docs/BENCH.md, written whole from the measurements. Every number in it is formatted from a
//! measurement or from a named constant; the prose around the tables says how they are made.

use std::fmt::Write;

use portalcast_xtask::baseline::{self, TOLERANCE_PERCENT};
use portalcast_xtask::bench_log::{group_digits, Run, Summary};

use super::sizes::{EWRAM, IWRAM, ROM, VRAM};
use super::{Measurements, CHART_FILE, CPU_HZ, CYCLES_PER_FRAME};

/// The thesis' frame rate at 120×80 without lighting (Espada Brau, 2006).
const THESIS_FPS: u64 = 35;
/// The resolution the thesis measured.
const THESIS_RESOLUTION: &str = "120x80";

/// The targets of issue #7: 60 fps at 120×80, 30 fps at 240×160, as (fps, cycles per frame).
pub(super) fn target(resolution: &str) -> Option<(u64, u64)> {
    match resolution {
        "120x80" => Some((60, CYCLES_PER_FRAME)),
        "240x160" => Some((30, 2 * CYCLES_PER_FRAME)),
        _ => None,
    }
}

/// What each measured kernel is, and its target in cycles per pixel where the brief sets one.
const KERNELS: [(&str, &str, Option<f64>); 11] = [
    (
        "col_dbl_unlit",
        "column, 120-wide (STRB mirrored), unlit",
        Some(6.0),
    ),
    ("col_dbl_lit", "column, 120-wide, lit", Some(9.0)),
    (
        "col_native_lit",
        "column, 240-wide, alone (read-modify-write), lit",
        None,
    ),
    (
        "col_pair_lit",
        "column pair, 240-wide (one store for two pixels), lit",
        None,
    ),
    ("flat_dbl_unlit", "span, 120-wide, unlit", None),
    ("flat_dbl_lit", "span, 120-wide, lit", Some(9.0)),
    ("flat_pair_unlit", "span, 240-wide pairs, unlit", None),
    ("flat_pair_lit", "span, 240-wide pairs, lit", Some(9.0)),
    (
        "sprite_dbl",
        "sprite post, 120-wide (STRB mirrored), lit",
        None,
    ),
    (
        "sprite_native",
        "sprite post, 240-wide (read-modify-write), lit",
        None,
    ),
    (
        "sprite_blend_dbl",
        "sprite post, 120-wide, lit, translucent (blend table in ROM)",
        None,
    ),
];

/// What each stage the ROM times covers.
fn stage_meaning(stage: &str) -> &'static str {
    match stage {
        "walk" => "the sector walk itself: visits, clip windows, portal recursion",
        "wall" => "walls and strips: column ownership, projection, the wall and strip columns and their kernels",
        "plane" => "floors and ceilings: span set-up, `R_MakeSpans`, the span kernels (and the sky, while it has no stage of its own)",
        "sky" => "the sky's columns",
        "thing" => "things and portal middles: their drawing, back to front (their collection, per visit, is in the wall stage)",
        _ => "(a stage this report has no description for yet)",
    }
}

/// `120x80` → `120×80 (2×2)`: how the docs name a resolution.
pub fn resolution_name(resolution: &str) -> String {
    match resolution {
        "120x80" => "120×80 (2×2)".to_string(),
        other => other.replace('x', "×"),
    }
}

pub(super) fn fps(cycles: u64) -> f64 {
    if cycles == 0 {
        0.0
    } else {
        CPU_HZ as f64 / cycles as f64
    }
}

/// The settings of `run` that differ from `base`'s, as `key=value` words.
fn differences(base: &Run, run: &Run) -> Vec<String> {
    run.settings
        .iter()
        .filter(|(key, value)| base.setting(key) != Some(value.as_str()))
        .map(|(key, value)| format!("{key}={value}"))
        .collect()
}

/// The settings of `run` other than the resolution, as `key=value` words.
fn label_without_resolution(run: &Run) -> String {
    run.settings
        .iter()
        .filter(|(key, _)| key != "res")
        .map(|(key, value)| format!("{key}={value}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// The guard's run (bench map, defaults) at `run`'s resolution.
fn default_run<'m>(measurements: &'m Measurements, run: &Run) -> Option<&'m Run> {
    measurements
        .guard()
        .iter()
        .find(|guard| guard.setting("res") == run.setting("res"))
}

/// A run's name in the chart's legend: the map, and the settings that differ from the defaults.
pub fn short_label(measurements: &Measurements, run: &Run) -> String {
    let Some(base) = default_run(measurements, run) else {
        return run.key();
    };
    let changed = differences(base, run);
    let mut words = vec![run.map.clone()];
    if changed.is_empty() {
        words.push("defaults".to_string());
    }
    words.extend(changed);
    words.join(", ")
}

/// The stage names of `runs`, in order of appearance.
fn stage_names(runs: &[&Run]) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for run in runs {
        for (name, _) in run.summary().stage_means {
            if !names.contains(&name) {
                names.push(name);
            }
        }
    }
    names
}

fn stage_cells(summary: &Summary, names: &[String]) -> String {
    let mut cells = String::new();
    for name in names {
        let mean = summary
            .stage_means
            .iter()
            .find(|(stage, _)| stage == name)
            .map_or(0, |(_, cycles)| *cycles);
        let _ = write!(cells, " {} |", group_digits(mean));
    }
    let _ = write!(cells, " {} |", group_digits(summary.other_mean));
    cells
}

fn accuracy_cells(measurements: &Measurements, run: &Run) -> String {
    match measurements.accuracy_of(run) {
        Some(accuracy) => format!(
            " {:.3} | {:.2} | {} | {} | {} |",
            accuracy.percent_of_pixels("surface_mismatches"),
            accuracy.percent_of_pixels("texel_mismatches"),
            accuracy.counter("wall_edge_px"),
            accuracy.counter("missed_sectors"),
            accuracy.counter("missed_things"),
        ),
        None => " — | — | — | — | — |".to_string(),
    }
}

fn cycle_cells(summary: &Summary) -> String {
    format!(
        " {} | {} | {} | {} | {:.1} |",
        group_digits(summary.mean),
        group_digits(summary.p50),
        group_digits(summary.p95),
        group_digits(summary.max),
        fps(summary.mean),
    )
}

fn stage_headers(names: &[String]) -> (String, String) {
    let mut header = String::new();
    let mut rule = String::new();
    for name in names {
        let _ = write!(header, " {name} |");
        rule.push_str("---|");
    }
    header.push_str(" other |");
    rule.push_str("---|");
    (header, rule)
}

/// Every run's cycles as one table (`cargo bench-rom` prints it).
pub fn cycle_table(runs: &[Run]) -> String {
    let all: Vec<&Run> = runs.iter().collect();
    let names = stage_names(&all);
    let (stage_header, stage_rule) = stage_headers(&names);
    let mut text = format!(
        "| map | settings | frames | mean | p50 | p95 | max | fps (mean) |{stage_header}\n|---|---|---|---|---|---|---|---|{stage_rule}\n"
    );
    for run in runs {
        let summary = run.summary();
        let _ = writeln!(
            text,
            "| {} | {} | {} |{}{}",
            run.map,
            run.label(),
            summary.frames,
            cycle_cells(&summary),
            stage_cells(&summary, &names)
        );
    }
    text
}

/// The gap between a run and its target, in words.
fn gap(summary: &Summary, target_cycles: u64) -> String {
    let times = |cycles: u64| cycles as f64 / target_cycles as f64;
    if summary.max <= target_cycles {
        "**met**: every frame within".to_string()
    } else if summary.mean <= target_cycles {
        format!("mean within; **max {:.1}× over**", times(summary.max))
    } else {
        format!(
            "**{:.1}× / {:.1}× over**",
            times(summary.mean),
            times(summary.max)
        )
    }
}

/// The whole of docs/BENCH.md.
pub fn write(measurements: &Measurements) -> String {
    let mut doc = String::new();
    intro(&mut doc);
    headline(&mut doc, measurements);
    method(&mut doc, measurements);
    knobs(&mut doc, measurements);
    maps(&mut doc, measurements);
    slope_knob(&mut doc, measurements);
    generated_maps(&mut doc, measurements);
    // The section brings its own heading (`report::freedoom`).
    doc.push_str(&measurements.freedoom_section);
    doc.push('\n');
    chart(&mut doc);
    instruction_set(&mut doc, measurements);
    kernels(&mut doc, measurements);
    set_up(&mut doc, measurements);
    doc.push_str(&super::cost_model::section(
        measurements.guard(),
        &measurements.setup_runs,
    ));
    doc.push('\n');
    // The section brings its own heading.
    doc.push_str(&measurements.profile_section);
    doc.push('\n');
    accuracy(&mut doc, measurements);
    sizes(&mut doc, measurements);
    // The section brings its own heading (`cargo bench-tick` prints the same block).
    doc.push_str(&measurements.tick_section);
    doc.push('\n');
    // The same again for the log lines' section (`cargo bench-logging`).
    doc.push_str(&measurements.logging_section);
    doc.push('\n');
    // The section brings its own heading (`cargo bench-math` writes the same block).
    doc.push_str(&measurements.math_section);
    doc.push_str("\n\n");
    guard(&mut doc, measurements);
    doc
}

fn intro(doc: &mut String) {
    let _ = write!(
        doc,
        "# portalcast benchmarks\n\n\
         <!-- Written by `cargo bench-report` (crates/xtask/src/report/): edit the generator, not this file. -->\n\n\
         Every figure here is measured by one command, `cargo bench-report`: it builds the ROM, runs it \
         in the real mGBA core (Debian's libmgba) through the harness, compares the engine with the f64 \
         oracle on the host, and writes this file and the chart [`{chart}`]({chart_link}) from nothing. \
         mGBA's cycle counts are deterministic, so the same sources give the same file: \
         `cargo bench-report --check` regenerates both in memory and fails if they differ from the \
         committed ones. The CPU runs {hz} cycles a second and the display shows a frame every {frame} \
         cycles: a frame drawn at 60 fps has {frame} cycles, at 30 fps {frame30}.\n\n",
        chart = CHART_FILE,
        chart_link = CHART_FILE.trim_start_matches("docs/"),
        hz = group_digits(CPU_HZ),
        frame = group_digits(CYCLES_PER_FRAME),
        frame30 = group_digits(2 * CYCLES_PER_FRAME),
    );
}

fn headline(doc: &mut String, measurements: &Measurements) {
    let guard = measurements.guard();
    let Some(first) = guard.first() else {
        return;
    };
    let _ = write!(
        doc,
        "## Headline: the bench map against the targets\n\n\
         The bench map at the default settings ({}), {} frames along its fly-through, cycles per \
         frame of `Renderer::render` measured by the ROM:\n\n\
         | resolution | mean | p95 | max | fps (mean) | target | gap (mean / max) |\n\
         |---|---|---|---|---|---|---|\n",
        label_without_resolution(first),
        first.frames.len(),
    );
    for run in guard {
        let summary = run.summary();
        let resolution = run.setting("res").unwrap_or("?");
        let (target_text, gap_text) = match target(resolution) {
            Some((target_fps, cycles)) => (
                format!("every frame ≤ {} ({target_fps} fps)", group_digits(cycles)),
                gap(&summary, cycles),
            ),
            None => ("—".to_string(), "—".to_string()),
        };
        let _ = writeln!(
            doc,
            "| {} | {} | {} | {} | {:.1} | {target_text} | {gap_text} |",
            resolution_name(resolution),
            group_digits(summary.mean),
            group_digits(summary.p95),
            group_digits(summary.max),
            fps(summary.mean),
        );
    }
    doc.push('\n');
    let thesis_cycles = CPU_HZ / THESIS_FPS;
    let unlit = guard
        .iter()
        .find(|run| run.setting("res") == Some(THESIS_RESOLUTION))
        .and_then(|base| {
            measurements.runs.iter().find(|run| {
                run.map == base.map && differences(base, run) == ["lighting=off".to_string()]
            })
        });
    let _ = write!(
        doc,
        "The thesis reached {THESIS_FPS} fps at {} without lighting (about {} cycles a frame). ",
        resolution_name(THESIS_RESOLUTION),
        group_digits(thesis_cycles)
    );
    if let Some(run) = unlit {
        let summary = run.summary();
        let ratio = summary.mean as f64 / thesis_cycles as f64;
        // Within 10 % a ratio to one decimal reads "1.0×": give the percentage instead.
        let comparison = match ratio {
            r if r >= 1.1 => format!("**{r:.1}× slower than the thesis**"),
            r if r >= 1.0 => format!("**{:.1} % slower than the thesis**", (r - 1.0) * 100.0),
            r if r > 1.0 / 1.1 => {
                format!(
                    "**{:.1} % faster than the thesis**",
                    (1.0 / r - 1.0) * 100.0
                )
            }
            r => format!("**{:.1}× faster than the thesis**", 1.0 / r),
        };
        let _ = write!(
            doc,
            "portalcast draws the bench map at {} without lighting at {:.1} fps (mean {} cycles): \
             {comparison}. The thesis measured its own scene; this is the bench map's \
             fly-through in mGBA.\n\n",
            resolution_name(THESIS_RESOLUTION),
            fps(summary.mean),
            group_digits(summary.mean),
        );
    } else {
        doc.push_str("(The bench scene measured no unlit run at that resolution.)\n\n");
    }
}

fn method(doc: &mut String, measurements: &Measurements) {
    let frames = measurements
        .guard()
        .first()
        .map_or(0, |run| run.frames.len());
    let bench_map = measurements.guard().first().map(|run| run.map.clone());
    let other_frames = measurements
        .runs
        .iter()
        .find(|run| Some(&run.map) != bench_map.as_ref())
        .map_or(0, |run| run.frames.len());
    let mut stages = stage_names(&measurements.runs.iter().collect::<Vec<_>>());
    stages.push("other".to_string());
    let _ = write!(
        doc,
        "## How the figures are made\n\n\
         The ROM's bench scene (R held at power-on) flies one fixed camera path through every map \
         (`crates/rom/src/flight.rs`): from the player start, a depth-first tour of the sectors a walker can \
         pass between, through the middle of each portal to the next sector's centre and back out \
         of dead ends, at about Doom's running speed, the eye at standing height, turning smoothly \
         towards where it goes. Like a player, it keeps clear of solid things: where one stands at \
         a sector's centre (the bench map's statue) the path stops short of it, and it goes round \
         one in its way. The path is derived from the map alone, so every map has one, and \
         every pose is exact in the engine's formats, so the host replays the ROM's frames exactly. \
         The path is flown through the map's live world (`crates/rom/src/live_flight.rs`), a game tick a \
         frame: the camera waits at a shut door and opens it, rides a lift standing on it, \
         and the light effects run, so the frames include movers mid-motion. \
         For each map and setting the ROM draws one unmeasured frame (it fills the per-resolution \
         tables, the column angles), then {frames} frames along the path on the bench map ({} on \
         every other map, the generated ones included), timing \
         `Renderer::render` with its cycle meter (timers 2 and 3 cascaded) and printing one line per \
         frame with the cycles of each stage:\n\n",
        other_frames
    );
    for stage in &stages {
        let meaning = if stage == "other" {
            "the rest of the frame, outside the named stages"
        } else {
            stage_meaning(stage)
        };
        let _ = writeln!(doc, "- `{stage}`: {meaning};");
    }
    let _ = write!(
        doc,
        "\nmean, p50 (median), p95 and max are over the frames of a run, the stage columns are \
         means, and fps (mean) is what the mean implies ({} / mean cycles); a frame shown at \
         the display's pace takes a whole number of {}-cycle frames. The bench scene runs the \
         regression guard's part first (the bench map at the default settings, at every \
         resolution), then the rest: `cargo bench-rom` prints just its cycle tables, without the \
         accuracy pass, and writes nothing.\n\n",
        group_digits(CPU_HZ),
        group_digits(CYCLES_PER_FRAME),
    );
}

fn knob_table(doc: &mut String, measurements: &Measurements, base: &Run) {
    let runs: Vec<&Run> = measurements
        .runs
        .iter()
        .filter(|run| run.map == base.map && run.setting("res") == base.setting("res"))
        .collect();
    let names = stage_names(&runs);
    let (stage_header, stage_rule) = stage_headers(&names);
    let _ = writeln!(
        doc,
        "| setting | mean | p50 | p95 | max | fps (mean) |{stage_header} surface % | texel % | wall edge (px) | missed sectors | missed things |\n\
         |---|---|---|---|---|---|{stage_rule}---|---|---|---|---|"
    );
    for run in runs {
        let changed = differences(base, run);
        let setting = if changed.is_empty() {
            format!("defaults ({})", label_without_resolution(run))
        } else {
            changed.join(" ")
        };
        let summary = run.summary();
        let _ = writeln!(
            doc,
            "| {setting} |{}{}{}",
            cycle_cells(&summary),
            stage_cells(&summary, &names),
            accuracy_cells(measurements, run)
        );
    }
    doc.push('\n');
}

fn knobs(doc: &mut String, measurements: &Measurements) {
    let Some(first) = measurements.guard().first() else {
        return;
    };
    let _ = write!(
        doc,
        "## Knobs on the bench map\n\n\
         One knob at a time from the defaults ({}), at every resolution, each along the same \
         fly-through. Cycles per frame; stage columns are means; the last four columns are the \
         accuracy against the oracle (see [Accuracy](#accuracy-against-the-f64-oracle)). The \
         knobs (`src/render/view.rs`; the Start menu changes each live):\n\n\
         - `lighting`: `off`, `sector` (each sector's light level), `depth` (sector light \
           darkened with distance, through the colormap);\n\
         - `tex`: texels read from the EWRAM copy (`ewram`: the textures that fit it, the most used first; all of the shipped ones; at 120×80 the hottest mip chains are read from the page rows that resolution leaves free in VRAM instead, `hw::memory::LentPageRows`) or the cartridge (`rom`);\n\
         - `prep`: the thesis' scene preprocessing: `on` plans the portal walk first and draws \
           each sector once over the touching columns of its visits (`src/render/visits.rs`), \
           `off` draws each visit as the walk reaches it;\n\
         - `floors`: floors and ceilings at the walls' horizontal resolution (`full`), or at \
           half of it under 240-wide walls (`half`, the Southpaw engine's trade in Doom II and \
           Duke Nukem Advance): each VRAM halfword of a span shows one texel, its even pixel's, \
           drawn by the 120-wide span kernels with a doubled step. Measured at 240×160 only: at \
           120 wide a halfword already holds one texel, so the value would change nothing and \
           is not offered there (the menu shows `-`).\n\n\
         Which wall owns a column is always decided exactly, from cross products of each vertex \
         against the column rays, once per vertex and frame. A precision knob rounded each \
         vertex's screen `x` to 16.16 or 24.8 instead (the thesis' way missed sectors: this \
         file as of commit 0ddd37d has its figures); once the exact split was cached per vertex \
         and frame, a rounded projection cost as much as the exact one and bought nothing, so \
         the knob was removed (issue 15).\n\n",
        label_without_resolution(first)
    );
    for base in measurements.guard() {
        let _ = write!(
            doc,
            "### {}\n\n",
            resolution_name(base.setting("res").unwrap_or("?"))
        );
        knob_table(doc, measurements, base);
    }
    half_floors(doc, measurements);
}

/// The `floors=half` run against the defaults at 240×160, and both against the 30 fps target.
fn half_floors(doc: &mut String, measurements: &Measurements) {
    let resolution = "240x160";
    let Some(base) = measurements
        .guard()
        .iter()
        .find(|run| run.setting("res") == Some(resolution))
    else {
        return;
    };
    let Some(half) = measurements
        .runs
        .iter()
        .find(|run| run.map == base.map && differences(base, run) == ["floors=half".to_string()])
    else {
        return;
    };
    let Some((target_fps, budget)) = target(resolution) else {
        return;
    };
    let (full_summary, half_summary) = (base.summary(), half.summary());
    let plane = |summary: &Summary| {
        summary
            .stage_means
            .iter()
            .find(|(stage, _)| stage == "plane")
            .map_or(0, |(_, cycles)| *cycles)
    };
    let saved = |before: u64, after: u64| 100.0 * (before as f64 - after as f64) / before as f64;
    let over = |cycles: u64| {
        if cycles <= budget {
            "within it".to_string()
        } else {
            format!(
                "{} cycles over ({:.1}× the budget)",
                group_digits(cycles - budget),
                cycles as f64 / budget as f64
            )
        }
    };
    let accuracy = |run: &Run| {
        measurements.accuracy_of(run).map_or_else(
            || "— / —".to_string(),
            |accuracy| {
                format!(
                    "{:.2} % / {:.3} %",
                    accuracy.percent_of_pixels("texel_mismatches"),
                    accuracy.percent_of_pixels("surface_mismatches")
                )
            },
        )
    };
    let _ = write!(
        doc,
        "### Half-width floors at {name}\n\n\
         At {name} the bench map's mean is {full_mean} cycles a frame with full-width floors and \
         {half_mean} with `floors=half` ({mean_saved:.1} % less; max {full_max} → {half_max}, \
         {max_saved:.1} % less), the plane stage {full_plane} → {half_plane} ({plane_saved:.1} % \
         less: the span set-up per span stays, the kernels' texel work halves). Against the \
         oracle, texel % / surface % go from {full_accuracy} to {half_accuracy}: every odd \
         column of a floor repeats its left neighbour's texel.\n\n\
         The {target_fps} fps target is {budget} cycles a frame. With full-width floors the mean \
         is {full_gap} and the max {full_max_gap}; with half-width floors the mean is still \
         {half_gap} and the max {half_max_gap}. {verdict}\n\n",
        name = resolution_name(resolution),
        full_mean = group_digits(full_summary.mean),
        half_mean = group_digits(half_summary.mean),
        mean_saved = saved(full_summary.mean, half_summary.mean),
        full_max = group_digits(full_summary.max),
        half_max = group_digits(half_summary.max),
        max_saved = saved(full_summary.max, half_summary.max),
        full_plane = group_digits(plane(&full_summary)),
        half_plane = group_digits(plane(&half_summary)),
        plane_saved = saved(plane(&full_summary), plane(&half_summary)),
        full_accuracy = accuracy(base),
        half_accuracy = accuracy(half),
        budget = group_digits(budget),
        full_gap = over(full_summary.mean),
        full_max_gap = over(full_summary.max),
        half_gap = over(half_summary.mean),
        half_max_gap = over(half_summary.max),
        verdict = if half_summary.max <= budget {
            format!(
                "Half-width floors reach {target_fps} fps at {} on every frame.",
                resolution_name(resolution)
            )
        } else {
            format!(
                "Half-width floors do not reach {target_fps} fps at {} yet: every frame within the \
                 target needs the slowest one {} cycles ({:.1} %) cheaper still, the mean {} \
                 ({:.1} %).",
                resolution_name(resolution),
                group_digits(half_summary.max - budget),
                saved(half_summary.max, budget),
                group_digits(half_summary.mean.saturating_sub(budget)),
                saved(half_summary.mean, budget).max(0.0),
            )
        },
    );
}

fn maps(doc: &mut String, measurements: &Measurements) {
    let runs: Vec<&Run> = measurements
        .runs
        .iter()
        .filter(|run| {
            default_run(measurements, run).is_some_and(|base| differences(base, run).is_empty())
        })
        .collect();
    let names = stage_names(&runs);
    let (stage_header, stage_rule) = stage_headers(&names);
    let _ = writeln!(
        doc,
        "## Every shipped map\n\n\
         Each map's own fly-through at the default settings.\n\n\
         | map | resolution | mean | p50 | p95 | max | fps (mean) |{stage_header} surface % | texel % | wall edge (px) | missed sectors | missed things |\n\
         |---|---|---|---|---|---|---|{stage_rule}---|---|---|---|---|"
    );
    for run in runs {
        let summary = run.summary();
        let _ = writeln!(
            doc,
            "| {} | {} |{}{}{}",
            run.map,
            resolution_name(run.setting("res").unwrap_or("?")),
            cycle_cells(&summary),
            stage_cells(&summary, &names),
            accuracy_cells(measurements, run)
        );
    }
    doc.push('\n');
}

/// The slope-mapping knob on each map whose runs vary it, at every resolution: the map's
/// default run and the other values of `slp=`.
fn slope_knob(doc: &mut String, measurements: &Measurements) {
    let bases: Vec<&Run> = measurements
        .runs
        .iter()
        .filter(|run| {
            default_run(measurements, run).is_some_and(|base| differences(base, run).is_empty())
                && measurements.runs.iter().any(|other| {
                    other.map == run.map
                        && other.setting("res") == run.setting("res")
                        && differences(run, other).len() == 1
                        && differences(run, other)[0].starts_with("slp=")
                })
        })
        .collect();
    if bases.is_empty() {
        return;
    }
    let _ = write!(
        doc,
        "## Knob: slope mapping\n\n\
         Sloped floors and ceilings are texture-mapped in perspective, exact every `N` pixels \
         along a span and affine between (`slp=N`, `src/render/planes.rs`; the default is \
         16). Flat planes are exact per row whatever `N`, so the knob is measured on the maps \
         with slopes, along their own fly-throughs. The texel column is the share of pixels \
         whose palette index differs from the f64 oracle's, which maps every pixel exactly: \
         `slp=1`'s figure is what the rest of the frame (walls, flat planes, rounding) \
         leaves, and each larger `N` adds its affine drift to it. The shipped slopes map also \
         holds room over room (a canyon whose pit opens into the air above it, and a bridge \
         over a walkway: docs/MAP_FORMAT.md, \"Room over room\"), so its rows are the figures \
         of a map with slopes and layers.\n\n"
    );
    // The headline's targets, for the maps with slopes at their defaults.
    let _ = writeln!(
        doc,
        "At the defaults, against the headline's targets:\n\n\
         | map | resolution | mean | max | target | gap (mean / max) |\n\
         |---|---|---|---|---|---|"
    );
    for base in &bases {
        let resolution = base.setting("res").unwrap_or("?");
        let Some((fps, cycles)) = target(resolution) else {
            continue;
        };
        let summary = base.summary();
        let _ = writeln!(
            doc,
            "| {} | {} | {} | {} | every frame ≤ {} ({fps} fps) | {} |",
            base.map,
            resolution_name(resolution),
            group_digits(summary.mean),
            group_digits(summary.max),
            group_digits(cycles),
            gap(&summary, cycles)
        );
    }
    doc.push('\n');
    for base in bases {
        let _ = write!(
            doc,
            "### {}, {}\n\n",
            base.map,
            resolution_name(base.setting("res").unwrap_or("?"))
        );
        knob_table(doc, measurements, base);
    }
}

/// The soak's bound on one frame (`tests/emulator_soak.rs`, `tests/emulator_generated.rs`).
const SOAK_FRAME_BOUND: u64 = 16 * CYCLES_PER_FRAME;

fn generated_maps(doc: &mut String, measurements: &Measurements) {
    let maps = portalcast_xtask::generated_maps::generated_maps();
    let defaults = |run: &Run| {
        measurements
            .guard()
            .iter()
            .find(|guard| guard.setting("res") == run.setting("res"))
            .is_some_and(|base| differences(base, run).is_empty())
    };
    let _ = writeln!(
        doc,
        "## Generated maps: the worst frames\n\n\
         Maps of kinds the shipped ones do not cover, generated by \
         `crates/xtask/src/generated_maps.rs` (issue 16) and built into a ROM from their own \
         directory as a user's maps are (`cargo generated-maps DIR`, then \
         `PORTALCAST_ASSETS=DIR cargo bench-rom`), each flown at the default settings. The \
         soak's bound on one frame is {} cycles (16 display frames); \
         `tests/emulator_generated.rs` holds every frame of these flights under it, and \
         docs/RELIABILITY.md records their long soak and oracle passes.\n\n\
         | map | kind | resolution | mean | max | fps (mean) | max, of the soak's bound |\n\
         |---|---|---|---|---|---|---|",
        group_digits(SOAK_FRAME_BOUND)
    );
    for run in measurements
        .generated_runs
        .iter()
        .filter(|run| defaults(run))
    {
        let summary = run.summary();
        let kind = maps
            .iter()
            .find(|map| map.name == run.map)
            .map_or("", |map| map.kind);
        let _ = writeln!(
            doc,
            "| {} | {kind} | {} | {} | {} | {:.1} | {:.0} % |",
            run.map,
            resolution_name(run.setting("res").unwrap_or("?")),
            group_digits(summary.mean),
            group_digits(summary.max),
            fps(summary.mean),
            100.0 * summary.max as f64 / SOAK_FRAME_BOUND as f64
        );
    }
    doc.push('\n');
}

fn chart(doc: &mut String) {
    let _ = write!(
        doc,
        "## Cycles along the fly-through\n\n\
         ![Cycles per frame along the fly-through, one panel per resolution]({})\n\n\
         One panel per resolution: every run's cycles per frame along its path, with the 60 and \
         30 fps budgets dashed. The bench map's runs share one path, so their lines differ only by \
         the knob; the other maps fly their own.\n\n",
        CHART_FILE.trim_start_matches("docs/")
    );
}

fn instruction_set(doc: &mut String, measurements: &Measurements) {
    if measurements.thumb_engine_runs.is_empty() {
        return;
    }
    doc.push_str(
        "## Knob: the engine's instruction set\n\n\
         The ROM targets `thumbv4t-none-eabi`: `core`, compiler-builtins and the gba runtime are \
         Thumb code, and the kernels are ARM assembly. The `portalcast` package itself (the \
         engine and the ROM binary) is compiled as ARM code by the `rom` cargo profile \
         (`-Ctarget-feature=-thumb-mode`); its hot functions run from IWRAM, where ARM code is \
         fetched as fast as Thumb and does its 64-bit products in one `SMULL`/`UMULL` instead of \
         a library call. `PORTALCAST_ENGINE_ISA=thumb` builds the engine as Thumb instead (the \
         `release` profile). The report runs the regression guard's part of the bench scene on \
         both:\n\n\
         | resolution | ARM engine mean | Thumb engine mean | ARM max | Thumb max | ARM speed-up (mean) |\n\
         |---|---|---|---|---|---|\n",
    );
    for arm in measurements.guard() {
        let Some(thumb) = measurements
            .thumb_engine_runs
            .iter()
            .find(|thumb| thumb.key() == arm.key())
        else {
            continue;
        };
        let (a, t) = (arm.summary(), thumb.summary());
        let _ = writeln!(
            doc,
            "| {} | {} | {} | {} | {} | {:.2}× |",
            resolution_name(arm.setting("res").unwrap_or("?")),
            group_digits(a.mean),
            group_digits(t.mean),
            group_digits(a.max),
            group_digits(t.max),
            t.mean as f64 / a.mean.max(1) as f64
        );
    }
    doc.push_str(
        "\nMixing the two needs one repair: compiler-builtins writes its four `__aeabi_*divmod` \
         helpers by hand as Thumb code that returns with `pop {pc}`, which does not switch back to \
         ARM state on the ARMv4T. The ROM links them `--wrap`ped to ARM versions in \
         `asm/runtime.s`, and the boot line's `division_digest` is checked against the host's. \
         `#[instruction_set(arm::a32)]` on single functions would be the other way; it is not \
         used because LLVM does not inline across instruction sets, and the renderer is built \
         of small helpers that must inline.\n\n",
    );
}

fn kernels(doc: &mut String, measurements: &Measurements) {
    doc.push_str(
        "## Kernels: cycles per pixel\n\n\
         Measured by the ROM (kernel check scene, L+R held at power-on) with texels and colormap \
         in IWRAM, as the difference between a long and a short run divided by the difference in \
         pixels, so the call and set-up cost cancels:\n\n\
         | kernel | cycles per pixel | target | over the target |\n|---|---|---|---|\n",
    );
    for (key, hundredths) in &measurements.kernels {
        let known = KERNELS.iter().find(|(name, _, _)| name == key);
        let description = known.map_or(key.as_str(), |(_, description, _)| description);
        let cycles = *hundredths as f64 / 100.0;
        let (target_text, over) = match known.and_then(|(_, _, target)| *target) {
            Some(target) if cycles > target => {
                (format!("≤ {target:.0}"), format!("+{:.2}", cycles - target))
            }
            Some(target) => (format!("≤ {target:.0}"), "met".to_string()),
            None => ("—".to_string(), String::new()),
        };
        let _ = writeln!(
            doc,
            "| {description} | {cycles:.2} | {target_text} | {over} |"
        );
    }
    doc.push_str(
        "\n`cargo test --test emulator_foundation` also proves that every kernel variant writes \
         exactly the same VRAM bytes as its Rust twin.\n\n",
    );
}

/// The brief's targets for the renderer's set-up: cycles per wall column and per span.
const WALL_SET_UP_TARGET: u64 = 300;
const SPAN_SET_UP_TARGET: u64 = 100;

/// The mean of a count over a run's frames.
fn mean_count(run: &Run, name: &str) -> u64 {
    let frames = run.frames.len().max(1) as u64;
    let sum: u64 = run
        .frames
        .iter()
        .filter_map(|frame| frame.counts.iter().find(|(key, _)| key == name))
        .map(|(_, value)| value)
        .sum();
    (sum + frames / 2) / frames
}

/// The mean cycles of stage `name` in `summary`.
fn stage_mean(summary: &Summary, name: &str) -> u64 {
    summary
        .stage_means
        .iter()
        .find(|(stage, _)| stage == name)
        .map_or(0, |(_, mean)| *mean)
}

/// `part / whole`, 0 when there is no whole.
fn per(part: u64, whole: u64) -> f64 {
    if whole == 0 {
        0.0
    } else {
        part as f64 / whole as f64
    }
}

/// `≤ target` met, or how far over it.
fn against(value: f64, target: u64) -> String {
    if value <= target as f64 {
        "met".to_string()
    } else {
        format!("**{:.1}× over**", value / target as f64)
    }
}

fn set_up(doc: &mut String, measurements: &Measurements) {
    doc.push_str(
        "## Set-up per wall column and per span, and the kernels as the game runs them\n\n\
         The bench scene ends by flying the guard's runs again (the bench map at the default \
         settings) on a canvas that prepares every kernel call up to its argument block and runs \
         none (`VramCanvas::without_kernels`), and prints each frame's counts \
         (`portalcast_rom::bench::SetupLine`). The wall stage's cycles there, over the wall columns, \
         are the **set-up per wall column**: ownership, projection, rows, clip windows, texture \
         column, mip level and light, the strips' set-up, and the per-wall and per-visit work \
         spread over the columns; the plane stage's, over the spans, the **set-up per span** \
         (`R_MakeSpans`, each span's depth, mip level, texture steps and light, and the sky's \
         columns). What the kernels add to each stage, over the pixels it draws, is their cost \
         per pixel as the game runs them: texels in EWRAM (at 120×80 the hottest chains in the \
         page rows that resolution leaves free in VRAM), the colormap in OBJ VRAM, the call \
         and its dispatch included (the kernel table above has texels and colormap in IWRAM and \
         the call cancelled out). The **set-up a frame** is each stage's cycles there, whole: a \
         change that evaluates fewer columns or spans (the walk's see-through portals) lowers it \
         while the figure per column may rise, the columns left out being the cheapest. Means \
         over the frames of the runs; `cargo bench-rom` prints this table too.\n\n",
    );
    doc.push_str(&set_up_table(
        measurements.guard(),
        &measurements.setup_runs,
    ));
    doc.push('\n');
}

/// The set-up table: each set-up run beside the bench run of the same map and settings.
pub fn set_up_table(runs: &[Run], setup_runs: &[Run]) -> String {
    let mut doc = String::from(
        "| resolution | wall columns | wall set-up a frame | set-up per wall column | target | \
         strips | wall pixels | kernel cycles per wall pixel | spans | plane set-up a frame | \
         set-up per span | target | plane pixels | kernel cycles per plane pixel |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for setup in setup_runs {
        let Some(drawn) = runs.iter().find(|run| run.key() == setup.key()) else {
            continue;
        };
        let (setup_summary, drawn_summary) = (setup.summary(), drawn.summary());
        let (wall_setup, plane_setup) = (
            stage_mean(&setup_summary, "wall"),
            stage_mean(&setup_summary, "plane"),
        );
        let wall_kernels = stage_mean(&drawn_summary, "wall").saturating_sub(wall_setup);
        let plane_kernels = stage_mean(&drawn_summary, "plane").saturating_sub(plane_setup);
        let (columns, strips, spans) = (
            mean_count(setup, "cols"),
            mean_count(setup, "strips"),
            mean_count(setup, "spans"),
        );
        let (wall_pixels, plane_pixels) =
            (mean_count(setup, "wall_px"), mean_count(setup, "plane_px"));
        let per_column = per(wall_setup, columns);
        let per_span = per(plane_setup, spans);
        let _ = writeln!(
            doc,
            "| {} | {} | {} | {:.0} | ≤ {WALL_SET_UP_TARGET}: {} | {} | {} | {:.1} | {} | {} | {:.0} | ≤ {SPAN_SET_UP_TARGET}: {} | {} | {:.1} |",
            resolution_name(setup.setting("res").unwrap_or("?")),
            group_digits(columns),
            group_digits(wall_setup),
            per_column,
            against(per_column, WALL_SET_UP_TARGET),
            group_digits(strips),
            group_digits(wall_pixels),
            per(wall_kernels, wall_pixels),
            group_digits(spans),
            group_digits(plane_setup),
            per_span,
            against(per_span, SPAN_SET_UP_TARGET),
            group_digits(plane_pixels),
            per(plane_kernels, plane_pixels),
        );
    }
    doc
}

fn accuracy(doc: &mut String, measurements: &Measurements) {
    let run_frames = measurements
        .guard()
        .first()
        .map_or(0, |run| run.frames.len());
    let compared = measurements
        .guard()
        .first()
        .and_then(|run| measurements.accuracy_of(run))
        .map_or(0, |line| line.counter("frames") as usize);
    let step = run_frames.checked_div(compared).unwrap_or(0);
    let total: u64 = measurements
        .accuracy
        .iter()
        .map(|line| line.counter("frames"))
        .sum();
    let _ = write!(
        doc,
        "## Accuracy against the f64 oracle\n\n\
         On the host, `bench-accuracy` (crates/oracle) replays every run of the bench scene: every \
         {step}th frame of the path ({compared} of {run_frames}; {total} frames in all) is drawn \
         by the fixed-point engine, through the rasterizer twins, and by the f64 ray-casting \
         oracle (`crates/oracle`), from the same pose with the same viewport and lighting rule, \
         and the two are compared pixel by pixel. The host's engine frames are the ROM's: \
         `cargo test --test emulator_render` proves them identical. The oracle is exact, so a \
         knob only changes the engine's side. The columns:\n\n\
         - **surface %**: pixels showing another surface (a wall, a strip, a floor, a ceiling, \
         the sky) than the oracle's, over all compared pixels. Neighbours with the same floor \
         and ceiling (heights, flats and light) joined by a portal without a middle image show \
         one floor and one ceiling, with no edge between them, and the engine draws them as \
         one plane (Doom's visplanes), so a floor or a ceiling counts as its plane group's \
         (`portalcast_oracle::plane_groups`), in the oracle's frame and the engine's alike;\n\
         - **texel %**: pixels on the right surface with another palette index (rounding at texel \
         edges, and the mip rule: the engine never uses a mip level smaller than its smallest \
         column kernel, the oracle follows the plain `floor(log2(z'/d_y))` rule);\n\
         - **wall edge (px)**: the largest vertical error of a wall's edges: in each column, for \
         every wall or strip both frames show there, the difference between the rows of their \
         top pixels and between the rows of their bottom pixels; the maximum over every column \
         of every compared frame;\n\
         - **missed sectors**: sectors the oracle's frame shows and the engine's does not, added \
         up over the compared frames (the thesis' 24.8 projection lost portals this way), \
         each counted as its plane group;\n\
         - **missed things**: things the oracle's frame shows in two pixels or more and the \
         engine's in none (`portalcast_oracle::MISSED_THING_MIN_PIXELS`), added up likewise. \
         With `things=off` the engine draws none, and the surface % counts their pixels: what \
         the knob gives up.\n\n\
         `cargo test --test render_oracle` bounds the same measures on sampled poses of every \
         map, and `cargo test --test render_host` checks that every pixel of every frame is \
         written exactly once.\n\n"
    );
}

fn sizes(doc: &mut String, measurements: &Measurements) {
    let sizes = &measurements.sizes;
    let boot = |key: &str| {
        measurements
            .boot
            .iter()
            .find(|(name, _)| name == key)
            .map(|(_, value)| *value)
    };
    let rom_code: u64 = sizes
        .sections
        .iter()
        .filter(|section| section.in_file)
        .map(|section| u64::from(section.size))
        .sum();
    let _ = write!(
        doc,
        "## Sizes\n\n\
         From the linked ELF's section headers and the `.gba` file:\n\n\
         | memory | used | of | left |\n|---|---|---|---|\n\
         | ROM (`target/portalcast.gba`) | {} | {} | {} |\n",
        group_digits(sizes.rom_file),
        group_digits(u64::from(ROM.usable)),
        group_digits(u64::from(ROM.usable).saturating_sub(sizes.rom_file)),
    );
    for region in [IWRAM, EWRAM] {
        let used = u64::from(sizes.used(region));
        let _ = writeln!(
            doc,
            "| {} | {} | {} | {} |",
            region.name,
            group_digits(used),
            group_digits(u64::from(region.usable)),
            group_digits(u64::from(region.usable).saturating_sub(used)),
        );
    }
    if let (Some(game), Some(sectors), Some(sector), Some(movers), Some(mover)) = (
        boot("game_bytes"),
        boot("live_sectors"),
        boot("sector_bytes"),
        boot("live_movers"),
        boot("mover_state_bytes"),
    ) {
        let (triggers, trigger) = (
            boot("live_triggers").unwrap_or(0),
            boot("trigger_bytes").unwrap_or(0),
        );
        let _ = write!(
            doc,
            "\nThe game's state (`Game`, in EWRAM) takes {} bytes. Of them, the live world \
             (`portalcast::world`, issue 18): the ROM's largest map with movers or light effects \
             gets a copy of its sector table, {sector} bytes a sector ({sectors} sectors: {} \
             bytes), which holds the moving heights and the effects' light levels; each mover \
             {mover} bytes of state ({movers} movers: {} bytes); and a copy of its switches and \
             walk-over lines, whose switches it throws, {trigger} bytes each ({triggers}: {} \
             bytes). A map with neither movers nor light effects keeps none. The bench scene \
             keeps a world of the same size of its own for its fly-through.\n",
            group_digits(game),
            group_digits(sectors * sector),
            group_digits(movers * mover),
            group_digits(triggers * trigger),
        );
    }
    let _ = write!(
        doc,
        "\nIWRAM's usable size leaves out the {} bytes at its top that the BIOS keeps; what IWRAM \
         has left is the stack's (the linker script asserts a minimum){}. The ROM's allocated \
         sections ({} bytes of them in the file):\n\n\
         | section | runs in | address | bytes |\n|---|---|---|---|\n",
        32 * 1024 - IWRAM.usable,
        match boot("stack_room") {
            Some(room) => format!(
                "; the ROM reports {} bytes of stack room at boot",
                group_digits(room)
            ),
            None => String::new(),
        },
        group_digits(rom_code),
    );
    for section in &sizes.sections {
        let region = [IWRAM, EWRAM, ROM, VRAM]
            .into_iter()
            .find(|region| section.runs_in(*region))
            .map_or("—", |region| region.name);
        let _ = writeln!(
            doc,
            "| `{}` | {region} | 0x{:08x} | {} |",
            section.name,
            section.address,
            group_digits(u64::from(section.size))
        );
    }
    for (index, section) in sizes.sections.iter().enumerate() {
        let shared = sizes.sections[..index]
            .iter()
            .find(|earlier| earlier.address == section.address);
        if let Some(under) = shared {
            // The kernel banks swap at run time; the math benchmark's overlay replaces the
            // renderer for good (linker.ld says why each).
            let how = if section.name.starts_with(".iwram_kernels") {
                ", the other span kernel bank: whichever of the two a call needs is copied in (a \
                 frame draws with one lighting, so it loads at most one; \
                 `hw::kernels::KernelBank`, linker.ld). IWRAM's use above counts the larger once"
            } else if section.name.starts_with(".iwram_columns") {
                ", another of the four column kernel banks: whichever a call needs is copied in \
                 (a frame draws with one lighting at one resolution, so it loads at most one; \
                 `hw::kernels::ColumnBank`, linker.ld). IWRAM's use above counts the largest once"
            } else {
                ": an overlay that the one scene using it copies over that code, which the scene \
                 never runs (linker.ld). IWRAM's use above counts those bytes once"
            };
            let _ = write!(
                doc,
                "\n`{}` shares its run addresses with `{}`{how}.\n",
                section.name, under.name
            );
        }
    }
    doc.push_str(
        "\n`cargo rom` prints the asset compiler's size report (ROM bytes per asset kind, and the \
         RAM each would need if copied) after the build.\n\n",
    );
}

fn guard(doc: &mut String, measurements: &Measurements) {
    let _ = write!(
        doc,
        "## Regression guard\n\n\
         `tests/bench_guard.rs` (part of `cargo xtest` and `cargo test`) runs the guard's part of \
         the bench scene (R and Select held at power-on: the bench map at the default settings, \
         every resolution) and fails if a mean or a max rises more than {TOLERANCE_PERCENT} % \
         above the committed baseline, [`{file}`]({link}); it says so, without failing, when one \
         falls more than {TOLERANCE_PERCENT} % below. Updating the baseline is an explicit, \
         reviewed step: `cargo bench-report --update-baseline` rewrites it (and this file), and \
         the new baseline is committed with the change that moved the figures.\n\n",
        file = baseline::BASELINE_FILE,
        link = baseline::BASELINE_FILE.trim_start_matches("docs/"),
    );
    let Some(committed) = &measurements.baseline else {
        doc.push_str("No baseline is committed yet.\n");
        return;
    };
    doc.push_str(
        "| run | baseline mean | mean now | baseline max | max now |\n|---|---|---|---|---|\n",
    );
    for entry in &committed.entries {
        let now = measurements.guard().iter().find(|run| {
            run.map == entry.field("map").unwrap_or_default()
                && run.setting("res") == entry.field("res")
        });
        let (mean_now, max_now) = now.map_or(("—".to_string(), "—".to_string()), |run| {
            let summary = run.summary();
            (group_digits(summary.mean), group_digits(summary.max))
        });
        let _ = writeln!(
            doc,
            "| {} | {} | {mean_now} | {} | {max_now} |",
            entry.key,
            group_digits(entry.mean),
            group_digits(entry.max)
        );
    }
}
