//! The sector walk (Doom's r_bsp): front to back from the eye's sector, through portals, with a
//! clip window per column. Each visit of a sector draws the walls and strips of the columns it
//! was given, records its ceiling and floor windows, draws those planes, and then recurses into
//! its portals with the narrowed windows. Columns handed to different portals never overlap, so
//! one set of per-column arrays serves the whole recursion.

use portalcast_format::{MapTables, Sector, Wall, NO_PORTAL, SKY};

use super::planes;
use super::spans::Window;
use super::surface::Surface;
use super::view::View;
use super::walls::{owned_columns, WallColumn, WallLerp, WallProjector};
use super::RenderAssets;
use crate::math::{recip_small, EyePoint, Fx24_8, WorldPoint};
use crate::raster::column::ColumnTexture;
use crate::raster::Canvas;
use crate::render::light::light_row;

/// Widest screen, in columns.
pub const MAX_COLUMNS: usize = 240;
/// Tallest screen, in rows.
pub const MAX_ROWS: usize = 160;
/// Deepest chain of portals followed; deeper sectors are left undrawn and counted.
pub const MAX_PORTAL_DEPTH: u32 = 64;

/// Counters of one frame, for the benchmarks and the tests.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameStats {
    /// Sector visits (a sector seen through two portals counts twice).
    pub sector_visits: u32,
    /// Wall columns evaluated (solid and portal).
    pub wall_columns: u32,
    /// Pixels drawn by column kernels (walls, strips, sky).
    pub column_pixels: u32,
    /// Pixels drawn by span kernels (floors, ceilings).
    pub span_pixels: u32,
    /// Portal chains cut at [`MAX_PORTAL_DEPTH`].
    pub depth_cutoffs: u32,
    /// Visits of a sector already visited this frame (through another portal): what the
    /// thesis' scene preprocessing would merge. Counted for sectors below
    /// [`VISITS_TRACKED`].
    pub repeat_visits: u32,
    /// Clock ticks in the wall stage (ownership, projection, wall and strip columns), when the
    /// renderer has a clock (the ROM's cycle meter); 0 otherwise.
    pub wall_ticks: u32,
    /// Clock ticks in the plane stage (spans, floors, ceilings, sky).
    pub plane_ticks: u32,
}

/// The renderer's per-frame working memory: clip windows, plane windows, span starts.
pub struct Renderer {
    clip: [Window; MAX_COLUMNS],
    ceiling: [Window; MAX_COLUMNS],
    floor: [Window; MAX_COLUMNS],
    span_start: [i16; MAX_ROWS],
    stats: FrameStats,
    column_angles: [i16; MAX_COLUMNS],
    column_angles_width: i32,
    clock: fn() -> u32,
    visited: [u32; VISITS_TRACKED / 32],
}

/// Sectors (by index) a frame tracks for [`FrameStats::repeat_visits`]: a bit each.
pub const VISITS_TRACKED: usize = 2048;

fn no_clock() -> u32 {
    0
}

impl Default for Renderer {
    fn default() -> Self {
        Renderer::new()
    }
}

/// What a visit needs that does not change during the frame.
struct Scene<'s, 'a> {
    map: &'s MapTables<'a>,
    assets: &'s RenderAssets<'a>,
    view: &'s View,
}

impl Renderer {
    /// Times the wall and plane stages with `clock` (a free-running counter, e.g. the ROM's
    /// cycle meter), reported in [`FrameStats`].
    pub fn with_clock(mut self, clock: fn() -> u32) -> Renderer {
        self.clock = clock;
        self
    }

    /// A renderer with empty working memory.
    pub const fn new() -> Renderer {
        Renderer {
            clip: [Window::EMPTY; MAX_COLUMNS],
            ceiling: [Window::EMPTY; MAX_COLUMNS],
            floor: [Window::EMPTY; MAX_COLUMNS],
            span_start: [0; MAX_ROWS],
            stats: FrameStats {
                sector_visits: 0,
                wall_columns: 0,
                column_pixels: 0,
                span_pixels: 0,
                depth_cutoffs: 0,
                repeat_visits: 0,
                wall_ticks: 0,
                plane_ticks: 0,
            },
            column_angles: [0; MAX_COLUMNS],
            column_angles_width: 0,
            visited: [0; VISITS_TRACKED / 32],
            clock: no_clock,
        }
    }

    /// Draws the frame `view` sees of `map` onto `canvas`.
    pub fn render(
        &mut self,
        map: &MapTables,
        assets: &RenderAssets,
        view: &View,
        canvas: &mut impl Canvas,
    ) -> FrameStats {
        let width = view.viewport.width as usize;
        let height = view.viewport.height as i16;
        debug_assert_eq!(width, canvas.resolution().width());
        self.stats = FrameStats::default();
        self.visited = [0; VISITS_TRACKED / 32];
        if self.column_angles_width != view.viewport.width {
            for (column, angle) in self.column_angles[..width].iter_mut().enumerate() {
                *angle = column_angle(
                    2 * (column as i32 - view.viewport.centre_x()) + 1,
                    2 * view.viewport.focal_x,
                );
            }
            self.column_angles_width = view.viewport.width;
        }
        for window in &mut self.clip[..width] {
            *window = Window {
                top: 0,
                bottom: height,
            };
        }
        let scene = Scene { map, assets, view };
        self.visit(&scene, canvas, view.sector, 0, width as i32, 0);
        self.stats
    }

    /// Draws `sector_index` in columns `first..end`, then walks into its portals.
    ///
    /// The recursion keeps only this small frame per level: the drawing, with its many locals,
    /// happens in [`Renderer::draw_sector`] and [`Renderer::portal_columns`], whose frames are
    /// gone before the next level starts. On the GBA a level of the walk then costs tens of
    /// bytes of the 8 KB stack instead of the drawing's ~300, so a chain of
    /// [`MAX_PORTAL_DEPTH`] portals fits (the extreme-map emulator test walks one and checks
    /// the stack's high-water mark).
    fn visit(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        sector_index: u16,
        first: i32,
        end: i32,
        depth: u32,
    ) {
        if depth > MAX_PORTAL_DEPTH {
            self.stats.depth_cutoffs += 1;
            return;
        }
        self.draw_sector(scene, canvas, sector_index, first, end);
        let sector = &scene.map.sectors[usize::from(sector_index)];
        for wall in scene.map.sector_walls(sector) {
            if wall.portal == NO_PORTAL {
                continue;
            }
            if let Some((start, stop)) = self.portal_columns(scene, wall, first, end) {
                self.visit(scene, canvas, wall.portal, start, stop, depth + 1);
            }
        }
    }

    /// The columns of `first..end` that the portal `wall` owns, if any. Out of line so that
    /// the ownership test's locals stay out of [`Renderer::visit`]'s frame.
    #[inline(never)]
    fn portal_columns(
        &self,
        scene: &Scene,
        wall: &Wall,
        first: i32,
        end: i32,
    ) -> Option<(i32, i32)> {
        self.owned(scene, wall, first, end)
            .map(|(_, _, start, stop)| (start, stop))
    }

    /// Draws one visit of `sector_index` in columns `first..end`: its walls and strips, then its
    /// ceiling and floor, narrowing the clip windows of the columns its portals own. Out of line:
    /// see [`Renderer::visit`].
    #[inline(never)]
    fn draw_sector(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        sector_index: u16,
        first: i32,
        end: i32,
    ) {
        self.stats.sector_visits += 1;
        if let Some(word) = self.visited.get_mut(usize::from(sector_index) / 32) {
            let bit = 1u32 << (sector_index % 32);
            self.stats.repeat_visits += u32::from(*word & bit != 0);
            *word |= bit;
        }
        let sector = &scene.map.sectors[usize::from(sector_index)];
        let walls = scene.map.sector_walls(sector);
        for column in first..end {
            self.ceiling[column as usize] = Window::EMPTY;
            self.floor[column as usize] = Window::EMPTY;
        }
        let walls_started = (self.clock)();
        for (offset, wall) in walls.iter().enumerate() {
            let wall_index = sector.first_wall + offset as u16;
            let Some((a, b, start, stop)) = self.owned(scene, wall, first, end) else {
                continue;
            };
            let projector = WallProjector::new(&scene.view.viewport, a, b);
            let length = wall_length(scene.map, wall);
            let mut stepper = projector.stepper(start);
            let interval = scene.view.perspective.interval();
            if interval == 1 {
                for column in start..stop {
                    let at = stepper.next_column();
                    self.wall_column(scene, canvas, sector, wall, wall_index, at, length, column);
                }
                continue;
            }
            // Exact at `column` and at `last`, interpolated between; the wall's last column is
            // always exact.
            let mut column = start;
            while column < stop {
                let last = (column + interval).min(stop - 1);
                let left = stepper.ahead(0);
                if last == column {
                    self.wall_column(
                        scene, canvas, sector, wall, wall_index, left, length, column,
                    );
                    break;
                }
                let span = last - column;
                let lerp = WallLerp::new(left, stepper.ahead(span), span);
                for offset in 0..span {
                    let at = lerp.at(offset, stepper.near_inverse_depth_ahead(offset));
                    self.wall_column(
                        scene,
                        canvas,
                        sector,
                        wall,
                        wall_index,
                        at,
                        length,
                        column + offset,
                    );
                }
                stepper.advance(span);
                column = last;
            }
        }
        let planes_started = (self.clock)();
        self.stats.wall_ticks += planes_started.wrapping_sub(walls_started);
        planes::draw(
            self.plane_job(scene, sector, sector_index, first, end),
            canvas,
        );
        self.stats.plane_ticks += (self.clock)().wrapping_sub(planes_started);
    }

    fn plane_job<'r>(
        &'r mut self,
        scene: &'r Scene,
        sector: &'r Sector,
        sector_index: u16,
        first: i32,
        end: i32,
    ) -> planes::PlaneJob<'r> {
        planes::PlaneJob {
            view: scene.view,
            assets: scene.assets,
            sector,
            sector_index,
            first: first as usize,
            ceiling: &self.ceiling[first as usize..end as usize],
            floor: &self.floor[first as usize..end as usize],
            span_start: &mut self.span_start,
            stats: &mut self.stats,
            column_angles: &self.column_angles,
        }
    }

    /// The eye-space ends of `wall` and the columns of `[first, end)` it owns, if any.
    fn owned(
        &self,
        scene: &Scene,
        wall: &Wall,
        first: i32,
        end: i32,
    ) -> Option<(EyePoint, EyePoint, i32, i32)> {
        let a = scene.view.eye.to_eye(vertex(scene.map, wall.start));
        let b = scene.view.eye.to_eye(vertex(scene.map, wall.end));
        let (start, stop) = owned_columns(&scene.view.viewport, a, b);
        let (start, stop) = (start.max(first), stop.min(end));
        (start < stop).then_some((a, b, start, stop))
    }

    #[allow(clippy::too_many_arguments)]
    fn wall_column(
        &mut self,
        scene: &Scene,
        canvas: &mut impl Canvas,
        sector: &Sector,
        wall: &Wall,
        wall_index: u16,
        at: WallColumn,
        length: Fx24_8,
        column: i32,
    ) {
        self.stats.wall_columns += 1;
        let x = column as usize;
        let view = scene.view;
        let row_of = |height: i32| {
            let above_eye = Fx24_8::from_int(height) - view.eye_z;
            let y = if at.near_inverse_depth <= 1 << 30 {
                view.viewport.projected_y(above_eye, at.inverse_depth)
            } else {
                projected_y_closer_than_near(&view.viewport, above_eye, at.near_inverse_depth)
            };
            view.viewport.first_row_at_or_after(y) as i16
        };
        let clip = self.clip[x];
        let ceiling_row = row_of(sector.ceil_z).max(clip.top);
        let floor_row = row_of(sector.floor_z).min(clip.bottom);
        self.ceiling[x] = Window {
            top: clip.top,
            bottom: ceiling_row.min(clip.bottom),
        };
        self.floor[x] = Window {
            top: floor_row.max(clip.top),
            bottom: clip.bottom,
        };
        let u = Fx24_8::from_bits(
            ((i64::from(at.along.to_bits()) * i64::from(length.to_bits())) >> 30) as i32,
        ) + Fx24_8::from_int(i32::from(wall.x_offset));
        let strip = WallStrip {
            scene,
            sector,
            depth: at.depth,
            u,
            column: x,
        };
        if wall.portal == NO_PORTAL {
            self.draw_strip(
                canvas,
                &strip,
                wall.texture,
                sector.ceil_z,
                Surface::Wall(wall_index),
                ceiling_row,
                floor_row,
                wall.y_offset,
            );
            self.clip[x] = Window::EMPTY;
            return;
        }
        let neighbour = &scene.map.sectors[usize::from(wall.portal)];
        let neighbour_ceiling_row =
            row_of(neighbour.ceil_z).clamp(ceiling_row, floor_row.max(ceiling_row));
        let neighbour_floor_row =
            row_of(neighbour.floor_z).clamp(neighbour_ceiling_row.min(floor_row), floor_row);
        // Between two sky sectors the lower ceiling's strip is sky too: leave it open so the
        // neighbour's sky fills it (Doom's sky hack; the oracle draws the same).
        let upper_drawn =
            neighbour.ceil_z < sector.ceil_z && !(is_sky(sector) && is_sky(neighbour));
        if upper_drawn {
            let upper = Surface::Upper(wall_index);
            self.draw_strip(
                canvas,
                &strip,
                wall.upper_texture,
                sector.ceil_z,
                upper,
                ceiling_row,
                neighbour_ceiling_row,
                wall.y_offset,
            );
        }
        if neighbour.floor_z > sector.floor_z {
            let lower = Surface::Lower(wall_index);
            self.draw_strip(
                canvas,
                &strip,
                wall.lower_texture,
                neighbour.floor_z,
                lower,
                neighbour_floor_row,
                floor_row,
                wall.y_offset,
            );
        }
        // Where no upper strip is drawn (the neighbour's ceiling is not lower, or both show the
        // sky), the neighbour gets the rows down from this sector's ceiling line: its own
        // ceiling (sky) fills them, and nothing is left undrawn between the two ceiling lines.
        let opening_top = if upper_drawn {
            neighbour_ceiling_row
        } else {
            ceiling_row
        };
        let opening_bottom = if neighbour.floor_z > sector.floor_z {
            neighbour_floor_row
        } else {
            floor_row
        };
        self.clip[x] = Window {
            top: opening_top,
            bottom: opening_bottom.max(opening_top),
        };
    }

    /// Draws rows `top..bottom` of one wall column with texture `texture`, whose v is anchored
    /// at height `anchor`.
    #[allow(clippy::too_many_arguments)]
    fn draw_strip(
        &mut self,
        canvas: &mut impl Canvas,
        strip: &WallStrip,
        texture: u16,
        anchor: i32,
        surface: Surface,
        top: i16,
        bottom: i16,
        y_offset: i16,
    ) {
        if top >= bottom {
            return;
        }
        let count = (bottom - top) as usize;
        self.stats.column_pixels += count as u32;
        canvas.set_surface(surface);
        let view = strip.scene.view;
        let colormap = light_row(
            strip.sector.light,
            strip.depth.to_int_floor(),
            view.lighting,
        )
        .map(|row| &strip.scene.assets.colormap[row]);
        let Some(texture) = strip.scene.assets.textures.get(usize::from(texture)) else {
            let column = ColumnTexture {
                texels: &BLANK_COLUMN,
                log2_height: 3,
                v: 0,
                dv: 0,
                colormap: None,
            };
            canvas.column(strip.column, top as usize, count, &column);
            return;
        };
        let level = mip_level(
            strip.depth,
            view.viewport.focal_y,
            texture.mip_count,
            texture.width_log2,
            texture.height_log2,
        );
        let width_log2 = u32::from(texture.level_width_log2(level));
        let height_log2 = u32::from(texture.level_height_log2(level));
        let texels = texture.wall_level(level);
        let u_texel = (strip.u.to_int_floor() >> level) & ((1 << width_log2) - 1);
        let column_texels =
            &texels[(u_texel as usize) << height_log2..((u_texel as usize) + 1) << height_log2];
        // v (texels at level 0) of row r: anchor − eye + y_offset + (r + ½ − cy)·z/d_y; as a
        // fraction of the texture height in 0.32 it is the same at every mip level.
        let base_log2 = u32::from(texture.height_log2);
        let eye_to_anchor = i64::from((Fx24_8::from_int(anchor) - view.eye_z).to_bits())
            + (i64::from(y_offset) << 8);
        let twice_row_offset = 2 * (i64::from(top) - i64::from(view.viewport.horizon_y)) + 1;
        let depth_bits = i64::from(strip.depth.to_bits());
        // z'/d_y in 24.8 through the 2.30 reciprocal of d_y (a table entry, no divide).
        let inverse_focal_y = i64::from(recip_small(view.viewport.focal_y as u32).to_bits());
        let step_bits = (depth_bits * inverse_focal_y) >> 30;
        // v in 24.8 texels; then scale to 0.32 of the height: × 2^(24 − log2 height).
        let v_bits = eye_to_anchor + ((twice_row_offset * depth_bits * inverse_focal_y) >> 31);
        let v = (v_bits << (24 - base_log2)) as u32;
        let dv = ((depth_bits * inverse_focal_y) >> (6 + base_log2)) as u32;
        let _ = step_bits;
        let column = ColumnTexture {
            texels: column_texels,
            log2_height: height_log2,
            v,
            dv,
            colormap,
        };
        canvas.column(strip.column, top as usize, count, &column);
    }
}

/// What one wall column's strips share.
struct WallStrip<'s, 'a> {
    scene: &'s Scene<'s, 'a>,
    sector: &'s Sector,
    depth: Fx24_8,
    u: Fx24_8,
    column: usize,
}

/// Texels for a surface whose texture is missing: palette index 0, as the oracle draws it.
static BLANK_COLUMN: [u8; 8] = [0; 8];

/// Screen `y` of a height `height_above_eye` on a wall closer than the near plane, where `1/z'`
/// (`near_inverse_depth`, units of 2^-30) exceeds 2.30's range: the same `cy − d_y·h/z'`, with
/// `1/z'` cut to 2^-22 units so the product stays in 64 bits, saturated to ±2^22 rows (any
/// such row is off screen and clamps to an edge).
fn projected_y_closer_than_near(
    viewport: &crate::math::Viewport,
    height_above_eye: Fx24_8,
    near_inverse_depth: i64,
) -> Fx24_8 {
    // 24.8 × int × 2^-22 units → 24.8 after >> 22.
    let offset = (i64::from(height_above_eye.to_bits())
        * i64::from(viewport.focal_y)
        * (near_inverse_depth >> 8))
        >> 22;
    let y = (i64::from(viewport.horizon_y) << 8) - offset;
    Fx24_8::from_bits(y.clamp(-(1 << 30), 1 << 30) as i32)
}

fn vertex(map: &MapTables, index: u16) -> WorldPoint {
    let v = map.vertices[usize::from(index)];
    WorldPoint::from_int(v.x, v.y)
}

/// A wall's length in 24.8, from the integer square root of its squared length.
fn wall_length(map: &MapTables, wall: &Wall) -> Fx24_8 {
    let (a, b) = (
        map.vertices[usize::from(wall.start)],
        map.vertices[usize::from(wall.end)],
    );
    let (dx, dy) = (i64::from(b.x - a.x), i64::from(b.y - a.y));
    // (length · 256)² = (dx² + dy²) · 65536.
    Fx24_8::from_bits(isqrt(((dx * dx + dy * dy) << 16) as u64) as i32)
}

/// Floor of the square root.
pub fn isqrt(n: u64) -> u64 {
    let mut root = 0u64;
    let mut bit = 1u64 << 62;
    let mut rest = n;
    while bit > n {
        bit >>= 2;
    }
    while bit != 0 {
        if rest >= root + bit {
            rest -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    root
}

/// The mip level for depth `depth`: `floor(log2(depth / focal_y))`, at least 0, below
/// `mip_count`, and keeping both sides at least 8 texels (the smallest column kernel).
pub fn mip_level(
    depth: Fx24_8,
    focal_y: i32,
    mip_count: u8,
    width_log2: u8,
    height_log2: u8,
) -> u8 {
    // floor(depth / focal_y) through the 2.30 reciprocal of focal_y: no divide.
    let ratio = ((i64::from(depth.to_bits()) * i64::from(recip_small(focal_y as u32).to_bits()))
        >> 38) as i32;
    let mut level = 0u8;
    while (ratio >> (level + 1)) > 0 {
        level += 1;
    }
    let smallest_side = width_log2.min(height_log2);
    level
        .min(mip_count.saturating_sub(1))
        .min(smallest_side.saturating_sub(3))
}

pub(crate) fn is_sky(sector: &Sector) -> bool {
    sector.ceil_texture == SKY
}

/// The binary angle (65,536 per turn) from the view direction to a column's ray, whose slope is
/// `q / twice_focal` (`q = 2(c − cx) + 1`): the largest angle with `tan ≤` the slope, found by
/// bisection on the sine table, so the sky needs no arctangent table. Computed once per
/// resolution.
pub fn column_angle(q: i32, twice_focal: i32) -> i16 {
    use crate::math::Angle;
    // Angles within ±45° (a quarter turn is 16,384): the field of view is 90°.
    let (mut low, mut high) = (-8192i32, 8192i32);
    while low < high {
        let middle = (low + high + 1).div_euclid(2);
        let (sin, cos) = Angle::from_bits(middle as u16).sin_cos();
        // tan(middle) ≤ q/2d  ⇔  sin·2d ≤ q·cos (cos > 0 here).
        if i64::from(sin.to_bits()) * i64::from(twice_focal)
            <= i64::from(q) * i64::from(cos.to_bits())
        {
            low = middle;
        } else {
            high = middle - 1;
        }
    }
    low as i16
}
