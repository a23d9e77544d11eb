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
//! - Things: a thing is a flat rectangle facing the camera (a plane of constant eye depth `z'`,
//!   its centre's, with `x'` and `z'` its eye coordinates): `width` units wide, centred on `x'`,
//!   `height` units tall from its bottom `b` (the sector's floor plus the thing's `z`, or, hanging,
//!   the ceiling minus `z` minus the height), one unit per texel, never mipmapped. The pixel whose
//!   ray is `m = (column + ½ − width/2) / focal_x` across and `k = (row + ½ − horizon) / focal_y`
//!   down per unit of depth meets the rectangle at `u = floor(m·z' − (x' − width/2))`,
//!   `v = floor(b + height − (eye_z − k·z'))`, and shows the thing if `0 ≤ u < width`,
//!   `0 ≤ v < height`, texel `(u, v)` is opaque, and the ray reaches the thing's sector: the sector
//!   is on the pixel's path through the portals and no surface of a sector before it on that path
//!   stopped the ray (the window the portal walk sees it through). Of several things there, the
//!   nearest (`z'`) shows; at equal depth the later in the map's table. A thing nearer than
//!   [`THING_DEPTH_MIN`] is not drawn. Lit by its sector's light at depth `z'`, like a wall.
//!   The compiler keeps each thing's footprint (a disc of at least half its width) and height
//!   inside its sector, so the rectangle lies inside the sector's volume, and "reaches the sector"
//!   is exactly "nothing nearer hides it".
//! - Middles: a portal wall's middle image (its `middle` sprite set, a still image) is drawn in
//!   the opening, where the pixel's ray passes from the wall's sector into the neighbour (on
//!   the wall, at the crossing's depth `t`): texel column `floor(u) mod width` with the wall's
//!   `u`, row `v = floor(anchor + y_offset − h)` with `anchor` the lower of the two ceilings and
//!   `h` the ray's height at the crossing, shown where `0 ≤ v < height` and the texel is opaque.
//!   It does not repeat vertically. Lit by the wall's own sector at depth `t`. A thing in the
//!   wall's sector or nearer covers it; anything behind the portal is covered by it.
//! - Translucency: a translucent thing or middle shows `blend[behind][front]` (the compiled
//!   `BlendTable`), `front` its lit texel and `behind` the index the pixel had without it.

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
    /// A thing's sprite, by index in the map's things table.
    Thing(u16),
    /// A portal wall's middle image, by wall index.
    Middle(u16),
}

/// Nearest eye depth, in world units, at which a thing is drawn (its centre's `z'`): nearer, its
/// sprite would fill the screen with a few texels, so it is left out, as the eye walks through a
/// thing that does not block.
pub const THING_DEPTH_MIN: i32 = 4;
