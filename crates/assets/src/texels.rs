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
    let columns: Vec<Vec<Option<u8>>> = (0..image.width())
        .map(|x| {
            (0..image.height())
                .map(|y| {
                    let p = image.get_pixel(x, y).0;
                    (p[3] >= SPRITE_ALPHA_OPAQUE).then(|| quantiser.nearest([p[0], p[1], p[2]]))
                })
                .collect()
        })
        .collect();
    sprite_posts(&columns)
}

/// Longest run one post holds (its length is a byte).
const POST_LENGTH_MAX: usize = 255;

/// Columns of texels (`None` transparent) in the post layout of [`portalcast_format::Sprite`].
pub(crate) fn sprite_posts(columns: &[Vec<Option<u8>>]) -> Vec<u8> {
    let mut posts = vec![0u8; 4 * columns.len()];
    for (u, column) in columns.iter().enumerate() {
        let offset = posts.len() as u32;
        posts[4 * u..4 * u + 4].copy_from_slice(&offset.to_le_bytes());
        let count_at = posts.len();
        posts.push(0);
        let mut v = 0;
        while v < column.len() {
            if column[v].is_none() {
                v += 1;
                continue;
            }
            let top = v;
            while v < column.len() && column[v].is_some() && v - top < POST_LENGTH_MAX {
                v += 1;
            }
            let texels: Vec<u8> = column[top..v].iter().flatten().copied().collect();
            posts.push(top as u8);
            posts.push(texels.len() as u8);
            posts.extend_from_slice(&texels);
            posts.push(*texels.last().expect("a post holds a texel"));
            posts[count_at] += 1;
        }
    }
    posts
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

    #[test]
    fn posts_hold_each_run_with_a_pad_texel() {
        // Column 0: empty; column 1: rows 1..3 and 5; column 2: opaque from top to bottom.
        let columns = vec![
            vec![None; 6],
            vec![None, Some(7), Some(8), None, None, Some(9)],
            (1..=6).map(Some).collect(),
        ];
        let posts = sprite_posts(&columns);
        let offsets: Vec<u32> = posts[..12]
            .chunks(4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        assert_eq!(offsets, [12, 13, 23]);
        assert_eq!(posts[12], 0, "no posts in an empty column");
        // Two posts: (top 1, 2 texels, pad), (top 5, 1 texel, pad).
        assert_eq!(&posts[13..23], &[2, 1, 2, 7, 8, 8, 5, 1, 9, 9]);
        assert_eq!(&posts[23..], &[1, 0, 6, 1, 2, 3, 4, 5, 6, 6]);
    }

    #[test]
    fn a_run_longer_than_255_is_two_posts() {
        let column: Vec<Option<u8>> = (0..256).map(|v| Some((v % 250 + 1) as u8)).collect();
        let posts = sprite_posts(&[column]);
        assert_eq!(
            u32::from_le_bytes([posts[0], posts[1], posts[2], posts[3]]),
            4
        );
        assert_eq!(posts[4], 2);
        let first = &posts[5..];
        assert_eq!((first[0], first[1]), (0, 255));
        // 255 texels, then the pad: a copy of the last (row 254).
        assert_eq!(first[2 + 254], (254 % 250 + 1) as u8);
        assert_eq!(first[2 + 255], first[2 + 254]);
        let second = &first[2 + 256..];
        assert_eq!(
            second,
            &[255, 1, (255 % 250 + 1) as u8, (255 % 250 + 1) as u8]
        );
    }

    #[test]
    fn the_format_reads_back_every_texel() {
        // A 5×40 pattern with runs of every length, gaps, and fully empty and full columns.
        let (width, height) = (5usize, 40usize);
        let texel = |u: usize, v: usize| -> Option<u8> {
            match u {
                0 => None,
                1 => Some((v + 1) as u8),
                _ => ((v * (u + 1)) % 7 < 4).then_some((u * 50 + v) as u8 | 1),
            }
        };
        let columns: Vec<Vec<Option<u8>>> = (0..width)
            .map(|u| (0..height).map(|v| texel(u, v)).collect())
            .collect();
        let posts = sprite_posts(&columns);
        let sprite = portalcast_format::Sprite {
            name: "pattern",
            width: width as u16,
            height: height as u16,
            posts: &posts,
        };
        for u in 0..width {
            for v in 0..height {
                let expected = texel(u, v).unwrap_or(portalcast_format::TRANSPARENT);
                assert_eq!(sprite.texel(u, v), expected, "({u}, {v})");
            }
            let mut below = 0;
            for post in sprite.column_posts(u) {
                assert!(usize::from(post.top) >= below, "posts run top to bottom");
                assert!(!post.is_empty());
                let pad = post.texels_and_pad[post.len()];
                assert_eq!(
                    pad,
                    post.texels_and_pad[post.len() - 1],
                    "pad copies the last"
                );
                below = usize::from(post.top) + post.len() + 1;
            }
        }
        assert_eq!(sprite.column_posts(0).count(), 0);
        assert_eq!(sprite.column_posts(1).count(), 1);
    }
}
