//! What is left of the frame budget, as a cost model: the set-up runs' stage cycles fitted, by
//! least squares over their frames, to the frame's counts (sector visits, wall columns, strips,
//! things, spans), so each unit's cost is measured from the game's own frames, and the frames
//! over the target are split into what their visits, columns, strips, things, spans and pixels
//! cost.

use std::fmt::Write as _;

use portalcast_xtask::bench_log::{group_digits, Frame, Run};

use super::markdown::{resolution_name, target};

/// The counts the wall stage's set-up is fitted to, as the set-up line names them, and how the
/// report names each.
const WALL_TERMS: [(&str, &str); 4] = [
    ("visits", "per sector visit"),
    ("cols", "per wall column"),
    ("strips", "per strip"),
    ("things", "per thing drawn"),
];

/// The counts the plane stage's set-up is fitted to.
const PLANE_TERMS: [(&str, &str); 2] = [("visits", "per sector visit"), ("spans", "per span")];

/// A stage's set-up fitted to counts: the cycles per unit of each term, then the fixed cycles
/// a frame, and how much of the frames' spread the fit explains.
struct Fit {
    /// Each term's count name and its cycles a unit.
    per_unit: Vec<(&'static str, f64)>,
    fixed: f64,
    r_squared: f64,
}

impl Fit {
    /// The cycles a unit of the count `name` (0 if the fit has no such term).
    fn cost(&self, name: &str) -> f64 {
        self.per_unit
            .iter()
            .find(|(term, _)| *term == name)
            .map_or(0.0, |(_, cost)| *cost)
    }
}

/// The frame's count `name` (0 if the line has none).
fn count(frame: &Frame, name: &str) -> f64 {
    frame
        .counts
        .iter()
        .find(|(key, _)| key == name)
        .map_or(0.0, |(_, value)| *value as f64)
}

/// The frame's cycles of stage `name` (0 if the line has none).
fn stage(frame: &Frame, name: &str) -> f64 {
    frame
        .stages
        .iter()
        .find(|(key, _)| key == name)
        .map_or(0.0, |(_, value)| *value as f64)
}

/// The least-squares solution of `rows · x ≈ values` (the normal equations, by Gaussian
/// elimination with partial pivoting); `None` if the columns are dependent (a count that never
/// changes, or two that always move together).
fn least_squares(rows: &[Vec<f64>], values: &[f64]) -> Option<Vec<f64>> {
    let width = rows.first()?.len();
    // [AᵀA | Aᵀb]
    let mut system = vec![vec![0.0; width + 1]; width];
    for (row, value) in rows.iter().zip(values) {
        for (equation, factor) in system.iter_mut().zip(row) {
            for (entry, other) in equation.iter_mut().zip(row) {
                *entry += factor * other;
            }
            equation[width] += factor * value;
        }
    }
    for column in 0..width {
        let pivot = (column..width)
            .max_by(|&a, &b| system[a][column].abs().total_cmp(&system[b][column].abs()))?;
        let scale = system[column][column].abs().max(1.0);
        if system[pivot][column].abs() <= 1e-9 * scale {
            return None;
        }
        system.swap(column, pivot);
        let pivot_row = system[column].clone();
        for (index, row) in system.iter_mut().enumerate() {
            if index != column {
                let factor = row[column] / pivot_row[column];
                for (entry, pivot_entry) in row.iter_mut().zip(&pivot_row).skip(column) {
                    *entry -= factor * pivot_entry;
                }
            }
        }
    }
    Some(
        (0..width)
            .map(|i| system[i][width] / system[i][i])
            .collect(),
    )
}

/// The frame's count `name`: from its set-up line, or else from the bench line of the drawn
/// frame at the same place on the path (the visits and things drawn, the same in both runs).
fn count_of(setup: &Frame, drawn: Option<&Frame>, name: &str) -> f64 {
    if setup.counts.iter().any(|(key, _)| key == name) {
        count(setup, name)
    } else {
        drawn.map_or(0.0, |frame| count(frame, name))
    }
}

/// The drawn frame of `drawn` at `setup`'s place on the path.
fn drawn_frame<'r>(drawn: &'r Run, setup: &Frame) -> Option<&'r Frame> {
    drawn.frames.iter().find(|frame| frame.index == setup.index)
}

/// The stage `stage_name`'s cycles of the frames of the set-up run `run` fitted to `terms`
/// and a constant (`drawn`: the same run with kernels, for the counts its lines carry).
fn fit(run: &Run, drawn: &Run, stage_name: &str, terms: &[(&'static str, &str)]) -> Option<Fit> {
    let features = |frame: &Frame| -> Vec<f64> {
        let bench = drawn_frame(drawn, frame);
        terms
            .iter()
            .map(|(name, _)| count_of(frame, bench, name))
            .chain(std::iter::once(1.0))
            .collect()
    };
    let rows: Vec<Vec<f64>> = run.frames.iter().map(features).collect();
    let values: Vec<f64> = run.frames.iter().map(|f| stage(f, stage_name)).collect();
    let solution = least_squares(&rows, &values)?;
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    let (mut residual, mut spread) = (0.0, 0.0);
    for (row, value) in rows.iter().zip(&values) {
        let predicted: f64 = row.iter().zip(&solution).map(|(a, b)| a * b).sum();
        residual += (value - predicted).powi(2);
        spread += (value - mean).powi(2);
    }
    let (per_unit, fixed) = solution.split_at(terms.len());
    Some(Fit {
        per_unit: terms
            .iter()
            .zip(per_unit)
            .map(|((name, _), cost)| (*name, *cost))
            .collect(),
        fixed: fixed[0],
        r_squared: if spread > 0.0 {
            1.0 - residual / spread
        } else {
            1.0
        },
    })
}

/// Signed cycles, grouped (the fit's constant may come out below 0).
fn signed(value: f64) -> String {
    let digits = group_digits(value.abs().round() as u64);
    if value < -0.5 {
        format!("−{digits}")
    } else {
        digits
    }
}

/// The section: the fits, then the frames over the target split by them. `runs` are the drawn
/// guard runs, `setup_runs` the same runs without kernels.
pub fn section(runs: &[Run], setup_runs: &[Run]) -> String {
    let mut doc = String::from(
        "## What is left: the set-up as a cost model\n\n\
         Each set-up run's stage cycles (the table above, frame by frame) fitted by least \
         squares over its frames to the frame's counts (from the same line, and the sector \
         visits and things drawn from the bench line of the same frame drawn with its kernels): \
         the wall stage to its sector visits, wall columns, strips and things drawn, the plane \
         stage to its visits and spans, each with a constant. A unit's cost is then what one more of it adds \
         to a frame, everything it brings along included: a visit's walls' set-up (ownership, \
         projection, the steppers, the run's entry), its things' collection and its plane's \
         job; a thing's projection, collection and clip windows. R² is how much of the frames' \
         spread the fit explains. `cargo bench-report` fits it from the bench scene's set-up \
         and bench lines (`portalcast_rom::bench::SetupLine`, `BenchLine`).\n\n",
    );
    let mut fits = Vec::new();
    doc.push_str("| resolution | wall stage: ");
    doc.push_str(
        &WALL_TERMS
            .iter()
            .map(|(_, label)| *label)
            .collect::<Vec<_>>()
            .join(" | "),
    );
    doc.push_str(" | fixed | R² | plane stage: ");
    doc.push_str(
        &PLANE_TERMS
            .iter()
            .map(|(_, label)| *label)
            .collect::<Vec<_>>()
            .join(" | "),
    );
    doc.push_str(" | fixed | R² |\n|---|");
    doc.push_str(&"---|".repeat(WALL_TERMS.len() + PLANE_TERMS.len() + 4));
    doc.push('\n');
    for setup in setup_runs {
        let Some(drawn) = runs.iter().find(|run| run.key() == setup.key()) else {
            continue;
        };
        let (Some(wall), Some(plane)) = (
            fit(setup, drawn, "wall", &WALL_TERMS),
            fit(setup, drawn, "plane", &PLANE_TERMS),
        ) else {
            continue;
        };
        let resolution = setup.setting("res").unwrap_or("?");
        let _ = write!(doc, "| {} |", resolution_name(resolution));
        for fit in [&wall, &plane] {
            for (_, cost) in &fit.per_unit {
                let _ = write!(doc, " {} |", signed(*cost));
            }
            let _ = write!(doc, " {} | {:.3} |", signed(fit.fixed), fit.r_squared);
        }
        doc.push('\n');
        fits.push((setup, drawn, wall, plane));
    }
    doc.push_str(
        "\nThe frames over the target, split by the fits: each count's mean over those frames \
         times its cost, the kernels (the drawn run's wall and plane stages less the set-up \
         run's, frame by frame: the pixels) and the things stage (drawing the sprites and \
         middles) as measured; the fits' residue is in the constants' column.\n\n\
         | resolution | frames over | mean cycles | visits | visits' set-up | wall columns | \
         columns' set-up | strips | strips' set-up | things | things' set-up | spans | spans' \
         set-up | constants and residue | kernels | things stage | outside the stages |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for (setup, drawn, wall, plane) in &fits {
        let resolution = setup.setting("res").unwrap_or("?");
        let Some((_, budget)) = target(resolution) else {
            continue;
        };
        let over: Vec<(&Frame, &Frame)> = drawn
            .frames
            .iter()
            .filter(|frame| frame.cycles > budget)
            .filter_map(|frame| {
                let bare = setup.frames.iter().find(|f| f.index == frame.index)?;
                Some((frame, bare))
            })
            .collect();
        if over.is_empty() {
            continue;
        }
        let mean = |value: &dyn Fn(&Frame, &Frame) -> f64| -> f64 {
            over.iter().map(|(d, s)| value(d, s)).sum::<f64>() / over.len() as f64
        };
        let mean_count = |name: &str| mean(&|d, s| count_of(s, Some(d), name));
        let (visits, columns, strips, things, spans) = (
            mean_count("visits"),
            mean_count("cols"),
            mean_count("strips"),
            mean_count("things"),
            mean_count("spans"),
        );
        let visits_cost = visits * (wall.cost("visits") + plane.cost("visits"));
        let columns_cost = columns * wall.cost("cols");
        let strips_cost = strips * wall.cost("strips");
        let things_cost = things * wall.cost("things");
        let spans_cost = spans * plane.cost("spans");
        let setup_total = mean(&|_, s| stage(s, "wall") + stage(s, "plane"));
        let residue =
            setup_total - visits_cost - columns_cost - strips_cost - things_cost - spans_cost;
        let kernels = mean(&|d, s| {
            stage(d, "wall") + stage(d, "plane") - stage(s, "wall") - stage(s, "plane")
        });
        let things_stage = mean(&|d, _| stage(d, "thing"));
        let cycles = mean(&|d, _| d.cycles as f64);
        let outside = cycles - setup_total - kernels - things_stage;
        let _ = writeln!(
            doc,
            "| {} | {} of {} | {} | {:.1} | {} | {:.0} | {} | {:.0} | {} | {:.1} | {} | {:.0} | {} | {} | {} | {} | {} |",
            resolution_name(resolution),
            over.len(),
            drawn.frames.len(),
            signed(cycles),
            visits,
            signed(visits_cost),
            columns,
            signed(columns_cost),
            strips,
            signed(strips_cost),
            things,
            signed(things_cost),
            spans,
            signed(spans_cost),
            signed(residue),
            signed(kernels),
            signed(things_stage),
            signed(outside),
        );
    }
    doc
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn least_squares_recovers_an_exact_linear_rule() {
        let rows: Vec<Vec<f64>> = (0..20)
            .map(|i| vec![f64::from(i % 7), f64::from(i * i % 11), 1.0])
            .collect();
        let values: Vec<f64> = rows
            .iter()
            .map(|r| 300.0 * r[0] + 45.0 * r[1] + 1000.0)
            .collect();
        let solution = least_squares(&rows, &values).unwrap();
        for (got, want) in solution.iter().zip([300.0, 45.0, 1000.0]) {
            assert!((got - want).abs() < 1e-6, "{solution:?}");
        }
    }

    #[test]
    fn least_squares_refuses_dependent_counts() {
        let rows: Vec<Vec<f64>> = (0..10)
            .map(|i| vec![f64::from(i), 2.0 * f64::from(i), 1.0])
            .collect();
        let values: Vec<f64> = (0..10).map(f64::from).collect();
        assert!(least_squares(&rows, &values).is_none());
    }
}
