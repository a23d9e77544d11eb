@ The math benchmark's ARM routines (src/math_bench.rs; the ROM's math scene, L held at power-on).
@ Each is the ARM version of one engine operation inside a loop shaped like the Rust benchmark
@ loop, so the ROM can time it from IWRAM next to the Thumb code the compiler makes of the Rust
@ function. Their Rust twins are `math_bench::Op::twin`; tests/emulator_math.rs requires the same
@ results for every operand pair.
@
@ They live in the benchmark's IWRAM overlay (section .bench_iwram, see linker.ld), which only the
@ math scene loads, so they cost the game no IWRAM.
@
@ Every routine: r0 = *const [i32; 2] pairs, r1 = pairs per round (>= 1), r2 = rounds (>= 1),
@ r3 = the routine's context: a block of words (a table's address, constants), or unused. Returns in r0 the
@ wrapping sum of the operation's results over all rounds and pairs.
@
@ Registers in the loop: r4 = first pair, r5 = pairs per round, r8 = sum, r9 = pair pointer,
@ r10 = pairs left in this round; the rounds left sit on the stack (one load and store per round,
@ not per pair). An operation gets the pair in r0 (a) and r1 (b) and may use r0-r3, r6, r7, r11,
@ r12 and lr; its constants are loaded from r3 into some of those before the loop.
@
@ ARMv4 MUL/MLA need Rd != Rm and SMULL/SMLAL need RdLo, RdHi and Rm distinct: every multiply
@ below is written that way.

    .section .bench_iwram.arm, "ax", %progbits
    .arm
    .align 2

.macro BENCH_BEGIN name
    .global \name
    .type \name, %function
\name:
    push    {r4-r11, lr}
    push    {r2, r3}                @ [sp] = rounds left
    mov     r4, r0
    mov     r5, r1
    mov     r8, #0
.endm

@ Starts a round, then loads the next pair into r0, r1. No operation defines labels 1 or 2.
.macro BENCH_LOOP
1:
    mov     r9, r4
    mov     r10, r5
2:
    ldmia   r9!, {r0, r1}
.endm

@ Adds the operation's result (in `result`) to the sum and closes both loops.
.macro BENCH_END name, result
    add     r8, r8, \result
    subs    r10, r10, #1
    bne     2b
    ldr     r2, [sp]
    subs    r2, r2, #1
    str     r2, [sp]
    bne     1b
    mov     r0, r8
    add     sp, sp, #8
    pop     {r4-r11, lr}
    bx      lr
    .size \name, . - \name
.endm

@ out = the 64-bit hi:lo rounded to nearest (ties toward +inf) at bit `shift`, low 32 bits
@ (src/math/fixed.rs: round_shift_i64, then the narrowing cast). Clobbers lo, hi.
.macro ROUND_SHIFT out, lo, hi, shift
    adds    \lo, \lo, #(1 << (\shift - 1))
    adc     \hi, \hi, #0
    mov     \out, \lo, lsr #\shift
    orr     \out, \out, \hi, lsl #(32 - \shift)
.endm

@ out = recip_pow2(n, 38) for n > 128: Fx24_8::recip_fx2_30 (src/math/recip.rs), through the
@ renderer's own RECIP_MANTISSA (asm/shared.s, assembled with this file), then rounded to the
@ result's scale. Clobbers n (it becomes 2^31 over the mantissa), t2, t3, t5 and tab (the seed
@ table's address, used as scratch as the wall loop's is): callers load it before each use.
.macro RECIP38 out, n, t2, t3, t5, tab
    RECIP_MANTISSA \n, \t2, \tab, \t3, \t5, \out
    rsbs    \t2, \t2, #24           @ right shift 62 - 38 - shift, 0 ..= 24 for n > 128
    moveq   \out, \n
    subne   \t2, \t2, #1            @ round to nearest: keep one more bit, add one, drop it
    movne   \out, \n, lsr \t2
    addne   \out, \out, #1
    movne   \out, \out, lsr #1
.endm

@ out = sin(ang) in 16.16 from the 1025-entry 2.30 quarter-wave table at `tab`, interpolated on
@ the low 4 bits of the 14-bit quadrant offset (src/math/angle.rs: Angle::sin). Only bits 0-15 of
@ `ang` count. Clobbers t1, t2.
.macro SIN out, ang, t1, t2, tab
    mov     \t1, \ang, lsl #18
    mov     \t1, \t1, lsr #18       @ offset in the quadrant
    tst     \ang, #0x4000
    rsbne   \t1, \t1, #0x4000       @ quadrants 1 and 3 run the quarter wave backwards
    mov     \t2, \t1, lsr #4        @ segment
    ldr     \out, [\tab, \t2, lsl #2]
    ands    \t1, \t1, #15           @ weight; at 0 the next entry is not read (it may not exist)
    addne   \t2, \tab, \t2, lsl #2
    ldrne   \t2, [\t2, #4]
    subne   \t2, \t2, \out
    mulne   \t1, \t2, \t1
    addne   \t1, \t1, #8
    addne   \out, \out, \t1, asr #4
    add     \out, \out, #0x2000     @ 2.30 -> 16.16, rounded
    mov     \out, \out, asr #14
    tst     \ang, #0x8000
    rsbne   \out, \out, #0          @ quadrants 2 and 3 are negative
.endm

@ The loop alone: a + b.
BENCH_BEGIN pc_mb_loop
BENCH_LOOP
    add     r0, r0, r1
BENCH_END pc_mb_loop, r0

@ Fx24_8::mul: (a * b + 2^7) >> 8.
BENCH_BEGIN pc_mb_mul24_8
BENCH_LOOP
    smull   r2, r3, r0, r1
    ROUND_SHIFT r0, r2, r3, 8
BENCH_END pc_mb_mul24_8, r0

@ Fx16_16::mul: (a * b + 2^15) >> 16.
BENCH_BEGIN pc_mb_mul16_16
BENCH_LOOP
    smull   r2, r3, r0, r1
    ROUND_SHIFT r0, r2, r3, 16
BENCH_END pc_mb_mul16_16, r0

@ Fx24_8::recip_fx2_30 of a. Context: the seed table's address (math::tables::RECIP_SEED_U16).
BENCH_BEGIN pc_mb_recip
BENCH_LOOP
    ldr     r7, [sp, #4]            @ the context
    ldr     r7, [r7]
    RECIP38 r6, r0, r1, r2, r3, r7
BENCH_END pc_mb_recip, r6

@ The BIOS Div call from ARM code: a / b, truncated. r0-r3 are the call's; the loop's state is
@ in r4 and up.
BENCH_BEGIN pc_mb_div_bios
BENCH_LOOP
    swi     #0x060000
BENCH_END pc_mb_div_bios, r0

@ a / b, truncated toward zero, by shift and subtract: find the quotient's top bit s by a
@ binary search (five compare-and-shift steps), then jump into a 32-step unrolled restoring
@ division at step s, three instructions (three cycles) per quotient bit.
BENCH_BEGIN pc_mb_div_soft
BENCH_LOOP
    eor     r2, r0, r1              @ sign of the quotient in bit 31
    cmp     r0, #0
    rsblt   r0, r0, #0              @ |a|
    cmp     r1, #0
    rsblt   r1, r1, #0              @ |b|
    mov     r3, #0                  @ s: the largest with |b| << s <= |a| (0 if none)
    mov     r12, r1
    cmp     r12, r0, lsr #16
    movls   r12, r12, lsl #16
    addls   r3, r3, #16
    cmp     r12, r0, lsr #8
    movls   r12, r12, lsl #8
    addls   r3, r3, #8
    cmp     r12, r0, lsr #4
    movls   r12, r12, lsl #4
    addls   r3, r3, #4
    cmp     r12, r0, lsr #2
    movls   r12, r12, lsl #2
    addls   r3, r3, #2
    cmp     r12, r0, lsr #1
    addls   r3, r3, #1
    rsb     r3, r3, #31
    add     r3, r3, r3, lsl #1      @ steps skipped x 3 instructions
    mov     r6, #0                  @ quotient
    add     pc, pc, r3, lsl #2      @ pc reads 8 ahead: lands on the first kept step
    nop
    .irp step, 31, 30, 29, 28, 27, 26, 25, 24, 23, 22, 21, 20, 19, 18, 17, 16, 15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0
    cmp     r0, r1, lsl #\step      @ |b| << step never overflows: step <= s
    subcs   r0, r0, r1, lsl #\step
    adc     r6, r6, r6
    .endr
    cmp     r2, #0
    rsblt   r6, r6, #0
BENCH_END pc_mb_div_soft, r6

@ Angle::sin_cos of a, folded as sin ^ rotate_left(cos, 16). Context: the quarter-wave table's
@ address (math::tables::SIN_QUARTER_FX2_30).
BENCH_BEGIN pc_mb_sin_cos
    ldr     r7, [r3]
BENCH_LOOP
    SIN     r11, r0, r1, r2, r7
    add     r0, r0, #0x4000         @ cos(a) = sin(a + quarter turn)
    SIN     r12, r0, r1, r2, r7
    eor     r0, r11, r12, ror #16
BENCH_END pc_mb_sin_cos, r0

@ EyeFrame::to_eye of the map point (a, b), folded as x' ^ rotate_left(z', 16). Context: eye x,
@ eye y (24.8), sin, cos (16.16). x' = dx (-sin) + dy cos, z' = dx cos + dy sin, each rounded
@ once from its 64-bit sum.
BENCH_BEGIN pc_mb_to_eye
    ldmia   r3, {r6, r7, r11, r12}
BENCH_LOOP
    sub     r0, r0, r6              @ dx
    sub     r1, r1, r7              @ dy
    smull   r2, r3, r0, r12
    smlal   r2, r3, r1, r11
    ROUND_SHIFT lr, r2, r3, 16      @ z'
    rsb     r0, r0, #0              @ (-dx) sin = dx (-sin), exactly
    smull   r2, r3, r0, r11
    smlal   r2, r3, r1, r12
    ROUND_SHIFT r0, r2, r3, 16      @ x'
    eor     r0, r0, lr, ror #16
BENCH_END pc_mb_to_eye, r0

@ Viewport::projected_x_saturating of the eye point (x' = a, z' = b): (cx z' + d x') * (1/z')
@ rounded to 16.16 and clamped. Context: cx, d (focal length in columns), the seed table's
@ address.
BENCH_BEGIN pc_mb_project_x
    ldmia   r3, {r6, r7}
BENCH_LOOP
    mul     r2, r1, r6              @ cx z'
    mla     r2, r0, r7, r2          @ + d x'
    ldr     r11, [sp, #4]           @ the context
    ldr     r11, [r11, #8]
    RECIP38 r0, r1, r3, r12, lr, r11
    smull   r1, r3, r2, r0
    ROUND_SHIFT r0, r1, r3, 22
    mov     r12, r3, asr #21        @ fits i32 iff bits 21-31 of the high word agree
    add     r12, r12, #1
    cmp     r12, #1
    movhi   r0, r3, asr #31         @ else clamp: 0x7fffffff above, 0x80000000 below
    mvnhi   r0, r0
    eorhi   r0, r0, #0x80000000
BENCH_END pc_mb_project_x, r0

@ linker.ld ends .iwram_render with this empty word-aligned section, so that the overlay's image,
@ loaded right after it, starts on a word even when the renderer is Thumb code (whose size may
@ be a multiple of 2 only). "R": kept, though nothing refers to it.
    .section .iwram_render_end, "aR", %progbits
    .balign 4

    @ The caller (src/hw/kernels.rs) restores the assembler's ARM/Thumb state for the code the
    @ compiler emits after this file.
