@ A portal middle's columns: where each column's ray crosses the middle's wall, and the sprite
@ column the batch kernel draws there (asm/sprite.s), in ARM code in IWRAM (with the wall loop:
@ it costs its columns' set-up in the slowest frames, where the bench hall's grate is in view).
@ Rust twin: src/render/things.rs (middle_columns), which the host draws with; the
@ emulator's ROM-versus-host frame test compares the two pixel for pixel, and the kernel check
@ (src/kernel_check.rs) on random walls. The job is built and checked by MiddleRun::new and
@ handed over by src/hw/kernels.rs.
@
@ u32 pc_middle_columns(MiddleRun *r0): for columns run.x..run.end whose opening is not empty
@ and whose denominator is in 1..2^32, writes a BatchColumn at run.out and advances it; returns
@ how many it wrote. Power-of-two image widths only (the canvas checks).
@
@ MiddleRun (words):
@   0 numerator (i64, the column before x)   8 denominator (i64, the same)
@  16 numerator step (i64)  24 denominator step (i64)  32 x  36 end
@  40 opening (Window words, by column)  44 out (BatchColumn, 20 bytes)
@  48 za  52 dz  56 length  60 x offset (24.8)  64 wall reciprocal  68 wall shift  72 nearest
@  76 horizon (16.16)  80 above-eye·d_y  84 d_y  88 1/d_y (2.30)  92 width (a power of two)
@  96 light mode (0 off, 1 fixed, 2 depth)  100 light base (the row, or level + boost)
@ 104 least depth (24.8)  108 recip seeds (u16[1024])
@
@ Registers kept across columns: r4/r5 the numerator, r6/r7 the denominator, r8 the column,
@ r9 the output, r10 the opening, r11 the run.

    .equ MR_NUM, 0
    .equ MR_DEN, 8
    .equ MR_STEPS, 16
    .equ MR_X, 32
    .equ MR_END, 36
    .equ MR_OPENING, 40
    .equ MR_OUT, 44
    .equ MR_ZA, 48
    .equ MR_DZ, 52
    .equ MR_LENGTH, 56
    .equ MR_X_OFFSET, 60
    .equ MR_WALL_RECIP, 64
    .equ MR_WALL_SHIFT, 68
    .equ MR_NEAREST, 72
    .equ MR_HORIZON, 76
    .equ MR_ABOVE, 80
    .equ MR_FOCAL_Y, 84
    .equ MR_IFOCAL_Y, 88
    .equ MR_WIDTH, 92
    .equ MR_LIGHT_MODE, 96
    .equ MR_LIGHT_BASE, 100
    .equ MR_DEPTH_MIN, 104
    .equ MR_SEEDS, 108

    .section .iwram_render.pc_middle_columns, "ax", %progbits
    .arm
    .global pc_middle_columns
    .type pc_middle_columns, %function
    .align 2
pc_middle_columns:
    push    {r4-r11, lr}
    mov     r11, r0
    ldmia   r11, {r4-r7}
    ldr     r8, [r11, #MR_X]
    ldr     r9, [r11, #MR_OUT]
    ldr     r10, [r11, #MR_OPENING]

.Lm_column:
    ldr     r0, [r11, #MR_END]
    cmp     r8, r0
    bge     .Lm_done
    add     r0, r11, #MR_STEPS
    ldmia   r0, {r0-r3}
    adds    r4, r4, r0
    adc     r5, r5, r1
    adds    r6, r6, r2
    adc     r7, r7, r3
    @ The opening: none (top ≥ bottom), no column.
    ldr     r12, [r10, r8, lsl #2]
    mov     r0, r12, lsl #16
    mov     r0, r0, asr #16
    cmp     r0, r12, asr #16
    bge     .Lm_next
    @ The denominator in 1..2^32, or no column.
    cmp     r7, #0
    bne     .Lm_next
    cmp     r6, #0
    beq     .Lm_next
    str     r12, [r9, #4]                   @ clip
    @ t = ⌊n·2^30/d⌋ clamped to 0..2^30 (ray_fraction), in r0.
    cmp     r5, #0
    blt     .Lm_t_zero
    bgt     .Lm_t_one
    cmp     r4, #0
    beq     .Lm_t_zero
    cmp     r4, r6
    bhs     .Lm_t_one
    @ recip_with_bit_length(d) (src/math/recip.rs): 2^31 over d's mantissa, and its shift.
    mov     r0, r6
    ldr     r2, [r11, #MR_SEEDS]
    RECIP_MANTISSA r0, r1, r2, r3, lr, r12
    add     r0, r0, #1
    mov     r0, r0, lsr #1                  @ r0: 2^(30+p)/d
    rsb     r1, r1, #31                     @ r1: p
    @ The estimate (n·r) >> p (under 2^31).
    umull   r2, r3, r4, r0
    mov     r0, r2, lsr r1
    rsb     r1, r1, #32
    orr     r0, r0, r3, lsl r1              @ (a shift by 32 gives 0)
    @ Its remainder n·2^30 − t·d, brought into 0..d a unit at a time.
    umull   r2, r3, r0, r6
    mov     r12, r4, lsl #30
    mov     lr, r4, lsr #2
    subs    r12, r12, r2
    sbc     lr, lr, r3                      @ lr:r12 the remainder
1:
    cmp     lr, #0
    bge     2f
    sub     r0, r0, #1
    adds    r12, r12, r6
    adc     lr, lr, #0
    b       1b
2:
    cmp     lr, #0
    bne     3f
    cmp     r12, r6
    blo     .Lm_t_done
3:
    add     r0, r0, #1
    subs    r12, r12, r6
    sbc     lr, lr, #0
    b       2b
.Lm_t_zero:
    mov     r0, #0
    b       .Lm_t_done
.Lm_t_one:
    mov     r0, #0x40000000
.Lm_t_done:
    @ The image column: ((x offset + (t·length >> 30)) >> 8) & width mask, with x and the
    @ light row (below) in the first word.
    ldr     r1, [r11, #MR_LENGTH]
    MUL_2_30 r2, r0, r1, r3
    ldr     r1, [r11, #MR_X_OFFSET]
    add     r2, r2, r1
    ldr     r1, [r11, #MR_WIDTH]
    sub     r1, r1, #1
    and     r2, r1, r2, asr #8
    orr     r3, r8, r2, lsl #8              @ r3: x | column << 8
    @ The depth za + (t·dz >> 30), at least the least depth, in r1.
    ldr     r1, [r11, #MR_DZ]
    MUL_2_30 r2, r0, r1, r12
    ldr     r1, [r11, #MR_ZA]
    add     r1, r1, r2
    ldr     r2, [r11, #MR_DEPTH_MIN]
    cmp     r1, r2
    movlt   r1, r2
    @ The light row: none (0xff), the sector's, or of base − (depth >> 12) clamped to 0..255.
    ldr     r0, [r11, #MR_LIGHT_MODE]
    ldr     r2, [r11, #MR_LIGHT_BASE]
    cmp     r0, #1
    movlo   r2, #0xff
    blo     4f
    beq     4f
    DEPTH_LIGHT_ROW r2, r1
4:
    orr     r3, r3, r2, lsl #16
    str     r3, [r9]                        @ x, column, light row
    @ 1/z' = min(d·(wall reciprocal) >> wall shift, nearest), or nearest, in r0.
    ldr     r0, [r11, #MR_NEAREST]
    ldr     r2, [r11, #MR_WALL_RECIP]
    cmp     r2, #0
    beq     6f
    umull   r2, r3, r6, r2
    ldr     r12, [r11, #MR_WALL_SHIFT]
    subs    lr, r12, #32
    movge   r2, r3, lsr lr
    movge   r3, #0
    bge     5f
    mov     r2, r2, lsr r12
    rsb     lr, r12, #32
    orr     r2, r2, r3, lsl lr
    mov     r3, r3, lsr r12
5:
    cmp     r3, #0
    bne     6f
    cmp     r2, r0
    movlo   r0, r2
6:
    @ The top row: horizon + (above-eye·d_y·(1/z') >> 22), clamped to ±2^30.
    ldr     r2, [r11, #MR_ABOVE]
    smull   r2, r3, r0, r2
    mov     r2, r2, lsr #22
    orr     r2, r2, r3, lsl #10
    mov     r3, r3, asr #22
    ldr     r12, [r11, #MR_HORIZON]
    adds    r2, r2, r12
    adc     r3, r3, r12, asr #31
    @ r3:r2 > 2^30: 2^30; < −2^30: −2^30.
    cmp     r3, #0
    bgt     7f
    blt     8f
    cmp     r2, #0x40000000
    bls     9f
7:
    mov     r2, #0x40000000
    b       9f
8:
    cmn     r3, #1
    bne     10f
    cmp     r2, #0xc0000000
    bhs     9f
10:
    mov     r2, #0xc0000000
9:
    str     r2, [r9, #8]                    @ y_top
    @ Rows per texel (1/z')·d_y >> 14, in r2.
    ldr     r2, [r11, #MR_FOCAL_Y]
    smull   r2, r3, r0, r2
    mov     r2, r2, lsr #14
    orr     r2, r2, r3, lsl #18
    str     r2, [r9, #12]                   @ scale
    @ Texels per row depth·(1/d_y) >> 22, one less where its product with the rows per texel
    @ passes 2^32, and where it still does a thousandth less until it fits (texels_per_row).
    ldr     r0, [r11, #MR_IFOCAL_Y]
    smull   r0, r3, r1, r0
    mov     r0, r0, lsr #22
    orr     r0, r0, r3, lsl #10
    bic     r2, r2, r2, asr #31             @ the rows per texel, at least 0
    mov     lr, #32                         @ the first cut is 1 (a shift by 32 is 0)
11:
    umull   r3, r12, r2, r0
    cmp     r12, #1
    bhi     13f
    bne     12f
    cmp     r3, #0
    beq     12f
13:
    sub     r0, r0, r0, lsr lr
    sub     r0, r0, #1
    mov     lr, #10                         @ the next a thousandth and 1
    b       11b
12:
    str     r0, [r9, #16]                   @ iscale
    add     r9, r9, #20

.Lm_next:
    add     r8, r8, #1
    b       .Lm_column

.Lm_done:
    ldr     r0, [r11, #MR_OUT]
    sub     r0, r9, r0
    @ (out − start) / 20 by the reciprocal: 20·n < 2^16 here, so ×3277 >> 16 is exact.
    ldr     r1, =3277
    mul     r0, r1, r0
    mov     r0, r0, lsr #16
    str     r9, [r11, #MR_OUT]
    pop     {r4-r11, lr}
    bx      lr
    .ltorg
    .size pc_middle_columns, . - pc_middle_columns

    @ The caller (src/hw/kernels.rs) restores the assembler's ARM/Thumb state for the code the
    @ compiler emits after this file.
