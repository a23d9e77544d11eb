//! A WAD's pictures in Doom's own palette: the palette (`PLAYPAL`) and light tables
//! (`COLORMAP`), flats (64×64 raw indices between the flat markers), patches (Doom's picture
//! format: columns of posts) and wall textures composed from patches (`PNAMES`, `TEXTURE1`,
//! `TEXTURE2`), as Doom's `r_data.c` builds them. Mapping them onto portalcast's palette, light
//! rows and texture sizes is the importer's next step.

use super::wad::{name8, Wad};
use super::DoomError;

/// A picture of palette indices, row-major, `None` where nothing is drawn (a patch's gaps, a
/// texture's pixels no patch covers).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IndexedImage {
    /// Columns.
    pub width: u16,
    /// Rows.
    pub height: u16,
    /// `width × height` texels, row by row.
    pub texels: Vec<Option<u8>>,
}

impl IndexedImage {
    fn blank(width: u16, height: u16) -> IndexedImage {
        IndexedImage {
            width,
            height,
            texels: vec![None; usize::from(width) * usize::from(height)],
        }
    }

    /// The texel at column `x`, row `y`.
    pub fn at(&self, x: u16, y: u16) -> Option<u8> {
        self.texels[usize::from(y) * usize::from(self.width) + usize::from(x)]
    }

    /// How many texels nothing is drawn at.
    pub fn gaps(&self) -> usize {
        self.texels.iter().filter(|texel| texel.is_none()).count()
    }
}

/// A patch: a picture with its offset (where its origin is, for sprites).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Patch {
    /// The picture.
    pub image: IndexedImage,
    /// Columns left of the origin.
    pub left: i16,
    /// Rows above the origin.
    pub top: i16,
}

/// One patch of a texture, at its place.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TexturePatch {
    /// Its column in the texture (may be negative: it is cut).
    pub x: i16,
    /// Its row in the texture.
    pub y: i16,
    /// Its lump name (through `PNAMES`).
    pub patch: String,
}

/// A wall texture's definition: its size and its patches, in drawing order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TextureDef {
    /// Its name.
    pub name: String,
    /// Columns.
    pub width: u16,
    /// Rows.
    pub height: u16,
    /// What it is drawn from, later patches over earlier ones.
    pub patches: Vec<TexturePatch>,
}

fn half(bytes: &[u8], at: usize) -> Option<i16> {
    Some(i16::from_le_bytes([*bytes.get(at)?, *bytes.get(at + 1)?]))
}

fn word(bytes: &[u8], at: usize) -> Option<i32> {
    Some(i32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?))
}

fn required<'w>(wad: &'w Wad, name: &str) -> Result<&'w [u8], DoomError> {
    wad.lump(name).ok_or_else(|| {
        DoomError::new(
            wad.path(),
            Some(name),
            "is missing: name an IWAD (Doom's or Freedoom's) for the graphics".to_string(),
        )
    })
}

/// The first of `PLAYPAL`'s palettes (the one Doom draws with), as RGB.
pub fn palette(wad: &Wad) -> Result<[[u8; 3]; 256], DoomError> {
    let bytes = required(wad, "PLAYPAL")?;
    if bytes.len() < 768 {
        return Err(DoomError::new(
            wad.path(),
            Some("PLAYPAL"),
            format!(
                "{} bytes is not a palette (768): the WAD is damaged",
                bytes.len()
            ),
        ));
    }
    let mut palette = [[0u8; 3]; 256];
    for (colour, rgb) in palette.iter_mut().zip(bytes.chunks_exact(3)) {
        colour.copy_from_slice(rgb);
    }
    Ok(palette)
}

/// `COLORMAP`'s tables: row 0 full light, then darker, as Doom's (32 light rows, then the
/// invulnerability and the all-black ones).
pub fn colormaps(wad: &Wad) -> Result<Vec<[u8; 256]>, DoomError> {
    let bytes = required(wad, "COLORMAP")?;
    if bytes.len() < 32 * 256 {
        return Err(DoomError::new(
            wad.path(),
            Some("COLORMAP"),
            format!(
                "{} bytes is fewer than 32 light rows of 256: the WAD is damaged",
                bytes.len()
            ),
        ));
    }
    Ok(bytes
        .chunks_exact(256)
        .map(|row| row.try_into().expect("256 bytes"))
        .collect())
}

/// Flat `name` (64×64 indices between `F_START` and `F_END`, or a PWAD's `FF_START`/`FF_END`).
pub fn flat(wad: &Wad, name: &str) -> Result<IndexedImage, DoomError> {
    let bytes = wad
        .lump_in(name, &["F_START", "FF_START"], &["F_END", "FF_END"])
        .ok_or_else(|| {
            DoomError::new(
                wad.path(),
                Some(name),
                "is not a flat of this WAD (none between F_START and F_END): check the name, or name the IWAD that has it".to_string(),
            )
        })?;
    if bytes.len() < 64 * 64 {
        return Err(DoomError::new(
            wad.path(),
            Some(name),
            format!("{} bytes is not a 64×64 flat", bytes.len()),
        ));
    }
    Ok(IndexedImage {
        width: 64,
        height: 64,
        texels: bytes[..64 * 64].iter().map(|&index| Some(index)).collect(),
    })
}

/// Decodes a picture-format lump: a header (width, height, offsets), a word per column to its
/// posts, each post a top row, a length, a pad byte, its texels and a pad byte, and `0xFF` after
/// a column's last. A post whose top is not below the last one's continues from it (the "tall
/// patch" rule DeePsea introduced, which Doom's ports follow for pictures over 254 rows).
pub fn patch(bytes: &[u8]) -> Option<Patch> {
    let (width, height) = (half(bytes, 0)?, half(bytes, 2)?);
    let (width, height) = (u16::try_from(width).ok()?, u16::try_from(height).ok()?);
    let mut image = IndexedImage::blank(width, height);
    for x in 0..width {
        let mut at = usize::try_from(word(bytes, 8 + 4 * usize::from(x))?).ok()?;
        let mut last_top: i32 = -1;
        loop {
            let top = *bytes.get(at)?;
            if top == 0xFF {
                break;
            }
            let top = if i32::from(top) <= last_top {
                last_top + i32::from(top)
            } else {
                i32::from(top)
            };
            last_top = top;
            let length = usize::from(*bytes.get(at + 1)?);
            let texels = bytes.get(at + 3..at + 3 + length)?;
            for (offset, &texel) in texels.iter().enumerate() {
                let y = top + offset as i32;
                if (0..i32::from(height)).contains(&y) {
                    image.texels[y as usize * usize::from(width) + usize::from(x)] = Some(texel);
                }
            }
            at += length + 4;
        }
    }
    Some(Patch {
        image,
        left: half(bytes, 4)?,
        top: half(bytes, 6)?,
    })
}

/// The wall textures of a WAD, by name: `TEXTURE1` then `TEXTURE2` (a later definition of a name
/// replaces an earlier one), their patches named through `PNAMES`.
pub struct Textures {
    defs: Vec<TextureDef>,
}

impl Textures {
    /// Reads the texture definitions of `wad`.
    pub fn read(wad: &Wad) -> Result<Textures, DoomError> {
        let damaged = |lump: &str, what: &str| {
            DoomError::new(
                wad.path(),
                Some(lump),
                format!("{what}: the WAD is damaged"),
            )
        };
        let pnames = required(wad, "PNAMES")?;
        let count = usize::try_from(word(pnames, 0).unwrap_or(-1))
            .ok()
            .filter(|&count| pnames.len() >= 4 + 8 * count)
            .ok_or_else(|| damaged("PNAMES", "its count runs past its end"))?;
        let names: Vec<String> = (0..count)
            .map(|index| name8(&pnames[4 + 8 * index..12 + 8 * index]))
            .collect();
        let mut defs: Vec<TextureDef> = Vec::new();
        for lump in ["TEXTURE1", "TEXTURE2"] {
            let Some(bytes) = wad.lump(lump) else {
                continue;
            };
            let count = usize::try_from(word(bytes, 0).unwrap_or(-1))
                .map_err(|_| damaged(lump, "no texture count"))?;
            for index in 0..count {
                let def = (|| {
                    let at = usize::try_from(word(bytes, 4 + 4 * index)?).ok()?;
                    let name = name8(bytes.get(at..at + 8)?);
                    let width = u16::try_from(half(bytes, at + 12)?).ok()?;
                    let height = u16::try_from(half(bytes, at + 14)?).ok()?;
                    let patch_count = usize::try_from(half(bytes, at + 20)?).ok()?;
                    let patches = (0..patch_count)
                        .map(|p| {
                            let place = at + 22 + 10 * p;
                            let patch = usize::try_from(half(bytes, place + 4)?).ok()?;
                            Some(TexturePatch {
                                x: half(bytes, place)?,
                                y: half(bytes, place + 2)?,
                                patch: names.get(patch)?.clone(),
                            })
                        })
                        .collect::<Option<Vec<_>>>()?;
                    Some(TextureDef {
                        name,
                        width,
                        height,
                        patches,
                    })
                })()
                .ok_or_else(|| {
                    damaged(
                        lump,
                        &format!("texture {index} runs past its end or names a patch PNAMES lacks"),
                    )
                })?;
                defs.retain(|known| known.name != def.name);
                defs.push(def);
            }
        }
        Ok(Textures { defs })
    }

    /// Texture `name`'s definition, if the WAD defines it.
    pub fn def(&self, name: &str) -> Option<&TextureDef> {
        self.defs.iter().find(|def| def.name == name)
    }

    /// How many textures are defined.
    pub fn len(&self) -> usize {
        self.defs.len()
    }

    /// Whether none is.
    pub fn is_empty(&self) -> bool {
        self.defs.is_empty()
    }

    /// Texture `name` drawn from its patches (each patch lump found by name in `wad`, the last
    /// of that name, as Doom does).
    pub fn compose(&self, wad: &Wad, name: &str) -> Result<IndexedImage, DoomError> {
        let def = self.def(name).ok_or_else(|| {
            DoomError::new(
                wad.path(),
                Some(name),
                "is not a texture of this WAD (not in TEXTURE1 or TEXTURE2): check the name, or name the IWAD that has it".to_string(),
            )
        })?;
        let mut image = IndexedImage::blank(def.width, def.height);
        for placed in &def.patches {
            let patch = wad.lump(&placed.patch).and_then(patch).ok_or_else(|| {
                DoomError::new(
                    wad.path(),
                    Some(&placed.patch),
                    format!(
                        "texture {name}'s patch is missing or not a picture: the WAD is damaged"
                    ),
                )
            })?;
            for y in 0..patch.image.height {
                for x in 0..patch.image.width {
                    let (tx, ty) = (
                        i32::from(placed.x) + i32::from(x),
                        i32::from(placed.y) + i32::from(y),
                    );
                    let inside = (0..i32::from(def.width)).contains(&tx)
                        && (0..i32::from(def.height)).contains(&ty);
                    if let (true, Some(texel)) = (inside, patch.image.at(x, y)) {
                        image.texels[ty as usize * usize::from(def.width) + tx as usize] =
                            Some(texel);
                    }
                }
            }
        }
        Ok(image)
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::doom::wad::tests::pwad;

    /// A 2×5 patch: column 0 a post of rows 1..3, column 1 two posts (row 3, then one whose top,
    /// 1, is not below the last: the tall-patch rule makes it 3 + 1).
    fn small_patch() -> Vec<u8> {
        let mut bytes = Vec::new();
        for value in [2i16, 5, 1, 4] {
            bytes.extend_from_slice(&value.to_le_bytes());
        }
        let column0 = [1u8, 2, 0, 10, 11, 0, 0xFF];
        let column1 = [3u8, 1, 0, 20, 0, 1, 1, 0, 21, 0, 0xFF];
        let first = 16u32;
        bytes.extend_from_slice(&first.to_le_bytes());
        bytes.extend_from_slice(&(first + column0.len() as u32).to_le_bytes());
        bytes.extend_from_slice(&column0);
        bytes.extend_from_slice(&column1);
        bytes
    }

    #[test]
    fn patches_decode_posts_gaps_and_tall_posts() {
        let patch = patch(&small_patch()).unwrap();
        assert_eq!((patch.left, patch.top), (1, 4));
        let image = &patch.image;
        assert_eq!((image.width, image.height), (2, 5));
        let column = |x| (0..5).map(|y| image.at(x, y)).collect::<Vec<_>>();
        assert_eq!(column(0), [None, Some(10), Some(11), None, None]);
        assert_eq!(column(1), [None, None, None, Some(20), Some(21)]);
        assert!(
            super::patch(&small_patch()[..20]).is_none(),
            "a cut lump is refused"
        );
    }

    #[test]
    fn textures_are_drawn_from_their_patches_and_flats_from_their_namespace() {
        let mut pnames = 1i32.to_le_bytes().to_vec();
        pnames.extend_from_slice(b"PATCH1\0\0");
        // TEXTURE1: one texture, 3×5, of one patch at x = 2, y = 0 (its second column cut off).
        let mut texture1 = 1i32.to_le_bytes().to_vec();
        texture1.extend_from_slice(&8i32.to_le_bytes());
        texture1.extend_from_slice(b"WALL\0\0\0\0");
        texture1.extend_from_slice(&0i32.to_le_bytes());
        for value in [3i16, 5] {
            texture1.extend_from_slice(&value.to_le_bytes());
        }
        texture1.extend_from_slice(&0i32.to_le_bytes());
        for value in [1i16, 2, 0, 0, 0, 0] {
            texture1.extend_from_slice(&value.to_le_bytes());
        }
        let flat_bytes = vec![7u8; 4096];
        let patch_bytes = small_patch();
        let wad = Wad::from_bytes(
            Path::new("t.wad"),
            pwad(&[
                ("PNAMES", &pnames),
                ("TEXTURE1", &texture1),
                ("PATCH1", &patch_bytes),
                ("F_START", b""),
                ("FLOOR", &flat_bytes),
                ("F_END", b""),
            ]),
        )
        .unwrap();
        let textures = Textures::read(&wad).unwrap();
        let wall = textures.compose(&wad, "WALL").unwrap();
        assert_eq!((wall.width, wall.height), (3, 5));
        assert_eq!(wall.at(2, 1), Some(10));
        assert_eq!(wall.at(0, 1), None);
        assert_eq!(wall.gaps(), 13);
        assert_eq!(flat(&wad, "FLOOR").unwrap().at(63, 63), Some(7));
        assert!(flat(&wad, "PATCH1").is_err(), "outside the flat markers");
    }
}
