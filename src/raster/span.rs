//! Affine spans over a 64×64 row-major texture: the twins of `asm/span.s`.

/// Side of the square texture the span kernels sample, in texels.
pub const SPAN_TEXTURE_SIDE: usize = 64;

/// A 64×64 texture in row-major order: texel `(u, v)` is at `v * 64 + u`.
pub type SpanTexture = [u8; SPAN_TEXTURE_SIDE * SPAN_TEXTURE_SIDE];

/// Where a span starts in the texture and how it steps, in 16.16 texels. Coordinates wrap modulo
/// the texture side, as the kernels' masks make them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SpanSteps {
    /// Texture column of the first texel, 16.16.
    pub u: u32,
    /// Texture row of the first texel, 16.16.
    pub v: u32,
    /// Column step per texel, 16.16 (two's complement: a negative step wraps).
    pub du: u32,
    /// Row step per texel, 16.16.
    pub dv: u32,
}

/// How texels become Mode 4 halfwords.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpanPacking {
    /// One texel per halfword, in both bytes: a logical pixel two screen pixels wide.
    Doubled,
    /// Two consecutive texels per halfword, left one in the low byte: native 240-wide rows.
    Pairs,
}

#[inline]
fn texel(texture: &SpanTexture, u: u32, v: u32) -> u8 {
    let column = (u >> 16) as usize & (SPAN_TEXTURE_SIDE - 1);
    let row = (v >> 16) as usize & (SPAN_TEXTURE_SIDE - 1);
    texture[row * SPAN_TEXTURE_SIDE + column]
}

/// Fills `dst` with one span, exactly as `pc_span64_doubled` / `pc_span64_pairs` do.
pub fn draw_span(dst: &mut [u16], texture: &SpanTexture, steps: SpanSteps, packing: SpanPacking) {
    let SpanSteps {
        mut u,
        mut v,
        du,
        dv,
    } = steps;
    for out in dst.iter_mut() {
        let left = texel(texture, u, v);
        // Texture coordinates wrap by design: the kernel's adds are modulo 2^32.
        u = u.wrapping_add(du);
        v = v.wrapping_add(dv);
        let right = match packing {
            SpanPacking::Doubled => left,
            SpanPacking::Pairs => {
                let texel_right = texel(texture, u, v);
                u = u.wrapping_add(du);
                v = v.wrapping_add(dv);
                texel_right
            }
        };
        *out = u16::from(left) | (u16::from(right) << 8);
    }
}

/// Receives spans: the VRAM back page through the asm kernels on the GBA, a host page through the
/// twins in tests.
pub trait SpanTarget {
    /// Draws `halfwords` halfwords of page row `row`, starting at halfword `first_halfword`.
    fn draw_span(
        &mut self,
        row: usize,
        first_halfword: usize,
        halfwords: usize,
        texture: &SpanTexture,
        steps: SpanSteps,
        packing: SpanPacking,
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gradient_texture() -> SpanTexture {
        core::array::from_fn(|i| (i % 251) as u8)
    }

    #[test]
    fn doubled_repeats_each_texel_in_both_bytes() {
        let texture = gradient_texture();
        let mut row = [0u16; 4];
        let steps = SpanSteps {
            u: 0,
            v: 1 << 16,
            du: 1 << 16,
            dv: 0,
        };
        draw_span(&mut row, &texture, steps, SpanPacking::Doubled);
        assert_eq!(row, [0x4040, 0x4141, 0x4242, 0x4343]);
    }

    #[test]
    fn pairs_pack_left_texel_low() {
        let texture = gradient_texture();
        let mut row = [0u16; 2];
        let steps = SpanSteps {
            u: 0,
            v: 0,
            du: 1 << 16,
            dv: 0,
        };
        draw_span(&mut row, &texture, steps, SpanPacking::Pairs);
        assert_eq!(row, [0x0100, 0x0302]);
    }

    #[test]
    fn coordinates_wrap_at_the_texture_edge_in_both_directions() {
        let texture = gradient_texture();
        let mut row = [0u16; 2];
        // Start one texel left of u = 0 with a negative step: columns 63, 62.
        let steps = SpanSteps {
            u: 63 << 16,
            v: 0,
            du: (-(1i32 << 16)) as u32,
            dv: 0,
        };
        draw_span(&mut row, &texture, steps, SpanPacking::Doubled);
        assert_eq!(row, [0x3f3f, 0x3e3e]);
    }
}
