//! Sprite columns: the twin of `asm/sprite.s`. A sprite column is a list of opaque runs (posts,
//! [`portalcast_format::Sprite`]); the kernel draws each run's rows inside a clip window and
//! skips the transparent rows between them without looking at them.
//!
//! The integers, shared with the kernel (16.16 rows and texels):
//! - a post from texel row `top`, `len` texels long, covers screen rows `[y0, y1)` with
//!   `y0 = y_top + top·scale` and `y1 = y0 + len·scale` (wrapping adds, as the ARM's);
//! - it draws rows `first..end`: `first = max((y0 + 0x7fff) >> 16, clip.top)` and
//!   `end = min((y1 + 0x7fff) >> 16, clip.bottom)` (the rows whose centre `r + ½` is in
//!   `[y0, y1)`, the walls' row rule);
//! - the texel of row `first` is `v >> 16` with `v = ((first << 16) + 0x8000 − y0) · iscale >> 16`
//!   (a 64-bit product), and `v` grows by `iscale` a row. Rounding may take the last row's `v` to
//!   the post's length: that reads the post's pad texel, a copy of its last.
//!
//! Posts run top to bottom, so the kernel stops at the first post that starts at or below the
//! clip window's bottom.

use super::Window;

/// One sprite column as the kernel takes it.
#[derive(Clone, Copy, Debug)]
pub struct SpriteColumn<'a> {
    /// The column's post count and posts ([`portalcast_format::Sprite::posts`] from the
    /// column's offset on).
    pub posts: &'a [u8],
    /// Screen row of the sprite's top edge (texel row 0), 16.16.
    pub y_top: i32,
    /// Screen rows per texel, 16.16.
    pub scale: i32,
    /// Texels per screen row, 16.16.
    pub iscale: u32,
    /// The rows the column may draw.
    pub clip: Window,
    /// Light row the texels go through (an identity row for unlit).
    pub colormap: &'a [u8; 256],
    /// For a translucent column, the table that blends the lit texel over the pixel behind
    /// (`blend[behind][front]`).
    pub blend: Option<&'a portalcast_format::BlendTable>,
}

/// One run of rows a sprite column draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpriteRun<'a> {
    /// First screen row.
    pub row: usize,
    /// Rows drawn.
    pub count: usize,
    /// 16.16 texel position of the first row within `texels`.
    pub v: u32,
    /// The post's texels and its pad texel.
    pub texels: &'a [u8],
}

impl<'a> SpriteColumn<'a> {
    /// The runs of rows the kernel draws, top to bottom.
    pub fn runs(&self) -> impl Iterator<Item = SpriteRun<'a>> + '_ {
        let posts = self.posts;
        let count = posts.first().copied().unwrap_or(0);
        let mut at = 1;
        let mut done = false;
        (0..count).filter_map(move |_| {
            if done {
                return None;
            }
            // A post that would end past the column's bytes ends the column, as in the kernel.
            let (Some(&top), Some(&len)) = (posts.get(at), posts.get(at + 1)) else {
                done = true;
                return None;
            };
            let (top, len) = (i32::from(top), usize::from(len));
            let Some(texels) = posts.get(at + 2..at + 2 + len + 1) else {
                done = true;
                return None;
            };
            at += 2 + len + 1;
            let y0 = self.y_top.wrapping_add(top.wrapping_mul(self.scale));
            let y1 = y0.wrapping_add((len as i32).wrapping_mul(self.scale));
            let first_unclipped = y0.wrapping_add(0x7fff) >> 16;
            if first_unclipped >= i32::from(self.clip.bottom) {
                done = true;
                return None;
            }
            let first = first_unclipped.max(i32::from(self.clip.top));
            let end = (y1.wrapping_add(0x7fff) >> 16).min(i32::from(self.clip.bottom));
            if first >= end {
                return None;
            }
            let offset = (first << 16).wrapping_add(0x8000).wrapping_sub(y0) as u32;
            let v = ((u64::from(offset) * u64::from(self.iscale)) >> 16) as u32;
            Some(SpriteRun {
                row: first as usize,
                count: (end - first) as usize,
                v,
                texels,
            })
        })
    }

    /// Whether the kernel reads only inside [`SpriteColumn::posts`] and steps no row past its
    /// post: the column has its post count, and the steps fit. The kernel bounds its walk of
    /// the posts by the column's end itself (a post that would end past it ends the column, as
    /// [`SpriteColumn::runs`] does), so the posts need no walk here.
    ///
    /// The rows: a post's rows end at `end = (y1 + 0x7fff) >> 16`, so every row `r` has
    /// `(r << 16) + 0x8000 − y0 < y1 − y0 = len·scale`, and its texel position is at most that
    /// times `iscale`, over 2^16: below `len` texels where `scale·iscale ≤ 2^32` (a row of the
    /// post never steps beyond a texel per row's worth of rows), with no wrap-around where
    /// `y_top` and `256·scale` stay far inside i32.
    pub fn reads_inside(&self) -> bool {
        !self.posts.is_empty() && steps_fit(self.y_top, self.scale, self.iscale)
    }

    /// The palette index a pixel that held `behind` gets from the lit texel `front`.
    #[inline]
    pub fn over(&self, behind: u8, front: u8) -> u8 {
        match self.blend {
            Some(blend) => blend[usize::from(behind)][usize::from(front)],
            None => front,
        }
    }

    /// The palette indices of `run`, top to bottom, before any blending.
    pub fn indices(&self, run: SpriteRun<'a>) -> impl Iterator<Item = u8> + 'a {
        let colormap = self.colormap;
        let iscale = self.iscale;
        let mut v = run.v;
        (0..run.count).map(move |_| {
            let texel = run.texels[(v >> 16) as usize];
            v = v.wrapping_add(iscale);
            colormap[usize::from(texel)]
        })
    }
}

/// Whether the sprite kernel's steps stay inside a post (see [`SpriteColumn::reads_inside`]).
#[inline(always)]
pub fn steps_fit(y_top: i32, scale: i32, iscale: u32) -> bool {
    scale >= 0
        && (scale as u64) * u64::from(iscale) <= 1 << 32
        && scale < 1 << 22
        && y_top.unsigned_abs() < 1 << 30
}

/// One column of a [`SpriteBatch`]: the fields of a [`SpriteColumn`] that vary from column to
/// column, compact (the ARM batch kernel reads them in this layout, `asm/sprite.s`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(C)]
pub struct BatchColumn {
    /// The logical screen column.
    pub x: u8,
    /// The image's column.
    pub column: u8,
    /// The colormap row (`u8::MAX`: unlit, the identity row).
    pub light_row: u8,
    /// The rows the column may draw.
    pub clip: Window,
    /// Screen row of the image's top edge, 16.16.
    pub y_top: i32,
    /// Screen rows per texel, 16.16.
    pub scale: i32,
    /// Texels per screen row, 16.16.
    pub iscale: u32,
}

/// Columns of one sprite image drawn by one call ([`super::Canvas::sprite_columns`]): a thing's
/// columns, or a portal middle's.
#[derive(Clone, Copy, Debug)]
pub struct SpriteBatch<'a> {
    /// The image's columns' offsets and posts ([`portalcast_format::Sprite::posts`]).
    pub posts: &'a [u8],
    /// The columns drawn, in order.
    pub columns: &'a [BatchColumn],
    /// The light rows the columns' `light_row`s name.
    pub colormap: &'a portalcast_format::Colormap,
    /// For a translucent image, the blend table (as [`SpriteColumn::blend`]).
    pub blend: Option<&'a portalcast_format::BlendTable>,
}

impl<'a> SpriteBatch<'a> {
    /// Column `record` as the sprite kernel draws it; `None` (the column is skipped, by the
    /// batch kernel too) where the image's offset table or its offset lies outside the posts.
    pub fn column(&self, record: &BatchColumn) -> Option<SpriteColumn<'a>> {
        let at = 4 * usize::from(record.column);
        let offset = u32::from_le_bytes(self.posts.get(at..at + 4)?.try_into().ok()?);
        let posts = self
            .posts
            .get(offset as usize..)
            .filter(|p| !p.is_empty())?;
        Some(SpriteColumn {
            posts,
            y_top: record.y_top,
            scale: record.scale,
            iscale: record.iscale,
            clip: record.clip,
            colormap: match record.light_row {
                u8::MAX => &super::IDENTITY_ROW,
                row => self.colormap.get(usize::from(row))?,
            },
            blend: self.blend,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two posts: rows 1..3 (texels 10, 11) and row 5 (texel 20), with their pads.
    const POSTS: [u8; 10] = [2, 1, 2, 10, 11, 11, 5, 1, 20, 20];

    fn column(clip: Window, scale: i32) -> SpriteColumn<'static> {
        SpriteColumn {
            posts: &POSTS,
            y_top: 0,
            scale,
            iscale: ((1u64 << 32) / scale as u64) as u32,
            clip,
            colormap: &crate::raster::IDENTITY_ROW,
            blend: None,
        }
    }

    fn pixels(column: &SpriteColumn) -> Vec<(usize, u8)> {
        column
            .runs()
            .flat_map(|run| (run.row..).zip(column.indices(run)))
            .collect()
    }

    #[test]
    fn one_row_a_texel_skips_the_gap() {
        let column = column(
            Window {
                top: 0,
                bottom: 100,
            },
            1 << 16,
        );
        assert_eq!(pixels(&column), [(1, 10), (2, 11), (5, 20)]);
    }

    #[test]
    fn doubled_rows_repeat_texels_and_clip_cuts_them() {
        let column = column(Window { top: 3, bottom: 11 }, 2 << 16);
        // Post 1 covers rows 2..6, post 2 rows 10..12.
        assert_eq!(pixels(&column), [(3, 10), (4, 11), (5, 11), (10, 20)]);
    }

    #[test]
    fn a_clip_above_a_post_stops_the_column() {
        let column = column(Window { top: 0, bottom: 2 }, 1 << 16);
        assert_eq!(pixels(&column), [(1, 10)]);
    }
}
