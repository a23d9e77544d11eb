//! Things (Doom's r_things): each sector visit collects the things of its sector that fall in
//! its columns, projected once and with the visit's clip windows over their columns copied (the
//! window a sector is seen through is exactly where its things may show: module `surface`); after
//! the scene, the things are drawn back to front, every column through the sprite kernel
//! clipped to its copied window.
//!
//! A thing's sprite is a rectangle facing the camera at its centre's depth `z'`, so one depth
//! orders two things wherever they overlap, and drawing the farther first is exact.

use portalcast_format::{Sprite, Thing, THING_HANGING};

use super::light::light_row;
use super::surface::{Surface, THING_DEPTH_MIN};
use super::view::View;
use super::RenderAssets;
use crate::math::{Fx24_8, WorldPoint};
use crate::raster::sprite::SpriteColumn;
use crate::raster::{Canvas, Window};
use portalcast_format::MapTables;

/// Things a frame draws at most (a thing seen through two portals counts twice); more are left
/// out and counted ([`ThingStats::dropped`]).
pub const VISIBLE_THINGS_MAX: usize = 64;

/// Columns of clip windows the visible things of a frame keep at most (a thing's columns in one
/// visit take one each); a thing that finds no room is left out and counted.
pub const THING_CLIP_COLUMNS: usize = 1024;

/// The colormap row that changes nothing: unlit sprites draw through it.
static IDENTITY_ROW: [u8; 256] = {
    let mut row = [0u8; 256];
    let mut index = 0;
    while index < 256 {
        row[index] = index as u8;
        index += 1;
    }
    row
};

/// A thing as one visit sees it: where its sprite lies on screen (16.16 columns and rows) and
/// which columns of the visit it covers.
#[derive(Clone, Copy, Debug, Default)]
struct VisibleThing {
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

/// Counters of the things stage in one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ThingStats {
    /// Things drawn (once per visit they were seen in).
    pub drawn: u32,
    /// Things seen but left out: no room in [`VISIBLE_THINGS_MAX`] or [`THING_CLIP_COLUMNS`].
    pub dropped: u32,
}

/// The things stage's per-frame memory.
pub struct Things {
    visible: [VisibleThing; VISIBLE_THINGS_MAX],
    count: usize,
    clips: [Window; THING_CLIP_COLUMNS],
    clips_used: usize,
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
    inverse_focal_y: i64,
}

impl<'v, 'a> ThingView<'v, 'a> {
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
            inverse_focal_y: i64::from(crate::math::recip_small(viewport.focal_y as u32).to_bits()),
        }
    }
}

impl Things {
    /// Empty.
    pub const fn new() -> Things {
        Things {
            visible: [VisibleThing {
                depth: 0,
                thing: 0,
                sprite: 0,
                first: 0,
                end: 0,
                clips_at: 0,
                light_row: 0,
                u_first: 0,
                iscale_x: 0,
                y_top: 0,
                scale: 0,
                iscale: 0,
            }; VISIBLE_THINGS_MAX],
            count: 0,
            clips: [Window::EMPTY; THING_CLIP_COLUMNS],
            clips_used: 0,
            stats: ThingStats {
                drawn: 0,
                dropped: 0,
            },
        }
    }

    /// Forgets the last frame's things.
    pub fn clear(&mut self) {
        self.count = 0;
        self.clips_used = 0;
        self.stats = ThingStats::default();
    }

    /// Collects the things of sector `sector_index` that show in the visit's columns
    /// `first..end`, whose clip windows are `clip` (indexed by column).
    #[inline(never)]
    pub(crate) fn collect(
        &mut self,
        frame: &ThingView,
        sector_index: u16,
        columns: core::ops::Range<i32>,
        clip: &[Window],
    ) {
        let (map, assets) = (frame.map, frame.assets);
        let (first, end) = (columns.start, columns.end);
        let range = map.things_range(sector_index);
        let sector = &map.sectors[usize::from(sector_index)];
        for (index, thing) in range.clone().zip(&map.things[range]) {
            let Some(image) = image_of(frame, thing) else {
                continue;
            };
            let Some(sprite) = assets.sprites.get(image) else {
                continue;
            };
            let Some(mut seen) = project(frame, sector, thing, sprite) else {
                continue;
            };
            let columns_first = (seen.first as i32).max(first);
            let columns_end = (seen.end as i32).min(end);
            if columns_first >= columns_end {
                continue;
            }
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
            seen.clips_at = self.clips_used as u16;
            self.clips[self.clips_used..self.clips_used + columns]
                .copy_from_slice(&clip[columns_first as usize..columns_end as usize]);
            self.clips_used += columns;
            self.visible[self.count] = seen;
            self.count += 1;
        }
    }

    /// Draws the collected things, farthest first (at equal depth, the map's earlier thing
    /// first), and returns the frame's counts.
    #[inline(never)]
    pub(crate) fn draw(&mut self, assets: &RenderAssets, canvas: &mut impl Canvas) -> ThingStats {
        let visible = &mut self.visible[..self.count];
        // Insertion sort: a frame's few things, often already nearly in order.
        for next in 1..visible.len() {
            let mut at = next;
            while at > 0 && drawn_before(&visible[at], &visible[at - 1]) {
                visible.swap(at, at - 1);
                at -= 1;
            }
        }
        for seen in visible.iter() {
            let sprite = &assets.sprites[usize::from(seen.sprite)];
            let colormap = match seen.light_row {
                u8::MAX => &IDENTITY_ROW,
                row => &assets.colormap[usize::from(row)],
            };
            canvas.set_surface(Surface::Thing(seen.thing));
            let last_column = usize::from(sprite.width) - 1;
            let mut u = seen.u_first;
            let clips = &self.clips[usize::from(seen.clips_at)..];
            for (x, clip) in (seen.first..seen.end).zip(clips) {
                if !clip.is_empty() {
                    let column = ((u >> 16) as usize).min(last_column);
                    canvas.sprite_column(
                        x as usize,
                        &SpriteColumn {
                            posts: &sprite.posts[sprite.column_offset(column)..],
                            y_top: seen.y_top,
                            scale: seen.scale,
                            iscale: seen.iscale,
                            clip: *clip,
                            colormap,
                        },
                    );
                }
                u = u.wrapping_add(seen.iscale_x);
            }
        }
        self.stats.drawn = self.count as u32;
        self.stats
    }
}

/// The image of `thing`'s sprite set the frame shows: its animation frame at the view's tick,
/// seen from the eye's side of it.
fn image_of(frame: &ThingView, thing: &Thing) -> Option<usize> {
    let set = frame.assets.sprite_sets.get(usize::from(thing.sprite))?;
    let eye = frame.view.eye.position;
    let (sin, cos) = crate::math::Angle::from_bits(thing.angle).sin_cos();
    let rotation = set.rotation(
        eye.x.to_bits() - thing.x_fx8,
        eye.y.to_bits() - thing.y_fx8,
        sin.to_bits(),
        cos.to_bits(),
    );
    Some(set.image(frame.view.tick, thing.frame_ticks.max(1), rotation))
}

/// Whether `a` is drawn before `b`: farther, or as far and earlier in the map.
fn drawn_before(a: &VisibleThing, b: &VisibleThing) -> bool {
    a.depth > b.depth || (a.depth == b.depth && a.thing < b.thing)
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
    // Texels per column and per row: z'/d in 16.16 (24.8 by 2.30 bits, shifted by 22).
    let iscale_x = ((i64::from(depth) * frame.inverse_focal_x) >> 22) as u32;
    let iscale = ((i64::from(depth) * frame.inverse_focal_y) >> 22) as u32;
    // The first column whose centre is right of the left edge, and its texture column.
    let first = ((x_left + 0x7fff) >> 16).max(0);
    let end = ((x_right + 0x7fff) >> 16).min(i64::from(viewport.width));
    let offset = ((first << 16) + 0x8000 - x_left) as u64;
    let u_first = ((offset * u64::from(iscale_x)) >> 16) as u32;
    let light = light_row(sector.light, depth >> 8, view.lighting);
    Some(VisibleThing {
        depth,
        thing: 0,
        sprite: 0,
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
