//! Reciprocals against exact integer division.

use portalcast::math::{
    quotient, recip_pow2, recip_pow2_exact, recip_small, Fx16_16, Fx24_8, Fx2_30, RECIP_SMALL_MAX,
};
use portalcast_format::limits::{EYE_DEPTH_MAX, EYE_DEPTH_MIN};
use proptest::prelude::*;

/// Error of `recip_pow2(n, k)` against the real `2^k / n`, in units of the result.
fn error(n: u32, k: u32) -> f64 {
    let exact = (1u128 << k) as f64 / n as f64;
    recip_pow2(n, k) as f64 - exact
}

#[test]
#[ignore = "scans all 2^31 mantissas: run with --release -- --ignored"]
fn scan_every_mantissa() {
    let mut worst_relative: f64 = 0.0;
    let mut worst_at = 0;
    for n in (1u32 << 31) + 1..=u32::MAX {
        // k = 62 puts the result in (2^30, 2^31): the mantissa reciprocal before rounding.
        let exact = (1u128 << 62) as f64 / n as f64;
        let relative = ((recip_pow2(n, 62) as f64 - exact).abs() - 0.5).max(0.0) / exact;
        if relative > worst_relative {
            worst_relative = relative;
            worst_at = n;
        }
    }
    println!("worst relative error beyond rounding: {worst_relative:.3e} at n = {worst_at:#x}");
}

/// The documented relative error of `recip_pow2` before its final rounding to nearest.
const RELATIVE_BOUND: f64 = 1e-9;

fn within_bound(n: u32, k: u32) -> bool {
    let exact = (1u128 << k) as f64 / n as f64;
    error(n, k).abs() <= RELATIVE_BOUND * exact + 0.5
}

#[test]
fn both_ends_and_middle_of_every_seed_cell() {
    for cell in 0u32..1024 {
        let low = (1u32 << 31) | (cell << 21);
        let high = low | ((1 << 21) - 1);
        for n in [
            low.max((1 << 31) + 1),
            low + 1,
            low | (1 << 20),
            high - 1,
            high,
        ] {
            assert!(within_bound(n, 62), "n = {n:#x}: error {}", error(n, 62));
            // The same mantissa at other exponents (k − shift fixed keeps the quotient in range).
            for shift in [1, 7, 15, 23] {
                let small = n >> shift;
                if (small as u64) << 31 > 1u64 << (62 - shift) {
                    assert!(
                        within_bound(small, 62 - shift),
                        "n = {small:#x}, k = {}",
                        62 - shift
                    );
                }
            }
        }
    }
}

#[test]
fn exact_path_is_correctly_rounded() {
    for n in [
        1u32,
        2,
        3,
        129,
        255,
        256,
        257,
        1000,
        65535,
        1 << 20,
        u32::MAX,
    ] {
        for k in [31u32, 38, 46, 62] {
            if (n as u64) << 31 <= 1u64 << k {
                continue;
            }
            let exact = (1u128 << k) as f64 / n as f64;
            let got = recip_pow2_exact(n, k) as f64;
            assert!((got - exact).abs() <= 0.5, "2^{k}/{n}: {got} vs {exact}");
        }
    }
}

#[test]
fn every_depth_of_the_declared_range() {
    // 1/z' for every 24.8 depth from the near plane to the far limit (5.9 million values).
    let mut worst_ulps: f64 = 0.0;
    for bits in EYE_DEPTH_MIN << 8..=EYE_DEPTH_MAX << 8 {
        let z = Fx24_8::from_bits(bits);
        let exact = (1u64 << 38) as f64 / bits as f64;
        let got = z.recip_fx2_30().to_bits() as f64;
        let allowed = RELATIVE_BOUND * exact + 0.5;
        let error = (got - exact).abs();
        assert!(error <= allowed, "1/z' at {bits}: {got} vs {exact}");
        worst_ulps = worst_ulps.max(error);
    }
    println!("1/z' over [1, 23171]: worst error {worst_ulps:.3} ulp of 2.30");
    assert_eq!(Fx24_8::ONE.recip_fx2_30(), Fx2_30::ONE);
    assert_eq!(Fx24_8::from_int(2).recip_fx2_30(), Fx2_30::HALF);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10000))]

    #[test]
    fn any_divisor_and_scale(n in 1u32.., k in 0u32..=62) {
        prop_assume!((n as u64) << 31 > 1u64 << k);
        prop_assert!(within_bound(n, k), "2^{}/{}: error {}", k, n, error(n, k));
        let exact = recip_pow2_exact(n, k) as i64;
        prop_assert!((recip_pow2(n, k) as i64 - exact).abs() <= 1 + (RELATIVE_BOUND * exact as f64) as i64);
    }

    #[test]
    fn inverse_depth_round_trips(bits in 129i32..=1 << 30) {
        // z' = 1/(1/z') as the column loop does it: both steps within their bounds.
        let w = Fx24_8::from_bits(bits).recip_fx2_30();
        let exact_w = (1u64 << 38) as f64 / bits as f64;
        prop_assert!((w.to_bits() as f64 - exact_w).abs() <= RELATIVE_BOUND * exact_w + 0.5);
        let z = w.recip_fx24_8();
        let exact_z = (1u64 << 38) as f64 / w.to_bits() as f64;
        prop_assert!((z.to_bits() as f64 - exact_z).abs() <= RELATIVE_BOUND * exact_z + 0.5);
        prop_assert_eq!(w.recip_fx24_8_exact().to_bits() as f64, exact_z.round());
        prop_assert_eq!(Fx24_8::from_bits(bits).recip_fx2_30_exact().to_bits() as f64, exact_w.round());
    }

    #[test]
    fn dda_steps_divide_by_small_counts(delta in any::<i32>(), n in 1u32..=RECIP_SMALL_MAX) {
        // |error| ≤ ½ ulp + |Δ|·2^-31 (the table's absolute error times Δ).
        let got = Fx16_16::from_bits(delta).div_small(n).to_bits() as f64;
        let exact = delta as f64 / n as f64;
        prop_assert!((got - exact).abs() <= 0.5 + delta.unsigned_abs() as f64 / (1u64 << 31) as f64);
    }

    #[test]
    fn small_quotients_are_exact(n in any::<u32>(), d in 1u32..=RECIP_SMALL_MAX) {
        prop_assert_eq!(quotient(n, d), n / d);
    }

    #[test]
    fn large_quotients_are_exact(n in any::<u32>(), d in RECIP_SMALL_MAX + 1..) {
        prop_assert_eq!(quotient(n, d), n / d);
    }
}

/// The quotient at the ends of its range and next to every multiple the table's rounding
/// could misplace: every divisor, with the largest dividends and those around its multiples.
#[test]
fn small_quotients_at_the_edges() {
    for d in 1..=RECIP_SMALL_MAX {
        let top = u32::MAX / d * d;
        for n in [0, 1, d - 1, d, d + 1, top - 1, top, u32::MAX, u32::MAX - 1] {
            assert_eq!(quotient(n, d), n / d, "{n} / {d}");
        }
    }
}

#[test]
fn every_small_reciprocal() {
    assert_eq!(recip_small(1), Fx2_30::ONE);
    assert_eq!(recip_small(2), Fx2_30::HALF);
    for n in 1..=RECIP_SMALL_MAX {
        let exact = (1u64 << 30) as f64 / n as f64;
        assert!(
            (recip_small(n).to_bits() as f64 - exact).abs() <= 0.5,
            "1/{n}"
        );
    }
}

#[test]
fn smallest_divisors() {
    // The smallest depth (just over ½) and inverse depth (129 ulps) the typed reciprocals
    // accept: quotients just under 2^31, where the 1e-9 bound allows 2.6 ulps.
    for (got, n) in [
        (Fx24_8::from_bits(129).recip_fx2_30().to_bits(), 129),
        (Fx2_30::from_bits(129).recip_fx24_8().to_bits(), 129),
        (Fx24_8::from_bits(130).recip_fx2_30().to_bits(), 130),
    ] {
        let exact = (1u64 << 38) as f64 / n as f64;
        assert!(
            (got as f64 - exact).abs() <= RELATIVE_BOUND * exact + 0.5,
            "1/{n}: {got} vs {exact}"
        );
        assert!(within_bound(n, 38));
    }
    assert_eq!(recip_pow2(1, 30), 1 << 30);
    assert_eq!(recip_pow2(2, 31), 1 << 30);
    assert_eq!(recip_pow2(3, 31), 715_827_883); // 2^31/3 = 715827882.67
    assert_eq!(recip_pow2(1, 0), 1);
    assert_eq!(recip_pow2(3, 0), 0);
    assert_eq!(recip_pow2(u32::MAX, 31), 1); // 0.50000000012 rounds up
    assert_eq!(recip_pow2(u32::MAX, 30), 0); // 0.25000000006 rounds down
}

#[cfg(debug_assertions)]
#[test]
#[should_panic]
fn reciprocal_of_a_depth_at_half_panics_in_debug() {
    let _ = Fx24_8::HALF.recip_fx2_30();
}

#[cfg(debug_assertions)]
#[test]
#[should_panic]
fn small_reciprocal_of_zero_panics_in_debug() {
    let _ = recip_small(0);
}
