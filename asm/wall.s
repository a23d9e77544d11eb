@ The wall loop: a run of a stepped wall's columns, Doom's R_RenderSegLoop, in ARM code in IWRAM.
@ Rust twin: the renderer's own column loop (src/render/walk.rs, draw_stepped_columns, through
@ column_windows, texture_column and draw_strip), which the host draws with; the emulator's
@ ROM-versus-host frame test compares the two pixel for pixel. The job is built and checked by
@ src/raster/wall_run.rs (WallRun) and handed over by src/hw/kernels.rs.
@
@ u32 pc_wall_run(WallRun *r0): draws columns run.column..run.stop and returns 0; or, at a
@ column whose drawn strips need a mip level outside their ranges, writes its windows, stores
@ the strips' rows in run.resume_rows with run.resume = 1 and the mip ratio in run.miss_ratio,
@ and returns 1. Called again with run.resume = 1 it draws those strips first. On return
@ run.column and the accumulators are those of the column it stopped at.
@
@ WallRun (words):
@   0 inverse_depth  4 inverse_depth_step  8 along_over_depth  12 along_over_depth_step
@  16..28 negated_scales[4] (−d_y·h, 24.8)  32 row_base (the rows' base's high word)  36 height
@  40 column  44 stop  48 kind (0 solid, 1 opening, 2 portal | upper << 8 | lower << 9)
@  52 clip  56 ceiling  60 floor (Window arrays: a word per column, top in the low half)
@  64 length  68 x_offset  72 inverse_focal_y  76 light_mode (0 off, 1 fixed, 2 depth)
@  80 light_base  84 colormap  88 recip_seeds (u16[1024])  92 horizon_row  96 page  100 native
@     (NATIVE_BIT where two pixels share a halfword, else 0)
@ 104 column_pixels  108 strips_drawn  112 miss_ratio  116 resume  120 resume_rows[2]
@ 128 strips[0], 156 strips[1]: +0 eye_to_anchor (low word)  +4 shape (level | log2 height << 8
@     | log2 base height << 16)  +8 ratio_low  +12 ratio_high  +16 width_mask  +20 texels
@     +24 kernel (120 wide: the doubled one; 240 wide: the pair kernel)
@ 184 planes_seen (1: a ceiling window had rows, 2: a floor window)
@
@ Registers kept across columns: r11 the run, r10 1/z', r9 the column, r5 the pixels drawn,
@ (from bit 16) the strips drawn, in bit 29 whether two pixels share a halfword (240 wide), and
@ in bits 30 and 31 whether a ceiling and a floor window had rows. The kernels keep r4-r11. At
@ 120 wide each strip is drawn at once, its doubled kernel entered with its registers set
@ (COLUMN_REGISTER_ENTRY, asm/shared.s): no job is written. At 240 wide the stack holds, per
@ strip, two kernel jobs (asm/column.s), those of an even column and of the odd one beside
@ it, which share VRAM halfwords: an even column's strip waits in its job (rows in it while
@ it waits) until the odd column's is set up, and the pair kernel draws both, one halfword
@ store a row where both have rows; one the odd column leaves alone is drawn after it (or
@ when the run ends or stops). The stack holds the column's strip rows too.

    .equ RUN_INV, 0
    .equ RUN_INV_STEP, 4
    .equ RUN_AOD, 8
    .equ RUN_AOD_STEP, 12
    .equ RUN_NEGATED_SCALE0, 16
    .equ RUN_NEGATED_SCALE2, 24
    .equ RUN_ROW_BASE, 32
    .equ RUN_HEIGHT, 36
    .equ RUN_COLUMN, 40
    .equ RUN_STOP, 44
    .equ RUN_KIND, 48
    .equ RUN_CLIP, 52
    .equ RUN_CEILING, 56
    .equ RUN_FLOOR, 60
    .equ RUN_LENGTH, 64
    .equ RUN_X_OFFSET, 68
    .equ RUN_IFOC, 72
    .equ RUN_LIGHT_MODE, 76
    .equ RUN_LIGHT_BASE, 80
    .equ RUN_COLORMAP, 84
    .equ RUN_SEEDS, 88
    .equ RUN_HORIZON_ROW, 92
    .equ RUN_PAGE, 96
    .equ RUN_NATIVE, 100
    .equ RUN_PIXELS, 104
    .equ RUN_STRIPS, 108
    .equ RUN_MISS, 112
    .equ RUN_RESUME, 116
    .equ RUN_RESUME_ROWS, 120
    .equ RUN_STRIP0, 128
    .equ RUN_STRIP1, 156
    .equ RUN_PLANES, 184

    .equ STRIP_EYE, 0
    .equ STRIP_SHAPE, 4
    .equ STRIP_LOW, 8
    .equ STRIP_HIGH, 12
    .equ STRIP_WMASK, 16
    .equ STRIP_TEXELS, 20
    .equ STRIP_KERNEL, 24

    @ The stack frame: the strips' rows, t/z' less x times its step, the last reciprocal's
    @ shift (0 at first), and each strip's two
    @ kernel jobs (24 bytes each: the even column's, then the odd one's; +16 the rows).
    .equ SP_ROWS0, 0
    .equ SP_ROWS1, 4
    .equ SP_AOD, 8
    .equ SP_SHIFT, 12
    .equ SP_SLOTS0, 16
    .equ SP_SLOTS1, 64
    .equ SLOT_COUNT_EVEN, 16
    .equ SLOT_COUNT_ODD, 40
    .equ SP_FRAME, 112

    @ r5's bit for a page whose halfwords hold two pixels.
    .equ NATIVE_BIT, 0x20000000

    @ \dst = clamp((base − scale·inv) >> 38, 0, height), WallSteps::row, with \negated the
    @ scale negated, \base the base's high word (its low word is ROW_BASE_LOW) and r10 = 1/z';
    @ \lo, \hi scratch (\dst may be \negated).
    .macro WALL_ROW dst, negated, base, height, lo, hi
    mvn     \lo, #0x20000000               @ ROW_BASE_LOW
    mov     \hi, \base
    smlal   \lo, \hi, \negated, r10
    mov     \dst, \hi, asr #6
    bic     \dst, \dst, \dst, asr #31
    cmp     \dst, \height
    movgt   \dst, \height
    .endm

    @ Sets up the strip at \strip, rows in r0, in its jobs at \slots, through .Lstrip.
    .macro WALL_STRIP strip, slots
    add     r2, r11, #\strip
    mov     r3, #(\slots + 8)
    bl      .Lstrip
    .endm

    @ Stops the run unless the strip at \strip's level selects the mip ratio r7 >> 6 (r7 the
    @ high word of z'/d_y). Keeps r0.
    .macro WALL_LEVEL_CHECK strip
    mov     r12, r7, asr #6
    add     r2, r11, #\strip + STRIP_LOW
    ldmia   r2, {r1, r2}                    @ the level's lowest and highest ratio
    cmp     r12, r1
    blt     .Lmiss
    cmp     r12, r2
    bgt     .Lmiss
    .endm

    @ \t = twice the row offset of row \top from the horizon, plus one: 2(top − cy) + 1, signed.
    @ Uses r0.
    .macro WALL_ROW_OFFSET t, top
    ldr     r0, [r11, #RUN_HORIZON_ROW]
    sub     \t, \top, r0
    mov     \t, \t, lsl #1
    add     \t, \t, #1
    .endm

    @ \dst = a strip's v at the row whose WALL_ROW_OFFSET is \t: (eye_to_anchor +
    @ (t·z'/d_y >> 31)) << (24 − base log2), low words, with r2 the strip and r6/r7 z'/d_y.
    @ Leaves the strip's shape in \sh (it may be \t); \t and \s scratch.
    .macro WALL_STRIP_V dst, t, s, sh
    umull   \dst, \s, r6, \t
    cmp     \t, #0
    sublt   \s, \s, r6                      @ a negative factor read as unsigned: take it back
    mla     \s, \t, r7, \s
    mov     \dst, \dst, lsr #31
    orr     \dst, \dst, \s, lsl #1
    ldr     \t, [r2, #STRIP_EYE]
    add     \dst, \dst, \t
    ldr     \sh, [r2, #STRIP_SHAPE]
    mov     \s, \sh, lsr #16               @ log2 of the base height
    rsb     \s, \s, #24
    mov     \dst, \dst, lsl \s
    .endm

    @ \dst = the strip's texel column: ((u >> 8) >> level) & width mask, 2^h texels each, with
    @ r4 u and \sh the shape; \t (it may be r4) and \s scratch.
    .macro WALL_STRIP_TEXELS dst, t, s, sh
    and     \s, \sh, #0xff
    mov     \dst, r4, asr #8
    ldr     \t, [r2, #STRIP_WMASK]
    and     \dst, \t, \dst, asr \s
    mov     \s, \sh, lsr #8
    and     \s, \s, #0xff
    ldr     \t, [r2, #STRIP_TEXELS]
    add     \dst, \t, \dst, lsl \s
    .endm

    @ \dst = dv = z'/d_y >> (6 + base log2), low word, with \sh the shape (kept); \s scratch.
    .macro WALL_STRIP_DV dst, s, sh
    mov     \s, \sh, lsr #16
    add     \s, \s, #6
    mov     \dst, r6, lsr \s
    rsb     \s, \s, #32
    orr     \dst, \dst, r7, lsl \s
    .endm

    .section .iwram_render.pc_wall_run, "ax", %progbits
    .arm
    .global pc_wall_run
    .type pc_wall_run, %function
    .align 2
pc_wall_run:
    push    {r4-r11, lr}
    sub     sp, sp, #SP_FRAME
    mov     r11, r0
    ldr     r9, [r11, #RUN_COLUMN]
    ldr     r10, [r11, #RUN_INV]
    @ t/z' at column x is base + x·step: the base, wrapping like the steps.
    ldr     r0, [r11, #RUN_AOD]
    ldr     r1, [r11, #RUN_AOD_STEP]
    mul     r2, r9, r1
    sub     r0, r0, r2
    str     r0, [sp, #SP_AOD]
    @ No strip waits; no pixels or strips drawn yet, and the packing's bit.
    mov     r0, #0
    str     r0, [sp, #SP_SHIFT]
    str     r0, [sp, #SP_SLOTS0 + SLOT_COUNT_EVEN]
    str     r0, [sp, #SP_SLOTS1 + SLOT_COUNT_EVEN]
    ldr     r5, [r11, #RUN_NATIVE]
    ldr     r0, [r11, #RUN_RESUME]
    cmp     r0, #0
    beq     .Lcolumn
    @ Started again at a column whose windows are written: its strips.
    mov     r1, #0
    str     r1, [r11, #RUN_RESUME]
    ldr     r0, [r11, #RUN_RESUME_ROWS]
    ldr     r1, [r11, #RUN_RESUME_ROWS + 4]
    str     r0, [sp, #SP_ROWS0]
    str     r1, [sp, #SP_ROWS1]
    b       .Ltexture

.Lcolumn:
    ldr     r0, [r11, #RUN_STOP]
    cmp     r9, r0
    bge     .Ldone
    add     r0, r11, #RUN_NEGATED_SCALE0
    ldmia   r0, {r1, r4, r6, r7, r8, r12}   @ the negated scales, row base, height
    WALL_ROW r2, r1, r8, r12, r0, r3        @ r2: the ceiling's row
    WALL_ROW r3, r4, r8, r12, r0, r1        @ r3: the floor's row
    add     r0, r11, #RUN_KIND
    ldmia   r0, {r1, r4, r6, r7}            @ kind, the clip, ceiling and floor windows
    @ The clip window: r8 top, r12 bottom (column_windows from here).
    ldr     r0, [r4, r9, lsl #2]
    mov     r8, r0, lsl #16
    mov     r8, r8, asr #16
    mov     r12, r0, asr #16
    cmp     r2, r8
    movlt   r2, r8                          @ ceiling row = max(ceiling, clip top)
    cmp     r3, r12
    movgt   r3, r12                         @ floor row = min(floor, clip bottom)
    @ The ceiling window, (clip top, min(ceiling row, clip bottom)), and the floor window,
    @ (max(floor row, clip top), clip bottom).
    cmp     r2, r12
    movlt   r0, r2
    movge   r0, r12
    cmp     r8, r0
    orrlt   r5, r5, #0x40000000             @ a ceiling window with rows
    orr     r0, r8, r0, lsl #16
    str     r0, [r6, r9, lsl #2]
    cmp     r3, r8
    movgt   r0, r3
    movle   r0, r8
    cmp     r0, r12
    orrlt   r5, r5, #0x80000000             @ a floor window with rows
    orr     r0, r0, r12, lsl #16
    str     r0, [r7, r9, lsl #2]
    ands    r0, r1, #3
    bne     .Lportal
    @ Solid: the clip window closes; one strip, from the ceiling row to the floor row.
    str     r0, [r4, r9, lsl #2]
    cmp     r2, r3
    bge     .Lnext
    orr     r0, r2, r3, lsl #16
    mov     r1, #0
    stmia   sp, {r0, r1}                    @ the strips' rows
    b       .Ltexture

.Lportal:
    cmp     r0, #1
    bne     .Lstripped
    @ An opening: the clip window from the ceiling row to the floor row, no strip.
    cmp     r3, r2
    movlt   r3, r2
    orr     r0, r2, r3, lsl #16
    str     r0, [r4, r9, lsl #2]
    b       .Lnext

.Lstripped:
    @ The neighbour's rows, clamped: r6 its ceiling's, r7 its floor's, each found only where
    @ its strip is drawn. Without an upper strip r6 is the ceiling row: the same windows, as
    @ the neighbour's floor row is never above its ceiling row (floor ≤ ceiling, rows
    @ monotone), so the clamp of r7 below gives what the neighbour's own ceiling row would.
    add     r0, r11, #RUN_NEGATED_SCALE2
    ldmia   r0, {r6, r7, r8, r12}           @ its negated scales, row base, height
    tst     r1, #0x100
    moveq   r6, r2
    beq     1f
    WALL_ROW r6, r6, r8, r12, r0, lr
    cmp     r6, r2
    movlt   r6, r2                          @ max(neighbour ceiling, ceiling row)
    cmp     r3, r2
    movge   r0, r3
    movlt   r0, r2                          @ max(floor row, ceiling row)
    cmp     r6, r0
    movgt   r6, r0
1:
    tst     r1, #0x200
    beq     2f
    WALL_ROW r7, r7, r8, r12, r0, lr
    cmp     r6, r3
    movlt   r0, r6
    movge   r0, r3                          @ min(neighbour ceiling row, floor row)
    cmp     r7, r0
    movlt   r7, r0
    cmp     r7, r3
    movgt   r7, r3
2:
    @ The opening: from the neighbour's ceiling row (upper strip) or the ceiling row, to the
    @ neighbour's floor row (lower strip) or the floor row; the strips where drawn.
    tst     r1, #0x100
    moveq   r8, r2
    movne   r8, r6
    tst     r1, #0x200
    moveq   r12, r3
    movne   r12, r7
    cmp     r12, r8
    movlt   r12, r8
    orr     r0, r8, r12, lsl #16
    str     r0, [r4, r9, lsl #2]
    mov     r0, #0
    tst     r1, #0x100
    beq     1f
    cmp     r2, r6
    orrlt   r0, r2, r6, lsl #16
1:
    mov     r8, #0
    tst     r1, #0x200
    beq     2f
    cmp     r7, r3
    orrlt   r8, r7, r3, lsl #16
2:
    stmia   sp, {r0, r8}                    @ the strips' rows
    orrs    r0, r0, r8
    beq     .Lnext

.Ltexture:
    @ z' = 1/(1/z'): recip_pow2(1/z', 38) (src/math/recip.rs): r0 2^31 over the mantissa,
    @ r1 its shift. The mantissa is 1/z' shifted by the last textured column's shift where
    @ that still normalises it (neighbouring columns' depths mostly share it), else found anew.
    ldr     r1, [sp, #SP_SHIFT]
    movs    r0, r10, lsl r1
    bpl     .Lrenormalise                   @ top bit clear: it needs more
    cmp     r10, r0, lsr r1
    bne     .Lrenormalise                   @ bits shifted out: it needs less
.Lnormalised:
    ldr     r2, [r11, #RUN_SEEDS]
    RECIP_OF_NORMALISED r0, r2, r3, r4, r12
    @ To 24.8, rounded: right by 62 − 38 − shift (the shift is 1..16 for 1/z' in
    @ [2^30 / EYE_DEPTH_MAX, 2^30], so 8..23).
    rsb     r1, r1, #23
    mov     r0, r0, lsr r1
    add     r0, r0, #1
    mov     r8, r0, lsr #1                  @ r8: z' in 24.8
    @ t/z' at this column, then t = (t/z')·z' >> 8, clamped to 0..2^30.
    ldr     r1, [r11, #RUN_AOD_STEP]
    ldr     r2, [sp, #SP_AOD]
    mla     r1, r9, r1, r2
    @ The product's high word below 2^6 (unsigned) leaves t in 0..2^30: no clamp (the others
    @ are the columns at a wall's ends, .Lclamp_along).
    smull   r2, r3, r1, r8
    cmp     r3, #64
    bhs     .Lclamp_along
    mov     r4, r2, lsr #8
    orr     r4, r4, r3, lsl #24
.Lalong:
    add     lr, r11, #RUN_LENGTH
    ldmia   lr, {r0, r1, r2, r3, r6, r7}    @ length, x offset, 1/d_y, light mode, base, colormap
    @ u = t·length >> 30, plus the x offset (24.8).
    MUL_2_30 r12, r4, r0, lr
    add     r4, r12, r1                     @ r4: u
    @ The light: no colormap, one row, or the row of base − z'/16 units, clamped to 0..255.
    cmp     r3, #2
    bne     1f
    DEPTH_LIGHT_ROW r6, r8
    add     r7, r7, r6, lsl #8
1:
    mov     r3, r7                          @ the colormap row (0: unlit)
    @ z'/d_y = z'·(1/d_y) in 24.8 × 2^30; the mip ratio is its bits from 38 up.
    smull   r6, r7, r8, r2                  @ r6/r7: z'/d_y
    mov     r8, r3                          @ r8: the colormap row
    @ Each drawn strip: its level must select the mip ratio (z'/d_y's bits from 38 up), or
    @ the run stops with the strips still to draw; a drawn strip leaves the pending rows.
    ldr     r0, [sp, #SP_ROWS0]
    cmp     r0, #0
    beq     3f
    WALL_LEVEL_CHECK RUN_STRIP0
    WALL_STRIP RUN_STRIP0, SP_SLOTS0
    mov     r0, #0
    str     r0, [sp, #SP_ROWS0]
3:
    ldr     r0, [sp, #SP_ROWS1]
    cmp     r0, #0
    beq     .Lnext
    WALL_LEVEL_CHECK RUN_STRIP1
    WALL_STRIP RUN_STRIP1, SP_SLOTS1

.Lnext:
    tst     r5, #NATIVE_BIT
    bne     .Lnext_native
.Lstep:
    ldr     r0, [r11, #RUN_INV_STEP]
    add     r9, r9, #1
    add     r10, r10, r0
    b       .Lcolumn

.Lnext_native:
    @ 240 wide: after an odd column, or an even one whose neighbour is not in the run, the
    @ strips still waiting are drawn alone.
    tst     r9, #1
    bne     1f
    ldr     r1, [r11, #RUN_STOP]
    add     r0, r9, #1
    cmp     r0, r1
    blt     .Lstep
1:
    ldr     r0, [sp, #SP_SLOTS0 + SLOT_COUNT_EVEN]
    ldr     r1, [sp, #SP_SLOTS1 + SLOT_COUNT_EVEN]
    orrs    r0, r0, r1
    blne    .Lflush
    b       .Lstep

.Lclamp_along:
    @ A negative product gives t = 0; a high word of 2^6 or more t ≥ 2^30, so 2^30.
    movs    r3, r3
    movmi   r4, #0
    movpl   r4, #0x40000000
    b       .Lalong

.Lrenormalise:
    mov     r0, r10
    RECIP_NORMALISE r0, r1
    str     r1, [sp, #SP_SHIFT]
    b       .Lnormalised

.Lmiss:
    @ Stop at this column, its windows written, its strips to draw when started again; the
    @ strips set up before it drawn now, with the kernels of their levels.
    str     r12, [r11, #RUN_MISS]
    tst     r5, #NATIVE_BIT
    blne    .Lflush
    ldr     r0, [sp, #SP_ROWS0]
    ldr     r1, [sp, #SP_ROWS1]
    str     r0, [r11, #RUN_RESUME_ROWS]
    str     r1, [r11, #RUN_RESUME_ROWS + 4]
    mov     r0, #1
    str     r0, [r11, #RUN_RESUME]
    b       .Lreturn

.Ldone:
    mov     r0, #0

.Lreturn:
    @ The run's state at column r9: its accumulators, the counts.
    str     r9, [r11, #RUN_COLUMN]
    str     r10, [r11, #RUN_INV]
    ldr     r2, [r11, #RUN_AOD_STEP]
    ldr     r3, [sp, #SP_AOD]
    mla     r1, r9, r2, r3
    str     r1, [r11, #RUN_AOD]
    ldr     r1, [r11, #RUN_PLANES]
    orr     r1, r1, r5, lsr #30
    str     r1, [r11, #RUN_PLANES]
    bic     r5, r5, #0xE0000000
    ldr     r1, [r11, #RUN_PIXELS]
    ldr     r2, [r11, #RUN_STRIPS]
    mov     r3, r5, lsl #16
    add     r1, r1, r3, lsr #16
    add     r2, r2, r5, lsr #16
    str     r1, [r11, #RUN_PIXELS]
    str     r2, [r11, #RUN_STRIPS]
    add     sp, sp, #SP_FRAME
    pop     {r4-r11, lr}
    bx      lr

    @ One strip of column r9 (draw_strip): r0 its rows (top | bottom << 16, not 0), r2 the
    @ strip, r3 the offset of its jobs from sp (plus the 8 this pushes); r4 = u (24.8), r6/r7 =
    @ z'/d_y (24.8 × 2^30), r8 = the colormap row (0: unlit). The column's job: dst, texture
    @ column, v and its step; then the kernel, or at 240 wide on an even column, the wait.
    @ Keeps r4-r11.
.Lstrip:
    mov     r1, r0, lsl #16
    mov     r1, r1, lsr #16                 @ r1: top
    rsb     r0, r1, r0, lsr #16             @ count
    add     r5, r5, r0
    add     r5, r5, #0x10000
    tst     r5, #NATIVE_BIT
    bne     .Lstrip_jobs
    @ 120 wide: the doubled kernel's registers, set here, no job written or read. r4-r7 are
    @ pushed as the kernel would push them, so the kernel's epilogue gives them back, and the
    @ kernel is entered with lr untouched: it returns to the loop itself (a tail call).
    push    {r4-r7}
    mov     r5, r0                          @ r5: count
    WALL_ROW_OFFSET r12, r1
    @ dst = page + top·240 + 2x.
    ldr     r0, [r11, #RUN_PAGE]
    rsb     r1, r1, r1, lsl #4
    add     r1, r0, r1, lsl #4
    add     r1, r1, r9, lsl #1              @ r1: dst
    WALL_STRIP_V r3, r12, r0, r12           @ r3: v; r12: the shape
    WALL_STRIP_DV r6, r0, r12               @ r6: dv (z'/d_y is done with)
    WALL_STRIP_TEXELS r7, r4, r0, r12       @ r7: texels (u is done with)
    mov     r4, r6                          @ r4: dv
    ldr     r0, [r2, #STRIP_KERNEL]
    mov     r2, r7                          @ r2: texels
    mov     r6, r8                          @ r6: the colormap row
    add     r0, r0, #COLUMN_REGISTER_ENTRY
    bx      r0

.Lstrip_jobs:
    @ 240 wide: the strip's job, in the even or the odd column's slot.
    push    {r3, lr}
    add     r3, sp, r3
    tst     r9, #1
    addne   r3, r3, #24                     @ r3: the job (an odd column: the second)
    str     r0, [r3, #16]
    str     r8, [r3, #20]
    @ dst = page + top·240 + (x & ~1): two pixels share a halfword.
    ldr     r0, [r11, #RUN_PAGE]
    rsb     r12, r1, r1, lsl #4
    add     r0, r0, r12, lsl #4
    bic     r12, r9, #1
    add     r0, r0, r12
    str     r0, [r3]
    WALL_ROW_OFFSET r1, r1
    WALL_STRIP_V r12, r1, lr, r0
    str     r12, [r3, #8]
    WALL_STRIP_TEXELS r12, r1, lr, r0
    str     r12, [r3, #4]
    WALL_STRIP_DV r12, lr, r0
    str     r12, [r3, #12]
    @ The kernel, on an odd column: the pair's, the even column's job first (without rows
    @ where it has none), which is then empty.
    ldr     r12, [r2, #STRIP_KERNEL]
    tst     r9, #1
    popeq   {r3, pc}
    sub     r0, r3, #24
    mov     lr, pc
    bx      r12
    ldr     r3, [sp]
    add     r3, sp, r3
    mov     r0, #0
    str     r0, [r3, #SLOT_COUNT_EVEN]
    pop     {r3, pc}

    @ Draws alone the strips of an even column still waiting (240 wide), each with its
    @ kernel, the odd column's job left out. Keeps r4-r11.
.Lflush:
    push    {r4, r6, lr}
    add     r4, sp, #12 + SP_SLOTS0
    add     r6, r11, #RUN_STRIP0 + STRIP_KERNEL
1:
    ldr     r0, [r4, #SLOT_COUNT_EVEN]
    cmp     r0, #0
    beq     2f
    mov     r0, #0
    str     r0, [r4, #SLOT_COUNT_ODD]
    ldr     r12, [r6]
    mov     r0, r4
    mov     lr, pc
    bx      r12
    mov     r0, #0
    str     r0, [r4, #SLOT_COUNT_EVEN]
2:
    add     r4, r4, #SP_SLOTS1 - SP_SLOTS0
    add     r6, r6, #RUN_STRIP1 - RUN_STRIP0
    add     r0, sp, #12 + SP_SLOTS1
    cmp     r4, r0
    bls     1b
    pop     {r4, r6, pc}
    .size pc_wall_run, . - pc_wall_run

    @ A column kernel that draws nothing: the set-up benchmark's stand-in (VramCanvas's
    @ without_kernels), so that the loop is timed up to its kernel calls. Entered as a kernel is,
    @ at its start or at its register entry, where the caller has pushed r4-r7 for it.
    .global pc_column_skip
    .type pc_column_skip, %function
    .align 2
pc_column_skip:
    bx      lr
    .org    pc_column_skip + COLUMN_REGISTER_ENTRY
    pop     {r4-r7}
    bx      lr
    .size pc_column_skip, . - pc_column_skip

    @ The caller (src/hw/kernels.rs) restores the assembler's ARM/Thumb state for the code the
    @ compiler emits after this file.
