//! The fixed-point formats: [`Fx24_8`], [`Fx16_16`], [`Fx2_30`].
//!
//! Each is a `#[repr(transparent)]` `i32` whose name states integer and fractional bits. The API
//! follows the `fixed` crate's conventions (`from_bits`/`to_bits`, `checked_`/`saturating_`/
//! `wrapping_` variants, `DELTA` for one unit in the last place) with integer-only conversions.
//!
//! Rounding: every product and every precision-narrowing conversion rounds to nearest with ties
//! toward +∞ (`(v + half) >> shift`), so its error is at most ½ ulp of the result. Plain
//! operators and the unprefixed methods panic on overflow in debug builds and wrap in release
//! (the ROM's profile), exactly like Rust's integers.

use core::fmt;
use core::ops::{Add, AddAssign, Neg, Sub, SubAssign};

/// Rounds `value / 2^shift` to nearest, ties toward +∞. `shift` must be at least 1.
#[inline]
const fn round_shift_i64(value: i64, shift: u32) -> i64 {
    (value + (1i64 << (shift - 1))) >> shift
}

/// Narrows an i64 that the caller's range analysis keeps inside i32; panics in debug otherwise.
#[inline]
#[track_caller]
const fn narrow(value: i64) -> i32 {
    debug_assert!(
        value >= i32::MIN as i64 && value <= i32::MAX as i64,
        "fixed-point overflow"
    );
    value as i32
}

#[inline]
const fn saturate(value: i64) -> i32 {
    if value > i32::MAX as i64 {
        i32::MAX
    } else if value < i32::MIN as i64 {
        i32::MIN
    } else {
        value as i32
    }
}

#[inline]
const fn checked_narrow(value: i64) -> Option<i32> {
    if value >= i32::MIN as i64 && value <= i32::MAX as i64 {
        Some(value as i32)
    } else {
        None
    }
}

/// Writes `bits / 2^frac_bits` as an exact decimal (every binary fraction has one).
fn write_exact_decimal(f: &mut fmt::Formatter<'_>, bits: i32, frac_bits: u32) -> fmt::Result {
    let magnitude = (bits as i64).unsigned_abs();
    let mask = (1u64 << frac_bits) - 1;
    if bits < 0 {
        f.write_str("-")?;
    }
    write!(f, "{}", magnitude >> frac_bits)?;
    let mut fraction = magnitude & mask;
    if fraction != 0 {
        f.write_str(".")?;
        while fraction != 0 {
            fraction *= 10;
            write!(f, "{}", fraction >> frac_bits)?;
            fraction &= mask;
        }
    }
    Ok(())
}

macro_rules! fixed_format {
    ($(#[$doc:meta])* $Name:ident, $frac:expr) => {
        $(#[$doc])*
        #[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
        #[repr(transparent)]
        pub struct $Name(i32);

        impl $Name {
            /// Number of fractional bits.
            pub const FRAC_BITS: u32 = $frac;
            /// Number of integer bits, sign included.
            pub const INT_BITS: u32 = 32 - $frac;
            /// Zero.
            pub const ZERO: Self = Self(0);
            /// One unit in the last place: the resolution.
            pub const DELTA: Self = Self(1);
            /// One.
            pub const ONE: Self = Self(1 << $frac);
            /// One half.
            pub const HALF: Self = Self(1 << ($frac - 1));
            /// Smallest value.
            pub const MIN: Self = Self(i32::MIN);
            /// Largest value.
            pub const MAX: Self = Self(i32::MAX);

            const FRAC_MASK: i32 = (1 << $frac) - 1;

            /// The value whose representation is `bits` (`bits / 2^FRAC_BITS`).
            #[inline]
            pub const fn from_bits(bits: i32) -> Self {
                Self(bits)
            }

            /// The representation: the value times `2^FRAC_BITS`.
            #[inline]
            pub const fn to_bits(self) -> i32 {
                self.0
            }

            /// The integer `n`, exactly. Panics in debug if it does not fit.
            #[inline]
            #[track_caller]
            pub const fn from_int(n: i32) -> Self {
                Self(n * (1 << $frac))
            }

            /// The integer `n`, or `None` if it does not fit.
            #[inline]
            pub const fn checked_from_int(n: i32) -> Option<Self> {
                match n.checked_mul(1 << $frac) {
                    Some(bits) => Some(Self(bits)),
                    None => None,
                }
            }

            /// The integer `n`, clamped to `[MIN, MAX]`.
            #[inline]
            pub const fn saturating_from_int(n: i32) -> Self {
                Self(n.saturating_mul(1 << $frac))
            }

            /// The largest integer `≤ self` (the `fixed` crate's `to_num` rounding).
            #[inline]
            pub const fn to_int_floor(self) -> i32 {
                self.0 >> $frac
            }

            /// The smallest integer `≥ self`.
            #[inline]
            pub const fn to_int_ceil(self) -> i32 {
                (self.0 >> $frac) + ((self.0 & Self::FRAC_MASK != 0) as i32)
            }

            /// The nearest integer, ties toward +∞.
            #[inline]
            pub const fn to_int_round(self) -> i32 {
                (self.0 >> $frac) + ((self.0 >> ($frac - 1)) & 1)
            }

            /// The first pixel whose centre is at or after this coordinate: the smallest integer
            /// `c` with `c + ½ ≥ self`, i.e. `ceil(self − ½)`. The pixel-ownership rule of the
            /// renderer: a span `[a, b)` owns pixels `first_pixel_at_or_after(a) ..
            /// first_pixel_at_or_after(b)`, so spans sharing an end share the boundary pixel
            /// index and no pixel is owned twice or by none.
            #[inline]
            pub const fn first_pixel_at_or_after(self) -> i32 {
                // (frac + half − 1) >> F is 1 exactly when frac > half, without overflow.
                (self.0 >> $frac) + (((self.0 & Self::FRAC_MASK) + (1 << ($frac - 1)) - 1) >> $frac)
            }

            /// The fractional part, in `[0, 1)`.
            #[inline]
            pub const fn frac(self) -> Self {
                Self(self.0 & Self::FRAC_MASK)
            }

            /// Absolute value. Panics in debug for `MIN`.
            #[inline]
            #[track_caller]
            pub const fn abs(self) -> Self {
                Self(self.0.abs())
            }

            /// `-1`, `0` or `1` as the sign of the value.
            #[inline]
            pub const fn signum(self) -> i32 {
                self.0.signum()
            }

            /// Sum, or `None` on overflow.
            #[inline]
            pub const fn checked_add(self, rhs: Self) -> Option<Self> {
                match self.0.checked_add(rhs.0) {
                    Some(bits) => Some(Self(bits)),
                    None => None,
                }
            }

            /// Sum clamped to `[MIN, MAX]`.
            #[inline]
            pub const fn saturating_add(self, rhs: Self) -> Self {
                Self(self.0.saturating_add(rhs.0))
            }

            /// Sum modulo `2^INT_BITS` (for coordinates that only matter modulo a power of two).
            #[inline]
            pub const fn wrapping_add(self, rhs: Self) -> Self {
                Self(self.0.wrapping_add(rhs.0))
            }

            /// Difference, or `None` on overflow.
            #[inline]
            pub const fn checked_sub(self, rhs: Self) -> Option<Self> {
                match self.0.checked_sub(rhs.0) {
                    Some(bits) => Some(Self(bits)),
                    None => None,
                }
            }

            /// Difference clamped to `[MIN, MAX]`.
            #[inline]
            pub const fn saturating_sub(self, rhs: Self) -> Self {
                Self(self.0.saturating_sub(rhs.0))
            }

            /// Difference modulo `2^INT_BITS`.
            #[inline]
            pub const fn wrapping_sub(self, rhs: Self) -> Self {
                Self(self.0.wrapping_sub(rhs.0))
            }

            /// `self · n`, exact. Panics in debug on overflow.
            #[inline]
            #[track_caller]
            pub const fn mul_int(self, n: i32) -> Self {
                Self(self.0 * n)
            }

            /// `self · n`, or `None` on overflow.
            #[inline]
            pub const fn checked_mul_int(self, n: i32) -> Option<Self> {
                match self.0.checked_mul(n) {
                    Some(bits) => Some(Self(bits)),
                    None => None,
                }
            }

            /// `self · n` clamped to `[MIN, MAX]`.
            #[inline]
            pub const fn saturating_mul_int(self, n: i32) -> Self {
                Self(self.0.saturating_mul(n))
            }

            /// `self · n` modulo `2^INT_BITS`.
            #[inline]
            pub const fn wrapping_mul_int(self, n: i32) -> Self {
                Self(self.0.wrapping_mul(n))
            }

            /// Product in the same format, rounded to nearest (error ≤ ½ ulp). Uses one
            /// 32×32→64 multiply. Panics in debug on overflow.
            #[inline]
            #[track_caller]
            pub const fn mul(self, rhs: Self) -> Self {
                Self(narrow(round_shift_i64(self.0 as i64 * rhs.0 as i64, $frac)))
            }

            /// Product in the same format, or `None` on overflow.
            #[inline]
            pub const fn checked_mul(self, rhs: Self) -> Option<Self> {
                match checked_narrow(round_shift_i64(self.0 as i64 * rhs.0 as i64, $frac)) {
                    Some(bits) => Some(Self(bits)),
                    None => None,
                }
            }

            /// Product in the same format, clamped to `[MIN, MAX]`.
            #[inline]
            pub const fn saturating_mul(self, rhs: Self) -> Self {
                Self(saturate(round_shift_i64(self.0 as i64 * rhs.0 as i64, $frac)))
            }

            /// Exact-division reference path: `self / n` rounded to nearest (ties toward +∞),
            /// through the integer divide (a library call on the ARM7TDMI). `n > 0`.
            #[inline]
            #[track_caller]
            pub const fn div_int_round(self, n: i32) -> Self {
                debug_assert!(n > 0, "divisor must be positive");
                Self(div_round_nearest(self.0 as i64, n as i64) as i32)
            }
        }

        impl Add for $Name {
            type Output = Self;
            #[inline]
            #[track_caller]
            fn add(self, rhs: Self) -> Self {
                Self(self.0 + rhs.0)
            }
        }

        impl Sub for $Name {
            type Output = Self;
            #[inline]
            #[track_caller]
            fn sub(self, rhs: Self) -> Self {
                Self(self.0 - rhs.0)
            }
        }

        impl Neg for $Name {
            type Output = Self;
            #[inline]
            #[track_caller]
            fn neg(self) -> Self {
                Self(-self.0)
            }
        }

        impl AddAssign for $Name {
            #[inline]
            #[track_caller]
            fn add_assign(&mut self, rhs: Self) {
                self.0 += rhs.0;
            }
        }

        impl SubAssign for $Name {
            #[inline]
            #[track_caller]
            fn sub_assign(&mut self, rhs: Self) {
                self.0 -= rhs.0;
            }
        }

        impl fmt::Debug for $Name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(concat!(stringify!($Name), "("))?;
                write_exact_decimal(f, self.0, $frac)?;
                f.write_str(")")
            }
        }

        impl fmt::Display for $Name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write_exact_decimal(f, self.0, $frac)
            }
        }
    };
}

fixed_format!(
    /// 24.8 fixed point: world positions, heights, eye-space coordinates, screen positions.
    ///
    /// Range `[-2^23, 2^23)` (±8 388 608), resolution `1/256` (0.00390625). The declared limits
    /// keep world coordinates within ±8192 and eye-space coordinates within ±23171, so sums
    /// and differences of positions never overflow.
    Fx24_8,
    8
);

fixed_format!(
    /// 16.16 fixed point: texture coordinates and their steps, slopes, sin/cos.
    ///
    /// Range `[-32768, 32768)`, resolution `1/65536` (1.53e-5). Texture coordinates that only
    /// matter modulo a power-of-two texture size use the `wrapping_` operations on purpose.
    Fx16_16,
    16
);

fixed_format!(
    /// 2.30 fixed point: inverse depth `1/z'`, unit-range reciprocals and wall parameters `t`.
    ///
    /// Range `[-2, 2)`, resolution `2^-30` (9.3e-10). With the near plane at depth 1, `1/z'` is
    /// in `(0, 1]`; at the far limit (23171 units) it is still 46341 ulps, a relative resolution
    /// of 2.2e-5.
    Fx2_30,
    30
);

/// Flips the signs of a fraction so that its denominator is positive.
#[inline]
#[track_caller]
const fn positive_denominator(num: i64, den: i64) -> (i64, i64) {
    debug_assert!(den != 0, "division by zero");
    if den < 0 {
        (-num, -den)
    } else {
        (num, den)
    }
}

/// `num / den` rounded to nearest, ties toward +∞; `den > 0`. The exact-division reference.
#[inline]
pub const fn div_round_nearest(num: i64, den: i64) -> i64 {
    // floor(num / den), plus one when the remainder is at least half the divisor.
    let quotient = num.div_euclid(den);
    let remainder = num.rem_euclid(den);
    if remainder >= den - remainder {
        quotient + 1
    } else {
        quotient
    }
}

impl Fx24_8 {
    /// `self · rhs` with a 16.16 factor (a sine, a scale), result in 24.8, rounded to nearest.
    /// Panics in debug on overflow.
    #[inline]
    #[track_caller]
    pub const fn mul_fx16_16(self, rhs: Fx16_16) -> Fx24_8 {
        Fx24_8(narrow(round_shift_i64(self.0 as i64 * rhs.0 as i64, 16)))
    }

    /// `self · rhs` with a 2.30 factor (an inverse depth, a small reciprocal, a parameter `t`),
    /// result in 24.8, rounded to nearest. Panics in debug on overflow.
    #[inline]
    #[track_caller]
    pub const fn mul_fx2_30(self, rhs: Fx2_30) -> Fx24_8 {
        Fx24_8(narrow(round_shift_i64(self.0 as i64 * rhs.0 as i64, 30)))
    }

    /// `self · rhs` with a 2.30 factor, result in 24.8, clamped to `[MIN, MAX]`.
    #[inline]
    pub const fn saturating_mul_fx2_30(self, rhs: Fx2_30) -> Fx24_8 {
        Fx24_8(saturate(round_shift_i64(self.0 as i64 * rhs.0 as i64, 30)))
    }

    /// `a·fa + b·fb` with 16.16 factors (a rotation row: `x' = −dx·sin + dy·cos`), result in
    /// 24.8 with a single rounding to nearest (error ≤ ½ ulp). Two 32×32→64 multiplies.
    /// Panics in debug on overflow.
    #[inline]
    #[track_caller]
    pub const fn dot_fx16_16(a: Fx24_8, fa: Fx16_16, b: Fx24_8, fb: Fx16_16) -> Fx24_8 {
        Fx24_8::from_product_fx16_16(Fx24_8::dot_fx16_16_unrounded(a, fa, b, fb))
    }

    /// [`dot_fx16_16`](Self::dot_fx16_16) before its rounding: `a·fa + b·fb` exactly, in
    /// 2^-24 units (a 40.24 value in an i64; within the declared world it stays under 2^40).
    #[inline]
    pub const fn dot_fx16_16_unrounded(a: Fx24_8, fa: Fx16_16, b: Fx24_8, fb: Fx16_16) -> i64 {
        a.0 as i64 * fa.0 as i64 + b.0 as i64 * fb.0 as i64
    }

    /// A product of 24.8 and 16.16 values in 2^-24 units (as
    /// [`dot_fx16_16_unrounded`](Self::dot_fx16_16_unrounded) gives it) rounded to 24.8, to
    /// nearest as [`dot_fx16_16`](Self::dot_fx16_16) rounds.
    #[inline]
    #[track_caller]
    pub const fn from_product_fx16_16(product: i64) -> Fx24_8 {
        Fx24_8(narrow(round_shift_i64(product, 16)))
    }

    /// `self · rhs` with a 2.30 factor, result in 16.16 (8 more fractional bits than
    /// [`mul_fx2_30`](Self::mul_fx2_30)), rounded to nearest and clamped to
    /// `[Fx16_16::MIN, Fx16_16::MAX]`: for screen positions that may lie far off screen.
    #[inline]
    pub const fn saturating_mul_fx2_30_as_fx16_16(self, rhs: Fx2_30) -> Fx16_16 {
        Fx16_16(saturate(round_shift_i64(self.0 as i64 * rhs.0 as i64, 22)))
    }

    /// Exact-division path: `self / den` as a 16.16 ratio, correctly rounded (ties toward +∞)
    /// and clamped to the 16.16 range. One 64-bit divide. `den ≠ 0`.
    #[inline]
    #[track_caller]
    pub const fn saturating_ratio_fx16_16(self, den: Fx24_8) -> Fx16_16 {
        let (num, den) = positive_denominator((self.0 as i64) << 16, den.0 as i64);
        Fx16_16(saturate(div_round_nearest(num, den)))
    }

    /// Exact-division path: `self / den` as a 2.30 ratio (a parameter `t`), correctly rounded.
    /// One 64-bit divide. `den ≠ 0`; panics in debug if `|self / den| ≥ 2`.
    #[inline]
    #[track_caller]
    pub const fn ratio_fx2_30(self, den: Fx24_8) -> Fx2_30 {
        let (num, den) = positive_denominator((self.0 as i64) << 30, den.0 as i64);
        Fx2_30(narrow(div_round_nearest(num, den)))
    }

    /// Exact-division path: `self · num / den`, correctly rounded to 24.8, with the product
    /// held in 64 bits. One 64-bit divide. `den ≠ 0`; panics in debug on overflow.
    #[inline]
    #[track_caller]
    pub const fn mul_ratio(self, num: Fx24_8, den: Fx24_8) -> Fx24_8 {
        let (num, den) = positive_denominator(self.0 as i64 * num.0 as i64, den.0 as i64);
        Fx24_8(narrow(div_round_nearest(num, den)))
    }

    /// The same value in 16.16 (exact). Panics in debug if `|self| ≥ 32768`.
    #[inline]
    #[track_caller]
    pub const fn to_fx16_16(self) -> Fx16_16 {
        Fx16_16(self.0 * (1 << 8))
    }

    /// The same value in 16.16, or `None` if `|self| ≥ 32768`.
    #[inline]
    pub const fn checked_to_fx16_16(self) -> Option<Fx16_16> {
        match self.0.checked_mul(1 << 8) {
            Some(bits) => Some(Fx16_16(bits)),
            None => None,
        }
    }

    /// The same value in 16.16, clamped to `[Fx16_16::MIN, Fx16_16::MAX]`.
    #[inline]
    pub const fn saturating_to_fx16_16(self) -> Fx16_16 {
        Fx16_16(self.0.saturating_mul(1 << 8))
    }
}

impl Fx16_16 {
    /// `self · rhs` with a 2.30 factor (`u = t · length`, `u/z = u · (1/z)`, a DDA step
    /// `Δ · (1/n)`), result in 16.16, rounded to nearest. Panics in debug on overflow.
    #[inline]
    #[track_caller]
    pub const fn mul_fx2_30(self, rhs: Fx2_30) -> Fx16_16 {
        Fx16_16(narrow(round_shift_i64(self.0 as i64 * rhs.0 as i64, 30)))
    }

    /// `self · rhs` with a 2.30 factor, result in 16.16, clamped to `[MIN, MAX]`.
    #[inline]
    pub const fn saturating_mul_fx2_30(self, rhs: Fx2_30) -> Fx16_16 {
        Fx16_16(saturate(round_shift_i64(self.0 as i64 * rhs.0 as i64, 30)))
    }

    /// `self · rhs` with a 2.30 factor, result in 16.16 modulo 2^16 (texture coordinates).
    #[inline]
    pub const fn wrapping_mul_fx2_30(self, rhs: Fx2_30) -> Fx16_16 {
        Fx16_16(round_shift_i64(self.0 as i64 * rhs.0 as i64, 30) as i32)
    }

    /// The value in 24.8, rounded to nearest (error ≤ ½ ulp of 24.8). Never overflows.
    #[inline]
    pub const fn to_fx24_8_round(self) -> Fx24_8 {
        Fx24_8(round_shift_i64(self.0 as i64, 8) as i32)
    }

    /// The value in 24.8, rounded toward −∞. Never overflows.
    #[inline]
    pub const fn to_fx24_8_floor(self) -> Fx24_8 {
        Fx24_8(self.0 >> 8)
    }

    /// The value in 2.30 (exact). Panics in debug if `|self| ≥ 2`.
    #[inline]
    #[track_caller]
    pub const fn to_fx2_30(self) -> Fx2_30 {
        Fx2_30(self.0 * (1 << 14))
    }

    /// The value in 2.30, clamped to `[Fx2_30::MIN, Fx2_30::MAX]`.
    #[inline]
    pub const fn saturating_to_fx2_30(self) -> Fx2_30 {
        Fx2_30(self.0.saturating_mul(1 << 14))
    }
}

impl Fx2_30 {
    /// The value in 16.16, rounded to nearest (error ≤ ½ ulp of 16.16). Never overflows.
    #[inline]
    pub const fn to_fx16_16_round(self) -> Fx16_16 {
        Fx16_16(round_shift_i64(self.0 as i64, 14) as i32)
    }

    /// The value in 24.8, rounded to nearest. Never overflows.
    #[inline]
    pub const fn to_fx24_8_round(self) -> Fx24_8 {
        Fx24_8(round_shift_i64(self.0 as i64, 22) as i32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    extern crate std;
    use std::format;

    #[test]
    fn debug_prints_the_exact_value() {
        assert_eq!(format!("{:?}", Fx24_8::from_bits(-384)), "Fx24_8(-1.5)");
        assert_eq!(format!("{}", Fx24_8::DELTA), "0.00390625");
        assert_eq!(format!("{}", Fx2_30::ONE), "1");
        assert_eq!(format!("{}", Fx16_16::MIN), "-32768");
    }

    #[test]
    fn integer_roundings() {
        let x = Fx24_8::from_bits(-385); // -1.50390625
        assert_eq!(x.to_int_floor(), -2);
        assert_eq!(x.to_int_ceil(), -1);
        assert_eq!(x.to_int_round(), -2);
        assert_eq!(Fx24_8::from_bits(-384).to_int_round(), -1); // tie toward +∞
        assert_eq!(Fx24_8::from_bits(384).to_int_round(), 2);
    }

    #[test]
    fn first_pixel_at_or_after_is_ceil_of_minus_half() {
        let cases = [
            (0, 0),
            (128, 0),
            (129, 1),
            (127, 0),
            (256, 1),
            (-128, -1),
            (-129, -1),
            (-1, 0),
            (-127, 0),
        ];
        for (bits, column) in cases {
            assert_eq!(
                Fx24_8::from_bits(bits).first_pixel_at_or_after(),
                column,
                "bits {bits}"
            );
        }
        assert_eq!(Fx24_8::MAX.first_pixel_at_or_after(), 1 << 23);
        assert_eq!(Fx24_8::MIN.first_pixel_at_or_after(), -(1 << 23));
    }

    #[test]
    fn division_reference_rounds_to_nearest() {
        assert_eq!(div_round_nearest(7, 2), 4);
        assert_eq!(div_round_nearest(-7, 2), -3);
        assert_eq!(div_round_nearest(-8, 3), -3);
        assert_eq!(div_round_nearest(5, 3), 2);
    }
}
