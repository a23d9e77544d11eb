//! Wall and sky columns: the twin of `asm/column.s`.

/// Smallest and largest texture heights the column kernels take, as log2.
pub const COLUMN_LOG2_HEIGHTS: core::ops::RangeInclusive<u32> = 3..=8;

/// One column's texture stepping. `v` and `dv` are fractions of the texture height in 0.32, so
/// the texel row is `v >> (32 - log2_height)` and wrapping past the bottom costs nothing.
#[derive(Clone, Copy, Debug)]
pub struct ColumnTexture<'a> {
    /// The texture column, top to bottom; its length is `1 << log2_height`.
    pub texels: &'a [u8],
    /// log2 of the column's height, in [`COLUMN_LOG2_HEIGHTS`].
    pub log2_height: u32,
    /// Position of the first drawn row, 0.32 of the height.
    pub v: u32,
    /// Step per screen row, 0.32 of the height.
    pub dv: u32,
    /// Light row (256 entries) the texel goes through, or `None` for unlit.
    pub colormap: Option<&'a [u8; 256]>,
}

impl ColumnTexture<'_> {
    /// The palette indices the kernel writes, top to bottom, for `count` rows.
    pub fn indices(&self, count: usize) -> impl Iterator<Item = u8> + '_ {
        debug_assert!(COLUMN_LOG2_HEIGHTS.contains(&self.log2_height));
        debug_assert_eq!(self.texels.len(), 1 << self.log2_height);
        let shift = 32 - self.log2_height;
        let mut v = self.v;
        (0..count).map(move |_| {
            let texel = self.texels[(v >> shift) as usize];
            // The kernel's ADD wraps: that is how v repeats the texture.
            v = v.wrapping_add(self.dv);
            match self.colormap {
                Some(colormap) => colormap[usize::from(texel)],
                None => texel,
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_wrap_through_the_column() {
        let texels: [u8; 8] = [10, 11, 12, 13, 14, 15, 16, 17];
        let column = ColumnTexture {
            texels: &texels,
            log2_height: 3,
            v: 6 << 29,
            dv: 1 << 29,
            colormap: None,
        };
        let drawn: Vec<u8> = column.indices(4).collect();
        assert_eq!(drawn, [16, 17, 10, 11]);
    }

    #[test]
    fn lit_columns_go_through_the_colormap() {
        let texels = [3u8; 8];
        let mut colormap = [0u8; 256];
        colormap[3] = 200;
        let column = ColumnTexture {
            texels: &texels,
            log2_height: 3,
            v: 0,
            dv: 1 << 28,
            colormap: Some(&colormap),
        };
        assert!(column.indices(5).all(|index| index == 200));
    }
}
