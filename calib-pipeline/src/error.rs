//! The errors of calib-pipeline: [`DataError`], a malformed input file named by file, line and
//! field; [`OptionError`], an option value the command line (or its library counterpart) does not
//! accept; [`ParseError`], an option's text that names no value; and [`PipelineError`], any of
//! the crate's errors, for a caller that returns one type.

use std::path::{Path, PathBuf};

use crate::error_scale::ScaleError;

/// Largest accepted magnitude of any value in the data files: far beyond any robot, far below
/// overflow in the interval evaluations.
pub const MAX_MAGNITUDE: f64 = 1e100;

/// A malformed input file: where and what was expected. Shown as
/// `file, line L, field `F`: message` (the line and the field when known).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}{}: {message}", file.display(), place(*line, field.as_deref()))]
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

/// `, line L, field `F`` for what is known of a [`DataError`]'s place in its file.
fn place(line: Option<usize>, field: Option<&str>) -> String {
    let mut s = String::new();
    if let Some(l) = line {
        s.push_str(&format!(", line {l}"));
    }
    if let Some(field) = field {
        s.push_str(&format!(", field `{field}`"));
    }
    s
}

/// An option value that is not accepted; the message names the option as the command line
/// spells it (the library functions that take the same settings report the same errors).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum OptionError {
    /// `--tolerance` is not a positive finite number.
    #[error("--tolerance: expected a positive number, found {0}")]
    Tolerance(f64),
    /// `--max-seconds` is not a positive number.
    #[error("--max-seconds: expected a positive number, found {0}")]
    MaxSeconds(f64),
    /// `--max-outliers` leaves no configuration.
    #[error("--max-outliers {outliers}: must be smaller than the number of configurations ({configurations})")]
    MaxOutliers {
        /// The fixed number of outliers asked for.
        outliers: usize,
        /// The number of configurations.
        configurations: usize,
    },
    /// `--scale-margin` is not a finite factor of at least 1.
    #[error("--scale-margin {0}: expected a factor >= 1")]
    ScaleMargin(f64),
}

/// An option's text that names none of its values (the `Err` of this crate's `FromStr` impls).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ParseError {
    /// Not a number of outliers ([`OutlierBudget`](crate::OutlierBudget)); holds the trimmed
    /// text.
    #[error("expected a number of configurations (0, 1, 2, …) or `auto`, found `{0}`")]
    OutlierBudget(String),
    /// Not a design criterion ([`Criterion`](crate::design::Criterion)); holds the text.
    #[error("unknown criterion `{0}`; expected `certified` or `d-optimal`")]
    Criterion(String),
}

/// Any error of calib-pipeline, for a caller that returns one type; its message is the inner
/// error's.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PipelineError {
    /// A malformed input file.
    #[error(transparent)]
    Data(#[from] DataError),
    /// An option value that is not accepted.
    #[error(transparent)]
    Option(#[from] OptionError),
    /// An option's text that names none of its values.
    #[error(transparent)]
    Parse(#[from] ParseError),
    /// An error-scale search that proved no factor consistent.
    #[error(transparent)]
    Scale(#[from] ScaleError),
}

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
