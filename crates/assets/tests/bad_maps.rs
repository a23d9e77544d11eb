//! Every map validation error has a bad map in `tests/bad/` that triggers it.
//!
//! Each file's first line says what it must produce: `# expect: LINE:COL: text`, meaning some
//! reported error is at LINE:COL and its message contains `text`. A second line
//! `# catalog: no-sky` compiles it against an asset set without a sky panorama.

use std::path::{Path, PathBuf};

use portalcast_assets::{compile_map_str, Catalog};

const TEXTURES: &[&str] = &[
    "brick", "ceiling", "grass", "metal", "step", "stone", "tiles", "trim", "water", "wood",
];
const SPRITES: &[&str] = &["flame", "grate", "statue", "torch"];
/// The torch's size, as the shipped `sprites/torch.png` has it (the things' checks use it).
const TORCH_SIZE: (u16, u16) = (16, 48);

fn bad_files() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/bad exists")
        .map(|e| e.expect("readable entry").path())
        .collect();
    files.sort();
    files
}

struct Expectation {
    line: u32,
    col: u32,
    text: String,
}

fn expectation(path: &Path, text: &str) -> Expectation {
    let header = text
        .lines()
        .next()
        .and_then(|l| l.strip_prefix("# expect: "))
        .unwrap_or_else(|| {
            panic!(
                "{}: first line must be `# expect: LINE:COL: text`",
                path.display()
            )
        });
    let mut parts = header.splitn(3, ':');
    let mut number = || parts.next().and_then(|n| n.trim().parse().ok());
    let (line, col) = (number().unwrap_or(0), number().unwrap_or(0));
    let text = parts.next().unwrap_or("").trim().to_string();
    Expectation { line, col, text }
}

#[test]
fn every_bad_map_reports_its_error_at_its_place() {
    let files = bad_files();
    assert!(
        files.len() >= 60,
        "expected the whole set of bad maps, found {}",
        files.len()
    );
    let mut failures = Vec::new();
    for path in &files {
        let text = std::fs::read_to_string(path).expect("bad map is UTF-8");
        let expected = expectation(path, &text);
        let has_sky = !text
            .lines()
            .nth(1)
            .is_some_and(|l| l.trim() == "# catalog: no-sky");
        let catalog = Catalog::new(TEXTURES.iter().copied(), SPRITES.iter().copied(), has_sky)
            .with_sprite_size("torch", TORCH_SIZE.0, TORCH_SIZE.1)
            .with_sprite_frames("flame", 4, 1)
            .with_sprite_frames("statue", 1, 8)
            .with_sprite_frames("grate", 1, 1);
        let file_name = path
            .file_name()
            .and_then(|n| n.to_str())
            .expect("UTF-8 name");
        match compile_map_str(file_name, &text, &catalog) {
            Ok(_) => failures.push(format!("{file_name}: compiled without error")),
            Err(errors) => {
                for diagnostic in &errors.0 {
                    let shown = diagnostic.to_string();
                    assert!(!shown.contains('\n'), "one line per error: {shown:?}");
                    assert!(
                        shown.starts_with(&format!(
                            "{file_name}:{}:{}: ",
                            diagnostic.loc.line, diagnostic.loc.col
                        )),
                        "file:line:col: prefix: {shown:?}"
                    );
                }
                let found = errors.0.iter().any(|d| {
                    d.loc.line == expected.line
                        && d.loc.col == expected.col
                        && d.message.contains(&expected.text)
                });
                if !found {
                    failures.push(format!(
                        "{file_name}: expected {}:{}: {:?}, got:\n  {}",
                        expected.line,
                        expected.col,
                        expected.text,
                        errors.to_string().replace('\n', "\n  ")
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
