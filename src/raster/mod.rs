//! Rasterizers: the portable Rust twins of the ARM kernels in `asm/`, the [`Canvas`] they draw
//! on, and the jobs of the ARM wall loop ([`wall_run`]) and span set-up ([`plane_run`]), whose
//! twins are the renderer's own.
//!
//! Every kernel in `asm/*.s` has a twin here with the same arguments and the same arithmetic
//! (including wrap-around), so the host can render exactly what the ROM renders; an emulator test
//! compares the two pixel for pixel.

pub mod column;
pub mod flat;
pub mod middle_run;
pub mod plane_run;
pub mod span;
pub mod sprite;
pub mod wall_run;

/// The light row that changes nothing: what draws unlit through a lit kernel (a sprite, or an
/// unlit column in a lit frame).
pub static IDENTITY_ROW: [u8; 256] = {
    let mut row = [0u8; 256];
    let mut index = 0;
    while index < 256 {
        row[index] = index as u8;
        index += 1;
    }
    row
};

/// A column window: rows `top..bottom` (half-open). `top >= bottom` means empty. `repr(C)`,
/// word aligned: the ARM wall loop reads and writes one as a word, `top` in its low half, and
/// `make_spans` compares two with one word compare.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
#[repr(C, align(4))]
pub struct Window {
    /// First row in the window.
    pub top: i16,
    /// One past the last row.
    pub bottom: i16,
}

impl Window {
    /// The empty window.
    pub const EMPTY: Window = Window { top: 0, bottom: 0 };

    /// True if no row is in the window.
    pub const fn is_empty(self) -> bool {
        self.top >= self.bottom
    }

    /// The window as the word the ARM wall loop stores: `top` in the low half. Two windows are
    /// equal if and only if their words are.
    #[inline(always)]
    pub const fn word(self) -> u32 {
        (self.top as u16 as u32) | ((self.bottom as u16 as u32) << 16)
    }
}

use crate::frame::{PAGE_HALFWORDS, PAGE_ROW_HALFWORDS};
use crate::raster::span::SpanTarget;
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
        HostPage {
            halfwords: [0; PAGE_HALFWORDS],
        }
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
        span::draw_span(
            &mut self.halfwords[start..start + halfwords],
            texture,
            steps,
            packing,
        );
    }
}

use crate::frame::Resolution;
use column::ColumnTexture;
use flat::FlatTexture;

/// Where the renderer's columns and spans go: VRAM through the asm kernels on the GBA, a host
/// page through the twins on the host. Coordinates are logical (at the canvas's resolution);
/// rows are page rows.
pub trait Canvas {
    /// The resolution this canvas draws at.
    fn resolution(&self) -> Resolution;
    /// Draws `count` rows of logical column `x`, from row `row` down.
    fn column(&mut self, x: usize, row: usize, count: usize, texture: &ColumnTexture);
    /// Draws columns `x` and `x + 1`, each `(row, count, texture)` as [`Canvas::column`]
    /// draws it, the first then the second. A canvas whose halfwords hold two pixels (the
    /// GBA's at 240 wide, `x` even) draws both with one kernel: one store a row where both
    /// have rows, instead of a read-modify-write for each.
    fn column_pair(
        &mut self,
        x: usize,
        first: (usize, usize, &ColumnTexture),
        second: (usize, usize, &ColumnTexture),
    ) {
        self.column(x, first.0, first.1, first.2);
        self.column(x + 1, second.0, second.1, second.2);
    }
    /// Draws the runs of sprite column `column` at logical column `x` (rows inside its clip
    /// window, which lies inside the screen).
    fn sprite_column(&mut self, x: usize, column: &sprite::SpriteColumn);
    /// Draws the columns of `batch` in order, each as [`Canvas::sprite_column`] draws it, and
    /// skips those [`sprite::SpriteBatch::column`] skips. A canvas with a batch kernel (the
    /// GBA's) draws them with one call.
    fn sprite_columns(&mut self, batch: &sprite::SpriteBatch) {
        for record in batch.columns {
            if let Some(column) = batch.column(record) {
                self.sprite_column(usize::from(record.x), &column);
            }
        }
    }
    /// Draws `count` logical pixels of row `row`, from logical column `x` rightwards.
    fn flat(&mut self, row: usize, x: usize, count: usize, texture: &FlatTexture);
    /// Whether the next flats are drawn at half horizontal resolution where a VRAM halfword
    /// holds two pixels (240 wide; [`FlatTexture::indices_from`]'s rule, ignored at 120 wide).
    /// The planes stage sets it around a plane's spans from the view; anything else (the menu,
    /// the HUD) draws full. Per plane rather than per span, so the default costs no span a
    /// thing.
    fn set_halved_flats(&mut self, halved: bool);
    /// Names the surface the next calls draw: recorded by the host's coverage checks, ignored
    /// on the GBA.
    #[inline]
    fn set_surface(&mut self, surface: crate::render::surface::Surface) {
        let _ = surface;
    }

    /// Says whether the next calls draw lit (through a colormap row) or unlit: a canvas whose
    /// kernels for the two are not all in fast memory at once (the GBA's kernel banks,
    /// `hw::kernels`) brings in the ones asked for. The renderer says it once a frame, from the
    /// view's lighting. Every call draws the same pixels whatever was said.
    #[inline]
    fn prefer_lighting(&mut self, lit: bool) {
        let _ = lit;
    }

    /// Draws the columns of `run` with the canvas's own column loop, if it has one (the GBA's
    /// ARM wall loop, `asm/wall.s`), and says how the run ended; `None` if it has none, and then
    /// nothing is drawn: the renderer draws the columns with its own loop, the loop's twin.
    #[inline]
    fn wall_run(&mut self, run: &mut wall_run::WallRun) -> Option<wall_run::WallRunEnd> {
        let _ = run;
        None
    }

    /// Draws the spans of `run` with the canvas's own span loop, if it has one (the GBA's ARM
    /// loop, `asm/plane.s`), and says where it stopped; `None` if it has none, and then nothing
    /// is drawn: the renderer makes and sets up the spans itself, the loop's twin.
    #[inline]
    fn plane_run(&mut self, run: &mut plane_run::PlaneRun) -> Option<plane_run::PlaneRunEnd> {
        let _ = run;
        None
    }

    /// Computes the columns of the portal middle `run` into `out`, one per column of the run
    /// at most, with the canvas's own loop if it has one (the GBA's ARM routine,
    /// `asm/middle.s`), and says how many it wrote; `None` if it has none: the renderer's own
    /// loop, the routine's twin, does it.
    #[inline]
    fn middle_columns(
        &mut self,
        run: &mut middle_run::MiddleRun,
        out: &mut [sprite::BatchColumn],
    ) -> Option<usize> {
        let _ = (run, out);
        None
    }
}

/// A [`HostPage`] drawn at a resolution: the host twin of the GBA's VRAM canvas.
pub struct HostCanvas<'a> {
    /// The page drawn into.
    pub page: &'a mut HostPage,
    /// The resolution drawn at.
    pub resolution: Resolution,
    /// Flats at half horizontal resolution ([`Canvas::set_halved_flats`]).
    pub halved_flats: bool,
}

impl HostCanvas<'_> {
    /// The palette index at logical column `x`, row `row`.
    fn get(&self, x: usize, row: usize) -> u8 {
        let halfword = self.page.halfwords
            [row * PAGE_ROW_HALFWORDS + x / self.resolution.pixels_per_halfword()];
        match (self.resolution.pixels_per_halfword(), x % 2) {
            (2, 1) => (halfword >> 8) as u8,
            _ => halfword as u8,
        }
    }

    fn put(&mut self, x: usize, row: usize, index: u8) {
        let halfword = &mut self.page.halfwords
            [row * PAGE_ROW_HALFWORDS + x / self.resolution.pixels_per_halfword()];
        *halfword = match (self.resolution.pixels_per_halfword(), x % 2) {
            (1, _) => u16::from(index) * 0x0101,
            (_, 0) => (*halfword & 0xff00) | u16::from(index),
            _ => (*halfword & 0x00ff) | (u16::from(index) << 8),
        };
    }
}

impl Canvas for HostCanvas<'_> {
    fn resolution(&self) -> Resolution {
        self.resolution
    }

    fn column(&mut self, x: usize, row: usize, count: usize, texture: &ColumnTexture) {
        assert!(x < self.resolution.width() && row + count <= self.resolution.height());
        for (offset, index) in texture.indices(count).enumerate() {
            self.put(x, row + offset, index);
        }
    }

    fn sprite_column(&mut self, x: usize, column: &sprite::SpriteColumn) {
        assert!(
            x < self.resolution.width()
                && column.clip.top >= 0
                && column.clip.bottom as usize <= self.resolution.height()
        );
        for run in column.runs() {
            for (offset, index) in column.indices(run).enumerate() {
                let row = run.row + offset;
                let index = column.over(self.get(x, row), index);
                self.put(x, row, index);
            }
        }
    }

    fn flat(&mut self, row: usize, x: usize, count: usize, texture: &FlatTexture) {
        assert!(row < self.resolution.height() && x + count <= self.resolution.width());
        let halved = self.halved_flats && self.resolution.pixels_per_halfword() == 2;
        let indices = texture.indices_from(x, count, halved);
        for (offset, index) in indices.enumerate() {
            self.put(x + offset, row, index);
        }
    }

    fn set_halved_flats(&mut self, halved: bool) {
        self.halved_flats = halved;
    }
}
