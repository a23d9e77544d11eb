//! Doom's palette as portalcast's: the same 256 colours in the GBA's BGR555, except that
//! portalcast keeps index 0 for "transparent" ([`TRANSPARENT`]) and Doom draws with it (black).
//! Texels of index 0 take another index of the same colour as the GBA shows it, the nearest
//! if none is (Doom's palettes hold several blacks).

use portalcast_format::{bgr555, Palette, TRANSPARENT};

use super::graphics::IndexedImage;

/// Doom's palette (RGB) as portalcast's, and the index Doom's index 0 becomes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DoomPalette {
    /// Index 0 transparent, every other Doom's colour in BGR555.
    pub palette: Palette,
    /// The index that shows Doom's colour 0.
    pub zero_becomes: u8,
}

impl DoomPalette {
    /// From `PLAYPAL`'s first palette ([`super::palette`]).
    pub fn new(rgb: &[[u8; 3]; 256]) -> DoomPalette {
        let mut palette = [0u16; 256];
        for (entry, &[r, g, b]) in palette.iter_mut().zip(rgb).skip(1) {
            *entry = bgr555(r, g, b);
        }
        let shown = |index: usize| {
            let five = |c: u16, shift: u16| i32::from((c >> shift) & 0x1f);
            let c = palette[index];
            (five(c, 0), five(c, 5), five(c, 10))
        };
        let zero = {
            let [r, g, b] = rgb[0];
            let c = bgr555(r, g, b);
            (
                i32::from(c & 0x1f),
                i32::from((c >> 5) & 0x1f),
                i32::from((c >> 10) & 0x1f),
            )
        };
        let zero_becomes = (1..256)
            .min_by_key(|&index| {
                let (r, g, b) = shown(index);
                (r - zero.0).pow(2) + (g - zero.1).pow(2) + (b - zero.2).pow(2)
            })
            .unwrap_or(1) as u8;
        palette[usize::from(TRANSPARENT)] = 0;
        DoomPalette {
            palette,
            zero_becomes,
        }
    }

    /// Doom's index `index` as portalcast's.
    pub fn index(&self, index: u8) -> u8 {
        if index == TRANSPARENT {
            self.zero_becomes
        } else {
            index
        }
    }

    /// `image`'s texels in portalcast's indices: its gaps [`TRANSPARENT`], Doom's index 0 the
    /// index that shows it.
    pub fn texels(&self, image: &IndexedImage) -> Vec<u8> {
        image
            .texels
            .iter()
            .map(|texel| texel.map_or(TRANSPARENT, |index| self.index(index)))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn without_a_second_black_index_0_becomes_the_nearest_colour() {
        let mut rgb = [[200u8, 200, 200]; 256];
        rgb[0] = [0, 0, 0];
        rgb[77] = [9, 8, 8];
        rgb[90] = [30, 0, 0];
        let colours = DoomPalette::new(&rgb);
        assert_eq!(colours.zero_becomes, 77);
        assert_eq!((colours.index(0), colours.index(90)), (77, 90));
        let image = IndexedImage {
            width: 3,
            height: 1,
            texels: vec![Some(0), None, Some(90)],
        };
        assert_eq!(colours.texels(&image), [77, TRANSPARENT, 90]);
    }
}
