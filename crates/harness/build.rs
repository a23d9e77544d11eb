//! Compiles the C shim over libmgba and links the system library.
//!
//! libmgba-dev ships no pkg-config file on Debian 12, so pkg-config is only a bonus: the header
//! check below is what decides, and its failure is one line that says what to install.

use std::path::Path;
use std::process::Command;

const MISSING: &str =
    "libmgba-dev is not installed: run the README setup command (it does apt-get install libmgba-dev)";

fn main() {
    println!("cargo:rerun-if-changed=shim/mgba_shim.c");
    println!("cargo:rerun-if-changed=shim/mgba_shim.h");
    println!("cargo:rerun-if-changed=build.rs");

    let mut build = cc::Build::new();
    match pkg_config_flags() {
        Some((cflags, libs)) => {
            for flag in cflags {
                if let Some(dir) = flag.strip_prefix("-I") {
                    build.include(dir);
                } else {
                    build.flag(&flag);
                }
            }
            for flag in libs {
                if let Some(dir) = flag.strip_prefix("-L") {
                    println!("cargo:rustc-link-search=native={dir}");
                } else if let Some(lib) = flag.strip_prefix("-l") {
                    println!("cargo:rustc-link-lib={lib}");
                }
            }
        }
        None => {
            if !Path::new("/usr/include/mgba/core/core.h").exists() {
                // panic! would add a backtrace hint and quoting; a plain line reads better.
                eprintln!("error: {MISSING}");
                std::process::exit(1);
            }
            println!("cargo:rustc-link-lib=mgba");
        }
    }

    build
        .file("shim/mgba_shim.c")
        .include("shim")
        .std("gnu11") // the mGBA headers need POSIX names such as PATH_MAX
        .warnings(true)
        .extra_warnings(true)
        .compile("portalcast_mgba_shim");
}

/// `(cflags, libs)` from pkg-config when a libmgba.pc exists, `None` otherwise.
fn pkg_config_flags() -> Option<(Vec<String>, Vec<String>)> {
    let query = |arg: &str| -> Option<Vec<String>> {
        let out = Command::new("pkg-config")
            .args([arg, "libmgba"])
            .output()
            .ok()?;
        if !out.status.success() {
            return None;
        }
        let text = String::from_utf8(out.stdout).ok()?;
        Some(text.split_whitespace().map(str::to_owned).collect())
    };
    let libs = query("--libs")?;
    let cflags = query("--cflags")?;
    Some((cflags, libs))
}
