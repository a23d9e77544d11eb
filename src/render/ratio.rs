//! Division without a divide instruction for the renderer's per-column and per-span set-up:
//! the divisor is normalised to 32 bits and multiplied by its table-and-Newton reciprocal
//! ([`recip_pow2`], relative error ≤ 1e-9), so a quotient costs a few multiplies instead of a
//! 64-bit library divide. Host and GBA run this same code, so the twins stay identical.

use crate::math::recip_pow2;

/// Approximately `num / den`, rounded to nearest (ties away from zero). `den != 0`, `|num| < 2^62`.
/// Relative error below `2^-28` (the divisor keeps 32 significant bits, the reciprocal 29), plus
/// one unit from the rounding.
#[inline]
pub fn ratio(num: i64, den: i64) -> i64 {
    debug_assert!(den != 0, "ratio with a zero divisor");
    let negative = (num < 0) != (den < 0);
    let d = den.unsigned_abs();
    // Adding half the divisor first rounds to nearest instead of truncating.
    let n = num.unsigned_abs() + (d >> 1);
    // d = mantissa · 2^shift with the mantissa in [2^31, 2^32).
    let bits = 64 - d.leading_zeros() as i32;
    let shift = bits - 32;
    let mantissa = if shift >= 0 {
        (d >> shift) as u32
    } else {
        (d << -shift) as u32
    };
    // 2^61 / mantissa, in (2^29, 2^30].
    let reciprocal = u64::from(recip_pow2(mantissa, 61));
    // n / d = n · reciprocal / 2^(61 + shift); n is split in 32-bit halves so no product
    // exceeds 64 bits.
    let total_shift = 61 + shift;
    let low = (n & 0xffff_ffff) * reciprocal;
    let high = (n >> 32) * reciprocal;
    let quotient = if total_shift >= 32 {
        (high >> (total_shift - 32)) + (low >> total_shift.min(63))
    } else {
        (high << (32 - total_shift)) + (low >> total_shift)
    };
    let quotient = quotient as i64;
    if negative {
        -quotient
    } else {
        quotient
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(5000))]
        #[test]
        fn within_the_documented_error_of_the_exact_quotient(num in -(1i64 << 61)..(1i64 << 61), den in prop_oneof![1i64..1000, -(1i64 << 40)..(1i64 << 40)]) {
            prop_assume!(den != 0);
            let exact = (num as f64 / den as f64).round() as i64;
            let approximate = ratio(num, den);
            let bound = (exact.unsigned_abs() >> 28) + 2;
            prop_assert!(approximate.abs_diff(exact) <= bound, "{num}/{den}: {approximate} vs {exact}");
        }
    }

    #[test]
    fn small_and_extreme_cases() {
        assert_eq!(ratio(0, 7), 0);
        assert_eq!(ratio(7, 1), 7);
        assert_eq!(ratio(-9, 3), -3);
        assert!((ratio(1 << 61, 3) - (1 << 61) / 3).abs() <= (1 << 32));
    }
}
