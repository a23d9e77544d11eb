//! Sine and cosine over every one of the 65536 angles, against f64.

use portalcast::math::{tables, Angle, Fx16_16};
use std::f64::consts::TAU;

/// The documented bound of `Angle::sin` / `Angle::cos`: ½ ulp of 16.16 for the final rounding,
/// `(π/2048)²/8` for the linear interpolation, `2^-30` for the 2.30 table and arithmetic.
const SIN_ERROR_BOUND: f64 = 7.93e-6;

fn value(x: Fx16_16) -> f64 {
    x.to_bits() as f64 / 65536.0
}

fn radians(angle: Angle) -> f64 {
    angle.to_bits() as f64 * TAU / 65536.0
}

#[test]
fn the_bound_is_the_sum_of_its_parts() {
    let interpolation = (std::f64::consts::PI / 2048.0).powi(2) / 8.0;
    let bound = 0.5 / 65536.0 + interpolation + 1.0 / (1u64 << 30) as f64;
    assert!(bound <= SIN_ERROR_BOUND, "{bound}");
}

#[test]
fn every_angle_is_within_the_bound() {
    let mut worst_sin: f64 = 0.0;
    let mut worst_cos: f64 = 0.0;
    for bits in 0..=u16::MAX {
        let angle = Angle::from_bits(bits);
        worst_sin = worst_sin.max((value(angle.sin()) - radians(angle).sin()).abs());
        worst_cos = worst_cos.max((value(angle.cos()) - radians(angle).cos()).abs());
    }
    println!(
        "max |sin error| = {worst_sin:.3e} ({:.4} ulp), max |cos error| = {worst_cos:.3e}",
        worst_sin * 65536.0
    );
    assert!(worst_sin <= SIN_ERROR_BOUND, "sin error {worst_sin:e}");
    assert!(worst_cos <= SIN_ERROR_BOUND, "cos error {worst_cos:e}");
}

#[test]
fn symmetries_hold_exactly() {
    for bits in 0..=u16::MAX {
        let angle = Angle::from_bits(bits);
        assert_eq!((-angle).sin(), -angle.sin(), "odd sine at {bits}");
        assert_eq!((-angle).cos(), angle.cos(), "even cosine at {bits}");
        assert_eq!(
            (angle + Angle::HALF).sin(),
            -angle.sin(),
            "half turn at {bits}"
        );
        assert_eq!(
            angle.cos(),
            (angle + Angle::QUARTER).sin(),
            "quarter turn at {bits}"
        );
        assert_eq!(
            angle.sin(),
            (Angle::HALF - angle).sin(),
            "supplement at {bits}"
        );
    }
}

#[test]
fn multiples_of_45_degrees_are_exact_table_entries() {
    let one = 65536;
    let diagonal = 46341; // round(65536 · √½) = round(46340.95)
    for eighth in 0..8u16 {
        let angle = Angle::from_bits(eighth * 8192);
        let (sin, cos) = angle.sin_cos();
        let expected_sin =
            [0, diagonal, one, diagonal, 0, -diagonal, -one, -diagonal][eighth as usize];
        let expected_cos =
            [one, diagonal, 0, -diagonal, -one, -diagonal, 0, diagonal][eighth as usize];
        assert_eq!(
            (sin.to_bits(), cos.to_bits()),
            (expected_sin, expected_cos),
            "{}°",
            eighth * 45
        );
    }
    assert_eq!(Angle::from_degrees(90), Angle::QUARTER);
    assert_eq!(Angle::from_degrees(45), Angle::EIGHTH);
    assert_eq!(Angle::from_degrees(-45), Angle::from_bits(57344));
}

#[test]
fn one_unit_from_the_axes() {
    // The first steps off 0° and 90° move by the slope of the sine: 2π/65536 ≈ 6.3 ulps.
    assert_eq!(Angle::from_bits(1).sin().to_bits(), 6);
    assert_eq!(Angle::from_bits(u16::MAX).sin().to_bits(), -6);
    assert_eq!(Angle::from_bits(16383).sin().to_bits(), 65536);
    assert_eq!(Angle::from_bits(16385).cos().to_bits(), -6);
}

#[test]
fn sine_rises_monotonically_over_the_first_quadrant() {
    let mut previous = Angle::ZERO.sin();
    for bits in 1..=16384u16 {
        let sin = Angle::from_bits(bits).sin();
        assert!(sin >= previous, "sine falls at {bits}");
        previous = sin;
    }
}

#[test]
fn unit_circle_is_kept() {
    // |sin² + cos² − 1| ≤ 2·(|sin| + |cos|)·ε + 2ε² ≤ 2√2·ε + 2ε².
    let bound =
        2.0 * std::f64::consts::SQRT_2 * SIN_ERROR_BOUND + 2.0 * SIN_ERROR_BOUND * SIN_ERROR_BOUND;
    for bits in 0..=u16::MAX {
        let (sin, cos) = Angle::from_bits(bits).sin_cos();
        let norm = value(sin).powi(2) + value(cos).powi(2);
        assert!((norm - 1.0).abs() <= bound, "norm {norm} at {bits}");
    }
}

#[test]
fn engine_table_is_the_generated_one() {
    assert_eq!(
        tables::SIN_QUARTER_FX2_30.to_vec(),
        portalcast_assets::numeric_tables::sin_quarter_table()
    );
    assert_eq!(
        tables::RECIP_SEED_U16.to_vec(),
        portalcast_assets::numeric_tables::recip_seed_table()
    );
    assert_eq!(
        tables::RECIP_SMALL_FX2_30.to_vec(),
        portalcast_assets::numeric_tables::recip_small_table()
    );
}

#[test]
fn angles_wrap() {
    assert_eq!(Angle::THREE_QUARTERS + Angle::HALF, Angle::QUARTER);
    assert_eq!(Angle::ZERO - Angle::EIGHTH, Angle::from_bits(57344));
    let mut angle = Angle::from_bits(65000);
    angle += Angle::from_bits(1000);
    assert_eq!(angle.to_bits(), 464);
    angle -= Angle::from_bits(465);
    assert_eq!(angle.to_bits(), u16::MAX);
}
