//! Turns assets and numeric tables into Rust statics in OUT_DIR, and hands the ROM link its
//! linker script.
use std::path::PathBuf;

fn main() {
    let out_dir = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let manifest_dir =
        PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR"));

    portalcast_assets::numeric_tables::write_rust_tables(&out_dir).expect("writing numeric tables");
    println!("cargo:rerun-if-changed=crates/assets/src/numeric_tables.rs");

    // Only the ROM binary links with our script; host builds (tests, tools) use the host linker.
    if std::env::var("CARGO_CFG_TARGET_OS").as_deref() == Ok("none") {
        let script = manifest_dir.join("linker.ld");
        println!("cargo:rustc-link-arg-bins=-T{}", script.display());
        println!("cargo:rerun-if-changed=linker.ld");
    }
    for asm in ["asm/span.s"] {
        println!("cargo:rerun-if-changed={asm}");
    }
}
