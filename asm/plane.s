@ A plane's spans: Doom's R_MakeSpans and R_MapPlane and the calls of the span kernels, in ARM
@ code in IWRAM. Rust twin: the renderer's own (src/render/spans.rs, make_spans; then
@ src/render/planes.rs, PlaneSpans::span_twin, and src/hw/kernels.rs, VramCanvas::flat), which
@ the host draws with; the emulator's ROM-versus-host frame test compares the two pixel for
@ pixel. The run is built and checked by src/raster/plane_run.rs (PlaneRun) and prepared by
@ src/hw/kernels.rs.
@
@ u32 pc_plane_run(PlaneRun *r0): turns the plane's column windows into spans, row by row as
@ make_spans does, and sets up and draws each. Returns 0 when the plane is done. It stops,
@ keeping where it was in run.x, run.old and run.mid, and returns 2 before a span whose mip
@ ratio (in run.miss_ratio) the run's level does not hold, 1 after a span it leaves to the
@ renderer (in run.pending: outside the viewport, or on the plane's far side of the horizon),
@ and 3 at a window outside the viewport's rows; called again, it goes on from there.
@
@ PlaneRun (words):
@   0 depth_numerator (|eye − plane|·2·d_y, 24.8)  4 horizon_y  8 below_eye  12 inverse_focal_y
@  16 ratio_low  20 ratio_high  24 level  28 side_log2  32 texels  36 centre_x
@  40..52 rays (2.30: centre x, centre y, step x, step y)  56..68 eye (16.16, x then y, 64-bit)
@  72 light_mode (0 off, 1 fixed, 2 depth)  76 light_base  80 colormap  84 recip_small (i32[512])
@  88 page  92 native  96 halved  100 kernels (by side from 8)  104 draw_edges  108 height
@ 112 width  116 miss_ratio  120 windows (column 0's place: the plane's first is at `first`)
@ 124 span_start (i16 per row)  128 x  132 end  136 old (window word)  140 mid  144 spans
@ 148 pixels  152..160 pending (start, end, row)  164 span_start_rows  168 chain (a square
@ flat's row-major mip chain, or null)  172 its side at level 0 (log2)  176 its shallowest
@ level  180 its deepest

    .equ PR_NUMER, 0
    .equ PR_HORIZON, 4
    .equ PR_BELOW, 8
    .equ PR_IFOC, 12
    .equ PR_RLOW, 16
    .equ PR_RHIGH, 20
    .equ PR_LEVEL, 24
    .equ PR_SIDE, 28
    .equ PR_TEXELS, 32
    .equ PR_CX, 36
    .equ PR_RAYS, 40
    .equ PR_EYE, 56
    .equ PR_LMODE, 72
    .equ PR_LBASE, 76
    .equ PR_CMAP, 80
    .equ PR_RECIP, 84
    .equ PR_PAGE, 88
    .equ PR_NATIVE, 92
    .equ PR_HALVED, 96
    .equ PR_KERNELS, 100
    .equ PR_EDGES, 104
    .equ PR_HEIGHT, 108
    .equ PR_WIDTH, 112
    .equ PR_MISS, 116
    .equ PR_WINDOWS, 120
    .equ PR_SPAN_START, 124
    .equ PR_X, 128
    .equ PR_END, 132
    .equ PR_OLD, 136
    .equ PR_MID, 140
    .equ PR_SPANS, 144
    .equ PR_PIXELS, 148
    .equ PR_PENDING, 152
    .equ PR_CHAIN, 168
    .equ PR_CHAIN_SIDE, 172
    .equ PR_CHAIN_SHALLOW, 176
    .equ PR_CHAIN_DEEP, 180

    @ \dst = ((eye word pair at \eye, or 0) + (z'·ray >> 22)) >> level, low word: the 64-bit
    @ sum as PlaneSpans::span_twin forms it. r10 = z' (24.8), r4 = level, r5 = 32 − level;
    @ r0, r1 scratch.
    .macro PLANE_COORD dst, ray, eye
    ldr     r1, [r11, #\ray]
    smull   r0, r1, r10, r1
    mov     r0, r0, lsr #22
    orr     r0, r0, r1, lsl #10
    mov     r1, r1, asr #22
    .if \eye >= 0
    ldr     \dst, [r11, #\eye]
    adds    r0, r0, \dst
    ldr     \dst, [r11, #\eye + 4]
    adc     r1, r1, \dst
    .endif
    mov     r0, r0, lsr r4
    orr     \dst, r0, r1, lsl r5
    .endm

    @ PackedUv::pack: \u = ((\u + half) >> k << 16) + ((\v + half) >> k), r3 = k, r2 = half.
    .macro PLANE_PACK u, v
    add     \u, \u, r2
    mov     \u, \u, asr r3
    add     \v, \v, r2
    mov     \v, \v, asr r3
    add     \u, \v, \u, lsl #16
    .endm

    @ \dst = the span kernel for the flat's side at the run's level (PR_KERNELS, by side from
    @ 8); \t and r0 scratch (\dst may be r0).
    .macro PLANE_KERNEL dst, t
    ldr     r0, [r11, #PR_SIDE]
    ldr     \t, [r11, #PR_KERNELS]
    sub     r0, r0, #3
    ldr     \dst, [\t, r0, lsl #2]
    .endm

    @ Rows \row.. \end (r2 the span starts) start a span at column r4; \row ends at \end.
    .macro PLANE_START_ROWS row, end
1:
    cmp     \row, \end
    bge     2f
    mov     r3, \row, lsl #1
    strh    r4, [r2, r3]
    add     \row, \row, #1
    b       1b
2:
    .endm

    .section .iwram_render.pc_plane_run, "ax", %progbits
    .arm
    .global pc_plane_run
    .type pc_plane_run, %function
    .align 2
pc_plane_run:
    push    {r4-r11, lr}
    mov     r11, r0
    ldr     r4, [r11, #PR_X]                @ r4: the column
    ldr     r5, [r11, #PR_END]              @ r5: the column after the plane's last
    ldr     r6, [r11, #PR_WINDOWS]          @ r6: the windows, column x's at r6 + 4x
    ldr     r7, [r11, #PR_OLD]              @ r7: the column before's window (normalised)
    mov     r8, #0                          @ r8: the column before's window as stored
    ldr     r0, [r11, #PR_MID]
    cmp     r0, #0
    beq     .Lpr_loop
    @ Stopped in column x's change of rows: on with it.
    mov     r0, #0
    str     r0, [r11, #PR_MID]
    cmp     r4, r5
    bhs     .Lpr_flush
    ldr     r8, [r6, r4, lsl #2]
    mov     r0, r8
    b       .Lpr_normalise
.Lpr_loop:
    @ Most columns have the window of the column before: one word compare.
    cmp     r4, r5
    bhs     .Lpr_flush
    ldr     r0, [r6, r4, lsl #2]
    cmp     r0, r8
    addeq   r4, r4, #1
    beq     .Lpr_loop
    mov     r8, r0
.Lpr_normalise:
    @ r0: the window, EMPTY (0) if empty; else inside the viewport's rows.
    mov     r1, r0, lsl #16
    mov     r1, r1, asr #16
    mov     r2, r0, asr #16
    cmp     r1, r2
    movge   r0, #0
    bge     1f
    ldr     r3, [r11, #PR_HEIGHT]
    cmp     r1, #0
    blt     .Lpr_bad
    cmp     r2, r3
    bgt     .Lpr_bad
1:
    cmp     r0, r7
    beq     .Lpr_next
    bl      .Lpr_change_rows
    cmp     r0, #0
    bne     .Lpr_stop
.Lpr_next:
    add     r4, r4, #1
    b       .Lpr_loop
.Lpr_flush:
    @ Past the last column: every row still open ends.
    cmp     r7, #0
    beq     .Lpr_done
    mov     r0, #0
    bl      .Lpr_change_rows
    cmp     r0, #0
    bne     .Lpr_stop
.Lpr_done:
    mov     r0, #0
.Lpr_stop:
    str     r4, [r11, #PR_X]
    pop     {r4-r11, lr}
    bx      lr
.Lpr_bad:
    mov     r0, #3
    b       .Lpr_stop

    @ Column x (r4) has window r0 where the column before had r7 (both normalised): ends the
    @ spans of the rows that leave, starts those of the rows that enter (change_rows), and
    @ returns 0 with r7 = r0; or stops at a span, with the rows still to end in run.old and
    @ run.mid set, and returns its status. Uses r9, r10 (kept across the spans) and r0-r3, r12.
.Lpr_change_rows:
    str     lr, [sp, #-4]!
    mov     r9, r7, lsl #16
    mov     r9, r9, asr #16                 @ r9: the old window's top
    mov     r10, r7, asr #16                @ r10: its bottom
    mov     r7, r0                          @ r7: the new window
1:
    @ Rows that leave at the top end their span here.
    cmp     r9, r10
    bge     3f
    mov     r0, r7, lsl #16
    cmp     r9, r0, asr #16
    blt     2f
    cmp     r9, r7, asr #16
    blt     3f
2:
    mov     r1, r9
    bl      .Lpr_emit
    cmp     r0, #0
    bne     .Lpr_top_stop
    add     r9, r9, #1
    b       1b
3:
    @ Then those that leave at the bottom.
    cmp     r10, r9
    ble     5f
    sub     r1, r10, #1
    mov     r0, r7, lsl #16
    cmp     r1, r0, asr #16
    blt     4f
    cmp     r1, r7, asr #16
    blt     5f
4:
    bl      .Lpr_emit
    cmp     r0, #0
    bne     .Lpr_bottom_stop
    sub     r10, r10, #1
    b       3b
5:
    @ Rows that enter start a span here; what remains of the old window is inside the new.
    mov     r0, r7, lsl #16
    mov     r0, r0, asr #16                 @ the new top
    mov     r1, r7, asr #16                 @ the new bottom
    cmp     r0, r1
    bge     8f
    cmp     r9, r10
    movge   r9, r1
    movge   r10, r1
    ldr     r2, [r11, #PR_SPAN_START]
    PLANE_START_ROWS r0, r9
    PLANE_START_ROWS r10, r1
8:
    mov     r0, #0
    ldr     lr, [sp], #4
    bx      lr
.Lpr_top_stop:
    @ A miss ends nothing: the row is ended again; a span left to the renderer is ended.
    cmp     r0, #1
    addeq   r9, r9, #1
    b       .Lpr_save
.Lpr_bottom_stop:
    cmp     r0, #1
    subeq   r10, r10, #1
.Lpr_save:
    orr     r1, r9, r10, lsl #16
    str     r1, [r11, #PR_OLD]
    mov     r1, #1
    str     r1, [r11, #PR_MID]
    ldr     lr, [sp], #4
    bx      lr

    @ The span of row r1 from its start to column x (r4); returns its status. Keeps r4-r11.
.Lpr_emit:
    ldr     r2, [r11, #PR_SPAN_START]
    mov     r3, r1, lsl #1
    ldrsh   r2, [r2, r3]
    mov     r3, r4
    @ Falls through to .Lpr_span.

    @ One span: row r1, columns r2..r3. Returns 0 drawn, 1 left to the renderer (in
    @ run.pending), 2 a mip ratio the level does not hold (in run.miss_ratio). Keeps r4-r11.
.Lpr_span:
    push    {r4-r10, lr}
    sub     sp, sp, #24                     @ the kernel's job (asm/flat.s)
    mov     r9, r1                          @ r9: the row
    mov     r7, r2                          @ r7: the first column
    mov     r8, r3                          @ r8: the column after the last
    @ Inside the viewport, not empty.
    add     r0, r11, #PR_HEIGHT
    ldmia   r0, {r0, r1}                    @ height, width
    cmp     r9, r0
    bhs     .Lpl_decline
    cmp     r8, r1
    bhi     .Lpl_decline
    cmp     r7, r8
    bhs     .Lpl_decline
    @ n = |2·(row − cy) + 1|, on the plane's side of the horizon and inside the table.
    ldr     r0, [r11, #PR_HORIZON]
    sub     r0, r9, r0
    mov     r0, r0, lsl #1
    adds    r0, r0, #1
    ldr     r1, [r11, #PR_BELOW]
    bmi     1f
    cmp     r1, #0
    beq     .Lpl_decline                    @ a ceiling's row below the horizon
    b       2f
1:
    cmp     r1, #0
    bne     .Lpl_decline                    @ a floor's row above the horizon
    rsb     r0, r0, #0
2:
    cmp     r0, #512
    bhs     .Lpl_decline
    @ z' = numerator · (1/n), 2.30 rounded to 24.8 (Fx24_8::mul_fx2_30).
    ldr     r1, [r11, #PR_RECIP]
    ldr     r1, [r1, r0, lsl #2]
    ldr     r2, [r11, #PR_NUMER]
    smull   r0, r1, r2, r1
    adds    r0, r0, #0x20000000
    adc     r1, r1, #0
    mov     r0, r0, lsr #30
    orr     r10, r0, r1, lsl #2             @ r10: z' in 24.8
    @ The mip ratio, z'·(1/d_y) >> 38: the run's level must hold it.
    ldr     r1, [r11, #PR_IFOC]
    smull   r0, r1, r10, r1
    mov     r1, r1, asr #6
    ldr     r0, [r11, #PR_RLOW]
    cmp     r1, r0
    blt     .Lpl_pick
    ldr     r0, [r11, #PR_RHIGH]
    cmp     r1, r0
    bgt     .Lpl_pick
.Lpl_level_held:
    @ The centre column's map position and the step per pixel at the level, packed.
    ldr     r4, [r11, #PR_LEVEL]
    rsb     r5, r4, #32
    PLANE_COORD r6, PR_RAYS, PR_EYE              @ r6: u at the centre
    PLANE_COORD r12, PR_RAYS+4, PR_EYE+8         @ r12: v at the centre
    PLANE_COORD lr, PR_RAYS+8, -1                @ lr: u's step
    PLANE_COORD r4, PR_RAYS+12, -1               @ r4: v's step (the level is done with)
    ldr     r3, [r11, #PR_SIDE]
    sub     r2, r3, #1
    mov     r0, #1
    mov     r2, r0, lsl r2                  @ r2: half a unit of the packed fractions
    PLANE_PACK r6, r12                      @ r6: the centre, packed
    PLANE_PACK lr, r4
    mov     r12, lr                         @ r12: the step, packed
    @ The span's first pixel is start − cx steps from the centre.
    ldr     r0, [r11, #PR_CX]
    sub     r0, r7, r0
    mla     r6, r12, r0, r6                 @ r6: the position of the first pixel
    @ The light: the run's row, or the row of base − z'/16 units, clamped to 0..255.
    add     r1, r11, #PR_LMODE
    ldmia   r1, {r0, r1, r5}                @ the light's mode, base and row (or colormap)
    cmp     r0, #2
    bne     1f
    DEPTH_LIGHT_ROW r1, r10
    add     r5, r5, r1, lsl #8
1:                                          @ r5: the colormap row (0: unlit)
    @ The span is drawn from here: counted.
    add     r2, r11, #PR_SPANS
    ldmia   r2, {r0, r1}                    @ spans, pixels
    add     r0, r0, #1
    add     r1, r1, r8
    sub     r1, r1, r7
    stmia   r2, {r0, r1}
    ldr     r0, [r11, #PR_PAGE]
    rsb     r1, r9, r9, lsl #4
    add     r4, r0, r1, lsl #4              @ r4: the row's first byte (row·240)
    ldr     r0, [r11, #PR_NATIVE]
    cmp     r0, #0
    beq     .Lpl_doubled
    @ 240 wide. An odd first pixel shares its halfword with the pixel on its left: it is
    @ written alone, read-modify-write, with the texel of its halfword's even pixel (one step
    @ back) where floors are halved.
    tst     r7, #1
    beq     2f
    ldr     r0, [r11, #PR_HALVED]
    cmp     r0, #0
    moveq   r0, r6
    subne   r0, r6, r12
    bl      .Lpl_texel
    ldr     r1, [r11, #PR_EDGES]
    cmp     r1, #0
    beq     1f
    add     r1, r4, r7
    sub     r1, r1, #1                      @ the halfword's even byte
    ldrh    r2, [r1]
    and     r2, r2, #0xff
    orr     r2, r2, r0, lsl #8
    strh    r2, [r1]
1:
    add     r6, r6, r12
    add     r7, r7, #1
2:
    @ An odd count: the last pixel (even) shares its halfword with the pixel on its right.
    sub     r0, r8, r7
    tst     r0, #1
    beq     3f
    sub     r0, r0, #1
    mla     r0, r12, r0, r6
    bl      .Lpl_texel
    sub     r8, r8, #1
    ldr     r1, [r11, #PR_EDGES]
    cmp     r1, #0
    beq     3f
    add     r1, r4, r8
    ldrh    r2, [r1]
    and     r2, r2, #0xff00
    orr     r2, r2, r0
    strh    r2, [r1]
3:
    cmp     r7, r8
    beq     .Lpl_drawn
    @ Whole halfwords from x (even): the pair kernel, or where floors are halved the doubled
    @ one (its byte store fills both pixels) at two steps a halfword.
    add     r0, r4, r7
    sub     r1, r8, r7
    mov     r1, r1, lsr #1
    ldr     r2, [r11, #PR_HALVED]
    cmp     r2, #0
    movne   r12, r12, lsl #1
    b       .Lpl_call
.Lpl_doubled:
    @ 120 wide: a halfword a pixel. The doubled kernel entered with its registers set
    @ (FLAT_REGISTER_ENTRY), no job: dst, texels, pos, step, count, colormap in r1-r6, and
    @ five words pushed for its epilogue to pop into r4-r8, which this routine restores itself.
    PLANE_KERNEL r0, r2
    add     r0, r0, #FLAT_REGISTER_ENTRY
    add     r1, r4, r7, lsl #1
    ldr     r2, [r11, #PR_TEXELS]
    mov     r3, r6
    mov     r4, r12
    mov     r6, r5
    sub     r5, r8, r7
    sub     sp, sp, #20
    adr     lr, .Lpl_drawn                  @ the kernel returns past the job call
    bx      r0
.Lpl_call:
    @ The job: dst, texels, pos, step, count (halfwords), colormap.
    ldr     r2, [r11, #PR_TEXELS]
    str     r0, [sp, #0]
    str     r2, [sp, #4]
    str     r6, [sp, #8]
    str     r12, [sp, #12]
    str     r1, [sp, #16]
    str     r5, [sp, #20]
    PLANE_KERNEL r12, r1
    mov     r0, sp
    mov     lr, pc
    bx      r12
.Lpl_drawn:
    mov     r0, #0
.Lpl_return:
    add     sp, sp, #24
    pop     {r4-r10, lr}
    bx      lr
.Lpl_pick:
    @ A ratio (r1) the run's level does not hold. With a chain (PlaneRun::pick_levels) the
    @ routine takes the level PlaneLevel::of picks: floor(log2(ratio)) (0 below 2), clamped to
    @ the chain's levels, with the ratios that pick it (mip_ratios_of_level); else it stops.
    ldr     r0, [r11, #PR_CHAIN]
    cmp     r0, #0
    beq     .Lpl_miss
    mov     r2, #0
    mov     r3, r1, asr #1
1:
    cmp     r3, #0
    ble     2f
    add     r2, r2, #1
    mov     r3, r3, asr #1
    b       1b
2:
    ldr     r3, [r11, #PR_CHAIN_SHALLOW]
    cmp     r2, r3
    movlt   r2, r3
    ldr     r4, [r11, #PR_CHAIN_DEEP]
    cmp     r2, r4
    movgt   r2, r4                          @ r2: the level
    mov     r5, #1
    cmp     r2, r3
    movle   r6, #0x80000000
    movgt   r6, r5, lsl r2
    str     r6, [r11, #PR_RLOW]
    cmp     r2, r4
    mvnge   r6, #0x80000000
    addlt   r6, r2, #1
    movlt   r6, r5, lsl r6
    sublt   r6, r6, #1
    str     r6, [r11, #PR_RHIGH]
    str     r2, [r11, #PR_LEVEL]
    ldr     r3, [r11, #PR_CHAIN_SIDE]
    sub     r4, r3, r2
    str     r4, [r11, #PR_SIDE]
    @ Its texels: the chain past the levels above it, the sum of 4^(side − m) for m < level.
    mov     r3, r3, lsl #1
3:
    subs    r2, r2, #1
    addge   r0, r0, r5, lsl r3
    subge   r3, r3, #2
    bgt     3b
    str     r0, [r11, #PR_TEXELS]
    b       .Lpl_level_held
.Lpl_miss:
    str     r1, [r11, #PR_MISS]
    mov     r0, #2
    b       .Lpl_return
.Lpl_decline:
    add     r0, r11, #PR_PENDING
    stmia   r0, {r7, r8, r9}                @ start, end, row
    mov     r0, #1
    b       .Lpl_return

    @ r0 = the palette index at packed position r0 (FlatTexture::indices): the texel, through
    @ the colormap row r5 unless it is 0. Uses r1-r3.
.Lpl_texel:
    ldr     r3, [r11, #PR_SIDE]
    mov     r1, #1
    mov     r1, r1, lsl r3
    sub     r1, r1, #1
    mov     r1, r1, lsl r3                  @ ((1 << k) − 1) << k
    rsb     r2, r3, #16
    sub     r2, r2, r3
    and     r1, r1, r0, lsr r2
    rsb     r2, r3, #32
    orr     r1, r1, r0, lsr r2              @ v·2^k + u
    ldr     r2, [r11, #PR_TEXELS]
    ldrb    r0, [r2, r1]
    cmp     r5, #0
    ldrbne  r0, [r5, r0]
    bx      lr
    .size pc_plane_run, . - pc_plane_run

    @ A span kernel that draws nothing: the set-up benchmark's stand-in (VramCanvas's
    @ without_kernels), so that the set-up is timed up to its kernel calls.
    .global pc_flat_skip
    .type pc_flat_skip, %function
    .align 2
pc_flat_skip:
    bx      lr
    .org    pc_flat_skip + FLAT_REGISTER_ENTRY
    pop     {r4-r8}
    bx      lr
    .size pc_flat_skip, . - pc_flat_skip

