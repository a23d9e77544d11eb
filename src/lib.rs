//! portalcast: a sector/portal 3D engine for the Game Boy Advance.
//!
//! The library is `no_std` and builds for the host (where `cargo test` checks the math, the
//! rasterizer twins and the renderer against an f64 oracle) and for `thumbv4t-none-eabi`, where a
//! game drives it: the shipped ROM (`crates/rom`) is one, built from this public API like any
//! other. A game brings its own maps, textures and sprites, compiled by
//! `portalcast_assets::Builder` in its build script (docs/GUIDE.md). See `docs/ARCHITECTURE.md`
//! for the pipeline.
#![cfg_attr(not(test), no_std)]
#![deny(unsafe_code)]
#![warn(missing_docs)]

pub mod frame;
pub mod math;
pub mod math_bench;
pub mod player;
pub mod raster;
pub mod render;
pub mod stack;
pub mod text;
pub mod world;

#[cfg(target_os = "none")]
pub mod hw;

/// What a game uses most, in one `use portalcast::prelude::*;`: the player and its controls, the
/// live world, the camera, settings and view, the renderer and its assets, the compiled assets'
/// types, and on the GBA the machine.
///
/// The same engine on the host, where a game's maps can be tested: a game's assets compiled as
/// its build script compiles them, the player walked forward half a second, and one frame drawn
/// into a host page.
///
/// ```
/// use portalcast::prelude::*;
/// use portalcast::raster::{HostCanvas, HostPage};
///
/// let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/minimal/assets");
/// let compiled = portalcast_assets::compile_dir(std::path::Path::new(dir)).unwrap();
/// let tables = compiled.host_tables();
/// let assets = tables.assets();
/// let map = assets.map("room").unwrap();
/// let (mut player, mut controls) = (Player::spawn(map), Controls::new());
/// for _ in 0..30 {
///     player.tick(&controls.read(Buttons::UP), map);
/// }
/// let settings = Settings::DEFAULT;
/// let view = View::new(&player.camera(), &settings);
/// let mut page = HostPage::new();
/// let mut canvas = HostCanvas { page: &mut page, resolution: settings.resolution, halved_flats: false };
/// let mut renderer = Box::new(Renderer::new());
/// let stats = renderer.render(map, &RenderAssets::from_assets(&assets), &view, &mut canvas);
/// assert_eq!(stats.wall_columns, 120);
/// ```
pub mod prelude {
    pub use crate::frame::Resolution;
    pub use crate::math::{Angle, Fx24_8, WorldPoint};
    pub use crate::player::input::{Buttons, Controls};
    pub use crate::player::Player;
    pub use crate::render::view::{Camera, Settings, View};
    pub use crate::render::walk::Renderer;
    pub use crate::render::RenderAssets;
    pub use crate::world::{remove_thing, World};
    pub use portalcast_format::{Assets, MapTables};

    #[cfg(target_os = "none")]
    pub use crate::hw::{input, log, memory, panic_screen, video::Display, Machine, ObjVram};
}

// The map compiler refuses maps whose views pass more portals in a row than the walk follows;
// it knows the walk's depth through the format crate's limit, which must be the walk's own.
const _: () = assert!(
    render::walk::MAX_PORTAL_DEPTH == portalcast_format::limits::PORTAL_DEPTH_MAX,
    "the map compiler's portal depth limit differs from the walk's"
);
