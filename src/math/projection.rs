//! Eye space, the near plane, and the projection to columns and rows.
//!
//! # Eye space
//!
//! For an eye at `e` looking at angle `a`: forward `f = (cos a, sin a)`, right
//! `r = (−sin a, cos a)`, and a map point `p` has eye coordinates `x' = (p − e)·r` (to the right)
//! and `z' = (p − e)·f` (depth), in 24.8 ([`EyeFrame::to_eye`]: one rounding, so the error is
//! at most ½ ulp plus `(|Δx| + |Δy|)·7.93e-6` from the sine table; on screen that is
//! `√2·d·7.93e-6 ≤ 0.0014` pixel whatever the distance).
//!
//! # The column rule
//!
//! A point in front of the eye projects to the continuous screen position
//! `x = cx + d·x'/z'` (`cx = width/2`, `d` = focal length). Column `c` covers `[c, c + 1)` and
//! is sampled at its centre `c + ½`. **A wall spanning the projected interval `[x0, x1)` owns
//! column `c` iff `x0 ≤ c + ½ < x1`**, so its columns are `first(x0) .. first(x1)` with
//! `first(x) = ceil(x − ½)` clamped to `[0, width]`.
//!
//! [`Viewport::first_column_at_or_after`] evaluates `first` without a division and without
//! rounding: `x0 ≤ c + ½` is, multiplied by `2·z' > 0`, the integer comparison
//! `2·d·X ≤ (2(c − cx) + 1)·Z` on the 24.8 bits `X`, `Z` (both sides fit i32 within the
//! declared limits), and a binary search over `c` in `[0, width]` finds the first column where
//! it holds (8 steps for 240 columns). Two walls sharing a vertex get the same boundary column
//! from the same eye point, so no column is owned twice or by none.
//! [`Viewport::side_of_column_ray`] is the same comparison for one column, valid for any point
//! (also behind the eye): the test for "which wall does column `c`'s ray hit".
//!
//! [`Viewport::projected_x_saturating`] gives the continuous `x` (for interpolation set-up),
//! approximately and clamped to 16.16: `1/z'` in 2.30 carries a relative error of at most
//! `1e-9 + z'·2^-31`, so `x` is off by at most that fraction of `|x|` (`1.1e-5` at the far
//! limit, 0.0026 pixel at the right edge of 240 columns) plus ½ ulp. It never decides column
//! ownership.
//!
//! Rows follow the same rule: row `y` is sampled at `y + ½`, a vertical span `[y0, y1)` owns
//! rows `first(y0) .. first(y1)` ([`Viewport::first_row_at_or_after`]).
//!
//! # Near plane
//!
//! [`clip_to_near_plane`] keeps the part of an eye-space segment with `z' ≥ NEAR_DEPTH`
//! (`limits::EYE_DEPTH_MIN` = 1 unit), before anything is projected. The clipped end is the
//! exact intersection rounded once to 24.8 (its `z'` is exactly 1), computed through the
//! integer divide: it happens for at most a few walls per frame. Where a shared vertex is behind
//! the near plane, the two walls' clipped ends differ; assign columns by
//! [`Viewport::side_of_column_ray`] on the unclipped vertices there.

use super::angle::Angle;
use super::fixed::{Fx16_16, Fx24_8, Fx2_30};
use super::geometry::{Side, WorldPoint};
use super::recip::recip_small;
use portalcast_format::limits;

/// The near plane depth: `limits::EYE_DEPTH_MIN` world units.
pub const NEAR_DEPTH: Fx24_8 = Fx24_8::from_int(limits::EYE_DEPTH_MIN);

/// A point in eye space, in 24.8 world units.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default, Debug)]
pub struct EyePoint {
    /// Distance to the right of the view direction (`x'`).
    pub x: Fx24_8,
    /// Depth along the view direction (`z'`).
    pub z: Fx24_8,
}

impl EyePoint {
    /// The point `(x', z')`.
    #[inline]
    pub const fn new(x: Fx24_8, z: Fx24_8) -> EyePoint {
        EyePoint { x, z }
    }
}

/// A point in eye space exactly where the view's 16.16 sine and cosine put it, before the
/// rounding to 24.8 of [`EyePoint`]: each coordinate is a sum of products of a 24.8 offset and a
/// 16.16 factor, in 2^-24 units. Which wall owns a column is decided on these
/// ([`Viewport::side_of_exact_column_ray`]): the column's ray is then the one the view's sine
/// and cosine define, the ray the oracle casts too, so no rounding of the vertex can give a
/// column to another wall (issue 16).
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct ExactEyePoint {
    x: i64,
    z: i64,
}

impl ExactEyePoint {
    /// The point rounded to 24.8: [`EyeFrame::to_eye`]'s result.
    #[inline]
    #[track_caller]
    pub const fn rounded(self) -> EyePoint {
        EyePoint {
            x: Fx24_8::from_product_fx16_16(self.x),
            z: Fx24_8::from_product_fx16_16(self.z),
        }
    }

    /// Whether the point is in front of the eye (`z' > 0`, exactly).
    #[inline]
    pub const fn in_front(self) -> bool {
        self.z > 0
    }
}

/// The eye's position and orientation, with the sine and cosine looked up once.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct EyeFrame {
    /// Position of the eye on the map plane.
    pub position: WorldPoint,
    /// View angle.
    pub angle: Angle,
    sin: Fx16_16,
    cos: Fx16_16,
}

impl EyeFrame {
    /// The eye at `position` looking at `angle`.
    #[inline]
    pub const fn new(position: WorldPoint, angle: Angle) -> EyeFrame {
        let (sin, cos) = angle.sin_cos();
        EyeFrame {
            position,
            angle,
            sin,
            cos,
        }
    }

    /// `sin` of the view angle, in 16.16.
    #[inline]
    pub const fn sin(&self) -> Fx16_16 {
        self.sin
    }

    /// `cos` of the view angle, in 16.16.
    #[inline]
    pub const fn cos(&self) -> Fx16_16 {
        self.cos
    }

    /// Eye coordinates of a map point: `x' = (p − e)·r`, `z' = (p − e)·f`, each rounded once
    /// (error ≤ ½ ulp + `(|Δx| + |Δy|)·7.93e-6`). Points of the declared world never overflow.
    #[inline]
    #[track_caller]
    pub fn to_eye(&self, p: WorldPoint) -> EyePoint {
        self.to_eye_exact(p).rounded()
    }

    /// [`to_eye`](Self::to_eye) before its rounding: exact.
    #[inline]
    #[track_caller]
    pub fn to_eye_exact(&self, p: WorldPoint) -> ExactEyePoint {
        let dx = p.x - self.position.x;
        let dy = p.y - self.position.y;
        ExactEyePoint {
            x: Fx24_8::dot_fx16_16_unrounded(dx, -self.sin, dy, self.cos),
            z: Fx24_8::dot_fx16_16_unrounded(dx, self.cos, dy, self.sin),
        }
    }

    /// The map point at eye coordinates `q`: `p = e + x'·r + z'·f` (for floors and ceilings).
    #[inline]
    #[track_caller]
    pub fn to_world(&self, q: EyePoint) -> WorldPoint {
        WorldPoint {
            x: self.position.x + Fx24_8::dot_fx16_16(q.x, -self.sin, q.z, self.cos),
            y: self.position.y + Fx24_8::dot_fx16_16(q.x, self.cos, q.z, self.sin),
        }
    }
}

/// The screen the projection maps to: size, focal lengths and horizon row.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct Viewport {
    /// Columns (120 or 240).
    pub width: i32,
    /// Rows (80 or 160).
    pub height: i32,
    /// Horizontal focal length in columns: `width / 2` for a 90° field of view.
    pub focal_x: i32,
    /// Vertical focal length in rows: `3·height / 4`, which makes the projection undistorted
    /// on the GBA's 240×160 square physical pixels whatever the logical resolution.
    pub focal_y: i32,
    /// Screen `y` of the horizon (`cy`), in `[0, height]`; `height / 2` looks level, and
    /// y-shearing moves it to look up or down.
    pub horizon_y: i32,
}

impl Viewport {
    /// A 90° viewport of `width × height` logical pixels, looking level.
    #[inline]
    #[track_caller]
    pub const fn new(width: i32, height: i32) -> Viewport {
        debug_assert!(
            width >= 2
                && width <= limits::SCREEN_WIDTH_MAX
                && height >= 2
                && height <= limits::SCREEN_HEIGHT_MAX,
            "screen larger than the declared limits"
        );
        Viewport {
            width,
            height,
            focal_x: width / 2,
            focal_y: 3 * height / 4,
            horizon_y: height / 2,
        }
    }

    /// Screen `x` of the view direction: `width / 2`.
    #[inline]
    pub const fn centre_x(&self) -> i32 {
        self.width / 2
    }

    /// Side of `p` relative to the ray from the eye through the centre of `column`, walking
    /// outward (Left: `p` projects left of the column centre, or is left of the ray's vertical
    /// plane when behind the eye). Exact: compares `2·d·x'` with `(2(c − cx) + 1)·z'` in i32.
    #[inline]
    #[track_caller]
    pub const fn side_of_column_ray(&self, p: EyePoint, column: i32) -> Side {
        let ray_x = (2 * (column - self.centre_x()) + 1) * p.z.to_bits();
        let point_x = 2 * self.focal_x * p.x.to_bits();
        Side::from_cross(point_x as i64 - ray_x as i64)
    }

    /// [`side_of_column_ray`](Self::side_of_column_ray) of the exact point `q`: compares
    /// `2·d·x'` with `(2(c − cx) + 1)·z'` in i64 on the unrounded coordinates (each product stays
    /// under 2^48 within the declared limits).
    #[inline]
    #[track_caller]
    pub const fn side_of_exact_column_ray(&self, q: ExactEyePoint, column: i32) -> Side {
        let ray_x = (2 * (column - self.centre_x()) + 1) as i64 * q.z;
        let point_x = 2 * self.focal_x as i64 * q.x;
        Side::from_cross(point_x - ray_x)
    }

    /// [`first_column_at_or_after`](Self::first_column_at_or_after) of the exact point `q`
    /// (in front of the eye): the rounded point's column, checked by the exact test only where
    /// the rounding could matter, and moved by it (a step at most, in practice).
    #[inline]
    #[track_caller]
    pub const fn first_column_at_or_after_exact(&self, q: ExactEyePoint) -> i32 {
        debug_assert!(q.in_front(), "projection needs a point in front of the eye");
        let rounded = q.rounded();
        if rounded.z.to_bits() <= 0 {
            return self.first_column_from_exact(q, self.centre_x());
        }
        let column = self.first_column_at_or_after(rounded);
        // Rounding moves each coordinate by at most half a 24.8 step, so the compared
        // quantities of `side_of_column_ray` by at most `d + |2(c − cx) + 1| / 2`: with both
        // neighbouring rays farther than that from the rounded point, the exact answer is the
        // same and the 64-bit tests are skipped.
        let clear_left = column == 0 || self.rounding_keeps_side(rounded, column - 1);
        let clear_right = column == self.width || self.rounding_keeps_side(rounded, column);
        if clear_left && clear_right {
            column
        } else {
            self.first_column_from_exact(q, column)
        }
    }

    /// Whether the side of the rounded point `p` (an [`ExactEyePoint::rounded`]) relative to
    /// column `column`'s ray is the exact point's too: true where the ray is farther from `p`
    /// than the rounding can move it.
    #[inline]
    #[track_caller]
    pub const fn rounding_keeps_side(&self, p: EyePoint, column: i32) -> bool {
        let margin = self.ray_margin(p, column);
        let tolerance = self.focal_x + self.width + 2;
        margin > tolerance || margin < -tolerance
    }

    /// `2·d·x' − (2(c − cx) + 1)·z'`: positive where `p` is right of column `c`'s ray.
    #[inline]
    #[track_caller]
    const fn ray_margin(&self, p: EyePoint, column: i32) -> i32 {
        2 * self.focal_x * p.x.to_bits() - (2 * (column - self.centre_x()) + 1) * p.z.to_bits()
    }

    /// The first column at or after the exact point `q`, walking from `column` by the exact
    /// test (the predicate is monotone in the column, so any start reaches it).
    #[inline]
    #[track_caller]
    const fn first_column_from_exact(&self, q: ExactEyePoint, mut column: i32) -> i32 {
        while column > 0 && !matches!(self.side_of_exact_column_ray(q, column - 1), Side::Right) {
            column -= 1;
        }
        while column < self.width && matches!(self.side_of_exact_column_ray(q, column), Side::Right)
        {
            column += 1;
        }
        column
    }

    /// The first column whose centre is at or right of the projection of `p`: `ceil(x − ½)`
    /// for `x = cx + d·x'/z'`, clamped to `[0, width]`. Exact (see the module docs). `z' > 0`.
    #[inline]
    #[track_caller]
    pub const fn first_column_at_or_after(&self, p: EyePoint) -> i32 {
        debug_assert!(
            p.z.to_bits() > 0,
            "projection needs a point in front of the eye"
        );
        let mut low = 0;
        let mut high = self.width;
        while low < high {
            let middle = (low + high) / 2;
            if matches!(self.side_of_column_ray(p, middle), Side::Right) {
                low = middle + 1;
            } else {
                high = middle;
            }
        }
        low
    }

    /// Continuous screen `x = cx + d·x'/z'` in 16.16, clamped to the 16.16 range, through the
    /// approximate reciprocal (see the module docs for the error). `z' > ½`.
    #[inline]
    #[track_caller]
    pub fn projected_x_saturating(&self, p: EyePoint) -> Fx16_16 {
        self.projection_numerator(p)
            .saturating_mul_fx2_30_as_fx16_16(p.z.recip_fx2_30())
    }

    /// Continuous screen `x` correctly rounded to 16.16 and clamped, through the integer divide:
    /// the reference for [`projected_x_saturating`](Self::projected_x_saturating). `z' > 0`.
    #[inline]
    #[track_caller]
    pub fn projected_x_exact(&self, p: EyePoint) -> Fx16_16 {
        debug_assert!(
            p.z.to_bits() > 0,
            "projection needs a point in front of the eye"
        );
        self.projection_numerator(p).saturating_ratio_fx16_16(p.z)
    }

    /// `cx·z' + d·x'`, so that `x = (cx·z' + d·x') / z'` saturates once. Each term is at most
    /// `120 · 23171` in 24.8 and the sum fits i32 within the declared limits.
    #[inline]
    #[track_caller]
    fn projection_numerator(&self, p: EyePoint) -> Fx24_8 {
        p.z.mul_int(self.centre_x()) + p.x.mul_int(self.focal_x)
    }

    /// Screen `y` of a height `height_above_eye` (`h − eye_z`) at inverse depth
    /// `inverse_depth = 1/z'`: `cy − d_y·(h − eye_z)·(1/z')`, in 24.8, rounded to nearest.
    /// Within the declared limits (`|h − eye_z| ≤ 16384`, `z' ≥ 1`) it is below `1.97e6` and
    /// never overflows.
    #[inline]
    #[track_caller]
    pub fn projected_y(&self, height_above_eye: Fx24_8, inverse_depth: Fx2_30) -> Fx24_8 {
        let offset = height_above_eye
            .mul_int(self.focal_y)
            .mul_fx2_30(inverse_depth);
        Fx24_8::from_int(self.horizon_y) - offset
    }

    /// The first column at or after the continuous screen `x` (`ceil(x − ½)`), clamped to
    /// `[0, width]`: the column rule for positions already in screen space (a sprite's edge).
    #[inline]
    pub const fn first_column_at_or_after_x(&self, x: Fx16_16) -> i32 {
        clamp(x.first_pixel_at_or_after(), 0, self.width)
    }

    /// The first row at or below the continuous screen `y` (`ceil(y − ½)`), clamped to
    /// `[0, height]`: a vertical span `[y0, y1)` owns rows `first(y0) .. first(y1)`.
    #[inline]
    pub const fn first_row_at_or_after(&self, y: Fx24_8) -> i32 {
        clamp(y.first_pixel_at_or_after(), 0, self.height)
    }

    /// Depth `z'` of the horizontal plane seen at the centre of `row`, for an eye
    /// `eye_above_plane = eye_z − plane_z` above it (negative for a ceiling):
    /// `z' = d_y·(eye_z − plane_z) / (row + ½ − cy)`, or `None` where the plane is not visible
    /// on that row (the row is on the other side of the horizon, or the plane is at eye level).
    ///
    /// Computed as `2·d_y·|Δ| · (1 / |2(row − cy) + 1|)` with [`recip_small`]: relative error
    /// `≤ (2·height + 1)·2^-31 ≤ 1.5e-7`, plus ½ ulp of 24.8. The row offset is never zero, as
    /// row centres sit half-way between integer horizon positions. `row` in `[0, height)`.
    #[inline]
    #[track_caller]
    pub const fn floor_depth_of_row(&self, eye_above_plane: Fx24_8, row: i32) -> Option<Fx24_8> {
        let doubled_offset = 2 * (row - self.horizon_y) + 1;
        let plane = eye_above_plane.signum();
        if plane == 0 || (plane > 0) != (doubled_offset > 0) {
            return None;
        }
        let numerator = eye_above_plane.abs().mul_int(2 * self.focal_y);
        Some(numerator.mul_fx2_30(recip_small(doubled_offset.unsigned_abs())))
    }
}

#[inline]
const fn clamp(value: i32, low: i32, high: i32) -> i32 {
    if value < low {
        low
    } else if value > high {
        high
    } else {
        value
    }
}

/// The part of an eye-space segment at or beyond the near plane, with its parameters on the
/// original segment (`t = 0` at its start, `1` at its end) for texture coordinates.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct ClippedSegment {
    /// Start of the kept part.
    pub start: EyePoint,
    /// End of the kept part.
    pub end: EyePoint,
    /// Parameter of `start` on the original segment, in `[0, 1]`.
    pub t_start: Fx2_30,
    /// Parameter of `end` on the original segment, in `[0, 1]`.
    pub t_end: Fx2_30,
}

/// Clips the segment `a → b` to `z' ≥ NEAR_DEPTH`; `None` if it lies entirely nearer.
///
/// A clipped end has `z' = NEAR_DEPTH` exactly and `x'` the exact intersection rounded to
/// nearest 24.8 (error ≤ ½ ulp); its `t` is the exact parameter rounded to nearest 2.30.
#[track_caller]
pub fn clip_to_near_plane(a: EyePoint, b: EyePoint) -> Option<ClippedSegment> {
    match (a.z >= NEAR_DEPTH, b.z >= NEAR_DEPTH) {
        (true, true) => Some(ClippedSegment {
            start: a,
            end: b,
            t_start: Fx2_30::ZERO,
            t_end: Fx2_30::ONE,
        }),
        (false, false) => None,
        (false, true) => {
            let (point, t) = near_crossing(a, b);
            Some(ClippedSegment {
                start: point,
                end: b,
                t_start: t,
                t_end: Fx2_30::ONE,
            })
        }
        (true, false) => {
            let (point, t) = near_crossing(a, b);
            Some(ClippedSegment {
                start: a,
                end: point,
                t_start: Fx2_30::ZERO,
                t_end: t,
            })
        }
    }
}

/// Where `a → b` crosses the near plane, and its parameter; one end is on each side.
#[track_caller]
fn near_crossing(a: EyePoint, b: EyePoint) -> (EyePoint, Fx2_30) {
    // Differences of depths within ±EYE_DEPTH_MAX fit 24.8 with room to spare.
    let to_plane = NEAR_DEPTH - a.z;
    let depth_span = b.z - a.z;
    let t = to_plane.ratio_fx2_30(depth_span);
    let x = a.x + (b.x - a.x).mul_ratio(to_plane, depth_span);
    (EyePoint { x, z: NEAR_DEPTH }, t)
}
