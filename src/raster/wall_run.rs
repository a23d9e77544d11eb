//! A run of a wall's columns, handed whole to a canvas that has a column loop of its own: the
//! GBA's ARM loop in `asm/wall.s` (`Canvas::wall_run`). The renderer's own loop over the same
//! columns (`render::walk`, `draw_stepped_wall`) is its portable twin: the host draws with it,
//! and the emulator's ROM-versus-host frame test compares the two pixel for pixel.
//!
//! Per column the loop does what the twin does (Doom's `R_RenderSegLoop`): the rows of the
//! wall's heights from its 32-bit `1/z'`, the column's ceiling, floor and clip windows, and,
//! where a strip is drawn, the texture column (one table-and-Newton reciprocal), the mip level,
//! the light and each strip's column kernel. It stops before a column whose strips need a mip
//! level the run does not hold, having changed nothing of it, so the renderer can look the level
//! up and start the run again at that column.
//!
//! Everything the loop reads or writes through a pointer is checked here when the run is built,
//! so building one is safe and the loop can trust it.

use core::marker::PhantomData;

use super::Window;
use portalcast_format::Colormap;

/// A wall's column accumulators and row constants, as the renderer's `SteppedWall` steps them:
/// `1/z'` and `t/z'` in 2.30 with their steps per column, `−d_y·h` of its four heights (24.8),
/// the high word of the rows' base ([`WallSteps::row`]), and the viewport's height.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct WallSteps {
    /// `1/z'` at the run's current column.
    pub inverse_depth: i32,
    /// Its step per column.
    pub inverse_depth_step: i32,
    /// `t/z'` at the run's current column.
    pub along_over_depth: i32,
    /// Its step per column.
    pub along_over_depth_step: i32,
    /// `−d_y·h` of the sector's ceiling and floor, then the neighbour's (`|d_y·h| < 2^29`).
    pub negated_scales: [i32; 4],
    /// The high word of the rows' base, [`WallSteps::row_base_of`] the horizon row.
    pub row_base: i32,
    /// Rows are clamped to `[0, height]`.
    pub height: i32,
}

/// The low word of every row base ([`WallSteps::row_base_of`]).
pub const ROW_BASE_LOW: u32 = 0xDFFF_FFFF;

impl WallSteps {
    /// The high word of the rows' base for the horizon at row `horizon_y`: the base is
    /// `(256·cy + 127)·2^30 + 2^29 − 1`, whose low word is [`ROW_BASE_LOW`] for every `cy`
    /// (`127·2^30` is `31·2^32 + 3·2^30`).
    pub const fn row_base_of(horizon_y: i32) -> i32 {
        (horizon_y << 6) + 31
    }

    /// The row of the height whose `−d_y·h` is `negated_scale` at the current column, clamped
    /// to `[0, height]`: `(256·cy + 127 − ((d_y·h·(1/z') + 2^29) >> 30)) >> 8`, the 24.8 row
    /// rounded to nearest and floored to its pixel, as one 64-bit sum and shift (`x − ⌊a⌋` is
    /// `⌈x − a⌉`, and `⌊⌈b / 2^30⌉ / 2^8⌋` is `⌊(b + 2^30 − 1) / 2^38⌋`): the ARM loop's one
    /// multiply-accumulate and shift a row.
    #[inline(always)]
    pub fn row(&self, negated_scale: i32) -> i32 {
        let base = i64::from(self.row_base) << 32 | i64::from(ROW_BASE_LOW);
        // |d_y·h·(1/z')| < 2^59: the row is below 2^21 in magnitude. max then min: `clamp`
        // would carry a panic path for a bound it cannot miss.
        let row = (base + i64::from(negated_scale) * i64::from(self.inverse_depth)) >> 38;
        (row as i32).max(0).min(self.height)
    }
}

/// What a wall's columns leave and draw: a solid wall (one strip, the clip window closed), a
/// portal with no strip (the opening between this sector's ceiling and floor), or a portal with
/// an upper strip, a lower strip or both.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WallKind {
    /// A solid wall.
    Solid,
    /// A portal whose neighbour's ceiling and floor are not inside this sector's.
    Opening,
    /// A portal with strips.
    Portal {
        /// The upper strip is drawn (see `render::walk::PortalJob`).
        upper: bool,
        /// The lower strip is drawn.
        lower: bool,
    },
}

impl WallKind {
    /// A portal drawing an upper strip or not, and a lower strip or not.
    pub const fn portal(upper: bool, lower: bool) -> WallKind {
        if upper || lower {
            WallKind::Portal { upper, lower }
        } else {
            WallKind::Opening
        }
    }

    /// Whether its columns draw each strip (the wall's own, or a portal's upper; a portal's
    /// lower).
    pub const fn draws(self) -> [bool; 2] {
        match self {
            WallKind::Solid => [true, false],
            WallKind::Opening => [false, false],
            WallKind::Portal { upper, lower } => [upper, lower],
        }
    }

    /// Whether its columns read the rows of the neighbour's heights (a portal with a strip).
    pub const fn reads_neighbour(self) -> bool {
        matches!(self, WallKind::Portal { .. })
    }

    /// The word the loop reads: 0, 1 or 2 in the low bits, the strips in bits 8 and 9.
    const fn word(self) -> u32 {
        match self {
            WallKind::Solid => 0,
            WallKind::Opening => 1,
            WallKind::Portal { upper, lower } => 2 | (upper as u32) << 8 | (lower as u32) << 9,
        }
    }
}

/// How the loop lights a column: not at all (the unlit kernels), through one colormap row for
/// the whole wall, or through the row of the sector's light less one step per 16 units of depth
/// (`render::light`).
#[derive(Clone, Copy, Debug)]
pub enum RunLight<'a> {
    /// Unlit.
    Off,
    /// One row.
    Fixed(&'a [u8; 256]),
    /// `light + DEPTH_BOOST − depth / DEPTH_UNITS_PER_STEP`, clamped to `0..=255`, of the table.
    Depth {
        /// The sector's light plus `DEPTH_BOOST`.
        base: i32,
        /// The whole colormap.
        colormap: &'a Colormap,
    },
}

/// What the loop needs of the texture: the wall's length and offset in texels, and `1/d_y`.
#[derive(Clone, Copy, Debug)]
pub struct RunTexturing {
    /// The wall's length in 24.8.
    pub length: i32,
    /// Its texture's x offset in 24.8.
    pub x_offset: i32,
    /// `1/d_y` in 2.30 bits.
    pub inverse_focal_y: i32,
    /// The viewport's horizon row.
    pub horizon_row: i32,
}

/// One strip's texture at a mip level, and the mip ratios that select it (an empty range until
/// the renderer has looked one up).
#[derive(Clone, Copy, Debug)]
pub struct StripRunLevel<'a> {
    /// `anchor − eye + y_offset` in 24.8 texels; only its low word reaches a pixel.
    pub eye_to_anchor: i64,
    /// log2 of the texture's height at level 0.
    pub base_height_log2: u32,
    /// The ratios `ratio_low..=ratio_high` select this level.
    pub ratio_low: i32,
    /// See `ratio_low`.
    pub ratio_high: i32,
    /// The mip level.
    pub level: u32,
    /// log2 of its width and height.
    pub width_log2: u32,
    /// See `width_log2`.
    pub height_log2: u32,
    /// Its texels, column-major: `2^(width_log2 + height_log2)` of them.
    pub texels: &'a [u8],
}

/// A strip as the loop reads it (layout: `asm/wall.s`).
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct StripRun {
    pub(crate) eye_to_anchor: u32,
    /// The mip level, log2 of its height and log2 of the texture's height at level 0, a byte
    /// each from the lowest.
    pub(crate) shape: u32,
    pub(crate) ratio_low: i32,
    pub(crate) ratio_high: i32,
    pub(crate) width_mask: u32,
    pub(crate) texels: *const u8,
    /// The canvas's column kernel for this height: where two pixels share a halfword, the one
    /// that draws two neighbouring columns at once (the loop hands it both).
    pub(crate) kernel: usize,
}

impl StripRun {
    /// `level` as the loop reads it, or [`StripRun::NONE`] where it breaks a kernel's bounds.
    #[inline(always)]
    fn of(level: StripRunLevel) -> StripRun {
        let sound = KERNEL_LOG2_HEIGHTS.contains(&level.height_log2)
            && level.width_log2 <= 16
            && level.texels.len() == 1 << (level.width_log2 + level.height_log2)
            && KERNEL_LOG2_HEIGHTS.contains(&level.base_height_log2);
        if !sound {
            return StripRun::NONE;
        }
        StripRun {
            eye_to_anchor: level.eye_to_anchor as u32,
            shape: level.level.min(31) | level.height_log2 << 8 | level.base_height_log2 << 16,
            ratio_low: level.ratio_low,
            ratio_high: level.ratio_high,
            width_mask: (1 << level.width_log2) - 1,
            texels: level.texels.as_ptr(),
            kernel: 0,
        }
    }

    /// log2 of the strip's height at its level (the GBA canvas picks its kernel by it).
    #[cfg_attr(not(target_os = "none"), allow(dead_code))]
    pub(crate) const fn height_log2(&self) -> u32 {
        (self.shape >> 8) & 0xff
    }

    const NONE: StripRun = StripRun {
        eye_to_anchor: 0,
        shape: 3 << 8 | 3 << 16,
        ratio_low: 1,
        ratio_high: 0,
        width_mask: 0,
        texels: core::ptr::null(),
        kernel: 0,
    };
}

/// The heights the column kernels take (log2): the same as `raster::column`'s.
const KERNEL_LOG2_HEIGHTS: core::ops::RangeInclusive<u32> = super::column::COLUMN_LOG2_HEIGHTS;

/// How a run stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WallRunEnd {
    /// Every column is drawn.
    Done,
    /// The current column's strips need the levels of this mip ratio: its windows are
    /// written, its strips not ([`WallRun::pending_strips`]); the loop starts again with them.
    MipLevel(i32),
}

/// The columns `column..stop` of a wall, with everything the loop reads and the windows it
/// writes (layout: `asm/wall.s`, checked against it on the GBA).
#[derive(Debug)]
#[repr(C)]
pub struct WallRun<'a> {
    pub(crate) steps: WallSteps,
    pub(crate) column: i32,
    pub(crate) stop: i32,
    pub(crate) kind: u32,
    pub(crate) clip: *mut Window,
    pub(crate) ceiling: *mut Window,
    pub(crate) floor: *mut Window,
    pub(crate) length: i32,
    pub(crate) x_offset: i32,
    pub(crate) inverse_focal_y: i32,
    pub(crate) light_mode: u32,
    pub(crate) light_base: i32,
    pub(crate) colormap: *const u8,
    pub(crate) recip_seeds: *const u16,
    pub(crate) horizon_row: i32,
    /// Set by the canvas: the page's first byte, and [`WallRun::NATIVE`] where two pixels
    /// share a halfword (else 0).
    pub(crate) page: *mut u8,
    pub(crate) native: u32,
    pub(crate) column_pixels: u32,
    pub(crate) strips_drawn: u32,
    pub(crate) miss_ratio: i32,
    /// 1 where the loop stopped at a column whose windows it has written: the rows of the
    /// strips it has still to draw there follow.
    pub(crate) resume: u32,
    pub(crate) resume_rows: [u32; 2],
    pub(crate) strips: [StripRun; 2],
    /// The plane windows the loop has written with rows in them: [`CEILING_SEEN`],
    /// [`FLOOR_SEEN`].
    pub(crate) planes_seen: u32,
    borrows: PhantomData<(&'a mut [Window], &'a [u8])>,
}

/// [`WallRun::planes_seen`]'s bit for a ceiling window with rows in it.
pub const CEILING_SEEN: u32 = 1;
/// [`WallRun::planes_seen`]'s bit for a floor window with rows in it.
pub const FLOOR_SEEN: u32 = 2;

impl<'a> WallRun<'a> {
    /// [`WallRun::native`] where two pixels share a halfword: the bit of the loop's flag word
    /// that says so (`asm/wall.s`, `NATIVE_BIT`).
    #[cfg_attr(not(target_os = "none"), allow(dead_code))]
    pub(crate) const NATIVE: u32 = 1 << 29;

    /// The columns `start..stop` of a wall with `steps` at `start`, writing the windows
    /// `clip`, `ceiling` and `floor` (indexed by column), its strips (0 upper or solid, 1
    /// lower) at `strips` (see [`WallRun::set_strip`]); or `None` if a window slice is too
    /// short or the range is empty.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    pub fn new(
        steps: WallSteps,
        kind: WallKind,
        start: i32,
        stop: i32,
        clip: &'a mut [Window],
        ceiling: &'a mut [Window],
        floor: &'a mut [Window],
        texturing: RunTexturing,
        light: RunLight<'a>,
        strips: [StripRunLevel<'a>; 2],
    ) -> Option<WallRun<'a>> {
        let end = usize::try_from(stop).ok()?;
        if start < 0 || start >= stop || [clip.len(), ceiling.len(), floor.len()].contains(&0) {
            return None;
        }
        if end > clip.len().min(ceiling.len()).min(floor.len()) || steps.height < 0 {
            return None;
        }
        let (light_mode, light_base, colormap) = match light {
            RunLight::Off => (0, 0, core::ptr::null()),
            RunLight::Fixed(row) => (1, 0, row.as_ptr()),
            RunLight::Depth { base, colormap } => (2, base, colormap.as_ptr().cast::<u8>()),
        };
        Some(WallRun {
            steps,
            column: start,
            stop,
            kind: kind.word(),
            clip: clip.as_mut_ptr(),
            ceiling: ceiling.as_mut_ptr(),
            floor: floor.as_mut_ptr(),
            length: texturing.length,
            x_offset: texturing.x_offset,
            inverse_focal_y: texturing.inverse_focal_y,
            light_mode,
            light_base,
            colormap,
            recip_seeds: crate::math::tables::RECIP_SEED_U16.as_ptr(),
            horizon_row: texturing.horizon_row,
            page: core::ptr::null_mut(),
            native: 0,
            column_pixels: 0,
            strips_drawn: 0,
            miss_ratio: 0,
            resume: 0,
            resume_rows: [0; 2],
            strips: strips.map(StripRun::of),
            planes_seen: 0,
            borrows: PhantomData,
        })
    }

    /// Strip `index` (0 upper or solid, 1 lower) takes `level`. A level whose texels are not
    /// `2^(width_log2 + height_log2)` or whose height no kernel takes is refused (the strip
    /// keeps an empty range, so the loop stops at its first column and asks again).
    #[inline(always)]
    pub fn set_strip(&mut self, index: usize, level: StripRunLevel<'a>) {
        if let Some(strip) = self.strips.get_mut(index) {
            *strip = StripRun::of(level);
        }
    }

    /// The wall's accumulators at the column the run is at.
    pub fn steps(&self) -> WallSteps {
        self.steps
    }

    /// The column the run is at (its `stop` when done).
    pub fn column(&self) -> i32 {
        self.column
    }

    /// Whether strip `index` has a level (a texture of a height the kernels take).
    pub fn strip_ready(&self, index: usize) -> bool {
        self.strips
            .get(index)
            .is_some_and(|strip| !strip.texels.is_null())
    }

    /// The strips' rows `(top, bottom)` still to draw at the run's column, whose windows the
    /// loop has written (it stopped there for a mip level); `None` if it has not started it.
    pub fn pending_strips(&self) -> Option<[(i32, i32); 2]> {
        let rows = |word: u32| ((word & 0xffff) as i32, (word >> 16) as i32);
        (self.resume != 0).then(|| self.resume_rows.map(rows))
    }

    /// Which plane windows the loop has written with rows in them so far: [`CEILING_SEEN`] and
    /// [`FLOOR_SEEN`]. A visit whose walls wrote none of a plane has no span of it to draw.
    pub fn planes_seen(&self) -> u32 {
        self.planes_seen
    }

    /// Pixels and strips drawn so far.
    pub fn drawn(&self) -> (u32, u32) {
        (self.column_pixels, self.strips_drawn)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn steps() -> WallSteps {
        WallSteps {
            inverse_depth: 1 << 24,
            inverse_depth_step: 0,
            along_over_depth: 0,
            along_over_depth_step: 0,
            negated_scales: [0; 4],
            row_base: WallSteps::row_base_of(40),
            height: 80,
        }
    }

    fn texturing() -> RunTexturing {
        RunTexturing {
            length: 64 << 8,
            x_offset: 0,
            inverse_focal_y: 1 << 24,
            horizon_row: 40,
        }
    }

    fn level(texels: &[u8], width_log2: u32, height_log2: u32) -> StripRunLevel<'_> {
        StripRunLevel {
            eye_to_anchor: 0,
            base_height_log2: 6,
            ratio_low: 0,
            ratio_high: 1,
            level: 0,
            width_log2,
            height_log2,
            texels,
        }
    }

    /// A run over `windows` (clip, ceiling, floor) with every other input fixed.
    fn run<'a>(
        windows: &'a mut [&'a mut [Window]; 3],
        kind: WallKind,
        columns: (i32, i32),
        strips: [StripRunLevel<'a>; 2],
    ) -> Option<WallRun<'a>> {
        let [clip, ceiling, floor] = windows;
        WallRun::new(
            steps(),
            kind,
            columns.0,
            columns.1,
            clip,
            ceiling,
            floor,
            texturing(),
            RunLight::Off,
            strips,
        )
    }

    #[test]
    fn a_run_needs_windows_past_its_last_column_and_a_column() {
        let texels = [0u8; 64 * 64];
        let strips = [level(&texels, 6, 6), level(&texels, 6, 6)];
        let [mut clip, mut ceiling, mut floor] = [[Window::EMPTY; 120]; 3];
        let mut check = |columns, short: bool| {
            let ceiling_len = if short { 99 } else { 120 };
            let mut windows = [&mut clip[..], &mut ceiling[..ceiling_len], &mut floor[..]];
            run(&mut windows, WallKind::Solid, columns, strips).is_some()
        };
        assert!(check((0, 120), false));
        assert!(!check((0, 121), false), "a column past the windows");
        assert!(!check((5, 5), false), "no column");
        assert!(!check((-1, 5), false), "a negative column");
        assert!(!check((0, 100), true), "a short window slice");
    }

    #[test]
    fn a_strip_level_the_kernels_cannot_take_is_refused() {
        let texels = [0u8; 64 * 64];
        let good = level(&texels, 6, 6);
        let [mut clip, mut ceiling, mut floor] = [[Window::EMPTY; 120]; 3];
        let mut windows = [&mut clip[..], &mut ceiling[..], &mut floor[..]];
        let portal = WallKind::Portal {
            upper: true,
            lower: true,
        };
        let mut run = run(&mut windows, portal, (0, 120), [good, good]).expect("a valid run");
        assert!(run.strip_ready(0) && run.strip_ready(1));
        // Too few texels for the level's size, a height no kernel takes, a base height out of
        // range: each leaves the strip with no level (an empty range, so the loop asks again).
        run.set_strip(0, level(&texels[..64 * 63], 6, 6));
        assert!(!run.strip_ready(0));
        run.set_strip(1, level(&texels[..64 * 4], 6, 2));
        assert!(!run.strip_ready(1));
        let tall_base = StripRunLevel {
            base_height_log2: 9,
            ..good
        };
        run.set_strip(1, tall_base);
        assert!(!run.strip_ready(1));
        run.set_strip(1, good);
        assert!(run.strip_ready(1));
        assert!(run.strips[0].ratio_low > run.strips[0].ratio_high);
    }

    #[test]
    fn pending_strips_unpack_their_rows() {
        let texels = [0u8; 64 * 64];
        let strips = [level(&texels, 6, 6), level(&texels, 6, 6)];
        let [mut clip, mut ceiling, mut floor] = [[Window::EMPTY; 120]; 3];
        let mut windows = [&mut clip[..], &mut ceiling[..], &mut floor[..]];
        let mut run = run(&mut windows, WallKind::Solid, (3, 9), strips).expect("a valid run");
        assert_eq!(run.pending_strips(), None);
        run.resume = 1;
        run.resume_rows = [12 | 40 << 16, 0];
        assert_eq!(run.pending_strips(), Some([(12, 40), (0, 0)]));
        assert_eq!((run.column(), run.stop), (3, 9));
    }
}
