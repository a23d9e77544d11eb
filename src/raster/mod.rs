//! Rasterizers: the portable Rust twins of the ARM kernels in `asm/`.
//!
//! Every kernel in `asm/*.s` has a twin here with the same arguments and the same arithmetic
//! (including wrap-around), so the host can render exactly what the ROM renders; an emulator test
//! compares the two pixel for pixel.

pub mod span;

use crate::frame::{PAGE_HALFWORDS, PAGE_ROW_HALFWORDS};
use crate::testpic::SpanTarget;
use span::{SpanPacking, SpanSteps, SpanTexture};

/// A Mode 4 page in host memory, drawn by the twins: what the ROM's VRAM page holds after the
/// same calls.
pub struct HostPage {
    /// The page, row-major, 120 halfwords per row.
    pub halfwords: [u16; PAGE_HALFWORDS],
}

impl HostPage {
    /// A page of index 0.
    pub fn new() -> HostPage {
        HostPage { halfwords: [0; PAGE_HALFWORDS] }
    }
}

impl Default for HostPage {
    fn default() -> Self {
        HostPage::new()
    }
}

impl SpanTarget for HostPage {
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
        span::draw_span(&mut self.halfwords[start..start + halfwords], texture, steps, packing);
    }
}
