//! Reciprocals without a divide instruction.
//!
//! The ARM7TDMI has neither a divide nor a count-leading-zeros instruction, so:
//!
//! - [`recip_pow2`] (and the typed [`Fx24_8::recip_fx2_30`], [`Fx2_30::recip_fx24_8`]): the
//!   general reciprocal, for `1/z'` per wall end or per column and `z' = 1/(1/z')` per column.
//!   The divisor is normalised into `[2^31, 2^32)` by five compare-and-shift steps (16, 8, 4, 2,
//!   1 bits), its top 10 mantissa bits index a 1024-entry `u16` seed table (2 KB), and one
//!   second-order Newton step `r ← r·(1 + δ + δ²)`, `δ = 1 − m·r`, refines the seed using five
//!   32-bit multiplies. The step cubes the seed's relative error (`|δ| < 2^-10.9` by
//!   construction, so `δ³ < 1.3e-10`) and the truncations of the 32-bit arithmetic add a few
//!   units of `2^-31`: the relative error before the final rounding is **at most `1e-9`**
//!   (measured over all 2^31 mantissas: `9.4e-10`, by the ignored test `scan_every_mantissa` in
//!   `tests/math_recip.rs`); the result is then rounded to nearest, adding at most ½ ulp.
//! - [`recip_small`]: `1/n` for small integers (`1 ≤ n < 512`: column counts of DDA steps up to
//!   240, doubled row offsets `2·|row − horizon| + 1` up to 321) from a 2.30 table (2 KB),
//!   rounded to nearest: absolute error `≤ 2^-31`, relative `≤ n·2^-31 ≤ 2.4e-7`.
//! - [`recip_pow2_exact`], [`Fx24_8::recip_fx2_30_exact`], [`Fx2_30::recip_fx24_8_exact`]: the
//!   exact-division reference path (a 64-bit library divide on the GBA), correctly rounded. The
//!   approximate and exact paths take the same arguments so they can be benchmarked side by
//!   side (and against the BIOS `Div` call) in the ROM.

use super::fixed::{div_round_nearest, Fx16_16, Fx24_8, Fx2_30};
use super::tables::{RECIP_SEED_BITS, RECIP_SEED_U16, RECIP_SMALL_FX2_30, RECIP_SMALL_LEN};

/// Largest `n` accepted by [`recip_small`].
pub const RECIP_SMALL_MAX: u32 = RECIP_SMALL_LEN as u32 - 1;

/// Normalises `n > 0`: returns `(m, s)` with `m = n · 2^s` in `[2^31, 2^32)`.
#[inline]
const fn normalise(n: u32) -> (u32, u32) {
    let mut mantissa = n;
    let mut shift = 0;
    if mantissa < 1 << 16 {
        mantissa <<= 16;
        shift += 16;
    }
    if mantissa < 1 << 24 {
        mantissa <<= 8;
        shift += 8;
    }
    if mantissa < 1 << 28 {
        mantissa <<= 4;
        shift += 4;
    }
    if mantissa < 1 << 30 {
        mantissa <<= 2;
        shift += 2;
    }
    if mantissa < 1 << 31 {
        mantissa <<= 1;
        shift += 1;
    }
    (mantissa, shift)
}

/// `2^31 / M` for the normalised mantissa `m = M · 2^31` (`M` in `[1, 2)`), in `(2^30, 2^31)`.
///
/// Seed `r ≈ 1/M` from the table with `δ = 1 − M·r`, `|δ| < 2^-10.9`; then the second-order
/// Newton step `r·(1 + δ + δ²)`, whose relative error is `δ³ < 2^-32.8`. All products are
/// 32-bit; their truncations add a few units of `2^-31`.
#[inline]
const fn mantissa_reciprocal(mantissa: u32) -> u32 {
    let index = ((mantissa >> (31 - RECIP_SEED_BITS)) & ((1 << RECIP_SEED_BITS) - 1)) as usize;
    // ≈ 2^16 / M, in (2^15, 2^16).
    let seed = RECIP_SEED_U16[index] as u32;
    // m·seed / 2^16 ≈ 2^31 · (1 − δ), split so that every product fits 32 bits.
    let high = mantissa >> 16;
    let low = mantissa & 0xFFFF;
    let product = high * seed + ((low * seed) >> 16);
    // δ · 2^31: the product is within 2^21 of 2^31, so the modular difference is the signed δ.
    let delta = (1u32 << 31).wrapping_sub(product) as i32;
    // δ² · 2^31 from δ/32 (|δ/32| < 2^15.1, so the square fits).
    let delta_over_32 = delta >> 5;
    let delta_squared = (delta_over_32 * delta_over_32) >> 21;
    // (δ + δ²) · 2^31.
    let series = delta + delta_squared;
    // seed · (δ + δ²) in units of 2^-31, the factor split in 8-bit halves to stay in i32.
    let series_high = series >> 8;
    let series_low = series & 0xFF;
    let seed = seed as i32;
    let correction = (seed * series_high + ((seed * series_low) >> 8)) >> 8;
    ((seed as u32) << 15).wrapping_add_signed(correction)
}

/// Approximately `2^k / n`, rounded to nearest, without a divide.
///
/// Preconditions (checked in debug): `n > 0`, and the quotient fits i32: `2^k / n < 2^31`.
/// Error: `|result − 2^k/n| ≤ 1e-9 · 2^k/n + ½`.
#[inline]
#[track_caller]
pub const fn recip_pow2(n: u32, k: u32) -> u32 {
    debug_assert!(n > 0, "reciprocal of zero");
    debug_assert!(
        k <= 62 && (n as u64) << 31 > (1u64 << k),
        "reciprocal overflows i32"
    );
    let (mantissa, shift) = normalise(n);
    let reciprocal = mantissa_reciprocal(mantissa);
    // 2^k / n = (reciprocal / 2^31) · 2^(k − 31 + shift), so shift right by 62 − k − shift.
    let right = 62 - (k + shift) as i32;
    if right > 32 {
        // The quotient is below ¼ (the mantissa reciprocal is below 2^31): it rounds to 0.
        0
    } else if right > 0 {
        // Round to nearest: keep one extra bit, add one, drop it.
        ((reciprocal >> (right - 1)) + 1) >> 1
    } else {
        reciprocal << -right
    }
}

/// `n`'s bit length less one, `p` (`2^p ≤ n < 2^(p+1)`), and `2^(30+p) / n`, in `(2^29, 2^30]`:
/// [`recip_pow2`]`(n, 30 + p)`, the same value, from one normalisation where counting the
/// leading zeros first took a library call (the ARM7TDMI has no `CLZ`) and a second one.
#[inline]
#[track_caller]
pub const fn recip_with_bit_length(n: u32) -> (u32, u32) {
    debug_assert!(n > 0, "reciprocal of zero");
    let (mantissa, shift) = normalise(n);
    // recip_pow2's rounding with its right shift by 62 − (30 + p) − shift = 1.
    ((mantissa_reciprocal(mantissa) + 1) >> 1, 31 - shift)
}

/// [`recip_with_bit_length`] of a 64-bit `n`: its bit length less one, `p`, and about
/// `2^(30+p) / n`, in `(2^29, 2^30]`, from its top 32 bits (relative error `≤ 2^-31` more).
/// Out of line: its one caller takes it once per portal middle, from code in VRAM that has no
/// room for a copy.
#[inline(never)]
#[track_caller]
pub const fn recip_u64_with_bit_length(n: u64) -> (u32, u32) {
    let high = (n >> 32) as u32;
    if high == 0 {
        return recip_with_bit_length(n as u32);
    }
    let (_, shift) = normalise(high);
    // The top 32 bits: bit 31 set, so the reciprocal is 2^61 over them.
    let (reciprocal, _) = recip_with_bit_length(((n << shift) >> 32) as u32);
    (reciprocal, 63 - shift)
}

/// `2^k / n` correctly rounded (ties toward +∞), through the integer divide: the reference path.
/// Same preconditions as [`recip_pow2`].
#[inline]
#[track_caller]
pub const fn recip_pow2_exact(n: u32, k: u32) -> u32 {
    debug_assert!(n > 0, "reciprocal of zero");
    debug_assert!(
        k <= 62 && (n as u64) << 31 > (1u64 << k),
        "reciprocal overflows i32"
    );
    div_round_nearest(1i64 << k, n as i64) as u32
}

/// `1 / n` in 2.30 for `1 ≤ n ≤ RECIP_SMALL_MAX` (511), from the table: error `≤ 2^-31`.
///
/// `n = 0` gives `Fx2_30::MAX` (saturated), and panics in debug.
#[inline]
#[track_caller]
pub const fn recip_small(n: u32) -> Fx2_30 {
    debug_assert!(n != 0, "reciprocal of zero");
    Fx2_30::from_bits(RECIP_SMALL_FX2_30[n as usize])
}

/// `n / d`, the integer quotient, for `d ≥ 1`. Up to `RECIP_SMALL_MAX` (511) with no divide
/// (the ARM7TDMI has none; the library's costs about 450 cycles): the product with
/// [`recip_small`] lands within 3 of the quotient (the table's `2^-31` over `n < 2^32`, and the
/// floor), and the steps below make it exact. A larger `d` takes the library's divide.
#[inline]
#[track_caller]
pub const fn quotient(n: u32, d: u32) -> u32 {
    if d > RECIP_SMALL_MAX {
        return n / d;
    }
    let mut quotient = ((n as u64 * recip_small(d).to_bits() as u64) >> 30) as u32;
    while quotient as u64 * d as u64 > n as u64 {
        quotient -= 1;
    }
    while (quotient as u64 + 1) * d as u64 <= n as u64 {
        quotient += 1;
    }
    quotient
}

impl Fx24_8 {
    /// `1 / self` in 2.30, for a depth `self > ½` (the near plane is 1): relative error
    /// `≤ 1e-9`, plus ½ ulp of 2.30 (so at most 1.6 ulp at depth 1, ½ ulp beyond depth 2).
    /// Panics in debug outside the domain.
    #[inline]
    #[track_caller]
    pub const fn recip_fx2_30(self) -> Fx2_30 {
        debug_assert!(self.to_bits() > 128, "1/z' needs z' > 1/2");
        // (2^30 · 2^8) / bits: 2^30 for the result's scale, 2^8 for the argument's.
        Fx2_30::from_bits(recip_pow2(self.to_bits() as u32, 38) as i32)
    }

    /// `1 / self` in 2.30, correctly rounded, through the integer divide (reference path).
    #[inline]
    #[track_caller]
    pub const fn recip_fx2_30_exact(self) -> Fx2_30 {
        debug_assert!(self.to_bits() > 128, "1/z' needs z' > 1/2");
        Fx2_30::from_bits(recip_pow2_exact(self.to_bits() as u32, 38) as i32)
    }
}

impl Fx2_30 {
    /// `1 / self` in 24.8, for an inverse depth `self > 2^-23` (128 ulps): relative error
    /// `≤ 1e-9`, plus ½ ulp of 24.8. Panics in debug outside the domain.
    #[inline]
    #[track_caller]
    pub const fn recip_fx24_8(self) -> Fx24_8 {
        debug_assert!(self.to_bits() > 128, "1/w needs w > 2^-23");
        Fx24_8::from_bits(recip_pow2(self.to_bits() as u32, 38) as i32)
    }

    /// `1 / self` in 24.8, correctly rounded, through the integer divide (reference path).
    #[inline]
    #[track_caller]
    pub const fn recip_fx24_8_exact(self) -> Fx24_8 {
        debug_assert!(self.to_bits() > 128, "1/w needs w > 2^-23");
        Fx24_8::from_bits(recip_pow2_exact(self.to_bits() as u32, 38) as i32)
    }
}

impl Fx16_16 {
    /// `self / n` for `1 ≤ n ≤ 511` (a DDA step over `n` columns), through [`recip_small`]:
    /// error `≤ ½ ulp + |self|·2^-31 ≤ 1.5 ulp`.
    #[inline]
    #[track_caller]
    pub const fn div_small(self, n: u32) -> Fx16_16 {
        self.mul_fx2_30(recip_small(n))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recip_with_bit_length_is_recip_pow2_at_the_bit_length() {
        // Every power of two and its neighbours, and a spread of values between.
        let spread = (0..=31u32)
            .flat_map(|bit| {
                let power = 1u32 << bit;
                [power - 1, power, power + 1, power | (power >> 1)]
            })
            .chain((1..20_000u32).map(|i| i.wrapping_mul(2_654_435_761) | 1));
        for n in spread.filter(|&n| n > 0) {
            let p = 31 - n.leading_zeros();
            assert_eq!(
                recip_with_bit_length(n),
                (recip_pow2(n, 30 + p), p),
                "n {n}"
            );
        }
    }

    #[test]
    fn recip_u64_with_bit_length_is_within_its_bound_of_the_exact_quotient() {
        let spread = (0..=63u32)
            .flat_map(|bit| {
                let power = 1u64 << bit;
                [
                    power - 1,
                    power,
                    power + 1,
                    power | (power >> 1),
                    power | (power - 1),
                ]
            })
            .chain((1..20_000u64).map(|i| i.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> (i % 40)));
        for n in spread.filter(|&n| n > 0) {
            let (reciprocal, p) = recip_u64_with_bit_length(n);
            assert_eq!(p, 63 - n.leading_zeros(), "n {n}");
            let exact = (1u128 << (30 + p)) as f64 / n as f64;
            assert!(
                (f64::from(reciprocal) - exact).abs() <= exact * 2.0f64.powi(-30) + 1.0,
                "n {n}: {reciprocal} against {exact}"
            );
            if n >> 32 == 0 {
                assert_eq!((reciprocal, p), recip_with_bit_length(n as u32), "n {n}");
            }
        }
    }

    #[test]
    fn normalise_puts_the_top_bit_at_31() {
        for n in [1u32, 2, 3, 255, 256, 65535, 65536, 1 << 30, u32::MAX] {
            let (mantissa, shift) = normalise(n);
            assert!(mantissa >= 1 << 31, "n {n}");
            assert_eq!(mantissa >> shift, n);
        }
    }

    #[test]
    fn powers_of_two_are_nearly_exact() {
        // M = 1 exactly sits in the first seed cell, where the error is largest on one side.
        assert_eq!(recip_pow2(256, 38), 1 << 30);
        assert_eq!(recip_pow2(1 << 20, 38), 1 << 18);
    }
}
