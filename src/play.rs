//! `cargo run` at the repository's top: starts `cargo play`, which builds the shipped ROM
//! (crates/rom) and opens it in mGBA when there is a display, or runs the demo headless in the
//! mGBA core with the log on stdout. A host program only; the ROM itself is crates/rom.

fn main() {
    // `cargo run` runs this with CARGO set to the cargo that built it.
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| env!("CARGO").into());
    let status = std::process::Command::new(&cargo)
        .arg("play")
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .status();
    match status {
        Ok(status) => std::process::exit(status.code().unwrap_or(1)),
        Err(error) => {
            eprintln!(
                "portalcast: could not start `{} play` ({error}); build the ROM with `cargo rom`",
                cargo.to_string_lossy()
            );
            std::process::exit(2);
        }
    }
}
