//! The shared palette (NeuQuant over every used image), nearest-colour mapping onto it, the
//! light colormap and the 50 % blend table.

use std::collections::HashMap;

use portalcast_format::{
    bgr555, BlendTable, Colormap, Palette, LIGHT_LEVELS, LIGHT_NEUTRAL, TRANSPARENT,
};

/// Colours NeuQuant chooses: every palette entry except the transparent index 0.
const QUANTISED_COLOURS: usize = 255;
/// NeuQuant samples one pixel in this many (1 = all, best; 10 = its recommended balance).
const SAMPLE_FACTOR: i32 = 10;
/// Below this many pixels NeuQuant looks at every pixel, so small asset sets still train well.
const FULL_SAMPLE_BELOW: usize = 64 * 1024;

/// A colormap whose row `row` maps opaque index `index` to `entry(row, index)`; index 0
/// (transparent) maps to 0 in every row.
pub(crate) fn colormap_of(mut entry: impl FnMut(usize, usize) -> u8) -> Box<Colormap> {
    let mut map = Box::new([[0u8; 256]; LIGHT_LEVELS]);
    for (row, entries) in map.iter_mut().enumerate() {
        for (index, slot) in entries.iter_mut().enumerate().skip(1) {
            *slot = entry(row, index);
        }
    }
    map
}

/// An RGB colour, 8 bits per channel.
pub(crate) type Rgb = [u8; 3];

/// The palette and a cache of nearest-colour lookups onto it.
pub(crate) struct Quantiser {
    palette: Palette,
    /// What the GBA shows for each entry (BGR555 expanded back to 8 bits per channel).
    shown: [Rgb; 256],
    cache: HashMap<Rgb, u8>,
}

/// Expands a 5-bit channel to 8 bits the way the colour reaches the screen.
fn expand(five: u16) -> u8 {
    let five = (five & 0x1f) as u8;
    (five << 3) | (five >> 2)
}

impl Quantiser {
    /// Builds the palette from opaque sample pixels (RGB).
    pub fn new(samples: &[Rgb]) -> Quantiser {
        let mut rgba = Vec::with_capacity(samples.len() * 4);
        for &[r, g, b] in samples {
            rgba.extend_from_slice(&[r, g, b, 255]);
        }
        if rgba.is_empty() {
            rgba.extend_from_slice(&[0, 0, 0, 255]);
        }
        let factor = if samples.len() < FULL_SAMPLE_BELOW {
            1
        } else {
            SAMPLE_FACTOR
        };
        let network = color_quant::NeuQuant::new(factor, QUANTISED_COLOURS, &rgba);
        let colours = network.color_map_rgb();
        let mut palette = [0u16; 256];
        let mut shown = [[0u8; 3]; 256];
        for (entry, rgb) in colours.chunks_exact(3).enumerate() {
            let index = entry + 1;
            palette[index] = bgr555(rgb[0], rgb[1], rgb[2]);
            let c = palette[index];
            shown[index] = [expand(c), expand(c >> 5), expand(c >> 10)];
        }
        palette[usize::from(TRANSPARENT)] = 0;
        Quantiser {
            palette,
            shown,
            cache: HashMap::new(),
        }
    }

    /// A quantiser onto a palette given whole (a Doom WAD's): entry 0 stays transparent, every
    /// other entry is a colour texels may take.
    pub fn fixed(palette: Palette) -> Quantiser {
        let mut shown = [[0u8; 3]; 256];
        for (index, &c) in palette.iter().enumerate().skip(1) {
            shown[index] = [expand(c), expand(c >> 5), expand(c >> 10)];
        }
        Quantiser {
            palette,
            shown,
            cache: HashMap::new(),
        }
    }

    /// What the GBA shows for entry `index`, 8 bits a channel.
    pub fn shown(&self, index: u8) -> Rgb {
        self.shown[usize::from(index)]
    }

    /// The palette in the GBA's format.
    pub fn palette(&self) -> Palette {
        self.palette
    }

    /// The opaque palette index whose shown colour is nearest to `rgb` (squared RGB distance;
    /// ties go to the lower index). Never [`TRANSPARENT`].
    pub fn nearest(&mut self, rgb: Rgb) -> u8 {
        if let Some(&index) = self.cache.get(&rgb) {
            return index;
        }
        let distance = |c: &Rgb| -> i32 {
            (0..3)
                .map(|k| (i32::from(c[k]) - i32::from(rgb[k])).pow(2))
                .sum()
        };
        let mut best = 1usize;
        for index in 2..256 {
            if distance(&self.shown[index]) < distance(&self.shown[best]) {
                best = index;
            }
        }
        let best = best as u8;
        self.cache.insert(rgb, best);
        best
    }

    /// The light colormap: row `r` scales each entry's shown colour by `r / 16`, clamped, and
    /// maps it back to the palette. Row `LIGHT_NEUTRAL >> 3` is exactly the identity.
    pub fn colormap(&mut self) -> Box<Colormap> {
        let neutral = usize::from(LIGHT_NEUTRAL >> 3);
        colormap_of(|row, index| {
            if row == neutral {
                index as u8
            } else {
                let scale =
                    |c: u8| ((u32::from(c) * row as u32 + 8) / neutral as u32).min(255) as u8;
                let [r, g, b] = self.shown[index];
                self.nearest([scale(r), scale(g), scale(b)])
            }
        })
    }

    /// The 50 % blend table: `blend[behind][front]` is the opaque index nearest (as
    /// [`Quantiser::nearest`]) to the average of the two entries' shown colours, each channel
    /// rounded half up, entry 0 counting as black (what the GBA shows for it). Symmetric;
    /// `blend[0][0]` is 0 and `blend[a][a]` is `a` (the average of a colour with itself is
    /// itself, and `a` is at distance 0 even where another entry shows the same colour).
    pub fn blend(&mut self) -> Box<BlendTable> {
        let mut table = Box::new([[0u8; 256]; 256]);
        for behind in 0..256 {
            table[behind][behind] = behind as u8;
            for front in behind + 1..256 {
                let (a, b) = (self.shown[behind], self.shown[front]);
                let average =
                    [0, 1, 2].map(|k| (u16::from(a[k]) + u16::from(b[k])).div_ceil(2) as u8);
                let index = self.nearest(average);
                table[behind][front] = index;
                table[front][behind] = index;
            }
        }
        table
    }
}
