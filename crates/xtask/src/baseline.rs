//! The regression guard's baseline: the bench map's mean and max cycles per frame at the default
//! settings, per resolution, committed in `docs/bench-baseline.txt`.
//!
//! mGBA's cycle counts are deterministic, so any change in them is a change in the ROM. The guard
//! test (`tests/bench_guard.rs`) fails when a mean or a max rises more than
//! [`TOLERANCE_PERCENT`] above the baseline, and says so (without failing) when one falls that
//! much below it. Only `cargo bench-report --update-baseline` rewrites the file: a new baseline
//! is a reviewed commit.

use std::path::PathBuf;

use crate::bench_log::{group_digits, Run};

/// How far above the baseline a mean or a max may rise before the guard fails, in percent.
pub const TOLERANCE_PERCENT: f64 = 2.0;

/// The baseline file, relative to the workspace root.
pub const BASELINE_FILE: &str = "docs/bench-baseline.txt";

/// The baseline file's path.
pub fn baseline_path() -> PathBuf {
    crate::workspace_root().join(BASELINE_FILE)
}

/// One guarded run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Entry {
    /// `map=NAME key=value …`, as in the bench lines.
    pub key: String,
    /// Mean cycles per frame.
    pub mean: u64,
    /// Slowest frame.
    pub max: u64,
}

impl Entry {
    /// The value of `key=` in the entry's key (the map, the resolution, …).
    pub fn field(&self, key: &str) -> Option<&str> {
        self.key
            .split_whitespace()
            .find_map(|word| word.strip_prefix(key)?.strip_prefix('='))
    }

    /// What the guard matches entries by: the map and the resolution (so a new knob, which
    /// lengthens the key, still finds its baseline).
    fn identity(&self) -> (Option<&str>, Option<&str>) {
        (self.field("map"), self.field("res"))
    }
}

/// The guarded figures and what they were measured with.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Baseline {
    /// The engine's instruction set (`arm`, or `thumb` under `PORTALCAST_ENGINE_ISA`).
    pub target: String,
    /// The guarded runs.
    pub entries: Vec<Entry>,
}

fn header() -> String {
    format!(
        "# The regression guard's baseline: the bench map at the default settings along the \
         fly-through,\n\
         # cycles per frame measured in mGBA (mean and max). tests/bench_guard.rs fails when a \
         mean or a\n\
         # max rises more than {TOLERANCE_PERCENT} % above these. Rewritten only by \
         `cargo bench-report --update-baseline`:\n\
         # commit the new file for review together with the change that moved the figures.\n"
    )
}

impl Baseline {
    /// The baseline of the guarded `runs` of a ROM whose engine is `target` (`arm` or `thumb`).
    pub fn from_runs(target: &str, runs: &[Run]) -> Baseline {
        Baseline {
            target: target.to_string(),
            entries: runs
                .iter()
                .map(|run| {
                    let summary = run.summary();
                    Entry {
                        key: run.key(),
                        mean: summary.mean,
                        max: summary.max,
                    }
                })
                .collect(),
        }
    }

    /// The file's text.
    pub fn to_text(&self) -> String {
        let mut text = header();
        text.push_str(&format!("target={}\n", self.target));
        for entry in &self.entries {
            text.push_str(&format!(
                "{} mean={} max={}\n",
                entry.key, entry.mean, entry.max
            ));
        }
        text
    }

    /// Reads [`Baseline::to_text`]'s format.
    pub fn parse(text: &str) -> Result<Baseline, String> {
        let mut target = None;
        let mut entries = Vec::new();
        for line in text.lines().map(str::trim) {
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            if let Some(value) = line.strip_prefix("target=") {
                target = Some(value.to_string());
                continue;
            }
            let mut key = Vec::new();
            let (mut mean, mut max) = (None, None);
            for word in line.split_whitespace() {
                match word.split_once('=') {
                    Some(("mean", value)) => mean = value.parse().ok(),
                    Some(("max", value)) => max = value.parse().ok(),
                    _ => key.push(word),
                }
            }
            let (Some(mean), Some(max)) = (mean, max) else {
                return Err(format!("baseline line without mean= and max=: {line:?}"));
            };
            entries.push(Entry {
                key: key.join(" "),
                mean,
                max,
            });
        }
        Ok(Baseline {
            target: target.ok_or("the baseline has no target= line")?,
            entries,
        })
    }
}

/// What the guard found.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Verdict {
    /// Figures more than [`TOLERANCE_PERCENT`] above the baseline (the guard fails).
    pub regressions: Vec<String>,
    /// Figures more than [`TOLERANCE_PERCENT`] below it (worth a new baseline).
    pub improvements: Vec<String>,
    /// Anything else worth saying: a missing entry, a changed settings label.
    pub notes: Vec<String>,
}

impl Verdict {
    /// Whether the guard passes.
    pub fn passed(&self) -> bool {
        self.regressions.is_empty()
    }
}

/// How `measured` compares with `baseline`, entry by entry.
pub fn check(baseline: &Baseline, measured: &Baseline) -> Verdict {
    let mut verdict = Verdict::default();
    if baseline.target != measured.target {
        verdict.notes.push(format!(
            "the baseline was measured on a {} ROM, this one is {}: not compared",
            baseline.target, measured.target
        ));
        return verdict;
    }
    for now in &measured.entries {
        let Some(before) = baseline
            .entries
            .iter()
            .find(|entry| entry.identity() == now.identity())
        else {
            verdict.regressions.push(format!(
                "{}: no baseline entry; run `cargo bench-report --update-baseline` and commit {BASELINE_FILE}",
                now.key
            ));
            continue;
        };
        if before.key != now.key {
            verdict.notes.push(format!(
                "the default settings changed since the baseline ({} → {})",
                before.key, now.key
            ));
        }
        for (what, old, new) in [
            ("mean", before.mean, now.mean),
            ("max", before.max, now.max),
        ] {
            let change = if old == 0 {
                0.0
            } else {
                100.0 * (new as f64 - old as f64) / old as f64
            };
            let message = format!(
                "{}: {what} {} cycles per frame against the baseline's {} ({change:+.2} %)",
                now.key,
                group_digits(new),
                group_digits(old)
            );
            if change > TOLERANCE_PERCENT {
                verdict.regressions.push(message);
            } else if change < -TOLERANCE_PERCENT {
                verdict.improvements.push(message);
            }
        }
    }
    verdict
}

#[cfg(test)]
mod tests {
    use super::*;

    fn baseline(mean: u64, max: u64) -> Baseline {
        Baseline {
            target: "thumbv4t-none-eabi".to_string(),
            entries: vec![Entry {
                key: "map=bench res=120x80 lighting=depth".to_string(),
                mean,
                max,
            }],
        }
    }

    #[test]
    fn the_text_format_round_trips() {
        let original = baseline(1_000_000, 2_000_000);
        assert_eq!(Baseline::parse(&original.to_text()).unwrap(), original);
    }

    #[test]
    fn a_slowdown_over_two_percent_fails_the_guard() {
        let before = baseline(1_000_000, 2_000_000);
        let verdict = check(&before, &baseline(1_020_001, 2_000_000));
        assert!(!verdict.passed());
        assert!(verdict.regressions[0].contains("mean"), "{verdict:?}");
        let verdict = check(&before, &baseline(1_000_000, 2_040_001));
        assert!(verdict.regressions[0].contains("max"), "{verdict:?}");
    }

    #[test]
    fn up_to_two_percent_passes_quietly() {
        let before = baseline(1_000_000, 2_000_000);
        let verdict = check(&before, &baseline(1_020_000, 1_960_000));
        assert_eq!(verdict, Verdict::default());
    }

    #[test]
    fn a_speed_up_over_two_percent_passes_and_suggests_a_new_baseline() {
        let verdict = check(
            &baseline(1_000_000, 2_000_000),
            &baseline(900_000, 2_000_000),
        );
        assert!(verdict.passed());
        assert_eq!(verdict.improvements.len(), 1);
    }

    #[test]
    fn a_new_knob_keeps_matching_by_map_and_resolution() {
        let mut now = baseline(1_000_000, 2_000_000);
        now.entries[0].key.push_str(" knob=value");
        let verdict = check(&baseline(1_000_000, 2_000_000), &now);
        assert!(verdict.passed());
        assert_eq!(verdict.notes.len(), 1);
    }

    #[test]
    fn a_missing_entry_fails_with_what_to_do() {
        let mut now = baseline(1_000_000, 2_000_000);
        now.entries[0].key = "map=bench res=240x160 lighting=depth".to_string();
        let verdict = check(&baseline(1_000_000, 2_000_000), &now);
        assert!(verdict.regressions[0].contains("--update-baseline"));
    }
}
