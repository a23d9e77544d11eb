//! Slopes at the extremes of their fixed-point form, against the f64 oracle: the steepest
//! planes the compiler takes (4 units of rise per unit of run), planes far from the world's
//! origin (where the 24.8 base and the 8.24 gradients round the most), a ceiling sloping down
//! to the player's height over a floor sloping up, and the eye a unit above a steep floor. At
//! sampled poses and at every resolution: at most 0.5 % of pixels on a different surface, no
//! hole, no missed sector, and every pixel drawn once. And the slope-mapping knob: each `N`'s
//! texels against the oracle's exact mapping, worse as `N` grows, `N = 1` the best.

mod common;

use common::*;
use portalcast::frame::Resolution;
use portalcast::render::view::{Camera, Settings, SlopeSteps};
use portalcast::render::walk::Renderer;
use portalcast_format::MapTables;

const SURFACE_MISMATCH_MAX_PERCENT: f64 = 0.5;

/// A pit whose four sides are sloped sectors as steep as the compiler allows, centred at
/// `(cx, cy)`: `steep` is the rise along the slopes over their 32-unit run (128 = 4 per unit).
/// Its ceilings slope too, the west one down to the player's height (48) over its floor.
fn pit(cx: i32, cy: i32, steep: i32) -> String {
    let (a, b, c) = (cx - 96, cx - 64, cx + 64);
    let (d, e, f) = (cy - 96, cy - 64, cy + 64);
    let (g, h) = (cx + 96, cy + 96);
    let top = steep;
    format!(
        "vertex p0 {b} {e}\nvertex p1 {c} {e}\nvertex p2 {c} {f}\nvertex p3 {b} {f}\n\
         vertex o0 {a} {d}\nvertex o1 {g} {d}\nvertex o2 {g} {h}\nvertex o3 {a} {h}\n\
         sector floor floor=0 ceil=256 floor_tex=tiles ceil_tex=ceiling light=180\n\
         wall p0 p1 portal=north lower=step upper=brick\nwall p1 p2 portal=east lower=step upper=brick\n\
         wall p2 p3 portal=south lower=step upper=brick\nwall p3 p0 portal=west lower=step upper=brick\n\
         sector north floor_slope=p0:0,p1:0,o0:{top} ceil_slope=p0:240,p1:240,o0:{ctop} floor_tex=stone ceil_tex=metal light=150\n\
         wall o0 o1 tex=brick\nwall o1 p1 portal=east lower=step upper=brick\nwall p1 p0 portal=floor\nwall p0 o0 portal=west lower=step upper=brick\n\
         sector east floor_slope=p1:0,p2:0,o1:{top} ceil=256 floor_tex=grass ceil_tex=ceiling light=160\n\
         wall o1 o2 tex=brick\nwall o2 p2 portal=south lower=step upper=brick\nwall p2 p1 portal=floor\nwall p1 o1 portal=north lower=step upper=brick\n\
         sector south floor_slope=p2:0,p3:0,o2:{top} ceil=256 floor_tex=wood ceil_tex=ceiling light=170\n\
         wall o2 o3 tex=brick\nwall o3 p3 portal=west lower=step upper=brick\nwall p3 p2 portal=floor\nwall p2 o2 portal=east lower=step upper=brick\n\
         sector west floor_slope=p3:0,p0:0,o3:{top} ceil_slope=p3:{wlow},p0:{wlow},o3:{whigh} floor_tex=marble ceil_tex=wood light=140\n\
         wall o3 o0 tex=brick\nwall o0 p0 portal=north lower=step upper=brick\nwall p0 p3 portal=floor\nwall p3 o3 portal=south lower=step upper=brick\n\
         player {cx} {cy}\n",
        ctop = 240 + top,
        wlow = 48 + 1,
        whigh = top + 48,
    )
}

/// Renders `map` at `camera` with the engine (at `steps`) and the oracle, at `resolution`.
fn compare(
    map: &MapTables,
    camera: &Camera,
    resolution: Resolution,
    steps: SlopeSteps,
    renderer: &mut Renderer,
) -> portalcast_oracle::Comparison {
    let settings = Settings {
        resolution,
        slope_steps: steps,
        ..Settings::DEFAULT
    };
    engine_against_oracle(map, camera, &settings, renderer, false)
}

fn compiled(name: &str, text: &str) -> portalcast_assets::CompiledMap {
    common::player::compile_map(name, text)
}

#[test]
fn the_steepest_slopes_near_and_far_from_the_origin_match_the_oracle() {
    let mut renderer = Renderer::new();
    let mut frames = 0;
    let mut worst = 0.0f64;
    for (name, cx, cy) in [
        ("pit-origin", 0, 0),
        ("pit-far", 8000, -8000),
        ("pit-odd", -7777, 5555),
    ] {
        let compiled = compiled(&format!("{name}.map"), &pit(cx, cy, 128));
        let map = compiled.tables();
        let mut poses = portalcast_oracle::sample_poses(&map, 16, 11);
        // The eye a unit above the steep north slope, looking along it and across it.
        for angle in [0u16, 16384, 49152] {
            poses.push(portalcast_oracle::Camera::from_fixed(
                cx * 256,
                (cy - 80) * 256,
                (64 + 1) * 256,
                angle,
                portalcast_oracle::find_sector(&map, f64::from(cx), f64::from(cy - 80)),
            ));
        }
        for pose in &poses {
            let (camera, _) = cameras_of_pose(pose);
            for resolution in Resolution::ALL {
                let comparison = compare(
                    &map,
                    &camera,
                    resolution,
                    SlopeSteps::DEFAULT,
                    &mut renderer,
                );
                let percent = comparison.surface_mismatch_percent();
                worst = worst.max(percent);
                frames += 1;
                assert!(
                    percent <= SURFACE_MISMATCH_MAX_PERCENT
                        && comparison.holes == 0
                        && comparison.missed_sectors.is_empty(),
                    "{name} {camera:?} {resolution:?}: {comparison:?} ({percent:.3} %)"
                );
            }
        }
    }
    println!("steep slopes: {frames} frames, worst surface mismatch {worst:.3} %");
}

#[test]
fn each_slope_step_s_texels_drift_from_the_exact_mapping_as_it_grows() {
    let compiled = compiled("pit.map", &pit(0, 0, 96));
    let map = compiled.tables();
    let mut renderer = Renderer::new();
    let poses = portalcast_oracle::sample_poses(&map, 12, 5);
    let mut texel_percent = Vec::new();
    for steps in SlopeSteps::ALL {
        let mut sum = 0.0;
        for pose in &poses {
            let (camera, _) = cameras_of_pose(pose);
            sum += compare(&map, &camera, Resolution::R240x160, steps, &mut renderer)
                .texel_mismatch_percent();
        }
        texel_percent.push((steps.label(), sum / poses.len() as f64));
    }
    println!("texels off the oracle by N: {texel_percent:?}");
    let exact = texel_percent[0].1;
    for &(label, percent) in &texel_percent[1..] {
        assert!(
            percent >= exact - 0.05,
            "N={label}: {percent:.2} % below N=1's {exact:.2} %"
        );
    }
    assert!(
        texel_percent.last().unwrap().1 > exact,
        "N=32 drifts from the exact mapping: {texel_percent:?}"
    );
}
