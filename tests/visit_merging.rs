//! The thesis' scene preprocessing merges the visits of a sector seen through several portals
//! into one (its §3 reports ×1.7). This measures what it could save here: how many of the
//! renderer's sector visits along the benchmark's fly-through are repeats, at every resolution.
//! A repeat visit costs the per-visit work only (window resets and the ownership tests of the
//! sector's walls); its columns and pixels are drawn once either way, so the saving is at most
//! that share of the per-visit work. Printed by
//! `cargo test --release --test visit_merging -- --nocapture`.

use portalcast::bench::{bench_map, default_settings, FRAMES_PER_SETTING};
use portalcast::flight::Flight;
use portalcast::frame::Resolution;
use portalcast::raster::{HostCanvas, HostPage};
use portalcast::render::demo::render_assets;
use portalcast::render::view::View;
use portalcast::render::walk::Renderer;

#[test]
fn repeat_visits_along_the_fly_through() {
    let map = bench_map();
    let assets = render_assets();
    let mut renderer = Renderer::new();
    for resolution in Resolution::ALL {
        let settings = default_settings(resolution);
        let (mut visits, mut repeats, mut worst) = (0u32, 0u32, 0.0f64);
        for camera in Flight::new(map).take(FRAMES_PER_SETTING as usize) {
            let mut page = HostPage::new();
            let stats = renderer.render(
                map,
                &assets,
                &View::new(&camera, &settings),
                &mut HostCanvas {
                    page: &mut page,
                    resolution,
                },
            );
            assert!(stats.repeat_visits < stats.sector_visits, "{stats:?}");
            visits += stats.sector_visits;
            repeats += stats.repeat_visits;
            worst = worst.max(f64::from(stats.repeat_visits) / f64::from(stats.sector_visits));
        }
        println!(
            "visit merging, {}: {repeats} of {visits} sector visits are repeats ({:.1} %), at most {:.1} % in one frame",
            resolution.label(),
            100.0 * f64::from(repeats) / f64::from(visits),
            100.0 * worst
        );
    }
}
