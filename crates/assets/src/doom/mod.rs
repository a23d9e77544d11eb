//! Doom-format maps (issue 19): WAD files, a map's lumps, GL nodes from the node builder, and the
//! convex cells they cut the map into. This is the importer's first part: it reads and checks a
//! map and measures what a conversion meets; turning the cells into portalcast's map tables (and
//! the palette, textures and things) is still to come.

mod cells;
mod gl;
mod graphics;
mod level;
mod wad;

use std::fmt;
use std::path::{Path, PathBuf};

pub use cells::{cells, reflex_depth, Cell, CellError, CellWall};
pub use gl::{build_gwa, FixedVertex, GlNodes, GlSeg, NODE_BUILDER};
pub use graphics::{
    colormaps, flat, palette, patch, IndexedImage, Patch, TextureDef, TexturePatch, Textures,
};
pub use level::{
    is_map_name, DoomLevel, DoomSector, DoomThing, DoomVertex, Linedef, Sidedef, NONE,
};
pub use wad::Wad;

/// What is wrong with a WAD or a map in it, and what to do: `file: lump: message`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DoomError {
    /// The file at fault.
    pub path: PathBuf,
    /// The lump at fault (`E1M1/LINEDEFS`), if one is.
    pub lump: Option<String>,
    /// What is wrong and what to do, one line.
    pub message: String,
}

impl DoomError {
    pub(crate) fn new(path: &Path, lump: Option<&str>, message: String) -> DoomError {
        DoomError {
            path: path.to_path_buf(),
            lump: lump.map(str::to_string),
            message,
        }
    }
}

impl fmt::Display for DoomError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: ", self.path.display())?;
        if let Some(lump) = &self.lump {
            write!(f, "lump {lump}: ")?;
        }
        f.write_str(&self.message)
    }
}

impl std::error::Error for DoomError {}
