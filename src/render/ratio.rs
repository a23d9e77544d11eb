//! Division without a divide instruction for the renderer's per-wall and per-span set-up: the
//! divisor is normalised to 32 significant bits and multiplied by its table-and-Newton reciprocal
//! ([`recip_pow2`], relative error ≤ 1e-9), so a quotient costs a few multiplies instead of a
//! 64-bit library divide. Host and GBA run this same code, so the twins stay identical.

use crate::math::recip_pow2;

/// Approximately `num · 2^shift / den`, rounded to nearest. `den != 0`, `|num| < 2^63`, and the
/// quotient must fit i64. Relative error below `2^-28` (the divisor keeps 32 significant bits,
/// its reciprocal 29), plus ½ from the rounding.
#[inline]
pub fn ratio_shifted(num: i64, shift: u32, den: i64) -> i64 {
    Divisor::new(den).ratio_shifted(num, shift)
}

/// A divisor normalised once, for several quotients by it ([`ratio_shifted`] is one): a wall's
/// stepper divides four values by the same scale.
#[derive(Clone, Copy, Debug)]
pub struct Divisor {
    /// `2^61 / mantissa`, in (2^29, 2^30], for the divisor's top 32 bits as the mantissa.
    reciprocal: u32,
    /// The divisor is about `mantissa · 2^exponent`.
    exponent: i32,
    negative: bool,
}

impl Divisor {
    /// `den != 0`. Out of line, as [`Divisor::ratio_shifted`]: IWRAM is short, and both are
    /// called per wall, not per column.
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".iwram.render_divisor_new")]
    pub fn new(den: i64) -> Divisor {
        debug_assert!(den != 0, "ratio with a zero divisor");
        let d = den.unsigned_abs();
        // d ≈ mantissa · 2^exponent with the mantissa in [2^31, 2^32).
        let exponent = 32 - leading_zeros(d) as i32;
        let mantissa = if exponent >= 0 {
            (d >> exponent) as u32
        } else {
            (d << -exponent) as u32
        };
        Divisor {
            reciprocal: recip_pow2(mantissa, 61),
            exponent,
            negative: den < 0,
        }
    }

    /// Approximately `num · 2^shift / self`, rounded to nearest: [`ratio_shifted`]'s result.
    #[inline(never)]
    #[cfg_attr(
        target_os = "none",
        link_section = ".iwram.render_divisor_ratio_shifted"
    )]
    pub fn ratio_shifted(&self, num: i64, shift: u32) -> i64 {
        let negative = (num < 0) != self.negative;
        // num · 2^shift / d = num · reciprocal / 2^(61 + exponent − shift). The product has at
        // most 63 + 30 bits: two 32-bit multiplies, `high · 2^32 + low`, where a 128-bit
        // product would take a library call's worth of multiplies and shifts.
        let magnitude = num.unsigned_abs();
        let reciprocal = u64::from(self.reciprocal);
        let low = u64::from(magnitude as u32) * reciprocal;
        let high = (magnitude >> 32) * reciprocal;
        let right = 61 + self.exponent - shift as i32;
        // The product shifted right by `right − 1` (its bits up to 64 past that: the quotient
        // fits i64), then rounded by its last bit.
        let quotient = if right > 32 {
            // `high + low / 2^32` is the product over 2^32 (below 2^62: no carry is lost).
            (((high + (low >> 32)) >> (right - 33)) + 1) >> 1
        } else if right > 0 {
            let kept = (right - 1) as u32;
            ((high << (32 - kept)).wrapping_add(low >> kept)).wrapping_add(1) >> 1
        } else {
            (high << 32).wrapping_add(low) << -right
        };
        let quotient = quotient as i64;
        if negative {
            -quotient
        } else {
            quotient
        }
    }
}

/// `d.leading_zeros()` for `d > 0`, by compare-and-shift steps on 32-bit halves: the ARM7TDMI
/// has no count-leading-zeros instruction, and the library's `__clzsi2` is a Thumb call.
#[inline(always)]
pub fn leading_zeros(d: u64) -> u32 {
    debug_assert!(d != 0, "leading zeros of zero");
    let high = (d >> 32) as u32;
    let (mut word, mut zeros) = if high != 0 { (high, 0) } else { (d as u32, 32) };
    if word < 1 << 16 {
        word <<= 16;
        zeros += 16;
    }
    if word < 1 << 24 {
        word <<= 8;
        zeros += 8;
    }
    if word < 1 << 28 {
        word <<= 4;
        zeros += 4;
    }
    if word < 1 << 30 {
        word <<= 2;
        zeros += 2;
    }
    if word < 1 << 31 {
        zeros += 1;
    }
    zeros
}

/// Approximately `num / den`, rounded to nearest; see [`ratio_shifted`].
#[inline]
pub fn ratio(num: i64, den: i64) -> i64 {
    ratio_shifted(num, 0, den)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(5000))]
        #[test]
        fn within_the_documented_error_of_the_exact_quotient(
            num in -(1i64 << 42)..(1i64 << 42),
            shift in 0u32..20,
            den in prop_oneof![1i64..1000, -(1i64 << 55)..(1i64 << 55)],
        ) {
            prop_assume!(den != 0);
            let exact = ((i128::from(num) << shift) as f64 / den as f64).round();
            prop_assume!(exact.abs() < 2f64.powi(62));
            let approximate = ratio_shifted(num, shift, den) as f64;
            let bound = exact.abs() / 2f64.powi(28) + 1.0;
            prop_assert!((approximate - exact).abs() <= bound, "{num}<<{shift}/{den}: {approximate} vs {exact}");
        }
    }

    /// The quotient as a 128-bit product would give it: what the two 32-bit products must
    /// reproduce bit for bit wherever the quotient fits i64.
    fn ratio_by_u128(divisor: &Divisor, num: i64, shift: u32) -> i64 {
        let product = u128::from(num.unsigned_abs()) * u128::from(divisor.reciprocal);
        let right = 61 + divisor.exponent - shift as i32;
        let quotient = if right > 0 {
            ((product >> (right - 1)) + 1) >> 1
        } else {
            product << -right
        } as i64;
        if (num < 0) != divisor.negative {
            -quotient
        } else {
            quotient
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig {
            cases: 20000,
            max_global_rejects: 1 << 20,
            ..ProptestConfig::default()
        })]
        #[test]
        fn two_32_bit_products_give_the_128_bit_product_s_quotient(
            num in prop_oneof![-(1i64 << 40)..(1i64 << 40), i64::MIN + 1..i64::MAX],
            shift in 0u32..64,
            den in prop_oneof![1i64..1000, -(1i64 << 62)..(1i64 << 62)],
        ) {
            prop_assume!(den != 0);
            let exact = (i128::from(num) << shift) as f64 / den as f64;
            prop_assume!(exact.abs() < 2f64.powi(62));
            let divisor = Divisor::new(den);
            prop_assert_eq!(divisor.ratio_shifted(num, shift), ratio_by_u128(&divisor, num, shift));
        }
    }

    proptest! {
        #[test]
        fn leading_zeros_is_the_library_count(d in 1u64.., shift in 0u32..64) {
            let d = (d >> shift).max(1);
            prop_assert_eq!(leading_zeros(d), d.leading_zeros());
        }
    }

    #[test]
    fn small_and_extreme_cases() {
        assert_eq!(ratio(0, 7), 0);
        assert_eq!(ratio(7, 1), 7);
        assert_eq!(ratio(-9, 3), -3);
        assert_eq!(ratio(7, 2), 4);
        assert!((ratio_shifted(3, 30, 3) - (1 << 30)).abs() <= 1);
        assert!((ratio(1 << 61, 3) - (1 << 61) / 3).abs() <= (1 << 34));
    }
}
