//! The ARM kernels of `asm/`, assembled into IWRAM, behind safe calls.

use crate::frame::{PAGE_HALFWORDS, PAGE_ROW_HALFWORDS};
use crate::raster::span::{SpanPacking, SpanSteps, SpanTexture};
use crate::testpic::SpanTarget;

// `raw`: the file is plain assembly, so `{r4-r10}` register lists are not format arguments.
core::arch::global_asm!(include_str!("../../asm/span.s"), options(raw));

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

/// A Mode 4 page in VRAM that the kernels draw into.
pub struct VramPage {
    base: *mut u16,
}

impl VramPage {
    /// The page that is not on screen while `shown_page` is.
    pub fn back_of(shown_page: usize) -> VramPage {
        let base = if shown_page == 0 { 0x0600_A000 } else { 0x0600_0000 };
        VramPage { base: base as *mut u16 }
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
