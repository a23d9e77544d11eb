//! Declared limits of the world. PROVISIONAL values: the fixed-point analysis (issue 3) replaces
//! them with values it derives and documents.

/// Largest absolute map coordinate, in world units (1 unit = 1 texel at mip level 0).
pub const WORLD_COORD_MAX: i32 = 8192;
/// Lowest floor or ceiling height, in world units.
pub const HEIGHT_MIN: i32 = -4096;
/// Highest floor or ceiling height, in world units.
pub const HEIGHT_MAX: i32 = 4096;
