//! The contract between the asset compiler (`portalcast-assets`, run by `build.rs` and by host
//! tests) and the engine (`portalcast`): the layout of every table the ROM reads, and the declared
//! numeric limits that the compiler enforces and the renderer relies on.
//!
//! This crate is `no_std`, has no dependencies and holds no logic beyond the data types and a few
//! accessors, so both sides agree on one definition. Every table type is `Copy`, `#[repr(C)]`
//! and borrows its arrays with a lifetime `'a`: the ROM uses `'static` tables emitted by the
//! compiler into `OUT_DIR`, host tests borrow the `Vec`s of a freshly compiled asset set.
//!
//! Conventions (see `docs/ARCHITECTURE.md`): map plane `(x, y)` with `y` drawn downward, heights
//! `z`; sectors convex with their walls stored clockwise on a top-down view, so the inside is to
//! the right of each wall `a → b`; binary angles of 65536 units per turn, 0 along +x, growing
//! toward +y.
#![no_std]

mod assets;
pub mod limits;
mod map;
pub mod memory;
mod texture;

pub use assets::Assets;
pub use map::{
    find_twin, sector_heights_fx8_at, LayerLink, Light, MapTables, Mover, Plane, PlayerSize,
    PlayerStart, Sector, SectorSlope, Thing, Trigger, Vertex, Wall, LIGHT_FLICKER, LIGHT_GLOW,
    LIGHT_STROBE, LIGHT_SWITCHED, LINK_CEILING, LINK_FLOOR, MOVER_CRUSHER, MOVER_DOOR, MOVER_LIFT,
    MOVER_ON_TOUCH, MOVER_ON_USE, MOVER_PLATFORM, NO_LINK, NO_PORTAL, NO_SLOPE, NO_TEXTURE,
    NO_TWIN, PLANE_ERROR_BOUND_FX8, SKY, STROBE_FLASH_TICKS, THING_HANGING, THING_SOLID,
    THING_TRANSLUCENT, TRIGGER_LINE, TRIGGER_SWITCH, TRIGGER_THROWN, WALL_MIDDLE_BLOCKS,
    WALL_MIDDLE_TRANSLUCENT, WALL_SWITCH,
};
pub use texture::{
    bgr555, colormap_row, BlendTable, Colormap, Palette, Post, Sky, Sprite, SpriteSet, Texture,
    TextureChain, LIGHT_LEVELS, LIGHT_NEUTRAL, POST_HEADER_BYTES, TRANSPARENT,
};

/// Forces 4-byte alignment on its contents, so the ROM can read blobs pulled in with
/// `include_bytes!` (alignment 1) with word loads and DMA.
///
/// The generated code wraps each blob once,
/// `static BLOB: Align4<[u8; N]> = Align4(*include_bytes!("..."));`, and hands out sub-slices of
/// `BLOB.0` with [`sub_slice`].
#[repr(C, align(4))]
pub struct Align4<T: ?Sized>(pub T);

/// `&blob[start..start + len]`, usable in `static` initializers (slice indexing is not `const`).
///
/// Panics (at compile time, in a `static`) if the range is out of bounds.
pub const fn sub_slice(blob: &[u8], start: usize, len: usize) -> &[u8] {
    blob.split_at(start).1.split_at(len).0
}
