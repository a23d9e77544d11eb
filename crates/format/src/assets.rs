//! A game's compiled assets as one value: what the asset compiler emits as `ASSETS` beside the
//! separate statics, and what the engine's start-up and renderer take.

use crate::{
    BlendTable, Colormap, MapTables, Palette, Sky, Sprite, SpriteSet, Texture, TextureChain,
};

/// Everything the asset compiler made from a game's asset directory: its palette and light
/// colormap, textures (with the texel blob they point into), sky, sprites and maps. The
/// generated `assets.rs` holds one, `ASSETS`; the engine takes it by reference.
#[derive(Clone, Copy, Debug)]
pub struct Assets<'a> {
    /// The shared palette (BGR555); entry 0 is transparent.
    pub palette: &'a Palette,
    /// Light rows: `colormap[colormap_row(light)][index]`.
    pub colormap: &'a Colormap,
    /// Textures by index, pointing into [`Assets::texel_blob`].
    pub textures: &'a [Texture<'a>],
    /// Every texture's texels, the hottest first.
    pub texel_blob: &'a [u8],
    /// The bytes at the start of the blob that the compiler placed in EWRAM: the hottest
    /// textures that fit beside the engine's and the game's own state.
    pub texel_ewram_len: usize,
    /// Texture chains, hottest first: which the engine copies into spare VRAM first.
    pub texture_chains_by_heat: &'a [(u16, TextureChain)],
    /// The sky panorama, if the assets have one.
    pub sky: Option<Sky<'a>>,
    /// The 50 % blend of translucent things and middles, if any map has them.
    pub blend: Option<&'a BlendTable>,
    /// Sprite images by index.
    pub sprites: &'a [Sprite<'a>],
    /// Sprite sets by index (things refer to them by index).
    pub sprite_sets: &'a [SpriteSet<'a>],
    /// Every map, sorted by name.
    pub maps: &'a [MapTables<'a>],
}

impl<'a> Assets<'a> {
    /// The map called `name`.
    pub fn map(&self, name: &str) -> Option<&'a MapTables<'a>> {
        self.maps.iter().find(|map| map.name == name)
    }
}
