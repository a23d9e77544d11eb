//! Turns assets and numeric tables into Rust statics in OUT_DIR, and hands the ROM link its
//! linker script.
//!
//! Assets come from `assets/`, or from the directory in `PORTALCAST_ASSETS` (a user's maps and
//! textures). A bad map or PNG stops the build with `file:line:col: what is wrong, what to do`
//! and nothing is written.
use std::path::PathBuf;

/// The environment variable naming a user's asset directory.
const ASSETS_ENV: &str = "PORTALCAST_ASSETS";

fn main() {
    let out_dir = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let manifest_dir = PathBuf::from(
        std::env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"),
    );

    portalcast_assets::numeric_tables::write_rust_tables(&out_dir).expect("writing numeric tables");
    println!("cargo:rerun-if-changed=crates/assets/src/numeric_tables.rs");

    println!("cargo:rerun-if-env-changed={ASSETS_ENV}");
    let assets_dir = match std::env::var_os(ASSETS_ENV) {
        Some(dir) => PathBuf::from(dir),
        None => manifest_dir.join("assets"),
    };
    println!("cargo:rerun-if-changed={}", assets_dir.display());
    let compiled = match portalcast_assets::compile_dir(&assets_dir) {
        Ok(compiled) => compiled,
        Err(errors) => {
            // One line per problem, each naming the file and line, last so that they end the
            // output; nothing was written.
            eprintln!(
                "portalcast: the assets in {} did not compile:",
                assets_dir.display()
            );
            eprintln!("{errors}");
            std::process::exit(1);
        }
    };
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
