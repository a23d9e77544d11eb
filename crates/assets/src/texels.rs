//! Mip chains and texel layouts of textures, the sky and sprites.

use image::RgbaImage;

use crate::images::SPRITE_ALPHA_OPAQUE;
use crate::palette::{Quantiser, Rgb};

/// One mip level in RGB, row-major.
struct Level {
    width: usize,
    height: usize,
    texels: Vec<Rgb>,
}

fn rgb_of(image: &RgbaImage) -> Level {
    Level {
        width: image.width() as usize,
        height: image.height() as usize,
        texels: image.pixels().map(|p| [p.0[0], p.0[1], p.0[2]]).collect(),
    }
}

/// Level 0 and every smaller level down to 1×1, each a box filter (2×2, or 2×1 once one side
/// is 1) of the one above, averaged in RGB with rounding.
fn mip_chain(image: &RgbaImage) -> Vec<Level> {
    let mut levels = vec![rgb_of(image)];
    while let Some(above) = levels.last().filter(|l| l.width > 1 || l.height > 1) {
        let width = (above.width / 2).max(1);
        let height = (above.height / 2).max(1);
        let (step_x, step_y) = (above.width / width, above.height / height);
        let mut texels = Vec::with_capacity(width * height);
        for y in 0..height {
            for x in 0..width {
                let mut sum = [0u32; 3];
                for dy in 0..step_y {
                    for dx in 0..step_x {
                        let texel = above.texels[(y * step_y + dy) * above.width + x * step_x + dx];
                        for (total, channel) in sum.iter_mut().zip(texel) {
                            *total += u32::from(channel);
                        }
                    }
                }
                let count = (step_x * step_y) as u32;
                texels.push(sum.map(|total| ((total + count / 2) / count) as u8));
            }
        }
        levels.push(Level {
            width,
            height,
            texels,
        });
    }
    levels
}

/// Number of mip levels of a `width × height` power-of-two texture, down to 1×1.
pub(crate) fn mip_count(width: u32, height: u32) -> u8 {
    (width.max(height).trailing_zeros() + 1) as u8
}

/// The texture's mip chain mapped to the palette: (column-major chain, row-major chain), each
/// built only if asked for.
pub(crate) fn texture_chains(
    image: &RgbaImage,
    columns: bool,
    rows: bool,
    quantiser: &mut Quantiser,
) -> (Vec<u8>, Vec<u8>) {
    let levels = mip_chain(image);
    let mut column_chain = Vec::new();
    let mut row_chain = Vec::new();
    for level in &levels {
        if columns {
            for x in 0..level.width {
                for y in 0..level.height {
                    column_chain.push(quantiser.nearest(level.texels[y * level.width + x]));
                }
            }
        }
        if rows {
            row_chain.extend(level.texels.iter().map(|&t| quantiser.nearest(t)));
        }
    }
    (column_chain, row_chain)
}

/// The sky, column-major.
pub(crate) fn sky_columns(image: &RgbaImage, quantiser: &mut Quantiser) -> Vec<u8> {
    let mut texels = Vec::with_capacity((image.width() * image.height()) as usize);
    for x in 0..image.width() {
        for y in 0..image.height() {
            let p = image.get_pixel(x, y).0;
            texels.push(quantiser.nearest([p[0], p[1], p[2]]));
        }
    }
    texels
}

/// A sprite, column-major, with index 0 where alpha is below 128.
pub(crate) fn sprite_columns(image: &RgbaImage, quantiser: &mut Quantiser) -> Vec<u8> {
    let mut texels = Vec::with_capacity((image.width() * image.height()) as usize);
    for x in 0..image.width() {
        for y in 0..image.height() {
            let p = image.get_pixel(x, y).0;
            texels.push(if p[3] < SPRITE_ALPHA_OPAQUE {
                portalcast_format::TRANSPARENT
            } else {
                quantiser.nearest([p[0], p[1], p[2]])
            });
        }
    }
    texels
}

/// The opaque pixels of an image, as palette training samples.
pub(crate) fn opaque_samples(image: &RgbaImage, out: &mut Vec<Rgb>) {
    out.extend(
        image
            .pixels()
            .filter(|p| p.0[3] >= SPRITE_ALPHA_OPAQUE)
            .map(|p| [p.0[0], p.0[1], p.0[2]]),
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chain_runs_down_to_one_by_one_and_averages() {
        let mut image = RgbaImage::new(8, 2);
        for (x, _, p) in image.enumerate_pixels_mut() {
            *p = image::Rgba([if x % 2 == 0 { 0 } else { 200 }, 10, 20, 255]);
        }
        let levels = mip_chain(&image);
        let sizes: Vec<(usize, usize)> = levels.iter().map(|l| (l.width, l.height)).collect();
        assert_eq!(sizes, [(8, 2), (4, 1), (2, 1), (1, 1)]);
        assert_eq!(levels.len(), usize::from(mip_count(8, 2)));
        assert!(levels[1].texels.iter().all(|&t| t == [100, 10, 20]));
    }
}
