//! Sprite sets: the files of `sprites/` grouped into the sets things name, each an animation of
//! one or more frames seen from one or eight rotations (`docs/MAP_FORMAT.md`, "Sprites").
//!
//! A set called NAME comes from one of these file schemes (never two):
//!
//! | files | frames | rotations |
//! |---|---|---|
//! | `NAME.png` | 1 | 1 |
//! | `NAME.1.png` … `NAME.K.png` | K ≥ 2 | 1 |
//! | `NAME.stripK.png` (K frames side by side) | K ≥ 2 | 1 |
//! | `NAME.r0.png` … `NAME.r7.png` | 1 | 8 |
//! | `NAME.1.r0.png` … `NAME.K.r7.png` | K ≥ 2 | 8 |
//!
//! [`scan`] checks the file names (every file, used or not: a misnamed file would otherwise be
//! silently ignored); [`load`] reads the images of a set some map uses and checks them.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use image::RgbaImage;

use crate::diag::{Diagnostic, Loc};
use crate::images::{self, SPRITE_ALPHA_OPAQUE};
use crate::SPRITES_DIR;

/// Most animation frames a set may have (`SpriteSet::frames` is a `u8`).
const FRAMES_MAX: u32 = u8::MAX as u32;
/// Rotations of a set that has them, 45° apart.
pub(crate) const ROTATIONS: u8 = 8;

/// What one file's name says it holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Part {
    /// `NAME.png`.
    Still,
    /// `NAME.K.png`: frame K (from 1).
    Frame(u32),
    /// `NAME.stripK.png`: K frames side by side.
    Strip(u32),
    /// `NAME.rR.png`: rotation R.
    Rotation(u8),
    /// `NAME.K.rR.png`: frame K seen from rotation R.
    FrameRotation(u32, u8),
}

/// The file schemes; a set's files all follow one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scheme {
    Still,
    Frames,
    Strip,
    Rotations,
    FramesRotations,
}

impl Part {
    fn scheme(self) -> Scheme {
        match self {
            Part::Still => Scheme::Still,
            Part::Frame(_) => Scheme::Frames,
            Part::Strip(_) => Scheme::Strip,
            Part::Rotation(_) => Scheme::Rotations,
            Part::FrameRotation(..) => Scheme::FramesRotations,
        }
    }

    /// The animation frame it holds (1 for a set without frames), for ordering.
    fn frame(self) -> u32 {
        match self {
            Part::Frame(k) | Part::FrameRotation(k, _) => k,
            _ => 1,
        }
    }

    /// The rotation it shows (0 for a set without rotations).
    fn rotation(self) -> u8 {
        match self {
            Part::Rotation(r) | Part::FrameRotation(_, r) => r,
            _ => 0,
        }
    }
}

impl Scheme {
    fn describe(self) -> &'static str {
        match self {
            Scheme::Still => "a still image (NAME.png)",
            Scheme::Frames => "an animation frame (NAME.K.png)",
            Scheme::Strip => "a strip of frames (NAME.stripK.png)",
            Scheme::Rotations => "a rotation (NAME.rR.png)",
            Scheme::FramesRotations => "a rotation of an animation frame (NAME.K.rR.png)",
        }
    }
}

/// One file of a set.
#[derive(Clone, Debug)]
pub(crate) struct SetFile {
    pub path: PathBuf,
    /// Frames side by side in the image (`NAME.stripK.png`), else 1.
    pub strip: u32,
}

/// A sprite set as its files give it.
#[derive(Clone, Debug)]
pub(crate) struct SetSource {
    /// The name things give.
    pub name: String,
    /// Animation frames (1: still).
    pub frames: u8,
    /// 1, or [`ROTATIONS`].
    pub rotations: u8,
    /// Its files in image order (frames major, rotations minor); empty if their names have
    /// errors ([`scan`] reports them).
    pub files: Vec<SetFile>,
    /// Every file of the set (`sprites/…`, in image order when the names are right), for the
    /// list of what is left out.
    pub file_names: Vec<String>,
}

impl SetSource {
    /// Images in the set: frames × rotations.
    pub fn image_count(&self) -> usize {
        usize::from(self.frames) * usize::from(self.rotations)
    }

    /// The name of image `index` of the set (frames major): the set's name, then `.K` (frame K,
    /// from 1) if it is animated, then `.rR` if it has rotations: the file name it has, or would
    /// have in separate files (a strip's frames).
    pub fn image_name(&self, index: usize) -> String {
        let rotations = usize::from(self.rotations);
        let mut name = self.name.clone();
        if self.frames > 1 {
            name.push_str(&format!(".{}", index / rotations + 1));
        }
        if self.rotations > 1 {
            name.push_str(&format!(".r{}", index % rotations));
        }
        name
    }
}

/// `sprites/FILE` for messages.
fn shown(path: &Path) -> String {
    let file = path.file_name().map_or_else(
        || path.display().to_string(),
        |f| f.to_string_lossy().into_owned(),
    );
    format!("{SPRITES_DIR}/{file}")
}

/// The message for a file name that follows no scheme.
fn no_scheme() -> String {
    "the file name follows none of the sprite file schemes; name a sprite set's images NAME.png (still), NAME.1.png, NAME.2.png, ... (animation frames), NAME.stripK.png (K frames side by side), NAME.r0.png ... NAME.r7.png (8 rotations) or NAME.1.r0.png ... NAME.K.r7.png (frames with rotations), see docs/MAP_FORMAT.md, \"Sprites\"".to_string()
}

/// Digits without a sign, as a number (saturating far beyond any limit), if `text` is digits.
fn digits(text: &str) -> Option<u32> {
    (!text.is_empty() && text.bytes().all(|b| b.is_ascii_digit()))
        .then(|| text.parse::<u32>().unwrap_or(u32::MAX))
}

/// A frame number: 1..=255, written without leading zeros.
fn frame_number(text: &str, stem: &str) -> Result<u32, String> {
    let k = digits(text).ok_or_else(no_scheme)?;
    if k == 0 {
        return Err(format!(
            "frame 0: animation frames are numbered from 1; renumber the frames of '{}' from 1",
            stem.split('.').next().unwrap_or(stem)
        ));
    }
    if text.starts_with('0') {
        return Err(format!(
            "frame number '{text}' has a leading zero; write it {}.png",
            stem.replacen(&format!(".{text}"), &format!(".{k}"), 1)
        ));
    }
    if k > FRAMES_MAX {
        return Err(format!(
            "frame {text} is beyond the {FRAMES_MAX} frames a sprite set may have; use fewer frames"
        ));
    }
    Ok(k)
}

/// A rotation `rR`, R in 0..=7; `None` if `text` is not `r` and digits.
fn rotation(text: &str) -> Option<Result<u8, String>> {
    let r = digits(text.strip_prefix('r')?)?;
    Some(if r < u32::from(ROTATIONS) {
        Ok(r as u8)
    } else {
        Err(format!(
            "rotation {text} does not exist; the eight rotations are r0 to r7 (docs/MAP_FORMAT.md, \"Sprites\")"
        ))
    })
}

/// The set a file belongs to and what it holds, from its name without the extension.
fn parse(stem: &str) -> Result<(&str, Part), String> {
    let mut pieces = stem.split('.');
    let name = pieces.next().unwrap_or_default();
    let rest: Vec<&str> = pieces.collect();
    if name.is_empty() {
        return Err(no_scheme());
    }
    let part = match rest.as_slice() {
        [] => Part::Still,
        [one] => {
            if let Some(count) = one.strip_prefix("strip").and_then(digits) {
                if count < 2 {
                    return Err(format!(
                        "a strip holds at least 2 frames side by side ({name}.stripK.png, K 2 or more); name a single image {name}.png"
                    ));
                }
                if count > FRAMES_MAX {
                    return Err(format!(
                        "a strip of {count} frames is more than the {FRAMES_MAX} a sprite set may have; use fewer frames"
                    ));
                }
                Part::Strip(count)
            } else if let Some(r) = rotation(one) {
                Part::Rotation(r?)
            } else {
                Part::Frame(frame_number(one, stem)?)
            }
        }
        [frame, turn] => {
            let r = rotation(turn).ok_or_else(no_scheme)??;
            Part::FrameRotation(frame_number(frame, stem)?, r)
        }
        _ => return Err(no_scheme()),
    };
    Ok((name, part))
}

/// Groups the PNGs of `sprites/` (by name without the extension; hidden ones, named `.…`, are
/// ignored) into sets, sorted by name.
/// Reports every file whose name follows no scheme, sets mixing schemes, frames with gaps or
/// missing rotations; a set with such errors keeps its name (so things naming it are not also
/// reported) but no files.
pub(crate) fn scan(files: &BTreeMap<String, PathBuf>) -> (Vec<SetSource>, Vec<Diagnostic>) {
    let mut errors = Vec::new();
    let mut by_name: BTreeMap<&str, Vec<(Part, &Path)>> = BTreeMap::new();
    // Hidden files (`._flame.png`, which macOS leaves on some drives) are no one's images.
    for (stem, path) in files.iter().filter(|(stem, _)| !stem.starts_with('.')) {
        match parse(stem) {
            Ok((name, part)) => by_name.entry(name).or_default().push((part, path)),
            Err(message) => errors.push(Diagnostic::new(path, (Loc::START, message))),
        }
    }
    let sets = by_name
        .into_iter()
        .map(|(name, parts)| assemble(name, parts, &mut errors))
        .collect();
    (sets, errors)
}

/// One set from its files (in name order), checking that they follow one scheme completely.
fn assemble(name: &str, mut parts: Vec<(Part, &Path)>, errors: &mut Vec<Diagnostic>) -> SetSource {
    let mut error = |path: &Path, message: String| {
        errors.push(Diagnostic::new(path, (Loc::START, message)));
    };
    let mut set = SetSource {
        name: name.to_string(),
        frames: 1,
        rotations: 1,
        files: Vec::new(),
        file_names: parts.iter().map(|(_, path)| shown(path)).collect(),
    };
    let (first, first_path) = parts[0];
    let scheme = first.scheme();
    let mut mixed = false;
    for (part, path) in &parts[1..] {
        if part.scheme() != scheme {
            mixed = true;
            error(
                path,
                format!(
                    "sprite set '{name}' mixes file schemes: this file is {} but {} is {}; give a set one scheme: remove or rename the files of the other",
                    part.scheme().describe(),
                    shown(first_path),
                    scheme.describe()
                ),
            );
        }
    }
    if mixed {
        return set;
    }
    parts.sort_by_key(|(part, _)| (part.frame(), part.rotation()));
    let mut complete = true;
    match scheme {
        Scheme::Still => {}
        Scheme::Strip => {
            for (_, path) in &parts[1..] {
                complete = false;
                error(
                    path,
                    format!(
                        "sprite set '{name}' already has the strip {}; give a set one strip: remove one of them",
                        shown(first_path)
                    ),
                );
            }
            if let Part::Strip(count) = first {
                set.frames = count as u8;
            }
        }
        Scheme::Frames | Scheme::FramesRotations => {
            let rotations = scheme == Scheme::FramesRotations;
            let mut numbers: Vec<u32> = parts.iter().map(|(part, _)| part.frame()).collect();
            numbers.dedup();
            let last = numbers.last().copied().unwrap_or(1);
            let missing: Vec<u32> = (1..last).filter(|k| !numbers.contains(k)).collect();
            let file_of = |k: String| {
                if rotations {
                    format!("{SPRITES_DIR}/{name}.{k}.r0.png ... {name}.{k}.r7.png")
                } else {
                    format!("{SPRITES_DIR}/{name}.{k}.png")
                }
            };
            if let Some(&gap) = missing.first() {
                complete = false;
                let after = parts
                    .iter()
                    .find(|(part, _)| part.frame() > gap)
                    .map_or(first_path, |(_, path)| path);
                let list = missing
                    .iter()
                    .map(u32::to_string)
                    .collect::<Vec<_>>()
                    .join(", ");
                let files = missing
                    .iter()
                    .map(|k| file_of(k.to_string()))
                    .collect::<Vec<_>>()
                    .join(", ");
                let frame = if missing.len() == 1 {
                    "frame"
                } else {
                    "frames"
                };
                error(
                    after,
                    format!(
                        "sprite set '{name}' has no {frame} {list} ({files}); number the frames from 1 without gaps: add the missing {frame} or renumber this one and those after it"
                    ),
                );
            } else if last < 2 {
                complete = false;
                let still = if rotations {
                    format!("rename its rotations {name}.r0.png ... {name}.r7.png")
                } else {
                    format!("rename this file {name}.png")
                };
                error(
                    first_path,
                    format!(
                        "sprite set '{name}' has only frame 1; an animation needs 2 frames or more: add {}, or {still} for a still set",
                        file_of("2".to_string())
                    ),
                );
            }
            if rotations {
                for k in &numbers {
                    let frame: Vec<&(Part, &Path)> = parts
                        .iter()
                        .filter(|(part, _)| part.frame() == *k)
                        .collect();
                    let prefix = format!("frame {k} of sprite set '{name}'");
                    complete &=
                        check_rotations(&frame, &prefix, &format!("{name}.{k}"), &mut error);
                }
                set.rotations = ROTATIONS;
            }
            set.frames = last as u8;
        }
        Scheme::Rotations => {
            let all: Vec<&(Part, &Path)> = parts.iter().collect();
            complete &= check_rotations(&all, &format!("sprite set '{name}'"), name, &mut error);
            set.rotations = ROTATIONS;
        }
    }
    if complete {
        set.file_names = parts.iter().map(|(_, path)| shown(path)).collect();
        set.files = parts
            .iter()
            .map(|(part, path)| SetFile {
                path: path.to_path_buf(),
                strip: match part {
                    Part::Strip(count) => *count,
                    _ => 1,
                },
            })
            .collect();
    }
    set
}

/// Reports rotations missing from one frame's files (sorted by rotation): `what` names the frame
/// or set, `stem` its files' names before `.rR`. Returns whether all eight are there.
fn check_rotations(
    files: &[&(Part, &Path)],
    what: &str,
    stem: &str,
    error: &mut impl FnMut(&Path, String),
) -> bool {
    let missing: Vec<u8> = (0..ROTATIONS)
        .filter(|r| !files.iter().any(|(part, _)| part.rotation() == *r))
        .collect();
    let Some((_, first)) = files.first() else {
        return true;
    };
    if missing.is_empty() {
        return true;
    }
    let rotations = missing
        .iter()
        .map(|r| format!("r{r}"))
        .collect::<Vec<_>>()
        .join(", ");
    let names = missing
        .iter()
        .map(|r| format!("{SPRITES_DIR}/{stem}.r{r}.png"))
        .collect::<Vec<_>>()
        .join(", ");
    error(
        first,
        format!(
            "{what} has no rotation {rotations} ({names}); a set with rotations needs all eight, r0 to r7: add the missing ones, or keep a single image for a set that looks the same from every side"
        ),
    );
    false
}

/// Reads the images of a set whose file names are right ([`SetSource::files`] not empty),
/// cutting strips into their frames, and checks them: each a valid sprite image, all the same
/// size. Returns them in set order (frames major, rotations minor), or `None` after reporting
/// what is wrong. Each file read is added to `files_read`.
pub(crate) fn load(
    set: &SetSource,
    files_read: &mut Vec<PathBuf>,
    errors: &mut Vec<Diagnostic>,
) -> Option<Vec<RgbaImage>> {
    let mut images = Vec::new();
    let mut ok = !set.files.is_empty();
    // The first file that loaded, and its images' size: the others must match it.
    let mut reference: Option<(&Path, (u32, u32))> = None;
    for file in &set.files {
        files_read.push(file.path.clone());
        let mut error = |loc: Loc, message: String| {
            errors.push(Diagnostic::new(&file.path, (loc, message)));
        };
        let image = match images::load(&file.path) {
            Ok(image) => image,
            Err((loc, message)) => {
                error(loc, message);
                ok = false;
                continue;
            }
        };
        let cut = if file.strip > 1 {
            cut_strip(&image, file.strip, &mut error)
        } else {
            let found = images::check_sprite(&image);
            let passed = found.is_empty();
            for (loc, message) in found {
                error(loc, message);
            }
            passed.then(|| vec![image])
        };
        let Some(cut) = cut else {
            ok = false;
            continue;
        };
        let size = cut[0].dimensions();
        match reference {
            None => reference = Some((&file.path, size)),
            Some((first, first_size)) if first_size != size => {
                ok = false;
                error(
                    Loc::START,
                    format!(
                        "the image is {}x{} but {} is {}x{}; all images of sprite set '{}' must be the same size: resize this one",
                        size.0,
                        size.1,
                        shown(first),
                        first_size.0,
                        first_size.1,
                        set.name
                    ),
                );
            }
            Some(_) => {}
        }
        images.extend(cut);
    }
    ok.then_some(images)
}

/// Cuts a strip of `count` frames side by side into its frames, checking them; `None` after
/// reporting what is wrong.
fn cut_strip(
    image: &RgbaImage,
    count: u32,
    error: &mut impl FnMut(Loc, String),
) -> Option<Vec<RgbaImage>> {
    let (width, height) = image.dimensions();
    if width % count != 0 {
        let frame = (width / count).max(1);
        error(
            Loc::START,
            format!(
                "the strip is {width} wide, which does not divide into its {count} frames (the name says {count}); make it {} wide ({count} frames of {frame}) or give the right count in the name",
                count * frame
            ),
        );
        return None;
    }
    let frame_width = width / count;
    let sides = images::check_sprite_sides(
        frame_width,
        height,
        &format!("each of the strip's {count} frames is {frame_width}x{height}: resize the strip"),
    );
    let mut ok = sides.is_empty();
    for (loc, message) in sides {
        error(loc, message);
    }
    let frames: Vec<RgbaImage> = (0..count)
        .map(|k| {
            image::imageops::crop_imm(image, k * frame_width, 0, frame_width, height).to_image()
        })
        .collect();
    for (k, frame) in (0..count).zip(&frames) {
        if !images::has_opaque_pixel(frame) {
            ok = false;
            error(
                Loc::new(1, k * frame_width + 1),
                format!(
                    "frame {} of the strip (columns {} to {}) is fully transparent (alpha below {SPRITE_ALPHA_OPAQUE}), so the thing would vanish on that frame; paint it with opaque pixels (alpha {SPRITE_ALPHA_OPAQUE} or more)",
                    k + 1,
                    k * frame_width,
                    (k + 1) * frame_width - 1
                ),
            );
        }
    }
    ok.then_some(frames)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_names_parse_into_their_parts() {
        assert_eq!(parse("torch"), Ok(("torch", Part::Still)));
        assert_eq!(parse("flame.12"), Ok(("flame", Part::Frame(12))));
        assert_eq!(parse("flame.strip4"), Ok(("flame", Part::Strip(4))));
        assert_eq!(parse("statue.r7"), Ok(("statue", Part::Rotation(7))));
        assert_eq!(
            parse("knight.3.r2"),
            Ok(("knight", Part::FrameRotation(3, 2)))
        );
        for bad in [
            "a.x", ".1", "a.1.2", "a.r1.r2", "a.strip", "a.stripx", "a.1.r", "a.b.c.d", "a.",
        ] {
            assert_eq!(parse(bad), Err(no_scheme()), "{bad}");
        }
        assert!(parse("a.0").is_err_and(|e| e.contains("numbered from 1")));
        assert!(parse("a.01").is_err_and(|e| e.contains("write it a.1.png")));
        assert!(parse("a.01.r3").is_err_and(|e| e.contains("write it a.1.r3.png")));
        assert!(parse("a.256").is_err_and(|e| e.contains("255 frames")));
        assert!(parse("a.r8").is_err_and(|e| e.contains("r0 to r7")));
        assert!(parse("a.strip1").is_err_and(|e| e.contains("at least 2 frames")));
        assert!(parse("a.strip0").is_err_and(|e| e.contains("at least 2 frames")));
        assert!(parse("a.strip999").is_err_and(|e| e.contains("255")));
    }

    #[test]
    fn image_names_follow_the_file_names() {
        let set = |frames, rotations| SetSource {
            name: "s".into(),
            frames,
            rotations,
            files: Vec::new(),
            file_names: Vec::new(),
        };
        assert_eq!(set(1, 1).image_name(0), "s");
        assert_eq!(set(4, 1).image_name(2), "s.3");
        assert_eq!(set(1, 8).image_name(5), "s.r5");
        assert_eq!(set(2, 8).image_name(9), "s.2.r1");
    }
}
