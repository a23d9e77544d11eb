//! The Mode 4 frame: resolutions, the page layout the rasterizers write, and what BG2's affine
//! unit shows of a page.
//!
//! A Mode 4 page is 240×160 bytes (one palette index per screen pixel), written as halfwords. The
//! three render resolutions use it differently:
//! - `R240x160`: native; each halfword holds two distinct pixels.
//! - `R120x160`: each logical pixel fills a whole halfword, so it is two screen pixels wide.
//! - `R120x80`: as `R120x160` for the top 80 rows only; BG2PD = 0x80 shows each row twice. The
//!   renderer really draws 9,600 logical pixels, not 38,400 scaled down.

/// Width of a Mode 4 page in bytes (screen pixels).
pub const PAGE_WIDTH: usize = 240;
/// Height of a Mode 4 page in rows (screen lines).
pub const PAGE_HEIGHT: usize = 160;
/// Halfwords per page row.
pub const PAGE_ROW_HALFWORDS: usize = PAGE_WIDTH / 2;
/// Halfwords in a whole page.
pub const PAGE_HALFWORDS: usize = PAGE_ROW_HALFWORDS * PAGE_HEIGHT;

/// A render resolution, selectable at run time.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Resolution {
    /// 120×80 logical pixels, each shown as 2×2 screen pixels.
    R120x80,
    /// 120×160 logical pixels, each shown 2 wide.
    R120x160,
    /// 240×160, native.
    R240x160,
}

impl Resolution {
    /// All resolutions, in the order Select cycles through them.
    pub const ALL: [Resolution; 3] = [
        Resolution::R120x80,
        Resolution::R120x160,
        Resolution::R240x160,
    ];

    /// Logical columns.
    pub const fn width(self) -> usize {
        match self {
            Resolution::R120x80 | Resolution::R120x160 => 120,
            Resolution::R240x160 => 240,
        }
    }

    /// Logical rows (page rows drawn).
    pub const fn height(self) -> usize {
        match self {
            Resolution::R120x80 => 80,
            Resolution::R120x160 | Resolution::R240x160 => 160,
        }
    }

    /// Logical pixels per page halfword: 1 when each pixel is doubled, 2 at native width.
    pub const fn pixels_per_halfword(self) -> usize {
        self.width() / PAGE_ROW_HALFWORDS
    }

    /// BG2PD, the 8.8 page-row step per screen line: 0x80 shows each page row on two lines.
    pub const fn bg2_pd(self) -> i16 {
        match self {
            Resolution::R120x80 => 0x80,
            Resolution::R120x160 | Resolution::R240x160 => 0x100,
        }
    }

    /// BG2PA, the 8.8 page-column step per screen pixel. Always 1: horizontal doubling comes
    /// from writing each logical pixel into both bytes of a halfword, which costs nothing.
    pub const fn bg2_pa(self) -> i16 {
        0x100
    }

    /// The resolution after this one in Select's cycle.
    pub const fn next(self) -> Resolution {
        match self {
            Resolution::R120x80 => Resolution::R120x160,
            Resolution::R120x160 => Resolution::R240x160,
            Resolution::R240x160 => Resolution::R120x80,
        }
    }

    /// The `WxH` label the ROM prints and tests parse.
    pub const fn label(self) -> &'static str {
        match self {
            Resolution::R120x80 => "120x80",
            Resolution::R120x160 => "120x160",
            Resolution::R240x160 => "240x160",
        }
    }

    /// Parses a label printed by [`Resolution::label`].
    pub fn from_label(label: &str) -> Option<Resolution> {
        Resolution::ALL.into_iter().find(|res| res.label() == label)
    }
}

/// The screen pixel BG2 shows at `(x, y)` of a page, given the affine step of `resolution`
/// (PA = 1, PB = PC = 0, reference point 0): the page byte at row `y·PD >> 8`, column `x`.
pub fn shown_index(page: &[u16; PAGE_HALFWORDS], resolution: Resolution, x: usize, y: usize) -> u8 {
    let page_row = (y * resolution.bg2_pd() as usize) >> 8;
    let halfword = page[page_row * PAGE_ROW_HALFWORDS + x / 2];
    if x.is_multiple_of(2) {
        (halfword & 0xff) as u8
    } else {
        (halfword >> 8) as u8
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_resolution_fills_the_screen() {
        for res in Resolution::ALL {
            let shown_rows = res.height() * 0x100 / res.bg2_pd() as usize;
            assert_eq!(shown_rows, PAGE_HEIGHT, "{res:?}");
            assert_eq!(res.width() / res.pixels_per_halfword(), PAGE_ROW_HALFWORDS);
            assert_eq!(Resolution::from_label(res.label()), Some(res));
        }
    }

    #[test]
    fn select_cycles_through_all_three() {
        let mut res = Resolution::R120x80;
        for _ in 0..3 {
            res = res.next();
        }
        assert_eq!(res, Resolution::R120x80);
    }
}
