//! WAD files: the header, the lump directory and the lumps, as Doom's `w_wad.c` reads them
//! (a 12-byte header, `IWAD` or `PWAD`, then 16-byte directory entries: offset, size, an
//! eight-byte name padded with NULs).

use std::path::{Path, PathBuf};

use super::DoomError;

/// One directory entry: its name and its bytes' place in the file.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Entry {
    name: String,
    offset: usize,
    size: usize,
}

/// A WAD file read whole, with its directory checked against the file's size.
#[derive(Clone, Debug)]
pub struct Wad {
    path: PathBuf,
    bytes: Vec<u8>,
    entries: Vec<Entry>,
}

/// The bytes of a little-endian 32-bit word at `at`.
fn word(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
}

/// An eight-byte lump or texture name: up to its first NUL, upper case (Doom's names are case
/// blind).
pub(crate) fn name8(bytes: &[u8]) -> String {
    bytes
        .iter()
        .take_while(|&&byte| byte != 0)
        .map(|&byte| char::from(byte).to_ascii_uppercase())
        .collect()
}

impl Wad {
    /// Reads the WAD at `path`.
    pub fn open(path: &Path) -> Result<Wad, DoomError> {
        let bytes = std::fs::read(path).map_err(|error| {
            DoomError::new(
                path,
                None,
                format!("cannot read it ({error}): check the path (a Doom WAD, e.g. /usr/share/games/doom/freedoom1.wad from Debian's freedoom)"),
            )
        })?;
        Wad::from_bytes(path, bytes)
    }

    /// The WAD in `bytes`, named `path` in errors.
    pub fn from_bytes(path: &Path, bytes: Vec<u8>) -> Result<Wad, DoomError> {
        let fail = |message: String| DoomError::new(path, None, message);
        if bytes.len() < 12 || !matches!(&bytes[..4], b"IWAD" | b"PWAD") {
            return Err(fail(
                "not a WAD file (it does not start with IWAD or PWAD): name a Doom WAD".to_string(),
            ));
        }
        let count = word(&bytes, 4) as usize;
        let directory = word(&bytes, 8) as usize;
        let directory_end = count
            .checked_mul(16)
            .and_then(|size| size.checked_add(directory))
            .filter(|&end| end <= bytes.len())
            .ok_or_else(|| {
                fail(format!(
                    "its directory ({count} entries at byte {directory}) runs past the file's {} bytes: the file is cut short or damaged",
                    bytes.len()
                ))
            })?;
        let mut entries = Vec::with_capacity(count);
        for at in (directory..directory_end).step_by(16) {
            let (offset, size) = (word(&bytes, at) as usize, word(&bytes, at + 4) as usize);
            let name = name8(&bytes[at + 8..at + 16]);
            if offset.checked_add(size).is_none_or(|end| end > bytes.len()) {
                return Err(DoomError::new(
                    path,
                    Some(&name),
                    format!(
                        "its {size} bytes at byte {offset} run past the file's {} bytes: the file is cut short or damaged",
                        bytes.len()
                    ),
                ));
            }
            entries.push(Entry { name, offset, size });
        }
        Ok(Wad {
            path: path.to_path_buf(),
            bytes,
            entries,
        })
    }

    /// `pwad`'s lumps loaded over `iwad`'s, as Doom loads a PWAD named with `-file`: a lump of
    /// either is found by name, the PWAD's first (its maps, and any texture, flat or patch it
    /// replaces). Named by the PWAD's path in errors.
    pub fn over(pwad: &Wad, iwad: &Wad) -> Wad {
        let mut bytes = iwad.bytes.clone();
        let base = bytes.len();
        bytes.extend_from_slice(&pwad.bytes);
        let mut entries = iwad.entries.clone();
        entries.extend(pwad.entries.iter().map(|entry| Entry {
            offset: entry.offset + base,
            ..entry.clone()
        }));
        Wad {
            path: pwad.path.clone(),
            bytes,
            entries,
        }
    }

    /// Whether it is an IWAD (a game's whole data) rather than a PWAD (a patch over one).
    pub fn is_iwad(&self) -> bool {
        self.bytes.starts_with(b"IWAD")
    }

    /// The file's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The lump names, in directory order.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.entries.iter().map(|entry| entry.name.as_str())
    }

    /// The last lump named `name` (a later lump replaces an earlier one, as in Doom).
    pub fn lump(&self, name: &str) -> Option<&[u8]> {
        let entry = self.entries.iter().rev().find(|entry| entry.name == name)?;
        Some(&self.bytes[entry.offset..entry.offset + entry.size])
    }

    /// The last lump named `name` between a start marker and its end marker (`F_START`/`F_END`
    /// or `FF_START`/`FF_END` for flats: a PWAD's own use the doubled names): a namespace, as
    /// Doom's flats and sprites are.
    pub fn lump_in(&self, name: &str, starts: &[&str], ends: &[&str]) -> Option<&[u8]> {
        let mut inside = false;
        let mut found = None;
        for entry in &self.entries {
            if starts.contains(&entry.name.as_str()) {
                inside = true;
            } else if ends.contains(&entry.name.as_str()) {
                inside = false;
            } else if inside && entry.name == name {
                found = Some(entry);
            }
        }
        found.map(|entry| &self.bytes[entry.offset..entry.offset + entry.size])
    }

    /// The lumps after the marker lump `marker` (a map's name, or `GL_` and it), up to the next
    /// lump not in `members`: a map's lumps by name. `None` if there is no such marker.
    pub fn group(&self, marker: &str, members: &[&str]) -> Option<Vec<(&str, &[u8])>> {
        let start = self
            .entries
            .iter()
            .rposition(|entry| entry.name == marker)?;
        Some(
            self.entries[start + 1..]
                .iter()
                .take_while(|entry| members.contains(&entry.name.as_str()))
                .map(|entry| {
                    (
                        entry.name.as_str(),
                        &self.bytes[entry.offset..entry.offset + entry.size],
                    )
                })
                .collect(),
        )
    }
}

/// Lump `wanted` of a group read with [`Wad::group`] after marker `marker`, or an error naming
/// `marker/wanted` in `wad` with `what_to_do`.
pub(crate) fn member<'a>(
    wad: &Wad,
    lumps: &[(&str, &'a [u8])],
    marker: &str,
    wanted: &str,
    what_to_do: &str,
) -> Result<&'a [u8], DoomError> {
    lumps
        .iter()
        .find(|(lump, _)| *lump == wanted)
        .map(|(_, bytes)| *bytes)
        .ok_or_else(|| {
            DoomError::new(
                wad.path(),
                Some(&format!("{marker}/{wanted}")),
                format!("is missing: {what_to_do}"),
            )
        })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A PWAD of `lumps`, laid out as Doom writes one.
    pub(crate) fn pwad(lumps: &[(&str, &[u8])]) -> Vec<u8> {
        let mut data = Vec::new();
        let mut directory = Vec::new();
        for (name, bytes) in lumps {
            directory.extend_from_slice(&(12 + data.len() as u32).to_le_bytes());
            directory.extend_from_slice(&(bytes.len() as u32).to_le_bytes());
            let mut padded = [0u8; 8];
            padded[..name.len()].copy_from_slice(name.as_bytes());
            directory.extend_from_slice(&padded);
            data.extend_from_slice(bytes);
        }
        let mut wad = b"PWAD".to_vec();
        wad.extend_from_slice(&(lumps.len() as u32).to_le_bytes());
        wad.extend_from_slice(&(12 + data.len() as u32).to_le_bytes());
        wad.extend(data);
        wad.extend(directory);
        wad
    }

    #[test]
    fn lumps_and_groups_are_found_by_name() {
        let bytes = pwad(&[
            ("MAP01", b""),
            ("THINGS", b"abc"),
            ("LINEDEFS", b"de"),
            ("PLAYPAL", b"p"),
        ]);
        let wad = Wad::from_bytes(Path::new("x.wad"), bytes).unwrap();
        assert_eq!(wad.lump("LINEDEFS"), Some(&b"de"[..]));
        let group = wad.group("MAP01", &["THINGS", "LINEDEFS"]).unwrap();
        assert_eq!(
            group,
            vec![("THINGS", &b"abc"[..]), ("LINEDEFS", &b"de"[..])]
        );
        assert!(wad.group("MAP02", &["THINGS"]).is_none());
    }

    #[test]
    fn a_damaged_file_is_refused_with_its_name_and_what_is_wrong() {
        let error = Wad::from_bytes(Path::new("bad.wad"), b"JUNKJUNKJUNK".to_vec()).unwrap_err();
        assert!(
            error.to_string().starts_with("bad.wad: not a WAD file"),
            "{error}"
        );
        let mut cut = pwad(&[("THINGS", b"abcdef")]);
        cut.truncate(cut.len() - 1);
        let error = Wad::from_bytes(Path::new("cut.wad"), cut).unwrap_err();
        assert!(error.to_string().contains("cut short"), "{error}");
    }
}
