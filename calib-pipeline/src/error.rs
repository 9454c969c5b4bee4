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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_file_line_and_field() {
        let e = DataError::new(Path::new("robot.toml"), Some(4), Some("joint[2].d"), "bad");
        assert_eq!(e.to_string(), "robot.toml, line 4, field `joint[2].d`: bad");
        let e = DataError::new(Path::new("a.csv"), None, None, "empty");
        assert_eq!(e.to_string(), "a.csv: empty");
    }

    #[test]
    fn offsets_at_a_line_start_are_on_that_line() {
        let text = "a = 1\nb = 2\n";
        assert_eq!(line_at(text, 0), 1);
        assert_eq!(line_at(text, 5), 1);
        assert_eq!(line_at(text, 6), 2);
        assert_eq!(line_at(text, 99), 3);
    }

    #[test]
    fn toml_errors_point_at_the_line() {
        let text = "a = 1\nb = [1,\nc = ";
        let err = toml::from_str::<toml::Value>(text).unwrap_err();
        let e = toml_error(Path::new("x.toml"), text, &err, "expected numbers");
        assert!(e.line.is_some_and(|l| l >= 2), "{e}");
        assert!(e.message.ends_with("expected numbers"));
    }
}
