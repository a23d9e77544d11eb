//! The renderer, in Doom's split: the sector walk (`walk`, Doom's r_bsp), wall projection
//! (`walls`, r_segs), floors and ceilings (`planes`, r_plane) and the texture and light rules
//! they share (`surface`, `light`), things (`things`, r_things), and the thesis' scene preprocessing (`visits`). Rasterizing
//! goes through [`crate::raster::Canvas`].

pub mod light;
pub mod planes;
pub mod ratio;
pub mod spans;
pub mod surface;
pub mod things;
pub mod view;
pub mod visits;
pub mod walk;
pub mod walls;

use portalcast_format::{Assets, BlendTable, Colormap, Sky, Sprite, SpriteSet, Texture};

/// What the renderer draws with: the compiled textures, the sky and the light colormap.
#[derive(Clone, Copy, Debug)]
pub struct RenderAssets<'a> {
    /// Textures by index (map tables refer to them by index).
    pub textures: &'a [Texture<'a>],
    /// The sky panorama.
    pub sky: Sky<'a>,
    /// Light rows.
    pub colormap: &'a Colormap,
    /// Sprite images by index.
    pub sprites: &'a [Sprite<'a>],
    /// Sprite sets by index (things refer to them by index): which image a thing shows.
    pub sprite_sets: &'a [SpriteSet<'a>],
    /// The 50 % blend of translucent things and middles, if any map has them.
    pub blend: Option<&'a BlendTable>,
}

/// The sky of assets without one: black, 1×8 texels. No map of theirs shows sky (the compiler
/// refuses a sky ceiling without a panorama), so it is never drawn.
static NO_SKY_TEXELS: [u8; 8] = [0; 8];

impl<'a> RenderAssets<'a> {
    /// The compiled assets as the renderer draws them, all read where the compiler left them
    /// (the cartridge). On the GBA, `hw::Machine::render_assets` hands out the same with the
    /// textures and the colormap copied to faster memory.
    pub fn from_assets(assets: &Assets<'a>) -> RenderAssets<'a> {
        RenderAssets {
            textures: assets.textures,
            sky: assets.sky.unwrap_or(Sky {
                width_log2: 0,
                height: 8,
                texels: &NO_SKY_TEXELS,
            }),
            colormap: assets.colormap,
            sprites: assets.sprites,
            sprite_sets: assets.sprite_sets,
            blend: assets.blend,
        }
    }
}
