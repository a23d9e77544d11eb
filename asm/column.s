@ Column kernels (walls, strips, the sky): one texture column stepped down one screen column.
@ ARM code in IWRAM (the even read-modify-write ones in the cartridge, below). Rust twins: src/raster/column.rs (identical pixels, tested).
@
@ r0 = *const ColumnJob:
@   +0  dst       *mut u8    first pixel: page + row*240 + byte column (see the variants)
@   +4  texels    *const u8  the texture column, `height` texels top to bottom
@   +8  v         u32        position in the column as a fraction of its height, 0.32:
@                            texel = v >> (32 - log2(height)), so wrapping is free
@   +12 dv        u32        step per screen row, same format
@   +16 count     u32        rows to draw, at least 1
@   +20 colormap  *const u8  256-entry light row (lit variants only)
@
@ Variants, for each texture height 8..256 (the shift must be an immediate); the sky's unlit
@ columns take the lit ones through the identity row in a lit frame:
@   pc_col_dbl_{unlit,lit}_hN   120-wide modes: STRB to VRAM writes the byte to both halves of
@                               the halfword, so one store draws a logical pixel 2 screen pixels
@                               wide. dst = page + row*240 + 2*x.
@   pc_col_even_{unlit,lit}_hN  240-wide mode, even x: read-modify-write of the halfword, keeping
@   pc_col_odd_{unlit,lit}_hN   the neighbour's byte. dst = page + row*240 + (x & ~1).
@ Per pixel (IWRAM texels and colormap): measured by the ROM's kernel check, see docs/BENCH.md.

    .macro PIXEL_DBL shift, lit
    ldrb    r0, [r2, r3, lsr #\shift]
    .if \lit
    ldrb    r0, [r6, r0]
    .endif
    add     r3, r3, r4
    strb    r0, [r1], #240
    .endm

    .macro PIXEL_RMW shift, lit, odd
    ldrb    r0, [r2, r3, lsr #\shift]
    .if \lit
    ldrb    r0, [r6, r0]
    .endif
    ldrh    r12, [r1]
    add     r3, r3, r4
    .if \odd
    and     r12, r12, #0xff
    orr     r12, r12, r0, lsl #8
    .else
    and     r12, r12, #0xff00
    orr     r12, r12, r0
    .endif
    strh    r12, [r1], #240
    .endm

    @ One kernel: the remainder (count % block) one pixel at a time, then unrolled blocks of 4,
    @ to keep the IWRAM footprint of the 36 variants down (blocks of 8 for the 120-wide ones
    @ took 672 bytes more for about half a cycle a pixel less).
    .macro PIXEL_ANY kind, shift, lit
    .ifc \kind, dbl
    PIXEL_DBL \shift, \lit
    .endif
    .ifc \kind, even
    PIXEL_RMW \shift, \lit, 0
    .endif
    .ifc \kind, odd
    PIXEL_RMW \shift, \lit, 1
    .endif
    .endm

    .macro COLUMN_KERNEL name, kind, shift, lit, block_log2
    .global \name
    .type \name, %function
    .align 2
\name:
    push    {r4-r7}
    ldmia   r0, {r1-r6}
    ands    r7, r5, #((1 << \block_log2) - 1)
    beq     2f
1:
    PIXEL_ANY \kind, \shift, \lit
    subs    r7, r7, #1
    bne     1b
2:
    movs    r5, r5, lsr #\block_log2
    beq     4f
3:
    .rept (1 << \block_log2)
    PIXEL_ANY \kind, \shift, \lit
    .endr
    subs    r5, r5, #1
    bne     3b
4:
    pop     {r4-r7}
    bx      lr
    .size \name, . - \name
    .endm

    @ Two banks share their IWRAM run addresses (linker.ld): the lit kernels and the unlit ones.
    @ src/hw/kernels.rs copies in the bank a call needs before it calls into it.
    .section .iwram_kernels_lit.pc_column, "ax", %progbits
    .arm
    .irp log2h, 3, 4, 5, 6, 7, 8
    COLUMN_KERNEL pc_col_dbl_lit_h\log2h, dbl, (32 - \log2h), 1, 2
    COLUMN_KERNEL pc_col_odd_lit_h\log2h, odd, (32 - \log2h), 1, 2
    .endr

    .section .iwram_kernels_unlit.pc_column, "ax", %progbits
    .arm
    .irp log2h, 3, 4, 5, 6, 7, 8
    COLUMN_KERNEL pc_col_dbl_unlit_h\log2h, dbl, (32 - \log2h), 0, 2
    COLUMN_KERNEL pc_col_odd_unlit_h\log2h, odd, (32 - \log2h), 0, 2
    .endr

    @ The even read-modify-write kernels run from the cartridge: a 240-wide even column takes
    @ the byte-store kernel unless its odd neighbour is drawn already (the wall loop,
    @ asm/wall.s), so they draw only the pixels beside an edge, and their 2 KB of IWRAM earn
    @ more elsewhere (docs/BENCH.md's fast-memory table).
    .section .text.pc_col_even, "ax", %progbits
    .arm
    .irp log2h, 3, 4, 5, 6, 7, 8
    COLUMN_KERNEL pc_col_even_lit_h\log2h, even, (32 - \log2h), 1, 2
    COLUMN_KERNEL pc_col_even_unlit_h\log2h, even, (32 - \log2h), 0, 2
    .endr


    @ The caller (src/hw/kernels.rs) restores the assembler's ARM/Thumb state for the code the
    @ compiler emits after this file.
