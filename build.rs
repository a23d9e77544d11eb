//! Turns assets and numeric tables into Rust statics in OUT_DIR, and hands the ROM link its
//! linker script, through the same [`portalcast_assets::Builder`] a game's build script calls.
//!
//! Assets come from `assets/`, or from `PORTALCAST_ASSETS`: a user's directory of maps and
//! textures, or a Doom WAD (docs/MAP_FORMAT.md, "Doom maps"; `PORTALCAST_IWAD` names a PWAD's
//! IWAD). `PORTALCAST_MAPS` picks maps by name. A bad map or PNG stops the build with
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
    let out_dir = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    portalcast_assets::numeric_tables::write_rust_tables(&out_dir).expect("writing numeric tables");
    println!("cargo:rerun-if-changed=crates/assets/src/numeric_tables.rs");

    println!("cargo:rerun-if-env-changed={ASSETS_ENV}");
    println!("cargo:rerun-if-env-changed={MAPS_ENV}");
    println!("cargo:rerun-if-env-changed={IWAD_ENV}");
    let assets =
        std::env::var_os(ASSETS_ENV).map_or_else(|| PathBuf::from("assets"), PathBuf::from);
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
    for asm in ["asm/span.s", "asm/column.s", "asm/flat.s"] {
        println!("cargo:rerun-if-changed={asm}");
    }
}
