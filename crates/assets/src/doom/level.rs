//! A Doom map's lumps in the Doom (not Hexen) format: vertices, linedefs, sidedefs, sectors and
//! things, as the Doom specs lay them out (all little-endian; "none" is 0xFFFF).

use super::wad::{member, name8, Wad};
use super::DoomError;

/// The lumps a map's marker is followed by (Doom's order; `BEHAVIOR` marks a Hexen map).
pub(crate) const MAP_LUMPS: [&str; 11] = [
    "THINGS", "LINEDEFS", "SIDEDEFS", "VERTEXES", "SEGS", "SSECTORS", "NODES", "SECTORS", "REJECT",
    "BLOCKMAP", "BEHAVIOR",
];

/// No sidedef, no partner seg, no linedef.
pub const NONE: u16 = 0xFFFF;

/// A map vertex, in whole map units.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DoomVertex {
    /// East.
    pub x: i16,
    /// North.
    pub y: i16,
}

/// A linedef: its two vertices, its flags and special, and its sidedefs (right, then left,
/// [`NONE`] where a one-sided line has none).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Linedef {
    /// Its first vertex.
    pub start: u16,
    /// Its second vertex: the right side is on the right going from start to end.
    pub end: u16,
    /// Doom's linedef flags (blocking, two-sided, unpegged, …).
    pub flags: u16,
    /// Its action (doors, lifts, switches, …), 0 for none.
    pub special: u16,
    /// The sectors its action moves: those with this tag.
    pub tag: u16,
    /// Its right and left sidedefs.
    pub sides: [u16; 2],
}

impl Linedef {
    /// Has a sidedef on both sides: a portal between two sectors.
    pub fn two_sided(&self) -> bool {
        self.sides[1] != NONE
    }
}

/// A sidedef: its texture offsets, its upper, lower and middle textures (`-` for none) and the
/// sector it faces.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Sidedef {
    /// Texture offset along the line.
    pub x_offset: i16,
    /// Texture offset up the wall.
    pub y_offset: i16,
    /// The texture above the opening of a two-sided line.
    pub upper: String,
    /// The texture below it.
    pub lower: String,
    /// A one-sided line's wall, or a two-sided line's see-through image.
    pub middle: String,
    /// The sector on this side.
    pub sector: u16,
}

/// A sector: heights, flats, light, special and tag.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DoomSector {
    /// Floor height.
    pub floor: i16,
    /// Ceiling height.
    pub ceiling: i16,
    /// The floor's flat.
    pub floor_flat: String,
    /// The ceiling's flat (`F_SKY1`: the sky).
    pub ceiling_flat: String,
    /// Light level, 0..=255.
    pub light: i16,
    /// Its effect (blinking light, damage, secret, …), 0 for none.
    pub special: u16,
    /// What linedef actions name it by.
    pub tag: u16,
}

/// A thing: where, facing where (degrees), its type and its flags.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct DoomThing {
    /// East.
    pub x: i16,
    /// North.
    pub y: i16,
    /// Facing, degrees anticlockwise from east.
    pub angle: i16,
    /// Its type (1: player 1's start, …).
    pub kind: u16,
    /// The skills and modes it appears in.
    pub flags: u16,
}

/// One map of a WAD.
#[derive(Clone, Debug)]
pub struct DoomLevel {
    /// Its marker's name (`E1M1`, `MAP01`).
    pub name: String,
    /// `VERTEXES`.
    pub vertices: Vec<DoomVertex>,
    /// `LINEDEFS`.
    pub linedefs: Vec<Linedef>,
    /// `SIDEDEFS`.
    pub sidedefs: Vec<Sidedef>,
    /// `SECTORS`.
    pub sectors: Vec<DoomSector>,
    /// `THINGS`.
    pub things: Vec<DoomThing>,
}

fn half(bytes: &[u8], at: usize) -> u16 {
    u16::from_le_bytes([bytes[at], bytes[at + 1]])
}

/// `bytes` cut into `size`-byte records, each read by `read`; an error naming the lump if the
/// size does not divide.
fn records<T>(
    wad: &Wad,
    lump: &str,
    bytes: &[u8],
    size: usize,
    read: impl Fn(&[u8]) -> T,
) -> Result<Vec<T>, DoomError> {
    if !bytes.len().is_multiple_of(size) {
        return Err(DoomError::new(
            wad.path(),
            Some(lump),
            format!(
                "{} bytes is not a whole number of {size}-byte records: the map is damaged, or not in Doom's format",
                bytes.len()
            ),
        ));
    }
    Ok(bytes.chunks_exact(size).map(read).collect())
}

impl DoomLevel {
    /// The sectors across the two-sided lines of sector `sector` (one a line, so a sector may
    /// come more than once).
    pub fn neighbours(&self, sector: u16) -> impl Iterator<Item = &DoomSector> {
        let sector_of = |side: u16| self.sidedefs[usize::from(side)].sector;
        self.linedefs
            .iter()
            .filter(|line| line.two_sided())
            .filter_map(move |line| {
                let (right, left) = (sector_of(line.sides[0]), sector_of(line.sides[1]));
                match (right == sector, left == sector) {
                    (true, false) => Some(left),
                    (false, true) => Some(right),
                    _ => None,
                }
            })
            .map(|index| &self.sectors[usize::from(index)])
    }

    /// Map `name` (`E1M1`, `MAP01`, …) of `wad`, its references checked.
    pub fn read(wad: &Wad, name: &str) -> Result<DoomLevel, DoomError> {
        let marker = name.to_ascii_uppercase();
        let lumps = wad.group(&marker, &MAP_LUMPS).ok_or_else(|| {
            let maps: Vec<&str> = wad.names().filter(|lump| is_map_name(lump)).collect();
            DoomError::new(
                wad.path(),
                None,
                format!("has no map {marker}: its maps are {}", maps.join(", ")),
            )
        })?;
        let lump = |wanted: &str| member(wad, &lumps, &marker, wanted, "the map is damaged");
        if lumps.iter().any(|(lump, _)| *lump == "BEHAVIOR") {
            return Err(DoomError::new(
                wad.path(),
                Some(&marker),
                "is a Hexen-format map: only Doom-format maps are supported (save it in Doom format in the editor)".to_string(),
            ));
        }
        let at = |suffix: &str| format!("{marker}/{suffix}");
        let vertices = records(wad, &at("VERTEXES"), lump("VERTEXES")?, 4, |r| DoomVertex {
            x: half(r, 0) as i16,
            y: half(r, 2) as i16,
        })?;
        let linedefs = records(wad, &at("LINEDEFS"), lump("LINEDEFS")?, 14, |r| Linedef {
            start: half(r, 0),
            end: half(r, 2),
            flags: half(r, 4),
            special: half(r, 6),
            tag: half(r, 8),
            sides: [half(r, 10), half(r, 12)],
        })?;
        let sidedefs = records(wad, &at("SIDEDEFS"), lump("SIDEDEFS")?, 30, |r| Sidedef {
            x_offset: half(r, 0) as i16,
            y_offset: half(r, 2) as i16,
            upper: name8(&r[4..12]),
            lower: name8(&r[12..20]),
            middle: name8(&r[20..28]),
            sector: half(r, 28),
        })?;
        let sectors = records(wad, &at("SECTORS"), lump("SECTORS")?, 26, |r| DoomSector {
            floor: half(r, 0) as i16,
            ceiling: half(r, 2) as i16,
            floor_flat: name8(&r[4..12]),
            ceiling_flat: name8(&r[12..20]),
            light: half(r, 20) as i16,
            special: half(r, 22),
            tag: half(r, 24),
        })?;
        let things = records(wad, &at("THINGS"), lump("THINGS")?, 10, |r| DoomThing {
            x: half(r, 0) as i16,
            y: half(r, 2) as i16,
            angle: half(r, 4) as i16,
            kind: half(r, 6),
            flags: half(r, 8),
        })?;
        let level = DoomLevel {
            name: marker,
            vertices,
            linedefs,
            sidedefs,
            sectors,
            things,
        };
        level.check_references(wad)?;
        Ok(level)
    }

    /// Every linedef's vertices and sidedefs, and every sidedef's sector, exist.
    fn check_references(&self, wad: &Wad) -> Result<(), DoomError> {
        let fail = |lump: &str, message: String| {
            Err(DoomError::new(
                wad.path(),
                Some(&format!("{}/{lump}", self.name)),
                message,
            ))
        };
        for (index, line) in self.linedefs.iter().enumerate() {
            for vertex in [line.start, line.end] {
                if usize::from(vertex) >= self.vertices.len() {
                    return fail(
                        "LINEDEFS",
                        format!("linedef {index} names vertex {vertex}, and there are {}: the map is damaged", self.vertices.len()),
                    );
                }
            }
            if line.sides[0] == NONE {
                return fail(
                    "LINEDEFS",
                    format!("linedef {index} has no right sidedef: give it one in the editor"),
                );
            }
            for side in line.sides.into_iter().filter(|&side| side != NONE) {
                if usize::from(side) >= self.sidedefs.len() {
                    return fail(
                        "LINEDEFS",
                        format!("linedef {index} names sidedef {side}, and there are {}: the map is damaged", self.sidedefs.len()),
                    );
                }
            }
        }
        for (index, side) in self.sidedefs.iter().enumerate() {
            if usize::from(side.sector) >= self.sectors.len() {
                return fail(
                    "SIDEDEFS",
                    format!(
                        "sidedef {index} faces sector {}, and there are {}: the map is damaged",
                        side.sector,
                        self.sectors.len()
                    ),
                );
            }
        }
        Ok(())
    }
}

/// `ExMy` or `MAPxx`: a map's marker name.
pub fn is_map_name(name: &str) -> bool {
    let bytes = name.as_bytes();
    match bytes {
        [b'E', e, b'M', m] => e.is_ascii_digit() && m.is_ascii_digit(),
        [b'M', b'A', b'P', a, b] => a.is_ascii_digit() && b.is_ascii_digit(),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::doom::wad::tests::pwad;

    fn halves(values: &[u16]) -> Vec<u8> {
        values.iter().flat_map(|v| v.to_le_bytes()).collect()
    }

    fn name(text: &str) -> [u8; 8] {
        let mut bytes = [0u8; 8];
        bytes[..text.len()].copy_from_slice(text.as_bytes());
        bytes
    }

    /// A square room: four vertices, four one-sided lines, one sector, a player start.
    fn square(extra: &[(&str, &[u8])], linedefs: &[u16]) -> Wad {
        let vertices = halves(&[0, 0, 64, 0, 64, 64, 0, 64]);
        let mut sidedef = halves(&[0, 0]);
        for texture in ["-", "-", "STARTAN3"] {
            sidedef.extend_from_slice(&name(texture));
        }
        sidedef.extend(halves(&[0]));
        let mut sector = halves(&[0, 128]);
        sector.extend_from_slice(&name("FLOOR4_8"));
        sector.extend_from_slice(&name("CEIL3_5"));
        sector.extend(halves(&[160, 0, 0]));
        let things = halves(&[32, 32, 90, 1, 7]);
        let lines = halves(linedefs);
        let mut lumps: Vec<(&str, &[u8])> = vec![
            ("E1M1", b""),
            ("THINGS", &things),
            ("LINEDEFS", &lines),
            ("SIDEDEFS", &sidedef),
            ("VERTEXES", &vertices),
            ("SECTORS", &sector),
        ];
        lumps.extend_from_slice(extra);
        Wad::from_bytes(Path::new("room.wad"), pwad(&lumps)).unwrap()
    }

    const LINES: [u16; 28] = [
        0, 1, 1, 0, 0, 0, NONE, 1, 2, 1, 0, 0, 0, NONE, 2, 3, 1, 0, 0, 0, NONE, 3, 0, 1, 0, 0, 0,
        NONE,
    ];

    #[test]
    fn a_doom_format_map_reads_whole() {
        let level = DoomLevel::read(&square(&[], &LINES), "e1m1").unwrap();
        assert_eq!(level.vertices[2], DoomVertex { x: 64, y: 64 });
        assert_eq!(level.linedefs.len(), 4);
        assert!(!level.linedefs[0].two_sided());
        assert_eq!(level.sidedefs[0].middle, "STARTAN3");
        assert_eq!(level.sectors[0].ceiling_flat, "CEIL3_5");
        assert_eq!(level.sectors[0].light, 160);
        assert_eq!(level.things[0].kind, 1);
    }

    #[test]
    fn hexen_maps_damaged_lumps_and_bad_references_are_refused_by_name() {
        let error = DoomLevel::read(&square(&[("BEHAVIOR", b"")], &LINES), "E1M1").unwrap_err();
        assert!(
            error
                .to_string()
                .contains("lump E1M1: is a Hexen-format map"),
            "{error}"
        );
        let error = DoomLevel::read(&square(&[], &LINES[..27]), "E1M1").unwrap_err();
        assert!(
            error
                .to_string()
                .contains("lump E1M1/LINEDEFS: 54 bytes is not a whole number of 14-byte records"),
            "{error}"
        );
        let mut bad = LINES;
        bad[1] = 9;
        let error = DoomLevel::read(&square(&[], &bad), "E1M1").unwrap_err();
        assert!(
            error.to_string().contains("linedef 0 names vertex 9"),
            "{error}"
        );
        assert!(is_map_name("E1M1") && is_map_name("MAP07") && !is_map_name("PLAYPAL"));
    }
}
