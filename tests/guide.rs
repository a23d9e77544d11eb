//! docs/GUIDE.md, followed exactly by a new user would: in a fresh directory outside this
//! repository, its files written as shown (the clone's path put where it says
//! `/path/to/portalcast`) and its `sh` blocks run in order, `cargo run --release` last. The game
//! must build into a `.gba` that runs in the real mGBA core (headless, as without a display) and
//! draws its room. And the guide's game is `examples/minimal`, file for file.

use std::path::{Path, PathBuf};
use std::process::Command;

/// What the guide says to do, in its order.
enum Step {
    /// Write `contents` to the file at this path (relative to the game's directory).
    File(String, String),
    /// Run this shell script in the game's directory.
    Shell(String),
}

/// The placeholder the guide uses for the clone's path.
const PLACEHOLDER: &str = "/path/to/portalcast";

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn guide() -> String {
    std::fs::read_to_string(repo().join("docs/GUIDE.md")).expect("reading docs/GUIDE.md")
}

/// The guide's steps: a fenced block right after a line `**`PATH`**…` is that file; an `sh`
/// block is a script to run; other blocks (`console`: what to install) are not run.
fn steps(guide: &str) -> Vec<Step> {
    let lines: Vec<&str> = guide.lines().collect();
    let mut steps = Vec::new();
    let mut index = 0;
    while index < lines.len() {
        let Some(info) = lines[index].strip_prefix("```") else {
            index += 1;
            continue;
        };
        let end = (index + 1..lines.len())
            .find(|&at| lines[at] == "```")
            .unwrap_or_else(|| panic!("GUIDE.md:{}: a block that never ends", index + 1));
        let body: String = lines[index + 1..end]
            .iter()
            .map(|line| format!("{line}\n"))
            .collect();
        // The paragraph that introduces the block starts with the file's name in bold.
        let paragraph_start = (0..index)
            .rev()
            .take_while(|&at| !lines[at].is_empty() || at + 1 == index)
            .last()
            .unwrap_or(index);
        let file = lines[paragraph_start]
            .strip_prefix("**`")
            .and_then(|rest| rest.split_once("`**"))
            .map(|(path, _)| path.to_string());
        match (file, info) {
            (Some(path), _) => steps.push(Step::File(path, body)),
            (None, "sh") => steps.push(Step::Shell(body)),
            _ => {}
        }
        index = end + 1;
    }
    steps
}

#[test]
fn the_guide_s_game_is_examples_minimal() {
    let example = repo().join("examples/minimal");
    let mut files = 0;
    for step in steps(&guide()) {
        let Step::File(path, contents) = step else {
            continue;
        };
        let shipped = std::fs::read_to_string(example.join(&path))
            .unwrap_or_else(|error| panic!("examples/minimal/{path}: {error}"));
        // The example sits in the repository: its paths are relative, its name its own.
        let relative = contents
            .replace(PLACEHOLDER, "../..")
            .replace("name = \"mygame\"", "name = \"minimal\"");
        let shipped_body: String = shipped
            .lines()
            .skip_while(|line| path == "Cargo.toml" && line.starts_with('#'))
            .map(|line| format!("{line}\n"))
            .collect();
        assert_eq!(
            relative, shipped_body,
            "docs/GUIDE.md's {path} differs from examples/minimal/{path}"
        );
        files += 1;
    }
    assert_eq!(files, 6, "the guide shows the example's six files");
}

#[test]
fn a_game_made_by_following_the_guide_builds_and_runs_in_mgba() {
    let base = std::env::temp_dir().join(format!("portalcast-guide-{}", std::process::id()));
    let game = base.join("mygame");
    let _ = std::fs::remove_dir_all(&base);
    std::fs::create_dir_all(&game).expect("making the game's directory");
    let root = repo();
    let root = root.to_str().expect("a UTF-8 path");
    let mut last_output = String::new();
    for step in steps(&guide()) {
        match step {
            Step::File(path, contents) => {
                let path = game.join(path);
                std::fs::create_dir_all(path.parent().unwrap()).unwrap();
                std::fs::write(&path, contents.replace(PLACEHOLDER, root)).unwrap();
            }
            Step::Shell(script) => {
                let output = shell(&game, &script.replace(PLACEHOLDER, root));
                last_output = output;
            }
        }
    }
    let gba = game.join("target/thumbv4t-none-eabi/release/mygame.gba");
    assert!(gba.is_file(), "no {}: {last_output}", gba.display());
    let frames: Vec<&str> = last_output
        .lines()
        .filter(|line| line.starts_with("game frame="))
        .collect();
    assert!(
        frames.len() >= 3,
        "the game's log lines, one a second over 240 frames: {last_output}"
    );
    assert!(
        frames.iter().all(|line| line.contains(" sector=0 ")),
        "{frames:?}"
    );
    let png = game.join("target/thumbv4t-none-eabi/release/frames/frame-000240.png");
    let image = image::open(&png)
        .unwrap_or_else(|error| panic!("{}: {error}", png.display()))
        .to_rgb8();
    let colours: std::collections::BTreeSet<[u8; 3]> =
        image.pixels().map(|pixel| pixel.0).collect();
    assert!(
        colours.len() >= 16,
        "the last frame shows a textured room, not {} colours: {}",
        colours.len(),
        png.display()
    );
    let _ = std::fs::remove_dir_all(&base);
}

/// Runs `script` in `dir` as a user's shell would, without a display (so the game runs headless
/// for 240 frames) and without this test's cargo variables; its output, or a panic with it.
fn shell(dir: &Path, script: &str) -> String {
    let output = Command::new("sh")
        .args(["-e", "-c", script])
        .current_dir(dir)
        .env("PORTALCAST_RUN_FRAMES", "240")
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("CARGO_TARGET_DIR")
        .env_remove("CARGO_BUILD_TARGET")
        .env_remove("RUSTFLAGS")
        .env_remove("CARGO_ENCODED_RUSTFLAGS")
        .env_remove("PORTALCAST_ASSETS")
        .env_remove("PORTALCAST_MAPS")
        .output()
        .unwrap_or_else(|error| panic!("running `{script}`: {error}"));
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(
        output.status.success(),
        "`{}` failed ({}): {text}",
        script.trim(),
        output.status
    );
    text
}
