//! Turns the engine's numeric tables (reciprocals, trigonometry) into Rust statics in OUT_DIR.
//! A game's own assets are compiled by its build script (`portalcast_assets::Builder`), not here.
use std::path::PathBuf;

fn main() {
    let out_dir = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    portalcast_assets::numeric_tables::write_rust_tables(&out_dir).expect("writing numeric tables");
    println!("cargo:rerun-if-changed=crates/assets/src/numeric_tables.rs");
    for asm in ["asm/span.s", "asm/column.s", "asm/flat.s"] {
        println!("cargo:rerun-if-changed={asm}");
    }
}
