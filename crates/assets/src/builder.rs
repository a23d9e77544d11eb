//! What a game's `build.rs` calls: [`Builder`] compiles the game's asset directory (or a Doom
//! WAD) into its `OUT_DIR`, tells cargo when to rerun, and, when the game is built for the GBA,
//! hands its link the ROM set-up (the linker script and the divide-helper wrapping) that
//! portalcast's engine needs. The engine's own `build.rs` is one such caller.

use std::fmt;
use std::path::{Path, PathBuf};

use crate::diag::CompileErrors;
use crate::Compiled;

/// The ROM layout every portalcast game links with: IWRAM for the engine's hot code and its
/// overlays, VRAM for the code that runs from there, EWRAM for the texture copy. It names
/// sections, never functions, so it fits any game built on the engine.
pub const LINKER_SCRIPT: &str = include_str!("../../../linker.ld");

/// The file name [`Builder::build`] writes [`LINKER_SCRIPT`] to, in `OUT_DIR`.
pub const LINKER_SCRIPT_FILE: &str = "portalcast.ld";

/// compiler-builtins' division helpers that the link routes to the engine's own (asm/runtime.s):
/// theirs are Thumb returning with `pop {pc}`, which cannot return to the engine's ARM code on
/// the ARMv4T.
pub const WRAPPED_DIVISION_HELPERS: [&str; 4] = [
    "__aeabi_uidivmod",
    "__aeabi_idivmod",
    "__aeabi_uldivmod",
    "__aeabi_ldivmod",
];

/// The file `include!` brings the compiled assets in from: `include!(concat!(env!("OUT_DIR"),
/// "/assets.rs"))`.
pub const ASSETS_FILE: &str = "assets.rs";

/// Compiles a game's assets from its `build.rs`, with the same `file:line:col` errors as the
/// engine's own build:
///
/// ```no_run
/// // build.rs
/// fn main() -> Result<(), portalcast_assets::BuildError> {
///     portalcast_assets::Builder::new("assets").build()?;
///     Ok(())
/// }
/// ```
///
/// The game then brings the statics in with `include!(concat!(env!("OUT_DIR"), "/assets.rs"))`
/// (docs/GUIDE.md). A relative path is taken from the package's directory
/// (`CARGO_MANIFEST_DIR`), as cargo runs build scripts there.
#[derive(Clone, Debug)]
pub struct Builder {
    assets: PathBuf,
    maps: Option<Vec<String>>,
    iwad: Option<PathBuf>,
    rom_link: bool,
    out_dir: Option<PathBuf>,
}

impl Builder {
    /// A build of the asset directory, or Doom WAD (`*.wad`), at `assets`: every map in it.
    pub fn new(assets: impl Into<PathBuf>) -> Builder {
        Builder {
            assets: assets.into(),
            maps: None,
            iwad: None,
            rom_link: true,
            out_dir: None,
        }
    }

    /// Only the maps `names` names (file names without extension, or a WAD's map names, in any
    /// case), and only what they use; `None` keeps every map.
    pub fn maps(mut self, names: Option<Vec<String>>) -> Builder {
        self.maps = names;
        self
    }

    /// The IWAD whose graphics a PWAD's maps use (docs/MAP_FORMAT.md, "Doom maps").
    pub fn iwad(mut self, iwad: Option<PathBuf>) -> Builder {
        self.iwad = iwad;
        self
    }

    /// Whether [`Builder::build`] hands a GBA build's link the ROM set-up (on by default; a
    /// package whose binaries are not GBA ROMs turns it off). Host builds never get it.
    pub fn rom_link(mut self, on: bool) -> Builder {
        self.rom_link = on;
        self
    }

    /// Writes into `dir` instead of cargo's `OUT_DIR` (a tool's or a test's own directory).
    pub fn out_dir(mut self, dir: impl Into<PathBuf>) -> Builder {
        self.out_dir = Some(dir.into());
        self
    }

    /// Compiles the assets into `OUT_DIR` ([`ASSETS_FILE`] and its blobs), prints cargo's
    /// `rerun-if-changed` lines, a warning naming the import report if the import left things
    /// out, and for a GBA build the link arguments. Run from a build script (it reads cargo's
    /// variables). On a bad map, image or WAD nothing is written and the error lists every
    /// problem, one line each.
    pub fn build(self) -> Result<Compiled, BuildError> {
        let out_dir = match &self.out_dir {
            Some(dir) => dir.clone(),
            None => PathBuf::from(cargo_var("OUT_DIR")?),
        };
        let assets = match self.assets.is_absolute() {
            true => self.assets.clone(),
            false => PathBuf::from(cargo_var("CARGO_MANIFEST_DIR")?).join(&self.assets),
        };
        println!("cargo:rerun-if-changed={}", assets.display());
        let compiled = self.compile(&assets)?;
        let report = compiled.import_report();
        let report_path = out_dir.join("import_report.txt");
        write(&report_path, &(report.join("\n") + "\n"))?;
        if !report.is_empty() {
            println!(
                "cargo:warning=the import left {} things out or fitted them: see {}",
                report.len(),
                report_path.display()
            );
        }
        let files = compiled
            .write_to(&out_dir)
            .map_err(|error| BuildError::Write(out_dir.clone(), error.to_string()))?;
        for file in files {
            println!("cargo:rerun-if-changed={}", file.display());
        }
        write(&out_dir.join("size_report.txt"), &compiled.size_report())?;
        if self.rom_link && std::env::var("CARGO_CFG_TARGET_OS").as_deref() == Ok("none") {
            let script = out_dir.join(LINKER_SCRIPT_FILE);
            write(&script, LINKER_SCRIPT)?;
            for arg in rom_link_args(&script) {
                println!("cargo:rustc-link-arg={arg}");
            }
        }
        Ok(compiled)
    }

    fn compile(&self, assets: &Path) -> Result<Compiled, BuildError> {
        let is_wad = assets
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("wad"));
        let failed = |lines: String| BuildError::Assets(assets.to_path_buf(), lines);
        if is_wad {
            let request = crate::doom::WadRequest {
                wad: assets.to_path_buf(),
                iwad: self.iwad.clone(),
                maps: self.maps.clone(),
            };
            crate::doom::compile_wad(&request).map_err(|errors| {
                failed(
                    errors
                        .iter()
                        .map(ToString::to_string)
                        .collect::<Vec<_>>()
                        .join("\n"),
                )
            })
        } else {
            match &self.maps {
                Some(maps) => crate::compile_dir_maps(assets, maps),
                None => crate::compile_dir(assets),
            }
            .map_err(|errors: CompileErrors| failed(errors.to_string()))
        }
    }
}

/// The link arguments of a portalcast ROM whose linker script is at `script`: the script, and
/// the wrapping of [`WRAPPED_DIVISION_HELPERS`].
pub fn rom_link_args(script: &Path) -> Vec<String> {
    std::iter::once(format!("-T{}", script.display()))
        .chain(
            WRAPPED_DIVISION_HELPERS
                .iter()
                .map(|helper| format!("--wrap={helper}")),
        )
        .collect()
}

fn cargo_var(name: &'static str) -> Result<String, BuildError> {
    std::env::var(name).map_err(|_| BuildError::NotInBuildScript(name))
}

fn write(path: &Path, text: &str) -> Result<(), BuildError> {
    std::fs::write(path, text)
        .map_err(|error| BuildError::Write(path.to_path_buf(), error.to_string()))
}

/// Why [`Builder::build`] stopped. Its `Debug` is its `Display`, so a build script's
/// `fn main() -> Result<(), BuildError>` ends with the located errors and nothing else.
pub enum BuildError {
    /// The assets did not compile: the directory or WAD, and the errors, one a line.
    Assets(PathBuf, String),
    /// A file could not be written.
    Write(PathBuf, String),
    /// A variable cargo sets for build scripts is missing: not run by cargo as a build script.
    NotInBuildScript(&'static str),
}

impl fmt::Display for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BuildError::Assets(path, lines) => write!(
                f,
                "portalcast: the assets in {} did not compile:\n{lines}",
                path.display()
            ),
            BuildError::Write(path, error) => {
                write!(f, "portalcast: writing {}: {error}", path.display())
            }
            BuildError::NotInBuildScript(name) => write!(
                f,
                "portalcast: {name} is unset: call Builder::build from a build script (build.rs), which cargo runs with it set"
            ),
        }
    }
}

impl fmt::Debug for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

impl std::error::Error for BuildError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_linker_script_names_sections_not_functions() {
        assert!(LINKER_SCRIPT.contains("ENTRY(__start)"));
        assert!(!LINKER_SCRIPT.contains("portalcast::"));
        assert!(!LINKER_SCRIPT.contains("_ZN"));
    }

    #[test]
    fn rom_link_args_wrap_the_four_helpers_after_the_script() {
        let args = rom_link_args(Path::new("/out/portalcast.ld"));
        assert_eq!(args[0], "-T/out/portalcast.ld");
        assert_eq!(args.len(), 5);
        assert!(args[1..]
            .iter()
            .all(|arg| arg.starts_with("--wrap=__aeabi_")));
    }

    #[test]
    fn outside_a_build_script_the_error_says_where_to_call_it() {
        let error = Builder::new("assets").build().unwrap_err();
        assert!(error.to_string().contains("build script"), "{error}");
        assert_eq!(format!("{error:?}"), error.to_string());
    }
}
