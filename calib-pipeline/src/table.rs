//! Reading a CSV file of numbers with a fixed header: every value finite and of sane magnitude,
//! every problem named by file, line and column.

use crate::{DataError, MAX_MAGNITUDE};
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
/// [`MAX_MAGNITUDE`].
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
        let record = record.map_err(|e| {
            let line = e.position().map(|p| p.line() as usize);
            let message = match e.kind() {
                csv::ErrorKind::UnequalLengths {
                    expected_len, len, ..
                } => format!("expected {expected_len} columns, found {len}"),
                _ => e.to_string(),
            };
            DataError::new(file, line, None, message)
        })?;
        let line = record
            .position()
            .map_or(out.rows.len() + 2, |p| p.line() as usize);
        let mut values = Vec::with_capacity(expected.len());
        for (field, raw) in expected.iter().zip(record.iter()) {
            let bad = |what: String| DataError::new(file, Some(line), Some(field), what);
            let v: f64 = raw
                .parse()
                .map_err(|_| bad(format!("expected a number, found `{raw}`")))?;
            if !v.is_finite() || v.abs() > MAX_MAGNITUDE {
                return Err(bad(format!(
                    "expected a finite number of magnitude below {MAX_MAGNITUDE:e}, found `{raw}`"
                )));
            }
            values.push(v);
        }
        out.rows.push(values);
        out.lines.push(line);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn header(cols: &[&str]) -> Vec<String> {
        cols.iter().map(|c| c.to_string()).collect()
    }

    #[test]
    fn reads_numbers_and_names_every_problem() {
        let h = header(&["q1", "px"]);
        let f = Path::new("m.csv");
        let t = parse_number_table(f, "q1, px\n1, 2\n3,4e2\n", &h).unwrap();
        assert_eq!(t.rows, vec![vec![1.0, 2.0], vec![3.0, 400.0]]);
        assert_eq!(t.lines, vec![2, 3]);
        let e = parse_number_table(f, "q1,py\n1,2\n", &h).unwrap_err();
        assert_eq!((e.line, e.field.as_deref()), (Some(1), None));
        assert!(e.message.contains("expected `q1,px`"), "{e}");
        let e = parse_number_table(f, "q1,px\n1,2\n1,x\n", &h).unwrap_err();
        assert_eq!((e.line, e.field.as_deref()), (Some(3), Some("px")));
        let e = parse_number_table(f, "q1,px\n1,2\n1,NaN\n", &h).unwrap_err();
        assert_eq!((e.line, e.field.as_deref()), (Some(3), Some("px")));
        let e = parse_number_table(f, "q1,px\n1e300,2\n", &h).unwrap_err();
        assert_eq!((e.line, e.field.as_deref()), (Some(2), Some("q1")));
        let e = parse_number_table(f, "q1,px\n1,2,3\n", &h).unwrap_err();
        assert_eq!(e.line, Some(2));
        assert!(e.message.contains("columns"), "{e}");
    }
}
