@ Sprite column kernels: the opaque runs (posts) of one sprite column, clipped to a window.
@ ARM code in IWRAM. Rust twin: src/raster/sprite.rs (its header gives the integers; identical
@ pixels, tested by the kernel check).
@
@ r0 = *const SpriteJob:
@   +0  dst       *mut u8    row 0 of the screen column: page + 2*x (doubled) or page + (x & ~1)
@   +4  posts     *const u8  the column: post count, then each post (top, length, texels, pad)
@   +8  y_top     i32        screen row of texel row 0, 16.16
@   +12 scale     i32        rows per texel, 16.16
@   +16 iscale    u32        texels per row, 16.16
@   +20 clip      u32        window: first row in the low half, one past the last in the high
@   +24 colormap  *const u8  256-entry light row (an identity row draws unlit)
@
@ Variants: pc_sprite_dbl (120 wide: STRB writes both bytes of the halfword), pc_sprite_even and
@ pc_sprite_odd (240 wide: read-modify-write of the halfword, keeping the neighbour's byte).
@ Cycles per pixel: docs/BENCH.md.

    .macro SPRITE_PIXEL kind
    ldrb    r10, [r2, r12, lsr #16]
    ldrb    r10, [r7, r10]
    add     r12, r12, r5
    .ifc \kind, dbl
    strb    r10, [r0], #240
    .else
    ldrh    r11, [r0]
    .ifc \kind, odd
    and     r11, r11, #0xff
    orr     r11, r11, r10, lsl #8
    .else
    and     r11, r11, #0xff00
    orr     r11, r11, r10
    .endif
    strh    r11, [r0], #240
    .endif
    .endm

    .macro SPRITE_KERNEL name, kind
    .global \name
    .type \name, %function
    .align 2
\name:
    push    {r4-r11, lr}
    ldmia   r0, {r1-r7}             @ dst, posts, y_top, scale, iscale, clip, colormap
    mov     r8, r6, lsl #16
    mov     r8, r8, asr #16         @ r8 = clip top
    mov     r6, r6, asr #16         @ r6 = clip bottom
    ldrb    r9, [r2], #1            @ r9 = posts left
1:
    subs    r9, r9, #1
    bmi     9f
    ldrb    r10, [r2]               @ top
    ldrb    r11, [r2, #1]           @ length
    add     r2, r2, #2              @ r2 = the post's texels
    add     lr, r2, r11
    add     lr, lr, #1              @ lr = the next post
    mla     r12, r10, r4, r3        @ r12 = y0 = y_top + top·scale
    mla     r10, r11, r4, r12       @ r10 = y1 = y0 + length·scale
    add     r0, r12, #0x8000
    sub     r0, r0, #1
    mov     r0, r0, asr #16         @ r0 = first row, unclipped
    cmp     r0, r6
    bge     9f                      @ starts at or below the window: so do the later posts
    cmp     r0, r8
    movlt   r0, r8                  @ first = max(first, clip top)
    add     r10, r10, #0x8000
    sub     r10, r10, #1
    mov     r10, r10, asr #16
    cmp     r10, r6
    movgt   r10, r6                 @ end = min(end, clip bottom)
    subs    r11, r10, r0            @ r11 = rows
    ble     8f
    mov     r10, r0, lsl #16
    add     r10, r10, #0x8000
    sub     r10, r10, r12           @ r10 = (first << 16) + 0x8000 − y0
    umull   r12, r10, r5, r10       @ ·iscale, 64 bits
    mov     r12, r12, lsr #16
    orr     r12, r12, r10, lsl #16  @ r12 = v, 16.16
    rsb     r0, r0, r0, lsl #4
    add     r0, r1, r0, lsl #4      @ r0 = dst + first·240
    @ The pixel uses r10 and (read-modify-write) r11: the posts left and the next post wait on
    @ the stack while r9 counts rows and lr blocks. The remainder of rows % 4 one at a time,
    @ then blocks of 4.
    push    {r9, lr}
    mov     lr, r11, lsr #2
    ands    r9, r11, #3
    beq     3f
2:
    SPRITE_PIXEL \kind
    subs    r9, r9, #1
    bne     2b
3:
    movs    r9, lr
    beq     5f
4:
    .rept 4
    SPRITE_PIXEL \kind
    .endr
    subs    r9, r9, #1
    bne     4b
5:
    pop     {r9, lr}
8:
    mov     r2, lr
    b       1b
9:
    pop     {r4-r11, lr}
    bx      lr
    .size \name, . - \name
    .endm

    .section .iwram.pc_sprite, "ax", %progbits
    .arm
    SPRITE_KERNEL pc_sprite_dbl, dbl
    SPRITE_KERNEL pc_sprite_even, even
    SPRITE_KERNEL pc_sprite_odd, odd

    @ The caller (src/hw/kernels.rs) restores the assembler's ARM/Thumb state for the code the
    @ compiler emits after this file.
