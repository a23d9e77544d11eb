//! The portalcast asset compiler. One implementation, used by the ROM's `build.rs` and by host tests.

pub mod numeric_tables;
