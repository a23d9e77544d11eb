//! Loading PNGs and checking them against what each use requires.

use std::path::Path;

use image::RgbaImage;

use crate::diag::{Loc, Located};

/// Smallest and largest texture side, in texels.
pub(crate) const TEXTURE_SIDE_MIN: u32 = 8;
pub(crate) const TEXTURE_SIDE_MAX: u32 = portalcast_format::limits::TEXTURE_SIZE_MAX as u32;
/// The sky's width covers one full turn and must be a power of two in this range.
const SKY_WIDTH_MIN: u32 = 64;
pub(crate) const SKY_WIDTH_MAX: u32 = 1024;
pub(crate) const SKY_HEIGHT_MIN: u32 = 16;
pub(crate) const SKY_HEIGHT_MAX: u32 = 256;
/// Largest sprite side, in texels.
const SPRITE_SIDE_MAX: u32 = 256;
/// Sprite pixels with alpha below this are transparent (palette index 0).
pub(crate) const SPRITE_ALPHA_OPAQUE: u8 = 128;

/// Reads and decodes a PNG.
pub(crate) fn load(path: &Path) -> Result<RgbaImage, Located> {
    let bytes = std::fs::read(path).map_err(|e| {
        (
            Loc::START,
            format!("cannot read the file ({e}); check it exists and is readable"),
        )
    })?;
    let image =
        image::load_from_memory_with_format(&bytes, image::ImageFormat::Png).map_err(|e| {
            (
                Loc::START,
                format!("cannot decode the PNG ({e}); save the image again as a PNG"),
            )
        })?;
    Ok(image.to_rgba8())
}

fn power_of_two_in(value: u32, min: u32, max: u32) -> bool {
    value.is_power_of_two() && (min..=max).contains(&value)
}

/// A wall or flat texture: power-of-two sides in 8..=256, and fully opaque (palette index 0 is
/// reserved for transparency).
pub(crate) fn check_texture(image: &RgbaImage) -> Vec<Located> {
    let mut errors = Vec::new();
    for (what, value) in [("width", image.width()), ("height", image.height())] {
        if !power_of_two_in(value, TEXTURE_SIDE_MIN, TEXTURE_SIDE_MAX) {
            errors.push((
                Loc::START,
                format!(
                    "{what} {value} is not a power of two between {TEXTURE_SIDE_MIN} and {TEXTURE_SIDE_MAX}; resize it"
                ),
            ));
        }
    }
    errors.extend(first_transparent(image, "textures"));
    errors
}

/// The sky panorama: power-of-two width in 64..=1024 (one full turn), power-of-two height in
/// 16..=256 (the column kernel wraps by masking), opaque.
pub(crate) fn check_sky(image: &RgbaImage) -> Vec<Located> {
    let mut errors = Vec::new();
    if !power_of_two_in(image.width(), SKY_WIDTH_MIN, SKY_WIDTH_MAX) {
        errors.push((
            Loc::START,
            format!(
                "width {} is not a power of two between {SKY_WIDTH_MIN} and {SKY_WIDTH_MAX}; resize the panorama (its width covers one full turn)",
                image.width()
            ),
        ));
    }
    if !power_of_two_in(image.height(), SKY_HEIGHT_MIN, SKY_HEIGHT_MAX) {
        errors.push((
            Loc::START,
            format!(
                "height {} is not a power of two between {SKY_HEIGHT_MIN} and {SKY_HEIGHT_MAX}; resize the panorama",
                image.height()
            ),
        ));
    }
    errors.extend(first_transparent(image, "the sky"));
    errors
}

/// A sprite image: sides 1..=256; alpha below 128 means transparent, and some pixel must be
/// opaque.
pub(crate) fn check_sprite(image: &RgbaImage) -> Vec<Located> {
    let mut errors = check_sprite_sides(image.width(), image.height(), "resize the sprite");
    if !has_opaque_pixel(image) {
        errors.push((
            Loc::START,
            format!(
                "every pixel is transparent (alpha below {SPRITE_ALPHA_OPAQUE}), so the thing would not show; paint the sprite with opaque pixels (alpha {SPRITE_ALPHA_OPAQUE} or more)"
            ),
        ));
    }
    errors
}

/// The sides of a sprite image, `width` × `height`: each 1..=256 (`fix` says what to do).
pub(crate) fn check_sprite_sides(width: u32, height: u32, fix: &str) -> Vec<Located> {
    [("width", width), ("height", height)]
        .into_iter()
        .filter(|(_, value)| !(1..=SPRITE_SIDE_MAX).contains(value))
        .map(|(what, value)| {
            (
                Loc::START,
                format!("{what} {value} is outside 1..={SPRITE_SIDE_MAX}; {fix}"),
            )
        })
        .collect()
}

/// Whether some pixel of a sprite image is opaque (alpha 128 or more).
pub(crate) fn has_opaque_pixel(image: &RgbaImage) -> bool {
    image.pixels().any(|p| p.0[3] >= SPRITE_ALPHA_OPAQUE)
}

fn first_transparent(image: &RgbaImage, what: &str) -> Option<Located> {
    let count = image.pixels().filter(|p| p.0[3] != 255).count();
    let (x, y, pixel) = image.enumerate_pixels().find(|(_, _, p)| p.0[3] != 255)?;
    Some((
        Loc::new(y + 1, x + 1),
        format!(
            "pixel is not opaque (alpha {}, {count} such pixel{} in all); {what} must be fully opaque because palette index 0 is reserved for transparency: remove the alpha channel",
            pixel.0[3],
            if count == 1 { "" } else { "s" }
        ),
    ))
}
