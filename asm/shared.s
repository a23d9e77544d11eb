@ What the ARM loops and kernels share (asm/wall.s, asm/plane.s, asm/middle.s, asm/column.s,
@ asm/flat.s, asm/sprite.s, and the math benchmark's asm/mathbench.s), as assembler macros:
@ assembled at the start of each of them (src/hw/kernels.rs), and purged after each by
@ asm/shared_end.s.
@
@ COLUMN_REGISTER_ENTRY: where a doubled column kernel (asm/column.s) goes on after loading
@ its job: the wall loop at 120 wide (asm/wall.s, .Lstrip) pushes r4-r7 as the kernel does,
@ loads r1-r6 itself and enters there; the kernel's epilogue pops them. The kernels check it.
    .equ COLUMN_REGISTER_ENTRY, 8

@ FLAT_REGISTER_ENTRY: the same for a span kernel (asm/flat.s), entered by the plane loop at
@ 120 wide (asm/plane.s) with r1-r6 set and five words pushed, which the kernel's epilogue
@ pops into r4-r8 (the loop keeps nothing there).
    .equ FLAT_REGISTER_ENTRY, 8

@ DUFF_ENTER count, skip, log2, mul, shift: a kernel's loop over blocks of 2^\log2 unrolled
@ steps, its first block entered part-way (Duff's device): \count (at least 1) becomes the
@ blocks, the count rounded up, and the pc jumps over the (−count) mod 2^\log2 steps the first
@ block skips, each \mul · 2^\shift bytes (\mul 1, 3 or 5); \skip scratch. The block follows.
    .macro DUFF_ENTER count, skip, log2, mul, shift
    add     \skip, \count, #((1 << \log2) - 1)
    mov     \count, \skip, lsr #\log2
    and     \skip, \skip, #((1 << \log2) - 1)
    rsb     \skip, \skip, #((1 << \log2) - 1)
    .if \mul == 3
    add     \skip, \skip, \skip, lsl #1
    .elseif \mul == 5
    add     \skip, \skip, \skip, lsl #2
    .endif
    add     pc, pc, \skip, lsl #\shift
    mov     r0, r0                          @ never run: pc reads two instructions ahead
    .endm

@ RECIP_MANTISSA m, s, table, seed, a, b: from \m > 0, \m = 2^63/(\m·2^\s) (2^31 over the
@ normalised mantissa M = \m·2^\s in [2^31, 2^32)) and \s the shift; \table holds the seed
@ table (u16[1024], RECIP_SEED_U16) and is used as scratch after; \seed, \a, \b scratch.
@ The Rust twin is the function itself: the loops' ROM-versus-host frames compare them.

    .macro RECIP_MANTISSA m, s, table, seed, a, b
    RECIP_NORMALISE \m, \s
    RECIP_OF_NORMALISED \m, \table, \seed, \a, \b
    .endm

@ RECIP_NORMALISE m, s: \m > 0 shifted left by \s until its top bit is set (RECIP_MANTISSA's
@ first half), by compare-and-shift steps of 16, 8, 4, 2 and 1 bits.
    .macro RECIP_NORMALISE m, s
    mov     \s, #0
    .irp    bits, 16, 8, 4, 2, 1
    cmp     \m, #(1 << (32 - \bits))
    movlo   \m, \m, lsl #\bits
    addlo   \s, \s, #\bits
    .endr
    .endm

@ RECIP_OF_NORMALISED m, table, seed, a, b: \m in [2^31, 2^32) becomes 2^63/\m (RECIP_MANTISSA's
@ second half); \table as there.
    .macro RECIP_OF_NORMALISED m, table, seed, a, b
    @ mantissa_reciprocal: the seed for its top 10 bits, then r·(1 + δ + δ²).
    mov     \seed, \m, lsr #21
    bic     \seed, \seed, #0x400
    mov     \seed, \seed, lsl #1
    ldrh    \seed, [\table, \seed]
    mov     \a, \m, lsr #16                 @ high half
    mov     \b, \m, lsl #16
    mov     \b, \b, lsr #16                 @ low half
    mul     \table, \seed, \b
    mov     \table, \table, lsr #16
    mla     \b, \seed, \a, \table           @ m·seed / 2^16
    rsb     \b, \b, #0x80000000             @ δ · 2^31
    mov     \table, \b, asr #5
    mul     \a, \table, \table
    add     \b, \b, \a, asr #21             @ (δ + δ²) · 2^31
    mov     \table, \b, asr #8
    and     \b, \b, #0xff
    mul     \a, \seed, \b
    mov     \a, \a, asr #8
    mla     \b, \seed, \table, \a
    mov     \b, \b, asr #8                  @ the correction
    add     \m, \b, \seed, lsl #15          @ 2^31 / M
    .endm

@ MUL_2_30 dst, t, factor, hi: \dst = (\t·\factor) >> 30, the low word: a 2.30 fraction \t of
@ \factor, as the twins' `(i64 · i64) >> 30` narrowed to i32; \hi scratch.
    .macro MUL_2_30 dst, t, factor, hi
    smull   \dst, \hi, \t, \factor
    mov     \dst, \dst, lsr #30
    orr     \dst, \dst, \hi, lsl #2
    .endm

@ DEPTH_LIGHT_ROW level, depth: \level (a sector's light level plus the depth boost) becomes
@ the colormap row of \level − \depth/16 units (\depth: z' in 24.8), clamped to 0..255 and
@ shifted right by 3: render::light's light_row for Lighting::SectorDepth, as the loops' twins
@ compute it (`run_light`, `light_rule`).
    .macro DEPTH_LIGHT_ROW level, depth
    sub     \level, \level, \depth, asr #12
    bic     \level, \level, \level, asr #31
    cmp     \level, #255
    movgt   \level, #255
    mov     \level, \level, lsr #3
    .endm

@ PUT_BYTE half, byte, odd: \half with its byte \odd (1: the high one) replaced by \byte (under
@ 256), the other kept: a 240-wide pixel's read-modify-write of its VRAM halfword.
    .macro PUT_BYTE half, byte, odd
    .if \odd
    and     \half, \half, #0xff
    orr     \half, \half, \byte, lsl #8
    .else
    and     \half, \half, #0xff00
    orr     \half, \half, \byte
    .endif
    .endm
