//! Doom's things as portalcast things (docs/MAP_FORMAT.md, "Doom maps"): which of a map's things
//! are imported, the sprite set each kind shows, and those sets composed from the WAD's sprite
//! lumps.
//!
//! - **Which.** Things of Doom's medium skill ("Hurt me plenty", Doom's default: flag 2), not
//!   multiplayer-only (flag 16), of a kind [`THING_KINDS`] knows: monsters, weapons, ammunition,
//!   health, armour, power-ups, keys and decorations. Player starts, teleport destinations and
//!   the boss brain's spawners are not drawn.
//! - **How.** Monsters stand still in their first frame (seen from eight directions); items
//!   and decorations play their frames (Doom's sequence: a health bonus's `ABCDCB`) at
//!   portalcast's default speed. Decorations Doom blocks are `solid`; hanging ones hang from
//!   the ceiling. The footprint is the engine's (half the sprite's width), and a thing must fit
//!   its piece: one that does not is left out (the report counts them).
//! - **Sprites.** A set is composed from the lumps between `S_START` and `S_END`
//!   (`NAMEF0` for a frame seen from every side, `NAMEF1` … `NAMEF8` for eight views, a lump
//!   named for two views drawing the second mirrored), each picture placed on one canvas by its
//!   offsets so that the origin Doom stands on the floor is the canvas's bottom centre (rows
//!   Doom draws below the floor are cut, as Doom's floor hides them). Doom's rotation `d` (the
//!   eye `(d − 1)·45°` anticlockwise from the thing's facing, y up) is portalcast's `r(9 − d) mod
//!   8` (y down).

use super::graphics::{patch, IndexedImage, Patch};
use super::level::DoomThing;
use super::wad::Wad;

/// A Doom thing kind portalcast imports.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct ThingKind {
    /// Doom's thing type (`THINGS` lump).
    pub doom_type: u16,
    /// Its sprite's four-letter name.
    pub sprite: &'static str,
    /// The frames it shows, in order (letters of its sprite's frames).
    pub frames: &'static str,
    /// Doom blocks it (`MF_SOLID`).
    pub solid: bool,
    /// It hangs from the ceiling (`MF_SPAWNCEILING`).
    pub hanging: bool,
}

const fn kind(doom_type: u16, sprite: &'static str, frames: &'static str) -> ThingKind {
    ThingKind {
        doom_type,
        sprite,
        frames,
        solid: false,
        hanging: false,
    }
}

const fn solid(doom_type: u16, sprite: &'static str, frames: &'static str) -> ThingKind {
    ThingKind {
        solid: true,
        ..kind(doom_type, sprite, frames)
    }
}

const fn hanging(
    doom_type: u16,
    sprite: &'static str,
    frames: &'static str,
    blocks: bool,
) -> ThingKind {
    ThingKind {
        solid: blocks,
        hanging: true,
        ..kind(doom_type, sprite, frames)
    }
}

/// The kinds imported, from Doom's `mobjinfo` (types, sprites, frames, flags).
pub(super) const THING_KINDS: &[ThingKind] = &[
    // Monsters, in their first frame.
    solid(3004, "POSS", "A"),
    solid(9, "SPOS", "A"),
    solid(65, "CPOS", "A"),
    solid(3001, "TROO", "A"),
    solid(3002, "SARG", "A"),
    solid(58, "SARG", "A"),
    solid(3006, "SKUL", "A"),
    solid(3005, "HEAD", "A"),
    solid(69, "BOS2", "A"),
    solid(3003, "BOSS", "A"),
    solid(68, "BSPI", "A"),
    solid(71, "PAIN", "A"),
    solid(66, "SKEL", "A"),
    solid(67, "FATT", "A"),
    solid(64, "VILE", "A"),
    solid(7, "SPID", "A"),
    solid(16, "CYBR", "A"),
    solid(84, "SSWV", "A"),
    hanging(72, "KEEN", "A", true),
    solid(88, "BBRN", "A"),
    // Weapons and ammunition.
    kind(2001, "SHOT", "A"),
    kind(82, "SGN2", "A"),
    kind(2002, "MGUN", "A"),
    kind(2003, "LAUN", "A"),
    kind(2004, "PLAS", "A"),
    kind(2005, "CSAW", "A"),
    kind(2006, "BFUG", "A"),
    kind(2007, "CLIP", "A"),
    kind(2008, "SHEL", "A"),
    kind(2010, "ROCK", "A"),
    kind(2047, "CELL", "A"),
    kind(2048, "AMMO", "A"),
    kind(2049, "SBOX", "A"),
    kind(2046, "BROK", "A"),
    kind(17, "CELP", "A"),
    kind(8, "BPAK", "A"),
    // Health, armour, power-ups and keys.
    kind(2011, "STIM", "A"),
    kind(2012, "MEDI", "A"),
    kind(2014, "BON1", "ABCDCB"),
    kind(2015, "BON2", "ABCDCB"),
    kind(2018, "ARM1", "AB"),
    kind(2019, "ARM2", "AB"),
    kind(83, "MEGA", "ABCD"),
    kind(2013, "SOUL", "ABCDCB"),
    kind(2022, "PINV", "ABCD"),
    kind(2023, "PSTR", "A"),
    kind(2024, "PINS", "ABCD"),
    kind(2025, "SUIT", "A"),
    kind(2026, "PMAP", "ABCDCB"),
    kind(2045, "PVIS", "AB"),
    kind(5, "BKEY", "AB"),
    kind(6, "YKEY", "AB"),
    kind(13, "RKEY", "AB"),
    kind(40, "BSKU", "AB"),
    kind(39, "YSKU", "AB"),
    kind(38, "RSKU", "AB"),
    // Decorations.
    solid(2028, "COLU", "A"),
    solid(2035, "BAR1", "AB"),
    solid(48, "ELEC", "A"),
    solid(30, "COL1", "A"),
    solid(31, "COL2", "A"),
    solid(32, "COL3", "A"),
    solid(33, "COL4", "A"),
    solid(36, "COL5", "AB"),
    solid(37, "COL6", "A"),
    solid(41, "CEYE", "ABCB"),
    solid(42, "FSKU", "ABC"),
    solid(43, "TRE1", "A"),
    solid(44, "TBLU", "ABCD"),
    solid(45, "TGRN", "ABCD"),
    solid(46, "TRED", "ABCD"),
    solid(55, "SMBT", "ABCD"),
    solid(56, "SMGT", "ABCD"),
    solid(57, "SMRT", "ABCD"),
    solid(47, "SMIT", "A"),
    solid(54, "TRE2", "A"),
    kind(34, "CAND", "A"),
    solid(35, "CBRA", "A"),
    solid(85, "TLMP", "ABCD"),
    solid(86, "TLP2", "ABCD"),
    solid(70, "FCAN", "ABC"),
    solid(25, "POL1", "A"),
    solid(26, "POL6", "AB"),
    solid(27, "POL4", "A"),
    solid(28, "POL2", "A"),
    solid(29, "POL3", "AB"),
    hanging(49, "GOR1", "ABCB", true),
    hanging(50, "GOR2", "A", true),
    hanging(51, "GOR3", "A", true),
    hanging(52, "GOR4", "A", true),
    hanging(53, "GOR5", "A", true),
    hanging(59, "GOR2", "A", false),
    hanging(60, "GOR4", "A", false),
    hanging(61, "GOR3", "A", false),
    hanging(62, "GOR5", "A", false),
    hanging(63, "GOR1", "ABCB", false),
    hanging(73, "HDB1", "A", true),
    hanging(74, "HDB2", "A", true),
    hanging(75, "HDB3", "A", true),
    hanging(76, "HDB4", "A", true),
    hanging(77, "HDB5", "A", true),
    hanging(78, "HDB6", "A", true),
    // Remains.
    kind(10, "PLAY", "W"),
    kind(12, "PLAY", "W"),
    kind(15, "PLAY", "N"),
    kind(18, "POSS", "L"),
    kind(19, "SPOS", "L"),
    kind(20, "TROO", "M"),
    kind(21, "SARG", "N"),
    kind(22, "HEAD", "L"),
    kind(24, "POL5", "A"),
    kind(79, "POB1", "A"),
    kind(80, "POB2", "A"),
    kind(81, "BRS1", "A"),
];

/// The kind of Doom thing type `doom_type`, if portalcast imports it.
pub(super) fn kind_of(doom_type: u16) -> Option<&'static ThingKind> {
    THING_KINDS.iter().find(|kind| kind.doom_type == doom_type)
}

/// The kind whose sprite set is named `set_name` ([`ThingKind::set_name`]).
pub(super) fn kind_of_set(set_name: &str) -> Option<&'static ThingKind> {
    THING_KINDS.iter().find(|kind| kind.set_name() == set_name)
}

/// Doom's thing flag of medium skill, and of things only in multiplayer games.
const SKILL_MEDIUM: u16 = 2;
const MULTIPLAYER_ONLY: u16 = 16;

/// Whether `thing` appears in a single-player game at medium skill.
pub(super) fn in_the_game(thing: &DoomThing) -> bool {
    thing.flags & SKILL_MEDIUM != 0 && thing.flags & MULTIPLAYER_ONLY == 0
}

impl ThingKind {
    /// The sprite set's name: its sprite and frames (`poss_a`, `bon1_abcdcb`): kinds showing
    /// the same frames share one.
    pub fn set_name(&self) -> String {
        format!("{}_{}", self.sprite, self.frames).to_ascii_lowercase()
    }
}

/// A sprite set composed from a WAD: `frames · rotations` images of one size, frame by frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct ComposedSet {
    /// Animation frames.
    pub frames: u8,
    /// 1, or 8.
    pub rotations: u8,
    /// Image `frame · rotations + rotation`.
    pub images: Vec<IndexedImage>,
}

/// Most texels a side of a sprite image may have.
const SIDE_MAX: i32 = 256;

/// One frame's views: index 0 seen from every side, 1 … 8 Doom's rotations; each a picture and
/// whether it is drawn mirrored.
type Views = [Option<(Patch, bool)>; 9];

/// The views of frame `frame` of sprite `sprite` in `wad`'s sprite lumps.
fn views(wad: &Wad, sprite: &str, frame: u8) -> Views {
    let mut views: Views = Default::default();
    for name in wad.names() {
        let bytes = name.as_bytes();
        if !(name.len() == 6 || name.len() == 8) || !name.starts_with(sprite) {
            continue;
        }
        let Some(lump) = wad.lump_in(name, &["S_START", "SS_START"], &["S_END", "SS_END"]) else {
            continue;
        };
        let Some(picture) = patch(lump) else {
            continue;
        };
        for (at, mirrored) in [(4, false), (6, true)] {
            if bytes.len() > at + 1 && bytes[at] == frame {
                let rotation = bytes[at + 1].wrapping_sub(b'0');
                if usize::from(rotation) < views.len() {
                    views[usize::from(rotation)] = Some((picture.clone(), mirrored));
                }
            }
        }
    }
    views
}

/// The picture of a view, mirrored if it is drawn so, with its offsets.
fn oriented((picture, mirrored): &(Patch, bool)) -> Patch {
    if !mirrored {
        return picture.clone();
    }
    let image = &picture.image;
    let mut texels = image.texels.clone();
    for row in texels.chunks_mut(usize::from(image.width.max(1))) {
        row.reverse();
    }
    Patch {
        image: IndexedImage {
            texels,
            ..image.clone()
        },
        left: image.width as i16 - picture.left,
        top: picture.top,
    }
}

/// Composes `kind`'s sprite set from `wad`: its frames, each from every side or from eight, on
/// one canvas. An error says which lump is missing or what is too large.
pub(super) fn compose_set(wad: &Wad, kind: &ThingKind) -> Result<ComposedSet, String> {
    let mut frames: Vec<Vec<Patch>> = Vec::new();
    for frame in kind.frames.bytes() {
        let views = views(wad, kind.sprite, frame);
        let letter = char::from(frame);
        let pictures: Vec<Patch> = if let Some(all) = &views[0] {
            vec![oriented(all)]
        } else {
            // portalcast's rotation r is Doom's (8 − r) mod 8 + 1.
            (0..8)
                .map(|r| {
                    let doom = (8 - r) % 8 + 1;
                    views[doom].as_ref().map(oriented).ok_or_else(|| {
                        format!(
                            "sprite lump {}{letter}{doom} (or {}{letter}0) is missing",
                            kind.sprite, kind.sprite
                        )
                    })
                })
                .collect::<Result<_, _>>()?
        };
        frames.push(pictures);
    }
    let rotations = if frames.iter().any(|views| views.len() == 8) {
        8
    } else {
        1
    };
    // A frame seen from every side, in a set with rotations, shows it from each.
    for views in &mut frames {
        if views.len() < rotations {
            let view = views[0].clone();
            views.resize(rotations, view);
        }
    }
    let all = frames.iter().flatten();
    let half = all
        .clone()
        .map(|p| i32::from(p.left).max(i32::from(p.image.width) - i32::from(p.left)))
        .max()
        .unwrap_or(1)
        .max(1);
    let top = all
        .clone()
        .map(|p| i32::from(p.top))
        .max()
        .unwrap_or(1)
        .max(1);
    let (width, height) = (2 * half, top);
    if width > SIDE_MAX || height > SIDE_MAX {
        return Err(format!(
            "sprite {} placed by its offsets is {width}x{height}, more than {SIDE_MAX} on a side",
            kind.sprite
        ));
    }
    let images: Vec<IndexedImage> = all
        .map(|picture| {
            let mut canvas = IndexedImage {
                width: width as u16,
                height: height as u16,
                texels: vec![None; (width * height) as usize],
            };
            let (x0, y0) = (half - i32::from(picture.left), top - i32::from(picture.top));
            for y in 0..picture.image.height {
                for x in 0..picture.image.width {
                    let (cx, cy) = (x0 + i32::from(x), y0 + i32::from(y));
                    if (0..width).contains(&cx) && (0..height).contains(&cy) {
                        if let Some(texel) = picture.image.at(x, y) {
                            canvas.texels[(cy * width + cx) as usize] = Some(texel);
                        }
                    }
                }
            }
            canvas
        })
        .collect();
    if images
        .iter()
        .any(|image| image.gaps() == image.texels.len())
    {
        return Err(format!(
            "sprite {} has a frame with nothing drawn above the floor",
            kind.sprite
        ));
    }
    Ok(ComposedSet {
        frames: frames.len() as u8,
        rotations: rotations as u8,
        images,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_is_listed_once_with_frames() {
        let mut types: Vec<u16> = THING_KINDS.iter().map(|k| k.doom_type).collect();
        types.sort_unstable();
        types.dedup();
        assert_eq!(types.len(), THING_KINDS.len());
        for kind in THING_KINDS {
            assert_eq!(kind.sprite.len(), 4, "{kind:?}");
            assert!(
                !kind.frames.is_empty() && kind.frames.len() <= 8,
                "{kind:?}"
            );
        }
    }

    #[test]
    fn medium_skill_single_player_things_are_in_the_game() {
        let thing = |flags| DoomThing {
            x: 0,
            y: 0,
            angle: 0,
            kind: 3004,
            flags,
        };
        assert!(in_the_game(&thing(7)));
        assert!(in_the_game(&thing(2)));
        assert!(!in_the_game(&thing(4)));
        assert!(!in_the_game(&thing(7 | 16)));
    }
}
