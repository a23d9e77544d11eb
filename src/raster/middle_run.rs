//! A portal middle's columns, handed whole to a canvas that has a loop of its own for them: the
//! GBA's ARM routine in `asm/middle.s` (`Canvas::middle_columns`). For each column of the
//! middle's wall it finds where the column's ray crosses the wall, exactly (a ray on a texel
//! edge takes the texel right of it, the oracle's rule), and from that the image column, the
//! depth's light row, the top row and the steps the sprite batch kernel draws with. The
//! renderer's own loop (`render::things::middle_columns`) is its portable twin: the
//! host draws with it, and the emulator's ROM-versus-host frame test compares the two pixel for
//! pixel, as the kernel check does on random walls (`kernel_check`).
//!
//! Everything the routine reads through a pointer is checked here, and what it writes by the
//! canvas, so building a run is safe and the routine can trust it.

use core::marker::PhantomData;

use super::Window;
use crate::math::tables::RECIP_SEED_U16;

/// The two affine quantities a middle's columns step, what every column shares, and (set by the
/// canvas) where its columns go.
#[derive(Debug)]
#[repr(C)]
pub struct MiddleRun<'a> {
    /// The numerator and the denominator of the ray's fraction along the wall at the column
    /// before `x`, then their steps per column (64-bit, low word first).
    pub(crate) numerator: [u32; 2],
    pub(crate) denominator: [u32; 2],
    pub(crate) numerator_step: [u32; 2],
    pub(crate) denominator_step: [u32; 2],
    /// The columns `x..end`.
    pub(crate) x: u32,
    pub(crate) end: u32,
    /// Where column 0's opening would be: the middle's are at columns `x..end`.
    pub(crate) opening: *const Window,
    /// Set by the canvas: where the next column goes.
    pub(crate) out: *mut u8,
    pub(crate) shared: MiddleShared,
    pub(crate) recip_seeds: *const u16,
    borrows: PhantomData<&'a [Window]>,
}

/// What a middle's columns share, as the renderer computes them for its own loop too.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub struct MiddleShared {
    /// The wall's first end's eye-space depth, and its change to the other end, in 24.8 bits.
    pub za: i32,
    /// See `za`.
    pub dz: i32,
    /// The wall's length and texture offset, in 24.8 bits.
    pub length_fx8: i32,
    /// See `length_fx8`.
    pub x_offset_fx8: i32,
    /// `1/z'` in 2.30 is the denominator times this, shifted right by `wall_shift`, at most
    /// `nearest`; `nearest` alone where the reciprocal is 0.
    pub wall_reciprocal: u32,
    /// See `wall_reciprocal`.
    pub wall_shift: u32,
    /// See `wall_reciprocal`.
    pub nearest: u32,
    /// The horizon row in 16.16 bits.
    pub horizon_fx16: i32,
    /// The eye's height over the image's top edge times `d_y`, in 24.8 bits.
    pub above_eye_focal: i32,
    /// `d_y`, and its reciprocal in 2.30 bits.
    pub focal_y: i32,
    /// See `focal_y`.
    pub inverse_focal_y: i32,
    /// The image's width in columns.
    pub width: u32,
    /// 0 unlit, 1 the colormap row `light_base`, 2 the row of `light_base − depth/16 units`.
    pub light_mode: u32,
    /// See `light_mode`.
    pub light_base: i32,
    /// The least depth a column takes, in 24.8 bits.
    pub depth_min: i32,
}

impl<'a> MiddleRun<'a> {
    /// The columns `columns` of a middle whose ray fraction has `numerator` and `denominator`
    /// at the column before the first, stepping by `steps`, seen through `opening` (indexed by
    /// column); `None` if `opening` does not hold them or the image's width is not a power of
    /// two (the routine masks the column).
    pub fn new(
        shared: MiddleShared,
        numerator: i64,
        denominator: i64,
        steps: (i64, i64),
        columns: core::ops::Range<i32>,
        opening: &'a [Window],
    ) -> Option<MiddleRun<'a>> {
        let (x, end) = (
            u32::try_from(columns.start).ok()?,
            u32::try_from(columns.end).ok()?,
        );
        if x > end || end as usize > opening.len() || !shared.width.is_power_of_two() {
            return None;
        }
        let words = |value: i64| [value as u32, (value >> 32) as u32];
        Some(MiddleRun {
            numerator: words(numerator),
            denominator: words(denominator),
            numerator_step: words(steps.0),
            denominator_step: words(steps.1),
            x,
            end,
            opening: opening.as_ptr(),
            out: core::ptr::null_mut(),
            shared,
            recip_seeds: RECIP_SEED_U16.as_ptr(),
            borrows: PhantomData,
        })
    }

    /// How many columns the run may write: one per column of `x..end`.
    pub fn columns(&self) -> usize {
        (self.end - self.x) as usize
    }
}
