//! The fixed-point formats against exact i128 arithmetic: every product and conversion is the
//! correctly rounded value (nearest, ties toward +∞), so its error is at most ½ ulp; the
//! checked, saturating and wrapping variants do what their names say at the extremes.

use portalcast::math::{div_round_nearest, Fx16_16, Fx24_8, Fx2_30};
use proptest::prelude::*;

/// `value / 2^shift` rounded to nearest, ties toward +∞, in i128.
fn round_shift(value: i128, shift: u32) -> i128 {
    (value + (1i128 << (shift - 1))) >> shift
}

/// Asserts `result_bits / 2^result_frac` is within ½ ulp of `exact / 2^exact_frac` and is the
/// value the documented rounding picks.
fn assert_rounded(result_bits: i32, exact: i128, exact_frac: u32, result_frac: u32) {
    let shift = exact_frac - result_frac;
    let twice_error = ((result_bits as i128) << (shift + 1)) - 2 * exact;
    assert!(
        twice_error.abs() <= 1i128 << shift,
        "error over ½ ulp: {result_bits} vs {exact}/2^{exact_frac}"
    );
    assert_eq!(result_bits as i128, round_shift(exact, shift));
}

fn in_i32(value: i128) -> bool {
    value >= i32::MIN as i128 && value <= i32::MAX as i128
}

const EXTREMES: [i32; 9] = [
    i32::MIN,
    i32::MIN + 1,
    -65536,
    -1,
    0,
    1,
    65536,
    i32::MAX - 1,
    i32::MAX,
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10000))]

    #[test]
    fn same_format_products_are_correctly_rounded(a in any::<i32>(), b in any::<i32>()) {
        let exact = a as i128 * b as i128;
        for (frac, result) in [
            (8, Fx24_8::from_bits(a).checked_mul(Fx24_8::from_bits(b)).map(Fx24_8::to_bits)),
            (16, Fx16_16::from_bits(a).checked_mul(Fx16_16::from_bits(b)).map(Fx16_16::to_bits)),
            (30, Fx2_30::from_bits(a).checked_mul(Fx2_30::from_bits(b)).map(Fx2_30::to_bits)),
        ] {
            let rounded = round_shift(exact, frac);
            match result {
                Some(bits) => assert_rounded(bits, exact, 2 * frac, frac),
                None => prop_assert!(!in_i32(rounded)),
            }
        }
        let saturated = Fx16_16::from_bits(a).saturating_mul(Fx16_16::from_bits(b)).to_bits();
        prop_assert_eq!(saturated as i128, round_shift(exact, 16).clamp(i32::MIN as i128, i32::MAX as i128));
    }

    #[test]
    fn mixed_products_name_their_format_and_round_once(a in any::<i32>(), b in any::<i32>()) {
        let exact = a as i128 * b as i128;
        // 24.8 × 16.16 → 24.8: the exact product has 24 fractional bits.
        let rounded = round_shift(exact, 16);
        if in_i32(rounded) {
            assert_rounded(Fx24_8::from_bits(a).mul_fx16_16(Fx16_16::from_bits(b)).to_bits(), exact, 24, 8);
        }
        // 24.8 × 2.30 → 24.8 and 16.16 × 2.30 → 16.16: shift by 30.
        let rounded = round_shift(exact, 30);
        let clamped = rounded.clamp(i32::MIN as i128, i32::MAX as i128);
        prop_assert_eq!(Fx24_8::from_bits(a).saturating_mul_fx2_30(Fx2_30::from_bits(b)).to_bits() as i128, clamped);
        prop_assert_eq!(Fx16_16::from_bits(a).saturating_mul_fx2_30(Fx2_30::from_bits(b)).to_bits() as i128, clamped);
        prop_assert_eq!(
            Fx16_16::from_bits(a).wrapping_mul_fx2_30(Fx2_30::from_bits(b)).to_bits(),
            rounded as i32
        );
        if in_i32(rounded) {
            assert_rounded(Fx24_8::from_bits(a).mul_fx2_30(Fx2_30::from_bits(b)).to_bits(), exact, 38, 8);
            assert_rounded(Fx16_16::from_bits(a).mul_fx2_30(Fx2_30::from_bits(b)).to_bits(), exact, 46, 16);
        }
        // 24.8 × 2.30 → 16.16, saturating (screen x far off screen).
        let rounded = round_shift(exact, 22).clamp(i32::MIN as i128, i32::MAX as i128);
        prop_assert_eq!(
            Fx24_8::from_bits(a).saturating_mul_fx2_30_as_fx16_16(Fx2_30::from_bits(b)).to_bits() as i128,
            rounded
        );
    }

    #[test]
    fn rotation_rows_round_once(
        a in -(1i32 << 22)..(1 << 22), fa in -65536i32..=65536,
        b in -(1i32 << 22)..(1 << 22), fb in -65536i32..=65536,
    ) {
        let exact = a as i128 * fa as i128 + b as i128 * fb as i128;
        let result = Fx24_8::dot_fx16_16(
            Fx24_8::from_bits(a), Fx16_16::from_bits(fa), Fx24_8::from_bits(b), Fx16_16::from_bits(fb),
        );
        assert_rounded(result.to_bits(), exact, 24, 8);
    }

    #[test]
    fn conversions_are_exact_or_rounded_to_nearest(bits in any::<i32>()) {
        let widened = bits as i128 * 256;
        match Fx24_8::from_bits(bits).checked_to_fx16_16() {
            Some(value) => prop_assert_eq!(value.to_bits() as i128, widened),
            None => prop_assert!(!in_i32(widened)),
        }
        prop_assert_eq!(
            Fx24_8::from_bits(bits).saturating_to_fx16_16().to_bits() as i128,
            widened.clamp(i32::MIN as i128, i32::MAX as i128)
        );
        assert_rounded(Fx16_16::from_bits(bits).to_fx24_8_round().to_bits(), bits as i128, 16, 8);
        prop_assert_eq!(Fx16_16::from_bits(bits).to_fx24_8_floor().to_bits(), bits.div_euclid(256));
        assert_rounded(Fx2_30::from_bits(bits).to_fx16_16_round().to_bits(), bits as i128, 30, 16);
        assert_rounded(Fx2_30::from_bits(bits).to_fx24_8_round().to_bits(), bits as i128, 30, 8);
        prop_assert_eq!(
            Fx16_16::from_bits(bits).saturating_to_fx2_30().to_bits() as i128,
            (bits as i128 * 16384).clamp(i32::MIN as i128, i32::MAX as i128)
        );
    }

    #[test]
    fn integer_roundings_match_the_definitions(bits in any::<i32>()) {
        let value = Fx24_8::from_bits(bits);
        prop_assert_eq!(value.to_int_floor(), bits.div_euclid(256));
        prop_assert_eq!(value.to_int_ceil() as i64, (bits as i64 + 255).div_euclid(256));
        prop_assert_eq!(value.to_int_round() as i64, (bits as i64 + 128).div_euclid(256));
        // The pixel rule: smallest c with c + ½ ≥ value, i.e. 256·c + 128 ≥ bits.
        let first = value.first_pixel_at_or_after() as i64;
        prop_assert!(256 * first + 128 >= bits as i64 && 256 * (first - 1) + 128 < bits as i64);
        prop_assert_eq!(value.frac().to_bits(), bits.rem_euclid(256));
    }

    #[test]
    fn checked_saturating_and_wrapping_sums(a in any::<i32>(), b in any::<i32>()) {
        let (x, y) = (Fx24_8::from_bits(a), Fx24_8::from_bits(b));
        let sum = a as i128 + b as i128;
        prop_assert_eq!(x.checked_add(y).map(Fx24_8::to_bits), a.checked_add(b));
        prop_assert_eq!(x.saturating_add(y).to_bits() as i128, sum.clamp(i32::MIN as i128, i32::MAX as i128));
        prop_assert_eq!(x.wrapping_add(y).to_bits(), a.wrapping_add(b));
        prop_assert_eq!(x.checked_sub(y).map(Fx24_8::to_bits), a.checked_sub(b));
        prop_assert_eq!(x.saturating_sub(y).to_bits(), a.saturating_sub(b));
        prop_assert_eq!(x.wrapping_sub(y).to_bits(), a.wrapping_sub(b));
        if let Some(bits) = a.checked_add(b) {
            prop_assert_eq!((x + y).to_bits(), bits);
        }
    }

    #[test]
    fn integer_multiples_and_exact_divisions(bits in any::<i32>(), n in any::<i32>()) {
        let x = Fx24_8::from_bits(bits);
        prop_assert_eq!(x.checked_mul_int(n).map(Fx24_8::to_bits), bits.checked_mul(n));
        prop_assert_eq!(x.saturating_mul_int(n).to_bits(), bits.saturating_mul(n));
        prop_assert_eq!(x.wrapping_mul_int(n).to_bits(), bits.wrapping_mul(n));
        if n > 0 {
            let exact = div_round_nearest(bits as i64, n as i64);
            prop_assert_eq!(exact as i128, rational_round(bits as i128, n as i128));
            prop_assert_eq!(x.div_int_round(n).to_bits() as i64, exact);
        }
    }

    #[test]
    fn exact_ratios_are_correctly_rounded(a in any::<i32>(), b in any::<i32>(), c in any::<i32>()) {
        prop_assume!(b != 0);
        // self / den in 16.16, saturating: round(a·2^16 / b).
        let expected = rational_round((a as i128) << 16, b as i128).clamp(i32::MIN as i128, i32::MAX as i128);
        prop_assert_eq!(Fx24_8::from_bits(a).saturating_ratio_fx16_16(Fx24_8::from_bits(b)).to_bits() as i128, expected);
        // self · num / den in 24.8.
        let expected = rational_round(a as i128 * c as i128, b as i128);
        if in_i32(expected) {
            prop_assert_eq!(
                Fx24_8::from_bits(a).mul_ratio(Fx24_8::from_bits(c), Fx24_8::from_bits(b)).to_bits() as i128,
                expected
            );
        }
        // A parameter t = self / den in 2.30, where |t| < 2.
        let expected = rational_round((a as i128) << 30, b as i128);
        if in_i32(expected) {
            prop_assert_eq!(Fx24_8::from_bits(a).ratio_fx2_30(Fx24_8::from_bits(b)).to_bits() as i128, expected);
        }
    }
}

/// `num / den` rounded to nearest, ties toward +∞, in i128.
fn rational_round(num: i128, den: i128) -> i128 {
    let (num, den) = if den < 0 { (-num, -den) } else { (num, den) };
    (2 * num + den).div_euclid(2 * den)
}

#[test]
fn extremes_of_every_format() {
    for &a in &EXTREMES {
        for &b in &EXTREMES {
            let exact = a as i128 * b as i128;
            for frac in [8u32, 16, 30] {
                let rounded = round_shift(exact, frac);
                let saturated = rounded.clamp(i32::MIN as i128, i32::MAX as i128);
                let got = match frac {
                    8 => Fx24_8::from_bits(a)
                        .saturating_mul(Fx24_8::from_bits(b))
                        .to_bits(),
                    16 => Fx16_16::from_bits(a)
                        .saturating_mul(Fx16_16::from_bits(b))
                        .to_bits(),
                    _ => Fx2_30::from_bits(a)
                        .saturating_mul(Fx2_30::from_bits(b))
                        .to_bits(),
                };
                assert_eq!(
                    got as i128, saturated,
                    "{a} × {b} in {frac} fractional bits"
                );
            }
        }
    }
    assert_eq!(Fx24_8::MAX.to_bits(), i32::MAX);
    assert_eq!(Fx24_8::MIN.to_bits(), i32::MIN);
    assert_eq!(Fx24_8::DELTA.to_bits(), 1);
    assert_eq!(Fx2_30::ONE.to_bits(), 1 << 30);
    assert_eq!(Fx24_8::from_int(8_388_607).to_bits(), 8_388_607 << 8);
    assert_eq!(Fx24_8::checked_from_int(8_388_608), None);
    assert_eq!(Fx24_8::checked_from_int(-8_388_608), Some(Fx24_8::MIN));
    assert_eq!(Fx2_30::checked_from_int(2), None);
    assert_eq!(Fx2_30::saturating_from_int(2), Fx2_30::MAX);
    assert_eq!(Fx16_16::saturating_from_int(-40_000), Fx16_16::MIN);
    // One ulp either side of zero and of one.
    assert_eq!((Fx24_8::ONE - Fx24_8::DELTA).to_int_floor(), 0);
    assert_eq!((Fx24_8::ONE - Fx24_8::DELTA).to_int_ceil(), 1);
    assert_eq!((-Fx24_8::DELTA).to_int_floor(), -1);
    assert_eq!((-Fx24_8::DELTA).to_int_ceil(), 0);
    // The smallest products that round away from zero, and the ties.
    assert_eq!(Fx24_8::DELTA.mul(Fx24_8::HALF), Fx24_8::DELTA); // ½ ulp ties up
    assert_eq!((-Fx24_8::DELTA).mul(Fx24_8::HALF), Fx24_8::ZERO); // −½ ulp ties up to 0
    assert_eq!(Fx2_30::DELTA.mul(Fx2_30::DELTA), Fx2_30::ZERO);
}

#[cfg(debug_assertions)]
mod debug_overflow_panics {
    use super::*;

    #[test]
    #[should_panic]
    fn sum_past_max() {
        let _ = Fx24_8::MAX + Fx24_8::DELTA;
    }

    #[test]
    #[should_panic]
    fn difference_past_min() {
        let _ = Fx16_16::MIN - Fx16_16::DELTA;
    }

    #[test]
    #[should_panic]
    fn product_past_max() {
        let _ = Fx24_8::from_int(1 << 12).mul(Fx24_8::from_int(1 << 12));
    }

    #[test]
    #[should_panic]
    fn mixed_product_past_max() {
        let _ = Fx16_16::from_int(30_000).mul_fx2_30(Fx2_30::from_bits(3 << 29));
    }

    #[test]
    #[should_panic]
    fn widening_conversion_past_max() {
        let _ = Fx24_8::from_int(32_768).to_fx16_16();
    }

    #[test]
    #[should_panic]
    fn integer_past_max() {
        let _ = Fx2_30::from_int(2);
    }

    #[test]
    #[should_panic]
    fn negating_min() {
        let _ = -Fx24_8::MIN;
    }
}
