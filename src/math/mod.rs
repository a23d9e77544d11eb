//! Fixed-point formats, angles, trig, reciprocals and exact integer geometry.
//!
//! Everything here is integer-only (no float reaches the ROM), `no_std`, free of `unsafe`, and
//! has no dependency besides the declared limits of `portalcast_format::limits`.
//!
//! # Formats
//!
//! | type | bits | range | resolution | holds |
//! |---|---|---|---|---|
//! | [`Fx24_8`] | i32, 8 fractional | `±2^23` (±8 388 608) | `1/256` | world positions, heights, eye-space `x'`, `z'`, screen `y` |
//! | [`Fx16_16`] | i32, 16 fractional | `±2^15` (±32 768) | `1/65536` | texture coordinates and steps, slopes, sin/cos, screen `x` |
//! | [`Fx2_30`] | i32, 30 fractional | `±2` | `2^-30` | inverse depth `1/z'`, small reciprocals `1/n`, wall parameter `t` |
//!
//! Why 2.30 for `1/z'` rather than the thesis' 8.24: with the near plane at 1 unit, `1/z' ≤ 1`,
//! so the integer bits beyond 2 are never used, and the six extra fractional bits keep the
//! far end (`1/23171` = 46341 ulps) and per-column interpolation steps precise. It also holds
//! the small reciprocals with a relative error of `n·2^-31` instead of 16.16's `n·2^-17`.
//!
//! Operations: `+`, `-`, [`Fx24_8::mul_int`] and the same-format [`Fx24_8::mul`] panic on
//! overflow in debug builds (and wrap in release, like Rust's integers); `checked_`,
//! `saturating_` and `wrapping_` variants say what else to do. A product of two formats names
//! its result: [`Fx24_8::mul_fx16_16`] → 24.8, [`Fx24_8::mul_fx2_30`] → 24.8,
//! [`Fx16_16::mul_fx2_30`] → 16.16, [`Fx24_8::dot_fx16_16`] → 24.8. Conversions are explicit
//! ([`Fx24_8::to_fx16_16`], [`Fx16_16::to_fx24_8_round`], [`Fx2_30::to_fx16_16_round`], …).
//! Products and narrowing conversions round to nearest (ties toward +∞): error ≤ ½ ulp of the
//! result. Products use one 32×32→64 multiply (`SMULL`, 3–6 cycles in ARM state), so they
//! belong in per-wall, per-row or per-column code; the per-pixel loops only add (`wrapping_add`
//! on texture coordinates, which only matter modulo a power-of-two texture size).
//!
//! # Own types rather than the `fixed` crate
//!
//! The API follows `fixed`'s conventions (`from_bits`/`to_bits`, `DELTA`, `checked_`/
//! `saturating_`/`wrapping_`, `to_int_floor` = its `to_num` rounding), but the types are our own:
//! - mixed-format products name their operand and result formats in the method name
//!   (`Fx24_8::mul_fx16_16` → 24.8), readable at the call site without type-level generics;
//! - every named operation, sine, cosine and the reciprocals included, is a `const fn` over
//!   `i32`, usable in `const` items and tables (only the operator traits are not `const`);
//! - rounding is ours to choose and document: nearest everywhere, stated per operation;
//! - no third-party crate enters the ROM's arithmetic, so what runs is what is read here;
//! - the 2.30 reciprocal, the exact column test and the geometry need the raw bits anyway.
//!
//! # Tables and their errors
//!
//! Generated at build time by `portalcast_assets::numeric_tables` ([`tables`]):
//!
//! | function | table | max error (bound / measured) |
//! |---|---|---|
//! | [`Angle::sin`], [`Angle::cos`] → 16.16 | quarter wave, 1025 × i32 2.30 (4 KB), linear interpolation | 7.93e-6 (0.52 ulp) / 7.905e-6 over all 65536 angles |
//! | [`recip_pow2`], [`Fx24_8::recip_fx2_30`], [`Fx2_30::recip_fx24_8`] | 1024 × u16 seeds (2 KB) + one second-order Newton step | relative ≤ 1e-9 (measured 9.4e-10 over all 2^31 mantissas) + ½ ulp |
//! | [`recip_small`] → 2.30, `1 ≤ n ≤ 511` | 512 × i32 (2 KB) | `2^-31` absolute, `n·2^-31` relative |
//!
//! # Declared limits
//!
//! From `portalcast_format::limits`, derived there from the products computed here:
//! world coordinates within `±8192`, heights within `±8192` (differences ≤ 16384), eye-space
//! coordinates and wall lengths within 23171 (the world's diagonal), near plane at depth 1,
//! texture coordinates within 32767, screens of 120 or 240 columns and 80 or 160 rows with
//! focal lengths ≤ 120. Within them no operation of this module overflows.
//!
//! # Geometry and projection
//!
//! [`geometry`]: side of a line, segment contact and point in a convex polygon, exact with
//! 64-bit cross products. [`projection`]: eye space, near-plane clipping and the one column
//! rule (a wall spanning `[x0, x1)` owns column `c` iff `x0 ≤ c + ½ < x1`, decided by exact
//! integer comparison).

pub mod angle;
pub mod fixed;
pub mod geometry;
pub mod projection;
pub mod recip;
pub mod tables;

pub use angle::Angle;
pub use fixed::{div_round_nearest, Fx16_16, Fx24_8, Fx2_30};
pub use geometry::{
    cross, point_in_convex_polygon, segment_contact, segments_intersect, side_of_line, Containment,
    SegmentContact, Side, WorldPoint,
};
pub use projection::{
    clip_to_near_plane, ClippedSegment, ExactEyePoint, EyeFrame, EyePoint, Viewport, NEAR_DEPTH,
};
pub use recip::{
    quotient, recip_pow2, recip_pow2_exact, recip_small, recip_u64_with_bit_length,
    recip_with_bit_length, RECIP_SMALL_MAX,
};
