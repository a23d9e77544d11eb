//! The thesis' scene preprocessing (`prep=on`, [`Preprocessing::On`]) on every shipped map along
//! the benchmark's fly-through, at every resolution, against the plain walk: the same columns,
//! drawn by the same walls, front to back. Only the rounding of a wall's steppers can differ (a
//! merged visit steps a wall from the merged run's first column, not from each portal's), so a
//! pixel may differ only by a texel on the same surface or by a wall edge one row off, and
//! rarely. The plain walk draws a sector's neighbours with the same planes as part of its visit
//! (one floor, one ceiling for all), the preprocessing each in a visit of its own: a floor or a
//! ceiling counts as its plane group's (`portalcast_oracle::plane_groups`), as the comparison
//! with the oracle counts it. Printed, with how much it merges:
//! `cargo test --release --test scene_preprocessing -- --nocapture`. The cycles it saves or
//! costs are in docs/BENCH.md (the `prep=on` rows).

use portalcast::frame::Resolution;
use portalcast::render::view::{Camera, Preprocessing, Settings, View};
use portalcast::render::walk::{FrameStats, Renderer};
use portalcast_format::MapTables;
use portalcast_oracle::{plane_groups, plane_surface, RecordingCanvas};
use portalcast_rom::assets::MAPS;
use portalcast_rom::bench::{default_settings, FRAMES_PER_SETTING};
use portalcast_rom::demo::render_assets;
use portalcast_rom::flight::Flight;

/// Differing pixels allowed, per pixel compared: one in ten thousand.
const DIFFERING_PIXELS_PER_PIXEL: f64 = 1e-4;

fn draw(
    renderer: &mut Renderer,
    map: &MapTables,
    camera: &Camera,
    settings: &Settings,
) -> (RecordingCanvas, FrameStats) {
    let mut canvas = RecordingCanvas::new(settings.resolution);
    let stats = renderer.render(
        map,
        &render_assets(),
        &View::new(camera, settings),
        &mut canvas,
    );
    (canvas, stats)
}

/// The pixels where `merged` differs from `plain`, after checking each is a texel on the same
/// surface or a wall edge moved by one row.
fn differing_pixels(
    plain: &RecordingCanvas,
    merged: &RecordingCanvas,
    groups: &[u16],
    context: &str,
) -> usize {
    let width = plain.resolution.width();
    let plane = |surface| plane_surface(groups, surface);
    let surface_at = |canvas: &RecordingCanvas, index: usize, rows: isize| {
        let row = (index / width) as isize + rows;
        (0..plain.resolution.height() as isize)
            .contains(&row)
            .then(|| plane(canvas.surfaces[row as usize * width + index % width]))
    };
    let mut differing = 0;
    for index in 0..plain.surfaces.len() {
        let (before, after) = (plane(plain.surfaces[index]), plane(merged.surfaces[index]));
        if before == after && plain.indices[index] == merged.indices[index] {
            continue;
        }
        differing += 1;
        let edge_moved = before != after
            && [-1, 1].iter().any(|&rows| {
                surface_at(plain, index, rows) == Some(after)
                    || surface_at(merged, index, rows) == Some(before)
            });
        assert!(
            before == after || edge_moved,
            "{context}: pixel ({}, {}) is {before:?} in the plain walk and {after:?} merged",
            index % width,
            index / width
        );
    }
    differing
}

#[test]
fn merged_visits_draw_what_the_plain_walk_draws_on_every_shipped_map() {
    let mut renderer = Box::new(Renderer::new());
    let (mut compared, mut differing, mut merged_anywhere) = (0usize, 0usize, 0u32);
    for map in MAPS.iter() {
        let groups = plane_groups(map);
        for resolution in Resolution::ALL {
            let plain = default_settings(resolution);
            let merged = Settings {
                preprocessing: Preprocessing::On,
                ..plain
            };
            let (mut visits, mut repeats, mut draws, mut merges, mut here) = (0, 0, 0, 0, 0);
            let mut seen_through = 0;
            for (frame, camera) in Flight::new(map)
                .take(FRAMES_PER_SETTING as usize)
                .enumerate()
            {
                let context = format!("{} {} frame {frame}", map.name, resolution.label());
                let (plain_canvas, plain_stats) = draw(&mut renderer, map, &camera, &plain);
                let (merged_canvas, merged_stats) = draw(&mut renderer, map, &camera, &merged);
                here += differing_pixels(&plain_canvas, &merged_canvas, &groups, &context);
                compared += plain_canvas.surfaces.len();
                assert!(merged_canvas.writes.iter().all(|&w| w == 1), "{context}");
                assert_eq!(merged_stats.plan_overflows, 0, "{context}");
                assert_eq!(plain_stats.merged_visits, 0, "{context}");
                // Every visit of the plain walk is either drawn or merged into another.
                assert_eq!(
                    merged_stats.sector_visits + merged_stats.merged_visits,
                    plain_stats.sector_visits,
                    "{context}"
                );
                assert_eq!(
                    merged_stats.column_pixels + merged_stats.span_pixels,
                    plain_stats.column_pixels + plain_stats.span_pixels,
                    "{context}"
                );
                // The plain walk sees through the portals between sectors with the same planes,
                // which the preprocessing draws: never a wall column more.
                assert!(
                    plain_stats.wall_columns <= merged_stats.wall_columns,
                    "{context}"
                );
                seen_through += merged_stats.wall_columns - plain_stats.wall_columns;
                visits += plain_stats.sector_visits;
                repeats += plain_stats.repeat_visits;
                draws += merged_stats.sector_visits;
                merges += merged_stats.merged_visits;
            }
            merged_anywhere += merges;
            if map.name == "bench" {
                assert!(seen_through > 0, "the bench hall's cells are seen through");
            }
            differing += here;
            println!(
                "{} {}: {visits} visits, {repeats} of them repeats; merged: {draws} draws, {merges} visits merged ({:.1} %); {here} pixels differ; the plain walk saw through {seen_through} wall columns",
                map.name,
                resolution.label(),
                100.0 * f64::from(merges) / f64::from(visits)
            );
        }
    }
    assert!(merged_anywhere > 0, "no shipped map merges a visit");
    assert!(
        differing as f64 <= DIFFERING_PIXELS_PER_PIXEL * compared as f64,
        "{differing} of {compared} pixels differ"
    );
}
