//! What the benchmark measures, shared by the ROM's bench scene and the host's accuracy report:
//! which maps and settings, in which order, how many frames, and the words each frame's line is
//! made of.
//!
//! A bench line reads `bench map=NAME <settings> frame=N cycles=C <stage>_cycles=… …`: the
//! settings are every `key=value` between `map=` and `frame=` ([`SettingsLabel`]), the stages
//! every field named `*_cycles` after `cycles=` ([`StageCycles`]). The report takes both
//! generically, so a new knob or a new stage needs one line here and nothing in the report.
//! mGBA's debug log cuts a line at 256 bytes, so keys and values stay short.

use core::fmt;

use portalcast_format::MapTables;

use crate::assets;
use crate::demo::lighting_label;
use portalcast::frame::Resolution;
use portalcast::render::light::Lighting;
use portalcast::render::view::{
    Floors, Preprocessing, Settings, SlopeSteps, TexturePlacement, ThingsShown,
};
use portalcast::render::walk::FrameStats;

/// Frames measured per setting along a map's [`crate::flight`] path, flown through its live
/// world ([`crate::live_flight`]), on every map but the bench map.
pub const FRAMES_PER_SETTING: u32 = 64;

/// Frames measured per setting on the bench map: the hall, the gallery, the courtyard and the
/// stairs, the corridor's door opened on the way (the camera waits for it in frames 236 to 263)
/// and the lift ridden down (frames 328 to 383). Longer, the lift's wait at the bottom and its
/// way back up (some 190 frames of the camera standing still) would weigh more than the rest of
/// the map. (The other maps keep [`FRAMES_PER_SETTING`]: the generated and extreme maps' bench
/// scenes run every one of their maps.)
pub const BENCH_MAP_FRAMES: u32 = 384;

/// The shipped map with slopes and room over room, whose frames [`SLOPES_MAP_FRAMES`] counts.
pub const SLOPES_MAP: &str = "slopes";

/// Frames measured per setting on the slopes map: its whole tour (229 frames), up the ramp, over
/// the canyon through the air above the pit (frames 26 to 31), down the stairs and along the
/// pit's floor under the bridge (frames 78 to 80), back up and over the bridge's deck (139 to
/// 141), the attic under its sloped ceiling and the bank: fewer would leave the bridge out.
pub const SLOPES_MAP_FRAMES: u32 = 232;

/// Frames measured per setting on `map`.
pub fn frames_for(map: &MapTables) -> u32 {
    match map.name {
        BENCH_MAP => BENCH_MAP_FRAMES,
        SLOPES_MAP => SLOPES_MAP_FRAMES,
        _ => FRAMES_PER_SETTING,
    }
}
/// The host compares every this many frames of the path with the oracle (frame 0 first).
pub const ACCURACY_FRAME_STEP: u32 = 8;
/// The map the knobs are measured on and the regression guard watches.
pub const BENCH_MAP: &str = "bench";
/// Printed after the regression guard's part of the bench scene.
pub const GUARD_DONE: &str = "bench guard done";
/// Printed at the end of the bench scene.
pub const BENCH_DONE: &str = "bench done";
/// The first word of the set-up runs' lines ([`SetupLine`]).
pub const SETUP_WORD: &str = "setup";

/// The bench map from the compiled assets (the first map if there is no `bench`).
pub fn bench_map() -> &'static MapTables<'static> {
    assets::MAPS
        .iter()
        .find(|map| map.name == BENCH_MAP)
        .unwrap_or(&assets::MAPS[0])
}

/// The default settings at `resolution`: what the ROM starts with and what each knob is varied
/// from.
pub const fn default_settings(resolution: Resolution) -> Settings {
    Settings {
        resolution,
        ..Settings::DEFAULT
    }
}

/// The settings measured at `resolution`: the defaults first, then each knob's other values,
/// one knob at a time. A new knob is one `.chain(…)` line. Half-width floors only where they are
/// offered (240 wide): at 120 wide they would draw the same pixels as the defaults.
pub fn knob_variants(resolution: Resolution) -> impl Iterator<Item = Settings> {
    let base = default_settings(resolution);
    core::iter::once(base)
        .chain(
            [Lighting::Off, Lighting::Sector]
                .into_iter()
                .map(move |lighting| Settings { lighting, ..base }),
        )
        .chain(core::iter::once(Settings {
            textures: TexturePlacement::Rom,
            ..base
        }))
        .chain(core::iter::once(Settings {
            preprocessing: Preprocessing::On,
            ..base
        }))
        .chain(Floors::offered_at(resolution).then_some(Settings {
            floors: Floors::Half,
            ..base
        }))
        .chain(core::iter::once(Settings {
            things: ThingsShown::Off,
            ..base
        }))
}

/// The regression guard's runs, first in the bench scene: the bench map at the default
/// settings, at every resolution.
pub fn guard_runs() -> impl Iterator<Item = (&'static MapTables<'static>, Settings)> {
    Resolution::ALL
        .into_iter()
        .map(|resolution| (bench_map(), default_settings(resolution)))
}

/// The slope-mapping knob's other values at every resolution, on each shipped map with a slope
/// (the bench map has none: the knob changes nothing there).
pub fn slope_runs() -> impl Iterator<Item = (&'static MapTables<'static>, Settings)> {
    assets::MAPS
        .iter()
        .filter(|map| !map.slopes.is_empty())
        .flat_map(|map| {
            Resolution::ALL.into_iter().flat_map(move |resolution| {
                SlopeSteps::ALL
                    .into_iter()
                    .filter(|steps| *steps != SlopeSteps::DEFAULT)
                    .map(move |slope_steps| {
                        (
                            map,
                            Settings {
                                slope_steps,
                                ..default_settings(resolution)
                            },
                        )
                    })
            })
        })
}

/// The rest of the bench scene, after the guard's runs: every other knob value on the bench map
/// at every resolution, then every other shipped map at the default settings, then the slope
/// knob on the maps with slopes ([`slope_runs`]).
pub fn report_runs() -> impl Iterator<Item = (&'static MapTables<'static>, Settings)> {
    let knobs = Resolution::ALL
        .into_iter()
        .flat_map(|resolution| knob_variants(resolution).skip(1))
        .map(|settings| (bench_map(), settings));
    let other_maps = assets::MAPS
        .iter()
        .filter(|map| map.name != bench_map().name)
        .flat_map(|map| {
            Resolution::ALL
                .into_iter()
                .map(move |resolution| (map, default_settings(resolution)))
        });
    knobs.chain(other_maps).chain(slope_runs())
}

/// The set-up runs, last in the bench scene: the guard's runs again, drawn on a canvas that
/// prepares every kernel call and runs none, so that the report can tell the renderer's
/// set-up per wall column and per span from its kernels' cycles per pixel.
pub fn setup_runs() -> impl Iterator<Item = (&'static MapTables<'static>, Settings)> {
    guard_runs()
}

/// Every run of the bench scene, in order: [`guard_runs`], then [`report_runs`].
pub fn all_runs() -> impl Iterator<Item = (&'static MapTables<'static>, Settings)> {
    guard_runs().chain(report_runs())
}

/// The settings as the `key=value` words of a bench line, e.g. `res=120x80 lighting=depth`.
/// A new knob is one `write!` line.
pub struct SettingsLabel<'s>(pub &'s Settings);

impl fmt::Display for SettingsLabel<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let settings = self.0;
        write!(f, "res={}", settings.resolution.label())?;
        write!(f, " lighting={}", lighting_label(settings.lighting))?;
        write!(f, " tex={}", settings.textures.label())?;
        write!(f, " prep={}", settings.preprocessing.label())?;
        write!(f, " floors={}", settings.floors.label())?;
        write!(f, " things={}", settings.things.label())?;
        write!(f, " slp={}", settings.slope_steps.label())?;
        Ok(())
    }
}

/// Longest line mGBA's debug log keeps whole: the ROM's logger flushes every 256 bytes.
pub const MAX_LINE_BYTES: usize = 255;

/// One frame's bench line: `bench map=NAME <settings> frame=N cycles=C <stages>`.
pub struct BenchLine<'l> {
    /// The map's name.
    pub map: &'l str,
    /// The settings the frame was drawn at.
    pub settings: &'l Settings,
    /// Position along the fly-through, from 0.
    pub frame: u32,
    /// Cycles of the whole render.
    pub cycles: u32,
    /// The renderer's counters for the frame (its stage timings).
    pub stats: &'l FrameStats,
}

impl BenchLine<'_> {
    /// The line after its first word: `map=NAME <settings> frame=N cycles=C <stages>`.
    fn write_body(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "map={} {} frame={} cycles={}{}",
            self.map,
            SettingsLabel(self.settings),
            self.frame,
            self.cycles,
            StageCycles(self.stats)
        )
    }
}

impl fmt::Display for BenchLine<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("bench ")?;
        self.write_body(f)?;
        // The things stage's time, and the sector visits and things drawn the report's cost
        // model fits the set-up to: on the bench line only, which the set-up line's counts
        // leave no room for in one mGBA log line.
        write!(
            f,
            " thing_cycles={} visits={} things={}",
            self.stats.thing_ticks, self.stats.sector_visits, self.stats.things_drawn
        )
    }
}

/// One frame's set-up line: `setup map=NAME <settings> frame=N cycles=C <stages> <counts>`,
/// a [`BenchLine`] of a frame drawn without kernels, with the counts the report divides by and
/// fits its cost model to: wall columns, wall strips, spans, and the pixels of the wall stage
/// (strips) and of the plane stage (spans and sky). The frame's sector visits and things drawn
/// are on its bench line (the same in both runs), which has the room.
pub struct SetupLine<'l>(pub BenchLine<'l>);

impl fmt::Display for SetupLine<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let stats = self.0.stats;
        write!(f, "{SETUP_WORD} ")?;
        self.0.write_body(f)?;
        write!(
            f,
            " cols={} strips={} spans={} wall_px={} plane_px={}",
            stats.wall_columns,
            stats.strips,
            stats.spans,
            stats.column_pixels - stats.sky_pixels,
            stats.span_pixels + stats.sky_pixels,
        )
    }
}

/// A frame's stage timings as the `name_cycles=N` words of a bench line, each with a leading
/// space. A new stage is one `write!` line.
pub struct StageCycles<'s>(pub &'s FrameStats);

impl fmt::Display for StageCycles<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let stats = self.0;
        write!(f, " wall_cycles={}", stats.wall_ticks)?;
        write!(f, " plane_cycles={}", stats.plane_ticks)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeSet;

    #[test]
    fn every_run_has_a_distinct_label_and_the_guard_comes_first() {
        let labels: Vec<String> = all_runs()
            .map(|(map, settings)| format!("map={} {}", map.name, SettingsLabel(&settings)))
            .collect();
        let distinct: BTreeSet<&String> = labels.iter().collect();
        assert_eq!(distinct.len(), labels.len(), "{labels:?}");
        assert_eq!(
            labels[0],
            "map=bench res=120x80 lighting=depth tex=ewram prep=off floors=full things=on slp=16"
        );
        assert_eq!(guard_runs().count(), Resolution::ALL.len());
    }

    #[test]
    fn the_longest_bench_line_fits_in_one_mgba_log_line() {
        let stats = FrameStats {
            sector_visits: u32::MAX,
            wall_columns: u32::MAX,
            column_pixels: u32::MAX,
            span_pixels: u32::MAX,
            strips: u32::MAX,
            sky_pixels: u32::MAX,
            spans: u32::MAX,
            depth_cutoffs: u32::MAX,
            repeat_visits: u32::MAX,
            merged_visits: u32::MAX,
            plan_overflows: u32::MAX,
            wall_ticks: u32::MAX,
            plane_ticks: u32::MAX,
            things_drawn: u32::MAX,
            things_dropped: u32::MAX,
            thing_ticks: u32::MAX,
            middles_drawn: u32::MAX,
            translucent_drawn: u32::MAX,
        };
        let stats = FrameStats {
            sky_pixels: 0,
            span_pixels: u32::MAX / 2,
            ..stats
        };
        for (map, settings) in all_runs().chain(setup_runs()) {
            let line = BenchLine {
                map: map.name,
                settings: &settings,
                frame: FRAMES_PER_SETTING,
                cycles: u32::MAX,
                stats: &stats,
            };
            for line in [line.to_string(), SetupLine(line).to_string()] {
                assert!(
                    line.len() <= MAX_LINE_BYTES,
                    "{} bytes: {line} (shorten the knob or stage words)",
                    line.len()
                );
            }
        }
    }

    #[test]
    fn labels_are_single_key_value_words() {
        for (_, settings) in all_runs() {
            let label = format!("{}", SettingsLabel(&settings));
            for word in label.split(' ') {
                let (key, value) = word.split_once('=').expect("key=value");
                assert!(!key.is_empty() && !value.is_empty() && !value.contains('='));
            }
        }
    }
}
