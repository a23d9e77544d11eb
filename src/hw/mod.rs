//! The hardware seam: the only place with `unsafe`. MMIO goes through the `gba` crate's typed
//! registers; the ARM kernels in `asm/` are linked in here and wrapped in safe, bounds-checked
//! calls. Everything above this module is portable and runs on the host too.
#![allow(unsafe_code)]

pub mod input;
pub mod kernels;
pub mod log;
pub mod machine;
pub mod math_bench;
pub mod memory;
pub mod meter;
pub mod panic_screen;
pub mod video;

pub use machine::{Machine, ObjVram};

use gba::mmio::{IME, KEYINPUT, WAITCNT};
use gba::prelude::WaitstateControl;

/// The buttons held right now, as a bit set in KEYINPUT order (A = bit 0 … L = bit 9), 1 = held.
pub fn keys_held() -> u16 {
    // KEYINPUT is active-low.
    !KEYINPUT.read().to_u16() & 0x03ff
}

/// WAITCNT value the ROM runs with: SRAM 8 cycles, WS0 first access 3 cycles and second access 1,
/// prefetch on. Retail carts and flash carts run this setting; GBATEK reports third-party flash
/// carts unstable at faster first-access settings (GBADoom's 2,1), so speed must come from IWRAM
/// code and RAM-resident data instead. gba's runtime writes the same value at boot; setting it
/// here too keeps the choice visible and independent of the runtime.
pub const WAITCNT_SETTING: u16 = 0x4317;

/// Applies [`WAITCNT_SETTING`]. Bits: SRAM 8 cycles (0-1 = 3), WS0 first access 3 (2-3 = 1),
/// WS0 second access 1 (4 = 1), WS1 4,2 and WS2 8,2 (unused), prefetch buffer on (14).
pub fn set_waitstates() {
    // SAFETY: a documented, conservative setting that every cart supports.
    unsafe { WAITCNT.write(WaitstateControl(WAITCNT_SETTING)) };
}

/// Runs `f` with interrupts masked (IME off), then restores IME: for timings that must not
/// include an interrupt handler. A VBlank that arrives meanwhile is served right after.
pub fn without_interrupts<R>(f: impl FnOnce() -> R) -> R {
    let enabled = IME.read();
    IME.write(false);
    let result = f();
    IME.write(enabled);
    result
}

/// The BIOS `Div` call (SWI 6): `(numerator / denominator, numerator % denominator)`, truncated
/// toward zero like Rust's `/` and `%`.
///
/// Panics if `denominator` is 0 (the real BIOS would loop forever) or the quotient overflows
/// (`i32::MIN / -1`).
#[inline(always)]
pub fn bios_div(numerator: i32, denominator: i32) -> (i32, i32) {
    assert!(
        denominator != 0 && !(numerator == i32::MIN && denominator == -1),
        // No arguments in the message: formatting them would keep the operands on the stack
        // in every caller's loop.
        "BIOS Div by zero, or of i32::MIN by -1"
    );
    let quotient: i32;
    let remainder: i32;
    // SAFETY: SWI 6 reads r0 and r1 and returns in r0, r1 and r3 (|quotient|); r2 is marked
    // clobbered as well because GBATEK does not promise it survives. It touches no memory of
    // ours and runs on the supervisor stack; the BIOS returns with the caller's flags. The
    // comment field is read from the instruction, whose width depends on the code mode.
    unsafe {
        #[cfg(target_feature = "thumb-mode")]
        core::arch::asm!(
            "swi #0x06",
            inlateout("r0") numerator => quotient,
            inlateout("r1") denominator => remainder,
            out("r2") _,
            out("r3") _,
            options(pure, nomem, nostack, preserves_flags),
        );
        #[cfg(not(target_feature = "thumb-mode"))]
        core::arch::asm!(
            "swi #0x060000",
            inlateout("r0") numerator => quotient,
            inlateout("r1") denominator => remainder,
            out("r2") _,
            out("r3") _,
            options(pure, nomem, nostack, preserves_flags),
        );
    }
    (quotient, remainder)
}
