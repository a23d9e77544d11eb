//! Things and portal middles (Doom's r_things and `R_DrawMasked`): each sector visit collects
//! the things of its sector that fall in its columns, projected once and with the visit's clip
//! windows over their columns copied (the window a sector is seen through is exactly where its
//! things may show: module `surface`), and after its walls the middle images of its portals,
//! a column each with the opening's window. After the scene they are drawn back to front, every
//! column through the sprite kernel clipped to its copied window.
//!
//! Back to front is the walk's order reversed: a visit's columns lie inside its parent's and
//! apart from its siblings', so any two visits that share a column are a sector and one seen
//! through it, and everything of the one behind is drawn first. Within a visit the middles
//! (on the sector's boundary) go before its things (inside it), and the things by depth: a
//! sprite is a rectangle facing the camera at its centre's depth `z'`, so one depth orders two
//! things wherever they overlap.

use portalcast_format::{
    Sprite, Thing, Wall, NO_TEXTURE, THING_HANGING, THING_TRANSLUCENT, WALL_MIDDLE_TRANSLUCENT,
};

use super::light::{light_row, light_rule, Lighting};
use super::surface::{Surface, THING_DEPTH_MIN};
use super::view::View;
use super::RenderAssets;
use crate::math::{quotient, recip_small, EyePoint, Fx16_16, Fx24_8, WorldPoint};
use crate::raster::middle_run::{MiddleRun, MiddleShared};
use crate::raster::sprite::{BatchColumn, SpriteBatch};
use crate::raster::{Canvas, Window};
use portalcast_format::MapTables;

/// Things a frame draws at most (a thing seen through two portals counts twice); more are left
/// out and counted ([`ThingStats::dropped`]).
pub const VISIBLE_THINGS_MAX: usize = 64;

/// Columns of clip windows the visible things of a frame keep at most (a thing's columns in one
/// visit take one each); a thing that finds no room is left out and counted.
pub const THING_CLIP_COLUMNS: usize = 1024;

/// Thing projections a frame keeps for later visits of their sectors (a sector seen through several
/// portals projects each of its things once); the things of a sector that finds no room are
/// projected on each visit.
pub const PROJECTIONS_MAX: usize = 64;

/// Sectors whose things' projections a frame keeps at most.
pub const PROJECTED_SECTORS_MAX: usize = 32;

/// [`VisibleThing::sprite`] of a projection whose image is not chosen yet.
const IMAGE_UNKNOWN: u16 = u16::MAX;

/// A projection of a thing that is not on screen: no columns.
const OFF_SCREEN: VisibleThing = VisibleThing {
    visit: 0,
    translucent: false,
    depth: 0,
    thing: 0,
    sprite: IMAGE_UNKNOWN,
    first: 0,
    end: 0,
    clips_at: 0,
    light_row: 0,
    u_first: 0,
    iscale_x: 0,
    y_top: 0,
    scale: 0,
    iscale: 0,
};

/// Where the projections of one sector's things start in [`Things::projections`].
#[derive(Clone, Copy, Debug, Default)]
struct ProjectedSector {
    sector: u16,
    at: u16,
}

/// Visible portal middles a frame draws at most; more are left out and counted.
pub const VISIBLE_MIDDLES_MAX: usize = 32;

/// Columns of portal middles a frame keeps at most: two full-width layers at 240×160 (Doom's
/// cages of bars show one through another: 240 dropped some on Freedoom's E1M1, 0.82 % of a
/// frame's pixels; `tests/doom_maps.rs`). 20 bytes a column of EWRAM.
pub const MIDDLE_COLUMNS_MAX: usize = 480;

/// Columns of a thing handed to the canvas in one call at most. Measured on the bench map
/// (`cargo bench-rom`), against 16 and 32: a smaller batch is cleared sooner each frame
/// ([`empty_batch`]), a larger one calls the canvas fewer times for a wide thing.
const THING_BATCH_COLUMNS: usize = 8;

/// The columns of the thing being drawn, handed to the canvas a batch at a time. The renderer
/// keeps it on the stack (IWRAM on the GBA, where the thing's column loop writes it and the
/// kernel reads it a cycle a word, against EWRAM's three): 160 bytes, at a depth far above the
/// walk's, each column filled before it is read.
pub(crate) type ThingBatch = [BatchColumn; THING_BATCH_COLUMNS];

/// A [`ThingBatch`] to fill: zeros, which clear fastest (the filling is never read).
#[inline(always)]
pub(crate) fn empty_batch() -> ThingBatch {
    [BatchColumn::default(); THING_BATCH_COLUMNS]
}

/// A batch column that draws nothing (the arrays' filling).
const BATCH_COLUMN_EMPTY: BatchColumn = BatchColumn {
    x: 0,
    column: 0,
    light_row: u8::MAX,
    clip: Window::EMPTY,
    y_top: 0,
    scale: 0,
    iscale: 0,
};

/// A thing as one visit sees it: where its sprite lies on screen (16.16 columns and rows) and
/// which columns of the visit it covers.
#[derive(Clone, Copy, Debug, Default)]
struct VisibleThing {
    /// The visit that saw it, in the walk's order.
    visit: u16,
    /// Drawn at 50 % over what is behind.
    translucent: bool,
    /// `z'` of the thing's centre, 24.8 bits: the drawing order.
    depth: i32,
    /// Index in the map's things.
    thing: u16,
    sprite: u16,
    /// Columns `first..end` of the visit the sprite covers.
    first: i16,
    end: i16,
    /// Where the windows of those columns start in [`Things::clips`].
    clips_at: u16,
    /// The colormap row (`u8::MAX`: unlit).
    light_row: u8,
    /// Texture column of column `first`, 16.16 texels.
    u_first: u32,
    /// Texels per column, 16.16.
    iscale_x: u32,
    /// Screen row of the sprite's top edge, 16.16.
    y_top: i32,
    /// Rows per texel, 16.16.
    scale: i32,
    /// Texels per row, 16.16.
    iscale: u32,
}

/// A portal's middle image as one visit sees it.
#[derive(Clone, Copy, Debug, Default)]
struct VisibleMiddle {
    /// The visit of the wall's sector, in the walk's order.
    visit: u16,
    wall: u16,
    image: u16,
    translucent: bool,
    /// Its columns in [`Things::middle_columns`].
    columns_at: u16,
    columns: u16,
}

/// A portal wall as one visit of its sector sees it.
pub(crate) struct PortalSeen {
    /// The visit, in the walk's order.
    pub visit: u16,
    /// The wall's sector.
    pub sector: u16,
    /// The wall's index.
    pub wall: u16,
    /// Its start and end in eye space.
    pub ends: (EyePoint, EyePoint),
    /// The visit's columns it owns.
    pub columns: core::ops::Range<i32>,
}

/// Something the stage draws: a thing or a middle, by index in its list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Drawn {
    Thing(u8),
    Middle(u8),
}

/// Counters of the things stage in one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ThingStats {
    /// Things drawn (once per visit they were seen in).
    pub drawn: u32,
    /// Things and middles seen but left out: no room in [`VISIBLE_THINGS_MAX`],
    /// [`THING_CLIP_COLUMNS`], [`VISIBLE_MIDDLES_MAX`] or [`MIDDLE_COLUMNS_MAX`].
    pub dropped: u32,
    /// Portal middles drawn (once per visit of their sector).
    pub middles: u32,
    /// Of the things and middles drawn, the translucent ones.
    pub translucent: u32,
}

/// The things stage's per-frame memory.
pub struct Things {
    visible: [VisibleThing; VISIBLE_THINGS_MAX],
    count: usize,
    clips: [Window; THING_CLIP_COLUMNS],
    clips_used: usize,
    middles: [VisibleMiddle; VISIBLE_MIDDLES_MAX],
    middle_count: usize,
    middle_columns: [BatchColumn; MIDDLE_COLUMNS_MAX],
    middle_columns_used: usize,
    order: [Drawn; VISIBLE_THINGS_MAX + VISIBLE_MIDDLES_MAX],
    /// This frame's projections of the things of the sectors in `projected_sectors`, over the
    /// whole width, a sector's things in the map's order.
    projections: [VisibleThing; PROJECTIONS_MAX],
    projections_used: usize,
    projected_sectors: [ProjectedSector; PROJECTED_SECTORS_MAX],
    projected_sector_count: usize,
    stats: ThingStats,
}

impl Default for Things {
    fn default() -> Self {
        Things::new()
    }
}

/// What the things stage needs of a frame: the map, the sprites, the view and its projection
/// constants.
pub(crate) struct ThingView<'v, 'a> {
    map: &'v MapTables<'a>,
    assets: &'v RenderAssets<'a>,
    view: &'v View,
    /// `1/d_x` and `1/d_y`, 2.30 bits.
    inverse_focal_x: i64,
    inverse_focal_y: i32,
}

impl<'v, 'a> ThingView<'v, 'a> {
    /// [`project`] of `thing` with its sprite set's first image (every image of a set has one
    /// size, the asset compiler's rule, so it places the sprite), its image not yet chosen
    /// ([`IMAGE_UNKNOWN`]); `None` where the set or the image is missing, or as `project`.
    ///
    /// In VRAM on the GBA (IWRAM has no room): every thing of every sector a frame visits is
    /// projected.
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".vram.things_project")]
    fn project_thing(
        &self,
        sector: &portalcast_format::Sector,
        thing: &Thing,
    ) -> Option<VisibleThing> {
        let set = self.assets.sprite_sets.get(usize::from(thing.sprite))?;
        let shape = self.assets.sprites.get(usize::from(set.first))?;
        project(self, sector, thing, shape)
    }

    /// The frame of `view` on `map`, with `assets`' sprites.
    pub(crate) fn new(
        map: &'v MapTables<'a>,
        assets: &'v RenderAssets<'a>,
        view: &'v View,
    ) -> ThingView<'v, 'a> {
        let viewport = &view.viewport;
        ThingView {
            map,
            assets,
            view,
            inverse_focal_x: i64::from(crate::math::recip_small(viewport.focal_x as u32).to_bits()),
            inverse_focal_y: crate::math::recip_small(viewport.focal_y as u32).to_bits(),
        }
    }
}

impl Things {
    /// Empty.
    pub const fn new() -> Things {
        Things {
            visible: [OFF_SCREEN; VISIBLE_THINGS_MAX],
            count: 0,
            clips: [Window::EMPTY; THING_CLIP_COLUMNS],
            clips_used: 0,
            middles: [VisibleMiddle {
                visit: 0,
                wall: 0,
                image: 0,
                translucent: false,
                columns_at: 0,
                columns: 0,
            }; VISIBLE_MIDDLES_MAX],
            middle_count: 0,
            middle_columns: [BATCH_COLUMN_EMPTY; MIDDLE_COLUMNS_MAX],
            middle_columns_used: 0,
            order: [Drawn::Thing(0); VISIBLE_THINGS_MAX + VISIBLE_MIDDLES_MAX],
            projections: [OFF_SCREEN; PROJECTIONS_MAX],
            projections_used: 0,
            projected_sectors: [ProjectedSector { sector: 0, at: 0 }; PROJECTED_SECTORS_MAX],
            projected_sector_count: 0,
            stats: ThingStats {
                drawn: 0,
                dropped: 0,
                middles: 0,
                translucent: 0,
            },
        }
    }

    /// Forgets the last frame's things.
    pub fn clear(&mut self) {
        self.count = 0;
        self.clips_used = 0;
        self.middle_count = 0;
        self.middle_columns_used = 0;
        self.projections_used = 0;
        self.projected_sector_count = 0;
        self.stats = ThingStats::default();
    }

    /// Collects the things of sector `sector_index` that show in the visit's columns
    /// `first..end`, whose clip windows are `clip` (indexed by column); `visit` numbers the
    /// visit in the walk's order.
    ///
    /// In the VRAM after the second page on the GBA (IWRAM has no room).
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".vram_after_pages.things_collect")]
    pub(crate) fn collect(
        &mut self,
        frame: &ThingView,
        visit: u16,
        sector_index: u16,
        columns: core::ops::Range<i32>,
        clip: &[Window],
    ) {
        let map = frame.map;
        let (first, end) = (columns.start, columns.end);
        let range = map.things_range(sector_index);
        if range.is_empty() {
            return;
        }
        let cached = self.projections_of(frame, sector_index, range.clone());
        let sector = &map.sectors[usize::from(sector_index)];
        for (offset, (index, thing)) in range.clone().zip(&map.things[range]).enumerate() {
            let projected;
            let projection = match cached {
                Some(at) => &self.projections[at + offset],
                None => match frame.project_thing(sector, thing) {
                    Some(seen) => {
                        projected = seen;
                        &projected
                    }
                    None => continue,
                },
            };
            // Most of a sector's things lie outside a visit's columns: the test reads two
            // fields of the projection (in EWRAM) and copies the whole only for the others.
            let columns_first = i32::from(projection.first).max(first);
            let columns_end = i32::from(projection.end).min(end);
            if columns_first >= columns_end {
                continue;
            }
            let mut seen = *projection;
            // Which image it shows (the rotation, the animation frame: a sine, products and
            // two divides) is found only for the things in a visit's columns, once a frame.
            let image = match seen.sprite {
                IMAGE_UNKNOWN => {
                    let Some(image) = image_of(frame, thing) else {
                        continue;
                    };
                    if let Some(at) = cached {
                        self.projections[at + offset].sprite =
                            u16::try_from(image).unwrap_or(IMAGE_UNKNOWN);
                    }
                    image
                }
                // Kept only once `image_of` found it among the sprites.
                known => usize::from(known),
            };
            let columns = (columns_end - columns_first) as usize;
            if self.count == VISIBLE_THINGS_MAX || self.clips_used + columns > THING_CLIP_COLUMNS {
                self.stats.dropped += 1;
                continue;
            }
            // The texture column moves with the first column drawn.
            seen.u_first = seen.u_first.wrapping_add(
                seen.iscale_x
                    .wrapping_mul((columns_first - seen.first as i32) as u32),
            );
            seen.first = columns_first as i16;
            seen.end = columns_end as i16;
            seen.thing = index as u16;
            seen.sprite = image as u16;
            seen.visit = visit;
            seen.translucent = thing.flags & THING_TRANSLUCENT != 0;
            seen.clips_at = self.clips_used as u16;
            self.clips[self.clips_used..self.clips_used + columns]
                .copy_from_slice(&clip[columns_first as usize..columns_end as usize]);
            self.clips_used += columns;
            self.visible[self.count] = seen;
            self.count += 1;
        }
    }

    /// Where the projections of the things of `sector_index` (its `range` of the map's things)
    /// start in [`Things::projections`]: made on the frame's first visit of the sector, kept
    /// for its later ones (a sector seen through several portals projects each thing once).
    /// `None` if there is no room left: the caller projects them itself.
    fn projections_of(
        &mut self,
        frame: &ThingView,
        sector_index: u16,
        range: core::ops::Range<usize>,
    ) -> Option<usize> {
        let sectors = &self.projected_sectors[..self.projected_sector_count];
        if let Some(known) = sectors.iter().find(|known| known.sector == sector_index) {
            return Some(usize::from(known.at));
        }
        let (at, count) = (self.projections_used, range.len());
        if self.projected_sector_count == PROJECTED_SECTORS_MAX || at + count > PROJECTIONS_MAX {
            return None;
        }
        let sector = &frame.map.sectors[usize::from(sector_index)];
        for (slot, thing) in self.projections[at..at + count]
            .iter_mut()
            .zip(&frame.map.things[range])
        {
            *slot = frame.project_thing(sector, thing).unwrap_or(OFF_SCREEN);
        }
        self.projected_sectors[self.projected_sector_count] = ProjectedSector {
            sector: sector_index,
            at: at as u16,
        };
        self.projected_sector_count += 1;
        self.projections_used = at + count;
        Some(at)
    }

    /// Collects the middle image of the portal `seen` shows (if it has one); `opening` holds the
    /// windows its columns left for the sector behind (indexed by column). Its columns come
    /// from the canvas's own loop where it has one (`Canvas::middle_columns`, the GBA's ARM
    /// routine), else from [`middle_columns`], its twin.
    ///
    /// Out of line and, on the GBA, in ROM: its columns come from the routine (in VRAM), and
    /// the VRAM it had is [`Things::draw_thing`]'s, whose column loop runs for every column of
    /// every thing.
    #[inline(never)]
    pub(crate) fn collect_middle(
        &mut self,
        frame: &ThingView,
        seen: PortalSeen,
        opening: &[Window],
        canvas: &mut impl Canvas,
    ) {
        let PortalSeen {
            visit,
            sector: sector_index,
            wall: wall_index,
            ends: (a, b),
            columns,
        } = seen;
        let (map, assets, view) = (frame.map, frame.assets, frame.view);
        let wall = &map.walls[usize::from(wall_index)];
        let Some(image) = middle_image(assets, wall) else {
            return;
        };
        let sprite = &assets.sprites[image];
        let count = (columns.end - columns.start) as usize;
        if self.middle_count == VISIBLE_MIDDLES_MAX
            || self.middle_columns_used + count > MIDDLE_COLUMNS_MAX
        {
            self.stats.dropped += 1;
            return;
        }
        let Some(neighbour) = wall.neighbour() else {
            return;
        };
        let sector = &map.sectors[usize::from(sector_index)];
        let behind = &map.sectors[usize::from(neighbour)];
        let top = sector.ceil_z.min(behind.ceil_z) + i32::from(wall.y_offset);
        let setup = MiddleSetup::new(
            view,
            (a, b),
            columns.start,
            top,
            (wall.length_fx8, wall.x_offset),
            sprite.width,
            sector.light,
        );
        let start = self.middle_columns_used;
        let out = &mut self.middle_columns[start..start + count];
        let written = middle_columns_of(
            canvas,
            &setup,
            columns,
            opening,
            out,
            (sector.light, view.lighting),
        );
        if written == 0 {
            return;
        }
        self.middles[self.middle_count] = VisibleMiddle {
            visit,
            wall: wall_index,
            image: image as u16,
            translucent: wall.flags & WALL_MIDDLE_TRANSLUCENT != 0,
            columns_at: start as u16,
            columns: written as u16,
        };
        self.middle_count += 1;
        self.middle_columns_used = start + written;
    }

    /// Draws the collected things and middles back to front, and returns the frame's counts,
    /// with the things' column batch ([`ThingBatch`]) on the stack of this routine's frame:
    /// called after the walk, so the walk's stack is no deeper for it. From ROM: once a frame.
    #[inline(never)]
    pub(crate) fn draw(&mut self, assets: &RenderAssets, canvas: &mut impl Canvas) -> ThingStats {
        let mut batch = empty_batch();
        self.draw_batched(assets, canvas, &mut batch)
    }

    /// [`Things::draw`]'s work, with `batch` for the things' columns.
    /// In the VRAM Mode 4 leaves free: once a frame, but its sort and loop over the things
    /// cost most in the slowest frames, which have the most things.
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".vram.things_draw")]
    fn draw_batched(
        &mut self,
        assets: &RenderAssets,
        canvas: &mut impl Canvas,
        batch: &mut ThingBatch,
    ) -> ThingStats {
        let drawn = self.count + self.middle_count;
        let (visible, middles) = (&self.visible, &self.middles);
        // Both lists are in the walk's order of visits, and the drawing goes the other way:
        // merged from their ends (a visit's middles before its things), only the things of one
        // visit are left out of order, and the insertion sort below has little to do.
        let order = &mut self.order[..drawn];
        let (mut things_left, mut middles_left) = (self.count, self.middle_count);
        for slot in order.iter_mut() {
            let middle_next = match (things_left, middles_left) {
                (_, 0) => false,
                (0, _) => true,
                (t, m) => middles[m - 1].visit >= visible[t - 1].visit,
            };
            *slot = if middle_next {
                middles_left -= 1;
                Drawn::Middle(middles_left as u8)
            } else {
                things_left -= 1;
                Drawn::Thing(things_left as u8)
            };
        }
        for next in 1..order.len() {
            let mut at = next;
            while at > 0 && drawn_before(visible, middles, order[at], order[at - 1]) {
                order.swap(at, at - 1);
                at -= 1;
            }
        }
        for at in 0..drawn {
            match self.order[at] {
                Drawn::Thing(index) => self.draw_thing(assets, canvas, usize::from(index), batch),
                Drawn::Middle(index) => self.draw_middle(assets, canvas, usize::from(index)),
            }
        }
        self.stats.drawn = self.count as u32;
        self.stats.middles = self.middle_count as u32;
        self.stats.translucent = (self.visible[..self.count]
            .iter()
            .filter(|t| t.translucent)
            .count()
            + self.middles[..self.middle_count]
                .iter()
                .filter(|m| m.translucent)
                .count()) as u32;
        self.stats
    }

    /// Thing `index`'s columns, in batches (in `batch`) to the canvas's sprite loop. In the VRAM
    /// Mode 4 leaves free on the GBA: its loop runs for every column of every thing drawn.
    #[inline(never)]
    #[cfg_attr(target_os = "none", link_section = ".vram.things_draw_thing")]
    fn draw_thing(
        &self,
        assets: &RenderAssets,
        canvas: &mut impl Canvas,
        index: usize,
        batch: &mut ThingBatch,
    ) {
        let seen = self.visible[index];
        let sprite = &assets.sprites[usize::from(seen.sprite)];
        let blend = if seen.translucent { assets.blend } else { None };
        canvas.set_surface(Surface::Thing(seen.thing));
        let last_column = usize::from(sprite.width) - 1;
        let mut u = seen.u_first;
        let clips = &self.clips[usize::from(seen.clips_at)..];
        let mut filled = 0;
        for (x, clip) in (seen.first..seen.end).zip(clips) {
            if !clip.is_empty() {
                batch[filled] = BatchColumn {
                    x: x as u8,
                    column: ((u >> 16) as usize).min(last_column) as u8,
                    light_row: seen.light_row,
                    clip: *clip,
                    y_top: seen.y_top,
                    scale: seen.scale,
                    iscale: seen.iscale,
                };
                filled += 1;
                if filled == THING_BATCH_COLUMNS {
                    canvas.sprite_columns(&SpriteBatch {
                        posts: sprite.posts,
                        columns: batch,
                        colormap: assets.colormap,
                        blend,
                    });
                    filled = 0;
                }
            }
            u = u.wrapping_add(seen.iscale_x);
        }
        if filled > 0 {
            canvas.sprite_columns(&SpriteBatch {
                posts: sprite.posts,
                columns: &batch[..filled],
                colormap: assets.colormap,
                blend,
            });
        }
    }

    fn draw_middle(&self, assets: &RenderAssets, canvas: &mut impl Canvas, index: usize) {
        let middle = &self.middles[index];
        let sprite = &assets.sprites[usize::from(middle.image)];
        let blend = if middle.translucent {
            assets.blend
        } else {
            None
        };
        canvas.set_surface(Surface::Middle(middle.wall));
        let at = usize::from(middle.columns_at);
        canvas.sprite_columns(&SpriteBatch {
            posts: sprite.posts,
            columns: &self.middle_columns[at..at + usize::from(middle.columns)],
            colormap: assets.colormap,
            blend,
        });
    }
}

/// The image column of texture coordinate `u_fx8` (24.8 texels) on an image `width` columns
/// wide, which repeats: a mask for the usual power-of-two widths, a 32-bit remainder otherwise
/// (the ARM7TDMI divides in software).
#[inline(always)]
fn wrap_column(u_fx8: i64, width: u32) -> u8 {
    let column = (u_fx8 >> 8) as i32;
    if width.is_power_of_two() {
        (column as u32 & (width - 1)) as u8
    } else {
        column.rem_euclid(width as i32) as u8
    }
}

/// What a middle's columns share and the ray fraction's numerator and denominator at the
/// column before the first, with their steps: the set-up of the columns of a wall whose
/// middle image is `width` columns wide with its top edge at height `top`, seen by `view`
/// from eye-space `a` to `b`, lit by its sector's `light` level (`Things::collect_middle`'s,
/// and the kernel check's, which hands it random walls).
pub struct MiddleSetup {
    /// What every column shares.
    pub(crate) shared: MiddleShared,
    /// The numerator of the ray's fraction along the wall at the column before the first.
    pub(crate) numerator: i64,
    /// Its denominator there.
    pub(crate) denominator: i64,
    /// Their steps per column.
    pub(crate) steps: (i64, i64),
}

impl MiddleSetup {
    /// The set-up of the middle columns from `first_column` on of the wall from `a` to `b`
    /// (eye space), `(length_fx8, x_offset)` its length in 24.8 bits and its texture offset.
    pub fn new(
        view: &View,
        (a, b): (EyePoint, EyePoint),
        first_column: i32,
        top: i32,
        (length_fx8, x_offset): (i32, i16),
        width: u16,
        light: u8,
    ) -> MiddleSetup {
        let viewport = &view.viewport;
        let twice_focal = 2 * i64::from(viewport.focal_x);
        let (xa, za) = (i64::from(a.x.to_bits()), i64::from(a.z.to_bits()));
        let (dx, dz) = (i64::from(b.x.to_bits()) - xa, i64::from(b.z.to_bits()) - za);
        // The eye's height over the image's top edge, times d_y: a column's top row is this over
        // its depth, from the centre row.
        let above_eye_focal =
            (i64::from(view.eye_z.to_bits()) - i64::from(top << 8)) * i64::from(viewport.focal_y);
        // The numerator and the denominator of the ray's fraction along the wall are affine in
        // the column: stepped from the column before the first, exactly.
        let q_before = i64::from(2 * first_column - 1 - viewport.width);
        let numerator = q_before * za - twice_focal * xa;
        let denominator = twice_focal * dx - q_before * dz;
        let steps = (2 * za, -2 * dz);
        // 1/z' is affine in the column: z' = za + t·dz = K/denominator, where
        // K = za·denominator + numerator·dz = 2d_x·(za·dx − xa·dz) is the same in every column
        // (positive where the wall is seen from the front). So 1/z' in 2.30, 2^38/z' in bits, is
        // the denominator times 2^38/K: one product a column instead of a reciprocal. Below
        // THING_DEPTH_MIN it is that depth's.
        let nearest = recip_small(THING_DEPTH_MIN as u32).to_bits() as u32;
        let wall_constant = za * denominator + numerator * dz;
        let (wall_reciprocal, wall_shift) = match u64::try_from(wall_constant) {
            // 2^38·d/K = d·(2^(30+p)/K) >> (p − 8); for p < 8, K < 256: z' under a unit for
            // every d ≥ 1, nearer than THING_DEPTH_MIN.
            Ok(constant) if constant >> 8 != 0 => {
                let (reciprocal, p) = crate::math::recip_u64_with_bit_length(constant);
                (reciprocal, p - 8)
            }
            _ => (0, 0),
        };
        // Per column, the products are of 32-bit factors (the module `limits`' world:
        // eye-space coordinates and their differences under 2^24 bits, heights times d_y under
        // 2^30): one multiply each on the ARM7TDMI, where 64-bit factors take three.
        debug_assert!(
            [za, dz, above_eye_focal]
                .iter()
                .all(|&value| i32::try_from(value).is_ok()),
            "a middle's factors outside 32 bits"
        );
        let (light_mode, light_base) = light_rule(light, view.lighting);
        MiddleSetup {
            shared: MiddleShared {
                za: za as i32,
                dz: dz as i32,
                length_fx8,
                x_offset_fx8: i32::from(x_offset) * 256,
                wall_reciprocal,
                wall_shift,
                nearest,
                horizon_fx16: viewport.horizon_y << 16,
                above_eye_focal: above_eye_focal as i32,
                focal_y: viewport.focal_y,
                inverse_focal_y: recip_small(viewport.focal_y as u32).to_bits(),
                width: u32::from(width),
                light_mode,
                light_base,
                depth_min: THING_DEPTH_MIN << 8,
            },
            numerator,
            denominator,
            steps,
        }
    }
}

/// The columns `columns` of a middle, as the canvas's own loop makes them
/// ([`Canvas::middle_columns`]) where it has one, else as `middle_columns`, their twin, does;
/// how many it wrote to `out`.
pub fn middle_columns_of(
    canvas: &mut impl Canvas,
    setup: &MiddleSetup,
    columns: core::ops::Range<i32>,
    opening: &[Window],
    out: &mut [BatchColumn],
    (light, lighting): (u8, Lighting),
) -> usize {
    let from_canvas = MiddleRun::new(
        setup.shared,
        setup.numerator,
        setup.denominator,
        setup.steps,
        columns.clone(),
        opening,
    )
    .and_then(|mut run| canvas.middle_columns(&mut run, out));
    match from_canvas {
        Some(written) => written,
        None => middle_columns(
            &setup.shared,
            (setup.numerator, setup.denominator),
            setup.steps,
            columns,
            opening,
            out,
            (light, lighting),
        ),
    }
}

/// A middle's columns `columns` into `out`, in order, as `asm/middle.s` computes them (the
/// routine's twin): for each column whose opening is not empty and whose denominator is in
/// `1..2^32`, where its ray crosses the wall ([`ray_fraction`]), the image column there, the
/// depth's light row, the image's top row and its steps. Returns how many it wrote. Out of line,
/// in ROM on the GBA: there it runs only for an image whose width is not a power of two.
#[inline(never)]
fn middle_columns(
    shared: &MiddleShared,
    (mut numerator, mut denominator): (i64, i64),
    (numerator_step, denominator_step): (i64, i64),
    columns: core::ops::Range<i32>,
    opening: &[Window],
    out: &mut [BatchColumn],
    (sector_light, lighting): (u8, Lighting),
) -> usize {
    let mut used = 0;
    for x in columns {
        numerator += numerator_step;
        denominator += denominator_step;
        let window = opening[x as usize];
        if window.is_empty() {
            continue;
        }
        // Where column x's ray crosses the wall: the fraction `t` of the way from a to b,
        // in 2.30, from the ray `x'·2d_x = q·z'` (`q = 2x + 1 − W`). Not the wall stage's
        // `WallProjector` stepping: its `t` is rounded, and a middle's texel decides its
        // surface (transparent or not), so a ray exactly on a texel edge must take the
        // texel right of it, as the oracle's does (measured: the stepper lost every third
        // bar of the bench's grate seen square on, 0.8 % of a frame's surfaces).
        // `numerator = q·z_a − 2d_x·x_a`, `denominator = 2d_x·(x_b − x_a) − q·(z_b − z_a)`.
        // A column the wall owns sees its front: the denominator is positive (and below
        // 2^32: the module `limits`' world).
        let Ok(denominator) = u32::try_from(denominator) else {
            continue;
        };
        if denominator == 0 {
            continue;
        }
        let t = ray_fraction(numerator, denominator) as i32;
        let depth = (shared.za + ((i64::from(t) * i64::from(shared.dz)) >> 30) as i32)
            .max(shared.depth_min);
        let u_fx8 =
            i64::from(shared.x_offset_fx8) + ((i64::from(t) * i64::from(shared.length_fx8)) >> 30);
        let inverse_depth = if shared.wall_reciprocal == 0 {
            shared.nearest
        } else {
            ((u64::from(denominator) * u64::from(shared.wall_reciprocal)) >> shared.wall_shift)
                .min(u64::from(shared.nearest)) as u32
        } as i32;
        let y_top = i64::from(shared.horizon_fx16)
            + ((i64::from(shared.above_eye_focal) * i64::from(inverse_depth)) >> 22);
        let rows_per_texel = (i64::from(inverse_depth) * i64::from(shared.focal_y)) >> 14;
        let light = light_row(sector_light, depth >> 8, lighting);
        out[used] = BatchColumn {
            x: x as u8,
            column: wrap_column(u_fx8, shared.width),
            light_row: light.map_or(u8::MAX, |row| row as u8),
            clip: window,
            y_top: y_top.clamp(-(1 << 30), 1 << 30) as i32,
            scale: rows_per_texel as i32,
            iscale: texels_per_row(depth, rows_per_texel, shared.inverse_focal_y),
        };
        used += 1;
    }
    used
}

/// `⌊numerator·2^30 / denominator⌋` clamped to `0..=2^30`, exactly: where a column's ray
/// crosses a middle's wall, in 2.30 (a ray exactly on a texel edge takes the texel right of it,
/// the oracle's tie rule). Outside the wall (`numerator ≤ 0` or `≥ denominator`) the clamp
/// alone; inside, both are under 2^32 and the quotient comes from the denominator's
/// reciprocal (`2^(30+p)/d` with `2^p ≤ d < 2^(p+1)`, within a unit or two of exact), its
/// remainder brought into `0..d` a unit at a time.
#[inline(always)]
fn ray_fraction(numerator: i64, denominator: u32) -> u32 {
    if numerator <= 0 {
        return 0;
    }
    let (n, d) = (numerator as u64, u64::from(denominator));
    if n >= d {
        return 1 << 30;
    }
    let (reciprocal, p) = crate::math::recip_with_bit_length(denominator);
    let mut t = (n * u64::from(reciprocal)) >> p;
    let (d, mut remainder) = (d as i64, (n << 30) as i64 - (t * d) as i64);
    while remainder < 0 {
        t -= 1;
        remainder += d;
    }
    while remainder >= d {
        t += 1;
        remainder -= d;
    }
    t as u32
}

/// Texels per row at eye depth `depth` (24.8 bits), `z'/d_y` in 16.16, one less where its
/// product with `rows_per_texel` would pass 2^32: the sprite kernel's bound on its steps
/// (`SpriteColumn::reads_inside`). For a thing both are rounded quotients of reciprocals good
/// to 1e-9, so the product passes 2^32 by a few units at most, less than one step of
/// `rows_per_texel` (at least `d_y / EYE_DEPTH_MAX`, about 170 in 16.16). A middle's depth
/// comes from the reciprocal of its wall's constant, which an eye near the wall's line makes
/// small, and there the two disagree by more (the long soak found 5 in 10,000, in the bench
/// gallery's window): a thousandth less, until the product fits.
fn texels_per_row(depth: i32, rows_per_texel: i64, inverse_focal_y: i32) -> u32 {
    // Both below 2^32 (depths under 2^23 bits, 2.30 reciprocals): 32-bit factors.
    let mut iscale = u64::from(((i64::from(depth) * i64::from(inverse_focal_y)) >> 22) as u32);
    let rows = u64::from(rows_per_texel.max(0) as u32);
    if rows * iscale > 1 << 32 {
        iscale -= 1;
        while rows * iscale > 1 << 32 {
            iscale -= (iscale >> 10) + 1;
        }
    }
    iscale as u32
}

/// The image of `wall`'s middle (a still sprite set's), if it has one.
fn middle_image(assets: &RenderAssets, wall: &Wall) -> Option<usize> {
    if wall.middle == NO_TEXTURE {
        return None;
    }
    let set = assets.sprite_sets.get(usize::from(wall.middle))?;
    Some(usize::from(set.first)).filter(|&image| image < assets.sprites.len())
}

/// The image of `thing`'s sprite set the frame shows: its animation frame at the view's tick,
/// seen from the eye's side of it; `None` if the set or the image is not among the assets.
/// Out of line: [`Things::collect`] calls it once per thing a frame, and kept apart it leaves
/// that loop small enough for the VRAM after a page. It runs from the cartridge, where a sine
/// costs about 280 cycles and a divide 450: the facing's sine only for a set that rotates, the
/// animation's quotients by the reciprocal table ([`quotient`], through
/// [`SpriteSet::image_by`](portalcast_format::SpriteSet::image_by)).
#[inline(never)]
fn image_of(frame: &ThingView, thing: &Thing) -> Option<usize> {
    let assets = frame.assets;
    let set = assets.sprite_sets.get(usize::from(thing.sprite))?;
    let rotation = if set.rotates() {
        let eye = frame.view.eye.position;
        let (sin, cos) = crate::math::Angle::from_bits(thing.angle).sin_cos();
        set.rotation(
            eye.x.to_bits() - thing.x_fx8,
            eye.y.to_bits() - thing.y_fx8,
            sin.to_bits(),
            cos.to_bits(),
        )
    } else {
        0
    };
    let image = set.image_by(frame.view.tick, thing.frame_ticks, rotation, quotient);
    assets.sprites.get(image).map(|_| image)
}

/// Whether `a` is drawn before `b`: of a later visit (behind), or of the same visit a middle
/// before a thing, and of two things the farther, or as far the earlier in the map.
fn drawn_before(visible: &[VisibleThing], middles: &[VisibleMiddle], a: Drawn, b: Drawn) -> bool {
    let visit = |item: Drawn| match item {
        Drawn::Thing(index) => visible[usize::from(index)].visit,
        Drawn::Middle(index) => middles[usize::from(index)].visit,
    };
    let (visit_a, visit_b) = (visit(a), visit(b));
    if visit_a != visit_b {
        return visit_a > visit_b;
    }
    match (a, b) {
        (Drawn::Thing(a), Drawn::Thing(b)) => {
            let (a, b) = (&visible[usize::from(a)], &visible[usize::from(b)]);
            a.depth > b.depth || (a.depth == b.depth && a.thing < b.thing)
        }
        (Drawn::Middle(_), Drawn::Thing(_)) => true,
        _ => false,
    }
}

/// Where `thing`'s sprite lies on the screen of `frame`, with its columns over the whole width;
/// `None` if it is nearer than [`THING_DEPTH_MIN`] or off the screen.
fn project(
    frame: &ThingView,
    sector: &portalcast_format::Sector,
    thing: &Thing,
    sprite: &Sprite,
) -> Option<VisibleThing> {
    let view = frame.view;
    let viewport = &view.viewport;
    let eye = view.eye.to_eye(WorldPoint {
        x: Fx24_8::from_bits(thing.x_fx8),
        y: Fx24_8::from_bits(thing.y_fx8),
    });
    let depth = eye.z.to_bits();
    if depth < THING_DEPTH_MIN << 8 {
        return None;
    }
    // 1/z' in 2.30; a product of 24.8 by 2.30 bits is 2^38 per unit.
    let inverse_depth = i64::from(eye.z.recip_fx2_30().to_bits());
    let (width, height) = (i32::from(sprite.width), i32::from(sprite.height));
    // Screen columns: `cx + d_x·x'/z'` in 16.16 (the 2^38 product shifted by 22).
    let centre_x = i64::from(viewport.width) << 15;
    let left_bits = i64::from(eye.x.to_bits() - (width << 7));
    let x_left = centre_x + ((left_bits * inverse_depth * i64::from(viewport.focal_x)) >> 22);
    let columns_per_texel = (inverse_depth * i64::from(viewport.focal_x)) >> 14;
    let x_right = x_left + i64::from(width) * columns_per_texel;
    let screen_width = i64::from(viewport.width) << 16;
    if x_right <= 0 || x_left >= screen_width {
        return None;
    }
    // Rows: `cy + d_y·(eye_z − h)/z'` for the sprite's top edge.
    let bottom = match thing.flags & THING_HANGING {
        0 => sector.floor_z + i32::from(thing.z),
        _ => sector.ceil_z - i32::from(thing.z) - height,
    };
    let top_bits = i64::from((bottom + height) << 8);
    let above_eye = i64::from(view.eye_z.to_bits()) - top_bits;
    let y_top = (i64::from(viewport.horizon_y) << 16)
        + ((above_eye * inverse_depth * i64::from(viewport.focal_y)) >> 22);
    let rows_per_texel = (inverse_depth * i64::from(viewport.focal_y)) >> 14;
    let y_bottom = y_top + i64::from(height) * rows_per_texel;
    if y_bottom <= 0 || y_top >= i64::from(viewport.height) << 16 {
        return None;
    }
    // Texels per column and per row: z'/d in 16.16 (24.8 by 2.30 bits, shifted by 22); per
    // row at most 2^32 / rows per texel, the sprite kernel's bound on its steps.
    let iscale_x = ((i64::from(depth) * frame.inverse_focal_x) >> 22) as u32;
    let iscale = texels_per_row(depth, rows_per_texel, frame.inverse_focal_y);
    // The first column whose centre is right of the left edge, and its texture column.
    // On screen, both edges are within the sprite's width (at most 256 texels of 30 columns)
    // of it: 16.16 holds them.
    let column_of = |x: i64| viewport.first_column_at_or_after_x(Fx16_16::from_bits(x as i32));
    let (first, end) = (i64::from(column_of(x_left)), i64::from(column_of(x_right)));
    let offset = ((first << 16) + 0x8000 - x_left) as u64;
    let u_first = ((offset * u64::from(iscale_x)) >> 16) as u32;
    let light = light_row(sector.light, depth >> 8, view.lighting);
    Some(VisibleThing {
        visit: 0,
        translucent: false,
        depth,
        thing: 0,
        sprite: IMAGE_UNKNOWN,
        first: first as i16,
        end: end as i16,
        clips_at: 0,
        light_row: light.map_or(u8::MAX, |row| row as u8),
        u_first,
        iscale_x,
        y_top: y_top as i32,
        scale: rows_per_texel as i32,
        iscale,
    })
}
