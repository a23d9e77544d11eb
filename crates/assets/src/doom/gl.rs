//! GL nodes: the convex subsectors a node builder cuts a Doom map into, read from the `GL_`
//! lumps glbsp writes (the GL-Nodes specification, versions 2 and 5: vertices in 16.16 units;
//! segs and subsectors, with each seg's partner on the other side of its line).
//!
//! The builder is Debian's `glbsp` (2.24): its default GL nodes are version 2, and it moves to
//! version 5 by itself where a map outgrows them. zdbsp is the other Debian builder, but its x86-64
//! build writes malformed version-5 nodes (issue 19's facts).

use std::path::{Path, PathBuf};
use std::process::Command;

use super::level::DoomVertex;
use super::wad::{member, Wad};
use super::DoomError;

/// The node builder's program name.
pub const NODE_BUILDER: &str = "glbsp";

/// A vertex in 16.16 map units.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FixedVertex {
    /// East, 16.16.
    pub x: i32,
    /// North, 16.16.
    pub y: i32,
}

/// A seg: a piece of a linedef (or a mini-seg along a partition line, with no linedef) bounding
/// one subsector.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GlSeg {
    /// Where it starts, going round its subsector.
    pub start: FixedVertex,
    /// Where it ends: the next seg's start.
    pub end: FixedVertex,
    /// The linedef it lies on, `None` for a mini-seg.
    pub linedef: Option<u16>,
    /// Which side of the linedef it is on: 0 right, 1 left.
    pub side: u16,
    /// The seg on the other side of the same line, bounding the neighbouring subsector, if any.
    pub partner: Option<u32>,
}

/// One map's GL nodes: its segs, and its subsectors as runs of them.
#[derive(Clone, Debug)]
pub struct GlNodes {
    /// `GL_SEGS`.
    pub segs: Vec<GlSeg>,
    /// Each subsector's segs: `first..first + count` of [`GlNodes::segs`], in order round it.
    pub subsectors: Vec<(u32, u32)>,
}

fn half(bytes: &[u8], at: usize) -> u32 {
    u32::from(u16::from_le_bytes([bytes[at], bytes[at + 1]]))
}

fn word(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
}

/// Runs the node builder on `wad`, writing its GL lumps into a GWA file under `scratch` (made if
/// missing), and returns that file's path.
pub fn build_gwa(wad: &Path, scratch: &Path) -> Result<PathBuf, DoomError> {
    std::fs::create_dir_all(scratch).map_err(|error| {
        DoomError::new(
            scratch,
            None,
            format!("cannot make the directory ({error})"),
        )
    })?;
    let stem = wad
        .file_stem()
        .map_or_else(|| "map".into(), |stem| stem.to_string_lossy());
    let gwa = scratch.join(format!("{stem}.gwa"));
    let output = Command::new(NODE_BUILDER)
        .args(["-q", "-xp"])
        .arg(wad)
        .arg("-o")
        .arg(&gwa)
        .output()
        .map_err(|error| {
            DoomError::new(
                wad,
                None,
                format!("cannot run the node builder `{NODE_BUILDER}` ({error}): install it (`apt-get install glbsp`; `cargo xtest`'s setup does)"),
            )
        })?;
    if !output.status.success() || !gwa.is_file() {
        let said = String::from_utf8_lossy(&output.stdout);
        let last = said
            .lines()
            .chain(String::from_utf8_lossy(&output.stderr).lines())
            .rfind(|line| !line.trim().is_empty())
            .unwrap_or("no message")
            .trim()
            .to_string();
        return Err(DoomError::new(
            wad,
            None,
            format!(
                "the node builder `{NODE_BUILDER}` failed ({}): {last}",
                output.status
            ),
        ));
    }
    Ok(gwa)
}

impl GlNodes {
    /// Map `name`'s GL nodes from `gwa` (glbsp's output), with `vertices` the map's own vertices
    /// (segs name either those or the GL lump's new ones).
    pub fn read(gwa: &Wad, name: &str, vertices: &[DoomVertex]) -> Result<GlNodes, DoomError> {
        let marker = format!("GL_{}", name.to_ascii_uppercase());
        let lumps = gwa
            .group(
                &marker,
                &["GL_VERT", "GL_SEGS", "GL_SSECT", "GL_NODES", "GL_PVS"],
            )
            .ok_or_else(|| {
                DoomError::new(
                    gwa.path(),
                    None,
                    format!("has no {marker}: the node builder did not build map {name}"),
                )
            })?;
        let lump = |wanted: &str| {
            member(
                gwa,
                &lumps,
                &marker,
                wanted,
                "the node builder's output is incomplete",
            )
        };
        let fail = |wanted: &str, message: String| {
            DoomError::new(gwa.path(), Some(&format!("{marker}/{wanted}")), message)
        };
        let verts = lump("GL_VERT")?;
        let version = match verts.get(..4) {
            Some(b"gNd2") => 2,
            Some(b"gNd5") => 5,
            _ => {
                return Err(fail(
                    "GL_VERT",
                    "is not GL nodes version 2 or 5 (glbsp's): rebuild them with glbsp".to_string(),
                ))
            }
        };
        if !(verts.len() - 4).is_multiple_of(8) {
            return Err(fail(
                "GL_VERT",
                format!("{} bytes is not whole vertices", verts.len()),
            ));
        }
        let gl_vertices: Vec<FixedVertex> = verts[4..]
            .chunks_exact(8)
            .map(|r| FixedVertex {
                x: word(r, 0) as i32,
                y: word(r, 4) as i32,
            })
            .collect();
        let (gl_flag, seg_size) = if version == 5 {
            (1u32 << 31, 16)
        } else {
            (1u32 << 15, 10)
        };
        let vertex = |index: u32| -> Option<FixedVertex> {
            if index & gl_flag != 0 {
                gl_vertices.get((index & !gl_flag) as usize).copied()
            } else {
                vertices.get(index as usize).map(|v| FixedVertex {
                    x: i32::from(v.x) << 16,
                    y: i32::from(v.y) << 16,
                })
            }
        };
        let segs_bytes = lump("GL_SEGS")?;
        if !segs_bytes.len().is_multiple_of(seg_size) {
            return Err(fail(
                "GL_SEGS",
                format!("{} bytes is not whole segs", segs_bytes.len()),
            ));
        }
        let mut segs = Vec::with_capacity(segs_bytes.len() / seg_size);
        for (index, r) in segs_bytes.chunks_exact(seg_size).enumerate() {
            let (start, end, linedef, side, partner) = if version == 5 {
                (word(r, 0), word(r, 4), half(r, 8), half(r, 10), word(r, 12))
            } else {
                let partner = half(r, 8);
                (
                    half(r, 0),
                    half(r, 2),
                    half(r, 4),
                    half(r, 6),
                    if partner == 0xFFFF { u32::MAX } else { partner },
                )
            };
            let (Some(start), Some(end)) = (vertex(start), vertex(end)) else {
                return Err(fail(
                    "GL_SEGS",
                    format!("seg {index} names a vertex that does not exist"),
                ));
            };
            segs.push(GlSeg {
                start,
                end,
                linedef: (linedef != 0xFFFF).then_some(linedef as u16),
                side: side as u16,
                partner: (partner != u32::MAX).then_some(partner),
            });
        }
        let ssect = lump("GL_SSECT")?;
        let size = if version == 5 { 8 } else { 4 };
        if !ssect.len().is_multiple_of(size) {
            return Err(fail(
                "GL_SSECT",
                format!("{} bytes is not whole subsectors", ssect.len()),
            ));
        }
        let subsectors: Vec<(u32, u32)> = ssect
            .chunks_exact(size)
            .map(|r| {
                if version == 5 {
                    (word(r, 4), word(r, 0))
                } else {
                    (half(r, 2), half(r, 0))
                }
            })
            .collect();
        for (index, &(first, count)) in subsectors.iter().enumerate() {
            if count < 3 || (first + count) as usize > segs.len() {
                return Err(fail(
                    "GL_SSECT",
                    format!("subsector {index} has segs {first}..{} of {}: the node builder's output is damaged", first + count, segs.len()),
                ));
            }
        }
        if let Some(index) = segs
            .iter()
            .position(|seg| seg.partner.is_some_and(|p| p as usize >= segs.len()))
        {
            return Err(fail(
                "GL_SEGS",
                format!("seg {index}'s partner does not exist"),
            ));
        }
        Ok(GlNodes { segs, subsectors })
    }
}
