//! Doom-format maps (issue 19): WAD files, a map's lumps, its pictures in Doom's palette, and two
//! ways to cut its sectors into the convex rooms portalcast draws.
//!
//! - [`cells()`]: the GL subsectors of Debian's glbsp ([`build_gwa`], [`GlNodes`]). Its
//!   partition lines cross linedefs at fractions no binary grid holds (a third of a unit on
//!   Freedoom's E1M1), so its cells bend a little on any fixed-point grid ([`reflex_depth`]:
//!   on E1M1 by up to 0.0029 units in 24.8, 0.79 in whole units, where two walls vanish).
//! - [`partition()`]: the importer's own, with no new vertex: every corner a map vertex in whole
//!   units, every piece exactly convex, each two-sided linedef one edge of one piece on each
//!   side. It cuts all 68 of Freedoom's maps (tests/doom_freedoom.rs), into fewer pieces than
//!   the node builder's subsectors where both were counted (E1M1: 434 against 509). This is the
//!   partition the importer builds on.
//!
//! [`compile_wad`] builds a ROM's asset set from a WAD (`PORTALCAST_ASSETS=….wad`, issue 19):
//! the pieces mapped as the module `convert` says and checked by the map compiler itself, then
//! the textures, flats and sky they use drawn from the WAD ([`Textures`], [`flat`]) in Doom's
//! palette ([`DoomPalette`]: its black, index 0, moved off the transparent index), with Doom's
//! `COLORMAP` as portalcast's light rows; what it cannot map yet goes to the import report.
//! [`compiler_findings`] runs the compiler alone (with or without stand-ins for what is not
//! mapped yet), for the tests over all of Freedoom's maps.
//!
//! Still to come (issue 19): manual doors cut into several pieces, masked middle textures, and
//! views deeper than the walk's 256 portals.

mod cells;
mod colours;
mod convert;
mod gl;
mod graphics;
mod import;
mod level;
mod movers;
mod partition;
mod things;
mod wad;

use std::fmt;
use std::path::{Path, PathBuf};

pub use cells::{cells, reflex_depth, Cell, CellError};
pub use colours::DoomPalette;
pub use convert::{compiler_findings, import_report, StandIns, STAND_IN_TEXTURE};
pub use gl::{build_gwa, FixedVertex, GlNodes, GlSeg, NODE_BUILDER};
pub use graphics::{
    colormaps, flat, palette, patch, IndexedImage, Patch, TextureDef, TexturePatch, Textures,
};
pub use import::{compile_wad, default_iwad, WadRequest, FREEDOOM_DIR};
pub use level::{
    is_map_name, DoomLevel, DoomSector, DoomThing, DoomVertex, Linedef, Sidedef, NONE,
};
pub use partition::{partition, PartitionError, Piece, PieceWall};
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
