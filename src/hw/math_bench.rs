//! The math benchmark's IWRAM code: the overlay that holds it, and safe calls into it.
//!
//! The benchmark's IWRAM variants (the loops of `math_bench::iwram_loops` and the ARM routines of
//! `asm/mathbench.s`) are stored in ROM after the IWRAM image and linked to run over the
//! renderer's per-frame code (`linker.ld`: `.bench_iwram` shares its run addresses with
//! `.iwram_render`: the portal walk and its wall and span stages). The math scene never runs that
//! code, so the overlay costs the game neither IWRAM nor stack room; but loading it
//! destroys the renderer until the next reset, which is why [`BenchCode::load`] is `unsafe` and
//! the math scene never returns.

use crate::math::tables::{RECIP_SEED_U16, SIN_QUARTER_FX2_30};
use crate::math_bench::{iwram_loops, Op, Pair, BENCH_EYE, BENCH_VIEWPORT};

extern "C" {
    static __bench_iwram_start: u8;
    static __bench_iwram_end: u8;
    static __bench_iwram_position_in_rom: u8;
}

/// The ARM routines' common signature (documented at the top of `asm/mathbench.s`): pairs, pairs
/// per round, rounds, context block.
type ArmRoutine = unsafe extern "C" fn(*const Pair, u32, u32, *const u32) -> i32;

extern "C" {
    fn pc_mb_loop(pairs: *const Pair, per_round: u32, rounds: u32, context: *const u32) -> i32;
    fn pc_mb_mul24_8(pairs: *const Pair, per_round: u32, rounds: u32, context: *const u32) -> i32;
    fn pc_mb_mul16_16(pairs: *const Pair, per_round: u32, rounds: u32, context: *const u32) -> i32;
    fn pc_mb_recip(pairs: *const Pair, per_round: u32, rounds: u32, context: *const u32) -> i32;
    fn pc_mb_div_bios(pairs: *const Pair, per_round: u32, rounds: u32, context: *const u32) -> i32;
    fn pc_mb_div_soft(pairs: *const Pair, per_round: u32, rounds: u32, context: *const u32) -> i32;
    fn pc_mb_sin_cos(pairs: *const Pair, per_round: u32, rounds: u32, context: *const u32) -> i32;
    fn pc_mb_to_eye(pairs: *const Pair, per_round: u32, rounds: u32, context: *const u32) -> i32;
    fn pc_mb_project_x(pairs: *const Pair, per_round: u32, rounds: u32, context: *const u32)
        -> i32;
}

/// Proof that the benchmark's IWRAM code is in place: the only way to run it.
pub struct BenchCode {
    bytes: usize,
}

impl BenchCode {
    /// Copies the overlay from ROM into IWRAM, over the renderer's per-frame code. There is no
    /// way back short of a reset: the IWRAM image is copied only at boot.
    ///
    /// # Safety
    ///
    /// No code of `.iwram_render` (`render::walk`, `render::walls`, `render::spans`: every
    /// `Renderer::render`) may run after this call, and the caller must not be running from there
    /// itself. The math scene calls it once, renders nothing and
    /// never returns to `main`.
    pub unsafe fn load() -> BenchCode {
        let start = &raw const __bench_iwram_start as usize;
        let end = &raw const __bench_iwram_end as usize;
        let source = &raw const __bench_iwram_position_in_rom as usize;
        for offset in (0..end - start).step_by(4) {
            // SAFETY: the linker script places the overlay's image at `source` in ROM and its
            // run addresses `start..end`, word-aligned (asserted there), inside `.iwram_render`,
            // which holds only code that the caller promises never to run again: no data, no
            // stack. Volatile, so the stores are kept and stay before the calls into the
            // overlay (the compiler does not know the code is run). A fence would do it too, but
            // on the ARMv4T it links to a missing `__sync_synchronize`.
            unsafe {
                let word = ((source + offset) as *const u32).read_volatile();
                ((start + offset) as *mut u32).write_volatile(word);
            }
        }
        BenchCode { bytes: end - start }
    }

    /// Size of the overlay in bytes.
    pub fn bytes(&self) -> usize {
        self.bytes
    }

    /// Runs `op`'s Thumb loop placed in IWRAM: `rounds` passes over `inputs`, returning the sum.
    pub fn run_in_iwram(&self, op: Op, inputs: &[Pair], rounds: u32) -> i32 {
        iwram_loops::run_op(op, inputs, rounds)
    }

    /// Runs `op`'s ARM routine from IWRAM, or `None` if `asm/mathbench.s` has none. Panics on
    /// an empty `inputs` or zero `rounds` (the routines run at least once), and on operands
    /// outside the operation's domain (where the routine would not equal its twin, or the BIOS
    /// would hang).
    pub fn run_arm(&self, op: Op, inputs: &[Pair], rounds: u32) -> Option<i32> {
        assert!(!inputs.is_empty() && rounds > 0);
        let recip_table = RECIP_SEED_U16.as_ptr() as u32;
        let (routine, context): (ArmRoutine, [u32; 4]) = match op {
            Op::Loop => (pc_mb_loop, [0; 4]),
            Op::MulFx24_8 => (pc_mb_mul24_8, [0; 4]),
            Op::MulFx16_16 => (pc_mb_mul16_16, [0; 4]),
            Op::Recip => {
                assert!(inputs.iter().all(|&[depth, _]| depth > 128));
                (pc_mb_recip, [recip_table, 0, 0, 0])
            }
            Op::DivBios | Op::DivSoft => {
                assert!(inputs
                    .iter()
                    .all(|&[a, b]| b != 0 && !(a == i32::MIN && b == -1)));
                let routine: ArmRoutine = if op == Op::DivBios {
                    pc_mb_div_bios
                } else {
                    pc_mb_div_soft
                };
                (routine, [0; 4])
            }
            Op::SinCos => (pc_mb_sin_cos, [SIN_QUARTER_FX2_30.as_ptr() as u32, 0, 0, 0]),
            Op::ToEye => (
                pc_mb_to_eye,
                [
                    BENCH_EYE.position.x.to_bits() as u32,
                    BENCH_EYE.position.y.to_bits() as u32,
                    BENCH_EYE.sin().to_bits() as u32,
                    BENCH_EYE.cos().to_bits() as u32,
                ],
            ),
            Op::ProjectX => {
                assert!(inputs.iter().all(|&[_, depth]| depth > 128));
                (
                    pc_mb_project_x,
                    [
                        BENCH_VIEWPORT.centre_x() as u32,
                        BENCH_VIEWPORT.focal_x as u32,
                        recip_table,
                        0,
                    ],
                )
            }
            Op::RecipExact | Op::DivSmall | Op::DivTable | Op::Column | Op::ProjectY => {
                return None
            }
        };
        // SAFETY: the overlay holding the routine is loaded (`self` proves it); the routine
        // reads `inputs.len()` pairs from `inputs` `rounds` times and its context block, which
        // holds what the routine's header in asm/mathbench.s lists: table addresses of the
        // full tables (every index the routines form is inside them, by their masks) and
        // constants. It writes only its registers and its own stack frame.
        Some(unsafe {
            routine(
                inputs.as_ptr(),
                inputs.len() as u32,
                rounds,
                context.as_ptr(),
            )
        })
    }
}
