//! Which textures the ROM copies to EWRAM: the hottest that fit the EWRAM its engine leaves them
//! ([`portalcast_format::memory::ewram_texel_budget`]); the others are read from the cartridge
//! (slower, 5 cycles a byte against 3), so a texture set of any size builds.

use portalcast_format::{TextureChain, Wall, MOVER_CRUSHER, MOVER_DOOR, SKY};

use crate::{Compiled, CompiledMap, CompiledTexture};

/// Per texture of `compiled` (in table order): whether the ROM copies it to EWRAM.
pub(crate) fn textures_in_ewram(compiled: &Compiled) -> Vec<bool> {
    let textures = &compiled.textures;
    let bytes: Vec<usize> = textures.iter().map(CompiledTexture::blob_bytes).collect();
    let heat: Vec<u64> = texture_heat(textures.len(), &compiled.maps)
        .iter()
        .map(|heat| heat.walls.saturating_add(heat.flats))
        .collect();
    in_ewram(
        &bytes,
        &heat,
        portalcast_format::memory::ewram_texel_budget(textures.len(), compiled.live_state_bytes()),
    )
}

/// How much of the maps a texture covers, in square world units times 256, apart for its two
/// chains: the walls that show it (a wall's length times the height it shows the texture over:
/// the whole wall, or an upper or lower strip) read its column-major chain, the floors and
/// ceilings (their area) its row-major one.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct ChainHeat {
    pub(crate) walls: u64,
    pub(crate) flats: u64,
}

/// Every texture's [`ChainHeat`]; a moving sector counts with the heights it has when the map
/// starts (a closed door's face is the upper strip of the walls into it). The more of the world
/// a chain covers, the more pixels it is likely to draw, so the EWRAM copy takes the hottest
/// textures first, and the ROM's copy into the VRAM a 120×80 frame leaves free the hottest
/// chains ([`chains_by_heat`]).
pub(crate) fn texture_heat(texture_count: usize, maps: &[CompiledMap]) -> Vec<ChainHeat> {
    let mut heat = vec![ChainHeat::default(); texture_count];
    let mut add = |texture: u16, chain: TextureChain, amount: i64| {
        if let Some(slot) = heat.get_mut(usize::from(texture)) {
            let slot = match chain {
                TextureChain::Columns => &mut slot.walls,
                TextureChain::Rows => &mut slot.flats,
            };
            *slot = slot.saturating_add(amount.max(0) as u64);
        }
    };
    for map in maps {
        // Each sector's floor and ceiling as the map starts.
        let mut heights: Vec<(i32, i32)> = map
            .sectors
            .iter()
            .map(|sector| (sector.floor_z, sector.ceil_z))
            .collect();
        for mover in &map.movers {
            if let Some(slot) = heights.get_mut(usize::from(mover.sector)) {
                match mover.kind {
                    MOVER_DOOR | MOVER_CRUSHER => slot.1 = mover.start,
                    _ => slot.0 = mover.start,
                }
            }
        }
        for (index, sector) in map.sectors.iter().enumerate() {
            let (floor_z, ceil_z) = heights[index];
            let first = usize::from(sector.first_wall);
            let walls: &[Wall] = &map.walls[first..first + usize::from(sector.wall_count)];
            let length = |wall: &Wall| i64::from(wall.length_fx8);
            let height = i64::from(ceil_z - floor_z);
            for wall in walls {
                match wall.neighbour() {
                    None => add(wall.texture, TextureChain::Columns, length(wall) * height),
                    Some(next) => {
                        let (next_floor, next_ceil) = heights[usize::from(next)];
                        let upper = i64::from(ceil_z - next_ceil);
                        let lower = i64::from(next_floor - floor_z);
                        add(
                            wall.upper_texture,
                            TextureChain::Columns,
                            length(wall) * upper,
                        );
                        add(
                            wall.lower_texture,
                            TextureChain::Columns,
                            length(wall) * lower,
                        );
                    }
                }
            }
            // Twice the area (the shoelace sum over the sector's clockwise outline), times 128.
            let doubled_area: i64 = walls
                .iter()
                .map(|wall| {
                    let (a, b) = (
                        map.vertices[usize::from(wall.start)],
                        map.vertices[usize::from(wall.end)],
                    );
                    i64::from(a.x) * i64::from(b.y) - i64::from(b.x) * i64::from(a.y)
                })
                .sum::<i64>()
                .abs();
            add(sector.floor_texture, TextureChain::Rows, doubled_area * 128);
            if sector.ceil_texture != SKY {
                add(sector.ceil_texture, TextureChain::Rows, doubled_area * 128);
            }
        }
    }
    heat
}

/// Every chain of `compiled`'s textures that some map uses (not empty), as (texture index,
/// chain), the hottest first ([`ChainHeat`]; ties by index, columns first).
pub(crate) fn chains_by_heat(compiled: &Compiled) -> Vec<(u16, TextureChain)> {
    let heat = texture_heat(compiled.textures.len(), &compiled.maps);
    let mut chains: Vec<(u64, u16, TextureChain)> = Vec::new();
    for (index, texture) in compiled.textures.iter().enumerate() {
        for (chain, texels, heat) in [
            (TextureChain::Columns, &texture.columns, heat[index].walls),
            (TextureChain::Rows, &texture.rows, heat[index].flats),
        ] {
            if !texels.is_empty() {
                chains.push((heat, index as u16, chain));
            }
        }
    }
    chains.sort_by_key(|&(heat, index, chain)| {
        (core::cmp::Reverse(heat), index, chain == TextureChain::Rows)
    });
    chains
        .into_iter()
        .map(|(_, index, chain)| (index, chain))
        .collect()
}

/// Which of the textures (`bytes` each, `heat` each) go to EWRAM within `budget` bytes: the
/// hottest first (ties by index), each that still fits, so a large cold texture never keeps
/// smaller hot ones out.
pub(crate) fn in_ewram(bytes: &[usize], heat: &[u64], budget: usize) -> Vec<bool> {
    let mut order: Vec<usize> = (0..bytes.len()).collect();
    order.sort_by_key(|&index| (core::cmp::Reverse(heat[index]), index));
    let mut chosen = vec![false; bytes.len()];
    let mut used = 0usize;
    for index in order {
        if used + bytes[index] <= budget {
            used += bytes[index];
            chosen[index] = true;
        }
    }
    chosen
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hottest_that_fit_go_first() {
        // 100 bytes of room: the hottest (index 1) fits, the next (index 0, 80 bytes) does not,
        // the colder small one (index 2) still does.
        let chosen = in_ewram(&[80, 60, 40, 50], &[50, 90, 10, 0], 100);
        assert_eq!(chosen, vec![false, true, true, false]);
        // Everything fits: everything goes.
        assert_eq!(in_ewram(&[8, 8], &[0, 0], 16), vec![true, true]);
        // Nothing fits.
        assert_eq!(in_ewram(&[8], &[5], 4), vec![false]);
    }

    #[test]
    fn equal_heat_keeps_the_table_order() {
        assert_eq!(
            in_ewram(&[10, 10, 10], &[7, 7, 7], 20),
            vec![true, true, false]
        );
    }
}
