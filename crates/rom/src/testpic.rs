//! The test picture: a 64×64 texture spread over rows with a per-row stretch, drawn by the span
//! kernel. It exercises the asm seam, both halfword packings, wrap-around in both directions and
//! all three resolutions; the emulator test compares the ROM's frame with the host twin's.

use portalcast::frame::{Resolution, PAGE_ROW_HALFWORDS};
use portalcast::raster::span::{
    SpanPacking, SpanSteps, SpanTarget, SpanTexture, SPAN_TEXTURE_SIDE,
};

/// The test picture's 256-colour BGR555 palette: hue bands whose brightness ramps within each
/// band, so neighbouring indices are easy to tell apart on screen and in a diff.
pub const fn palette() -> [u16; 256] {
    let mut palette = [0u16; 256];
    let mut index = 0;
    while index < 256 {
        let band = index / 32;
        let level = (index % 32) as u16;
        let (r, g, b) = match band {
            0 => (level, level, level),
            1 => (level, 0, 0),
            2 => (0, level, 0),
            3 => (0, 0, level),
            4 => (level, level, 0),
            5 => (0, level, level),
            6 => (level, 0, level),
            _ => (31, level, level / 2),
        };
        palette[index] = r | (g << 5) | (b << 10);
        index += 1;
    }
    palette
}

/// The test texture: a checkerboard of 8×8 cells in two hue bands, a bright border and a diagonal,
/// so both axes and their wrap points are visible.
pub const fn texture() -> SpanTexture {
    let mut texels = [0u8; SPAN_TEXTURE_SIDE * SPAN_TEXTURE_SIDE];
    let mut v = 0;
    while v < SPAN_TEXTURE_SIDE {
        let mut u = 0;
        while u < SPAN_TEXTURE_SIDE {
            let cell = ((u / 8) + (v / 8)) % 2;
            let shade = ((u + v) / 4) as u8; // 0..=31 within a band
            let texel = if u == 0 || v == 0 {
                255
            } else if u == v {
                31
            } else if cell == 0 {
                32 + shade
            } else {
                96 + shade
            };
            texels[v * SPAN_TEXTURE_SIDE + u] = texel;
            u += 1;
        }
        v += 1;
    }
    texels
}

/// Span steps for logical row `row` of the picture at `resolution`, scrolled by `phase` texels.
///
/// Rows are stretched more towards the bottom, like a floor seen in perspective, and sheared so
/// v changes along each row; both steps are exact in 16.16.
pub fn row_steps(row: usize, resolution: Resolution, phase: u32) -> SpanSteps {
    // Normalise to 160 rows and 240 columns so every resolution shows the same picture.
    let row_160 = (row * 160 / resolution.height()) as u32;
    let width_scale = (240 / resolution.width()) as u32;
    let du = (0x3000 + row_160 * 0x200) * width_scale;
    let dv = (row_160 * 0x40) * width_scale;
    let centre_offset = du.wrapping_mul(resolution.width() as u32 / 2);
    SpanSteps {
        u: (phase << 16).wrapping_sub(centre_offset),
        v: row_160 << 15,
        du,
        dv,
    }
}

/// Draws the whole test picture at `resolution` into `target`.
pub fn draw(target: &mut impl SpanTarget, resolution: Resolution, phase: u32) {
    let packing = match resolution.pixels_per_halfword() {
        1 => SpanPacking::Doubled,
        _ => SpanPacking::Pairs,
    };
    for row in 0..resolution.height() {
        let steps = row_steps(row, resolution, phase);
        target.draw_span(row, 0, PAGE_ROW_HALFWORDS, &TEXTURE, steps, packing);
    }
}

/// The test texture, evaluated at compile time so the ROM keeps it in ROM.
pub static TEXTURE: SpanTexture = texture();
/// The test palette, evaluated at compile time.
pub static PALETTE: [u16; 256] = palette();
