//! Wall projection (Doom's r_segs): which columns a wall owns, and its depth and texture
//! position at each of them.
//!
//! **Ownership.** Column `c`'s ray leaves a convex sector through exactly one wall: the wall
//! `a → b` with `a` not right of the ray and `b` right of it ([`Viewport::side_of_column_ray`],
//! exact integer tests on the unclipped eye-space vertices, valid in front of and behind the
//! eye). A ray through a vertex belongs to the wall that starts there. Adjacent walls share the
//! vertex test, so no column is owned twice or by none, and no "assume it is to the left"
//! guess is needed for vertices behind the eye.
//!
//! **Per column.** With `q = 2(c − cx) + 1`, the ray is `x' : z' = q : 2d`. Intersecting it with
//! the wall line `a + t(b − a)` gives, in exact integers of the 24.8 coordinates,
//! `t = N(c)/D(c)` and `z' = 2d·K/D(c)` with `N = a.z·q − 2d·a.x`, `D = 2d·Δx − q·Δz` and
//! `K = a.z·Δx − a.x·Δz`. `N` and `D` are linear in `c`. The depth is clamped to the near plane
//! (`NEAR_DEPTH`), so an eye closer than that to a wall sees it as at the near plane.

use super::ratio::{ratio, ratio_shifted, Divisor};
use crate::math::{ExactEyePoint, EyePoint, Fx24_8, Fx2_30, Side, Viewport, NEAR_DEPTH};
use crate::raster::wall_run::WallSteps;

/// The columns `[start, end)` where a monotone predicate over `0..width` holds.
fn columns_where(width: i32, holds: impl Fn(i32) -> bool) -> (i32, i32) {
    let at_zero = holds(0);
    // The first column where the predicate differs from column 0 (or `width`).
    let (mut low, mut high) = (1, width);
    while low < high {
        let middle = (low + high) / 2;
        if holds(middle) == at_zero {
            low = middle + 1;
        } else {
            high = middle;
        }
    }
    if at_zero {
        (0, low)
    } else {
        (low, width)
    }
}

/// The columns `[start, end)` whose rays leave through the wall `a → b` (eye space).
pub fn owned_columns(viewport: &Viewport, a: EyePoint, b: EyePoint) -> (i32, i32) {
    let width = viewport.width;
    let (a_start, a_end) =
        columns_where(width, |c| viewport.side_of_column_ray(a, c) != Side::Right);
    let (b_start, b_end) =
        columns_where(width, |c| viewport.side_of_column_ray(b, c) == Side::Right);
    (a_start.max(b_start), a_end.min(b_end))
}

/// Which of the columns `[first, end)` have a point to the right of their ray: a prefix or a
/// suffix of them, since [`Viewport::side_of_column_ray`] is monotone in the column (the ray's
/// slope grows with it). Found by bisection over `[first, end)` only, so a narrow portal window
/// costs few steps, and computed once per vertex: the walls meeting at a vertex share it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VertexSplit {
    /// The point is right of column `first`'s ray, so right of every ray before `boundary`.
    right_first: bool,
    /// The first column in `(first, end]` whose side differs from column `first`'s (or `end`).
    boundary: i32,
}

impl VertexSplit {
    /// The split of the columns `[first, end)` (`first < end`) by the eye-space point `p`.
    pub fn new(viewport: &Viewport, p: EyePoint, first: i32, end: i32) -> VertexSplit {
        VertexSplit::by_side(first, end, |c| {
            viewport.side_of_column_ray(p, c) == Side::Right
        })
    }

    /// [`VertexSplit::new`] of an exact point: what the renderer's column ownership uses
    /// ([`ExactEyePoint`]). `rounded` is the point rounded; `exact` computes the point itself,
    /// which only a split whose ends lie within a rounding step of a column's ray needs: there the
    /// exact test decides.
    pub fn new_exact(
        viewport: &Viewport,
        rounded: EyePoint,
        exact: impl FnOnce() -> ExactEyePoint,
        first: i32,
        end: i32,
    ) -> VertexSplit {
        let split = VertexSplit::new(viewport, rounded, first, end);
        let keeps = |column: i32| viewport.rounding_keeps_side(rounded, column);
        if keeps(first)
            && (split.boundary == first + 1 || keeps(split.boundary - 1))
            && (split.boundary == end || keeps(split.boundary))
        {
            return split;
        }
        VertexSplit::of_exact(viewport, exact, first, end)
    }

    /// [`VertexSplit::new_exact`] where the rounding could matter: the exact point's split.
    /// Out of line and, on the GBA, in ROM: only a vertex within a rounding step of a column's
    /// ray comes here, and the renderer's IWRAM has no room for it.
    #[cold]
    #[inline(never)]
    fn of_exact(
        viewport: &Viewport,
        exact: impl FnOnce() -> ExactEyePoint,
        first: i32,
        end: i32,
    ) -> VertexSplit {
        let q = exact();
        VertexSplit::by_side(first, end, |c| {
            viewport.side_of_exact_column_ray(q, c) == Side::Right
        })
    }

    /// The split of `[first, end)` by a point right of the rays of the columns where `right`
    /// says so (a prefix or a suffix of them).
    fn by_side(first: i32, end: i32, right: impl Fn(i32) -> bool) -> VertexSplit {
        debug_assert!(first < end, "an empty column range");
        let right_first = right(first);
        let (mut low, mut high) = (first + 1, end);
        while low < high {
            let middle = (low + high) / 2;
            if right(middle) == right_first {
                low = middle + 1;
            } else {
                high = middle;
            }
        }
        VertexSplit {
            right_first,
            boundary: low,
        }
    }

    /// The split of the columns `[first, end)` (`first < end`) by a vertex whose own columns
    /// start at `first_column` (the first column whose centre is at or right of its projection,
    /// in `[0, width]`): it is right of the rays of the columns before `first_column` and not
    /// right of the others, which is the shape [`VertexSplit::new`] finds by bisection.
    #[inline]
    pub const fn from_first_column(first_column: i32, first: i32, end: i32) -> VertexSplit {
        if first_column > first {
            VertexSplit {
                right_first: true,
                boundary: if first_column < end {
                    first_column
                } else {
                    end
                },
            }
        } else {
            VertexSplit {
                right_first: false,
                boundary: end,
            }
        }
    }
}

/// The columns of `[first, end)` whose rays leave through the wall `a → b`, from the splits of
/// the same range by `a` and `b`: `a` not right of the ray and `b` right of it. The same
/// columns as [`owned_columns`] clamped to `[first, end)`: a monotone predicate restricted to a
/// range changes at the same column, clamped into it (and where it does not change inside the
/// range, the range is wholly in or out of the wall's columns on both ways).
pub fn owned_columns_in(a: VertexSplit, b: VertexSplit, first: i32, end: i32) -> (i32, i32) {
    let (a_start, a_end) = if a.right_first {
        (a.boundary, end)
    } else {
        (first, a.boundary)
    };
    let (b_start, b_end) = if b.right_first {
        (first, b.boundary)
    } else {
        (b.boundary, end)
    };
    (a_start.max(b_start), a_end.min(b_end))
}

/// A wall's depth and texture parameter along the columns it owns.
#[derive(Clone, Copy, Debug)]
pub struct WallProjector {
    twice_focal: i64,
    centre_x: i64,
    a_x: i64,
    a_z: i64,
    delta_x: i64,
    delta_z: i64,
    cross: i64,
}

/// One column of a wall: what its texture column needs (its rows come from [`WallRows`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WallColumn {
    /// Eye-space depth, at least `NEAR_DEPTH`.
    pub depth: Fx24_8,
    /// Where the ray meets the wall, from its start (0) to its end (1), in 2.30.
    pub along: Fx2_30,
}

impl WallProjector {
    /// The projector of the wall `a → b` (eye space) on `viewport`.
    pub fn new(viewport: &Viewport, a: EyePoint, b: EyePoint) -> WallProjector {
        let (a_x, a_z) = (i64::from(a.x.to_bits()), i64::from(a.z.to_bits()));
        let delta_x = i64::from(b.x.to_bits()) - a_x;
        let delta_z = i64::from(b.z.to_bits()) - a_z;
        WallProjector {
            twice_focal: 2 * i64::from(viewport.focal_x),
            centre_x: i64::from(viewport.centre_x()),
            a_x,
            a_z,
            delta_x,
            delta_z,
            cross: a_z * delta_x - a_x * delta_z,
        }
    }

    /// Depth and position along the wall at an owned column `column`.
    pub fn at(&self, column: i32) -> WallColumn {
        let q = 2 * (i64::from(column) - self.centre_x) + 1;
        let numerator = self.a_z * q - self.twice_focal * self.a_x;
        let denominator = self.twice_focal * self.delta_x - q * self.delta_z;
        debug_assert!(denominator != 0, "column {column} does not cross the wall");
        let depth_bits = ratio(self.twice_focal * self.cross, denominator);
        let depth = if depth_bits < i64::from(NEAR_DEPTH.to_bits()) {
            NEAR_DEPTH
        } else {
            Fx24_8::from_bits(depth_bits.min(i64::from(i32::MAX)) as i32)
        };
        // 28 bits of fraction keep the shifted numerator below 2^62 at the declared limits.
        let along = (ratio(numerator << 28, denominator) << 2).clamp(0, 1 << 30);
        WallColumn {
            depth,
            along: Fx2_30::from_bits(along as i32),
        }
    }
}

/// Steps a wall's `1/z'` and `t/z'` across its columns: both are affine in the column, so after
/// an exact start (through [`ratio`]) each column costs two 64-bit adds, one reciprocal and one
/// multiply. The steps are rounded once, so after `n` columns `1/z'` is within `n/2 + 1` units
/// of 2^-30 of the exact value (at most 1.2e-7 across 240 columns).
///
/// The accumulators are 64-bit because `1/z'` leaves 2.30's range (above 2) wherever the wall
/// is closer than half a unit: an eye 1/256 unit from a wall sees `1/z'` up to about 2^9. Only
/// the values read are clamped to the near plane; the accumulators stay exact.
#[derive(Clone, Copy, Debug)]
pub struct WallStepper {
    inverse_depth: i64,
    inverse_depth_step: i64,
    along_over_depth: i64,
    along_over_depth_step: i64,
}

/// `1/z'` of the far limit, in 2.30: the stepper never goes below it.
const SMALLEST_INVERSE_DEPTH: i32 = (1 << 30) / portalcast_format::limits::EYE_DEPTH_MAX;

/// Largest `|t/z'|` (2.30) multiplied by a depth. On the wall `t/z' ≤ 1/z' ≤ 1`; it grows past
/// that only outside the wall, or without bound when the eye is a few 1/65536 of a unit from
/// the wall's line (the scale `2d·cross` is then tiny), where the product would overflow i64.
/// Clamping changes no result: at a depth of at least 1 unit (2^8 in 24.8), `|t/z'| ≥ 2^32`
/// gives `|t| ≥ 2^32 > 2^30`, which the final clamp of `t` to `0..=2^30` maps to the same end.
const ALONG_OVER_DEPTH_MAX: i64 = 1 << 32;

/// `t = (t/z') · z'` in 2.30, from `t/z'` (2.30) and `z'` (24.8, at least `NEAR_DEPTH`), clamped to
/// the wall: `0..=2^30`.
fn along_at_depth(along_over_depth: i64, depth: Fx24_8) -> i64 {
    // |t/z'| ≤ 2^32 and z' < 2^31 bits: the product stays below 2^63.
    (along_over_depth.clamp(-ALONG_OVER_DEPTH_MAX, ALONG_OVER_DEPTH_MAX)
        * i64::from(depth.to_bits()))
        >> 8
}

impl WallProjector {
    /// A stepper starting at the owned column `first_column`.
    pub fn stepper(&self, first_column: i32) -> WallStepper {
        let q = 2 * (i64::from(first_column) - self.centre_x) + 1;
        let numerator = self.a_z * q - self.twice_focal * self.a_x;
        let denominator = self.twice_focal * self.delta_x - q * self.delta_z;
        // With D in 2^-8 and 2dK in 2^-16 units, 1/z' = D/(2dK) is in 2^-8 units and
        // t/z' = N/(2dK) likewise: × 2^38 / (2dK) gives 2.30.
        let scale = Divisor::new(self.twice_focal * self.cross);
        let to_fx2_30 = |value: i64| scale.ratio_shifted(value, 38);
        WallStepper {
            inverse_depth: to_fx2_30(denominator),
            inverse_depth_step: to_fx2_30(-2 * self.delta_z),
            along_over_depth: to_fx2_30(numerator),
            along_over_depth_step: to_fx2_30(2 * self.a_z),
        }
    }
}

impl WallStepper {
    /// The current column's `1/z'` (units of 2^-30), clamped to the near plane and the far
    /// limit, and clamped only at the far limit: closer than the near plane the texture position
    /// needs the true `1/z'` (an eye 1/256 unit from a wall). No reciprocal.
    #[inline]
    pub fn rows(&self) -> (Fx2_30, i64) {
        let near_inverse_depth = self.inverse_depth.max(i64::from(SMALLEST_INVERSE_DEPTH));
        let inverse_depth = Fx2_30::from_bits(near_inverse_depth.min(1 << 30) as i32);
        (inverse_depth, near_inverse_depth)
    }

    /// The current column's depth and position along the wall ([`WallColumn::depth`],
    /// [`WallColumn::along`]): what its texture column needs, one reciprocal, with the near
    /// plane's clamp (the column loop of walls that reach it; [`SteppedWall::texturing`] is the
    /// same where no clamp is needed).
    #[inline(always)]
    pub fn texturing(&self) -> (Fx24_8, Fx2_30) {
        let (inverse_depth, near_inverse_depth) = self.rows();
        let depth = inverse_depth.recip_fx24_8();
        let along = if near_inverse_depth <= 1 << 30 {
            along_at_depth(self.along_over_depth, depth)
        } else {
            ratio_shifted(self.along_over_depth, 30, near_inverse_depth)
        };
        (depth, Fx2_30::from_bits(along.clamp(0, 1 << 30) as i32))
    }

    /// Steps to the next column.
    #[inline]
    pub fn step(&mut self) {
        self.inverse_depth += self.inverse_depth_step;
        self.along_over_depth += self.along_over_depth_step;
    }

    /// This stepper `columns ≥ 0` columns on: the sums of that many [`WallStepper::step`]s.
    pub fn advanced(&self, columns: i32) -> WallStepper {
        let columns = i64::from(columns);
        WallStepper {
            inverse_depth: self.inverse_depth + self.inverse_depth_step * columns,
            along_over_depth: self.along_over_depth + self.along_over_depth_step * columns,
            ..*self
        }
    }

    /// The columns `[first, end)` of the `columns` from the current one where `1/z'` needs no
    /// clamp (within `[SMALLEST_INVERSE_DEPTH, 2^30]`): one run, possibly empty, since `1/z'`
    /// is affine in the column. A wall the eye stands next to reaches the near plane only in
    /// its columns nearest the eye, so the rest can take [`SteppedWall`].
    pub fn unclamped_columns(&self, columns: i32) -> (i32, i32) {
        // Saturated, the value stays monotone in the column, so each test below holds on a
        // prefix or a suffix of the columns, and where it does not saturate it is the value
        // the steps reach.
        let inverse_depth_at = |column: i32| {
            self.inverse_depth
                .saturating_add(self.inverse_depth_step.saturating_mul(i64::from(column)))
        };
        let beyond_far = columns_where(columns, |c| {
            inverse_depth_at(c) < i64::from(SMALLEST_INVERSE_DEPTH)
        });
        let within_near = columns_where(columns, |c| inverse_depth_at(c) > 1 << 30);
        // The columns outside a prefix or a suffix run `(start, end)` of `0..columns`.
        let outside = |(start, end): (i32, i32)| {
            if start == 0 {
                (end, columns)
            } else {
                (0, start)
            }
        };
        let (far_first, far_end) = outside(beyond_far);
        let (near_first, near_end) = outside(within_near);
        let first = far_first.max(near_first);
        (first, far_end.min(near_end).max(first))
    }
}

/// Heights whose rows a wall column needs: its sector's ceiling and floor, and a portal's
/// neighbour's ceiling and floor (unused for a solid wall).
pub const ROW_HEIGHTS: usize = 4;

/// The screen rows of a wall's [`ROW_HEIGHTS`] heights, column after column (Doom's
/// `R_RenderSegLoop` steps `topfrac`/`bottomfrac` the same way).
///
/// A height `h` (24.8, above the eye) lands on row `first_row_at_or_after(cy − round(d_y·h·(1/z')))`
/// ([`Viewport::projected_y`]). Where `1/z'` needs no clamp, it is the stepper's accumulator,
/// affine in the column and within `[SMALLEST_INVERSE_DEPTH, 2^30]` over the whole wall, so a
/// 32-bit accumulator steps it exactly: [`WallRows::Stepped`] adds its step per column and
/// multiplies by each height's `d_y·h` (below 2^29) into 64 bits, one multiply-accumulate a
/// height with the rounding's 2^29 folded in. Integer arithmetic throughout, so every row is
/// bit-identical to the projection computed afresh, without the 64-bit accumulators (16
/// registers for four heights) that spilled to the stack at every column. Walls where `1/z'`
/// reaches the near or the far clamp somewhere in their columns take [`WallRows::Exact`], which
/// evaluates each column as before.
#[derive(Clone, Copy, Debug)]
pub enum WallRows {
    /// `1/z'` within `[SMALLEST_INVERSE_DEPTH, 2^30]` over every column of the wall: the rows
    /// of a [`SteppedWall`] (its `t/z'` unused).
    Stepped {
        /// The wall's 32-bit `1/z'` and row constants.
        wall: SteppedWall,
        /// Whether the wall is a portal with a strip, whose neighbour's heights (the last two)
        /// are read.
        neighbour: bool,
    },
    /// Each column's rows from its clamped `1/z'`.
    Exact {
        /// `1/z'` of the current column, unclamped (units of 2^-30).
        inverse_depth: i64,
        /// Its step per column.
        inverse_depth_step: i64,
        /// The heights above the eye.
        heights: [Fx24_8; ROW_HEIGHTS],
        /// The screen they project to.
        viewport: Viewport,
    },
}

impl WallRows {
    /// The rows of `heights` (above the eye) on the `columns ≥ 1` columns the stepper starts at;
    /// without a `neighbour` (a solid wall), only the first two are computed (the last two
    /// read 0).
    pub fn new(
        viewport: &Viewport,
        heights: [Fx24_8; ROW_HEIGHTS],
        neighbour: bool,
        stepper: &WallStepper,
        columns: i32,
    ) -> WallRows {
        match SteppedWall::rows_of(viewport, heights, stepper, columns) {
            Some(wall) => WallRows::Stepped { wall, neighbour },
            None => WallRows::Exact {
                inverse_depth: stepper.inverse_depth,
                // One column steps nowhere: its step is never used (see `rows_of`).
                inverse_depth_step: if columns > 1 {
                    stepper.inverse_depth_step
                } else {
                    0
                },
                heights,
                viewport: *viewport,
            },
        }
    }

    /// The current column's rows, unclipped (in `[0, height]`); then steps to the next column.
    #[inline(always)]
    pub fn next_column(&mut self) -> [i16; ROW_HEIGHTS] {
        match self {
            WallRows::Stepped { wall, neighbour } => {
                // Rows lie in `[0, height]`: i16 holds them.
                let rows = wall.rows(*neighbour).map(|row| row as i16);
                wall.step();
                rows
            }
            WallRows::Exact { .. } => self.next_exact_column(),
        }
    }

    /// [`WallRows::next_column`] of [`WallRows::Exact`]: out of line, since the wall loops
    /// inline the stepped path at each of their call sites, and run from ROM (no IWRAM section
    /// attribute): only walls within a unit of the eye or at the far
    /// limit take it, and IWRAM is short.
    #[inline(never)]
    fn next_exact_column(&mut self) -> [i16; ROW_HEIGHTS] {
        let WallRows::Exact {
            inverse_depth,
            inverse_depth_step,
            heights,
            viewport,
        } = self
        else {
            return [0; ROW_HEIGHTS];
        };
        let near_inverse_depth = (*inverse_depth).max(i64::from(SMALLEST_INVERSE_DEPTH));
        let clamped = Fx2_30::from_bits(near_inverse_depth.min(1 << 30) as i32);
        *inverse_depth += *inverse_depth_step;
        heights.map(|height| {
            let y = if near_inverse_depth <= 1 << 30 {
                viewport.projected_y(height, clamped)
            } else {
                projected_y_closer_than_near(viewport, height, near_inverse_depth)
            };
            viewport.first_row_at_or_after(y) as i16
        })
    }
}

/// A wall on which [`WallStepper`] and [`WallRows`] need no clamp and no 64-bit accumulator:
/// `1/z'` stays within `[SMALLEST_INVERSE_DEPTH, 2^30]` ([`WallRows::Stepped`]'s condition) and
/// `t/z'` within i32 over every column, so every column's rows and texturing are the stepper's
/// and the rows' own, bit for bit, from four 32-bit accumulators. Both quantities are affine in
/// the column, so checking the first and the last column checks them all. Most walls of a frame
/// are such walls; the wall loop keeps this state in registers (Doom's `R_RenderSegLoop` steps
/// its `rw_scale` and `topfrac` the same way).
#[derive(Clone, Copy, Debug)]
pub struct SteppedWall(WallSteps);

impl SteppedWall {
    /// The rows of `heights` on the `columns ≥ 1` columns `stepper` starts at, with no `t/z'`
    /// (zero); `None` where `1/z'` needs a clamp at the first or the last column (and so,
    /// being affine, somewhere).
    fn rows_of(
        viewport: &Viewport,
        heights: [Fx24_8; ROW_HEIGHTS],
        stepper: &WallStepper,
        columns: i32,
    ) -> Option<SteppedWall> {
        let first = stepper.inverse_depth;
        // One column steps nowhere: its step (unbounded where the wall is seen edge on) is
        // never used, and is kept out of the products.
        let step = if columns > 1 {
            stepper.inverse_depth_step
        } else {
            0
        };
        let last = first + step * i64::from(columns - 1);
        let range = i64::from(SMALLEST_INVERSE_DEPTH)..=1 << 30;
        if !(range.contains(&first) && range.contains(&last)) {
            return None;
        }
        // |d_y·h| < 2^29: 24.8 heights within HEIGHT_DIFF_MAX, d_y ≤ 120.
        let negated_scale = |height: Fx24_8| -height.mul_int(viewport.focal_y).to_bits();
        Some(SteppedWall(WallSteps {
            inverse_depth: first as i32,
            inverse_depth_step: step as i32,
            along_over_depth: 0,
            along_over_depth_step: 0,
            negated_scales: heights.map(negated_scale),
            row_base: WallSteps::row_base_of(viewport.horizon_y),
            height: viewport.height,
        }))
    }

    /// The wall `stepper` starts on, over its `columns ≥ 1` columns, with the rows of `heights`
    /// (see [`WallRows::new`]); `None` where a column needs a clamp or a 64-bit accumulator.
    pub fn new(
        viewport: &Viewport,
        heights: [Fx24_8; ROW_HEIGHTS],
        stepper: &WallStepper,
        columns: i32,
    ) -> Option<SteppedWall> {
        let SteppedWall(rows) = SteppedWall::rows_of(viewport, heights, stepper, columns)?;
        // As in `rows_of`: one column steps nowhere, so its step is kept out.
        let along_step = if columns > 1 {
            stepper.along_over_depth_step
        } else {
            0
        };
        let first = stepper.along_over_depth;
        let last = along_step
            .checked_mul(i64::from(columns - 1))
            .and_then(|run| run.checked_add(first))?;
        i32::try_from(last).ok()?;
        Some(SteppedWall(WallSteps {
            along_over_depth: i32::try_from(first).ok()?,
            along_over_depth_step: i32::try_from(along_step).ok()?,
            ..rows
        }))
    }

    /// Its accumulators and row constants, as a canvas's own wall loop takes them.
    pub fn steps(&self) -> WallSteps {
        self.0
    }

    /// The wall at the column a canvas's loop left `steps` at.
    pub fn from_steps(steps: WallSteps) -> SteppedWall {
        SteppedWall(steps)
    }

    /// The current column's rows of the four heights, unclipped (in `[0, height]`): those of
    /// [`WallRows::next_column`]. Without a `neighbour` (a solid wall) the last two read 0.
    #[inline(always)]
    pub fn rows(&self, neighbour: bool) -> [i32; ROW_HEIGHTS] {
        let wall = &self.0;
        let scales = &wall.negated_scales;
        if neighbour {
            scales.map(|scale| wall.row(scale))
        } else {
            [wall.row(scales[0]), wall.row(scales[1]), 0, 0]
        }
    }

    /// The current column's depth and position along the wall: [`WallStepper::texturing`]'s,
    /// which on such a wall is one reciprocal and one 32×32-bit product.
    #[inline(always)]
    pub fn texturing(&self) -> (Fx24_8, Fx2_30) {
        let depth = Fx2_30::from_bits(self.0.inverse_depth).recip_fx24_8();
        let along = (i64::from(self.0.along_over_depth) * i64::from(depth.to_bits())) >> 8;
        (depth, Fx2_30::from_bits(along.clamp(0, 1 << 30) as i32))
    }

    /// Steps to the next column. Past the wall's last column the sums may leave i32; they are
    /// never read then.
    #[inline(always)]
    pub fn step(&mut self) {
        let wall = &mut self.0;
        wall.inverse_depth = wall.inverse_depth.wrapping_add(wall.inverse_depth_step);
        wall.along_over_depth = wall
            .along_over_depth
            .wrapping_add(wall.along_over_depth_step);
    }
}

/// A wall's [`ROW_HEIGHTS`] heights where a sloped floor or ceiling makes them vary along it:
/// each is affine in the position `t` along the wall (0 at its start, 1 at its end), since a
/// plane's height is affine along any line. Doom's renderer has flat sectors only; Build steps
/// the same straight edges.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SlopedHeights {
    /// The heights above the eye at the wall's start, 24.8.
    pub start: [Fx24_8; ROW_HEIGHTS],
    /// Each height at the end less at the start, in 24.8 bits.
    pub rise: [i32; ROW_HEIGHTS],
}

impl SlopedHeights {
    /// The rows of the heights at the current column of `stepper`, whose texturing gave
    /// `along`: each height at `along` (rounded down to 1/256), projected with the column's
    /// clamped `1/z'` as [`WallRows::Exact`] projects a flat one. A height is affine in `t` and
    /// `t/z'` affine in the column, so each row follows a straight screen line.
    pub fn rows(
        &self,
        viewport: &Viewport,
        stepper: &WallStepper,
        along: Fx2_30,
    ) -> [i32; ROW_HEIGHTS] {
        let near_inverse_depth = stepper.inverse_depth.max(i64::from(SMALLEST_INVERSE_DEPTH));
        let clamped = Fx2_30::from_bits(near_inverse_depth.min(1 << 30) as i32);
        let along = i64::from(along.to_bits());
        core::array::from_fn(|index| {
            // |rise| ≤ 2^23 bits (HEIGHT_DIFF_MAX), along ≤ 2^30: the product fits i64.
            let height = Fx24_8::from_bits(
                self.start[index].to_bits() + ((i64::from(self.rise[index]) * along) >> 30) as i32,
            );
            let y = if near_inverse_depth <= 1 << 30 {
                viewport.projected_y(height, clamped)
            } else {
                projected_y_closer_than_near(viewport, height, near_inverse_depth)
            };
            viewport.first_row_at_or_after(y)
        })
    }
}

/// Largest `1/z'` (units of 2^-30) [`projected_y_closer_than_near`] multiplies by: `z'` of
/// 2^-12 unit. An eye a few 1/65536 of a unit from a wall's line sees `1/z'` far beyond it, and
/// `h · d_y · 1/z'` would overflow i64 (`|h| ≤ 2^22` in 24.8 bits, `d_y < 2^7`). The cut
/// changes no row: at `1/z' = 2^42` even the smallest height, 1/256 unit, lies
/// `60 · 2^12 / 2^8 = 960` rows or more from the horizon, off every screen, like the true row.
const NEAR_INVERSE_DEPTH_MAX: i64 = 1 << 42;

/// Screen `y` of a height `height_above_eye` on a wall closer than the near plane, where `1/z'`
/// (`near_inverse_depth`, units of 2^-30) exceeds 2.30's range: the same `cy − d_y·h/z'`, with
/// `1/z'` cut to 2^-22 units (and at [`NEAR_INVERSE_DEPTH_MAX`]) so the product stays in 64
/// bits, saturated to ±2^22 rows (any such row is off screen and clamps to an edge).
fn projected_y_closer_than_near(
    viewport: &Viewport,
    height_above_eye: Fx24_8,
    near_inverse_depth: i64,
) -> Fx24_8 {
    // |h| ≤ 2^22 bits (HEIGHT_DIFF_MAX), d_y ≤ 120, 1/z' >> 8 ≤ 2^34: |product| ≤ 120 · 2^56,
    // below 2^63.
    // 24.8 × int × 2^-22 units → 24.8 after >> 22.
    let offset = (i64::from(height_above_eye.to_bits())
        * i64::from(viewport.focal_y)
        * (near_inverse_depth.min(NEAR_INVERSE_DEPTH_MAX) >> 8))
        >> 22;
    let y = (i64::from(viewport.horizon_y) << 8) - offset;
    Fx24_8::from_bits(y.clamp(-(1 << 30), 1 << 30) as i32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_stepper_stays_close_to_the_exact_projection() {
        let viewport = Viewport::new(240, 160);
        let walls = [
            ((-300, 40), (500, 900)),
            ((-60, 60), (60, 60)),
            ((-9000, 200), (9000, 20000)),
            ((-5, 2), (5, 3)),
        ];
        for ((ax, az), (bx, bz)) in walls {
            let (a, b) = (eye(ax, az), eye(bx, bz));
            let (start, stop) = owned_columns(&viewport, a, b);
            let projector = WallProjector::new(&viewport, a, b);
            let mut stepper = projector.stepper(start);
            for column in start..stop {
                let (stepped_inverse_depth, _) = stepper.rows();
                stepper.step();
                // The exact 1/z' from the geometry, in f64, in units of 2^-30.
                let q = f64::from(2 * (column - viewport.centre_x()) + 1);
                let d2 = f64::from(2 * viewport.focal_x);
                let (fa_x, fa_z) = (f64::from(a.x.to_bits()), f64::from(a.z.to_bits()));
                let (dx, dz) = (
                    f64::from(b.x.to_bits()) - fa_x,
                    f64::from(b.z.to_bits()) - fa_z,
                );
                let denominator = d2 * dx - q * dz;
                let cross = fa_z * dx - fa_x * dz;
                let exact = (denominator / (d2 * cross) * 2f64.powi(38)).min(f64::from(1 << 30));
                let steps = f64::from(column - start);
                let error = (f64::from(stepped_inverse_depth.to_bits()) - exact).abs();
                assert!(
                    error <= steps / 2.0 + 2.0 + exact * 2f64.powi(-27),
                    "wall {a:?}-{b:?} column {column}: 1/z off by {error}"
                );
            }
        }
    }

    fn eye(x: i32, z: i32) -> EyePoint {
        EyePoint::new(Fx24_8::from_int(x), Fx24_8::from_int(z))
    }

    #[test]
    fn a_wall_straight_ahead_owns_the_columns_between_its_ends() {
        let viewport = Viewport::new(120, 80);
        // From x' = -60 to +60 at depth 60: exactly the 90° field of view.
        let (start, end) = owned_columns(&viewport, eye(-60, 60), eye(60, 60));
        assert_eq!((start, end), (0, 120));
        let middle = WallProjector::new(&viewport, eye(-60, 60), eye(60, 60)).at(60);
        assert_eq!(middle.depth, Fx24_8::from_int(60));
        // Column 60's centre is at x' = 0.5 of 120: along = 60.5/120.
        let expected = (60.5 / 120.0 * f64::from(1 << 30)) as i32;
        assert!((middle.along.to_bits() - expected).abs() <= 8);
    }

    #[test]
    fn adjacent_walls_share_their_boundary_column() {
        let viewport = Viewport::new(240, 160);
        let (a, b, c) = (eye(-100, 40), eye(7, 93), eye(90, 20));
        let first = owned_columns(&viewport, a, b);
        let second = owned_columns(&viewport, b, c);
        assert_eq!(first.1, second.0);
        assert_eq!((first.0, second.1), (0, 240));
    }

    #[test]
    fn a_back_facing_wall_owns_nothing() {
        let viewport = Viewport::new(120, 80);
        let (start, end) = owned_columns(&viewport, eye(60, 60), eye(-60, 60));
        assert!(start >= end);
    }

    #[test]
    fn a_vertex_behind_the_eye_still_splits_columns_exactly() {
        // Eye inside a room whose corner is behind it: the two walls meeting there split the
        // screen with no gap and no overlap.
        let viewport = Viewport::new(120, 80);
        let (a, corner, c) = (eye(-50, 30), eye(-5, -10), eye(40, 30));
        let first = owned_columns(&viewport, a, corner);
        let second = owned_columns(&viewport, corner, c);
        let owners = |column: i32| {
            usize::from((first.0..first.1).contains(&column))
                + usize::from((second.0..second.1).contains(&column))
        };
        // Every column whose ray crosses either wall in front is owned exactly once.
        for column in 0..120 {
            assert!(owners(column) <= 1, "column {column}");
        }
    }
}

#[cfg(test)]
mod row_tests {
    use super::*;
    use proptest::prelude::*;

    /// A 240×160 or 120×80 viewport with its horizon `look` rows off the middle.
    fn test_viewport(wide: bool, look: i32) -> Viewport {
        let mut viewport = if wide {
            Viewport::new(240, 160)
        } else {
            Viewport::new(120, 80)
        };
        viewport.horizon_y = (viewport.horizon_y + look).clamp(0, viewport.height);
        viewport
    }

    /// The wall between the eye-space points `[ax, az]` and `[bx, bz]` (times `scale`, 24.8
    /// bits), turned to face the eye, and the columns it owns; `None` if it owns none, or if it
    /// passes through the eye: no map has such a wall (the eye is strictly inside its sector,
    /// and no other sector's wall reaches inside it), and its projection has no divisor.
    fn front_facing_wall(
        viewport: &Viewport,
        [ax, az, bx, bz]: [i32; 4],
        scale: i32,
    ) -> Option<(EyePoint, EyePoint, i32, i32)> {
        let (ax64, az64, bx64, bz64) = (i64::from(ax), i64::from(az), i64::from(bx), i64::from(bz));
        if ax64 * bz64 == az64 * bx64 && ax64 * bx64 + az64 * bz64 <= 0 {
            return None;
        }
        let a = EyePoint::new(Fx24_8::from_bits(ax * scale), Fx24_8::from_bits(az * scale));
        let b = EyePoint::new(Fx24_8::from_bits(bx * scale), Fx24_8::from_bits(bz * scale));
        // A back-facing wall owns nothing; the same wall seen from its front does.
        let (a, b) = if owned_columns(viewport, a, b).0 < owned_columns(viewport, a, b).1 {
            (a, b)
        } else {
            (b, a)
        };
        let (start, stop) = owned_columns(viewport, a, b);
        (start < stop).then_some((a, b, start, stop))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]
        /// The stepped rows are the rows computed afresh at every column, bit for bit, at every
        /// height and horizon, including walls that reach the near or far clamp (which must
        /// fall back to the exact evaluation).
        #[test]
        fn stepped_rows_are_the_exact_rows(
            ax in -4000i32..4000, az in -4000i32..4000,
            bx in -4000i32..4000, bz in -4000i32..4000,
            scale in prop_oneof![Just(1i32), Just(37), Just(256), Just(2048)],
            heights in proptest::array::uniform4(-(1i32 << 22)..(1 << 22)),
            wide in any::<bool>(),
            look in -40i32..=40,
        ) {
            let viewport = test_viewport(wide, look);
            let Some((a, b, start, stop)) = front_facing_wall(&viewport, [ax, az, bx, bz], scale)
            else {
                return Ok(());
            };
            let projector = WallProjector::new(&viewport, a, b);
            let stepper = projector.stepper(start);
            let heights = heights.map(Fx24_8::from_bits);
            let mut rows = WallRows::new(&viewport, heights, true, &stepper, stop - start);
            let mut exact = WallRows::Exact {
                inverse_depth: stepper.inverse_depth,
                inverse_depth_step: stepper.inverse_depth_step,
                heights,
                viewport,
            };
            for column in start..stop {
                prop_assert_eq!(rows.next_column(), exact.next_column(), "column {}", column);
            }
        }

        /// The unclamped run is exactly the columns whose `1/z'` needs no clamp, and a stepper
        /// advanced to any column is the one stepped there.
        #[test]
        fn the_unclamped_run_is_where_no_clamp_is_needed(
            ax in -4000i32..4000, az in -4000i32..4000,
            bx in -4000i32..4000, bz in -4000i32..4000,
            scale in prop_oneof![Just(1i32), Just(37), Just(256), Just(2048)],
            wide in any::<bool>(),
        ) {
            let viewport = test_viewport(wide, 0);
            let Some((a, b, start, stop)) = front_facing_wall(&viewport, [ax, az, bx, bz], scale)
            else {
                return Ok(());
            };
            let first_stepper = WallProjector::new(&viewport, a, b).stepper(start);
            let (first, end) = first_stepper.unclamped_columns(stop - start);
            let range = i64::from(SMALLEST_INVERSE_DEPTH)..=1 << 30;
            let mut stepper = first_stepper;
            for offset in 0..stop - start {
                let advanced = first_stepper.advanced(offset);
                prop_assert_eq!(advanced.inverse_depth, stepper.inverse_depth);
                prop_assert_eq!(advanced.along_over_depth, stepper.along_over_depth);
                let unclamped = range.contains(&stepper.inverse_depth);
                prop_assert_eq!(
                    unclamped,
                    (first..end).contains(&offset),
                    "offset {} of {:?}", offset, (first, end)
                );
                stepper.step();
            }
        }

        /// Where a wall needs no clamp, the 32-bit [`SteppedWall`] gives every column the rows
        /// and the texturing of the 64-bit stepper and of [`WallRows::Exact`], bit for bit.
        #[test]
        fn a_stepped_wall_is_the_stepper_bit_for_bit(
            ax in -4000i32..4000, az in -4000i32..4000,
            bx in -4000i32..4000, bz in -4000i32..4000,
            scale in prop_oneof![Just(1i32), Just(37), Just(256), Just(2048)],
            heights in proptest::array::uniform4(-(1i32 << 22)..(1 << 22)),
            wide in any::<bool>(),
            look in -40i32..=40,
        ) {
            let viewport = test_viewport(wide, look);
            let Some((a, b, start, stop)) = front_facing_wall(&viewport, [ax, az, bx, bz], scale)
            else {
                return Ok(());
            };
            let mut stepper = WallProjector::new(&viewport, a, b).stepper(start);
            let heights = heights.map(Fx24_8::from_bits);
            let Some(mut wall) = SteppedWall::new(&viewport, heights, &stepper, stop - start) else {
                return Ok(());
            };
            let mut exact = WallRows::Exact {
                inverse_depth: stepper.inverse_depth,
                inverse_depth_step: stepper.inverse_depth_step,
                heights,
                viewport,
            };
            for column in start..stop {
                let expected = exact.next_column().map(i32::from);
                prop_assert_eq!(wall.rows(true), expected, "column {}", column);
                let solid = wall.rows(false);
                prop_assert_eq!(&solid[..2], &expected[..2], "column {}", column);
                prop_assert_eq!(wall.texturing(), stepper.texturing(), "column {}", column);
                wall.step();
                stepper.step();
            }
        }
    }
}

#[cfg(test)]
mod split_tests {
    use super::*;
    use crate::math::{Angle, EyeFrame, WorldPoint};
    use proptest::prelude::*;

    /// A point of the map near the ray of `column` (at `depth` units), rounded to 24.8: within a
    /// rounding step of a column centre, where only the exact test can tell the sides apart.
    fn near_ray(eye: &EyeFrame, viewport: &Viewport, column: i32, depth: f64) -> WorldPoint {
        let slope =
            f64::from(2 * (column - viewport.centre_x()) + 1) / f64::from(2 * viewport.focal_x);
        let (sin, cos) = eye.angle.sin_cos();
        let (sin, cos) = (
            f64::from(sin.to_bits()) / 65536.0,
            f64::from(cos.to_bits()) / 65536.0,
        );
        let (dx, dy) = (depth * (cos - slope * sin), depth * (sin + slope * cos));
        let bits = |base: Fx24_8, offset: f64| {
            Fx24_8::from_bits(base.to_bits() + (offset * 256.0).round() as i32)
        };
        WorldPoint::new(bits(eye.position.x, dx), bits(eye.position.y, dy))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4000))]
        #[test]
        fn exact_splits_are_the_exact_test_s(
            ex in -2000i32..2000, ey in -2000i32..2000, fine in 0i32..256,
            angle in any::<u16>(),
            column in 0i32..240, depth in 1.0f64..3000.0,
            px in -800i32..800, py in -800i32..800,
            near in any::<bool>(),
            wide in any::<bool>(),
            first in 0i32..240, len in 1i32..240,
        ) {
            let viewport = if wide { Viewport::new(240, 160) } else { Viewport::new(120, 80) };
            let eye = EyeFrame::new(
                WorldPoint::new(Fx24_8::from_bits(ex * 256 + fine), Fx24_8::from_bits(ey * 256 - fine)),
                Angle::from_bits(angle),
            );
            let point = if near {
                near_ray(&eye, &viewport, column % viewport.width, depth)
            } else {
                WorldPoint::new(eye.position.x + Fx24_8::from_bits(px * 37), eye.position.y + Fx24_8::from_bits(py * 41))
            };
            let q = eye.to_eye_exact(point);
            prop_assert_eq!(q.rounded(), eye.to_eye(point));
            let right = |c: i32| viewport.side_of_exact_column_ray(q, c) == Side::Right;
            let first = first % viewport.width;
            let end = (first + len).min(viewport.width);
            prop_assert_eq!(
                VertexSplit::new_exact(&viewport, q.rounded(), || q, first, end),
                VertexSplit::by_side(first, end, right)
            );
            if q.in_front() && q.rounded().z.to_bits() > 0 {
                let brute = (0..viewport.width).find(|&c| !right(c)).unwrap_or(viewport.width);
                prop_assert_eq!(viewport.first_column_at_or_after_exact(q), brute);
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]
        #[test]
        fn split_ownership_is_the_clamped_full_ownership(
            ax in -3000i32..3000, az in -3000i32..3000,
            bx in -3000i32..3000, bz in -3000i32..3000,
            wide in any::<bool>(),
            first in 0i32..240, len in 1i32..240,
        ) {
            let viewport = if wide { Viewport::new(240, 160) } else { Viewport::new(120, 80) };
            let first = first % viewport.width;
            let end = (first + len).min(viewport.width);
            let a = EyePoint::new(Fx24_8::from_bits(ax * 37), Fx24_8::from_bits(az * 37));
            let b = EyePoint::new(Fx24_8::from_bits(bx * 37), Fx24_8::from_bits(bz * 37));
            let (start, stop) = owned_columns(&viewport, a, b);
            let (start, stop) = (start.max(first), stop.min(end));
            let split = |p| VertexSplit::new(&viewport, p, first, end);
            let (split_start, split_stop) = owned_columns_in(split(a), split(b), first, end);
            prop_assert_eq!(start < stop, split_start < split_stop);
            if start < stop {
                prop_assert_eq!((start, stop), (split_start, split_stop));
            }
        }

        #[test]
        fn a_split_from_the_exact_first_column_is_the_bisected_split(
            x in -3000i32..3000, z in 1i32..3000,
            wide in any::<bool>(),
            first in 0i32..240, len in 1i32..240,
        ) {
            // The precision knob builds its splits with `from_first_column`: given the exact
            // first column, it must agree with the bisection, so only the rounding differs.
            let viewport = if wide { Viewport::new(240, 160) } else { Viewport::new(120, 80) };
            let first = first % viewport.width;
            let end = (first + len).min(viewport.width);
            let p = EyePoint::new(Fx24_8::from_bits(x * 37), Fx24_8::from_bits(z * 37));
            let column = viewport.first_column_at_or_after(p);
            prop_assert_eq!(
                VertexSplit::from_first_column(column, first, end),
                VertexSplit::new(&viewport, p, first, end)
            );
        }
    }
}
