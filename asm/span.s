@ Affine texture span kernels for a 64x64 row-major 8bpp texture (the test picture; the renderer's
@ lit span kernels build on the same shape). ARM code in the cartridge: only the test picture
@ draws with them, and IWRAM's bytes go to the renderer's hot code. The Rust twins are in src/raster/span.rs; tests require identical pixels.
@
@ Both take one argument, r0 = *const SpanJob:
@   +0  dst        *mut u16   halfword-aligned destination in Mode 4 VRAM (or any RAM)
@   +4  texture    *const u8  64*64 texels, row-major: texel(u, v) = texture[v*64 + u]
@   +8  u          u32 16.16  wraps modulo 64 texels
@   +12 v          u32 16.16  wraps modulo 64 texels
@   +16 du         u32 16.16  step per texel
@   +20 dv         u32 16.16
@   +24 halfwords  u32        halfwords to write, at least 1
@
@ Mode 4 VRAM ignores nothing on halfword stores, so both kernels write whole halfwords: one
@ texel twice (120-column modes, each logical pixel 2 screen pixels wide) or two texels (240).

    .section .text.pc_span, "ax", %progbits
    .arm
    .align 2

    .global pc_span64_doubled
    .type pc_span64_doubled, %function
pc_span64_doubled:
    push    {r4-r10, lr}
    ldmia   r0, {r1-r7}             @ dst, texture, u, v, du, dv, halfwords
    mov     r8, #63
1:
    and     r9, r8, r3, lsr #16     @ u texel column
    and     r10, r8, r4, lsr #16    @ v texel row
    add     r9, r9, r10, lsl #6
    ldrb    r9, [r2, r9]
    add     r3, r3, r5
    add     r4, r4, r6
    orr     r9, r9, r9, lsl #8      @ same index in both bytes: one logical pixel, 2 wide
    strh    r9, [r1], #2
    subs    r7, r7, #1
    bne     1b
    pop     {r4-r10, lr}
    bx      lr
    .size pc_span64_doubled, . - pc_span64_doubled

    .global pc_span64_pairs
    .type pc_span64_pairs, %function
pc_span64_pairs:
    push    {r4-r11, lr}
    ldmia   r0, {r1-r7}
    mov     r8, #63
1:
    and     r9, r8, r3, lsr #16
    and     r10, r8, r4, lsr #16
    add     r9, r9, r10, lsl #6
    ldrb    r9, [r2, r9]            @ left pixel: low byte
    add     r3, r3, r5
    add     r4, r4, r6
    and     r11, r8, r3, lsr #16
    and     r10, r8, r4, lsr #16
    add     r11, r11, r10, lsl #6
    ldrb    r11, [r2, r11]          @ right pixel: high byte
    add     r3, r3, r5
    add     r4, r4, r6
    orr     r9, r9, r11, lsl #8
    strh    r9, [r1], #2
    subs    r7, r7, #1
    bne     1b
    pop     {r4-r11, lr}
    bx      lr
    .size pc_span64_pairs, . - pc_span64_pairs

    @ The caller (src/hw/kernels.rs) restores the assembler's ARM/Thumb state for the code the
    @ compiler emits after this file.
