@ Floor and ceiling span kernels: one screen row across a square 2^k x 2^k flat, stepping a
@ packed texture position (the layout Doom's R_DrawSpan uses). ARM code in IWRAM.
@ Rust twins: src/raster/flat.rs (identical pixels, tested).
@
@ The position packs both coordinates in one register, each integer part directly above its
@ fraction so one ADD steps both:
@   bits 32-k .. 31  : u integer (k bits)      bits 16 .. 31-k : u fraction
@   bits 16-k .. 15  : v integer (k bits)      bits 0 .. 15-k  : v fraction
@ texel index = v*2^k + u = ((pos >> (16-2k)) & ((2^k-1) << k)) | (pos >> (32-k)).
@
@ r0 = *const FlatJob:
@   +0  dst       *mut u16   halfword address of the first output halfword
@   +4  texels    *const u8  2^k * 2^k texels, row-major
@   +8  pos       u32        packed position of the first pixel
@   +12 step      u32        packed step per logical pixel
@   +16 count     u32        halfwords to write, at least 1
@   +20 colormap  *const u8  256-entry light row (lit variants only)
@
@ Variants for k = 3..6:
@   pc_flat_dbl_{unlit,lit}_kK    one logical pixel per halfword (120-wide modes; STRB mirrors)
@   pc_flat_pair_{unlit,lit}_kK   two logical pixels per halfword (240 mode), left one low
@ Per pixel (IWRAM texels and colormap): measured by the ROM's kernel check, see docs/BENCH.md.

    .macro FLAT_TEXEL k, lit, out
    and     \out, r7, r3, lsr #(16 - 2 * \k)
    orr     \out, \out, r3, lsr #(32 - \k)
    ldrb    \out, [r2, \out]
    .if \lit
    ldrb    \out, [r6, \out]
    .endif
    add     r3, r3, r4
    .endm

    .macro FLAT_OUT kind, k, lit
    .ifc \kind, dbl
    FLAT_TEXEL \k, \lit, r0
    strb    r0, [r1], #2
    .else
    FLAT_TEXEL \k, \lit, r0
    FLAT_TEXEL \k, \lit, r12
    orr     r0, r0, r12, lsl #8
    strh    r0, [r1], #2
    .endif
    .endm

    @ Blocks of 8 output halfwords for the doubled kernels, of 4 (8 pixels) for the pair ones.
    .macro FLAT_KERNEL name, kind, k, lit, block_log2
    .global \name
    .type \name, %function
    .align 2
\name:
    push    {r4-r8}
    ldmia   r0, {r1-r6}
    @ The plane loop's entry (FLAT_REGISTER_ENTRY): the assembler refuses the .org if the two
    @ instructions above grow.
    .org    \name + FLAT_REGISTER_ENTRY
    mov     r7, #((1 << \k) - 1)
    mov     r7, r7, lsl #\k
    @ Blocks of 2^block_log2 halfwords, the first entered part-way: FLAT_OUT is 6 or 5
    @ instructions a doubled halfword (lit or not), 12 or 10 a pair's: 3·8 or 5·4 bytes,
    @ 3·16 or 5·8.
    .ifc \kind, dbl
    DUFF_ENTER r5, r8, \block_log2, (5 - 2 * \lit), (2 + \lit)
    .else
    DUFF_ENTER r5, r8, \block_log2, (5 - 2 * \lit), (3 + \lit)
    .endif
3:
    .rept (1 << \block_log2)
    FLAT_OUT \kind, \k, \lit
    .endr
    subs    r5, r5, #1
    bne     3b
    pop     {r4-r8}
    bx      lr
    .size \name, . - \name
    .endm

    @ The lit and the unlit bank (see asm/column.s).
    .section .iwram_kernels_lit.pc_flat, "ax", %progbits
    .arm
    .irp k, 3, 4, 5, 6
    FLAT_KERNEL pc_flat_dbl_lit_k\k, dbl, \k, 1, 3
    FLAT_KERNEL pc_flat_pair_lit_k\k, pair, \k, 1, 2
    .endr

    .section .iwram_kernels_unlit.pc_flat, "ax", %progbits
    .arm
    .irp k, 3, 4, 5, 6
    FLAT_KERNEL pc_flat_dbl_unlit_k\k, dbl, \k, 0, 3
    FLAT_KERNEL pc_flat_pair_unlit_k\k, pair, \k, 0, 2
    .endr

    @ The caller (src/hw/kernels.rs) restores the assembler's ARM/Thumb state for the code the
    @ compiler emits after this file.
