//! The cycle meter: timers 2 and 3 cascaded into one free-running 32-bit CPU-cycle counter.
//! It wraps every 2^32 cycles (256 s); spans are measured with wrapping subtraction.

use gba::mmio::{
    TIMER2_CONTROL, TIMER2_COUNT, TIMER2_RELOAD, TIMER3_CONTROL, TIMER3_COUNT, TIMER3_RELOAD,
};
use gba::timers::{TimerControl, TimerScale};

/// Starts the counter from zero. Timer 2 counts every cycle; timer 3 counts timer 2's overflows.
pub fn start() {
    TIMER2_CONTROL.write(TimerControl::new());
    TIMER3_CONTROL.write(TimerControl::new());
    TIMER2_RELOAD.write(0);
    TIMER3_RELOAD.write(0);
    TIMER3_CONTROL.write(TimerControl::new().with_cascade(true).with_enabled(true));
    TIMER2_CONTROL.write(
        TimerControl::new()
            .with_scale(TimerScale::_1)
            .with_enabled(true),
    );
}

/// The current count. The high half is read on both sides of the low half so a carry between
/// the two reads cannot produce a value 65,536 cycles off. In IWRAM: the renderer reads it three
/// times a sector visit, through a function pointer. (It sat in the VRAM Mode 4 leaves free
/// while IWRAM was full; the slopes' code took that room's last bytes, and moving the sloped
/// paths out of the hot functions left IWRAM room for these 48 bytes.)
#[inline(never)]
#[cfg_attr(target_os = "none", link_section = ".iwram.meter_now")]
pub fn now() -> u32 {
    loop {
        let high = TIMER3_COUNT.read();
        let low = TIMER2_COUNT.read();
        if TIMER3_COUNT.read() == high {
            return (u32::from(high) << 16) | u32::from(low);
        }
    }
}

/// Cycles from `since` (a value of [`now`]) to now.
#[inline]
pub fn cycles_since(since: u32) -> u32 {
    now().wrapping_sub(since)
}
