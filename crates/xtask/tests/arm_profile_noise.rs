//! `cargo rom` hides the warnings the ARM profile's `-thumb-mode` flag makes on every build and
//! shows everything else (issue 16, defect 5).

use portalcast_xtask::ArmProfileNoise;

/// What cargo printed on a rebuild of the engine (nightly of 2026-11), with a real warning of
/// the engine's own and its count in between.
const OUTPUT: &str = "   Compiling portalcast v0.1.0 (/work/main)
warning: unknown and unstable feature specified for `-Ctarget-feature`: `thumb-mode`
  |
  = note: it is still passed through to the codegen backend, but use of this feature might be unsound and the behavior of this feature can change in the future
  = help: consider filing a feature request

'-thumb-mode' is not a recognized feature for this target (ignoring feature)
'-thumb-mode' is not a recognized feature for this target (ignoring feature)
warning: `portalcast` (build script) generated 1 warning
warning: unstable feature specified for `-Ctarget-feature`: `thumb-mode`
  |
  = note: this feature is not stably supported; its behavior can change in the future

warning: unused variable: `x`
 --> src/lib.rs:1:5
  |

warning: `portalcast` (lib) generated 2 warnings
warning: `portalcast` (bin \"portalcast\") generated 1 warning (1 duplicate)
    Finished `rom` profile [optimized + debuginfo] target(s) in 10.27s";

#[test]
fn only_the_profile_flag_s_warnings_are_hidden() {
    let mut noise = ArmProfileNoise::default();
    let shown: Vec<&str> = OUTPUT.lines().filter(|line| noise.keep(line)).collect();
    assert_eq!(
        shown,
        [
            "   Compiling portalcast v0.1.0 (/work/main)",
            "warning: unused variable: `x`",
            " --> src/lib.rs:1:5",
            "  |",
            "",
            "warning: `portalcast` (lib) generated 2 warnings",
            "    Finished `rom` profile [optimized + debuginfo] target(s) in 10.27s",
        ]
    );
}
