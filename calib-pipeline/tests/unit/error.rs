//! The tests of `calib_pipeline::error`.

use calib_pipeline::*;
use std::path::Path;

#[test]
fn errors_name_file_line_and_field() {
    let e = DataError::new(Path::new("robot.toml"), Some(4), Some("joint[2].d"), "bad");
    assert_eq!(e.to_string(), "robot.toml, line 4, field `joint[2].d`: bad");
    let e = DataError::new(Path::new("a.csv"), None, None, "empty");
    assert_eq!(e.to_string(), "a.csv: empty");
    let e = DataError::new(Path::new("u.toml"), None, Some("pos_mm"), "negative");
    assert_eq!(e.to_string(), "u.toml, field `pos_mm`: negative");
    let e = DataError::new(Path::new("m.csv"), Some(7), None, "short row");
    assert_eq!(e.to_string(), "m.csv, line 7: short row");
    // Through the crate's umbrella error, the same text.
    assert_eq!(
        PipelineError::from(e).to_string(),
        "m.csv, line 7: short row"
    );
}

/// The messages the CLIs print and Python raises, byte for byte (the typed errors replaced
/// strings formatted at the call sites).
#[test]
fn option_and_parse_errors_keep_their_messages() {
    let cases: [(PipelineError, &str); 7] = [
        (
            OptionError::Tolerance(-1.0).into(),
            "--tolerance: expected a positive number, found -1",
        ),
        (
            OptionError::MaxSeconds(f64::NAN).into(),
            "--max-seconds: expected a positive number, found NaN",
        ),
        (
            OptionError::MaxOutliers {
                outliers: 3,
                configurations: 3,
            }
            .into(),
            "--max-outliers 3: must be smaller than the number of configurations (3)",
        ),
        (
            OptionError::ScaleMargin(0.5).into(),
            "--scale-margin 0.5: expected a factor >= 1",
        ),
        (
            ParseError::OutlierBudget("-1".into()).into(),
            "expected a number of configurations (0, 1, 2, …) or `auto`, found `-1`",
        ),
        (
            ParseError::Criterion("a-optimal".into()).into(),
            "unknown criterion `a-optimal`; expected `certified` or `d-optimal`",
        ),
        (
            error_scale::ScaleError::NotConsistent { largest: 64.0 }.into(),
            "the data are not consistent with the model even with the error bounds × 64: a model error, or outliers (try --max-outliers auto)",
        ),
    ];
    for (e, text) in cases {
        assert_eq!(e.to_string(), text);
    }
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

#[test]
fn non_finite_numbers_are_named_with_file_line_and_field() {
    let f = Path::new("data.toml");
    assert_eq!(finite_number(f, Some(3), "x", -2.5), Ok(-2.5));
    assert_eq!(
        finite_number(f, None, "x", MAX_MAGNITUDE),
        Ok(MAX_MAGNITUDE)
    );
    let overflow: f64 = "1e999".parse().unwrap();
    for (v, found) in [
        (f64::NAN, "NaN"),
        (f64::INFINITY, "inf"),
        (f64::NEG_INFINITY, "-inf"),
        (overflow, "inf"),
        (-1e101, "-1e101"),
    ] {
        let e = finite_number(f, Some(3), "joint[2].d", v).unwrap_err();
        let text = e.to_string();
        assert!(
            text.starts_with("data.toml, line 3, field `joint[2].d`: expected a finite number"),
            "{text}"
        );
        assert!(text.contains(&format!("found {found}")), "{text}");
    }
}
