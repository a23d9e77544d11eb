//! The contract between the asset compiler (`portalcast-assets`, run by `build.rs` and by host
//! tests) and the engine (`portalcast`): the layout of every table the ROM reads, and the declared
//! numeric limits that the compiler enforces and the renderer relies on.
//!
//! This crate is `no_std`, has no dependencies and holds no logic beyond the data types, so both
//! sides agree on one definition.
#![no_std]

pub mod limits;
