//! Reading a CSV file of numbers: with a fixed header ([`parse_number_table`]) or picking named
//! columns out of an instrument's export ([`parse_named_columns`]: `,`, `;` or tab delimiters and
//! decimal commas detected); every value finite and of sane magnitude, every problem named by
//! file, line and column.

use crate::{finite_number, DataError};
use std::path::Path;

/// The data rows of a number table, with the 1-based file line of each.
#[derive(Clone, Debug, PartialEq)]
pub struct NumberTable {
    /// One vector per data row, in header order.
    pub rows: Vec<Vec<f64>>,
    /// The file line of each row (the header is line 1).
    pub lines: Vec<usize>,
}

/// Parses `text` (the contents of `file`) as a CSV table whose header must be exactly
/// `expected` (fields trimmed), and whose every cell is a finite number of magnitude at most
/// [`MAX_MAGNITUDE`](crate::MAX_MAGNITUDE).
pub fn parse_number_table(
    file: &Path,
    text: &str,
    expected: &[String],
) -> Result<NumberTable, DataError> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| DataError::new(file, Some(1), None, format!("cannot read the header: {e}")))?
        .iter()
        .map(str::to_string)
        .collect();
    if header != expected {
        return Err(DataError::new(
            file,
            Some(1),
            None,
            format!(
                "unexpected header `{}`; expected `{}`",
                header.join(","),
                expected.join(",")
            ),
        ));
    }
    let mut out = NumberTable {
        rows: Vec::new(),
        lines: Vec::new(),
    };
    for record in reader.records() {
        let record = record.map_err(|e| record_error(file, e))?;
        let line = record
            .position()
            .map_or(out.rows.len() + 2, |p| line_at_byte(text, p.byte()));
        let mut values = Vec::with_capacity(expected.len());
        for (field, raw) in expected.iter().zip(record.iter()) {
            values.push(number(file, line, field, raw, raw)?);
        }
        out.rows.push(values);
        out.lines.push(line);
    }
    Ok(out)
}

/// How a table writes its numbers: the field delimiter and the decimal mark.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Dialect {
    /// `,`, `;` or a tab.
    pub delimiter: u8,
    /// Numbers written with a decimal comma (`1,5` for 1.5): only with `;` or tab delimiters.
    pub decimal_comma: bool,
}

impl Dialect {
    /// The dialect of `text`: the delimiter is the one of `;`, tab and `,` the header line holds
    /// (in that order of preference: a `;` or tab header with commas in it is a European
    /// spreadsheet's); numbers use a decimal comma when the delimiter is not `,` and a data line
    /// holds a comma.
    pub fn detect(text: &str) -> Dialect {
        let mut lines = text.lines();
        let header = lines.next().unwrap_or("");
        let delimiter = if header.contains(';') {
            b';'
        } else if header.contains('\t') {
            b'\t'
        } else {
            b','
        };
        let decimal_comma = delimiter != b',' && lines.take(20).any(|l| l.contains(','));
        Dialect {
            delimiter,
            decimal_comma,
        }
    }

    /// A short description for messages: `';'-separated, decimal commas`.
    pub fn describe(&self) -> String {
        let d = match self.delimiter {
            b'\t' => "tab".to_string(),
            c => format!("'{}'", c as char),
        };
        let mark = if self.decimal_comma {
            "decimal commas"
        } else {
            "decimal points"
        };
        format!("{d}-separated, {mark}")
    }
}

/// Parses `text` (the contents of `file`) as a table in its own [`Dialect`] and returns the
/// columns named `columns` (header fields trimmed, matched exactly), in that order; other columns
/// are ignored. Every selected cell must be a finite number of magnitude at most
/// [`MAX_MAGNITUDE`](crate::MAX_MAGNITUDE); a missing column is named with the header's columns.
///
/// ```
/// use calib_pipeline::parse_named_columns;
/// let text = "Time;q;x\n2,0E+13;1,5;-3\n";
/// let cols = ["x".to_string(), "q".to_string()];
/// let t = parse_named_columns(std::path::Path::new("t.csv"), text, &cols).unwrap();
/// assert_eq!(t.rows, vec![vec![-3.0, 1.5]]);
/// ```
pub fn parse_named_columns(
    file: &Path,
    text: &str,
    columns: &[String],
) -> Result<NumberTable, DataError> {
    let dialect = Dialect::detect(text);
    let mut reader = csv::ReaderBuilder::new()
        .delimiter(dialect.delimiter)
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| DataError::new(file, Some(1), None, format!("cannot read the header: {e}")))?
        .iter()
        .map(str::to_string)
        .collect();
    let mut picked = Vec::with_capacity(columns.len());
    for c in columns {
        match header.iter().position(|h| h == c) {
            Some(i) => picked.push(i),
            None => {
                return Err(DataError::new(
                    file,
                    Some(1),
                    Some(c),
                    format!(
                        "no column `{c}` in the header (read as {}); its columns are: {}",
                        dialect.describe(),
                        header.join(", ")
                    ),
                ))
            }
        }
    }
    let mut out = NumberTable {
        rows: Vec::new(),
        lines: Vec::new(),
    };
    for record in reader.records() {
        let record = record.map_err(|e| record_error(file, e))?;
        let line = record
            .position()
            .map_or(out.rows.len() + 2, |p| line_at_byte(text, p.byte()));
        let mut values = Vec::with_capacity(columns.len());
        for (field, &i) in columns.iter().zip(&picked) {
            let raw = record.get(i).unwrap_or("");
            let text = if dialect.decimal_comma {
                raw.replace(',', ".")
            } else {
                raw.to_string()
            };
            values.push(number(file, line, field, raw, &text)?);
        }
        out.rows.push(values);
        out.lines.push(line);
    }
    Ok(out)
}

/// The 1-based line of the record starting at the byte offset `byte` of `text` (csv's own line
/// count is off by one on files with CRLF line ends).
fn line_at_byte(text: &str, byte: u64) -> usize {
    let bytes = text.as_bytes();
    let mut end = usize::try_from(byte).map_or(bytes.len(), |b| b.min(bytes.len()));
    // A record after a CRLF starts, for csv, at the LF.
    while end < bytes.len() && (bytes[end] == b'\n' || bytes[end] == b'\r') {
        end += 1;
    }
    1 + bytes[..end].iter().filter(|&&c| c == b'\n').count()
}

/// The message of a malformed CSV record.
fn record_error(file: &Path, e: csv::Error) -> DataError {
    let line = e.position().map(|p| p.line() as usize);
    let message = match e.kind() {
        csv::ErrorKind::UnequalLengths {
            expected_len, len, ..
        } => format!("expected {expected_len} columns, found {len}"),
        _ => e.to_string(),
    };
    DataError::new(file, line, None, message)
}

/// `text` (the cell `raw` as written) as a finite number of sane magnitude ([`finite_number`]).
fn number(file: &Path, line: usize, field: &str, raw: &str, text: &str) -> Result<f64, DataError> {
    let v: f64 = text.parse().map_err(|_| {
        DataError::new(
            file,
            Some(line),
            Some(field),
            format!("expected a number, found `{raw}`"),
        )
    })?;
    finite_number(file, Some(line), field, v)
}
