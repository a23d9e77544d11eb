//! The math micro-benchmark: the engine's arithmetic, one operation at a time, so the ROM can
//! time each in cycles (the math scene, L held at power-on) and `cargo bench-math` can put the
//! figures in `docs/BENCH.md`.
//!
//! Every [`Op`] is a function of an operand pair `[a, b]` returning one `i32` (two results are
//! folded into one with [`pair_digest`]). Each runs over [`INPUTS`] operand pairs spread over the
//! engine's declared ranges: the cost of a multiply, a BIOS divide or a software divide depends on
//! the operands' magnitudes, so one fixed operand would flatter or punish it.
//!
//! The timed loop ([`rom_loops`]) walks the pairs `rounds` times and adds up the results, so
//! nothing can be optimised away: the pairs come through `black_box` every round, and the sum is
//! returned. The same loop is compiled twice, in two modules whose names the linker script tells
//! apart: `rom_loops` stays in the cartridge ROM (`.text`), `iwram_loops` goes to the IWRAM
//! overlay that only the math scene loads (see `linker.ld` and `hw::math_bench`), so both
//! placements run the same Thumb instructions. The hand-written ARM routines of
//! `asm/mathbench.s` walk the pairs the same way; [`Op::twin`] is the Rust function each must
//! agree with, which `tests/emulator_math.rs` checks on the ROM's results.
//!
//! The module is portable: on the host the loops simply run (the test uses them as the
//! reference); only the BIOS divide needs the GBA, and its host twin is the integer divide it is
//! specified to equal.

use crate::math::{Angle, EyeFrame, EyePoint, Fx16_16, Fx24_8, Fx2_30, Viewport, WorldPoint};
use crate::render::ratio::ratio;
use core::hint::black_box;

/// Operand pairs per operation.
pub const INPUTS: usize = 16;

/// One operand pair `[a, b]`; what each half means is the operation's (see [`Op`]).
pub type Pair = [i32; 2];

/// The eye the eye-space benchmark transforms points with: off the origin, at an angle that is
/// no multiple of 45°, so neither sine nor cosine is a special value.
pub const BENCH_EYE: EyeFrame = EyeFrame::new(
    WorldPoint::new(
        Fx24_8::from_bits(1234 * 256 + 128),
        Fx24_8::from_bits(-987 * 256 - 64),
    ),
    Angle::from_bits(0x2345),
);

/// The viewport of the projection benchmarks: 240 columns, where the exact column search takes
/// the most steps.
pub const BENCH_VIEWPORT: Viewport = Viewport::new(240, 160);

/// The engine's operations the benchmark times, in the order the ROM prints them.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub enum Op {
    /// The loop alone: load the pair, add its halves, accumulate. Every other figure includes
    /// this overhead.
    Loop,
    /// [`Fx24_8::mul`]: 24.8 × 24.8 → 24.8, rounded (`a`, `b`: 24.8).
    MulFx24_8,
    /// [`Fx16_16::mul`]: 16.16 × 16.16 → 16.16, rounded (`a`, `b`: 16.16).
    MulFx16_16,
    /// [`Fx24_8::recip_fx2_30`]: `1/z'` by seed table and one Newton step (`a`: depth in 24.8).
    Recip,
    /// [`Fx24_8::recip_fx2_30_exact`]: `1/z'` through the 64-bit library divide (`a`: depth).
    RecipExact,
    /// [`Fx16_16::div_small`]: `a / n` by the small-reciprocal table (`a`: 16.16, `b`: `n` in
    /// `1..=511`).
    DivSmall,
    /// `render::ratio::ratio`: the renderer's division by table (normalise, reciprocal, 64-bit
    /// product), rounded to nearest (`a / b`, integers).
    DivTable,
    /// The BIOS `Div` call (SWI 6): `a / b` truncated toward zero.
    DivBios,
    /// `a / b` in Rust: truncated toward zero, `__aeabi_idiv` of compiler-builtins in Thumb.
    DivSoft,
    /// [`Angle::sin_cos`] (`a`: angle in its low 16 bits); the result is
    /// `pair_digest(sin, cos)`.
    SinCos,
    /// [`EyeFrame::to_eye`] with [`BENCH_EYE`] (`a`, `b`: map point in 24.8); the result is
    /// `pair_digest(x', z')`.
    ToEye,
    /// [`Viewport::projected_x_saturating`] on [`BENCH_VIEWPORT`]: screen `x` of an eye-space
    /// point, through the reciprocal (`a`: `x'`, `b`: `z'`, 24.8).
    ProjectX,
    /// [`Viewport::first_column_at_or_after`] on [`BENCH_VIEWPORT`]: the exact column rule by
    /// binary search (`a`: `x'`, `b`: `z'`).
    Column,
    /// [`Viewport::projected_y`] on [`BENCH_VIEWPORT`]: screen `y` of a height at an inverse
    /// depth (`a`: height above the eye in 24.8, `b`: `1/z'` in 2.30).
    ProjectY,
}

/// How one half of an operand pair is spread.
#[derive(Clone, Copy)]
enum Spread {
    /// A magnitude with its top bit at a random position in `min..=max` bits (so every
    /// magnitude class is present), negative half the time if signed.
    Bits { min: u32, max: u32, signed: bool },
    /// Uniform over `0..=mask` (`mask` all ones).
    Uniform { mask: u32 },
}

const fn xorshift(state: u32) -> u32 {
    let mut x = state;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    x
}

const fn draw(state: u32, spread: Spread) -> (i32, u32) {
    match spread {
        Spread::Uniform { mask } => {
            let state = xorshift(state);
            ((state & mask) as i32, state)
        }
        Spread::Bits { min, max, signed } => {
            let first = xorshift(state);
            let second = xorshift(first);
            let bits = min + first % (max - min + 1);
            let magnitude = (second & ((1u32 << bits) - 1)) | (1u32 << (bits - 1));
            let value = if signed && first & (1 << 31) != 0 {
                -(magnitude as i32)
            } else {
                magnitude as i32
            };
            (value, second)
        }
    }
}

const fn pairs(seed: u32, a: Spread, b: Spread) -> [Pair; INPUTS] {
    let mut out = [[0; 2]; INPUTS];
    let mut state = seed;
    let mut index = 0;
    while index < INPUTS {
        let (first, next) = draw(state, a);
        let (second, next) = draw(next, b);
        out[index] = [first, second];
        state = next;
        index += 1;
    }
    out
}

const fn signed(min: u32, max: u32) -> Spread {
    Spread::Bits {
        min,
        max,
        signed: true,
    }
}

const fn unsigned(min: u32, max: u32) -> Spread {
    Spread::Bits {
        min,
        max,
        signed: false,
    }
}

const NONE: Spread = Spread::Uniform { mask: 0 };

// The ranges keep every result inside its format (see each `Op`); comments give the bound.
// 24.8 × 24.8: |a| < 2^22, |b| < 2^16, so the 24.8 product stays below 2^30.
const MUL_FX24_8_INPUTS: [Pair; INPUTS] = pairs(0x1234_5678, signed(8, 22), signed(4, 16));
// 16.16 × 16.16: |a|, |b| < 2^23, so the product stays below 2^30.
const MUL_FX16_16_INPUTS: [Pair; INPUTS] = pairs(0x2345_6789, signed(8, 23), signed(8, 23));
// Depths from 1 to 16384 units (the near plane is 1; the world's diagonal 23171).
const RECIP_INPUTS: [Pair; INPUTS] = pairs(0x3456_789a, unsigned(9, 22), NONE);
// 16.16 numerators below 256 in magnitude, divisors 1..=511.
const DIV_SMALL_INPUTS: [Pair; INPUTS] = pairs(0x4567_89ab, signed(8, 24), unsigned(1, 9));
// Integer quotients of every size; never a zero divisor, never i32::MIN / -1.
const DIV_INPUTS: [Pair; INPUTS] = pairs(0x5678_9abc, signed(1, 31), signed(1, 24));
const ANGLE_INPUTS: [Pair; INPUTS] = pairs(0x6789_abcd, Spread::Uniform { mask: 0xffff }, NONE);
// Map points within the declared ±8192 units.
const POINT_INPUTS: [Pair; INPUTS] = pairs(0x789a_bcde, signed(4, 21), signed(4, 21));
// Eye-space points: x' within ±8192 units, z' from 1 to 8192 units.
const EYE_POINT_INPUTS: [Pair; INPUTS] = pairs(0x89ab_cdef, signed(4, 21), unsigned(9, 21));
// Heights within ±16384 units, inverse depths from 2^-15 to 1.
const HEIGHT_INPUTS: [Pair; INPUTS] = pairs(0x9abc_def0, signed(4, 22), unsigned(15, 30));

/// Two results folded into one: `first ^ second.rotate_left(16)` (one `EOR` with a rotated
/// operand in ARM), so that a wrong value in either half shows.
#[inline(always)]
pub const fn pair_digest(first: i32, second: i32) -> i32 {
    first ^ second.rotate_left(16)
}

/// Folds the results of the [`INPUTS`] pairs in order into one word the ROM can print and the
/// test can compare: any single wrong result changes it.
pub fn mix(results: impl IntoIterator<Item = i32>) -> u32 {
    results
        .into_iter()
        .fold(0u32, |mixed, result| mixed.rotate_left(5) ^ result as u32)
}

impl Op {
    /// Every operation, in the order the ROM measures and prints them.
    pub const ALL: [Op; 14] = [
        Op::Loop,
        Op::MulFx24_8,
        Op::MulFx16_16,
        Op::Recip,
        Op::RecipExact,
        Op::DivSmall,
        Op::DivTable,
        Op::DivBios,
        Op::DivSoft,
        Op::SinCos,
        Op::ToEye,
        Op::ProjectX,
        Op::Column,
        Op::ProjectY,
    ];

    /// The operation's name in the ROM's log lines (`op=NAME`).
    pub const fn name(self) -> &'static str {
        match self {
            Op::Loop => "loop",
            Op::MulFx24_8 => "mul24_8",
            Op::MulFx16_16 => "mul16_16",
            Op::Recip => "recip",
            Op::RecipExact => "recip_exact",
            Op::DivSmall => "div_small",
            Op::DivTable => "div_table",
            Op::DivBios => "div_bios",
            Op::DivSoft => "div_soft",
            Op::SinCos => "sin_cos",
            Op::ToEye => "to_eye",
            Op::ProjectX => "project_x",
            Op::Column => "column",
            Op::ProjectY => "project_y",
        }
    }

    /// The operation named `name` in the log lines.
    pub fn from_name(name: &str) -> Option<Op> {
        Op::ALL.into_iter().find(|op| op.name() == name)
    }

    /// True if `asm/mathbench.s` has an ARM routine for this operation.
    pub const fn has_arm(self) -> bool {
        matches!(
            self,
            Op::Loop
                | Op::MulFx24_8
                | Op::MulFx16_16
                | Op::Recip
                | Op::DivBios
                | Op::DivSoft
                | Op::SinCos
                | Op::ToEye
                | Op::ProjectX
        )
    }

    /// The operand pairs, spread over the operation's domain.
    pub const fn inputs(self) -> [Pair; INPUTS] {
        match self {
            Op::Loop | Op::MulFx24_8 => MUL_FX24_8_INPUTS,
            Op::MulFx16_16 => MUL_FX16_16_INPUTS,
            Op::Recip | Op::RecipExact => RECIP_INPUTS,
            Op::DivSmall => DIV_SMALL_INPUTS,
            Op::DivTable | Op::DivBios | Op::DivSoft => DIV_INPUTS,
            Op::SinCos => ANGLE_INPUTS,
            Op::ToEye => POINT_INPUTS,
            Op::ProjectX | Op::Column => EYE_POINT_INPUTS,
            Op::ProjectY => HEIGHT_INPUTS,
        }
    }

    /// The engine's Rust function on one pair: the value every variant (Thumb loop in ROM or
    /// IWRAM, ARM routine) must return. For [`Op::DivBios`] it is the integer divide the BIOS
    /// call is specified to equal.
    pub fn twin(self, a: i32, b: i32) -> i32 {
        match self {
            Op::Loop => ops::add(a, b),
            Op::MulFx24_8 => ops::mul_fx24_8(a, b),
            Op::MulFx16_16 => ops::mul_fx16_16(a, b),
            Op::Recip => ops::recip(a),
            Op::RecipExact => ops::recip_exact(a),
            Op::DivSmall => ops::div_small(a, b),
            Op::DivTable => ops::div_table(a, b),
            Op::DivBios | Op::DivSoft => ops::div_soft(a, b),
            Op::SinCos => ops::sin_cos(a),
            Op::ToEye => ops::to_eye(&BENCH_EYE, a, b),
            Op::ProjectX => ops::project_x(&BENCH_VIEWPORT, a, b),
            Op::Column => ops::column(&BENCH_VIEWPORT, a, b),
            Op::ProjectY => ops::project_y(&BENCH_VIEWPORT, a, b),
        }
    }

    /// Runs the Thumb loop placed in ROM (on the host: the same loop, compiled for the host).
    pub fn run_in_rom(self, inputs: &[Pair], rounds: u32) -> i32 {
        rom_loops::run_op(self, inputs, rounds)
    }
}

/// The operations on one pair, as the loops inline them.
mod ops {
    use super::*;

    #[inline(always)]
    pub fn add(a: i32, b: i32) -> i32 {
        a.wrapping_add(b)
    }

    #[inline(always)]
    pub fn mul_fx24_8(a: i32, b: i32) -> i32 {
        Fx24_8::from_bits(a).mul(Fx24_8::from_bits(b)).to_bits()
    }

    #[inline(always)]
    pub fn mul_fx16_16(a: i32, b: i32) -> i32 {
        Fx16_16::from_bits(a).mul(Fx16_16::from_bits(b)).to_bits()
    }

    #[inline(always)]
    pub fn recip(a: i32) -> i32 {
        Fx24_8::from_bits(a).recip_fx2_30().to_bits()
    }

    #[inline(always)]
    pub fn recip_exact(a: i32) -> i32 {
        Fx24_8::from_bits(a).recip_fx2_30_exact().to_bits()
    }

    #[inline(always)]
    pub fn div_small(a: i32, b: i32) -> i32 {
        Fx16_16::from_bits(a).div_small(b as u32).to_bits()
    }

    #[inline(always)]
    pub fn div_table(a: i32, b: i32) -> i32 {
        // |a / b| ≤ |a|: the rounded quotient fits i32.
        ratio(i64::from(a), i64::from(b)) as i32
    }

    #[inline(always)]
    pub fn div_bios(a: i32, b: i32) -> i32 {
        #[cfg(target_os = "none")]
        {
            crate::hw::bios_div(a, b).0
        }
        #[cfg(not(target_os = "none"))]
        {
            div_soft(a, b)
        }
    }

    #[inline(always)]
    pub fn div_soft(a: i32, b: i32) -> i32 {
        a / b
    }

    #[inline(always)]
    pub fn sin_cos(a: i32) -> i32 {
        let (sin, cos) = Angle::from_bits(a as u16).sin_cos();
        pair_digest(sin.to_bits(), cos.to_bits())
    }

    #[inline(always)]
    pub fn to_eye(eye: &EyeFrame, a: i32, b: i32) -> i32 {
        let point = eye.to_eye(WorldPoint::new(Fx24_8::from_bits(a), Fx24_8::from_bits(b)));
        pair_digest(point.x.to_bits(), point.z.to_bits())
    }

    #[inline(always)]
    pub fn project_x(viewport: &Viewport, a: i32, b: i32) -> i32 {
        viewport.projected_x_saturating(eye_point(a, b)).to_bits()
    }

    #[inline(always)]
    pub fn column(viewport: &Viewport, a: i32, b: i32) -> i32 {
        viewport.first_column_at_or_after(eye_point(a, b))
    }

    #[inline(always)]
    pub fn project_y(viewport: &Viewport, a: i32, b: i32) -> i32 {
        viewport
            .projected_y(Fx24_8::from_bits(a), Fx2_30::from_bits(b))
            .to_bits()
    }

    #[inline(always)]
    fn eye_point(a: i32, b: i32) -> EyePoint {
        EyePoint::new(Fx24_8::from_bits(a), Fx24_8::from_bits(b))
    }
}

/// The timed loop: `rounds` passes over `inputs`, summing the results. The pairs go through
/// `black_box` every pass, so the compiler can neither hoist a pass's work out of the loop nor
/// read the pairs from their constant (they stay where the caller put them, in IWRAM).
#[inline(always)]
fn run(inputs: &[Pair], rounds: u32, op: impl Fn(i32, i32) -> i32) -> i32 {
    let mut sum = 0i32;
    for _ in 0..rounds {
        for &[a, b] in black_box(inputs) {
            sum = sum.wrapping_add(op(a, b));
        }
    }
    sum
}

/// One `#[inline(never)]` loop per operation and a dispatcher. Expanded twice, each copy's loops
/// in its own section (`$section`: ROM or the IWRAM overlay), so the two copies run the
/// same instructions from different memories. The contexts (eye, viewport) go through
/// `black_box` so they are run-time values, as in the renderer.
///
/// `$place` tells the copies apart: LLVM merges identical functions (it does not look at where
/// the linker will put them), which would send both placements to one copy. Every loop passes
/// `$place` through `black_box` once, before its loop, so the copies differ by one constant.
macro_rules! bench_loops {
    ($place:expr, $section:literal) => {
        use super::{ops, Op, Pair, BENCH_EYE, BENCH_VIEWPORT};
        use core::hint::black_box;

        /// [`super::run`], marked with this copy's placement.
        #[inline(always)]
        fn run(inputs: &[Pair], rounds: u32, op: impl Fn(i32, i32) -> i32) -> i32 {
            black_box($place);
            super::run(inputs, rounds, op)
        }

        /// Runs `op`'s loop: `rounds` passes over `inputs`, returning the sum of the results.
        pub fn run_op(op: Op, inputs: &[Pair], rounds: u32) -> i32 {
            match op {
                Op::Loop => Loops::add(inputs, rounds),
                Op::MulFx24_8 => Loops::mul_fx24_8(inputs, rounds),
                Op::MulFx16_16 => Loops::mul_fx16_16(inputs, rounds),
                Op::Recip => Loops::recip(inputs, rounds),
                Op::RecipExact => Loops::recip_exact(inputs, rounds),
                Op::DivSmall => Loops::div_small(inputs, rounds),
                Op::DivTable => Loops::div_table(inputs, rounds),
                Op::DivBios => Loops::div_bios(inputs, rounds),
                Op::DivSoft => Loops::div_soft(inputs, rounds),
                Op::SinCos => Loops::sin_cos(inputs, rounds),
                Op::ToEye => Loops::to_eye(inputs, rounds),
                Op::ProjectX => Loops::project_x(inputs, rounds),
                Op::Column => Loops::column(inputs, rounds),
                Op::ProjectY => Loops::project_y(inputs, rounds),
            }
        }

        /// The loops, one per operation: methods, so that their section attribute is not
        /// unsafe code (it is on a free function).
        struct Loops;

        impl Loops {
            #[inline(never)]
            #[cfg_attr(target_os = "none", link_section = $section)]
            fn add(inputs: &[Pair], rounds: u32) -> i32 {
                run(inputs, rounds, ops::add)
            }

            #[inline(never)]
            #[cfg_attr(target_os = "none", link_section = $section)]
            fn mul_fx24_8(inputs: &[Pair], rounds: u32) -> i32 {
                run(inputs, rounds, ops::mul_fx24_8)
            }

            #[inline(never)]
            #[cfg_attr(target_os = "none", link_section = $section)]
            fn mul_fx16_16(inputs: &[Pair], rounds: u32) -> i32 {
                run(inputs, rounds, ops::mul_fx16_16)
            }

            #[inline(never)]
            #[cfg_attr(target_os = "none", link_section = $section)]
            fn recip(inputs: &[Pair], rounds: u32) -> i32 {
                run(inputs, rounds, |a, _| ops::recip(a))
            }

            #[inline(never)]
            #[cfg_attr(target_os = "none", link_section = $section)]
            fn recip_exact(inputs: &[Pair], rounds: u32) -> i32 {
                run(inputs, rounds, |a, _| ops::recip_exact(a))
            }

            #[inline(never)]
            #[cfg_attr(target_os = "none", link_section = $section)]
            fn div_small(inputs: &[Pair], rounds: u32) -> i32 {
                run(inputs, rounds, ops::div_small)
            }

            #[inline(never)]
            #[cfg_attr(target_os = "none", link_section = $section)]
            fn div_table(inputs: &[Pair], rounds: u32) -> i32 {
                run(inputs, rounds, ops::div_table)
            }

            #[inline(never)]
            #[cfg_attr(target_os = "none", link_section = $section)]
            fn div_bios(inputs: &[Pair], rounds: u32) -> i32 {
                run(inputs, rounds, ops::div_bios)
            }

            #[inline(never)]
            #[cfg_attr(target_os = "none", link_section = $section)]
            fn div_soft(inputs: &[Pair], rounds: u32) -> i32 {
                run(inputs, rounds, ops::div_soft)
            }

            #[inline(never)]
            #[cfg_attr(target_os = "none", link_section = $section)]
            fn sin_cos(inputs: &[Pair], rounds: u32) -> i32 {
                run(inputs, rounds, |a, _| ops::sin_cos(a))
            }

            #[inline(never)]
            #[cfg_attr(target_os = "none", link_section = $section)]
            fn to_eye(inputs: &[Pair], rounds: u32) -> i32 {
                let eye = black_box(BENCH_EYE);
                run(inputs, rounds, |a, b| ops::to_eye(&eye, a, b))
            }

            #[inline(never)]
            #[cfg_attr(target_os = "none", link_section = $section)]
            fn project_x(inputs: &[Pair], rounds: u32) -> i32 {
                let viewport = black_box(BENCH_VIEWPORT);
                run(inputs, rounds, |a, b| ops::project_x(&viewport, a, b))
            }

            #[inline(never)]
            #[cfg_attr(target_os = "none", link_section = $section)]
            fn column(inputs: &[Pair], rounds: u32) -> i32 {
                let viewport = black_box(BENCH_VIEWPORT);
                run(inputs, rounds, |a, b| ops::column(&viewport, a, b))
            }

            #[inline(never)]
            #[cfg_attr(target_os = "none", link_section = $section)]
            fn project_y(inputs: &[Pair], rounds: u32) -> i32 {
                let viewport = black_box(BENCH_VIEWPORT);
                run(inputs, rounds, |a, b| ops::project_y(&viewport, a, b))
            }
        }
    };
}

/// The loops placed in the cartridge ROM (the default `.text`): Thumb code paying the cart's
/// wait states on every fetch.
pub mod rom_loops {
    bench_loops!(0x524f_4d00_u32, ".text.rom.math_bench_loops");
}

/// The same loops placed in the IWRAM overlay (their section, `.bench_iwram`). They
/// are only valid once the overlay is loaded, so only `hw::math_bench` calls them.
#[cfg(target_os = "none")]
pub(crate) mod iwram_loops {
    bench_loops!(0x4957_5241_u32, ".bench_iwram.math_bench_loops");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_loop_sums_its_operation_over_pairs_and_rounds() {
        for op in Op::ALL {
            let inputs = op.inputs();
            let once = inputs
                .iter()
                .fold(0i32, |sum, &[a, b]| sum.wrapping_add(op.twin(a, b)));
            assert_eq!(op.run_in_rom(&inputs, 1), once, "{op:?}");
            assert_eq!(op.run_in_rom(&inputs, 3), once.wrapping_mul(3), "{op:?}");
        }
    }

    #[test]
    fn operands_stay_in_each_operation_s_domain() {
        for op in Op::ALL {
            let inputs = op.inputs();
            // Spread: no operand repeats, so a loop cannot profit from one fixed value.
            for (index, pair) in inputs.iter().enumerate() {
                assert!(!inputs[..index].contains(pair), "{op:?}: {pair:?} repeats");
            }
            for [a, b] in inputs {
                match op {
                    Op::Recip | Op::RecipExact => assert!(a > 256, "{op:?}: depth {a}"),
                    Op::DivSmall => assert!((1..=511).contains(&b), "{op:?}: n {b}"),
                    Op::DivTable | Op::DivBios | Op::DivSoft => {
                        assert!(b != 0 && a != i32::MIN, "{op:?}: {a} / {b}")
                    }
                    Op::ProjectX | Op::Column => assert!(b >= 256, "{op:?}: depth {b}"),
                    Op::ProjectY => assert!(b > 0 && b <= 1 << 30, "{op:?}: 1/z' {b}"),
                    _ => {}
                }
            }
        }
    }

    #[test]
    fn names_round_trip() {
        for op in Op::ALL {
            assert_eq!(Op::from_name(op.name()), Some(op));
        }
    }
}
