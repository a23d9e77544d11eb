//! The compiled maps and render assets as the ROM uses them: the map the game starts on
//! (`DEMO_MAP`), the next map for the menu, and the textures placed as the settings ask. (The
//! bench scene's camera path is `crate::flight`.)

use portalcast_format::{Colormap, MapTables, Texture};

use crate::assets;
use portalcast::render::light::Lighting;
use portalcast::render::view::TexturePlacement;
use portalcast::render::RenderAssets;

/// Name of the map the demo shows.
pub const DEMO_MAP: &str = "bench";

/// The demo map from the compiled assets (the first map if there is no `bench`).
pub fn demo_map() -> MapTables<'static> {
    *assets::MAPS
        .iter()
        .find(|map| map.name == DEMO_MAP)
        .unwrap_or(&assets::MAPS[0])
}

/// The compiled map called `name`.
pub fn map_named(name: &str) -> Option<MapTables<'static>> {
    assets::MAPS.iter().find(|map| map.name == name).copied()
}

/// The map after `map` in the compiled order (wrapping): what Start switches to.
pub fn next_map(map: &MapTables) -> MapTables<'static> {
    let index = assets::MAPS
        .iter()
        .position(|candidate| candidate.name == map.name)
        .unwrap_or(0);
    assets::MAPS[(index + 1) % assets::MAPS.len()]
}

/// The compiled textures, sky and colormap.
pub fn render_assets() -> RenderAssets<'static> {
    RenderAssets::from_assets(&assets::ASSETS)
}

/// The compiled assets with the textures and colormap `placement` asks for: `in_fast_memory`
/// hands out the copies in fast memory (the ROM's `hw::memory`: texels in EWRAM, the colormap in
/// the OBJ VRAM that Mode 4 leaves free; the host has no such memory and passes the cartridge's
/// own).
pub fn assets_for(
    placement: TexturePlacement,
    in_fast_memory: fn() -> (&'static [Texture<'static>], &'static Colormap),
) -> RenderAssets<'static> {
    let (textures, colormap) = match placement {
        TexturePlacement::Rom => (assets::TEXTURES, &assets::COLORMAP.0),
        TexturePlacement::Ewram => in_fast_memory(),
    };
    RenderAssets {
        textures,
        colormap,
        ..render_assets()
    }
}

/// The label the ROM prints for a lighting setting.
pub const fn lighting_label(lighting: Lighting) -> &'static str {
    match lighting {
        Lighting::Off => "off",
        Lighting::Sector => "sector",
        Lighting::SectorDepth => "depth",
    }
}

/// Parses [`lighting_label`].
pub fn lighting_from_label(label: &str) -> Option<Lighting> {
    [Lighting::Off, Lighting::Sector, Lighting::SectorDepth]
        .into_iter()
        .find(|l| lighting_label(*l) == label)
}
