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

use crate::assets;
use portalcast_format::{Align4, Texture};

#[link_section = ".ewram_bss"]
static mut TEXEL_COPY: Align4<[u8; assets::TEXEL_BLOB_LEN]> = Align4([0; assets::TEXEL_BLOB_LEN]);
#[link_section = ".ewram_bss"]
static mut EWRAM_TEXTURES: MaybeUninit<[Texture<'static>; assets::TEXTURE_COUNT]> =
    MaybeUninit::uninit();
static mut TEXTURES_TAKEN: bool = false;

/// The texture placement knob's EWRAM side: copies every texel (both layouts, all mip levels)
/// from the cartridge to EWRAM and returns the textures re-pointed there. EWRAM reads cost 3
/// cycles a byte against the cartridge's 5 (WAITCNT 0x4317, sequential or not: the kernels'
/// texel loads are random). Done once; later calls return the same table.
pub fn textures_in_ewram() -> &'static [Texture<'static>] {
    // SAFETY: single-threaded, and the flag makes the copy and the table's initialisation
    // happen once, before the only shared references to either are made; the interrupt
    // handler touches neither.
    unsafe {
        let table: *mut [Texture<'static>; assets::TEXTURE_COUNT] =
            (&raw mut EWRAM_TEXTURES).cast();
        let taken = &raw mut TEXTURES_TAKEN;
        if !*taken {
            *taken = true;
            let copy_slot: *mut Align4<[u8; assets::TEXEL_BLOB_LEN]> = &raw mut TEXEL_COPY;
            let copy: &'static mut [u8; assets::TEXEL_BLOB_LEN] = &mut (*copy_slot).0;
            copy.copy_from_slice(&assets::TEXEL_BLOB.0);
            let copy: &'static [u8] = copy;
            let blob = assets::TEXEL_BLOB.0.as_ptr() as usize;
            let rebase = |texels: &[u8]| {
                let offset = texels.as_ptr() as usize - blob;
                &copy[offset..offset + texels.len()]
            };
            let moved: [Texture<'static>; assets::TEXTURE_COUNT] = core::array::from_fn(|index| {
                let texture = assets::TEXTURES[index];
                Texture {
                    columns: rebase(texture.columns),
                    rows: rebase(texture.rows),
                    ..texture
                }
            });
            table.write(moved);
        }
        &*table
    }
}
