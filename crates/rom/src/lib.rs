//! The shipped portalcast ROM's game and scenes, on the engine's public API: the game (the
//! player on the shipped maps, with the Start menu), the demo's assets and settings, the
//! benchmark's fly-throughs and lines, the kernel check, the test picture and the boot
//! self-check. `main.rs` is the ROM; the host tests and the oracle read these same modules.
//!
//! Its assets are `assets/` at the repository's top (or `PORTALCAST_ASSETS`), compiled by its
//! build script through `portalcast_assets::Builder`, as any game's are.
#![cfg_attr(not(test), no_std)]
#![deny(unsafe_code)]
#![warn(missing_docs)]

pub mod assets;
pub mod bench;
pub mod demo;
pub mod flight;
pub mod game;
pub mod kernel_check;
pub mod live_flight;
pub mod menu;
pub mod selfcheck;
pub mod testpic;
