//! Compiles the ROM's assets into OUT_DIR and hands its link the linker script, through the same
//! [`portalcast_assets::Builder`] a game's build script calls.
//!
//! Assets come from the repository's `assets/`, or from `PORTALCAST_ASSETS`: a user's directory
//! of maps and textures, or a Doom WAD (docs/MAP_FORMAT.md, "Doom maps"; `PORTALCAST_IWAD` names
//! a PWAD's IWAD). `PORTALCAST_MAPS` picks maps by name. A bad map or PNG stops the build with
//! `file:line:col: what is wrong, what to do`, a bad WAD with `file: lump …: what to do`, and
//! nothing is written.
use std::path::PathBuf;

/// The environment variable naming a user's asset directory, or a Doom WAD (`*.wad`).
const ASSETS_ENV: &str = "PORTALCAST_ASSETS";
/// The environment variable picking maps by name, comma-separated (`E1M1,E1M2`).
const MAPS_ENV: &str = "PORTALCAST_MAPS";
/// The environment variable naming the IWAD whose graphics a PWAD's maps use.
const IWAD_ENV: &str = "PORTALCAST_IWAD";

fn main() {
    println!("cargo:rerun-if-env-changed={ASSETS_ENV}");
    println!("cargo:rerun-if-env-changed={MAPS_ENV}");
    println!("cargo:rerun-if-env-changed={IWAD_ENV}");
    // Relative paths are the repository's, as `cargo rom` is run there (cargo runs this script
    // in crates/rom).
    let assets = PathBuf::from("../..")
        .join(std::env::var_os(ASSETS_ENV).map_or_else(|| PathBuf::from("assets"), PathBuf::from));
    let maps: Option<Vec<String>> = std::env::var(MAPS_ENV)
        .ok()
        .filter(|list| !list.trim().is_empty())
        .map(|list| {
            list.split(',')
                .map(|name| name.trim().to_string())
                .collect()
        });
    let built = portalcast_assets::Builder::new(assets)
        .maps(maps)
        .iwad(std::env::var_os(IWAD_ENV).map(PathBuf::from))
        .build();
    if let Err(error) = built {
        // One line per problem, each naming the file and line (or the WAD, the map and the
        // lump), last so that they end the output; nothing was written.
        eprintln!("{error}");
        std::process::exit(1);
    }
}
