//! Colour tables and image tables: palette, light colormap, textures, sky, sprites.

/// The shared 256-colour palette in the GBA's BGR555 format: bits 0-4 red, 5-9 green, 10-14 blue.
/// Entry [`TRANSPARENT`] is reserved: no texture or sky texel uses it.
pub type Palette = [u16; 256];

/// Palette index that means "transparent" in sprites; never used by opaque images.
pub const TRANSPARENT: u8 = 0;

/// Number of rows in the light [`Colormap`].
pub const LIGHT_LEVELS: usize = 32;

/// The light level (and colormap row `LIGHT_NEUTRAL >> 3`) that shows textures unchanged.
pub const LIGHT_NEUTRAL: u8 = 128;

/// Light remapping: `colormap[row][index]` is the palette index that best shows colour `index`
/// at light row `row`.
///
/// Row `r` scales the colour's RGB by `r / 16` (clamped to full intensity) and takes the
/// nearest palette colour: row 0 is black, row 16 is the identity, row 31 is almost twice as
/// bright. Brighter rows are higher; pick the row with [`colormap_row`]. Index 0 (transparent)
/// maps to 0 in every row, and no other index maps to 0.
pub type Colormap = [[u8; 256]; LIGHT_LEVELS];

/// The colormap row for a sector light level `0..=255` (128 is neutral).
pub const fn colormap_row(light: u8) -> usize {
    (light >> 3) as usize
}

/// Converts 8-bit RGB to the GBA's BGR555, rounding each channel to the nearest of 32 steps.
pub const fn bgr555(r: u8, g: u8, b: u8) -> u16 {
    const fn five(c: u8) -> u16 {
        ((c as u16 * 31 + 127) / 255) & 0x1f
    }
    five(r) | (five(g) << 5) | (five(b) << 10)
}

/// The 50 % blend of two palette colours: `blend[behind][front]` is the palette index nearest
/// the average of the two colours (never [`TRANSPARENT`] unless both are). Built by the asset
/// compiler, shipped only when a map draws something translucent.
pub type BlendTable = [[u8; 256]; 256];

/// A power-of-two texture of palette indices with its mip chain, in up to two layouts.
///
/// Level `m` is `max(width >> m, 1)` × `max(height >> m, 1)` texels; the chain runs down to 1×1,
/// so `mip_count = max(width_log2, height_log2) + 1`. Each level is a box filter of the level
/// above, computed in RGB and then mapped to the palette.
///
/// * [`columns`](Self::columns), for walls: column-major, texel `(u, v)` of a level at
///   `u * level_height + v`, so a wall column is a contiguous run.
/// * [`rows`](Self::rows), for floors and ceilings: row-major, texel `(u, v)` at
///   `v * level_width + u`, with `u` along world +x and `v` along world +y, so the picture seen
///   from above (y down) is the image as painted.
///
/// Levels follow each other, level 0 first ([`level_offset`](Self::level_offset)). A layout
/// that no map uses is left out (empty slice).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct Texture<'a> {
    /// The image's file name without extension.
    pub name: &'a str,
    /// log2 of the width at level 0 (3..=8).
    pub width_log2: u8,
    /// log2 of the height at level 0 (3..=8).
    pub height_log2: u8,
    /// Number of mip levels, level 0 included.
    pub mip_count: u8,
    /// Column-major mip chain (walls), or empty if no wall uses this texture.
    pub columns: &'a [u8],
    /// Row-major mip chain (flats), or empty if no floor or ceiling uses this texture.
    pub rows: &'a [u8],
}

impl<'a> Texture<'a> {
    /// log2 of the width of mip level `level`.
    pub const fn level_width_log2(&self, level: u8) -> u8 {
        self.width_log2.saturating_sub(level)
    }

    /// log2 of the height of mip level `level`.
    pub const fn level_height_log2(&self, level: u8) -> u8 {
        self.height_log2.saturating_sub(level)
    }

    /// Texels in mip level `level`.
    #[inline]
    pub const fn level_len(&self, level: u8) -> usize {
        1 << (self.level_width_log2(level) + self.level_height_log2(level))
    }

    /// Offset of mip level `level` in either chain.
    #[inline]
    pub const fn level_offset(&self, level: u8) -> usize {
        let sides_log2 = self.width_log2 as u32 + self.height_log2 as u32;
        if level <= self.width_log2 && level <= self.height_log2 {
            // Neither side has stopped halving: a geometric series of ratio 1/4,
            // Σ_{m<level} 2^(sides − 2m) = (2^(sides+2) − 2^(sides+2−2·level)) / 3, with no
            // loop (the renderer asks for a level per wall column and per span).
            return ((1usize << (sides_log2 + 2))
                - (1usize << (sides_log2 + 2 - 2 * level as u32)))
                / 3;
        }
        let mut offset = 0;
        let mut m = 0;
        while m < level {
            offset += self.level_len(m);
            m += 1;
        }
        offset
    }

    /// Total texels in one layout's chain.
    pub const fn chain_len(&self) -> usize {
        self.level_offset(self.mip_count)
    }

    /// Mip level `level` of the column-major (wall) chain. Panics if absent.
    #[inline]
    pub fn wall_level(&self, level: u8) -> &'a [u8] {
        let start = self.level_offset(level);
        &self.columns[start..start + self.level_len(level)]
    }

    /// Mip level `level` of the row-major (flat) chain. Panics if absent.
    #[inline]
    pub fn flat_level(&self, level: u8) -> &'a [u8] {
        let start = self.level_offset(level);
        &self.rows[start..start + self.level_len(level)]
    }
}

/// One of a [`Texture`]'s two mip chains: the column-major one walls read, or the row-major one
/// floors and ceilings read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextureChain {
    /// [`Texture::columns`].
    Columns,
    /// [`Texture::rows`].
    Rows,
}

impl<'a> Texture<'a> {
    /// The texels of `chain` (empty where no map uses that layout).
    pub const fn chain(&self, chain: TextureChain) -> &'a [u8] {
        match chain {
            TextureChain::Columns => self.columns,
            TextureChain::Rows => self.rows,
        }
    }

    /// The texture with `chain` read from `texels` instead (a copy of it elsewhere).
    pub const fn with_chain<'b>(self, chain: TextureChain, texels: &'b [u8]) -> Texture<'b>
    where
        'a: 'b,
    {
        match chain {
            TextureChain::Columns => Texture {
                columns: texels,
                ..self
            },
            TextureChain::Rows => Texture {
                rows: texels,
                ..self
            },
        }
    }
}

/// The 360° sky panorama, drawn behind sectors whose ceiling is [`SKY`](crate::SKY).
///
/// Column-major: texel `(u, v)` at `u * height + v`. The width is a power of two covering one
/// full turn, so the column for view angle `a` (binary, 65536 per turn) is
/// `a >> (16 - width_log2)`; `v = 0` is the top row.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct Sky<'a> {
    /// log2 of the width in texels (one full turn).
    pub width_log2: u8,
    /// Height in texels.
    pub height: u16,
    /// Palette indices, column-major; never [`TRANSPARENT`].
    pub texels: &'a [u8],
}

/// A sprite image, stored as Doom's patches are: each column a list of opaque runs ("posts"),
/// so that drawing skips the transparent texels instead of testing each one. Its origin is the
/// bottom centre, placed at the thing's position.
///
/// `posts` holds, first, `width` little-endian `u32` offsets (from the start of `posts`), one per
/// column, left to right; at each offset the column: a post count (`u8`), then each post, top to
/// bottom: its first row (`u8`), its length `n` (`u8`, 1..=255), its `n` texels (palette indices,
/// never [`TRANSPARENT`]) and one pad texel, a copy of the last, which a column kernel stepping
/// the post's texels may read at its last row when its row steps round up. A run longer than
/// 255 texels is two posts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct Sprite<'a> {
    /// The image's file name without extension.
    pub name: &'a str,
    /// Width in texels (1..=256).
    pub width: u16,
    /// Height in texels (1..=256).
    pub height: u16,
    /// The columns' offsets and posts (layout above).
    pub posts: &'a [u8],
}

/// A thing's images: an animation of `frames` frames, each seen from `rotations` directions
/// (1, or 8 a turn apart by 45°). Image `first + frame·rotations + rotation` of the sprites
/// table shows frame `frame` seen from rotation `rotation` ([`SpriteSet::rotation`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub struct SpriteSet<'a> {
    /// The set's name (the sprite name things give).
    pub name: &'a str,
    /// Index of its first image in the sprites table.
    pub first: u16,
    /// Animation frames (1: still).
    pub frames: u8,
    /// Directions it is seen from: 1 or 8.
    pub rotations: u8,
}

/// `tan(22.5°)` in 16.16, rounded: the boundary between two of eight rotations.
const TAN_22_5_FX16: i64 = 27_146;

impl SpriteSet<'_> {
    /// The image (index in the sprites table) shown at game tick `tick` (60 a second), each
    /// frame shown for `frame_ticks` ticks (0 counts as 1), from rotation `rotation` (below
    /// [`SpriteSet::rotations`]).
    #[inline]
    pub fn image(&self, tick: u32, frame_ticks: u16, rotation: u8) -> usize {
        self.image_by(tick, frame_ticks, rotation, |n, d| n / d)
    }

    /// [`SpriteSet::image`] with its quotients taken by `quotient(n, d)` (`n / d`, `d ≥ 1`): the
    /// ROM's runs from the cartridge, where the library's divide costs about 450 cycles.
    #[inline]
    pub fn image_by(
        &self,
        tick: u32,
        frame_ticks: u16,
        rotation: u8,
        quotient: impl Fn(u32, u32) -> u32,
    ) -> usize {
        // A still set (most are) needs no divide: the ARM7TDMI has none.
        let frame = match self.frames as u32 {
            0 | 1 => 0,
            frames => {
                let shown = quotient(tick, frame_ticks.max(1) as u32);
                shown - quotient(shown, frames) * frames
            }
        };
        self.first as usize + frame as usize * self.rotations as usize + rotation as usize
    }

    /// Whether the image depends on the side it is seen from: eight rotations (one otherwise).
    #[inline]
    pub const fn rotates(&self) -> bool {
        self.rotations == 8
    }

    /// Which of the set's rotations shows a thing facing `facing` (binary angle, 65536 a turn)
    /// to an eye at `(dx, dy)` from it (any fixed-point scale, the same for both): rotation `r`
    /// is the thing seen from the direction `facing + r·45°`, the nearest of eight (rotation 0:
    /// the thing faces the eye). Always 0 for a set with one rotation. `sin` and `cos` are the
    /// facing's, 16.16.
    pub fn rotation(&self, dx: i32, dy: i32, sin: i32, cos: i32) -> u8 {
        if !self.rotates() {
            return 0;
        }
        let (dx, dy, sin, cos) = (dx as i64, dy as i64, sin as i64, cos as i64);
        // The eye's direction in the thing's frame: `along` its facing, `across` toward growing
        // angles.
        let along = dx * cos + dy * sin;
        let across = dy * cos - dx * sin;
        if across.abs() * 65_536 < TAN_22_5_FX16 * along.abs() {
            if along >= 0 {
                0
            } else {
                4
            }
        } else if along.abs() * 65_536 < TAN_22_5_FX16 * across.abs() {
            if across > 0 {
                2
            } else {
                6
            }
        } else {
            match (along > 0, across > 0) {
                (true, true) => 1,
                (false, true) => 3,
                (false, false) => 5,
                (true, false) => 7,
            }
        }
    }
}

/// Bytes a post takes before its texels: first row and length.
pub const POST_HEADER_BYTES: usize = 2;

/// One opaque run of a sprite column.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Post<'a> {
    /// First row of the run, 0 at the image's top.
    pub top: u8,
    /// The run's texels, top to bottom, followed by the pad texel (a copy of the last).
    pub texels_and_pad: &'a [u8],
}

impl Post<'_> {
    /// Rows in the run.
    pub fn len(&self) -> usize {
        self.texels_and_pad.len() - 1
    }

    /// Never true: a post holds at least one texel.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl<'a> Sprite<'a> {
    /// The byte offset of column `u`'s post count in [`Sprite::posts`].
    #[inline]
    pub fn column_offset(&self, u: usize) -> usize {
        let at = 4 * u;
        let bytes = [
            self.posts[at],
            self.posts[at + 1],
            self.posts[at + 2],
            self.posts[at + 3],
        ];
        u32::from_le_bytes(bytes) as usize
    }

    /// The posts of column `u`, top to bottom.
    pub fn column_posts(&self, u: usize) -> impl Iterator<Item = Post<'a>> + 'a {
        let posts = self.posts;
        let mut at = self.column_offset(u);
        let count = posts[at];
        at += 1;
        (0..count).map(move |_| {
            let top = posts[at];
            let len = usize::from(posts[at + 1]);
            let start = at + POST_HEADER_BYTES;
            at = start + len + 1;
            Post {
                top,
                texels_and_pad: &posts[start..start + len + 1],
            }
        })
    }

    /// The texel at column `u`, row `v` (0 at the top): [`TRANSPARENT`] where no post covers it.
    pub fn texel(&self, u: usize, v: usize) -> u8 {
        self.column_posts(u)
            .find_map(|post| {
                let row = v.checked_sub(usize::from(post.top))?;
                (row < post.len()).then(|| post.texels_and_pad[row])
            })
            .unwrap_or(TRANSPARENT)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotations_turn_with_the_facing_and_frames_with_the_tick() {
        let set = SpriteSet {
            name: "s",
            first: 10,
            frames: 3,
            rotations: 8,
        };
        // The eye 48 west of the thing; (sin, cos) of the facing in 16.16.
        let rotation = |sin: i32, cos: i32| set.rotation(-48 << 8, 0, sin, cos);
        let half = 46_341; // cos 45°
        assert_eq!(rotation(0, 65_536), 4); // facing east: its back
        assert_eq!(rotation(65_536, 0), 2); // facing south
        assert_eq!(rotation(0, -65_536), 0); // facing west: its front
        assert_eq!(rotation(-65_536, 0), 6); // facing north
        assert_eq!(rotation(half, half), 3); // facing south-east
        assert_eq!(set.image(0, 4, 5), 15);
        assert_eq!(set.image(4, 4, 5), 23);
        assert_eq!(set.image(12, 4, 5), 15);
        let still = SpriteSet {
            rotations: 1,
            ..set
        };
        assert_eq!(still.rotation(-48, 0, 0, 65_536), 0);
    }

    fn texture(width_log2: u8, height_log2: u8) -> Texture<'static> {
        Texture {
            name: "t",
            width_log2,
            height_log2,
            mip_count: width_log2.max(height_log2) + 1,
            columns: &[],
            rows: &[],
        }
    }

    #[test]
    fn square_chain_is_four_thirds() {
        let t = texture(6, 6);
        assert_eq!(t.mip_count, 7);
        assert_eq!(t.level_offset(1), 4096);
        assert_eq!(t.level_offset(2), 4096 + 1024);
        assert_eq!(t.chain_len(), 5461);
    }

    #[test]
    fn narrow_chain_clamps_the_short_side_at_one() {
        // 64×16: 64×16, 32×8, 16×4, 8×2, 4×1, 2×1, 1×1.
        let t = texture(6, 4);
        let sizes: [(u8, u8); 7] =
            core::array::from_fn(|m| (t.level_width_log2(m as u8), t.level_height_log2(m as u8)));
        assert_eq!(
            sizes,
            [(6, 4), (5, 3), (4, 2), (3, 1), (2, 0), (1, 0), (0, 0)]
        );
        assert_eq!(t.chain_len(), 1024 + 256 + 64 + 16 + 4 + 2 + 1);
    }

    #[test]
    fn level_offsets_are_the_running_sum_of_level_sizes() {
        for width_log2 in 0..=9u8 {
            for height_log2 in 0..=9u8 {
                let t = texture(width_log2, height_log2);
                let mut running = 0;
                for level in 0..=t.mip_count {
                    assert_eq!(
                        t.level_offset(level),
                        running,
                        "{width_log2}x{height_log2} level {level}"
                    );
                    running += t.level_len(level);
                }
            }
        }
    }

    #[test]
    fn bgr555_rounds_each_channel() {
        assert_eq!(bgr555(255, 255, 255), 0x7fff);
        assert_eq!(bgr555(255, 0, 0), 0x001f);
        assert_eq!(bgr555(0, 255, 0), 0x03e0);
        assert_eq!(bgr555(0, 0, 255), 0x7c00);
        assert_eq!(bgr555(4, 5, 0), 1 << 5);
        assert_eq!(colormap_row(LIGHT_NEUTRAL), 16);
        assert_eq!(colormap_row(255), LIGHT_LEVELS - 1);
    }
}
