//! Declared limits of the world, derived from the fixed-point products the engine computes.
//!
//! The asset compiler rejects maps outside these limits; the renderer relies on them to keep
//! every product inside its integer type. All values are `i32` in world units (1 unit = 1 texel
//! at mip level 0) or pixels. The engine's formats (see `portalcast::math`) are 24.8 for
//! positions, heights and eye-space coordinates (range ±2^23, resolution 1/256), 16.16 for
//! texture coordinates and steps (range ±2^15), and 2.30 for inverse depth and unit-range
//! reciprocals (range ±2).
//!
//! # The products that bound the world
//!
//! With `D = EYE_DISTANCE_MAX` (the farthest two points of the world can be apart), `d =
//! FOCAL_LENGTH_MAX`, `W = SCREEN_WIDTH_MAX`, `Δh = HEIGHT_DIFF_MAX`:
//!
//! | product (where) | type | bound with the values below | limit it sets |
//! |---|---|---|---|
//! | `2·d·x'` and `(2k+1)·z'`, the exact column test (per vertex) | i32, 24.8 bits | `241 · 23171 · 256 = 1.43e9 < 2^31` | `D ≤ 34_800`, so `WORLD_COORD_MAX ≤ 12_300` |
//! | `u = x_offset + t·length`, wall texture `u` (per wall) | 16.16 | `255 + 23171 < 32768` | `D ≤ 32_512`, so `WORLD_COORD_MAX ≤ 11_494` |
//! | `u/z'` for perspective-correct `u` (per wall, per column) | 16.16 | `32767 / EYE_DEPTH_MIN = 32767` | `EYE_DEPTH_MIN ≥ 1` |
//! | `1/z'` (per column) | 2.30 | `1 / EYE_DEPTH_MIN = 1 < 2` | `EYE_DEPTH_MIN > 1/2` |
//! | `2·d·Δh`, floor depth `z' = d·Δh / (row + ½ − cy)` (per row) | i32, 24.8 bits | `240 · 16384 · 256 = 1.01e9 < 2^31` | `Δh ≤ 34_952` |
//! | floor depth next to the horizon, `2·d·Δh` (per row) | 24.8 | `3.93e6 < 2^23` | `Δh ≤ 34_952` |
//! | `d·Δh / z'`, projected row of a height (per vertex, per column) | 24.8 | `120 · 16384 / 1 = 1.97e6 < 2^23` | `Δh ≤ 69_905` |
//! | eye transform `(p − e)·r`, `(p − e)·f` (per vertex) | i64 | `2^22 · 2^16 · 2 = 2^39` | none |
//! | orientation cross products (per test) | i64 | `2 · (2^22)^2 = 2^45` | none |
//!
//! `WORLD_COORD_MAX = 8192` is the largest power of two under both world bounds (11_494 and
//! 12_300): a vertex is `±8192`, a 16384-unit square, 256 rooms of 64 units across. Doom's
//! 16.16 world stops near `±32768`; this engine keeps 8 fractional bits for positions and
//! spends the rest on exact column tests in 32 bits. The heights get the same power of two:
//! `Δh = 16384` leaves a factor 2.1 under the tightest height bound.
//!
//! Texture coordinates that only matter modulo the texture size (the vertical `v` of walls, the
//! map position stepped along a floor span) wrap at 2^16 texels on purpose, which keeps every
//! power-of-two texture intact; they set no limit.

/// Largest absolute map coordinate, in world units. See the module table: the wall `u` in 16.16
/// allows 11_494, the exact column test in i32 12_300; this is the largest power of two below.
pub const WORLD_COORD_MAX: i32 = 8192;

/// Lowest floor or ceiling height, in world units (and lowest eye height).
pub const HEIGHT_MIN: i32 = -8192;

/// Highest floor or ceiling height, in world units (and highest eye height).
pub const HEIGHT_MAX: i32 = 8192;

/// Steepest slope of a floor or ceiling: rise per unit of run along x or along y (4 is about
/// 76°). [`Plane`](crate::Plane)'s 8.24 gradients hold 8; the bound keeps a plane's height at the
/// world origin (up to `HEIGHT_MAX + 4·2·WORLD_COORD_MAX` units) within 24.8's i32, and a
/// sloped span's depth rule away from overflow.
pub const SLOPE_GRADIENT_MAX: i32 = 4;

/// Largest difference between two heights of the world, in particular between a floor or ceiling
/// and the eye: `HEIGHT_MAX − HEIGHT_MIN`. The floor depth `2·d·Δh` in 24.8 bits must fit i32
/// (`Δh ≤ 34_952`); this leaves a factor 2.1.
pub const HEIGHT_DIFF_MAX: i32 = HEIGHT_MAX - HEIGHT_MIN;

/// Farthest two points of the world can be apart: `ceil(2·√2·WORLD_COORD_MAX)` (the diagonal of
/// the square). Bounds `|x'|`, `|z'|` of every eye-space point and the length of every wall.
pub const EYE_DISTANCE_MAX: i32 = 23_171;

/// Longest wall (or portal): no longer than the world's diagonal.
pub const WALL_LENGTH_MAX: i32 = EYE_DISTANCE_MAX;

/// Near plane: the renderer clips eye-space segments to `z' ≥ EYE_DEPTH_MIN` before projecting.
///
/// At 1 unit, `1/z' ≤ 1` fits 2.30 and `u/z' ≤ 32767` fits 16.16. What the clip removes lies
/// within `√2` units of the eye horizontally (inside the 90° frustum) and, to be on screen, within
/// `H / d_y = 160/120 ≈ 1.34` units vertically, i.e. inside the player's own body: any collision
/// rule that keeps the eye 2 units from walls, floors and ceilings makes the clip invisible.
pub const EYE_DEPTH_MIN: i32 = 1;

/// Largest eye-space depth of any point of the world (`= EYE_DISTANCE_MAX`); `1/z'` at this
/// depth is `2^30 / 23171 ≈ 46341` units of 2.30, a resolution of `2.2e-5` relative.
pub const EYE_DEPTH_MAX: i32 = EYE_DISTANCE_MAX;

/// Largest texture side in texels (`width_log2`, `height_log2 ≤ 8` in the texture tables).
pub const TEXTURE_SIZE_MAX: i32 = 256;

/// Largest texture coordinate the engine holds unwrapped, in texels: the integer range of 16.16.
/// A wall's `u` runs from `x_offset mod width` (`< TEXTURE_SIZE_MAX`) to that plus the wall's
/// length, `255 + WALL_LENGTH_MAX = 23426 ≤ 32767`.
pub const TEXTURE_COORD_MAX: i32 = 32_767;

/// Deepest portal chain the renderer follows from the eye's sector (the walk's
/// `MAX_PORTAL_DEPTH`, which `src/lib.rs` asserts equal): sectors further along a chain are left
/// undrawn, so the map compiler refuses a map where a view could cross more portals in a row.
pub const PORTAL_DEPTH_MAX: u32 = 256;

/// Most things one map may place. [`crate::MapTables::sector_things`] indexes the things table
/// with `u16` entries, which this keeps far inside; the bound also caps the table at 20 KiB of ROM
/// (20 bytes a thing) and the things the renderer may have to consider in one frame. The map
/// compiler refuses a map with more.
pub const THINGS_MAX: u32 = 1024;

/// Most movers (doors, lifts, platforms, crushers: [`crate::Mover`]) one map may have. The game
/// keeps a live state for each mover and checks every one each tick (what starts it, whether its
/// move fits the player's body), so the bound caps that work and that RAM; it also keeps mover
/// indices far inside `u16`. The map compiler refuses a map with more.
pub const MOVERS_MAX: u32 = 64;

/// Most triggers (switches and walk-over lines: [`crate::Trigger`]) one map may have. The game
/// scans them when the player uses a wall or crosses a portal, so the bound caps that scan; it
/// also caps the table at 2 KiB of ROM (8 bytes a trigger). The map compiler refuses a map with
/// more.
pub const TRIGGERS_MAX: u32 = 256;

/// Most sectors with a light effect ([`crate::Light`]) one map may have. The game sets each
/// one's level every frame it draws, so the bound caps that work; it also caps the table at
/// 2 KiB of ROM (8 bytes a light). The map compiler refuses a map with more.
pub const LIGHTS_MAX: u32 = 256;

/// Widest logical screen, in columns (Mode 4 at full width).
pub const SCREEN_WIDTH_MAX: i32 = 240;

/// Narrowest logical screen, in columns (two pixels per column).
pub const SCREEN_WIDTH_MIN: i32 = 120;

/// Tallest logical screen, in rows.
pub const SCREEN_HEIGHT_MAX: i32 = 160;

/// Shortest logical screen, in rows (rendered at 80 and doubled by the BG2 affine scale).
pub const SCREEN_HEIGHT_MIN: i32 = 80;

/// Largest focal length, in pixels. With a 90° horizontal field of view `d_x = width / 2`, and
/// with the GBA's square physical pixels `d_y = 3·height / 4`; both are at most 120.
pub const FOCAL_LENGTH_MAX: i32 = 120;

/// Smallest focal length, in pixels (`120 / 2`, `3·80 / 4`).
pub const FOCAL_LENGTH_MIN: i32 = 60;

// The arithmetic of the module table, checked by the compiler.
const FX24_8_ONE: i64 = 256;
const FX16_16_INT_MAX: i64 = 32_767;
const I32_MAX: i64 = i32::MAX as i64;
const FX24_8_INT_MAX: i64 = I32_MAX / FX24_8_ONE;

// EYE_DISTANCE_MAX is the ceiling of the diagonal: D² ≥ 8·W² > (D − 1)².
const _: () = {
    let w = WORLD_COORD_MAX as i64;
    let d = EYE_DISTANCE_MAX as i64;
    assert!(d * d >= 8 * w * w && (d - 1) * (d - 1) < 8 * w * w);
};
// Exact column test: (2k+1)·Z with |2k+1| ≤ W+1, and 2·d·X, in i32.
const _: () = {
    let z_bits = EYE_DISTANCE_MAX as i64 * FX24_8_ONE;
    assert!((SCREEN_WIDTH_MAX as i64 + 1) * z_bits <= I32_MAX);
    assert!(2 * FOCAL_LENGTH_MAX as i64 * z_bits <= I32_MAX);
};
// Wall u in 16.16, and u/z' in 16.16 at the near plane.
const _: () = assert!(
    (TEXTURE_SIZE_MAX - 1 + WALL_LENGTH_MAX) as i64 <= TEXTURE_COORD_MAX as i64
        && TEXTURE_COORD_MAX as i64 <= FX16_16_INT_MAX
);
const _: () = assert!(EYE_DEPTH_MIN >= 1);
// Floor depth: 2·d·Δh in 24.8 bits fits i32, and so does the depth itself.
const _: () = {
    let product = 2 * FOCAL_LENGTH_MAX as i64 * HEIGHT_DIFF_MAX as i64;
    assert!(product * FX24_8_ONE <= I32_MAX);
    assert!(product <= FX24_8_INT_MAX);
};
// Projected row offset d·Δh/z' at the near plane in 24.8.
const _: () = assert!(
    FOCAL_LENGTH_MAX as i64 * HEIGHT_DIFF_MAX as i64 / EYE_DEPTH_MIN as i64 <= FX24_8_INT_MAX
);
const _: () = assert!(HEIGHT_DIFF_MAX == HEIGHT_MAX - HEIGHT_MIN && HEIGHT_MIN < HEIGHT_MAX);
const _: () = assert!(
    SCREEN_WIDTH_MAX / 2 <= FOCAL_LENGTH_MAX
        && 3 * SCREEN_HEIGHT_MAX / 4 <= FOCAL_LENGTH_MAX
        && SCREEN_WIDTH_MIN / 2 >= FOCAL_LENGTH_MIN
        && 3 * SCREEN_HEIGHT_MIN / 4 >= FOCAL_LENGTH_MIN
);
const _: () = assert!(THINGS_MAX < u16::MAX as u32);
