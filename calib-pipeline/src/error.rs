//! [`DataError`]: a malformed input file, named by file, line and field.

use std::fmt;
use std::path::{Path, PathBuf};

/// Largest accepted magnitude of any value in the data files: far beyond any robot, far below
/// overflow in the interval evaluations.
pub const MAX_MAGNITUDE: f64 = 1e100;

/// A malformed input file: where and what was expected.
#[derive(Debug, Clone, PartialEq)]
pub struct DataError {
    /// The file.
    pub file: PathBuf,
    /// The 1-based line, when known.
    pub line: Option<usize>,
    /// The field (column or key), when known.
    pub field: Option<String>,
    /// What is wrong and what was expected.
    pub message: String,
}

impl DataError {
    /// An error in `file`, at `line` and `field` when known.
    pub fn new(
        file: &Path,
        line: Option<usize>,
        field: Option<&str>,
        message: impl Into<String>,
    ) -> DataError {
        DataError {
            file: file.to_path_buf(),
            line,
            field: field.map(str::to_string),
            message: message.into(),
        }
    }
}

impl fmt::Display for DataError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some(l) = self.line {
            write!(f, ", line {l}")?;
        }
        if let Some(field) = &self.field {
            write!(f, ", field `{field}`")?;
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for DataError {}

/// The text of `file`, or an error naming it.
pub fn read_text(file: &Path) -> Result<String, DataError> {
    std::fs::read_to_string(file)
        .map_err(|e| DataError::new(file, None, None, format!("cannot read the file: {e}")))
}

/// The 1-based line of byte `offset` of `text` (an offset at the start of a line is on that
/// line, not the one before).
pub fn line_at(text: &str, offset: usize) -> usize {
    text.as_bytes()[..offset.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// A TOML parse error of `text` (the contents of `file`) as a [`DataError`] at the line the
/// parser points to, with `expected` appended to its message.
pub fn toml_error(file: &Path, text: &str, e: &toml::de::Error, expected: &str) -> DataError {
    let line = e.span().map(|s| line_at(text, s.start));
    DataError::new(file, line, None, format!("{}; {expected}", e.message()))
}
