//! The ROM's bench lines and the host's accuracy lines, read generically, and their summaries.
//!
//! A bench line is `bench map=NAME <settings> frame=N cycles=C <stage>_cycles=… …`: the
//! settings are every `key=value` word between `map=` and `frame=`, the stages every later word
//! whose key ends in `_cycles` (see `portalcast_rom::bench`). An accuracy line is
//! `accuracy map=NAME <settings> frames=N <counter>=…`. Nothing here knows the knob or stage
//! names, so new ones become rows and columns of the report by themselves.

use std::collections::BTreeSet;

/// What the ROM prints after the regression guard's runs (`portalcast_rom::bench::GUARD_DONE`).
pub const GUARD_DONE: &str = "bench guard done";
/// What the ROM prints at the end of its bench scene (`portalcast_rom::bench::BENCH_DONE`).
pub const BENCH_DONE: &str = "bench done";

/// One measured frame of a bench run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    /// Position along the fly-through, from 0.
    pub index: u32,
    /// Cycles of the whole render.
    pub cycles: u64,
    /// Cycles of each named stage (`wall`, `plane`, …), in line order.
    pub stages: Vec<(String, u64)>,
    /// The line's other numbers after `cycles=` (a set-up line's counts: `cols`, `spans`, …).
    pub counts: Vec<(String, u64)>,
}

/// The frames of one map at one setting, in the order the ROM printed them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Run {
    /// The map's name.
    pub map: String,
    /// The settings as `(key, value)`, in line order.
    pub settings: Vec<(String, String)>,
    /// The frames.
    pub frames: Vec<Frame>,
}

/// The value of the word `key=VALUE` of a debug line, if it has one.
pub fn field<'a>(line: &'a str, key: &str) -> Option<&'a str> {
    line.split_whitespace()
        .find_map(|word| word.strip_prefix(key)?.strip_prefix('='))
}

/// The `key=value` words of a line, after its first word.
fn fields(line: &str) -> Vec<(&str, &str)> {
    line.split_whitespace()
        .skip(1)
        .filter_map(|word| word.split_once('='))
        .collect()
}

/// `map=NAME` and the settings words of a line, up to the word keyed `end`; the rest after it.
type Head<'l> = (&'l str, Vec<(String, String)>, Vec<(&'l str, &'l str)>);

fn split_head<'l>(line: &'l str, end: &str) -> Result<Head<'l>, String> {
    let words = fields(line);
    let (first_key, map) = *words
        .first()
        .ok_or_else(|| format!("no fields in {line:?}"))?;
    if first_key != "map" {
        return Err(format!("{line:?} does not start with map="));
    }
    let end_at = words
        .iter()
        .position(|(key, _)| *key == end)
        .ok_or_else(|| {
            format!("no {end}= in {line:?} (mGBA cuts lines at 256 bytes: shorten the labels)")
        })?;
    let settings = words[1..end_at]
        .iter()
        .map(|(key, value)| (key.to_string(), value.to_string()))
        .collect();
    Ok((map, settings, words[end_at..].to_vec()))
}

fn number(key: &str, value: &str, line: &str) -> Result<u64, String> {
    value
        .parse()
        .map_err(|_| format!("{key}={value} is not a number in {line:?}"))
}

impl Run {
    /// `map=NAME key=value …`: what identifies the run in bench and accuracy lines alike.
    pub fn key(&self) -> String {
        run_key(&self.map, &self.settings)
    }

    /// The settings as `key=value` words joined by spaces.
    pub fn label(&self) -> String {
        settings_label(&self.settings)
    }

    /// The value of setting `key`.
    pub fn setting(&self, key: &str) -> Option<&str> {
        self.settings
            .iter()
            .find(|(name, _)| name == key)
            .map(|(_, value)| value.as_str())
    }

    /// Mean, percentiles and stage means of the run's cycles.
    pub fn summary(&self) -> Summary {
        Summary::of(&self.frames)
    }
}

/// The settings as `key=value` words joined by spaces.
pub fn settings_label(settings: &[(String, String)]) -> String {
    settings
        .iter()
        .map(|(key, value)| format!("{key}={value}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// `map=NAME` followed by the settings label.
pub fn run_key(map: &str, settings: &[(String, String)]) -> String {
    format!("map={map} {}", settings_label(settings))
}

/// The bench runs in `log` (other lines are skipped), grouped by map and settings in the order
/// they first appear.
pub fn bench_runs(log: &str) -> Result<Vec<Run>, String> {
    runs_of(log, "bench")
}

/// The set-up runs in `log` (`portalcast_rom::bench::SetupLine`: frames drawn without kernels, with
/// their counts), grouped like [`bench_runs`].
pub fn setup_runs(log: &str) -> Result<Vec<Run>, String> {
    runs_of(log, SETUP_WORD)
}

/// The first word of the ROM's set-up lines (`portalcast_rom::bench::SETUP_WORD`).
pub const SETUP_WORD: &str = "setup";

/// The runs of the lines of `log` that start with `word` and `map=`.
fn runs_of(log: &str, word: &str) -> Result<Vec<Run>, String> {
    let prefix = format!("{word} map=");
    let mut runs: Vec<Run> = Vec::new();
    for line in log.lines().filter(|line| line.starts_with(&prefix)) {
        let (map, settings, rest) = split_head(line, "frame")?;
        let mut frame = Frame {
            index: 0,
            cycles: 0,
            stages: Vec::new(),
            counts: Vec::new(),
        };
        let mut has_cycles = false;
        for (key, value) in rest {
            if key == "frame" {
                frame.index = number(key, value, line)? as u32;
            } else if key == "cycles" {
                frame.cycles = number(key, value, line)?;
                has_cycles = true;
            } else if let Some(stage) = key.strip_suffix("_cycles") {
                frame
                    .stages
                    .push((stage.to_string(), number(key, value, line)?));
            } else {
                frame
                    .counts
                    .push((key.to_string(), number(key, value, line)?));
            }
        }
        if !has_cycles {
            return Err(format!("no cycles= in {line:?}"));
        }
        match runs
            .iter_mut()
            .find(|run| run.map == map && run.settings == settings)
        {
            Some(run) => run.frames.push(frame),
            None => runs.push(Run {
                map: map.to_string(),
                settings,
                frames: vec![frame],
            }),
        }
    }
    Ok(runs)
}

/// The counters of one accuracy line, keyed like [`Run::key`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Accuracy {
    /// `map=NAME key=value …`.
    pub key: String,
    /// Every numeric field after the settings (`frames`, `pixels`, `surface_mismatches`, …).
    pub counters: Vec<(String, u64)>,
}

impl Accuracy {
    /// Counter `name`, 0 if the line had none.
    pub fn counter(&self, name: &str) -> u64 {
        self.counters
            .iter()
            .find(|(key, _)| key == name)
            .map_or(0, |(_, value)| *value)
    }

    /// `part` in percent of the pixels compared.
    pub fn percent_of_pixels(&self, part: &str) -> f64 {
        let pixels = self.counter("pixels");
        if pixels == 0 {
            0.0
        } else {
            100.0 * self.counter(part) as f64 / pixels as f64
        }
    }
}

/// The accuracy lines in `log`.
pub fn accuracy_lines(log: &str) -> Result<Vec<Accuracy>, String> {
    log.lines()
        .filter(|line| line.starts_with("accuracy map="))
        .map(|line| {
            let (map, settings, rest) = split_head(line, "frames")?;
            let counters = rest
                .into_iter()
                .map(|(key, value)| Ok((key.to_string(), number(key, value, line)?)))
                .collect::<Result<_, String>>()?;
            Ok(Accuracy {
                key: run_key(map, &settings),
                counters,
            })
        })
        .collect()
}

/// The numeric `key=value` fields of the first line starting with `prefix`.
pub fn numbers_of_line(log: &str, prefix: &str) -> Option<Vec<(String, u64)>> {
    let line = log.lines().find(|line| line.starts_with(prefix))?;
    Some(
        line.split_whitespace()
            .filter_map(|word| word.split_once('='))
            .filter_map(|(key, value)| Some((key.to_string(), value.parse().ok()?)))
            .collect(),
    )
}

/// The statistics of a run's cycles per frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Summary {
    /// Frames measured.
    pub frames: usize,
    /// Mean, rounded to the nearest cycle.
    pub mean: u64,
    /// Median (nearest rank).
    pub p50: u64,
    /// 95th percentile (nearest rank).
    pub p95: u64,
    /// Slowest frame.
    pub max: u64,
    /// Mean cycles of each named stage, in line order.
    pub stage_means: Vec<(String, u64)>,
    /// Mean cycles outside the named stages (the walk's set-up, clearing, …): the mean of the
    /// total less each frame's named stages, never below 0.
    pub other_mean: u64,
}

fn rounded_mean(values: impl Iterator<Item = u64>, count: usize) -> u64 {
    if count == 0 {
        return 0;
    }
    let sum: u64 = values.sum();
    (sum + count as u64 / 2) / count as u64
}

/// The nearest-rank percentile `p` of ascending `sorted`: the smallest value with at least `p`
/// percent of the values at or below it.
pub fn percentile(sorted: &[u64], p: usize) -> u64 {
    if sorted.is_empty() {
        return 0;
    }
    let rank = (sorted.len() * p).div_ceil(100).max(1);
    sorted[rank.min(sorted.len()) - 1]
}

impl Summary {
    /// The summary of `frames`.
    pub fn of(frames: &[Frame]) -> Summary {
        let count = frames.len();
        let mut sorted: Vec<u64> = frames.iter().map(|frame| frame.cycles).collect();
        sorted.sort_unstable();
        let mut stage_names: Vec<String> = Vec::new();
        let mut seen = BTreeSet::new();
        for frame in frames {
            for (name, _) in &frame.stages {
                if seen.insert(name.clone()) {
                    stage_names.push(name.clone());
                }
            }
        }
        let stage_of = |frame: &Frame, name: &str| {
            frame
                .stages
                .iter()
                .find(|(stage, _)| stage == name)
                .map_or(0, |(_, cycles)| *cycles)
        };
        let stage_means = stage_names
            .iter()
            .map(|name| {
                let mean = rounded_mean(frames.iter().map(|frame| stage_of(frame, name)), count);
                (name.clone(), mean)
            })
            .collect();
        let other = frames.iter().map(|frame| {
            let named: u64 = frame.stages.iter().map(|(_, cycles)| cycles).sum();
            frame.cycles.saturating_sub(named)
        });
        Summary {
            frames: count,
            mean: rounded_mean(sorted.iter().copied(), count),
            p50: percentile(&sorted, 50),
            p95: percentile(&sorted, 95),
            max: sorted.last().copied().unwrap_or(0),
            stage_means,
            other_mean: rounded_mean(other, count),
        }
    }
}

/// `n` with a comma every three digits: `1234567` → `1,234,567`.
pub fn group_digits(n: u64) -> String {
    let digits = n.to_string();
    let mut grouped = String::with_capacity(digits.len() + digits.len() / 3);
    for (index, digit) in digits.chars().enumerate() {
        if index > 0 && (digits.len() - index).is_multiple_of(3) {
            grouped.push(',');
        }
        grouped.push(digit);
    }
    grouped
}

#[cfg(test)]
mod tests {
    use super::*;

    const LOG: &str = "\
portalcast boot waitcnt=0x4317 iwram_used=19772 stack_room=12740
bench map=bench res=120x80 lighting=depth frame=0 cycles=1000 wall_cycles=500 plane_cycles=300
bench map=bench res=120x80 lighting=depth frame=1 cycles=3000 wall_cycles=1000 plane_cycles=1000
bench map=bench res=120x80 lighting=off frame=0 cycles=900 wall_cycles=400 plane_cycles=300 sky_cycles=100
accuracy map=bench res=120x80 lighting=off frames=8 pixels=200 surface_mismatches=3
";

    #[test]
    fn runs_group_by_map_and_settings_and_stages_are_generic() {
        let runs = bench_runs(LOG).unwrap();
        assert_eq!(runs.len(), 2);
        assert_eq!(runs[0].key(), "map=bench res=120x80 lighting=depth");
        assert_eq!(runs[0].setting("lighting"), Some("depth"));
        let summary = runs[0].summary();
        assert_eq!((summary.mean, summary.p50, summary.max), (2000, 1000, 3000));
        assert_eq!(
            summary.stage_means,
            vec![("wall".to_string(), 750), ("plane".to_string(), 650)]
        );
        assert_eq!(summary.other_mean, 600);
        let off = runs[1].summary();
        assert_eq!(off.stage_means.len(), 3);
        assert_eq!(off.other_mean, 100);
    }

    #[test]
    fn a_cut_line_is_an_error() {
        let error = bench_runs("bench map=bench res=120x80 lighting=de\n").unwrap_err();
        assert!(error.contains("256 bytes"), "{error}");
    }

    #[test]
    fn accuracy_lines_are_keyed_like_runs() {
        let lines = accuracy_lines(LOG).unwrap();
        assert_eq!(lines[0].key, "map=bench res=120x80 lighting=off");
        assert_eq!(lines[0].counter("frames"), 8);
        assert!((lines[0].percent_of_pixels("surface_mismatches") - 1.5).abs() < 1e-12);
        let boot = numbers_of_line(LOG, "portalcast boot").unwrap();
        assert!(boot.contains(&("stack_room".to_string(), 12740)));
    }

    #[test]
    fn percentiles_use_the_nearest_rank() {
        let sorted: Vec<u64> = (1..=20).collect();
        assert_eq!(percentile(&sorted, 50), 10);
        assert_eq!(percentile(&sorted, 95), 19);
        assert_eq!(percentile(&sorted, 100), 20);
        assert_eq!(percentile(&[7], 95), 7);
    }

    #[test]
    fn digits_are_grouped_by_three() {
        assert_eq!(group_digits(0), "0");
        assert_eq!(group_digits(999), "999");
        assert_eq!(group_digits(280_896), "280,896");
        assert_eq!(group_digits(1_234_567), "1,234,567");
    }
}
