//! The ARM kernels of `asm/`, assembled into IWRAM, behind safe calls.

use crate::frame::{PAGE_HALFWORDS, PAGE_ROW_HALFWORDS};
use crate::raster::span::SpanTarget;
use crate::raster::span::{SpanPacking, SpanSteps, SpanTexture};

// `raw`: the files are plain assembly, so `{r4-r10}` register lists are not format arguments.
// Each file switches the assembler to ARM; `restore_code_mode!` switches it back to the mode
// this crate's own code is compiled in (Thumb, or ARM under `-thumb-mode`), which the compiler
// assumes when it emits the functions that follow.
macro_rules! restore_code_mode {
    () => {
        #[cfg(target_feature = "thumb-mode")]
        core::arch::global_asm!(".text", ".thumb");
        #[cfg(not(target_feature = "thumb-mode"))]
        core::arch::global_asm!(".text", ".arm");
    };
}

core::arch::global_asm!(include_str!("../../asm/span.s"), options(raw));
restore_code_mode!();

/// The argument block of the span kernels; its layout is documented at the top of `asm/span.s`.
#[repr(C)]
struct SpanJob {
    dst: *mut u16,
    texture: *const u8,
    u: u32,
    v: u32,
    du: u32,
    dv: u32,
    halfwords: u32,
}

extern "C" {
    fn pc_span64_doubled(job: *const SpanJob);
    fn pc_span64_pairs(job: *const SpanJob);
}

/// Why a page refuses a write while its lower rows hold textures.
const ROWS_LENT: &str =
    "the page rows below a 120x80 frame are lent to textures: drop the LentPageRows first";

/// A Mode 4 page in VRAM that the kernels draw into.
pub struct VramPage {
    pub(crate) base: *mut u16,
}

impl VramPage {
    /// The page that is not on screen while `shown_page` is.
    pub fn back_of(shown_page: usize) -> VramPage {
        let base = if shown_page == 0 {
            0x0600_A000
        } else {
            0x0600_0000
        };
        VramPage {
            base: base as *mut u16,
        }
    }
}

impl VramPage {
    /// Sets every pixel of the page to palette index 0. Panics while its lower rows are lent to
    /// textures ([`super::memory::LentPageRows`]).
    pub fn clear(&mut self) {
        assert!(!super::memory::page_rows_lent(), "{ROWS_LENT}");
        for offset in 0..PAGE_HALFWORDS {
            // SAFETY: offset < 19,200 halfwords, the page size; VRAM takes 16-bit stores.
            unsafe { self.base.add(offset).write_volatile(0) };
        }
    }

    /// The page's base address (0x0600_0000 or 0x0600_A000), printed for tests that read VRAM.
    pub fn address(&self) -> usize {
        self.base as usize
    }
}

impl SpanTarget for VramPage {
    fn draw_span(
        &mut self,
        row: usize,
        first_halfword: usize,
        halfwords: usize,
        texture: &SpanTexture,
        steps: SpanSteps,
        packing: SpanPacking,
    ) {
        let start = row * PAGE_ROW_HALFWORDS + first_halfword;
        // The kernels trust their arguments; these checks keep every store inside the page.
        assert!(halfwords >= 1 && first_halfword + halfwords <= PAGE_ROW_HALFWORDS);
        assert!(start + halfwords <= PAGE_HALFWORDS);
        let job = SpanJob {
            // SAFETY: `start + halfwords` is within the 19,200-halfword page (checked above).
            dst: unsafe { self.base.add(start) },
            texture: texture.as_ptr(),
            u: steps.u,
            v: steps.v,
            du: steps.du,
            dv: steps.dv,
            halfwords: halfwords as u32,
        };
        // SAFETY: the job points at a live texture and an in-bounds VRAM run of halfword stores.
        unsafe {
            match packing {
                SpanPacking::Doubled => pc_span64_doubled(&job),
                SpanPacking::Pairs => pc_span64_pairs(&job),
            }
        }
    }
}

/// Assembles `asm/<file>` after the shared macros (asm/shared.s), purges them after it
/// (asm/shared_end.s), then restores the code mode.
macro_rules! assemble_with_shared_macros {
    ($file:literal) => {
        core::arch::global_asm!(
            include_str!("../../asm/shared.s"),
            include_str!(concat!("../../asm/", $file)),
            include_str!("../../asm/shared_end.s"),
            options(raw)
        );
        restore_code_mode!();
    };
}

// The column, span and sprite kernels and the wall, plane and middle loops share macros
// (asm/shared.s), assembled with each of them.
assemble_with_shared_macros!("column.s");
assemble_with_shared_macros!("flat.s");
assemble_with_shared_macros!("sprite.s");
assemble_with_shared_macros!("wall.s");
assemble_with_shared_macros!("plane.s");
assemble_with_shared_macros!("middle.s");
// The math benchmark's ARM routines: assembled here with the kernels and the loops' shared macros
// (its reciprocal is the wall loop's), placed in the benchmark's IWRAM overlay by their section,
// and called through `hw::math_bench`.
assemble_with_shared_macros!("mathbench.s");

// Interworking-safe division helpers that the ROM links in place of compiler-builtins' own
// (`--wrap`, see the file's header); nothing here calls them by name.
core::arch::global_asm!(include_str!("../../asm/runtime.s"), options(raw));
restore_code_mode!();

use crate::frame::Resolution;
use crate::raster::column::{ColumnTexture, COLUMN_LOG2_HEIGHTS};
use crate::raster::flat::{FlatTexture, FLAT_LOG2_SIDES};
use crate::raster::middle_run::{MiddleRun, MiddleShared};
use crate::raster::plane_run::{PlaneRun, PlaneRunEnd};
use crate::raster::sprite::{steps_fit, BatchColumn, SpriteBatch, SpriteColumn};
use crate::raster::wall_run::{StripRun, WallRun, WallRunEnd, WallSteps, ROW_BASE_LOW};
use crate::raster::{Canvas, IDENTITY_ROW};

extern "C" {
    fn pc_wall_run(run: *mut WallRun) -> u32;
    fn pc_plane_run(run: *mut PlaneRun) -> u32;
    fn pc_middle_columns(run: *mut MiddleRun) -> u32;
    fn pc_column_skip(job: *const ColumnJob);
    fn pc_flat_skip(job: *const FlatJob);
}

// `asm/wall.s` reads the run at these offsets (its header lists them).
const _: () = {
    use core::mem::{offset_of, size_of};
    assert!(offset_of!(WallRun, steps) == 0);
    assert!(offset_of!(WallSteps, negated_scales) == 16);
    assert!(offset_of!(WallSteps, row_base) == 32);
    // The loop makes the rows' base's low word with `mvn #0x20000000`.
    assert!(ROW_BASE_LOW == !0x2000_0000);
    assert!(offset_of!(WallRun, column) == 40);
    assert!(offset_of!(WallRun, kind) == 48);
    assert!(offset_of!(WallRun, clip) == 52);
    assert!(offset_of!(WallRun, length) == 64);
    assert!(offset_of!(WallRun, light_mode) == 76);
    assert!(offset_of!(WallRun, colormap) == 84);
    assert!(offset_of!(WallRun, recip_seeds) == 88);
    assert!(offset_of!(WallRun, horizon_row) == 92);
    assert!(offset_of!(WallRun, page) == 96);
    assert!(offset_of!(WallRun, column_pixels) == 104);
    assert!(offset_of!(WallRun, miss_ratio) == 112);
    assert!(offset_of!(WallRun, resume) == 116);
    assert!(offset_of!(WallRun, resume_rows) == 120);
    assert!(offset_of!(WallRun, strips) == 128);
    assert!(size_of::<StripRun>() == 28);
    assert!(offset_of!(StripRun, shape) == 4);
    assert!(offset_of!(StripRun, width_mask) == 16);
    assert!(offset_of!(StripRun, texels) == 20);
    assert!(offset_of!(StripRun, kernel) == 24);
    assert!(offset_of!(WallRun, planes_seen) == 184);
    assert!(size_of::<WallRun>() == 188);
    // `asm/plane.s` reads the plane's run at these.
    assert!(offset_of!(PlaneRun, inverse_focal_y) == 12);
    assert!(offset_of!(PlaneRun, level) == 24);
    assert!(offset_of!(PlaneRun, texels) == 32);
    assert!(offset_of!(PlaneRun, rays) == 40);
    assert!(offset_of!(PlaneRun, eye) == 56);
    assert!(offset_of!(PlaneRun, light_mode) == 72);
    assert!(offset_of!(PlaneRun, recip_small) == 84);
    assert!(offset_of!(PlaneRun, page) == 88);
    assert!(offset_of!(PlaneRun, kernels) == 100);
    assert!(offset_of!(PlaneRun, width) == 112);
    assert!(offset_of!(PlaneRun, miss_ratio) == 116);
    assert!(offset_of!(PlaneRun, windows) == 120);
    assert!(offset_of!(PlaneRun, x) == 128);
    assert!(offset_of!(PlaneRun, mid) == 140);
    assert!(offset_of!(PlaneRun, spans) == 144);
    assert!(offset_of!(PlaneRun, pending) == 152);
    assert!(offset_of!(PlaneRun, chain) == 168);
    assert!(offset_of!(PlaneRun, chain_side_log2) == 172);
    assert!(offset_of!(PlaneRun, chain_shallowest) == 176);
    assert!(offset_of!(PlaneRun, chain_deepest) == 180);
    // `asm/middle.s` reads the middle's run at these, and writes `BatchColumn`s (below).
    assert!(offset_of!(MiddleRun, numerator_step) == 16);
    assert!(offset_of!(MiddleRun, x) == 32);
    assert!(offset_of!(MiddleRun, opening) == 40);
    assert!(offset_of!(MiddleRun, out) == 44);
    assert!(offset_of!(MiddleRun, shared) == 48);
    assert!(offset_of!(MiddleShared, x_offset_fx8) == 12);
    assert!(offset_of!(MiddleShared, nearest) == 24);
    assert!(offset_of!(MiddleShared, inverse_focal_y) == 40);
    assert!(offset_of!(MiddleShared, width) == 44);
    assert!(offset_of!(MiddleShared, depth_min) == 56);
    assert!(offset_of!(MiddleRun, recip_seeds) == 108);
    assert!(offset_of!(BatchColumn, x) == 0);
    assert!(offset_of!(BatchColumn, scale) == 12);
    assert!(size_of::<FlatJob>() == 24);
    assert!(offset_of!(SpriteJob, y_top) == 8);
    assert!(offset_of!(SpriteJob, colormap) == 24);
    assert!(offset_of!(SpriteJob, blend) == 28);
    assert!(offset_of!(SpriteJob, run) == 32);
    assert!(offset_of!(SpriteJob, posts_end) == 36);
    // `pc_sprite_columns` (asm/sprite.s) reads the batch and its columns at these.
    assert!(size_of::<BatchColumn>() == 20);
    assert!(offset_of!(BatchColumn, column) == 1);
    assert!(offset_of!(BatchColumn, light_row) == 2);
    assert!(offset_of!(BatchColumn, clip) == 4);
    assert!(offset_of!(BatchColumn, y_top) == 8);
    assert!(offset_of!(BatchColumn, iscale) == 16);
    assert!(offset_of!(SpriteBatchJob, posts_len) == 12);
    assert!(offset_of!(SpriteBatchJob, identity) == 20);
    assert!(offset_of!(SpriteBatchJob, page) == 28);
    assert!(offset_of!(SpriteBatchJob, runs) == 32);
    assert!(offset_of!(SpriteBatchJob, native) == 44);
};

/// The argument block of the column kernels (`asm/column.s`); the pair kernels take two.
#[derive(Clone, Copy)]
#[repr(C)]
struct ColumnJob {
    dst: *mut u8,
    texels: *const u8,
    v: u32,
    dv: u32,
    count: u32,
    colormap: *const u8,
}

/// The argument block of the sprite kernels (`asm/sprite.s`).
#[repr(C)]
struct SpriteJob {
    dst: *mut u8,
    posts: *const u8,
    y_top: i32,
    scale: i32,
    iscale: u32,
    clip: u32,
    colormap: *const u8,
    blend: *const u8,
    /// The run routine's address (`SPRITE_RUNS`).
    run: usize,
    /// One past the column's last byte: the kernel ends the column at a post that would pass it.
    posts_end: *const u8,
}

/// The argument block of the sprite batch kernel (`asm/sprite.s`, `pc_sprite_columns`).
#[repr(C)]
struct SpriteBatchJob {
    columns: *const BatchColumn,
    count: u32,
    posts: *const u8,
    posts_len: u32,
    colormap: *const u8,
    identity: *const u8,
    blend: *const u8,
    page: *mut u8,
    /// The run routines for 120 wide, and 240 wide even and odd (`sprite_run`).
    runs: [usize; 3],
    /// 0: 120 wide, 1: 240 wide.
    native: u32,
}

/// The argument block of the flat kernels (`asm/flat.s`).
#[repr(C)]
struct FlatJob {
    dst: *mut u16,
    texels: *const u8,
    pos: u32,
    step: u32,
    count: u32,
    colormap: *const u8,
}

type ColumnKernel = unsafe extern "C" fn(*const ColumnJob);
type FlatKernel = unsafe extern "C" fn(*const FlatJob);

macro_rules! kernel_table {
    ($job:ty; $($name:ident),+ $(,)?) => {{
        extern "C" { $(fn $name(job: *const $job);)+ }
        [$($name as unsafe extern "C" fn(*const $job)),+]
    }};
}

/// Column kernels by `[packing][lit][log2_height - 3]`; packing 0 = doubled (120 wide), 1 = the
/// pairs of columns that share halfwords (240 wide), which take two jobs.
static COLUMN_KERNELS: [[[ColumnKernel; 6]; 2]; 2] = [
    [
        kernel_table!(ColumnJob; pc_col_dbl_unlit_h3, pc_col_dbl_unlit_h4, pc_col_dbl_unlit_h5, pc_col_dbl_unlit_h6, pc_col_dbl_unlit_h7, pc_col_dbl_unlit_h8),
        kernel_table!(ColumnJob; pc_col_dbl_lit_h3, pc_col_dbl_lit_h4, pc_col_dbl_lit_h5, pc_col_dbl_lit_h6, pc_col_dbl_lit_h7, pc_col_dbl_lit_h8),
    ],
    [
        kernel_table!(ColumnJob; pc_col_pair_unlit_h3, pc_col_pair_unlit_h4, pc_col_pair_unlit_h5, pc_col_pair_unlit_h6, pc_col_pair_unlit_h7, pc_col_pair_unlit_h8),
        kernel_table!(ColumnJob; pc_col_pair_lit_h3, pc_col_pair_lit_h4, pc_col_pair_lit_h5, pc_col_pair_lit_h6, pc_col_pair_lit_h7, pc_col_pair_lit_h8),
    ],
];

/// Flat kernels by `[pairs][lit][log2_side - 3]`.
static FLAT_KERNELS: [[[FlatKernel; 4]; 2]; 2] = [
    [
        kernel_table!(FlatJob; pc_flat_dbl_unlit_k3, pc_flat_dbl_unlit_k4, pc_flat_dbl_unlit_k5, pc_flat_dbl_unlit_k6),
        kernel_table!(FlatJob; pc_flat_dbl_lit_k3, pc_flat_dbl_lit_k4, pc_flat_dbl_lit_k5, pc_flat_dbl_lit_k6),
    ],
    [
        kernel_table!(FlatJob; pc_flat_pair_unlit_k3, pc_flat_pair_unlit_k4, pc_flat_pair_unlit_k5, pc_flat_pair_unlit_k6),
        kernel_table!(FlatJob; pc_flat_pair_lit_k3, pc_flat_pair_lit_k4, pc_flat_pair_lit_k5, pc_flat_pair_lit_k6),
    ],
];

/// The span kernels of the set-up benchmark's canvas (`VramCanvas::without_kernels`) for
/// `pc_plane_run`: a stand-in that returns at once (`asm/plane.s`).
static SKIPPED_FLAT_KERNELS: [FlatKernel; 4] = [pc_flat_skip; 4];

extern "C" {
    fn pc_sprite(job: *const SpriteJob);
    fn pc_sprite_columns(job: *const SpriteBatchJob);
    // Run routines of `pc_sprite`, with its own register convention (asm/sprite.s): never
    // called from Rust, only their addresses handed to it.
    fn pc_sprite_run_dbl();
    fn pc_sprite_run_even();
    fn pc_sprite_run_odd();
    fn pc_sprite_run_blend_dbl();
    fn pc_sprite_run_blend_even();
    fn pc_sprite_run_blend_odd();
}

/// The run routines of `pc_sprite` by `[translucent][packing]` (packing doubled, even, odd).
fn sprite_run(translucent: bool, packing: usize) -> usize {
    // A static table: built in the function, its six addresses were stored on the stack on
    // every sprite column.
    static RUNS: [[unsafe extern "C" fn(); 3]; 2] = [
        [pc_sprite_run_dbl, pc_sprite_run_even, pc_sprite_run_odd],
        [
            pc_sprite_run_blend_dbl,
            pc_sprite_run_blend_even,
            pc_sprite_run_blend_odd,
        ],
    ];
    RUNS[usize::from(translucent)][packing] as usize
}

extern "C" {
    static __kernels_lit_start: u8;
    static __kernels_lit_end: u8;
    static __kernels_lit_position_in_rom: u8;
    static __kernels_unlit_start: u8;
    static __kernels_unlit_end: u8;
    static __kernels_unlit_position_in_rom: u8;
    static __columns_dbl_lit_start: u8;
    static __columns_dbl_lit_end: u8;
    static __columns_dbl_lit_position_in_rom: u8;
    static __columns_dbl_unlit_start: u8;
    static __columns_dbl_unlit_end: u8;
    static __columns_dbl_unlit_position_in_rom: u8;
    static __columns_pair_lit_start: u8;
    static __columns_pair_lit_end: u8;
    static __columns_pair_lit_position_in_rom: u8;
    static __columns_pair_unlit_start: u8;
    static __columns_pair_unlit_end: u8;
    static __columns_pair_unlit_position_in_rom: u8;
}

/// The span kernels' bank in IWRAM ([`KernelBank::id`]; 0 at boot, none yet). linker.ld gives
/// the two the same run addresses.
static LOADED_BANK: gba::prelude::GbaCell<u8> = gba::prelude::GbaCell::new(0);

/// The column kernels' bank in IWRAM ([`ColumnBank::id`]; 0 at boot, none yet). linker.ld
/// gives the four the same run addresses, after the span kernels' banks.
static LOADED_COLUMN_BANK: gba::prelude::GbaCell<u8> = gba::prelude::GbaCell::new(0);

/// Copies a bank's image (`start..end` in IWRAM, from `source` in ROM) over the run addresses
/// the banks of its kind share.
#[cold]
#[inline(never)]
fn copy_bank(start: usize, end: usize, source: usize) {
    let blocks = (end - start) / 32;
    // SAFETY: linker.ld places the bank's image at `source` in ROM and its run addresses
    // `start..end` in IWRAM, word aligned (asserted there), over the other banks' code only.
    // No kernel is running: the kernels are leaves, called from this file only, each call
    // after its bank's `ensure`, and no interrupt handler calls one. The copy is the gba crate's
    // eight-word LDM/STM loop (in IWRAM), then the last words one at a time; volatile, so
    // the stores stay before the calls that follow (the compiler does not see the code it
    // runs).
    unsafe {
        gba::mem::copy_u32x8_unchecked(start as *mut [u32; 8], source as *const [u32; 8], blocks);
        for offset in (blocks * 32..end - start).step_by(4) {
            let word = ((source + offset) as *const u32).read_volatile();
            ((start + offset) as *mut u32).write_volatile(word);
        }
    }
}

/// The span kernels' banks, lit and unlit: [`KernelBank::ensure`] is the only way to a span
/// kernel.
struct KernelBank;

impl KernelBank {
    /// How [`LOADED_BANK`] names the lit (or the unlit) bank.
    #[inline(always)]
    const fn id(lit: bool) -> u8 {
        if lit {
            1
        } else {
            2
        }
    }

    /// Whether the lit bank is the one in IWRAM.
    #[inline(always)]
    fn lit_loaded() -> bool {
        LOADED_BANK.read() == KernelBank::id(true)
    }

    /// Brings the lit (or the unlit) bank into IWRAM unless it is there.
    #[inline(always)]
    fn ensure(lit: bool) {
        if LOADED_BANK.read() != KernelBank::id(lit) {
            KernelBank::load(lit);
        }
    }

    /// Copies a bank's image from ROM over the other's run addresses.
    #[cold]
    #[inline(never)]
    fn load(lit: bool) {
        // SAFETY (of the addresses): the linker's symbols, read for their addresses only.
        if lit {
            copy_bank(
                &raw const __kernels_lit_start as usize,
                &raw const __kernels_lit_end as usize,
                &raw const __kernels_lit_position_in_rom as usize,
            );
        } else {
            copy_bank(
                &raw const __kernels_unlit_start as usize,
                &raw const __kernels_unlit_end as usize,
                &raw const __kernels_unlit_position_in_rom as usize,
            );
        }
        LOADED_BANK.write(KernelBank::id(lit));
    }

    /// The bank index (0 unlit, 1 lit) of the kernels that draw with `colormap`, brought in if
    /// needed, and the row they read. Unlit draws take the lit bank with an identity row when
    /// that bank is in: a blank span or the menu in a lit frame costs no copy.
    #[inline(always)]
    fn for_colormap(colormap: Option<&[u8; 256]>) -> (usize, *const u8) {
        match colormap {
            Some(row) => {
                KernelBank::ensure(true);
                (1, row.as_ptr())
            }
            None if KernelBank::lit_loaded() => (1, IDENTITY_ROW.as_ptr()),
            None => {
                KernelBank::ensure(false);
                (0, core::ptr::null())
            }
        }
    }
}

/// The column kernels' banks, by lighting and by packing (a resolution draws with one packing:
/// the doubled kernels at 120 wide, the pair kernels at 240): [`ColumnBank::ensure`] is the
/// only way to a column kernel.
struct ColumnBank;

impl ColumnBank {
    /// How [`LOADED_COLUMN_BANK`] names the bank of `packing` (an index of
    /// [`COLUMN_KERNELS`]), lit or not.
    #[inline(always)]
    const fn id(lit: bool, packing: usize) -> u8 {
        1 + !lit as u8 + 2 * packing as u8
    }

    /// Brings the bank of `packing`, lit or not, into IWRAM unless it is there.
    #[inline(always)]
    fn ensure(lit: bool, packing: usize) {
        if LOADED_COLUMN_BANK.read() != ColumnBank::id(lit, packing) {
            ColumnBank::load(lit, packing);
        }
    }

    /// Copies a bank's image from ROM over the others' run addresses.
    #[cold]
    #[inline(never)]
    fn load(lit: bool, packing: usize) {
        // SAFETY (of the addresses): the linker's symbols, read for their addresses only.
        match (lit, packing) {
            (true, 0) => copy_bank(
                &raw const __columns_dbl_lit_start as usize,
                &raw const __columns_dbl_lit_end as usize,
                &raw const __columns_dbl_lit_position_in_rom as usize,
            ),
            (false, 0) => copy_bank(
                &raw const __columns_dbl_unlit_start as usize,
                &raw const __columns_dbl_unlit_end as usize,
                &raw const __columns_dbl_unlit_position_in_rom as usize,
            ),
            (true, _) => copy_bank(
                &raw const __columns_pair_lit_start as usize,
                &raw const __columns_pair_lit_end as usize,
                &raw const __columns_pair_lit_position_in_rom as usize,
            ),
            (false, _) => copy_bank(
                &raw const __columns_pair_unlit_start as usize,
                &raw const __columns_pair_unlit_end as usize,
                &raw const __columns_pair_unlit_position_in_rom as usize,
            ),
        }
        LOADED_COLUMN_BANK.write(ColumnBank::id(lit, packing));
    }

    /// As [`KernelBank::for_colormap`], for the column kernels of `packing`.
    #[inline(always)]
    fn for_colormap(colormap: Option<&[u8; 256]>, packing: usize) -> (usize, *const u8) {
        match colormap {
            Some(row) => {
                ColumnBank::ensure(true, packing);
                (1, row.as_ptr())
            }
            None if LOADED_COLUMN_BANK.read() == ColumnBank::id(true, packing) => {
                (1, IDENTITY_ROW.as_ptr())
            }
            None => {
                ColumnBank::ensure(false, packing);
                (0, core::ptr::null())
            }
        }
    }
}

/// The back page in VRAM as a [`Canvas`]: columns and spans go to the asm kernels.
pub struct VramCanvas {
    page: VramPage,
    resolution: Resolution,
    /// False for the benchmark's set-up measurement: every call is prepared as usual, up to
    /// the kernel's argument block, and the kernel is not run.
    kernels: bool,
    /// Flats at half horizontal resolution ([`Canvas::set_halved_flats`]).
    halved_flats: bool,
}

impl VramCanvas {
    /// Draws into `page` at `resolution`. Panics if the frame is taller than the rows the page
    /// keeps while its lower rows are lent to textures ([`super::memory::LentPageRows`]).
    pub fn new(page: VramPage, resolution: Resolution) -> VramCanvas {
        assert!(
            !super::memory::page_rows_lent() || resolution.height() <= super::memory::LENT_FROM_ROW,
            "{ROWS_LENT}"
        );
        VramCanvas {
            page,
            resolution,
            kernels: true,
            halved_flats: false,
        }
    }

    /// A canvas that prepares every column and span as [`VramCanvas::new`]'s does and draws
    /// no pixel: the benchmark times the renderer on it to tell its set-up from its kernels.
    pub fn without_kernels(page: VramPage, resolution: Resolution) -> VramCanvas {
        VramCanvas {
            kernels: false,
            ..VramCanvas::new(page, resolution)
        }
    }

    fn row_address(&self, row: usize) -> *mut u8 {
        // SAFETY (of the arithmetic): callers check row < 160, so this stays in the page.
        self.page
            .base
            .cast::<u8>()
            .wrapping_add(row * crate::frame::PAGE_WIDTH)
    }

    /// Hands `run` this page, the viewport, the packing and the span kernels for its light
    /// (bringing their bank in), as `flat` picks them for a span.
    #[inline(always)]
    fn prepare_plane_run(&mut self, run: &mut PlaneRun) {
        let native = self.resolution.pixels_per_halfword() == 2;
        let halved = native && self.halved_flats;
        let bank = if run.unlit() {
            // As `flat` draws an unlit span: through the lit bank and the identity row when
            // that bank is in.
            let (bank, row) = if self.kernels {
                KernelBank::for_colormap(None)
            } else {
                (0, core::ptr::null())
            };
            run.colormap = row;
            bank
        } else {
            if self.kernels {
                KernelBank::ensure(true);
            }
            1
        };
        run.kernels = if self.kernels {
            FLAT_KERNELS[usize::from(native && !halved)][bank]
                .as_ptr()
                .cast::<usize>()
        } else {
            SKIPPED_FLAT_KERNELS.as_ptr().cast::<usize>()
        };
        run.page = self.page.base.cast::<u8>();
        run.native = u32::from(native);
        run.halved = u32::from(halved);
        run.draw_edges = u32::from(self.kernels);
        run.height = self.resolution.height() as u32;
        run.width = self.resolution.width() as u32;
    }

    /// Which column kernels draw on this page ([`COLUMN_KERNELS`]' first index): the doubled
    /// ones where a halfword shows one pixel (120 wide), the pair ones where it holds two.
    #[inline(always)]
    fn column_packing(&self) -> usize {
        usize::from(self.resolution.pixels_per_halfword() == 2)
    }

    /// The kernel job of `count` rows of column `x` from `row`, lit through `colormap` (null:
    /// unlit), and its kernel's height index, after one test of every bound a column kernel
    /// trusts: its pixels inside the page, a kernel for its height, and that many texels.
    #[inline(always)]
    fn column_job(
        &self,
        x: usize,
        row: usize,
        count: usize,
        texture: &ColumnTexture,
        colormap: *const u8,
    ) -> (ColumnJob, usize) {
        let height_index = texture
            .log2_height
            .wrapping_sub(*COLUMN_LOG2_HEIGHTS.start()) as usize;
        assert!(
            x < self.resolution.width()
                && count > 0
                && row + count <= self.resolution.height()
                && height_index < COLUMN_KERNELS[0][0].len()
                && texture.texels.len() == 1 << texture.log2_height
        );
        let byte_column = match self.resolution.pixels_per_halfword() {
            1 => 2 * x,
            _ => x & !1,
        };
        let job = ColumnJob {
            dst: self.row_address(row).wrapping_add(byte_column),
            texels: texture.texels.as_ptr(),
            v: texture.v,
            dv: texture.dv,
            count: count as u32,
            colormap,
        };
        (job, height_index)
    }

    /// One native pixel written by read-modify-write of its halfword, keeping the neighbour.
    fn put_native(&mut self, x: usize, row: usize, index: u8) {
        let halfword = self.row_address(row).wrapping_add(x & !1).cast::<u16>();
        // SAFETY: in the page (bounds checked by the callers); VRAM takes 16-bit accesses.
        unsafe {
            let old = halfword.read_volatile();
            let new = if x.is_multiple_of(2) {
                (old & 0xff00) | u16::from(index)
            } else {
                (old & 0x00ff) | (u16::from(index) << 8)
            };
            halfword.write_volatile(new);
        }
    }
}

fn colormap_pointer(colormap: Option<&[u8; 256]>) -> *const u8 {
    colormap.map_or(core::ptr::null(), |row| row.as_ptr())
}

impl Canvas for VramCanvas {
    fn resolution(&self) -> Resolution {
        self.resolution
    }

    #[inline(always)]
    fn column(&mut self, x: usize, row: usize, count: usize, texture: &ColumnTexture) {
        let packing = self.column_packing();
        // An unlit column (the sky's) in a lit frame takes the lit kernel through the identity
        // row (`ColumnBank::for_colormap`): the same pixels, without loading the other bank.
        let (bank, colormap) = if self.kernels {
            ColumnBank::for_colormap(texture.colormap, packing)
        } else {
            let lit = texture.colormap.is_some();
            (usize::from(lit), colormap_pointer(texture.colormap))
        };
        let (job, height) = self.column_job(x, row, count, texture, colormap);
        if !self.kernels {
            return;
        }
        if packing == 0 {
            // SAFETY: the column lies inside the page (`column_job` checked it), the texel
            // column holds 2^log2_height bytes and every index the kernel forms is below that;
            // the colormap, if used, has 256 entries; the kernel is its bank's, which
            // `ColumnBank::for_colormap` brought in.
            unsafe { COLUMN_KERNELS[0][bank][height](&job) };
        } else {
            // 240 wide: the pair kernel, the column's neighbour left out (no rows).
            let mut jobs = [job; 2];
            jobs[1 - x % 2].count = 0;
            // SAFETY: as above; the pair kernel reads two jobs and draws none of a job with
            // no rows.
            unsafe { COLUMN_KERNELS[1][bank][height](jobs.as_ptr()) };
        }
    }

    #[inline(never)]
    fn column_pair(
        &mut self,
        x: usize,
        first: (usize, usize, &ColumnTexture),
        second: (usize, usize, &ColumnTexture),
    ) {
        let ((even_row, even_count, even_texture), (odd_row, odd_count, odd_texture)) =
            (first, second);
        if self.column_packing() == 0
            || !x.is_multiple_of(2)
            || even_texture.log2_height != odd_texture.log2_height
        {
            self.column(x, even_row, even_count, even_texture);
            self.column(x + 1, odd_row, odd_count, odd_texture);
            return;
        }
        // One bank for both: the lit one where either is lit, the other through the identity
        // row.
        let lit = even_texture.colormap.is_some() || odd_texture.colormap.is_some();
        let (bank, unlit_row) = match (lit, self.kernels) {
            (true, true) => {
                ColumnBank::ensure(true, 1);
                (1, IDENTITY_ROW.as_ptr())
            }
            (true, false) => (1, IDENTITY_ROW.as_ptr()),
            (false, true) => ColumnBank::for_colormap(None, 1),
            (false, false) => (0, core::ptr::null()),
        };
        let row_of =
            |texture: &ColumnTexture| texture.colormap.map_or(unlit_row, |row| row.as_ptr());
        let (even_job, height) =
            self.column_job(x, even_row, even_count, even_texture, row_of(even_texture));
        let (odd_job, _) =
            self.column_job(x + 1, odd_row, odd_count, odd_texture, row_of(odd_texture));
        if self.kernels {
            // SAFETY: both columns lie inside the page and hold their texels (`column_job`
            // checked each), at one height, the kernel's; the colormaps, where used, have 256
            // entries; the kernel is its bank's, brought in above.
            unsafe { COLUMN_KERNELS[1][bank][height]([even_job, odd_job].as_ptr()) };
        }
    }

    #[inline(never)]
    fn sprite_column(&mut self, x: usize, column: &SpriteColumn) {
        // Every bound the kernel trusts but the posts' end (it tests that itself), in one test:
        // the window inside the page, the post count there, and the steps inside a post
        // (`SpriteColumn::reads_inside`).
        let clip = column.clip;
        assert!(
            x < self.resolution.width()
                && clip.top >= 0
                && clip.bottom as usize <= self.resolution.height()
                && column.reads_inside()
        );
        let posts = column.posts.as_ptr_range();
        let byte_column = match self.resolution.pixels_per_halfword() {
            1 => 2 * x,
            _ => x & !1,
        };
        let packing = match self.resolution.pixels_per_halfword() {
            1 => 0,
            _ => 1 + x % 2,
        };
        let job = SpriteJob {
            dst: self.row_address(0).wrapping_add(byte_column),
            posts: posts.start,
            y_top: column.y_top,
            scale: column.scale,
            iscale: column.iscale,
            clip: clip.word(),
            colormap: column.colormap.as_ptr(),
            blend: column
                .blend
                .map_or(core::ptr::null(), |blend| blend.as_ptr().cast()),
            run: sprite_run(column.blend.is_some(), packing),
            posts_end: posts.end,
        };
        if self.kernels && !clip.is_empty() {
            // SAFETY: the window's rows lie inside the page (checked above), so every store
            // does; the kernel reads the post count (`posts` is not empty: `reads_inside`) and
            // every post header, texel and pad only below `posts_end`, and steps no row past its
            // post (`reads_inside`'s steps); the colormap has 256 entries, and the blend table,
            // which only the translucent runs read, 65,536 (every behind·256 + front); the run
            // routine is one of `pc_sprite`'s, for this packing. The kernel is in IWRAM outside
            // the banks.
            unsafe { pc_sprite(&job) };
        }
    }

    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".iwram.vram_canvas_sprite_columns")]
    fn sprite_columns(&mut self, batch: &SpriteBatch) {
        // Every bound the kernel trusts but the ones it tests itself (the offsets, the posts'
        // end, the light rows: `SpriteBatch::column`'s), in one pass over the columns.
        let (width, height) = (self.resolution.width(), self.resolution.height() as i16);
        assert!(batch.columns.iter().all(|record| {
            usize::from(record.x) < width
                && record.clip.top >= 0
                && record.clip.bottom <= height
                && steps_fit(record.y_top, record.scale, record.iscale)
        }));
        let translucent = batch.blend.is_some();
        let job = SpriteBatchJob {
            columns: batch.columns.as_ptr(),
            count: batch.columns.len() as u32,
            posts: batch.posts.as_ptr(),
            posts_len: batch.posts.len() as u32,
            colormap: batch.colormap.as_ptr().cast(),
            identity: IDENTITY_ROW.as_ptr(),
            blend: batch
                .blend
                .map_or(core::ptr::null(), |blend| blend.as_ptr().cast()),
            page: self.row_address(0),
            runs: [0, 1, 2].map(|packing| sprite_run(translucent, packing)),
            native: u32::from(self.resolution.pixels_per_halfword() == 2),
        };
        if self.kernels {
            // SAFETY: every column's window lies inside the page and its x inside the row
            // (checked above), so every store does; the kernel reads a column's offset entry and
            // its post count only inside `posts` (it tests both), and every post only below its
            // end, stepping no row past its post (each column's steps checked above); a light
            // row is one of the colormap's 32 rows of 256 (tested by the kernel) or the identity
            // row; the blend table, read only by the translucent runs, has 65,536 entries; the
            // run routines are `pc_sprite`'s. The kernel is in IWRAM outside the banks.
            unsafe { pc_sprite_columns(&job) };
        }
    }

    /// In ROM: the planes' spans go to `plane_run` (`asm/plane.s`), and only the spans it
    /// leaves (rows on a plane's far side of the horizon, planes without a flat) and the menu
    /// come here.
    #[inline(never)]
    fn flat(&mut self, row: usize, x: usize, count: usize, texture: &FlatTexture) {
        // Every bound the kernels trust, in one test: the span inside the page row, a kernel
        // for its side, and that many texels.
        let side = texture.log2_side.wrapping_sub(*FLAT_LOG2_SIDES.start()) as usize;
        assert!(
            row < self.resolution.height()
                && count > 0
                && x + count <= self.resolution.width()
                && side < FLAT_KERNELS[0][0].len()
                && texture.texels.len() == 1 << (2 * texture.log2_side)
        );
        let (mut x, mut count, mut texture) = (x, count, *texture);
        if self.resolution.pixels_per_halfword() == 2 {
            // Whole halfwords go to the pair kernel; a pixel sharing its halfword with a
            // neighbour outside the span is written here with the twin's arithmetic.
            if x % 2 == 1 {
                // Halved floors show the halfword's even pixel's texel, one step back
                // (`u32::MAX` steps wrap to minus one).
                let source = if self.halved_flats {
                    texture.advanced(u32::MAX)
                } else {
                    texture
                };
                let index = source.indices(1).next().unwrap_or(0);
                if self.kernels {
                    self.put_native(x, row, index);
                }
                texture = texture.advanced(1);
                x += 1;
                count -= 1;
            }
            if count % 2 == 1 {
                let index = texture
                    .advanced(count as u32 - 1)
                    .indices(1)
                    .next()
                    .unwrap_or(0);
                if self.kernels {
                    self.put_native(x + count - 1, row, index);
                }
                count -= 1;
            }
            if count == 0 {
                return;
            }
        }
        // Halved floors at 240 wide: one texel per halfword, the even pixel's, so the doubled
        // kernel (whose byte store VRAM mirrors into both bytes) steps two pixels at a time.
        let (pairs, dst_halfword, halfwords, step) = match self.resolution.pixels_per_halfword() {
            1 => (0, x, count, texture.step.0),
            _ if self.halved_flats => (0, x / 2, count / 2, texture.step.0.wrapping_mul(2)),
            _ => (1, x / 2, count / 2, texture.step.0),
        };
        let (bank, colormap) = if self.kernels {
            KernelBank::for_colormap(texture.colormap)
        } else {
            let lit = texture.colormap.is_some();
            (usize::from(lit), colormap_pointer(texture.colormap))
        };
        let job = FlatJob {
            dst: self
                .row_address(row)
                .cast::<u16>()
                .wrapping_add(dst_halfword),
            texels: texture.texels.as_ptr(),
            pos: texture.pos.0,
            step,
            count: halfwords as u32,
            colormap,
        };
        let kernel = FLAT_KERNELS[pairs][bank][side];
        if self.kernels {
            // SAFETY: the run lies inside the page row (checked above); the flat holds 4^k
            // texels and the kernel's index is below that by construction of its masks; the
            // kernel's bank is in (`KernelBank::for_colormap`), and its colormap row has 256
            // entries.
            unsafe { kernel(&job) };
        }
    }

    fn set_halved_flats(&mut self, halved: bool) {
        self.halved_flats = halved;
    }

    fn prefer_lighting(&mut self, lit: bool) {
        if self.kernels {
            KernelBank::ensure(lit);
            ColumnBank::ensure(lit, self.column_packing());
        }
    }

    /// Inlined where the wall loop calls it (in IWRAM): with the sloped maps' copy of that loop
    /// as a second caller it was otherwise left out of line, in the cartridge.
    #[inline(always)]
    fn wall_run(&mut self, run: &mut WallRun) -> Option<WallRunEnd> {
        // The run's own checks (`WallRun::new`, `set_strip`) hold its windows and texels; these
        // keep its columns and rows inside this page.
        assert!(
            (0..=self.resolution.width() as i32).contains(&run.stop)
                && (0..=self.resolution.height() as i32).contains(&run.steps.height)
        );
        let native = self.resolution.pixels_per_halfword() == 2;
        let lit = run.light_mode != 0;
        if self.kernels {
            // The loop hands its strips' kernels the run's row (none when unlit): the bank
            // of its lighting and packing.
            ColumnBank::ensure(lit, usize::from(native));
        }
        let lit = usize::from(lit);
        for strip in &mut run.strips {
            if strip.texels.is_null() {
                // No level yet: the loop stops before drawing it and asks for one.
                continue;
            }
            let height = (strip.height_log2() - COLUMN_LOG2_HEIGHTS.start()) as usize;
            // At 120 wide the doubled kernels; at 240 the pair kernels, which the loop hands
            // each strip of two neighbouring columns at once.
            strip.kernel = if self.kernels {
                COLUMN_KERNELS[usize::from(native)][lit][height] as usize
            } else {
                pc_column_skip as ColumnKernel as usize
            };
        }
        run.page = self.page.base.cast::<u8>();
        run.native = if native { WallRun::NATIVE } else { 0 };
        // SAFETY: `WallRun::new` and `set_strip` checked every pointer the loop follows: the
        // window slices reach past `stop`, each strip with texels holds 2^(width + height)
        // of them at a kernel's height and its column index is masked to its width, the
        // colormap row index is at most 31 of the 32-row table; the assertion above keeps
        // every column below the page's width and every row below its height; the kernels
        // are this canvas's for the strip's height and lighting, from the bank `ensure` brought
        // in.
        let end = unsafe { pc_wall_run(run) };
        Some(if end == 0 {
            WallRunEnd::Done
        } else {
            WallRunEnd::MipLevel(run.miss_ratio)
        })
    }

    #[inline(always)]
    fn middle_columns(&mut self, run: &mut MiddleRun, out: &mut [BatchColumn]) -> Option<usize> {
        assert!(out.len() >= run.columns());
        run.out = out.as_mut_ptr().cast::<u8>();
        // SAFETY: `MiddleRun::new` checked that the openings the routine reads (columns
        // `x..end`) are those of the slice it was given, and the reciprocal table has the 1,024
        // entries its 10-bit index reaches; it writes at most one column per column of the run,
        // which the assertion above fits in `out`.
        let written = unsafe { pc_middle_columns(run) } as usize;
        assert!(written <= run.columns());
        Some(written)
    }

    #[inline(always)]
    fn plane_run(&mut self, run: &mut PlaneRun) -> Option<PlaneRunEnd> {
        if run.page.is_null() {
            self.prepare_plane_run(run);
        }
        // Prepared for this page: its kernels, rows and columns; a start column for every row.
        assert!(
            run.page == self.page.base.cast::<u8>()
                && !run.kernels.is_null()
                && run.span_start_rows >= run.height
        );
        // SAFETY: `PlaneRun::new` and `set_level` checked what the loop follows: the windows
        // it reads are those of the slice it was given (columns `x..end`), the reciprocal
        // table has the 512 entries the loop bounds its index by, the texels (when the level
        // range is not empty) hold the square of a side a kernel takes, and the colormap row
        // index is at most 31 of the 32-row table (or the run's one row, or the identity row
        // set here); the assertion above and `prepare_plane_run` keep its rows below this
        // page's height and the start slice's length (it stops at a window past them), its
        // spans' columns below the page's width, and hand it this canvas's kernels for the
        // run's light and packing, from the bank brought in.
        Some(match unsafe { pc_plane_run(run) } {
            0 => PlaneRunEnd::Done,
            1 => run.declined(),
            2 => PlaneRunEnd::MipLevel(run.miss_ratio),
            _ => panic!("a plane window outside the viewport's rows"),
        })
    }
}
