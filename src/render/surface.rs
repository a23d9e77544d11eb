//! What a pixel shows, and the texture rules that pick its texel. The f64 oracle
//! (`crates/oracle`) implements the same rules in floating point; the accuracy tests compare the
//! two pixel by pixel.
//!
//! - Walls: `u` is the distance along the wall from its start vertex plus the wall's x offset;
//!   `v` is the distance below the anchor height plus the y offset. A solid wall and an upper
//!   strip are anchored at their own sector's ceiling, a lower strip at the neighbour's floor.
//!   Texel `(floor(u) mod width, floor(v) mod height)`, at mip level `m`: both divided by `2^m`.
//! - Floors and ceilings: texel `(floor(x) mod side, floor(y) mod side)` of the map point hit.
//! - Mip level: `floor(log2(z' / focal_y))`, at least 0 and below the texture's mip count, with
//!   `z'` the eye-space depth of the column (walls) or row (flats).
//! - Sky: column `floor(angle / 2π · width) mod width` of the ray's map angle; row
//!   `floor((y − horizon) · 160 / height) + sky_height / 2`, clamped to the image, for the pixel
//!   centre `y = row + ½`: the panorama is two screens tall so looking up or down stays covered.

/// The surface a pixel belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Surface {
    /// Not drawn (a hole, if any pixel ends a frame like this).
    #[default]
    None,
    /// A solid wall, by wall index.
    Wall(u16),
    /// The strip above a portal (this ceiling down to the neighbour's), by wall index.
    Upper(u16),
    /// The strip below a portal (the neighbour's floor down to this floor), by wall index.
    Lower(u16),
    /// A sector's floor.
    Floor(u16),
    /// A sector's ceiling.
    Ceiling(u16),
    /// The sky panorama.
    Sky,
}
