//! Freedoom's maps in a ROM of their own (issue 19): what
//! `PORTALCAST_ASSETS=/usr/share/games/doom/freedoom1.wad PORTALCAST_MAPS=… cargo rom` builds,
//! for the emulator tests and the bench (`target/rom-freedoom`, apart from the shipped ROM's
//! target so that neither rebuilds the other).

use std::path::{Path, PathBuf};

use crate::{TaskError, TaskResult};

/// Where Debian's `freedoom` package puts its WADs (`portalcast_assets::doom::FREEDOOM_DIR`).
pub const FREEDOOM_DIR: &str = "/usr/share/games/doom";
/// Freedoom Phase 1's IWAD.
pub const FREEDOOM1: &str = "freedoom1.wad";
/// The maps the tests and the bench build: E1M1 (GBADoom's anchor) and two more of Phase 1,
/// the second episode's opener and E1M3, a larger map.
pub const MAPS: [&str; 3] = ["E1M1", "E1M3", "E2M1"];

/// Freedoom Phase 1's WAD, or an error saying how to install it.
pub fn freedoom1_wad() -> TaskResult<PathBuf> {
    let wad = Path::new(FREEDOOM_DIR).join(FREEDOOM1);
    if wad.is_file() {
        Ok(wad)
    } else {
        Err(TaskError(format!(
            "{} is missing: install Debian's freedoom package (`cargo xtest` does: apt-get install freedoom)",
            wad.display()
        )))
    }
}

/// The ROM's target directory and `.gba`.
pub fn rom_paths() -> (PathBuf, PathBuf) {
    let target = crate::workspace_root().join("target").join("rom-freedoom");
    let gba = target.join("freedoom.gba");
    (target, gba)
}

/// Builds the ROM of Freedoom's [`MAPS`] and returns its `.gba`.
pub fn build_freedoom_rom() -> TaskResult<PathBuf> {
    let wad = freedoom1_wad()?;
    let (target, gba) = rom_paths();
    std::fs::create_dir_all(&target)
        .map_err(|error| TaskError(format!("{}: {error}", target.display())))?;
    crate::build_rom_with_maps(&wad, Some(&MAPS.join(",")), &target, &gba)?;
    Ok(gba)
}

/// The small map drawn in Eureka (`assets/eureka/`, issue 19): a PWAD whose textures come from
/// Freedoom's Phase 2 IWAD, found by its map name as `PORTALCAST_IWAD`'s default does.
pub const EUREKA_WAD: &str = "assets/eureka/eureka-demo.wad";

/// Builds the ROM of the Eureka map (`target/rom-eureka/eureka-demo.gba`) and returns it.
pub fn build_eureka_rom() -> TaskResult<PathBuf> {
    let wad = crate::workspace_root().join(EUREKA_WAD);
    let target = crate::workspace_root().join("target").join("rom-eureka");
    let gba = target.join("eureka-demo.gba");
    std::fs::create_dir_all(&target)
        .map_err(|error| TaskError(format!("{}: {error}", target.display())))?;
    crate::build_rom_with_maps(&wad, None, &target, &gba)?;
    Ok(gba)
}
