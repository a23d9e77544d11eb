@ Column kernels (walls, strips, the sky): one texture column stepped down one screen column.
@ ARM code in IWRAM. Rust twins: src/raster/column.rs (identical pixels, tested; a pair
@ kernel's twin is its two columns drawn one after the other, `Canvas::column_pair`).
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
@                               wide. dst = page + row*240 + 2*x. The wall loop enters them
@                               past their job load, its registers set (COLUMN_REGISTER_ENTRY).
@   pc_col_pair_{unlit,lit}_hN  240-wide mode: two jobs, the columns x and x + 1 (x even) that
@                               share the halfwords (either may be left out), dst = page +
@                               row*240 + x each; below, at PAIR_KERNEL.
@ Per pixel (IWRAM texels and colormap): measured by the ROM's kernel check, see docs/BENCH.md.

    .macro PIXEL_DBL shift, lit
    ldrb    r0, [r2, r3, lsr #\shift]
    .if \lit
    ldrb    r0, [r6, r0]
    .endif
    add     r3, r3, r4
    strb    r0, [r1], #240
    .endm

    .macro COLUMN_KERNEL name, shift, lit, block_log2
    .global \name
    .type \name, %function
    .align 2
\name:
    push    {r4-r7}
    ldmia   r0, {r1-r6}
    @ The wall loop's entry (asm/wall.s, .Lstrip): r4-r7 pushed and r1-r6 loaded by it. The
    @ assembler refuses the .org if the two instructions above grow.
    .org    \name + COLUMN_REGISTER_ENTRY
    @ Blocks of 2^block_log2 rows, the first entered part-way: a lit row is 16 bytes, an
    @ unlit one 12.
    .if \lit
    DUFF_ENTER r5, r7, \block_log2, 1, 4
    .else
    DUFF_ENTER r5, r7, \block_log2, 3, 2
    .endif
3:
    .rept (1 << \block_log2)
    PIXEL_DBL \shift, \lit
    .endr
    subs    r5, r5, #1
    bne     3b
    pop     {r4-r7}
    bx      lr
    .size \name, . - \name
    .endm

    @ One pixel of one column of a pair by read-modify-write of its halfword, keeping the
    @ other byte (the even column's in the low byte): \dst, \tex, \v, \dv, \cmap its job's
    @ registers; r0 and r12 scratch.
    .macro PIXEL_ALONE dst, tex, v, dv, cmap, shift, lit, odd
    ldrb    r0, [\tex, \v, lsr #\shift]
    .if \lit
    ldrb    r0, [\cmap, r0]
    .endif
    ldrh    r12, [\dst]
    add     \v, \v, \dv
    PUT_BYTE r12, r0, \odd
    strh    r12, [\dst], #240
    .endm

    @ The rows of one column of a pair (\dst .. \cmap its job's registers, \count its rows)
    @ above the other's first (\other): on to \past if there are none (left), else falls
    @ through when its rows are done.
    .macro ALONE_ROWS dst, tex, v, dv, cmap, count, other, shift, lit, odd, past
9:
    cmp     \dst, \other
    bhs     \past
    PIXEL_ALONE \dst, \tex, \v, \dv, \cmap, \shift, \lit, \odd
    subs    \count, \count, #1
    bne     9b
    .endm

    @ One row of both columns: one halfword store, no read. r1 the even column's dst (the odd
    @ one's is the same); r0 and r7 scratch.
    .macro PIXEL_PAIR shift, lit
    ldrb    r0, [r2, r3, lsr #\shift]
    ldrb    r7, [r8, r9, lsr #\shift]
    add     r3, r3, r4
    add     r9, r9, r10
    .if \lit
    ldrb    r0, [r6, r0]
    ldrb    r7, [lr, r7]
    .endif
    orr     r0, r0, r7, lsl #8
    strh    r0, [r1], #240
    .endm

    @ A pair kernel: the columns 2k and 2k + 1 of a 240-wide page, r0 = *const [ColumnJob; 2]
    @ (the even column's job, then the odd one's), each dst = page + its top row·240 + 2k.
    @ A count of 0 leaves that column out. The rows only one column draws (above and below
    @ the other's) take a read-modify-write each; the rows both draw, one halfword store.
    @ The pixels are those of the two columns drawn one after the other by read-modify-write.
    .macro PAIR_KERNEL name, shift, lit
    .global \name
    .type \name, %function
    .align 2
\name:
    push    {r4-r11, lr}
    ldmia   r0!, {r1-r6}                    @ even: dst, texels, v, dv, count, colormap
    ldmia   r0, {r7-r11, lr}                @ odd
0:  @ A column left out, or done, is below every row: its dst the largest address.
    cmp     r5, #0
    mvneq   r1, #0
    cmp     r11, #0
    mvneq   r7, #0
1:  @ The even column's rows above the odd one's.
    ALONE_ROWS r1, r2, r3, r4, r6, r5, r7, \shift, \lit, 0, 2f
    mvn     r1, #0
2:  @ The odd column's rows above the even one's.
    ALONE_ROWS r7, r8, r9, r10, lr, r11, r1, \shift, \lit, 1, 3f
    b       0b
3:  @ Both at one row, or both done.
    cmn     r1, #1
    beq     5f
    cmp     r5, r11
    movlo   r12, r5
    movhs   r12, r11
    sub     r5, r5, r12
    sub     r11, r11, r12
    @ Four rows a turn, the first entered part-way: a lit row is 32 bytes, an unlit one 24.
    .if \lit
    DUFF_ENTER r12, r0, 2, 1, 5
    .else
    DUFF_ENTER r12, r0, 2, 3, 3
    .endif
4:
    .rept 4
    PIXEL_PAIR \shift, \lit
    .endr
    subs    r12, r12, #1
    bne     4b
    mov     r7, r1
    b       0b
5:
    pop     {r4-r11, lr}
    bx      lr
    .size \name, . - \name
    .endm

    @ Four banks share their IWRAM run addresses (linker.ld): by lighting, and by packing (a
    @ resolution draws with one). src/hw/kernels.rs (`ColumnBank`) copies in the bank a call
    @ needs before it calls into it.
    .section .iwram_columns_dbl_lit.pc_column, "ax", %progbits
    .arm
    .irp log2h, 3, 4, 5, 6, 7, 8
    COLUMN_KERNEL pc_col_dbl_lit_h\log2h, (32 - \log2h), 1, 4
    .endr

    .section .iwram_columns_dbl_unlit.pc_column, "ax", %progbits
    .arm
    .irp log2h, 3, 4, 5, 6, 7, 8
    COLUMN_KERNEL pc_col_dbl_unlit_h\log2h, (32 - \log2h), 0, 4
    .endr

    .section .iwram_columns_pair_lit.pc_column, "ax", %progbits
    .arm
    .irp log2h, 3, 4, 5, 6, 7, 8
    PAIR_KERNEL pc_col_pair_lit_h\log2h, (32 - \log2h), 1
    .endr

    .section .iwram_columns_pair_unlit.pc_column, "ax", %progbits
    .arm
    .irp log2h, 3, 4, 5, 6, 7, 8
    PAIR_KERNEL pc_col_pair_unlit_h\log2h, (32 - \log2h), 0
    .endr


    @ The caller (src/hw/kernels.rs) restores the assembler's ARM/Thumb state for the code the
    @ compiler emits after this file.
