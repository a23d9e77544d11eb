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

// The map compiler refuses maps whose views pass more portals in a row than the walk follows;
// it knows the walk's depth through the format crate's limit, which must be the walk's own.
const _: () = assert!(
    render::walk::MAX_PORTAL_DEPTH == portalcast_format::limits::PORTAL_DEPTH_MAX,
    "the map compiler's portal depth limit differs from the walk's"
);
