//! Floor and ceiling spans over square flats: the twin of `asm/flat.s`.

/// Flat sides the span kernels take, as log2 (8 to 64 texels).
pub const FLAT_LOG2_SIDES: core::ops::RangeInclusive<u32> = 3..=6;

/// A texture position packed the way the span kernels step it: u's integer part in the top
/// `k` bits with its fraction below, v's integer part in bits `16-k..16` with its fraction below.
/// One wrapping add steps both; a carry out of v's field moves u by one unit of its 16-k-bit
/// fraction, at most 2^-10 texel per wrap of v (the error bound the tests check).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PackedUv(pub u32);

impl PackedUv {
    /// Packs 16.16 coordinates (in texels; they wrap modulo the side) for a `2^log2_side` flat,
    /// rounding each to the packed fraction (16 - k bits): a packed step is off by at most half a
    /// unit of that fraction, so a span of n pixels drifts at most n/2 units plus one unit per
    /// carry between the fields. The packing is the same for positions and for steps, and v keeps
    /// its sign, so a negative step's borrow into u happens once per wrap, not every pixel.
    pub fn pack(u_16_16: i32, v_16_16: i32, log2_side: u32) -> PackedUv {
        debug_assert!(FLAT_LOG2_SIDES.contains(&log2_side));
        let k = log2_side;
        let half_unit = 1i32 << (k - 1);
        let u_field = (u_16_16.wrapping_add(half_unit) >> k) as u32;
        let v_field = v_16_16.wrapping_add(half_unit) >> k;
        PackedUv((u_field << 16).wrapping_add(v_field as u32))
    }

    /// The u and v fields of this position, each in units of 2^-(16-k) texel, modulo the side.
    pub fn unpack(self) -> (u32, u32) {
        (self.0 >> 16, self.0 & 0xffff)
    }

    /// The texel index `v * 2^k + u` the kernel reads at this position.
    #[inline]
    pub fn texel_index(self, log2_side: u32) -> usize {
        let k = log2_side;
        let row_mask = ((1u32 << k) - 1) << k;
        (((self.0 >> (16 - 2 * k)) & row_mask) | (self.0 >> (32 - k))) as usize
    }
}

/// One span's texture stepping over a `2^log2_side`-square row-major flat.
#[derive(Clone, Copy, Debug)]
pub struct FlatTexture<'a> {
    /// The flat, row-major, `4^log2_side` texels.
    pub texels: &'a [u8],
    /// log2 of the side, in [`FLAT_LOG2_SIDES`].
    pub log2_side: u32,
    /// Position of the first pixel.
    pub pos: PackedUv,
    /// Step per logical pixel.
    pub step: PackedUv,
    /// Light row the texel goes through, or `None` for unlit.
    pub colormap: Option<&'a [u8; 256]>,
}

impl FlatTexture<'_> {
    /// The palette indices the kernel writes, left to right, for `count` logical pixels.
    pub fn indices(&self, count: usize) -> impl Iterator<Item = u8> + '_ {
        debug_assert_eq!(self.texels.len(), 1 << (2 * self.log2_side));
        let mut pos = self.pos.0;
        (0..count).map(move |_| {
            let texel = self.texels[PackedUv(pos).texel_index(self.log2_side)];
            pos = pos.wrapping_add(self.step.0);
            match self.colormap {
                Some(colormap) => colormap[usize::from(texel)],
                None => texel,
            }
        })
    }

    /// The palette indices of `count` pixels from logical column `x`, left to right:
    /// [`FlatTexture::indices`], or with `halved` (half-width floors at 240 wide,
    /// [`crate::render::view::Floors::Half`]) each pixel shows the texel of its VRAM halfword's
    /// even pixel, one step back for an odd column, so a halfword holds one texel twice. The
    /// host canvases draw through this; the GBA's kernels step the even pixels by a doubled
    /// step, which wraps to the same positions.
    pub fn indices_from(
        &self,
        x: usize,
        count: usize,
        halved: bool,
    ) -> impl Iterator<Item = u8> + '_ {
        (x..x + count).scan(self.pos.0, move |pos, column| {
            let back = if halved && column % 2 == 1 {
                self.step.0
            } else {
                0
            };
            let at = pos.wrapping_sub(back);
            *pos = pos.wrapping_add(self.step.0);
            Some(self.index_at(PackedUv(at)))
        })
    }

    fn index_at(&self, pos: PackedUv) -> u8 {
        let texel = self.texels[pos.texel_index(self.log2_side)];
        match self.colormap {
            Some(colormap) => colormap[usize::from(texel)],
            None => texel,
        }
    }

    /// The same span started `skip` pixels further right: what the GBA wrapper uses when it
    /// draws an odd leading pixel itself and hands the rest to the pair kernel.
    pub fn advanced(&self, skip: u32) -> Self {
        FlatTexture {
            pos: PackedUv(self.pos.0.wrapping_add(self.step.0.wrapping_mul(skip))),
            ..*self
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packing_addresses_every_texel_of_a_64_flat() {
        for v in 0..64 {
            for u in 0..64 {
                let packed = PackedUv::pack(u << 16, v << 16, 6);
                assert_eq!(packed.texel_index(6), (v * 64 + u) as usize);
            }
        }
    }

    #[test]
    fn stepping_stays_within_the_documented_drift() {
        // 240 pixels stepping both ways, with a negative v step: the decoded packed position
        // must stay within n/2 + carries + 1 units (2^-10 texel for a 64 flat) of the exact one.
        let side = 6;
        let unit_bits = 16 - side;
        let period = 1i64 << 16; // the side (64 texels) in packed units
        for &(u0, v0, du, dv) in &[
            (5 << 16 | 0x1234, 60 << 16 | 0x8000, 0x1_2345, -0x0_9876),
            (0, 0, -0x2_8000, 0x3_0001),
            (63 << 16, 1 << 16, 0x0_0101, -0x0_0001),
        ] {
            let mut pos = PackedUv::pack(u0, v0, side);
            let step = PackedUv::pack(du, dv, side);
            let mut carries = 0i64;
            let mut previous_v = pos.unpack().1;
            for i in 0..240i64 {
                let (u, v) = pos.unpack();
                let exact_u = (u0 as i64 + du as i64 * i) >> side;
                let exact_v = (v0 as i64 + dv as i64 * i) >> side;
                let distance = |a: i64, b: i64| {
                    let d = (a - b).rem_euclid(period);
                    d.min(period - d)
                };
                let bound = i / 2 + carries + 2;
                assert!(
                    distance(u as i64, exact_u) <= bound,
                    "u at pixel {i} ({unit_bits}-bit units)"
                );
                assert!(distance(v as i64, exact_v) <= i / 2 + 2, "v at pixel {i}");
                pos = PackedUv(pos.0.wrapping_add(step.0));
                let v_now = pos.unpack().1;
                if (v_now as i64 - previous_v as i64).abs() > (period / 2) {
                    carries += 1;
                }
                previous_v = v_now;
            }
        }
    }
}
