@ Interworking-safe replacements for compiler-builtins' four `__aeabi_*divmod` helpers.
@
@ The engine is compiled as ARM code inside a Thumb ROM (Cargo.toml, profile `rom`). On the
@ ARMv4T a return with `pop {pc}` does not switch state, and compiler-builtins writes these four
@ helpers by hand as Thumb code that returns exactly so: an ARM caller would resume in Thumb state
@ and crash. The ROM build links with `--wrap=__aeabi_uidivmod` (and the other three), so every
@ call, from ARM or Thumb code, lands here instead. Each wrapper is ARM code that calls the
@ division routines compiler-builtins writes in Rust (those return with `bx`) and returns with
@ `bx lr`, which works for callers in either state.
@
@ The Rust twin is Rust's own `/` and `%`: `selfcheck::division_digest` runs both on the host and
@ in the ROM, and tests/emulator_foundation.rs requires the same digest.

    .section .text.pc_runtime, "ax", %progbits
    .arm
    .align 2

@ (r0 = n, r1 = d) -> r0 = n / d, r1 = n % d, unsigned 32-bit.
    .global __wrap___aeabi_uidivmod
    .type __wrap___aeabi_uidivmod, %function
__wrap___aeabi_uidivmod:
    push    {r4, r5, r6, lr}
    mov     r4, r0
    mov     r5, r1
    bl      __aeabi_uidiv
    mul     r1, r0, r5
    sub     r1, r4, r1
    pop     {r4, r5, r6, lr}
    bx      lr
    .size __wrap___aeabi_uidivmod, . - __wrap___aeabi_uidivmod

@ (r0 = n, r1 = d) -> r0 = n / d, r1 = n % d, signed 32-bit (truncating, as Rust).
    .global __wrap___aeabi_idivmod
    .type __wrap___aeabi_idivmod, %function
__wrap___aeabi_idivmod:
    push    {r4, r5, r6, lr}
    mov     r4, r0
    mov     r5, r1
    bl      __aeabi_idiv
    mul     r1, r0, r5
    sub     r1, r4, r1
    pop     {r4, r5, r6, lr}
    bx      lr
    .size __wrap___aeabi_idivmod, . - __wrap___aeabi_idivmod

@ (r0:r1 = n, r2:r3 = d) -> r0:r1 = n / d, r2:r3 = n % d, unsigned 64-bit, through
@ `__udivmoddi4(n, d, *mut rem)`.
    .global __wrap___aeabi_uldivmod
    .type __wrap___aeabi_uldivmod, %function
__wrap___aeabi_uldivmod:
    push    {r4, lr}
    sub     sp, sp, #16
    add     r4, sp, #8
    str     r4, [sp]
    bl      __udivmoddi4
    ldr     r2, [sp, #8]
    ldr     r3, [sp, #12]
    add     sp, sp, #16
    pop     {r4, lr}
    bx      lr
    .size __wrap___aeabi_uldivmod, . - __wrap___aeabi_uldivmod

@ (r0:r1 = n, r2:r3 = d) -> r0:r1 = n / d, r2:r3 = n % d, signed 64-bit: the unsigned division of
@ the magnitudes, the quotient negated when the signs differ, the remainder taking n's sign.
    .global __wrap___aeabi_ldivmod
    .type __wrap___aeabi_ldivmod, %function
__wrap___aeabi_ldivmod:
    push    {r4, r5, r6, lr}
    sub     sp, sp, #16
    mov     r4, r1                  @ n's sign (bit 31)
    eor     r5, r1, r3              @ the quotient's sign
    cmp     r1, #0
    bge     1f
    rsbs    r0, r0, #0
    rsc     r1, r1, #0
1:  cmp     r3, #0
    bge     2f
    rsbs    r2, r2, #0
    rsc     r3, r3, #0
2:  add     r6, sp, #8
    str     r6, [sp]
    bl      __udivmoddi4
    ldr     r2, [sp, #8]
    ldr     r3, [sp, #12]
    cmp     r5, #0
    bge     3f
    rsbs    r0, r0, #0
    rsc     r1, r1, #0
3:  cmp     r4, #0
    bge     4f
    rsbs    r2, r2, #0
    rsc     r3, r3, #0
4:  add     sp, sp, #16
    pop     {r4, r5, r6, lr}
    bx      lr
    .size __wrap___aeabi_ldivmod, . - __wrap___aeabi_ldivmod
