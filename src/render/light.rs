//! The light rule: a sector's level plus a depth falloff, turned into a colormap row so a lit
//! pixel costs one byte load. The oracle calls these same functions.

use crate::raster::wall_run::RunLight;
use portalcast_format::{colormap_row, Colormap, LIGHT_NEUTRAL};

/// Lighting quality, a run-time knob.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lighting {
    /// Textures as they are: the unlit kernels, no colormap.
    Off,
    /// Each sector's own light level.
    Sector,
    /// The sector's level, brighter near the eye and darker far away.
    SectorDepth,
}

/// Extra light at depth 0 in [`Lighting::SectorDepth`].
pub const DEPTH_BOOST: i32 = 32;
/// World units of depth per light step lost in [`Lighting::SectorDepth`].
pub const DEPTH_UNITS_PER_STEP: i32 = 16;

/// The light level (0..=255) of a surface of a sector with `sector_light`, seen at eye-space
/// depth `depth` (whole world units, ≥ 0).
pub const fn light_level(sector_light: u8, depth: i32, lighting: Lighting) -> u8 {
    match lighting {
        Lighting::Off => LIGHT_NEUTRAL,
        Lighting::Sector => sector_light,
        Lighting::SectorDepth => {
            let level = sector_light as i32 + DEPTH_BOOST - depth / DEPTH_UNITS_PER_STEP;
            if level < 0 {
                0
            } else if level > 255 {
                255
            } else {
                level as u8
            }
        }
    }
}

/// The colormap row a pixel goes through, or `None` when lighting is off (unlit kernels).
pub const fn light_row(sector_light: u8, depth: i32, lighting: Lighting) -> Option<usize> {
    match lighting {
        Lighting::Off => None,
        _ => Some(colormap_row(light_level(sector_light, depth, lighting))),
    }
}

/// [`light_row`] as a canvas's wall loop applies it column by column (`asm/wall.s`): no
/// colormap, the sector's one row, or the row of `light + DEPTH_BOOST − (z' >> 12)` (z' in
/// 24.8) clamped to `0..=255` and shifted right by 3, of `colormap`.
pub fn run_light(sector_light: u8, lighting: Lighting, colormap: &Colormap) -> RunLight<'_> {
    match lighting {
        Lighting::Off => RunLight::Off,
        Lighting::Sector => RunLight::Fixed(&colormap[colormap_row(sector_light)]),
        Lighting::SectorDepth => RunLight::Depth {
            base: i32::from(sector_light) + DEPTH_BOOST,
            colormap,
        },
    }
}

/// [`light_row`] as the ARM middle loop takes it (`asm/middle.s`, `MiddleShared`): mode 0 (no
/// colormap), 1 (the colormap row `base`) or 2 (the row of `base − (z' >> 12)`, z' in 24.8,
/// clamped to `0..=255` and shifted right by 3), and `base`.
pub fn light_rule(sector_light: u8, lighting: Lighting) -> (u32, i32) {
    match lighting {
        Lighting::Off => (0, 0),
        Lighting::Sector => (1, colormap_row(sector_light) as i32),
        Lighting::SectorDepth => (2, i32::from(sector_light) + DEPTH_BOOST),
    }
}

// The loop's depth rule is `light_level`'s only while a step is 16 units (`z' >> 12` is
// `(z' >> 8) / 16`) and a colormap row 8 levels.
const _: () = assert!(DEPTH_UNITS_PER_STEP == 16);
const _: () = assert!(colormap_row(255) == 31 && colormap_row(8) == 1 && colormap_row(7) == 0);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn depth_falloff_brightens_near_and_darkens_far() {
        assert_eq!(light_level(128, 0, Lighting::SectorDepth), 160);
        assert_eq!(light_level(128, 512, Lighting::SectorDepth), 128);
        assert_eq!(light_level(10, 100_000, Lighting::SectorDepth), 0);
        assert_eq!(light_level(250, 0, Lighting::SectorDepth), 255);
        assert_eq!(light_level(77, 9_999, Lighting::Sector), 77);
        assert_eq!(light_row(77, 0, Lighting::Off), None);
    }
}
