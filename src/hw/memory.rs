//! Memory figures from the linker script's symbols.

extern "C" {
    static __iwram_start: u8;
    static __bss_end: u8;
    static __ewram_bss_end: u8;
    static __vram_code_start: u32;
    static __vram_code_end: u32;
    static __vram_code_position_in_rom: u32;
    static __vram_after_pages_start: u32;
    static __vram_after_pages_end: u32;
    static __vram_after_pages_position_in_rom: u32;
    /// linker.ld's reserve for the stack (a symbol whose address is the value).
    static STACK_RESERVE: u8;
}

pub use crate::stack::{IWRAM_START, STACK_PAINT, STACK_TOP};

/// The stack room the linker script reserves below the BIOS area (`STACK_RESERVE` in linker.ld):
/// the stack must never go deeper, or code and data grown into the rest of IWRAM would be
/// overwritten. Printed with the high-water mark, so the tests compare with the script itself.
pub fn stack_reserve() -> usize {
    &raw const STACK_RESERVE as usize
}

/// Start of EWRAM.
pub const EWRAM_START: usize = 0x0200_0000;

/// Bytes of EWRAM the ROM uses so far: its `.ewram_bss` (the renderer's memory) and what
/// [`ewram_uninit`] has handed out (the game's state, the texture copy); nothing is ever written
/// above them.
pub fn ewram_used() -> usize {
    // SAFETY: single-threaded read of a word only `take_ewram` writes.
    let next = unsafe { (&raw const EWRAM_NEXT).read() };
    next.max(&raw const __ewram_bss_end as usize) - EWRAM_START
}

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

/// Bytes left unpainted below the caller's stack pointer: the painting function's own frame
/// and anything the compiler keeps just below `sp` while it runs.
const PAINT_MARGIN: usize = 256;

/// Fills the stack's room, from the end of `.bss` to just below the current stack pointer, with
/// [`STACK_PAINT`], so that [`stack_high_water`] can later tell how deep the stack has gone.
/// Call it once, first thing in `main`, while the stack is shallow. Interrupts may stay on: the
/// handler runs on the IRQ stack at the top of IWRAM, outside the painted room.
#[inline(never)]
pub fn paint_stack() {
    let sp: usize;
    // SAFETY: reads the stack pointer into a register; touches no memory.
    unsafe {
        core::arch::asm!("mov {0}, sp", out(reg) sp, options(nomem, nostack, preserves_flags))
    };
    let mut address = painted_start();
    let stop = sp - PAINT_MARGIN;
    while address < stop {
        // SAFETY: the words between the end of .bss and the live stack frame belong to no
        // object (the linker script reserves them for the stack), and are word aligned.
        unsafe { (address as *mut u32).write_volatile(STACK_PAINT) };
        address += 4;
    }
}

/// The first painted address: the end of `.bss`, rounded up to a word.
fn painted_start() -> usize {
    (&raw const __bss_end as usize + 3) & !3
}

/// The deepest the user stack has reached since [`paint_stack`], in bytes below
/// [`STACK_TOP`]: the distance from the top to the lowest word that lost its paint. Compare it
/// with [`stack_room`]; when they meet, the stack has run into `.bss`.
pub fn stack_high_water() -> usize {
    let mut address = painted_start();
    // SAFETY: word-aligned reads inside IWRAM, between the end of .bss and the stack top.
    while address < STACK_TOP && unsafe { (address as *const u32).read_volatile() } == STACK_PAINT {
        address += 4;
    }
    STACK_TOP - address
}

use crate::raster::Window;
use crate::render::walk::{ColumnWindows, Renderer, WindowStore};
use core::mem::MaybeUninit;
use gba::dma::{DestAddrControl, DmaControl, SrcAddrControl};
use gba::mmio::{DMA3_CONTROL, DMA3_COUNT, DMA3_DEST, DMA3_SRC};

/// The renderer the ROM draws with: its column windows in VRAM ([`VramWindows`]), the rest in
/// EWRAM.
pub type GbaRenderer = Renderer<VramWindows>;

#[link_section = ".ewram_bss"]
static mut RENDERER: MaybeUninit<GbaRenderer> = MaybeUninit::uninit();
static mut RENDERER_TAKEN: bool = false;

/// The renderer's [`ColumnWindows`] in the OBJ VRAM that Mode 4 leaves free, after the
/// colormap ([`colormap_in_vram`]). Every wall column reads a clip window and writes three
/// windows, and `make_spans` reads two per column and a span start per row: VRAM answers a
/// halfword in 1 cycle, EWRAM in 3, and IWRAM has no room. VRAM ignores byte stores to OBJ
/// tiles; the renderer stores these arrays as halfwords and words only (an `i16` or a
/// [`Window`](crate::render::spans::Window) at a time), and the ROM-versus-host pixel tests
/// would see a lost store.
///
/// A token with no data: [`renderer_in_ewram`] makes the only one, so the one `&mut` it hands
/// out at a time is the only reference to that memory.
pub struct VramWindows(());

/// Where [`VramWindows`] keeps the windows.
const WINDOWS_VRAM: usize = FREE_OBJ_VRAM + core::mem::size_of::<portalcast_format::Colormap>();

impl WindowStore for VramWindows {
    #[inline(always)]
    fn windows(&mut self) -> &mut ColumnWindows {
        const {
            assert!(
                WINDOWS_VRAM + core::mem::size_of::<ColumnWindows>()
                    <= FREE_OBJ_VRAM + FREE_OBJ_VRAM_BYTES
            );
            assert!(WINDOWS_VRAM.is_multiple_of(core::mem::align_of::<ColumnWindows>()));
            assert!(WINDOWS_VRAM + core::mem::size_of::<ColumnWindows>() <= VRAM_CODE_START);
        };
        // SAFETY: the address is in the free OBJ VRAM (asserted above), used for nothing else,
        // aligned, and holds a valid `ColumnWindows` (`renderer_in_ewram` wrote one before
        // making the only token); the `&mut self` borrow makes this the only reference.
        unsafe { &mut *(WINDOWS_VRAM as *mut ColumnWindows) }
    }

    /// As the default, by DMA: one word per column, with no instruction fetched from the
    /// cartridge per column (the caller runs from ROM: the loop took about 30 cycles a column).
    fn open_clip(&mut self, width: usize, height: i16) {
        let clip = self.windows().clip_mut();
        assert!(width <= clip.len());
        let open = Window {
            top: 0,
            bottom: height,
        }
        .word();
        let control = DmaControl::new()
            .with_src_addr_control(SrcAddrControl::Fixed)
            .with_dest_addr_control(DestAddrControl::Increment)
            .with_transfer_32bit(true)
            .with_enabled(true);
        // SAFETY: DMA3 copies `width` words from `open`, which lives until the transfer ends
        // (waited for below), to the first `width` clip windows: words of the `&mut` borrow
        // above (`Window` is a word-aligned word), in the free OBJ VRAM, which takes word
        // stores. Nothing else uses DMA3.
        unsafe {
            DMA3_SRC.write((&raw const open).cast());
            DMA3_DEST.write(clip.as_mut_ptr().cast());
            DMA3_COUNT.write(width as u16);
            DMA3_CONTROL.write(control);
        }
        // The transfer starts a few cycles after the write: `open` must outlive it, and the
        // windows must be open before the walk reads them.
        while DMA3_CONTROL.read().enabled() {}
        core::hint::black_box(&open);
    }
}

/// The empty windows, copied to VRAM word by word (VRAM takes no byte stores).
static EMPTY_WINDOWS: ColumnWindows = ColumnWindows::new();

/// The renderer's working memory: the column windows in VRAM ([`VramWindows`]), the rest (the
/// portal walk's levels, the visit plan, the vertex cache) in EWRAM, timing its stages with
/// `clock`. Built in place from the constant empty renderer: passed in by value it would go
/// through the stack first, which has no room for it. Hands it out once.
pub fn renderer_in_ewram(clock: fn() -> u32) -> &'static mut GbaRenderer {
    // SAFETY: single-threaded, and the flag makes this the only reference ever made to the
    // static and the only `VramWindows` token; the interrupt handler never touches either. The
    // windows' words lie in the free OBJ VRAM (`VramWindows::windows` asserts it).
    unsafe {
        let taken = &raw mut RENDERER_TAKEN;
        assert!(!*taken, "the renderer's memory is handed out once");
        *taken = true;
        const WORDS: usize = core::mem::size_of::<ColumnWindows>() / 4;
        let source = (&raw const EMPTY_WINDOWS).cast::<u32>();
        let destination = WINDOWS_VRAM as *mut u32;
        for word in 0..WORDS {
            destination
                .add(word)
                .write_volatile(source.add(word).read());
        }
        let slot: *mut GbaRenderer = (&raw mut RENDERER).cast();
        slot.write(const { Renderer::with_windows(VramWindows(())) });
        let renderer = &mut *slot;
        renderer.set_clock(clock);
        renderer
    }
}

use crate::frame;
use portalcast_format::{Align4, Texture, TextureChain};

/// The end of EWRAM.
const EWRAM_END: usize = EWRAM_START + portalcast_format::memory::EWRAM_BYTES;

/// The first EWRAM byte no one has been handed yet ([`ewram_uninit`]); 0 until the first hand-out,
/// which starts it at the end of the linked `.ewram_bss`. In IWRAM's `.bss`, which the runtime
/// clears at boot (EWRAM's is not: a real GBA powers on with arbitrary bytes there).
#[link_section = ".bss.ewram_next"]
static mut EWRAM_NEXT: usize = 0;

/// Hands out `bytes` bytes of EWRAM aligned to `align` that were never handed out before:
/// their address. Panics, naming what was asked and what is left, if EWRAM is full.
fn take_ewram(bytes: usize, align: usize) -> usize {
    // SAFETY: single-threaded; the interrupt handler never hands out memory.
    unsafe {
        let next = &raw mut EWRAM_NEXT;
        if *next == 0 {
            *next = &raw const __ewram_bss_end as usize;
        }
        let start = (*next).next_multiple_of(align);
        let left = EWRAM_END.saturating_sub(start);
        assert!(
            bytes <= left,
            "EWRAM is full: {bytes} bytes asked for, {left} left"
        );
        *next = start + bytes;
        start
    }
}

/// Room for a `T` in EWRAM, above the linked statics, handed out once and never taken back: for
/// the large parts of a game (its live world, a game state with the map's sector table) that
/// the stack's room in IWRAM cannot hold. Build it in place from a constant, so that the
/// compiler copies it from the cartridge rather than through the stack:
/// `memory::ewram_uninit().write(const { World::new() })`. EWRAM reads cost 3 cycles (IWRAM 1).
/// Panics if EWRAM is full.
pub fn ewram_uninit<T>() -> &'static mut MaybeUninit<T> {
    let at = take_ewram(core::mem::size_of::<T>(), core::mem::align_of::<T>());
    // SAFETY: `take_ewram` never hands out a byte twice, the bytes lie in EWRAM above every
    // linked static (so nothing else uses them), and the address is aligned for `T`. A
    // `MaybeUninit` needs no initialising.
    unsafe { &mut *(at as *mut MaybeUninit<T>) }
}

/// Room for `len` values of `T` in EWRAM, as [`ewram_uninit`].
pub fn ewram_uninit_slice<T>(len: usize) -> &'static mut [MaybeUninit<T>] {
    let bytes = core::mem::size_of::<T>()
        .checked_mul(len)
        .expect("EWRAM is full: a slice larger than the address space");
    let at = take_ewram(bytes, core::mem::align_of::<T>());
    // SAFETY: as `ewram_uninit`, for `len` values.
    unsafe { core::slice::from_raw_parts_mut(at as *mut MaybeUninit<T>, len) }
}

/// A copy of `values` in EWRAM, as [`ewram_uninit_slice`] hands out room: a game's own live
/// copy of tables it changes (a map's things, for `world::remove_thing`).
pub fn ewram_copy<T: Copy>(values: &[T]) -> &'static mut [T] {
    let slots = ewram_uninit_slice::<T>(values.len());
    for (slot, value) in slots.iter_mut().zip(values) {
        slot.write(*value);
    }
    // SAFETY: every one of the slots was written just above.
    unsafe { &mut *(core::ptr::from_mut(slots) as *mut [T]) }
}

/// The texture table [`textures_in_ewram`] made, once it has: (first entry, entries).
static mut EWRAM_TEXTURES: (usize, usize) = (0, 0);

/// The texture placement knob's EWRAM side: copies the first `ewram_len` bytes of `blob` (the
/// asset compiler's texel blob, which holds the hottest textures that fit first, both layouts
/// and all mip levels: its `TEXEL_EWRAM_LEN`) from the cartridge to EWRAM, and returns
/// `textures` with those re-pointed at the copy and the others still in the cartridge. EWRAM
/// reads cost 3 cycles a byte against the cartridge's 5 (WAITCNT 0x4317, sequential or not: the
/// kernels' texel loads are random). Done once; later calls return the same table, whatever
/// they pass.
pub fn textures_in_ewram(
    textures: &'static [Texture<'static>],
    blob: &'static [u8],
    ewram_len: usize,
) -> &'static [Texture<'static>] {
    // SAFETY: single-threaded; the table's address is recorded once, after the whole table is
    // written; the interrupt handler touches none of it.
    unsafe {
        let made = &raw mut EWRAM_TEXTURES;
        if (*made).1 == 0 && !textures.is_empty() {
            let copy: &'static mut [MaybeUninit<Align4<[u8; 4]>>] =
                ewram_uninit_slice(ewram_len.div_ceil(4));
            let copy: &'static mut [u8] =
                core::slice::from_raw_parts_mut(copy.as_mut_ptr().cast::<u8>(), ewram_len);
            copy.copy_from_slice(&blob[..ewram_len]);
            let copy: &'static [u8] = copy;
            let blob_start = blob.as_ptr() as usize;
            // Texels in the copied prefix are read from the copy; the rest from the cartridge.
            let rebase = |texels: &'static [u8]| {
                let offset = (texels.as_ptr() as usize).wrapping_sub(blob_start);
                copy.get(offset..offset.wrapping_add(texels.len()))
                    .unwrap_or(texels)
            };
            // Entry by entry in place: the whole table built on the stack first would take
            // 28 bytes a texture of the 4 KiB the stack has (a Doom map's 109 textures: 3 KiB,
            // which once ran the stack into the interrupt handler's pointer).
            let table = ewram_uninit_slice::<Texture<'static>>(textures.len());
            for (slot, texture) in table.iter_mut().zip(textures) {
                slot.write(Texture {
                    columns: rebase(texture.columns),
                    rows: rebase(texture.rows),
                    ..*texture
                });
            }
            *made = (table.as_ptr() as usize, table.len());
        }
        let (at, len) = *made;
        if len == 0 {
            return &[];
        }
        core::slice::from_raw_parts(at as *const Texture<'static>, len)
    }
}

/// The first byte of the OBJ tile VRAM that Mode 4 leaves free: its two bitmap pages take
/// 0x0600_0000..0x0601_4000, and no sprite is ever shown.
const FREE_OBJ_VRAM: usize = 0x0601_4000;
/// Bytes of OBJ VRAM free in Mode 4.
const FREE_OBJ_VRAM_BYTES: usize = 0x4000;
static mut COLORMAP_COPIED: bool = false;
/// Where the code that runs from VRAM starts: linker.ld's `vram` region, the top of the free
/// OBJ VRAM, above the colormap and the column windows.
const VRAM_CODE_START: usize = 0x0601_6E60;
static mut CODE_COPIED: bool = false;

/// Copies the code that runs from VRAM from the cartridge, once: linker.ld's `.vram_code`
/// (functions whose section is `.vram.*`) to the top of the free OBJ VRAM, and
/// `.vram_after_pages_code` to the 2,560 bytes after the second 240×160 bitmap page. Call it at boot, before anything calls that code and before the soak's
/// guard regions are read (its guards over that VRAM prove nothing writes there afterwards).
pub fn code_in_vram() {
    // SAFETY: single-threaded; the flag makes the copy happen once, before any of the code runs
    // (nothing calls it before boot calls this). Each image's run addresses lie in its linker.ld
    // region: the top of the free OBJ VRAM from VRAM_CODE_START (checked below), above the
    // windows (asserted in `VramWindows::windows`), and the VRAM after the second page, which
    // the renderer never writes (its pages are 240×160 bytes: `frame::PAGE_HALFWORDS`). The images
    // and run addresses are word aligned (linker.ld's ASSERT and ALIGN) and whole words long.
    unsafe {
        let copied = &raw mut CODE_COPIED;
        if *copied {
            return;
        }
        *copied = true;
        assert_eq!(
            &raw const __vram_code_start as usize, VRAM_CODE_START,
            "linker.ld's vram region and hw::memory::VRAM_CODE_START disagree"
        );
        for (start, end, image) in [
            (
                &raw const __vram_code_start,
                &raw const __vram_code_end,
                &raw const __vram_code_position_in_rom,
            ),
            (
                &raw const __vram_after_pages_start,
                &raw const __vram_after_pages_end,
                &raw const __vram_after_pages_position_in_rom,
            ),
        ] {
            let words = (end as usize - start as usize) / 4;
            for word in 0..words {
                start
                    .cast_mut()
                    .add(word)
                    .write_volatile(image.add(word).read());
            }
        }
    }
}

/// The light colormap, copied once from the cartridge to the OBJ VRAM that Mode 4 leaves free
/// (8 KB of its 16). The lit kernels read one colormap byte per pixel: VRAM answers a byte
/// read in 1 cycle, EWRAM in 3 and the cartridge in 5 (WAITCNT 0x4317), and IWRAM has no room
/// for it. The copy uses word stores (VRAM ignores byte stores to OBJ tiles); afterwards the
/// colormap is only read. Call it at boot, before the soak's guard regions are read.
pub fn colormap_in_vram(
    colormap: &portalcast_format::Colormap,
) -> &'static portalcast_format::Colormap {
    use portalcast_format::Colormap;
    const WORDS: usize = core::mem::size_of::<Colormap>() / 4;
    const { assert!(core::mem::size_of::<Colormap>() <= FREE_OBJ_VRAM_BYTES) };
    // SAFETY: single-threaded; the flag makes the copy happen once, before any shared
    // reference to the copy is made. The words written lie in the free OBJ VRAM (asserted
    // above), which nothing else in the ROM uses; the source is the cartridge's word-aligned
    // colormap (`Align4`). VRAM is readable with byte loads, which is all the renderer does.
    unsafe {
        let copied = &raw mut COLORMAP_COPIED;
        if !*copied {
            *copied = true;
            let source = colormap.as_ptr().cast::<u8>();
            let destination = FREE_OBJ_VRAM as *mut u32;
            for word in 0..WORDS {
                // Byte by byte: the colormap handed in need not be word aligned.
                let bytes = core::array::from_fn(|byte| source.add(word * 4 + byte).read());
                destination
                    .add(word)
                    .write_volatile(u32::from_le_bytes(bytes));
            }
        }
        &*(FREE_OBJ_VRAM as *const Colormap)
    }
}

/// The light colormap copied to EWRAM (8 KiB, handed out by [`ewram_uninit`]): for a game that
/// gives the OBJ VRAM [`colormap_in_vram`] would take to its own sprites (`hw::ObjVram`).
pub fn colormap_in_ewram(
    colormap: &portalcast_format::Colormap,
) -> &'static portalcast_format::Colormap {
    use portalcast_format::{Colormap, LIGHT_LEVELS};
    let rows = ewram_uninit_slice::<[u8; 256]>(LIGHT_LEVELS);
    for (slot, row) in rows.iter_mut().zip(colormap) {
        slot.write(*row);
    }
    // SAFETY: every one of the `LIGHT_LEVELS` rows was written above, and a `Colormap` is
    // exactly those rows, with their alignment.
    unsafe { &*rows.as_ptr().cast::<Colormap>() }
}

/// Page rows from this one down are what a frame of at most this many rows never draws: BG2
/// shows a 120×80 frame's rows 0..80 at twice their height, so rows 80..160 of both Mode 4
/// pages are free while that resolution is on screen.
pub const LENT_FROM_ROW: usize = 80;

/// The free rows of each page, as (first byte, end): 19,200 bytes each.
const LENT_ROWS: [(usize, usize); 2] = [
    (
        0x0600_0000 + LENT_FROM_ROW * frame::PAGE_WIDTH,
        0x0600_0000 + frame::PAGE_HEIGHT * frame::PAGE_WIDTH,
    ),
    (
        0x0600_A000 + LENT_FROM_ROW * frame::PAGE_WIDTH,
        0x0600_A000 + frame::PAGE_HEIGHT * frame::PAGE_WIDTH,
    ),
];

/// In IWRAM's `.bss`, which the runtime clears at boot (EWRAM's is not: a real GBA powers on
/// with arbitrary bytes there). A section of its own: the compiler does not merge it with the
/// other `.bss` flags, whose addressing the hot code shares.
#[link_section = ".bss.rows_lent"]
static mut ROWS_LENT: bool = false;
/// The texture table of the lent rows ([`LentPageRows::textures`]), in EWRAM from the first
/// lend on: (first entry, entries).
static mut LENT_TEXTURES: (usize, usize) = (0, 0);

/// Whether the page rows from [`LENT_FROM_ROW`] hold texture chains ([`LentPageRows`]): no
/// canvas or clear may write them then.
pub fn page_rows_lent() -> bool {
    // SAFETY: single-threaded; the interrupt handler never touches the flag.
    unsafe { (&raw const ROWS_LENT).read() }
}

/// The page rows a 120×80 frame never draws ([`LENT_FROM_ROW`]), lent to the hottest texture
/// chains: VRAM answers a byte read in 1 cycle, EWRAM in 3, so every wall and floor pixel of
/// those chains costs 2 cycles less. While it lives, [`page_rows_lent`] is true and
/// [`VramCanvas`](super::kernels::VramCanvas) refuses frames taller than those rows (it
/// panics): drop it before drawing at another resolution.
pub struct LentPageRows {
    chains: u16,
    bytes: u16,
}

impl LentPageRows {
    /// Copies the chains of `textures` (the table [`textures_in_ewram`] returns, or the
    /// cartridge's) into the free page rows, hottest first (`chains_by_heat`, the asset
    /// compiler's `TEXTURE_CHAINS_BY_HEAT`), each that still fits; `None` if the rows are lent
    /// already, or if `textures` has not as many entries as at the first lend (whose table,
    /// in EWRAM, every lend reuses). Copy it only while the display shows a resolution of at
    /// most [`LENT_FROM_ROW`] rows, or the chains show on screen until the next flip.
    #[inline(never)]
    pub fn lend(
        textures: &[Texture<'static>],
        chains_by_heat: &[(u16, TextureChain)],
    ) -> Option<LentPageRows> {
        LentPageRows::prepare(textures.len());
        // SAFETY: single-threaded read of what `prepare` recorded.
        let (at, len) = unsafe { (&raw const LENT_TEXTURES).read() };
        if page_rows_lent() || len == 0 || textures.len() != len {
            return None;
        }
        let mut free = LENT_ROWS;
        let (mut chains, mut bytes) = (0u16, 0u16);
        // SAFETY: single-threaded. The flag is set before any VRAM byte is written, and while
        // it is set nothing else writes the lent rows (the canvas and `VramPage::clear` check
        // it). Each copy lies inside one block of `LENT_ROWS` (checked by the fit test), at a
        // word-aligned address, written by halfword stores (VRAM takes no byte stores); the
        // slices made over it are read only, and live no longer than the `&self` borrow
        // `textures` hands them out under, after which `Drop` clears the flag. The table (in
        // EWRAM, handed out once above and used by nothing else) is written whole before the
        // first shared reference to it is made.
        unsafe {
            (&raw mut ROWS_LENT).write(true);
            let table = core::slice::from_raw_parts_mut(at as *mut Texture<'static>, len);
            table.copy_from_slice(textures);
            for &(index, chain) in chains_by_heat {
                let Some(slot) = table.get_mut(usize::from(index)) else {
                    continue;
                };
                let texels = slot.chain(chain);
                let Some(block) = free
                    .iter_mut()
                    .find(|(at, end)| !texels.is_empty() && at + texels.len() <= *end)
                else {
                    continue;
                };
                let destination = block.0 as *mut u16;
                for (half, pair) in texels.chunks(2).enumerate() {
                    let high = pair.get(1).copied().unwrap_or(0);
                    destination
                        .add(half)
                        .write_volatile(u16::from(pair[0]) | u16::from(high) << 8);
                }
                let copy: &'static [u8] =
                    core::slice::from_raw_parts(block.0 as *const u8, texels.len());
                *slot = slot.with_chain(chain, copy);
                block.0 += texels.len().next_multiple_of(4);
                chains += 1;
                bytes = bytes.saturating_add(texels.len() as u16);
            }
        }
        Some(LentPageRows { chains, bytes })
    }

    /// Hands out the EWRAM table of `textures` entries that every [`LentPageRows::lend`] uses,
    /// now rather than at the first lend, so that a scene's EWRAM is all handed out when it
    /// starts; once (later calls change nothing).
    pub fn prepare(textures: usize) {
        // SAFETY: single-threaded; the table's address is recorded once, and the interrupt
        // handler never touches it.
        unsafe {
            let made = &raw mut LENT_TEXTURES;
            if (*made).1 == 0 && textures != 0 {
                let table = ewram_uninit_slice::<Texture<'static>>(textures);
                *made = (table.as_ptr() as usize, table.len());
            }
        }
    }

    /// The textures, the lent chains read from the page rows.
    pub fn textures(&self) -> &[Texture<'_>] {
        // SAFETY: `lend` wrote the whole table before making `self`; it is only rewritten by
        // the next `lend`, which cannot run while `self` lives (the flag).
        unsafe {
            let (at, len) = (&raw const LENT_TEXTURES).read();
            core::slice::from_raw_parts(at as *const Texture<'static>, len)
        }
    }

    /// How many chains and bytes it holds.
    pub fn held(&self) -> (u16, u16) {
        (self.chains, self.bytes)
    }
}

impl Drop for LentPageRows {
    fn drop(&mut self) {
        // SAFETY: single-threaded; no slice into the rows outlives `self` (`textures`).
        unsafe { (&raw mut ROWS_LENT).write(false) };
    }
}
