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

/// `value` when it is a number the data files accept — finite (not NaN, not an infinity, not a
/// decimal beyond the range of doubles, which reads as one) and of magnitude at most
/// [`MAX_MAGNITUDE`] — else a [`DataError`] in `file` at `line` and `field` that shows what was
/// found. The robots' readers pass the numbers of their data and vendor files through here (the
/// CSV readers of this crate do too), so that no NaN or infinity reaches a computation or an
/// output file.
pub fn finite_number(
    file: &Path,
    line: Option<usize>,
    field: &str,
    value: f64,
) -> Result<f64, DataError> {
    if value.is_finite() && value.abs() <= MAX_MAGNITUDE {
        return Ok(value);
    }
    let found = if value.is_infinite() {
        format!("{value} (an infinity, or a decimal beyond the range of doubles)")
    } else {
        format!("{value:e}")
    };
    Err(DataError::new(
        file,
        line,
        Some(field),
        format!("expected a finite number of magnitude at most {MAX_MAGNITUDE:e}, found {found}"),
    ))
}

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
