//! Error reports: one line each, `file:line:col: what is wrong, what to do`.

use std::fmt;
use std::path::{Path, PathBuf};

/// A position in a source file: 1-based line and column (columns count characters). For a PNG,
/// line is the pixel row + 1 and column the pixel column + 1; whole-image problems are at 1:1.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct Loc {
    /// 1-based line (or pixel row + 1).
    pub line: u32,
    /// 1-based column in characters (or pixel column + 1).
    pub col: u32,
}

impl Loc {
    /// The first character of a file (or the top-left pixel of an image).
    pub const START: Loc = Loc { line: 1, col: 1 };

    /// A location from 1-based line and column.
    pub const fn new(line: u32, col: u32) -> Loc {
        Loc { line, col }
    }
}

/// A message located in a file: what is wrong and what to do about it.
pub(crate) type Located = (Loc, String);

/// One error found in the assets.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct Diagnostic {
    /// The file at fault (the asset directory joined with its relative path).
    pub path: PathBuf,
    /// Where in the file.
    pub loc: Loc,
    /// What is wrong and what to do, one line.
    pub message: String,
}

impl Diagnostic {
    pub(crate) fn new(path: &Path, (loc, message): Located) -> Diagnostic {
        Diagnostic {
            path: path.to_path_buf(),
            loc,
            message,
        }
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}:{}: {}",
            self.path.display(),
            self.loc.line,
            self.loc.col,
            self.message
        )
    }
}

/// Every error found while compiling an asset directory, sorted by file and position.
/// Displays as one line per error.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CompileErrors(pub Vec<Diagnostic>);

impl CompileErrors {
    pub(crate) fn sorted(mut diagnostics: Vec<Diagnostic>) -> CompileErrors {
        diagnostics.sort();
        diagnostics.dedup();
        CompileErrors(diagnostics)
    }

    pub(crate) fn in_file(path: &Path, errors: Vec<Located>) -> CompileErrors {
        CompileErrors::sorted(
            errors
                .into_iter()
                .map(|e| Diagnostic::new(path, e))
                .collect(),
        )
    }
}

impl fmt::Display for CompileErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, diagnostic) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{diagnostic}")?;
        }
        Ok(())
    }
}

impl std::error::Error for CompileErrors {}
