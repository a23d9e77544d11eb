//! The compiled assets: the statics `build.rs` generated from `assets/` (or
//! `$PORTALCAST_ASSETS`) with the asset compiler. The ROM and the host tests read the same ones.
#![allow(missing_docs)]

include!(concat!(env!("OUT_DIR"), "/assets.rs"));
