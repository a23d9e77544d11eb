//! Binary angles and their sine and cosine.
//!
//! A turn is 2^16 units; angle 0 looks along +x and angles grow toward +y (clockwise on the
//! top-down view, y down). Angles wrap by design, so `+` and `-` on [`Angle`] are modular.
//!
//! # Sine table and its error
//!
//! One quarter wave, `2^10 = 1024` segments (1025 entries of 2.30, 4100 bytes), linearly
//! interpolated on the low 4 bits of the 14-bit in-quadrant offset, then rounded to 16.16. The
//! other quadrants are mirrors, so `sin(−a) = −sin(a)`, `sin(a + ½ turn) = −sin(a)` and
//! `cos(a) = sin(a + ¼ turn)` hold exactly, and the results at multiples of 45° are exact table
//! entries (0, ±1, ±`46341/65536`).
//!
//! Error budget, against the true `sin(2π·a/65536)`:
//! - linear interpolation over a segment of `h = π/2048` rad: `≤ h²/8 = 2.94e-7` (0.019 ulp of
//!   16.16);
//! - table entries and the interpolation in 2.30: `≤ 2^-30` (0.00006 ulp);
//! - final rounding to 16.16: `≤ 2^-17` (0.5 ulp).
//!
//! Bound: **`|error| ≤ 7.93e-6` (0.52 ulp of 16.16)**; measured over all 65536 angles by
//! `tests/math_trig.rs`: 7.905e-6 (0.518 ulp). Why 16.16 is enough: an angular error `δ` in the
//! eye basis moves a point at distance `z'` by `z'·δ`, i.e. `d·δ` pixels on screen whatever the
//! distance: `120 · 7.93e-6 = 0.001` pixel.

use super::fixed::{Fx16_16, Fx2_30};
use super::tables::{SIN_QUARTER_FX2_30, SIN_QUARTER_LOG2_SEGMENTS};
use core::ops::{Add, AddAssign, Neg, Sub, SubAssign};

/// A binary angle: `u16`, 65536 units per turn, wrapping.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default, Debug)]
#[repr(transparent)]
pub struct Angle(u16);

/// Bits of the offset inside a quadrant (`2^14` units per quarter turn).
const QUADRANT_BITS: u32 = 14;
/// Low bits of the in-quadrant offset used as the interpolation weight.
const INTERPOLATION_BITS: u32 = QUADRANT_BITS - SIN_QUARTER_LOG2_SEGMENTS;

impl Angle {
    /// Units in a full turn.
    pub const UNITS_PER_TURN: u32 = 1 << 16;
    /// 0°, looking along +x.
    pub const ZERO: Angle = Angle(0);
    /// 45°.
    pub const EIGHTH: Angle = Angle(1 << 13);
    /// 90°, looking along +y.
    pub const QUARTER: Angle = Angle(1 << 14);
    /// 180°.
    pub const HALF: Angle = Angle(1 << 15);
    /// 270°.
    pub const THREE_QUARTERS: Angle = Angle(3 << 14);

    /// The angle of `bits` units.
    #[inline]
    pub const fn from_bits(bits: u16) -> Angle {
        Angle(bits)
    }

    /// The angle in units, in `0..65536`.
    #[inline]
    pub const fn to_bits(self) -> u16 {
        self.0
    }

    /// `degrees` rounded to the nearest unit (ties toward +∞), wrapped into one turn.
    /// Exact for multiples of 45/8192 of a degree, so for every multiple of 45°.
    #[inline]
    pub const fn from_degrees(degrees: i32) -> Angle {
        let units = (degrees as i64 * 65536 * 2 + 360).div_euclid(720);
        Angle(units as u16)
    }

    /// Sum modulo one turn.
    #[inline]
    pub const fn wrapping_add(self, rhs: Angle) -> Angle {
        Angle(self.0.wrapping_add(rhs.0))
    }

    /// Difference modulo one turn.
    #[inline]
    pub const fn wrapping_sub(self, rhs: Angle) -> Angle {
        Angle(self.0.wrapping_sub(rhs.0))
    }

    /// Sine, in 16.16; error ≤ 0.52 ulp (see the module docs).
    #[inline]
    pub const fn sin(self) -> Fx16_16 {
        let quadrant = self.0 >> QUADRANT_BITS;
        let offset = (self.0 & ((1 << QUADRANT_BITS) - 1)) as u32;
        // Quadrants 1 and 3 run the quarter wave backwards; 2 and 3 are negative.
        let offset = if quadrant & 1 == 0 {
            offset
        } else {
            (1 << QUADRANT_BITS) - offset
        };
        // Round the magnitude, then apply the sign, so that the sine stays exactly odd.
        let magnitude = Fx2_30::from_bits(quarter_sine_fx2_30(offset)).to_fx16_16_round();
        if quadrant >= 2 {
            Fx16_16::from_bits(-magnitude.to_bits())
        } else {
            magnitude
        }
    }

    /// Cosine, in 16.16: `sin(self + ¼ turn)`, so the same error bound.
    #[inline]
    pub const fn cos(self) -> Fx16_16 {
        self.wrapping_add(Angle::QUARTER).sin()
    }

    /// `(sin, cos)`.
    #[inline]
    pub const fn sin_cos(self) -> (Fx16_16, Fx16_16) {
        (self.sin(), self.cos())
    }
}

/// `sin(offset · 90° / 2^14)` in 2.30 for `offset` in `0..=2^14`, interpolated.
#[inline]
const fn quarter_sine_fx2_30(offset: u32) -> i32 {
    let index = (offset >> INTERPOLATION_BITS) as usize;
    let weight = (offset & ((1 << INTERPOLATION_BITS) - 1)) as i32;
    let low = SIN_QUARTER_FX2_30[index];
    if weight == 0 {
        // Also keeps the last entry (offset 2^14) from reading past the table.
        return low;
    }
    let high = SIN_QUARTER_FX2_30[index + 1];
    // |high − low| ≤ 2^30 · π/2048 < 2^21, times a weight < 2^4: no overflow in i32.
    low + (((high - low) * weight + (1 << (INTERPOLATION_BITS - 1))) >> INTERPOLATION_BITS)
}

impl Add for Angle {
    type Output = Angle;
    /// Modular: angles wrap by design.
    #[inline]
    fn add(self, rhs: Angle) -> Angle {
        self.wrapping_add(rhs)
    }
}

impl Sub for Angle {
    type Output = Angle;
    /// Modular: angles wrap by design.
    #[inline]
    fn sub(self, rhs: Angle) -> Angle {
        self.wrapping_sub(rhs)
    }
}

impl Neg for Angle {
    type Output = Angle;
    /// The opposite rotation, modulo one turn.
    #[inline]
    fn neg(self) -> Angle {
        Angle(self.0.wrapping_neg())
    }
}

impl AddAssign for Angle {
    #[inline]
    fn add_assign(&mut self, rhs: Angle) {
        *self = *self + rhs;
    }
}

impl SubAssign for Angle {
    #[inline]
    fn sub_assign(&mut self, rhs: Angle) {
        *self = *self - rhs;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cardinal_and_diagonal_values_are_exact() {
        let one = Fx16_16::ONE.to_bits();
        let diagonal = 46341; // round(65536 / √2)
        let expect = [
            (0, 0, one),
            (45, diagonal, diagonal),
            (90, one, 0),
            (135, diagonal, -diagonal),
            (180, 0, -one),
            (225, -diagonal, -diagonal),
            (270, -one, 0),
            (315, -diagonal, diagonal),
        ];
        for (degrees, sin, cos) in expect {
            let angle = Angle::from_degrees(degrees);
            assert_eq!(angle.sin().to_bits(), sin, "sin {degrees}°");
            assert_eq!(angle.cos().to_bits(), cos, "cos {degrees}°");
        }
    }

    #[test]
    fn trig_evaluates_at_compile_time() {
        const QUARTER_SINE: Fx16_16 = Angle::QUARTER.sin();
        const HALF_COSINE: Fx16_16 = Angle::HALF.cos();
        assert_eq!(QUARTER_SINE, Fx16_16::ONE);
        assert_eq!(HALF_COSINE, Fx16_16::from_int(-1));
    }

    #[test]
    fn degrees_wrap() {
        assert_eq!(Angle::from_degrees(-90), Angle::THREE_QUARTERS);
        assert_eq!(Angle::from_degrees(450), Angle::QUARTER);
        assert_eq!(Angle::from_degrees(360), Angle::ZERO);
    }
}
