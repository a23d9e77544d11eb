//! The hardware seam: the only place with `unsafe`. MMIO goes through the `gba` crate's typed
//! registers; the ARM kernels in `asm/` are linked in here and wrapped in safe, bounds-checked
//! calls. Everything above this module is portable and runs on the host too.
#![allow(unsafe_code)]

pub mod input;
pub mod kernels;
pub mod log;
pub mod memory;
pub mod meter;
pub mod video;

use gba::mmio::{KEYINPUT, WAITCNT};
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
