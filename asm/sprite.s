@ Sprite column kernel: the opaque runs (posts) of one sprite column, clipped to a window.
@ ARM code in IWRAM. Rust twin: src/raster/sprite.rs (its header gives the integers; identical
@ pixels, tested by the kernel check).
@
@ pc_sprite, r0 = *const SpriteJob:
@   +0  dst       *mut u8    row 0 of the screen column: page + 2*x (doubled) or page + (x & ~1)
@   +4  posts     *const u8  the column: post count, then each post (top, length, texels, pad)
@   +8  y_top     i32        screen row of texel row 0, 16.16
@   +12 scale     i32        rows per texel, 16.16
@   +16 iscale    u32        texels per row, 16.16
@   +20 clip      u32        window: first row in the low half, one past the last in the high
@   +24 colormap  *const u8  256-entry light row (an identity row draws unlit)
@   +28 blend     *const u8  the 256×256 table (behind·256 + front) the blending runs read
@   +32 run       address    the run routine that draws each post's rows (below)
@   +36 posts_end *const u8  one past the column's last byte: a post that would pass it ends
@                            the column (the Rust twin's rule), so no read leaves the column
@
@ pc_sprite walks the posts and finds each one's rows in the window and its first texel; a run
@ routine draws them. One post loop for every way of drawing keeps IWRAM small. Run routines
@ (not callable from Rust: their registers are these, not the C ABI's):
@   in   r0 the first pixel's byte in VRAM, r2 the post's texels, r12 v (16.16), r11 rows (≥ 1),
@        r5 iscale, r7 colormap, r1 the blend table
@   free r3, r4, r9, r10, r11; keep everything else, return with bx lr
@   pc_sprite_run_dbl           120 wide: STRB writes both bytes of the halfword
@   pc_sprite_run_even, _odd    240 wide: read-modify-write of the halfword, keeping the other byte
@   pc_sprite_run_blend_dbl, _blend_even, _blend_odd: the same, each pixel the blend of the lit
@                               texel over the one behind it, read back from VRAM
@ Cycles per pixel: docs/BENCH.md.

    .section .iwram.pc_sprite, "ax", %progbits
    .arm

    .global pc_sprite
    .type pc_sprite, %function
    .align 2
pc_sprite:
    push    {r4-r11, lr}
    add     r8, r0, #28
    ldmia   r8, {r8, r9, r10}
    push    {r8, r9, r10, r11}      @ .Lposts' frame: the blend table, the run routine, the
                                    @ column's end, and a word for its return address
    ldmia   r0, {r1-r7}             @ dst, posts, y_top, scale, iscale, clip, colormap
    mov     r8, r6, lsl #16
    mov     r8, r8, asr #16         @ r8 = clip top
    mov     r6, r6, asr #16         @ r6 = clip bottom
    bl      .Lposts
    add     sp, sp, #16
    pop     {r4-r11, lr}
    bx      lr
    .size pc_sprite, . - pc_sprite

@ .Lposts: the posts of one column, drawn (pc_sprite's loop, shared with pc_sprite_columns).
@ In: r1 dst, r2 the column's posts, r3 y_top, r4 scale, r5 iscale, r6 clip bottom, r8 clip
@ top, r7 colormap; [sp] the blend table, [sp, #4] the run routine, [sp, #8] the column's end,
@ [sp, #12] free (the return address goes there). Uses every register but sp.
.Lposts:
    str     lr, [sp, #12]
    ldrb    r9, [r2], #1            @ r9 = posts left
1:
    subs    r9, r9, #1
    bmi     9f
    ldr     r12, [sp, #8]           @ the column's end
    add     r10, r2, #2
    cmp     r10, r12
    bhi     9f                      @ the post's header would pass it
    ldrb    r10, [r2]               @ top
    ldrb    r11, [r2, #1]           @ length
    add     r2, r2, #2              @ r2 = the post's texels
    add     lr, r2, r11
    add     lr, lr, #1              @ lr = the next post
    cmp     lr, r12
    bhi     9f                      @ its texels and pad would pass it
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
    push    {r1, r3, r4, r9, lr}    @ the run may use r1, r3, r4, r9
    ldr     r1, [sp, #20]           @ the blend table
    ldr     r9, [sp, #24]           @ the run routine
    mov     lr, pc
    bx      r9
    pop     {r1, r3, r4, r9, lr}
8:
    mov     r2, lr
    b       1b
9:
    ldr     pc, [sp, #12]

@ pc_sprite_columns, r0 = *const SpriteBatchJob: the columns of one sprite image, each drawn as
@ pc_sprite draws it (src/raster/sprite.rs: SpriteBatch, its twin Canvas::sprite_columns):
@   +0  columns   *const BatchColumn  (20 bytes each: +0 x, +1 image column, +2 light row
@                                      (255: unlit), +4 clip, +8 y_top, +12 scale, +16 iscale)
@   +4  count     u32
@   +8  posts     *const u8  the image: its columns' offsets (4 bytes each), then their posts
@   +12 posts_len u32
@   +16 colormap  *const u8  light row 0 (rows of 256)
@   +20 identity  *const u8  the unlit row
@   +24 blend     *const u8
@   +28 page      *mut u8    row 0 of the page
@   +32 runs      3 addresses, the run routines for 120 wide, and 240 wide even and odd
@   +44 native    u32        0: 120 wide, 1: 240 wide
@ A column whose offset entry or offset lies outside the image, or whose light row is not one
@ of the 32, is skipped, as the twin skips it.
    .equ LIGHT_ROWS, 32
    .equ BATCH_COLUMN_BYTES, 20

    .global pc_sprite_columns
    .type pc_sprite_columns, %function
    .align 2
pc_sprite_columns:
    push    {r4-r11, lr}
    sub     sp, sp, #28             @ .Lposts' frame (16 bytes), then r9-r11 across it
    mov     r11, r0
    ldr     r0, [r11, #24]
    str     r0, [sp]                @ the blend table
    ldr     r10, [r11]              @ r10 = the next column
    ldr     r9, [r11, #4]           @ r9 = columns left
1:
    subs    r9, r9, #1
    bmi     9f
    ldrb    r4, [r10, #1]           @ image column
    ldr     r6, [r11, #8]           @ r6 = the image's bytes
    ldr     r5, [r11, #12]          @ r5 = their count
    add     r7, r6, r4, lsl #2      @ r7 = the column's offset entry
    add     r0, r7, #4
    add     r1, r6, r5              @ r1 = the image's end
    cmp     r0, r1
    bhi     8f
    ldrb    r0, [r7]
    ldrb    r2, [r7, #1]
    ldrb    r3, [r7, #2]
    ldrb    r12, [r7, #3]
    orr     r0, r0, r2, lsl #8
    orr     r0, r0, r3, lsl #16
    orr     r0, r0, r12, lsl #24    @ r0 = the column's offset
    cmp     r0, r5
    bhs     8f
    add     r2, r6, r0              @ r2 = the column's posts
    str     r1, [sp, #8]            @ the column's end
    ldrb    r1, [r10, #2]
    cmp     r1, #255
    ldreq   r7, [r11, #20]
    beq     2f
    cmp     r1, #LIGHT_ROWS
    bhs     8f
    ldr     r7, [r11, #16]
    add     r7, r7, r1, lsl #8      @ r7 = the colormap row
2:
    ldrb    r1, [r10]               @ x
    ldr     r0, [r11, #28]          @ the page
    ldr     r3, [r11, #44]
    cmp     r3, #0
    addeq   r0, r0, r1, lsl #1      @ 120 wide: both bytes of halfword x
    ldreq   r3, [r11, #32]
    beq     3f
    bic     r12, r1, #1
    add     r0, r0, r12             @ 240 wide: the halfword holding pixel x
    tst     r1, #1
    ldreq   r3, [r11, #36]
    ldrne   r3, [r11, #40]
3:
    str     r3, [sp, #4]            @ the run routine
    mov     r1, r0                  @ r1 = dst
    ldr     r6, [r10, #4]           @ clip
    mov     r8, r6, lsl #16
    mov     r8, r8, asr #16         @ r8 = clip top
    mov     r6, r6, asr #16         @ r6 = clip bottom
    add     r0, r10, #8
    ldmia   r0, {r3, r4, r5}        @ y_top, scale, iscale
    add     r0, sp, #16
    stmia   r0, {r9, r10, r11}
    bl      .Lposts
    add     r0, sp, #16
    ldmia   r0, {r9, r10, r11}
8:
    add     r10, r10, #BATCH_COLUMN_BYTES
    b       1b
9:
    add     sp, sp, #28
    pop     {r4-r11, lr}
    bx      lr
    .size pc_sprite_columns, . - pc_sprite_columns

    @ Looks up the lit texel of the row into r10 and steps v.
    .macro LIT_TEXEL
    ldrb    r10, [r2, r12, lsr #16]
    ldrb    r10, [r7, r10]
    add     r12, r12, r5
    .endm

    @ 120 wide: the remainder of rows % 4 one at a time, then blocks of 4.
    .global pc_sprite_run_dbl
    .type pc_sprite_run_dbl, %function
    .align 2
pc_sprite_run_dbl:
    mov     r3, r11, lsr #2
    ands    r11, r11, #3
    beq     2f
1:
    LIT_TEXEL
    strb    r10, [r0], #240
    subs    r11, r11, #1
    bne     1b
2:
    cmp     r3, #0
    bxeq    lr
3:
    .rept 4
    LIT_TEXEL
    strb    r10, [r0], #240
    .endr
    subs    r3, r3, #1
    bne     3b
    bx      lr
    .size pc_sprite_run_dbl, . - pc_sprite_run_dbl

    @ 240 wide: puts r10 into the byte `\odd` of the halfword in r9 and stores it, a row on.
    .macro STORE_NATIVE odd
    PUT_BYTE r9, r10, \odd
    strh    r9, [r0], #240
    .endm

    @ 240 wide: the byte `\odd` of each halfword.
    .macro RUN_NATIVE name, odd
    .global \name
    .type \name, %function
    .align 2
\name:
1:
    LIT_TEXEL
    ldrh    r9, [r0]
    STORE_NATIVE \odd
    subs    r11, r11, #1
    bne     1b
    bx      lr
    .size \name, . - \name
    .endm

    RUN_NATIVE pc_sprite_run_even, 0
    RUN_NATIVE pc_sprite_run_odd, 1

    .global pc_sprite_run_blend_dbl
    .type pc_sprite_run_blend_dbl, %function
    .align 2
pc_sprite_run_blend_dbl:
1:
    LIT_TEXEL
    ldrb    r9, [r0]
    add     r9, r10, r9, lsl #8
    ldrb    r10, [r1, r9]
    strb    r10, [r0], #240
    subs    r11, r11, #1
    bne     1b
    bx      lr
    .size pc_sprite_run_blend_dbl, . - pc_sprite_run_blend_dbl

    @ 240 wide, blending: one loop for both bytes of the halfword, r4 the byte's shift (0 for
    @ the even pixel, 8 for the odd), a few cycles a pixel dearer than a loop for each but half
    @ their IWRAM.
    .global pc_sprite_run_blend_odd
    .type pc_sprite_run_blend_odd, %function
    .align 2
pc_sprite_run_blend_odd:
    mov     r4, #8
    b       1f
    .size pc_sprite_run_blend_odd, . - pc_sprite_run_blend_odd

    .global pc_sprite_run_blend_even
    .type pc_sprite_run_blend_even, %function
pc_sprite_run_blend_even:
    mov     r4, #0
1:
    LIT_TEXEL
    ldrh    r9, [r0]
    mov     r3, r9, lsr r4
    and     r3, r3, #0xff
    add     r3, r10, r3, lsl #8
    ldrb    r10, [r1, r3]
    mov     r3, #0xff
    bic     r9, r9, r3, lsl r4
    orr     r9, r9, r10, lsl r4
    strh    r9, [r0], #240
    subs    r11, r11, #1
    bne     1b
    bx      lr
    .size pc_sprite_run_blend_even, . - pc_sprite_run_blend_even

    @ The caller (src/hw/kernels.rs) restores the assembler's ARM/Thumb state for the code the
    @ compiler emits after this file.
