//! Turns assets and numeric tables into Rust statics in OUT_DIR, and hands the ROM link its
//! linker script.
//!
//! Assets come from `assets/`, or from `PORTALCAST_ASSETS`: a user's directory of maps and
//! textures, or a Doom WAD (docs/MAP_FORMAT.md, "Doom maps"; `PORTALCAST_IWAD` names a PWAD's
//! IWAD). `PORTALCAST_MAPS` picks maps by name. A bad map or PNG stops the build with
//! `file:line:col: what is wrong, what to do`, a bad WAD with `file: lump …: what to do`, and
//! nothing is written.
use std::path::{Path, PathBuf};

/// The environment variable naming a user's asset directory, or a Doom WAD (`*.wad`).
const ASSETS_ENV: &str = "PORTALCAST_ASSETS";
/// The environment variable picking maps by name, comma-separated (`E1M1,E1M2`).
const MAPS_ENV: &str = "PORTALCAST_MAPS";
/// The environment variable naming the IWAD whose graphics a PWAD's maps use.
const IWAD_ENV: &str = "PORTALCAST_IWAD";

/// Compiles the asset directory or the Doom WAD (`*.wad`) at `path`, with only the maps `maps`
/// names if it names any; the errors one a line.
fn compile_assets(
    path: &Path,
    maps: Option<Vec<String>>,
) -> Result<portalcast_assets::Compiled, String> {
    let is_wad = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("wad"));
    if is_wad {
        let request = portalcast_assets::doom::WadRequest {
            wad: path.to_path_buf(),
            iwad: std::env::var_os(IWAD_ENV).map(PathBuf::from),
            maps,
        };
        portalcast_assets::doom::compile_wad(&request).map_err(|errors| {
            errors
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join("\n")
        })
    } else {
        match &maps {
            Some(maps) => portalcast_assets::compile_dir_maps(path, maps),
            None => portalcast_assets::compile_dir(path),
        }
        .map_err(|errors| errors.to_string())
    }
}

fn main() {
    let out_dir = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let manifest_dir = PathBuf::from(
        std::env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"),
    );

    portalcast_assets::numeric_tables::write_rust_tables(&out_dir).expect("writing numeric tables");
    println!("cargo:rerun-if-changed=crates/assets/src/numeric_tables.rs");

    println!("cargo:rerun-if-env-changed={ASSETS_ENV}");
    println!("cargo:rerun-if-env-changed={MAPS_ENV}");
    println!("cargo:rerun-if-env-changed={IWAD_ENV}");
    let assets_path = match std::env::var_os(ASSETS_ENV) {
        Some(path) => PathBuf::from(path),
        None => manifest_dir.join("assets"),
    };
    println!("cargo:rerun-if-changed={}", assets_path.display());
    let maps: Option<Vec<String>> = std::env::var(MAPS_ENV)
        .ok()
        .filter(|list| !list.trim().is_empty())
        .map(|list| {
            list.split(',')
                .map(|name| name.trim().to_string())
                .collect()
        });
    let compiled = match compile_assets(&assets_path, maps) {
        Ok(compiled) => compiled,
        Err(errors) => {
            // One line per problem, each naming the file and line (or the WAD, the map and the
            // lump), last so that they end the output; nothing was written.
            eprintln!(
                "portalcast: the assets in {} did not compile:",
                assets_path.display()
            );
            eprintln!("{errors}");
            std::process::exit(1);
        }
    };
    let report = compiled.import_report();
    let report_path = out_dir.join("import_report.txt");
    std::fs::write(&report_path, report.join("\n") + "\n").expect("writing the import report");
    if !report.is_empty() {
        println!(
            "cargo:warning=the import left {} things out or fitted them: see {}",
            report.len(),
            report_path.display()
        );
    }
    let files = compiled.write_to(&out_dir).unwrap_or_else(|error| {
        eprintln!(
            "portalcast: writing the compiled assets into {}: {error}",
            out_dir.display()
        );
        std::process::exit(1);
    });
    for file in files {
        println!("cargo:rerun-if-changed={}", file.display());
    }
    std::fs::write(out_dir.join("size_report.txt"), compiled.size_report())
        .expect("writing the size report");

    // Only the ROM binary links with our script; host builds (tests, tools) use the host linker.
    if std::env::var("CARGO_CFG_TARGET_OS").as_deref() == Ok("none") {
        let script = manifest_dir.join("linker.ld");
        println!("cargo:rustc-link-arg-bins=-T{}", script.display());
        println!("cargo:rerun-if-changed=linker.ld");
    }
    for asm in ["asm/span.s", "asm/column.s", "asm/flat.s"] {
        println!("cargo:rerun-if-changed={asm}");
    }
}
