//! The frames the default settings draw, hashed: a change that is meant to leave every pixel
//! alone (a faster stepper, a cache, a table moved) must leave this hash alone.
//!
//! `cargo test --release --test frames_hash -- --nocapture` prints the hash.

use portalcast::frame::Resolution;
use portalcast::math::Angle;
use portalcast::render::view::{Camera, View};
use portalcast::render::walk::Renderer;
use portalcast_format::MapTables;
use portalcast_oracle::RecordingCanvas;
use portalcast_rom::assets;
use portalcast_rom::bench::default_settings;
use portalcast_rom::demo::render_assets;
use portalcast_rom::flight::Flight;

/// Frames of each map's fly-through hashed (from its start: the map as drawn, no mover moved;
/// the value below was measured on these).
const HASHED_FRAMES: usize = 64;

/// The poses sampled on `map`: every frame of its fly-through, and its first pose turned
/// by eighths of a turn (a vertex behind the eye on most of them).
fn poses(map: &MapTables) -> Vec<Camera> {
    let flight: Vec<Camera> = Flight::new(map).take(HASHED_FRAMES).collect();
    let turns = (0..8u16).map(|turn| {
        let mut camera = flight[0];
        camera.angle = Angle::from_bits(camera.angle.to_bits().wrapping_add(turn * 8192 + 123));
        camera
    });
    flight.iter().copied().chain(turns).collect()
}

/// FNV-1a over the frames the default settings draw at the sampled poses of every shipped map:
/// the value below was first measured on the engine of commit e53fb17, so the default settings
/// draw the same pixels as then, bit for bit (the speed work of issue 15 kept it: stepped rows,
/// the vertex cache, the strips' level cache, the compiled wall lengths). It was measured again when
/// floor and ceiling spans started stepping from the row's centre column instead of their own
/// first pixel (so that merging sector visits changes no texel; tests/scene_preprocessing.rs),
/// a change of plane texels only, and of no surface (the oracle figures in docs/BENCH.md). And
/// again when column ownership moved from the rounded eye-space vertices to the exact ones
/// (`ExactEyePoint`, issue 16): 53 halfwords of the 576 frames of the three maps' fly-throughs
/// changed, columns whose ray passes within a rounding step of a vertex.
#[test]
fn the_default_settings_draw_the_same_frames_as_before() {
    let assets = render_assets();
    let mut renderer = Renderer::new();
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for map in assets::MAPS {
        // The poses the value below was measured at: every 4th frame, then the turns.
        let poses = poses(map);
        let (flight, turns) = poses.split_at(HASHED_FRAMES);
        for &camera in flight.iter().step_by(4).chain(turns) {
            for resolution in Resolution::ALL {
                let view = View::new(&camera, &default_settings(resolution));
                let mut canvas = RecordingCanvas::new(resolution);
                renderer.render(map, &assets, &view, &mut canvas);
                for byte in canvas
                    .page
                    .halfwords
                    .iter()
                    .flat_map(|half| half.to_le_bytes())
                {
                    hash = (hash ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3);
                }
            }
        }
    }
    println!("exact frames hash {hash:#018x}");
    assert_eq!(hash, EXACT_FRAMES_HASH, "{hash:#018x}");
}

/// Re-recorded when things, portal middles and translucency began to be drawn (issue 17; the
/// new images changed the palette too), when the bench map got its door and lift (issue 18:
/// new sectors along the fly-through, which the cartridge's tables draw open and raised), and
/// when the fly-through began to keep a player's clearance from solid things and to give every
/// sector on its way a frame (other poses; the commit changed no drawing code). And when the
/// spans began to take their map position and step from the frame's plane rays (one product per
/// coordinate, `render::view::PlaneRays`) instead of from the depth's product with the focal
/// length and then with the sine and cosine: 188 of the 4,147,200 halfwords hashed changed, a
/// plane texel each, and the oracle's figures in docs/BENCH.md did not move. And when a portal
/// middle's `1/z'` began to come from one product a column (the denominator of its `t` times the
/// wall's constant reciprocal) instead of the reciprocal of its rounded depth: 7 halfwords
/// changed. And when the slopes map was shipped (issue 20): with it left out, the hash was still
/// `0x7b71_ac7a_dbbe_c601`, the flat maps' frames unchanged. And when the slopes map got its
/// canyon with room over room (issue 20): with it left out the hash was again that one.
const EXACT_FRAMES_HASH: u64 = 0x2ab3_4124_d8db_83b8;
