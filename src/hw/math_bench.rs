//! The math benchmark's IWRAM code: the overlay that holds it, and safe calls into it.
//!
//! The benchmark's IWRAM variants (the Thumb loops of `math_bench::iwram_loops` and the ARM
//! routines of `asm/mathbench.s`) are linked to run just above `.bss`, in the part of IWRAM the
//! stack only reaches when it is more than `stack_room − overlay size` deep, and stored in ROM
//! after the EWRAM image (`linker.ld`, section `.bench_iwram`). Only the math scene copies them
//! in ([`BenchCode::load`]), so the game keeps all of its stack room; the scene's own stack stays
//! far above the overlay (checked when loading).

use crate::math::tables::{RECIP_SEED_U16, SIN_QUARTER_FX2_30};
use crate::math_bench::{iwram_loops, Op, Pair, BENCH_EYE, BENCH_VIEWPORT};

extern "C" {
    static __bench_iwram_start: u8;
    static __bench_iwram_end: u8;
    /// linker.ld's reserve for the math scene's stack above the overlay (the symbol's address is
    /// the value).
    static MATH_SCENE_STACK: u8;
    static __bench_iwram_position_in_rom: u8;
}

/// Stack the math scene keeps free between its stack pointer and the overlay's end when it
/// loads the overlay. Its deepest calls (formatting a log line) reach about 612 bytes below that
/// frame: the scene prints its high-water mark (`stack used=…`, 868 bytes below the stack's top,
/// 256 of them above this frame, when this was set), and tests/emulator_math.rs checks it
/// against the linker's reserve.
const STACK_MARGIN: usize = 768;

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
    /// Copies the overlay from ROM into IWRAM. Panics if the caller's stack is within
    /// `STACK_MARGIN` bytes of the overlay's end (the copy would overwrite live stack, or the
    /// stack would later grow into the code).
    pub fn load() -> BenchCode {
        let start = &raw const __bench_iwram_start as usize;
        let end = &raw const __bench_iwram_end as usize;
        let source = &raw const __bench_iwram_position_in_rom as usize;
        let marker = core::hint::black_box(0u8);
        let stack = &raw const marker as usize;
        assert!(
            end + STACK_MARGIN <= stack,
            "the benchmark overlay (0x{start:08x}..0x{end:08x}) is too close to the stack (0x{stack:08x})"
        );
        for offset in (0..end - start).step_by(4) {
            // SAFETY: the linker script places the overlay's image at `source` in ROM and
            // reserves `start..end` in IWRAM for it, word-aligned; nothing else lives there (it
            // is above .bss, and the stack is more than STACK_MARGIN bytes above, checked).
            // Volatile, so the stores are kept and stay before the calls into the overlay (the
            // compiler does not know the code is run). A fence would do it too, but on the
            // ARMv4T it links to a missing `__sync_synchronize`.
            unsafe {
                let word = ((source + offset) as *const u32).read_volatile();
                ((start + offset) as *mut u32).write_volatile(word);
            }
        }
        BenchCode { bytes: end - start }
    }

    /// Where the overlay ends: the bottom of the math scene's stack room.
    pub fn end(&self) -> usize {
        (&raw const __bench_iwram_end as usize + 3) & !3
    }

    /// The stack the linker script keeps between the overlay's end and the stack's top
    /// (`MATH_SCENE_STACK`); printed with the scene's high-water mark for the tests.
    pub fn stack_reserve(&self) -> usize {
        &raw const MATH_SCENE_STACK as usize
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
