//! Checks the ROM runs at power-on and the host repeats, so a test can compare the two.
//!
//! [`division_digest`] exercises the four division-with-remainder helpers that the ROM links from
//! `asm/runtime.s` in place of compiler-builtins' own (the engine is ARM code in a Thumb ROM; see
//! that file). On the host the same function uses the compiler's division, which is the twin.

use core::hint::black_box;

/// FNV-1a over the quotients and remainders of a fixed set of divisions in every integer width
/// the engine divides in: unsigned and signed, 32 and 64 bits, with divisors of both signs, 1,
/// and the extremes.
pub fn division_digest() -> u32 {
    let mut digest = 0x811c_9dc5u32;
    let mut mix = |value: u64| {
        for byte in value.to_le_bytes() {
            digest = (digest ^ u32::from(byte)).wrapping_mul(0x0100_0193);
        }
    };
    let numerators: [i64; 8] = [
        0,
        1,
        7,
        -7,
        1 << 40,
        -(1 << 40) - 12_345,
        i64::from(i32::MAX),
        i64::from(i32::MIN),
    ];
    let divisors: [i64; 7] = [1, -1, 3, -3, 7919, -65_536, (1 << 33) + 5];
    for &n in &numerators {
        for &d in &divisors {
            let (n32, d32) = (black_box(n as i32), black_box(d as i32));
            if let (Some(quotient), Some(remainder)) = (n32.checked_div(d32), n32.checked_rem(d32))
            {
                mix(black_box(quotient) as u64);
                mix(black_box(remainder) as u64);
            }
            let (u32n, u32d) = (black_box(n as u32), black_box(d as u32));
            if let (Some(quotient), Some(remainder)) =
                (u32n.checked_div(u32d), u32n.checked_rem(u32d))
            {
                mix(u64::from(black_box(quotient)));
                mix(u64::from(black_box(remainder)));
            }
            let (n64, d64) = (black_box(n), black_box(d));
            mix(black_box(n64 / d64) as u64);
            mix(black_box(n64 % d64) as u64);
            let (u64n, u64d) = (black_box(n as u64), black_box(d as u64));
            mix(black_box(u64n / u64d));
            mix(black_box(u64n % u64d));
        }
    }
    digest
}
