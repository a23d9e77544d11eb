//! The commands and files that README.md and docs/*.md show exist (issue 22: a review found 8 of
//! 17 claims stale). Every `cargo X` inside a code span or block must be a cargo command or one
//! of `.cargo/config.toml`'s aliases, its `-p` a workspace package, its `--bin` a binary and its
//! `--test` a test target of the workspace; every path of the repository named in one must exist.
//! Removing or renaming a documented command, alias, binary, test or file fails this test.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The cargo commands the docs may use besides the aliases.
const CARGO_COMMANDS: [&str; 9] = [
    "build", "check", "clippy", "doc", "fmt", "run", "test", "tree", "clean",
];

/// The top-level names a repository path in the docs starts with.
const TOP_LEVEL: [&str; 13] = [
    "src/",
    "crates/",
    "docs/",
    "assets/",
    "asm/",
    "tests/",
    ".cargo/",
    ".ci/",
    "linker.ld",
    "Cargo.toml",
    "build.rs",
    "rust-toolchain.toml",
    "README.md",
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// README.md and every docs/*.md, with their text.
fn documents() -> Vec<(PathBuf, String)> {
    let mut paths = vec![root().join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .expect("docs/")
        .map(|entry| entry.expect("an entry").path())
        .filter(|path| path.extension().is_some_and(|extension| extension == "md"))
        .collect();
    docs.sort();
    paths.extend(docs);
    paths
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).expect("a readable doc");
            (path, text)
        })
        .collect()
}

/// The code of a Markdown text: the contents of fenced blocks and of inline code spans.
fn code_of(text: &str) -> Vec<String> {
    let mut code = Vec::new();
    let mut in_block = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            in_block = !in_block;
            continue;
        }
        if in_block {
            code.push(line.to_string());
            continue;
        }
        let mut parts = line.split('`');
        parts.next();
        while let Some(span) = parts.next() {
            code.push(span.to_string());
            parts.next();
        }
    }
    code
}

/// The aliases of `.cargo/config.toml`.
fn aliases() -> BTreeSet<String> {
    let config = std::fs::read_to_string(root().join(".cargo/config.toml")).expect("config");
    config
        .lines()
        .skip_while(|line| line.trim() != "[alias]")
        .skip(1)
        .take_while(|line| !line.trim_start().starts_with('['))
        .filter_map(|line| {
            line.split_once('=')
                .map(|(name, _)| name.trim().to_string())
        })
        .filter(|name| !name.is_empty() && !name.starts_with('#'))
        .collect()
}

/// The workspace's packages by name, with their directories.
fn packages() -> Vec<(String, PathBuf)> {
    let mut packages = vec![("portalcast".to_string(), root())];
    for entry in std::fs::read_dir(root().join("crates")).expect("crates/") {
        let dir = entry.expect("an entry").path();
        let manifest = std::fs::read_to_string(dir.join("Cargo.toml")).unwrap_or_default();
        if let Some(name) = manifest
            .lines()
            .find_map(|line| line.strip_prefix("name = \""))
            .and_then(|rest| rest.strip_suffix('"'))
        {
            packages.push((name.to_string(), dir));
        }
    }
    packages
}

/// Whether `package` (a directory) has a binary called `name`.
fn has_binary(package: &Path, name: &str) -> bool {
    let manifest = std::fs::read_to_string(package.join("Cargo.toml")).unwrap_or_default();
    package.join("src/bin").join(format!("{name}.rs")).exists()
        || package.join("src/bin").join(name).join("main.rs").exists()
        || manifest.contains(&format!("name = \"{name}\""))
}

/// The problems of one `cargo …` command line of the docs.
fn check_command(
    words: &[&str],
    aliases: &BTreeSet<String>,
    packages: &[(String, PathBuf)],
) -> Vec<String> {
    let mut problems = Vec::new();
    let Some(command) = words.first() else {
        return problems;
    };
    if !CARGO_COMMANDS.contains(command) && !aliases.contains(*command) {
        problems.push(format!(
            "`cargo {command}` is neither a cargo command nor an alias"
        ));
    }
    let value = |flag: &str| {
        words
            .iter()
            .position(|word| *word == flag)
            .and_then(|index| words.get(index + 1))
            .copied()
    };
    let package = value("-p").map(|name| packages.iter().find(|(known, _)| known == name));
    if let Some(None) = package {
        problems.push(format!(
            "`-p {}` names no workspace package",
            value("-p").unwrap_or("")
        ));
    }
    if let Some(bin) = value("--bin") {
        let dirs: Vec<&PathBuf> = match package {
            Some(Some((_, dir))) => vec![dir],
            _ => packages.iter().map(|(_, dir)| dir).collect(),
        };
        if !dirs.iter().any(|dir| has_binary(dir, bin)) {
            problems.push(format!("`--bin {bin}` names no binary"));
        }
    }
    if let Some(test) = value("--test") {
        let found = packages
            .iter()
            .any(|(_, dir)| dir.join("tests").join(format!("{test}.rs")).exists());
        if !found {
            problems.push(format!("`--test {test}` names no test target"));
        }
    }
    problems
}

/// A repository path named in `word`, without what follows it (`:line`, `#anchor`, punctuation).
fn repository_path(word: &str) -> Option<String> {
    let word = word.trim_matches(|c: char| "`()[],;'\"".contains(c));
    if !TOP_LEVEL.iter().any(|top| word.starts_with(top)) {
        return None;
    }
    let path = word
        .split([':', '#'])
        .next()
        .unwrap_or(word)
        .trim_end_matches(['.', ',', ')']);
    // Placeholders and patterns are not files.
    let placeholder = path.chars().any(|c| "*…{<".contains(c))
        || path.split('/').any(|part| {
            part.chars().any(|c| c.is_ascii_uppercase())
                && part == part.to_uppercase()
                && part.len() > 1
                && !part.contains('.')
        });
    (!placeholder).then(|| path.to_string())
}

#[test]
fn every_documented_command_and_path_exists() {
    let aliases = aliases();
    let packages = packages();
    let mut problems = Vec::new();
    let (mut commands, mut paths) = (0, 0);
    for (doc, text) in documents() {
        let name = doc
            .strip_prefix(root())
            .unwrap_or(&doc)
            .display()
            .to_string();
        for code in code_of(&text) {
            for (index, _) in code.match_indices("cargo ") {
                let before = &code[..index];
                if before.ends_with(|c: char| c.is_alphanumeric() || c == '-' || c == '_') {
                    continue;
                }
                // The command's words, up to a shell operator or a comment, each without the
                // punctuation prose puts around it.
                let words: Vec<&str> = code[index + "cargo ".len()..]
                    .split_whitespace()
                    .take_while(|word| {
                        !matches!(*word, "&&" | "|" | ";" | "||") && !word.starts_with('#')
                    })
                    .map(|word| word.trim_matches(|c: char| "`:;,.()".contains(c)))
                    .collect();
                commands += 1;
                for problem in check_command(&words, &aliases, &packages) {
                    problems.push(format!("{name}: {problem}: `{}`", code.trim()));
                }
            }
            for word in code.split_whitespace() {
                if let Some(path) = repository_path(word) {
                    paths += 1;
                    // The guide's paths are the game's it builds, which is examples/minimal.
                    let in_game = name.ends_with("GUIDE.md")
                        && root().join("examples/minimal").join(&path).exists();
                    if !root().join(&path).exists() && !in_game {
                        problems.push(format!("{name}: `{path}` does not exist"));
                    }
                }
            }
        }
    }
    println!("{commands} cargo commands and {paths} paths checked");
    assert!(
        commands > 50 && paths > 50,
        "the scan found too little: {commands} commands, {paths} paths"
    );
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn a_removed_command_or_path_is_caught() {
    let aliases = aliases();
    let packages = packages();
    assert!(check_command(&["no-such-alias"], &aliases, &packages).len() == 1);
    assert!(check_command(&["test", "--test", "no_such_test"], &aliases, &packages).len() == 1);
    assert!(
        check_command(
            &["run", "-p", "portalcast-harness", "--bin", "no-such-bin"],
            &aliases,
            &packages
        )
        .len()
            == 1
    );
    assert!(check_command(
        &["run", "-p", "portalcast-harness", "--bin", "pc-run"],
        &aliases,
        &packages
    )
    .is_empty());
    assert_eq!(
        repository_path("`src/render/walk.rs:12`"),
        Some("src/render/walk.rs".to_string())
    );
    assert_eq!(repository_path("maps/NAME.map"), None);
    assert!(!root().join("src/no_such_file.rs").exists());
}
