//! One plane's spans, handed whole to a canvas that has a span loop of its own: the GBA's ARM
//! routine in `asm/plane.s` (`Canvas::plane_run`), Doom's `R_MakeSpans`, `R_MapPlane` and the
//! calls of its span kernel in one. The renderer's own (`render::spans::make_spans`, then
//! `render::planes`' `PlaneSpans::span_twin` and `Canvas::flat`) is its portable twin: the host
//! draws with it, and the emulator's ROM-versus-host frame test compares the two pixel for
//! pixel.
//!
//! The routine turns the plane's column windows into spans as `make_spans` does, and per span
//! does what the twin does: the row's depth from the table of small reciprocals, the mip ratio
//! (it stops before a span whose ratio the plane's level does not hold, so the renderer can look
//! the level up and start it again), the map position of the row's centre pixel and the step per
//! pixel from the frame's plane rays, both packed, the light row, and at 240 wide the pixels
//! that share a halfword with a pixel outside the span; then the span kernel.
//!
//! Everything the routine reads or writes through a pointer is checked here or by the canvas
//! when the run is prepared, and the routine checks each span's row and columns against the
//! viewport, so building a run is safe and the routine can trust it.

use core::marker::PhantomData;

use super::flat::FLAT_LOG2_SIDES;
use super::wall_run::RunLight;
use super::Window;
use crate::math::tables::{RECIP_SMALL_FX2_30, RECIP_SMALL_LEN};

/// What a plane's spans share: its depth rule, the frame's rays, the eye, its light and (set by
/// [`PlaneRun::set_level`]) its mip level; and, set by the canvas, where and how it draws.
#[derive(Debug)]
#[repr(C)]
pub struct PlaneRun<'a> {
    /// `|eye − plane|·2·d_y` in 24.8 bits: a row's depth is this times `1/|2·(row − cy) + 1|`.
    pub(crate) depth_numerator: i32,
    pub(crate) horizon_y: i32,
    /// 1 for a floor seen from above: its rows are below the horizon; 0 for a ceiling.
    pub(crate) below_eye: u32,
    /// `1/d_y` in 2.30 bits, for the mip ratio.
    pub(crate) inverse_focal_y: i32,
    /// The mip ratios the level holds (an empty range before the first level).
    pub(crate) ratio_low: i32,
    pub(crate) ratio_high: i32,
    pub(crate) level: u32,
    pub(crate) side_log2: u32,
    pub(crate) texels: *const u8,
    pub(crate) centre_x: i32,
    /// The frame's plane rays in 2.30 bits: centre x, centre y, step x, step y.
    pub(crate) rays: [i32; 4],
    /// The eye's map position in 16.16, 64-bit, low word first: x, then y.
    pub(crate) eye: [u32; 4],
    /// 0 unlit, 1 one row, 2 the row of the depth (as [`RunLight`]).
    pub(crate) light_mode: u32,
    pub(crate) light_base: i32,
    pub(crate) colormap: *const u8,
    pub(crate) recip_small: *const i32,
    /// Set by the canvas: the page's first byte, 1 where two pixels share a halfword, 1 for
    /// halved floors there, the span kernels of the plane's light by flat side (`FLAT_LOG2_SIDES`
    /// from its start), 1 to write the pixels the kernels do not, and the viewport.
    pub(crate) page: *mut u8,
    pub(crate) native: u32,
    pub(crate) halved: u32,
    pub(crate) kernels: *const usize,
    pub(crate) draw_edges: u32,
    pub(crate) height: u32,
    pub(crate) width: u32,
    /// The mip ratio of the span the routine stopped at.
    pub(crate) miss_ratio: i32,
    /// Where column 0's window would be: the plane's are at columns `x..end`.
    pub(crate) windows: *const Window,
    /// The column each row's open span starts at, one entry per row (`span_start_rows`).
    pub(crate) span_start: *mut i16,
    /// The scan: the next column, the column after the last, the window the rows still open
    /// are in, and 1 while the column `x`'s change of rows is under way.
    pub(crate) x: u32,
    pub(crate) end: u32,
    pub(crate) old: u32,
    pub(crate) mid: u32,
    /// Spans and pixels the routine drew.
    pub(crate) spans: u32,
    pub(crate) pixels: u32,
    /// The span the routine left to the renderer: start, end, row.
    pub(crate) pending: [u32; 3],
    /// The rows `span_start` has (the canvas checks they cover its height).
    pub(crate) span_start_rows: u32,
    /// Set by [`PlaneRun::pick_levels`]: the flat's row-major mip chain, where the routine
    /// picks a span's level itself (null: it stops and the renderer picks), its side at level
    /// 0 (log2), and the levels its spans may take.
    pub(crate) chain: *const u8,
    pub(crate) chain_side_log2: u32,
    pub(crate) chain_shallowest: u32,
    pub(crate) chain_deepest: u32,
    borrows: PhantomData<(&'a [u8], &'a [Window], &'a mut [i16])>,
}

/// Where a canvas's span loop stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlaneRunEnd {
    /// Every span is drawn.
    Done,
    /// Before a span whose mip ratio this is, which the run's level does not hold.
    MipLevel(i32),
    /// After a span it left to the renderer, undrawn: one outside the viewport, or on a row on
    /// the plane's far side of the horizon.
    Declined {
        /// Its row.
        row: usize,
        /// Its first column.
        start: usize,
        /// The column after its last.
        end: usize,
    },
}

/// A plane's constants, as `render::planes` computes them for its own spans.
#[derive(Clone, Copy, Debug)]
pub struct PlaneConstants {
    /// `|eye − plane|·2·d_y` in 24.8 bits.
    pub depth_numerator: i32,
    /// The horizon row.
    pub horizon_y: i32,
    /// The plane is below the eye.
    pub below_eye: bool,
    /// `1/d_y` in 2.30 bits.
    pub inverse_focal_y: i32,
    /// The viewport's centre column.
    pub centre_x: i32,
    /// The frame's plane rays in 2.30 bits: centre x, centre y, step x, step y.
    pub rays: [i32; 4],
    /// The eye's map position in 16.16.
    pub eye: (i64, i64),
}

impl<'a> PlaneRun<'a> {
    /// The run of a plane with `constants`, lit by `light`, over `windows` (one per column from
    /// column `first`), with `span_start` for scratch (one entry per row), and no level yet.
    pub fn new(
        constants: PlaneConstants,
        light: RunLight<'a>,
        windows: &'a [Window],
        first: usize,
        span_start: &'a mut [i16],
    ) -> PlaneRun<'a> {
        let (light_mode, light_base, colormap) = match light {
            RunLight::Off => (0, 0, core::ptr::null()),
            RunLight::Fixed(row) => (1, 0, row.as_ptr()),
            RunLight::Depth { base, colormap } => (2, base, colormap.as_ptr().cast::<u8>()),
        };
        let words = |value: i64| [value as u32, (value >> 32) as u32];
        let ([x_low, x_high], [y_low, y_high]) = (words(constants.eye.0), words(constants.eye.1));
        PlaneRun {
            depth_numerator: constants.depth_numerator,
            horizon_y: constants.horizon_y,
            below_eye: u32::from(constants.below_eye),
            inverse_focal_y: constants.inverse_focal_y,
            ratio_low: 1,
            ratio_high: 0,
            level: 0,
            side_log2: 0,
            texels: core::ptr::null(),
            centre_x: constants.centre_x,
            rays: constants.rays,
            eye: [x_low, x_high, y_low, y_high],
            light_mode,
            light_base,
            colormap,
            recip_small: RECIP_SMALL_FX2_30.as_ptr(),
            page: core::ptr::null_mut(),
            native: 0,
            halved: 0,
            kernels: core::ptr::null(),
            draw_edges: 0,
            height: 0,
            width: 0,
            miss_ratio: 0,
            windows: windows.as_ptr().wrapping_sub(first),
            x: first as u32,
            end: (first + windows.len()) as u32,
            span_start_rows: span_start.len() as u32,
            span_start: span_start.as_mut_ptr(),
            chain: core::ptr::null(),
            chain_side_log2: 0,
            chain_shallowest: 0,
            chain_deepest: 0,
            old: 0,
            mid: 0,
            spans: 0,
            pixels: 0,
            pending: [0; 3],
            borrows: PhantomData,
        }
    }

    /// The plane takes mip `level` for the ratios `ratios`: its flat `texels`, `2^side_log2`
    /// texels a side. A level whose side no span kernel takes, or whose texels are not a square
    /// of that side, is refused: the run keeps an empty range, so every span asks again.
    pub fn set_level(&mut self, level: u8, side_log2: u32, texels: &'a [u8], ratios: (i32, i32)) {
        let fits = FLAT_LOG2_SIDES.contains(&side_log2) && texels.len() == 1 << (2 * side_log2);
        (self.ratio_low, self.ratio_high) = if fits { ratios } else { (1, 0) };
        self.level = u32::from(level);
        self.side_log2 = side_log2;
        self.texels = if fits {
            texels.as_ptr()
        } else {
            core::ptr::null()
        };
    }

    /// Lets the routine pick each span's level itself, as the renderer's rule does
    /// (`render::planes`' `PlaneLevel::of`): the level `floor(log2(ratio))` clamped to
    /// `shallowest..=deepest`, its texels at its place in `chain`, a square flat's row-major mip
    /// chain of side `2^side_log2` at level 0. Refused (the routine keeps stopping for the
    /// renderer) unless every level in the range has a side a span kernel takes and lies inside
    /// `chain`.
    pub fn pick_levels(&mut self, chain: &'a [u8], side_log2: u32, shallowest: u8, deepest: u8) {
        let (shallowest, deepest) = (u32::from(shallowest), u32::from(deepest));
        let sides_fit = shallowest <= deepest
            && deepest <= side_log2
            && FLAT_LOG2_SIDES.contains(&(side_log2 - deepest))
            && FLAT_LOG2_SIDES.contains(&(side_log2 - shallowest));
        // The deepest level's end: Σ_{m ≤ deepest} 4^(side − m).
        let chain_end = || {
            (0..=deepest)
                .map(|level| 1usize << (2 * (side_log2 - level)))
                .sum::<usize>()
        };
        if sides_fit && chain_end() <= chain.len() {
            self.chain = chain.as_ptr();
            self.chain_side_log2 = side_log2;
            self.chain_shallowest = shallowest;
            self.chain_deepest = deepest;
        }
    }

    /// Whether the run has a level its spans can be drawn at.
    pub fn has_level(&self) -> bool {
        !self.texels.is_null()
    }

    /// The spans and pixels the canvas's loop drew.
    pub fn drawn(&self) -> (u32, u32) {
        (self.spans, self.pixels)
    }

    /// The span the loop left to the renderer (`PlaneRunEnd::Declined`).
    pub fn declined(&self) -> PlaneRunEnd {
        let [start, end, row] = self.pending.map(|word| word as usize);
        PlaneRunEnd::Declined { row, start, end }
    }

    /// Whether the run has no colormap row of its own (unlit): the canvas then picks the
    /// kernels' bank and the row it hands them.
    pub fn unlit(&self) -> bool {
        self.light_mode == 0
    }
}

// The routine reads `1/n` for `n = |2·(row − cy) + 1|` from the table, and leaves a span whose
// `n` is 512 or more to the renderer: the table must have those 512 entries.
const _: () = assert!(RECIP_SMALL_LEN == 512);

#[cfg(test)]
mod tests {
    use super::*;

    fn run<'a>(windows: &'a [Window], span_start: &'a mut [i16]) -> PlaneRun<'a> {
        let constants = PlaneConstants {
            depth_numerator: 1 << 16,
            horizon_y: 40,
            below_eye: true,
            inverse_focal_y: 1 << 24,
            centre_x: 60,
            rays: [1 << 30, 0, 0, 1 << 24],
            eye: (-(1 << 40), 1 << 33),
        };
        PlaneRun::new(constants, RunLight::Off, windows, 7, span_start)
    }

    #[test]
    fn a_level_is_taken_only_with_a_square_of_a_side_the_kernels_take() {
        let windows = [Window { top: 0, bottom: 4 }; 3];
        let mut span_start = [0i16; 80];
        let mut run = run(&windows, &mut span_start);
        assert!(!run.has_level(), "no level before the first");
        assert!(
            run.ratio_low > run.ratio_high,
            "an empty range asks for one"
        );
        let flat = [0u8; 64 * 64];
        run.set_level(2, 6, &flat, (4, 7));
        assert!(run.has_level());
        assert_eq!(
            (run.ratio_low, run.ratio_high, run.level, run.side_log2),
            (4, 7, 2, 6)
        );
        // A square of another side, and a side no kernel takes: refused, the range empty.
        run.set_level(1, 5, &flat, (2, 3));
        assert!(!run.has_level() && run.ratio_low > run.ratio_high);
        run.set_level(0, 7, &[0u8; 128 * 128], (0, 1));
        assert!(!run.has_level() && run.ratio_low > run.ratio_high);
    }

    #[test]
    fn levels_are_picked_by_the_loop_only_inside_the_chain_and_the_kernels_sides() {
        let windows = [Window { top: 0, bottom: 4 }; 3];
        let mut span_start = [0i16; 80];
        // A 64-texel square's chain down to 8 texels: 4096 + 1024 + 256 + 64.
        let chain = [0u8; 5440];
        let mut picking = run(&windows, &mut span_start);
        picking.pick_levels(&chain, 6, 0, 3);
        assert_eq!(
            (
                picking.chain,
                picking.chain_side_log2,
                picking.chain_shallowest,
                picking.chain_deepest
            ),
            (chain.as_ptr(), 6, 0, 3)
        );
        let refused = |chain: &[u8], side: u32, shallowest: u8, deepest: u8| {
            let mut span_start = [0i16; 80];
            let mut picking = run(&windows, &mut span_start);
            picking.pick_levels(chain, side, shallowest, deepest);
            picking.chain.is_null()
        };
        assert!(
            refused(&chain[..5439], 6, 0, 3),
            "the deepest level past the chain"
        );
        assert!(refused(&chain, 6, 0, 4), "a 4-texel level no kernel takes");
        assert!(
            refused(&chain, 7, 0, 3),
            "a 128-texel level no kernel takes"
        );
        assert!(refused(&chain, 6, 2, 1), "an empty range");
        // A 128-texel square from its level 1 (64) to 3 (16): 16384 + 4096 + 1024 + 256.
        assert!(refused(&[0u8; 21759], 7, 1, 3));
        assert!(!refused(&[0u8; 21760], 7, 1, 3));
    }

    #[test]
    fn the_scan_starts_at_the_first_window_with_the_eye_in_words() {
        let windows = [Window { top: 1, bottom: 9 }; 5];
        let mut span_start = [0i16; 80];
        let run = run(&windows, &mut span_start);
        assert_eq!((run.x, run.end, run.old, run.mid), (7, 12, 0, 0));
        // windows[0] is read at column `first`.
        assert_eq!(run.windows.wrapping_add(7), windows.as_ptr());
        assert_eq!(run.eye, [0, (-(1i64 << 40) >> 32) as u32, 0, 2]);
        assert_eq!(run.drawn(), (0, 0));
    }
}
