//! Floors, ceilings and sky (Doom's r_plane): a visit's per-column windows become horizontal
//! spans (`spans::make_spans`), each drawn across a flat with one packed texture step; sky
//! windows are drawn as panorama columns instead.

use portalcast_format::limits::EYE_DEPTH_MAX;
use portalcast_format::{Colormap, Plane, Sector, SectorSlope, Texture};

use super::light::Lighting;
use super::light::{light_row, run_light};
use super::spans::{make_spans, Window};
use super::surface::Surface;
use super::view::View;
use super::walk::{is_sky, mip_level_of_ratio, mip_ratio, mip_ratios_of_level, FrameStats};
use super::RenderAssets;
use crate::math::{recip_small, recip_u64_with_bit_length, Fx24_8};
use crate::raster::column::ColumnTexture;
use crate::raster::flat::{FlatTexture, PackedUv, FLAT_LOG2_SIDES};
use crate::raster::plane_run::{PlaneConstants, PlaneRun, PlaneRunEnd};
use crate::raster::Canvas;

/// One visit's planes.
pub struct PlaneJob<'r> {
    /// The frame's view.
    pub view: &'r View,
    /// Textures, sky and colormap.
    pub assets: &'r RenderAssets<'r>,
    /// The sector visited.
    pub sector: &'r Sector,
    /// Its index.
    pub sector_index: u16,
    /// Screen column of the first window.
    pub first: usize,
    /// Ceiling window per column from `first`; none if no column shows the ceiling.
    pub ceiling: &'r [Window],
    /// Floor window per column from `first`; none if no column shows the floor.
    pub floor: &'r [Window],
    /// Scratch for `make_spans`, one entry per row.
    pub span_start: &'r mut [i16],
    /// Counters.
    pub stats: &'r mut FrameStats,
    /// Map-angle offset of each screen column's ray from the view direction (binary angle).
    pub column_angles: &'r [i16],
}

impl PlaneJob<'_> {
    /// [`PlaneJob::draw`] for a sector whose floor or ceiling slopes, with its `planes`: a
    /// sloped plane's spans through `SlopedSpans`, a flat one's through the renderer's own
    /// span loop (the twin of the canvas's, pixel for pixel), the sky as always. Out of line and
    /// in ROM, so that the flat sectors' `draw` in IWRAM is what it was.
    #[inline(never)]
    pub fn draw_with_slopes(self, canvas: &mut impl Canvas, planes: SectorSlope) {
        let PlaneJob {
            view,
            assets,
            sector,
            sector_index,
            first,
            ceiling,
            floor,
            span_start,
            stats,
            column_angles,
        } = self;
        let sky = is_sky(sector);
        if sky {
            canvas.set_surface(Surface::Sky);
            for (offset, window) in ceiling.iter().enumerate() {
                if !window.is_empty() {
                    stats.column_pixels += (window.bottom - window.top) as u32;
                    stats.sky_pixels += (window.bottom - window.top) as u32;
                    sky_column(view, assets, column_angles, canvas, first + offset, *window);
                }
            }
        }
        let surfaces = [
            (
                Surface::Ceiling(sector_index),
                ceiling,
                planes.ceiling,
                sector.ceil_texture,
            ),
            (
                Surface::Floor(sector_index),
                floor,
                planes.floor,
                sector.floor_texture,
            ),
        ];
        canvas.set_halved_flats(view.halved_floors);
        for (surface, windows, plane, texture) in &surfaces[usize::from(sky)..] {
            if windows.is_empty() {
                continue;
            }
            canvas.set_surface(*surface);
            if plane.is_flat() {
                let height = plane.base_fx8 >> 8;
                PlaneSpans::new(view, assets, sector, height, *texture)
                    .draw_twin(canvas, windows, first, span_start, stats);
            } else {
                let mut spans = SlopedSpans::new(view, assets, sector, plane, *texture);
                make_spans(windows, first, span_start, |row, start, end| {
                    spans.span(canvas, stats, row, start, end);
                });
            }
        }
        canvas.set_halved_flats(false);
    }

    /// Draws the visit's ceiling (or sky) and floor.
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".iwram.render_planes_draw")]
    pub fn draw(self, canvas: &mut impl Canvas) {
        let PlaneJob {
            view,
            assets,
            sector,
            sector_index,
            first,
            ceiling,
            floor,
            span_start,
            stats,
            column_angles,
        } = self;
        let sky = is_sky(sector);
        if sky {
            canvas.set_surface(Surface::Sky);
            for (offset, window) in ceiling.iter().enumerate() {
                if !window.is_empty() {
                    stats.column_pixels += (window.bottom - window.top) as u32;
                    stats.sky_pixels += (window.bottom - window.top) as u32;
                    sky_column(view, assets, column_angles, canvas, first + offset, *window);
                }
            }
        }
        // The ceiling (unless it is sky), then the floor: one span loop for both, so that its code
        // is in IWRAM once.
        let planes = [
            (
                Surface::Ceiling(sector_index),
                ceiling,
                sector.ceil_z,
                sector.ceil_texture,
            ),
            (
                Surface::Floor(sector_index),
                floor,
                sector.floor_z,
                sector.floor_texture,
            ),
        ];
        canvas.set_halved_flats(view.halved_floors);
        for (surface, windows, height, texture) in &planes[usize::from(sky)..] {
            if windows.is_empty() {
                // No column of the visit shows it (the walls said so: `PlaneJob::ceiling`).
                continue;
            }
            canvas.set_surface(*surface);
            let mut plane = PlaneSpans::new(view, assets, sector, *height, *texture);
            if !plane.draw_run(canvas, windows, first, span_start, stats) {
                plane.draw_twin(canvas, windows, first, span_start, stats);
            }
        }
        canvas.set_halved_flats(false);
    }
}

/// One plane's constants, set up once per visit and surface so that a span computes only what
/// depends on its row and its first column (Doom's `R_MapPlane` after `R_DrawPlanes`).
struct PlaneSpans<'r> {
    /// The depth rule, the frame's rays and the eye, in the bits the canvas's span loop takes
    /// them in (`raster::plane_run`): its twin below reads the same.
    constants: PlaneConstants,
    /// The eye is in the plane: no row shows it.
    edge_on: bool,
    /// The flat, if the map's texture index names one.
    texture: Option<&'r Texture<'r>>,
    /// Smallest mip level the span kernels take (their flats are at most 64 texels a side).
    smallest_kernel_level: u8,
    light: u8,
    lighting: Lighting,
    colormap: &'r Colormap,
    /// The mip level the last span took, kept while the spans' mip ratio stays in its range
    /// (the rows of a plane go one way in depth, so most spans reuse it).
    level: PlaneLevel<'r>,
}

/// A flat's mip level and what its spans need of it, with the [`mip_ratio`]s that select it.
#[derive(Clone, Copy)]
struct PlaneLevel<'r> {
    ratio_low: i32,
    ratio_high: i32,
    level: u8,
    side_log2: u32,
    texels: &'r [u8],
}

impl<'r> PlaneLevel<'r> {
    /// The level the span rule picks for `ratio` on `texture`: the mip rule on its largest
    /// square, never below `smallest`.
    #[inline(always)]
    fn pick(texture: &Texture<'r>, ratio: i32, smallest: u8) -> u8 {
        let largest = texture.width_log2.min(texture.height_log2);
        mip_level_of_ratio(ratio, texture.mip_count, largest, largest).max(smallest)
    }

    /// No level yet: every ratio is out of its range.
    const NONE: PlaneLevel<'static> = PlaneLevel {
        ratio_low: 1,
        ratio_high: 0,
        level: 0,
        side_log2: 0,
        texels: &[],
    };

    /// The level [`PlaneLevel::pick`] picks for `ratio` on `texture`, with the ratios that pick
    /// it too (`smallest`: the largest flat the kernels take). Out of line and, on the GBA, in
    /// ROM: the canvas's span loop picks a square flat's levels itself.
    #[inline(never)]
    fn of(texture: &Texture<'r>, ratio: i32, smallest: u8) -> PlaneLevel<'r> {
        let level = Self::pick(texture, ratio, smallest);
        let deepest = Self::pick(texture, i32::MAX, smallest);
        let (ratio_low, ratio_high) = mip_ratios_of_level(level, smallest, deepest);
        PlaneLevel {
            ratio_low,
            ratio_high,
            level,
            side_log2: u32::from(texture.level_width_log2(level)),
            texels: texture.flat_level(level),
        }
    }
}

impl<'r> PlaneSpans<'r> {
    fn new(
        view: &View,
        assets: &'r RenderAssets<'r>,
        sector: &Sector,
        height: i32,
        texture: u16,
    ) -> PlaneSpans<'r> {
        let eye_above_plane = view.eye_z - Fx24_8::from_int(height);
        let texture = assets.textures.get(usize::from(texture));
        let largest = texture.map_or(0, |t| t.width_log2.min(t.height_log2));
        let rays = view.plane_rays;
        PlaneSpans {
            constants: PlaneConstants {
                // |eye − plane|·2·d_y in 24.8.
                depth_numerator: eye_above_plane
                    .abs()
                    .mul_int(2 * view.viewport.focal_y)
                    .to_bits(),
                horizon_y: view.viewport.horizon_y,
                below_eye: eye_above_plane.to_bits() > 0,
                inverse_focal_y: recip_small(view.viewport.focal_y as u32).to_bits(),
                centre_x: view.viewport.centre_x(),
                rays: [rays.centre.0, rays.centre.1, rays.step.0, rays.step.1]
                    .map(|factor| factor.to_bits()),
                eye: (
                    i64::from(view.eye.position.x.to_bits()) << 8,
                    i64::from(view.eye.position.y.to_bits()) << 8,
                ),
            },
            edge_on: eye_above_plane.to_bits() == 0,
            texture,
            smallest_kernel_level: largest.saturating_sub(*FLAT_LOG2_SIDES.end() as u8),
            light: sector.light,
            lighting: view.lighting,
            colormap: assets.colormap,
            level: PlaneLevel::NONE,
        }
    }

    /// Draws the plane's spans with the canvas's own loop ([`Canvas::plane_run`]); `false`
    /// if it has none or the plane has no flat to draw (nothing is drawn then).
    #[inline(always)]
    fn draw_run(
        &mut self,
        canvas: &mut impl Canvas,
        windows: &[Window],
        first: usize,
        span_start: &mut [i16],
        stats: &mut FrameStats,
    ) -> bool {
        let Some(texture) = self.texture.filter(|_| !self.edge_on) else {
            return false;
        };
        let light = run_light(self.light, self.lighting, self.colormap);
        let mut run = PlaneRun::new(self.constants, light, windows, first, span_start);
        if texture.width_log2 == texture.height_log2 {
            // A square flat: the canvas's loop may pick its spans' levels itself, by the rule
            // of `PlaneLevel::of`.
            let smallest = self.smallest_kernel_level;
            let deepest = PlaneLevel::pick(texture, i32::MAX, smallest);
            run.pick_levels(texture.rows, texture.width_log2.into(), smallest, deepest);
        }
        loop {
            match canvas.plane_run(&mut run) {
                None => return false,
                Some(PlaneRunEnd::Done) => break,
                Some(PlaneRunEnd::MipLevel(ratio)) => {
                    self.level = PlaneLevel::of(texture, ratio, self.smallest_kernel_level);
                    let level = &self.level;
                    run.set_level(
                        level.level,
                        level.side_log2,
                        level.texels,
                        (level.ratio_low, level.ratio_high),
                    );
                    // As `Canvas::flat` refuses a flat of a side no kernel takes.
                    assert!(run.has_level(), "a flat level no span kernel takes");
                }
                Some(PlaneRunEnd::Declined { row, start, end }) => {
                    self.span_twin(canvas, stats, row, start, end);
                }
            }
        }
        let (spans, pixels) = run.drawn();
        stats.spans += spans;
        stats.span_pixels += pixels;
        true
    }

    /// Draws the plane's spans as the renderer makes and sets them up: the twin of the
    /// canvas's loop. Out of line and, on the GBA, in ROM: there only planes without a flat
    /// to draw come here.
    #[inline(never)]
    fn draw_twin(
        &mut self,
        canvas: &mut impl Canvas,
        windows: &[Window],
        first: usize,
        span_start: &mut [i16],
        stats: &mut FrameStats,
    ) {
        make_spans(windows, first, span_start, |row, start, end| {
            self.span_twin(canvas, stats, row, start, end);
        });
    }

    /// Row `row`, columns `start..end`: the map point under each pixel centre is
    /// `e + z'·f + z'·(x + ½ − cx)/d_x · r`, with `z'` the plane's depth on this row
    /// ([`Viewport::floor_depth_of_row`](crate::math::Viewport::floor_depth_of_row)'s rule).
    /// The twin of the canvas's own set-up ([`Canvas::plane_run`]). Out of line and, on the
    /// GBA, in ROM: there only the spans the ARM loop leaves (rows on the far side of the
    /// horizon) and those of planes without a flat come here. Counts the span in `stats`.
    #[inline(never)]
    fn span_twin(
        &mut self,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        row: usize,
        start: usize,
        end: usize,
    ) {
        stats.span_pixels += (end - start) as u32;
        stats.spans += 1;
        let PlaneConstants {
            depth_numerator,
            horizon_y,
            below_eye,
            inverse_focal_y,
            centre_x,
            rays,
            eye: (eye_x, eye_y),
        } = self.constants;
        let doubled_offset = 2 * (row as i32 - horizon_y) + 1;
        let (Some(texture), false, true) = (
            self.texture,
            self.edge_on,
            below_eye == (doubled_offset > 0),
        ) else {
            // Rounding put a row of this window on the far side of the horizon (nothing of the
            // plane is visible there), or the map names no flat: draw index 0 so the pixel is
            // still written once.
            let blank = FlatTexture {
                texels: &BLANK_FLAT,
                log2_side: 3,
                pos: PackedUv(0),
                step: PackedUv(0),
                colormap: None,
            };
            canvas.flat(row, start, end - start, &blank);
            return;
        };
        let depth = Fx24_8::from_bits(depth_numerator)
            .mul_fx2_30(recip_small(doubled_offset.unsigned_abs()));
        let ratio = mip_ratio(i64::from(depth.to_bits()), i64::from(inverse_focal_y));
        if !(self.level.ratio_low..=self.level.ratio_high).contains(&ratio) {
            self.level = PlaneLevel::of(texture, ratio, self.smallest_kernel_level);
        }
        let PlaneLevel {
            level,
            side_log2,
            texels,
            ..
        } = self.level;
        let depth_bits = i64::from(depth.to_bits());
        // Map position of the centre column's pixel centre and the step per pixel, in 16.16:
        // 24.8 × 2.30 is 26.38, 22 bits more than 16.16. Every pixel of a row gets the same
        // coordinates whichever span it falls in (the span's first pixel is `start − cx` packed
        // steps from the centre, as the kernel steps), so how the walk splits a plane into
        // visits changes no texel; from the centre, the packed step's rounding drifts over at
        // most half the row.
        let [centre_x_ray, centre_y_ray, step_x_ray, step_y_ray] =
            rays.map(|factor| (depth_bits * i64::from(factor)) >> 22);
        let (x, y) = (eye_x + centre_x_ray, eye_y + centre_y_ray);
        let (step_x, step_y) = (step_x_ray, step_y_ray);
        // Texture coordinates wrap, so keeping the low 32 bits of each is exact.
        let at_level = |value: i64| (value >> level) as i32;

        let colormap = light_row(self.light, depth.to_int_floor(), self.lighting)
            .map(|row| &self.colormap[row]);
        let centre = PackedUv::pack(at_level(x), at_level(y), side_log2);
        let step = PackedUv::pack(at_level(step_x), at_level(step_y), side_log2);
        let steps_from_centre = (start as u32).wrapping_sub(centre_x as u32);
        let flat = FlatTexture {
            texels,
            log2_side: side_log2,
            pos: PackedUv(
                centre
                    .0
                    .wrapping_add(step.0.wrapping_mul(steps_from_centre)),
            ),
            step,
            colormap,
        };
        canvas.flat(row, start, end - start, &flat);
    }
}

/// A sloped floor or ceiling's spans ([`SlopeSteps`](super::view::SlopeSteps)). On row `y`
/// the ray through column `x`'s pixel centre, `e + t·ray(x)` in the map at height
/// `eye_z − k·t` (`k = (2(y − horizon) + 1)/(2·d_y)`), meets the plane `z = z_e + t·g(x)`
/// (`z_e` its height under the eye, `g(x) = G·ray(x)` its rise along the ray) at the depth
/// `t = (eye_z − z_e)/(k + g(x))`; its map point `e + t·ray(x)` gives the texel as a flat's
/// ([`PlaneSpans::span_twin`]), and `t` the light and the mip level. `ray(x)` and `g(x)` are
/// affine in `x`, so a span computes `t` (one reciprocal) at every `N`-th pixel and at its last,
/// and steps the map point linearly between. Out of line and in ROM: only sloped planes come
/// here.
struct SlopedSpans<'r> {
    constants: PlaneConstants,
    /// `eye_z − z_e` in 24.8 bits: positive where the plane is below the eye there.
    eye_above_plane: i64,
    /// The plane's gradients, 8.24.
    gradient: (i64, i64),
    texture: Option<&'r Texture<'r>>,
    smallest_kernel_level: u8,
    light: u8,
    lighting: Lighting,
    colormap: &'r Colormap,
    level: PlaneLevel<'r>,
    step_log2: u32,
}

/// Nearest and farthest depths a sloped span takes, 24.8 bits: a pixel past the plane's
/// horizon (a rounding at its edge) is drawn at the far limit.
const SLOPE_DEPTH_BITS: (i64, i64) = (1, EYE_DEPTH_MAX as i64 * 256);

impl<'r> SlopedSpans<'r> {
    fn new(
        view: &View,
        assets: &'r RenderAssets<'r>,
        sector: &Sector,
        plane: &Plane,
        texture: u16,
    ) -> SlopedSpans<'r> {
        let texture = assets.textures.get(usize::from(texture));
        let largest = texture.map_or(0, |t| t.width_log2.min(t.height_log2));
        let rays = view.plane_rays;
        let eye = view.eye.position;
        let under_eye = plane.height_fx8_at(eye.x.to_bits(), eye.y.to_bits());
        SlopedSpans {
            constants: PlaneConstants {
                depth_numerator: 0,
                horizon_y: view.viewport.horizon_y,
                below_eye: false,
                inverse_focal_y: recip_small(view.viewport.focal_y as u32).to_bits(),
                centre_x: view.viewport.centre_x(),
                rays: [rays.centre.0, rays.centre.1, rays.step.0, rays.step.1]
                    .map(|factor| factor.to_bits()),
                eye: (
                    i64::from(eye.x.to_bits()) << 8,
                    i64::from(eye.y.to_bits()) << 8,
                ),
            },
            eye_above_plane: i64::from(view.eye_z.to_bits()) - i64::from(under_eye),
            gradient: (
                i64::from(plane.gradient_x_fx24),
                i64::from(plane.gradient_y_fx24),
            ),
            texture,
            smallest_kernel_level: largest.saturating_sub(*FLAT_LOG2_SIDES.end() as u8),
            light: sector.light,
            lighting: view.lighting,
            colormap: assets.colormap,
            level: PlaneLevel::NONE,
            step_log2: u32::from(view.slope_steps.log2),
        }
    }

    /// The depth (24.8 bits) and map point (16.16) of column `x`'s pixel on the row whose
    /// `k` (2.30 bits) is `k`.
    #[inline(always)]
    fn exact(&self, k: i64, x: i32) -> (i64, i64, i64) {
        let [centre_x, centre_y, step_x, step_y] = self.constants.rays.map(i64::from);
        let columns = i64::from(x - self.constants.centre_x);
        let (ray_x, ray_y) = (centre_x + columns * step_x, centre_y + columns * step_y);
        // 8.24 × 2.30 → 2.30 after >> 24; each product below 2^57.
        let rise = (self.gradient.0 * ray_x + self.gradient.1 * ray_y) >> 24;
        let denominator = k + rise;
        let depth = if denominator == 0 || (denominator > 0) != (self.eye_above_plane > 0) {
            SLOPE_DEPTH_BITS.1
        } else {
            // t = |eye − z_e|·2^30/|k + g|, with 2^30/n = r/2^p.
            let (reciprocal, bit_length) = recip_u64_with_bit_length(denominator.unsigned_abs());
            ((self.eye_above_plane.abs() * i64::from(reciprocal)) >> bit_length)
                .clamp(SLOPE_DEPTH_BITS.0, SLOPE_DEPTH_BITS.1)
        };
        let (eye_x, eye_y) = self.constants.eye;
        // 24.8 × 2.30 → 16.16 after >> 22, as a flat's span.
        (
            depth,
            eye_x + ((depth * ray_x) >> 22),
            eye_y + ((depth * ray_y) >> 22),
        )
    }

    /// Row `row`, columns `start..end`, in pieces of `N` pixels: each exact at its first pixel
    /// and stepped to the next piece's first (or the span's last) pixel, lit and mip-mapped by
    /// its first pixel's depth. Counts the span in `stats`.
    fn span(
        &mut self,
        canvas: &mut impl Canvas,
        stats: &mut FrameStats,
        row: usize,
        start: usize,
        end: usize,
    ) {
        stats.span_pixels += (end - start) as u32;
        stats.spans += 1;
        let (Some(texture), false) = (self.texture, self.eye_above_plane == 0) else {
            let blank = FlatTexture {
                texels: &BLANK_FLAT,
                log2_side: 3,
                pos: PackedUv(0),
                step: PackedUv(0),
                colormap: None,
            };
            canvas.flat(row, start, end - start, &blank);
            return;
        };
        let doubled_offset = 2 * (row as i64 - i64::from(self.constants.horizon_y)) + 1;
        // k = (2(y − horizon) + 1)/(2·d_y) in 2.30, from 1/d_y's.
        let k = (doubled_offset * i64::from(self.constants.inverse_focal_y)) >> 1;
        let pieces = 1usize << self.step_log2;
        let (end, mut x) = (end as i32, start as i32);
        let mut here = self.exact(k, x);
        while x < end {
            let count = (end - x).min(pieces as i32);
            // The next piece's first pixel, or the span's last: the step's far end.
            let (next, steps) = if x + count < end {
                (x + count, count)
            } else {
                (end - 1, count - 1)
            };
            let there = if steps > 0 { self.exact(k, next) } else { here };
            let (depth, u, v) = here;
            let ratio = mip_ratio(depth, i64::from(self.constants.inverse_focal_y));
            if !(self.level.ratio_low..=self.level.ratio_high).contains(&ratio) {
                self.level = PlaneLevel::of(texture, ratio, self.smallest_kernel_level);
            }
            let PlaneLevel {
                level,
                side_log2,
                texels,
                ..
            } = self.level;
            let per_pixel = |delta: i64| {
                if steps == pieces as i32 {
                    delta >> self.step_log2
                } else if steps > 0 {
                    (delta * i64::from(recip_small(steps as u32).to_bits())) >> 30
                } else {
                    0
                }
            };
            // Texture coordinates wrap, so keeping the low 32 bits of each is exact.
            let at_level = |value: i64| (value >> level) as i32;
            let colormap = light_row(self.light, (depth >> 8) as i32, self.lighting)
                .map(|row| &self.colormap[row]);
            let flat = FlatTexture {
                texels,
                log2_side: side_log2,
                pos: PackedUv::pack(at_level(u), at_level(v), side_log2),
                step: PackedUv::pack(
                    at_level(per_pixel(there.1 - u)),
                    at_level(per_pixel(there.2 - v)),
                    side_log2,
                ),
                colormap,
            };
            canvas.flat(row, x as usize, count as usize, &flat);
            here = there;
            x += count;
        }
    }
}

static BLANK_FLAT: [u8; 64] = [0; 64];

/// One sky column: panorama column from the ray's map angle, rows from the horizon. Inlined
/// in both callers, so that the flat planes' copy runs from IWRAM (called out of line, it ran
/// from the cartridge: 5,866 cycles a frame of the bench map's 120×80 fly-through).
#[inline(always)]
fn sky_column(
    view: &View,
    assets: &RenderAssets,
    column_angles: &[i16],
    canvas: &mut impl Canvas,
    column: usize,
    window: Window,
) {
    let sky = &assets.sky;
    let height_log2 = u32::from(sky.height).trailing_zeros();
    debug_assert!(
        sky.height.is_power_of_two(),
        "the sky's height must be a power of two"
    );
    let ray_angle = view
        .eye
        .angle
        .to_bits()
        .wrapping_add(column_angles[column] as u16);
    let sky_column = (u32::from(ray_angle) << sky.width_log2) >> 16;
    let height = usize::from(sky.height);
    let texels = &sky.texels[sky_column as usize * height..(sky_column as usize + 1) * height];
    // Row r shows panorama row h/2 + floor((r + ½ − cy)·160/H); H is 80 or 160.
    let top = i32::from(window.top);
    let twice_offset = 2 * (top - view.viewport.horizon_y) + 1;
    // The shipped heights divide exactly by shifts (t·80 / 80 = t, ⌊t·80 / 160⌋ = t >> 1):
    // the ARM7TDMI has no divide, and the library's is Thumb code in ROM.
    let (lines_per_row, first_line) = match view.viewport.height {
        80 => (2, twice_offset),
        160 => (1, twice_offset >> 1),
        height => (160 / height, (twice_offset * 80).div_euclid(height)),
    };
    let v = ((i32::from(sky.height) / 2 + first_line) as u32) << (32 - height_log2);
    let dv = (lines_per_row as u32) << (32 - height_log2);
    let texture = ColumnTexture {
        texels,
        log2_height: height_log2,
        v,
        dv,
        colormap: None,
    };
    canvas.column(
        column,
        window.top as usize,
        (window.bottom - window.top) as usize,
        &texture,
    );
}
