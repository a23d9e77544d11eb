//! Memory figures from the linker script's symbols.

extern "C" {
    static __iwram_start: u8;
    static __bss_end: u8;
}

/// Where the BIOS's user-mode stack starts; it grows down towards our data.
pub const STACK_TOP: usize = 0x0300_7F00;
/// Start of IWRAM.
pub const IWRAM_START: usize = 0x0300_0000;

/// Bytes of IWRAM taken by code, data and zeroed data.
pub fn iwram_used() -> usize {
    let end = &raw const __bss_end as usize;
    end - IWRAM_START
}

/// Bytes between the end of our data and the stack top: the most the stack may ever use.
pub fn stack_room() -> usize {
    let start = &raw const __iwram_start as usize;
    debug_assert_eq!(start, IWRAM_START);
    STACK_TOP - (&raw const __bss_end as usize)
}

use crate::render::walk::Renderer;
use core::mem::MaybeUninit;

#[link_section = ".ewram_bss"]
static mut RENDERER: MaybeUninit<Renderer> = MaybeUninit::uninit();
static mut RENDERER_TAKEN: bool = false;

/// The renderer's working memory (clip and plane windows, about 3.7 KB), placed in EWRAM so it
/// does not take the IWRAM stack the portal recursion needs. Hands it out once.
pub fn renderer_in_ewram(renderer: Renderer) -> &'static mut Renderer {
    // SAFETY: single-threaded, and the flag makes this the only reference ever made to the
    // static; the interrupt handler never touches either.
    unsafe {
        let taken = &raw mut RENDERER_TAKEN;
        assert!(!*taken, "the renderer's memory is handed out once");
        *taken = true;
        let slot: *mut Renderer = (&raw mut RENDERER).cast();
        slot.write(renderer);
        &mut *slot
    }
}
