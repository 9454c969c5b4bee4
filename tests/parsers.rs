//! Property tests of every input parser (`robot.toml`, `uncertainty.toml`, `measurements.csv` of
//! the hexapod and of the arm, the hexapod's `poses.csv` and `workspace.toml`, and the shared number table): on random
//! text, on valid files truncated or mutated, with huge, tiny and non-finite numbers and odd
//! Unicode, a parser returns a value or a [`DataError`] naming the file it was given — it never
//! panics. Random bytes go through the `read_*` functions (a file that is not UTF-8 is an error
//! naming it too).

use calib_pipeline::{parse_number_table, DataError, MAX_MAGNITUDE};
use proptest::prelude::*;
use std::path::Path;

/// The name every parser is given; every error must carry it.
const FILE: &str = "under-test.txt";

/// A parser under test: the text in, `Ok(())` or the error out.
type Parser = fn(&Path, &str) -> Result<(), DataError>;

fn gough_robot(f: &Path, t: &str) -> Result<(), DataError> {
    calib_gough::files::parse_robot(f, t).map(|_| ())
}
fn gough_uncertainty(f: &Path, t: &str) -> Result<(), DataError> {
    let u = calib_gough::files::parse_uncertainty(f, t)?;
    calib_gough::files::check_uncertainty(f, &u, false)
}
fn gough_measurements(f: &Path, t: &str) -> Result<(), DataError> {
    calib_gough::files::parse_measurements(f, t, 6).map(|_| ())
}
fn gough_poses(f: &Path, t: &str) -> Result<(), DataError> {
    calib_gough::files::parse_poses(f, t).map(|_| ())
}
fn gough_workspace(f: &Path, t: &str) -> Result<(), DataError> {
    calib_gough::workspace::parse_workspace(f, t).map(|_| ())
}
fn arm_robot(f: &Path, t: &str) -> Result<(), DataError> {
    calib_arm::files::parse_robot(f, t).map(|_| ())
}
fn arm_uncertainty(f: &Path, t: &str) -> Result<(), DataError> {
    calib_arm::files::parse_uncertainty(f, t).map(|_| ())
}
fn arm_measurements(f: &Path, t: &str) -> Result<(), DataError> {
    calib_arm::files::parse_measurements(f, t, 6).map(|_| ())
}
fn number_table(f: &Path, t: &str) -> Result<(), DataError> {
    let header: Vec<String> = ["a", "b", "c"].map(String::from).to_vec();
    let table = parse_number_table(f, t, &header)?;
    // What the table accepts is what it promises: finite numbers of bounded magnitude.
    assert!(table
        .rows
        .iter()
        .flatten()
        .all(|v| v.is_finite() && v.abs() <= MAX_MAGNITUDE));
    Ok(())
}

/// Every parser with a valid text of its format (simulated data sets of both robots).
fn valid_files() -> Vec<(&'static str, Parser, String)> {
    let hexapod = calib_gough::simulate::simulate(
        &calib_gough::simulate::builtin_hexapod(),
        9,
        7,
        calib_gough::measurement::Uncertainty::PAPER,
        1.0,
        0.1,
    );
    let [(_, gm), (_, gr), (_, gu), _] =
        calib_gough::simulate::data_set_files(&hexapod, 7, 1.0, &[]);
    let arm = calib_arm::robot::builtin_arm();
    let u = calib_arm::simulate::Uncertainty::TRACKER;
    let sim = calib_arm::simulate::simulate(&arm, 5, 7, u, 1.0, &[]);
    vec![
        ("gough robot.toml", gough_robot as Parser, gr),
        ("gough uncertainty.toml", gough_uncertainty, gu),
        ("gough poses.csv", gough_poses, poses_csv(&gm)),
        ("gough measurements.csv", gough_measurements, gm),
        (
            "gough workspace.toml",
            gough_workspace,
            include_str!("../calib-gough/tests/data/workspace.toml").to_string(),
        ),
        (
            "arm robot.toml",
            arm_robot,
            calib_arm::write::robot_toml(&arm),
        ),
        (
            "arm uncertainty.toml",
            arm_uncertainty,
            calib_arm::write::uncertainty_toml(&u),
        ),
        (
            "arm measurements.csv",
            arm_measurements,
            calib_arm::write::measurements_csv(&sim.readings, 6),
        ),
        (
            "number table",
            number_table,
            "a,b,c\n1,2,3\n-4.5e1, 6 ,7\n".to_string(),
        ),
    ]
}

/// The poses of a measurements file: its first seven columns.
fn poses_csv(measurements: &str) -> String {
    measurements
        .lines()
        .map(|l| l.split(',').take(7).collect::<Vec<_>>().join(",") + "\n")
        .collect()
}

/// Runs `parser` on `text`: it must return, and an error must name [`FILE`].
fn check(what: &str, parser: Parser, text: &str) -> Result<(), TestCaseError> {
    let file = Path::new(FILE);
    let outcome = std::panic::catch_unwind(|| parser(file, text));
    match outcome {
        Err(_) => Err(TestCaseError::fail(format!("{what} panicked on {text:?}"))),
        Ok(Err(e)) => {
            prop_assert_eq!(&e.file, file);
            prop_assert!(e.to_string().starts_with(FILE), "{}: {}", what, e);
            prop_assert!(!e.message.is_empty());
            Ok(())
        }
        Ok(Ok(())) => Ok(()),
    }
}

/// Tokens that break parsers: numbers at and beyond every limit, non-numbers, quoting and table
/// syntax, and Unicode that is wide, combining, right-to-left or outside the BMP.
const TOKENS: &[&str] = &[
    "",
    "0",
    "-0",
    "1e308",
    "-1e308",
    "1e309",
    "1e100",
    "1.0000001e100",
    "5e-324",
    "NaN",
    "nan",
    "inf",
    "-inf",
    "+inf",
    "0x10",
    "1_000",
    "9999999999999999999999999999",
    "1e",
    ".",
    "-",
    "+",
    ",",
    ",,",
    "\"",
    "'",
    "\"\"\"",
    "[",
    "]",
    "[[",
    "]]",
    "{",
    "}",
    "=",
    "==",
    "#",
    "\n",
    "\r\n",
    "\r",
    "\t",
    " ",
    "\0",
    "\u{feff}",
    "é",
    "e\u{301}",
    "\u{202e}",
    "\u{200b}",
    "🦀",
    "𝟙",
    "٣",
    "[[leg]]",
    "[[joint]]",
    "[base]",
    "[tool]",
    "radius = -1",
    "radius = [1, 2]",
    "a = [1, 2]",
    "L7",
    "q7",
    "px",
    "angle_deg",
    "pos = 1e999",
];

/// One edit of a text: at a position (a fraction of its length), delete some characters, insert
/// a token or replace characters by it.
#[derive(Clone, Debug)]
enum Edit {
    Delete(f64, usize),
    Insert(f64, usize),
    Replace(f64, usize, usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    let at = 0.0..1.0f64;
    let token = 0..TOKENS.len();
    prop_oneof![
        (at.clone(), 1..8usize).prop_map(|(p, n)| Edit::Delete(p, n)),
        (at.clone(), token.clone()).prop_map(|(p, t)| Edit::Insert(p, t)),
        (at, 1..6usize, token).prop_map(|(p, n, t)| Edit::Replace(p, n, t)),
    ]
}

/// The text with the edits applied (positions on character boundaries).
fn apply(text: &str, edits: &[Edit]) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for e in edits {
        let at = |p: f64, len: usize| ((p * len as f64) as usize).min(len);
        match *e {
            Edit::Delete(p, n) => {
                let i = at(p, chars.len());
                let j = (i + n).min(chars.len());
                chars.drain(i..j);
            }
            Edit::Insert(p, t) => {
                let i = at(p, chars.len());
                chars.splice(i..i, TOKENS[t].chars());
            }
            Edit::Replace(p, n, t) => {
                let i = at(p, chars.len());
                let j = (i + n).min(chars.len());
                chars.splice(i..j, TOKENS[t].chars());
            }
        }
    }
    chars.into_iter().collect()
}

/// Every number of the text replaced, in turn, by tokens from [`TOKENS`] (huge, tiny, non-finite).
fn renumber(text: &str, picks: &[usize]) -> String {
    let mut out = String::with_capacity(text.len());
    let mut k = 0;
    let mut rest = text;
    while let Some(start) = rest.find(|c: char| c.is_ascii_digit()) {
        let end = rest[start..]
            .find(|c: char| !(c.is_ascii_digit() || ".eE+-".contains(c)))
            .map_or(rest.len(), |e| start + e);
        out.push_str(&rest[..start]);
        match picks.get(k) {
            Some(&t) => out.push_str(TOKENS[t % 20]),
            None => out.push_str(&rest[start..end]),
        }
        k += 1;
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn random_text_never_panics(text in "\\PC{0,200}", garbage in prop::collection::vec(any::<char>(), 0..60)) {
        let garbage: String = garbage.into_iter().collect();
        for (what, parser, _) in valid_files_cached() {
            check(what, *parser, &text)?;
            check(what, *parser, &garbage)?;
        }
    }

    #[test]
    fn truncated_valid_files_never_panic(cut in 0.0..1.0f64) {
        for (what, parser, valid) in valid_files_cached() {
            let chars: Vec<char> = valid.chars().collect();
            let n = (cut * chars.len() as f64) as usize;
            let text: String = chars[..n].iter().collect();
            check(what, *parser, &text)?;
        }
    }

    #[test]
    fn mutated_valid_files_never_panic(edits in prop::collection::vec(edit(), 1..6)) {
        for (what, parser, valid) in valid_files_cached() {
            check(what, *parser, &apply(valid, &edits))?;
        }
    }

    #[test]
    fn extreme_numbers_never_panic(picks in prop::collection::vec(0..TOKENS.len(), 0..40)) {
        for (what, parser, valid) in valid_files_cached() {
            check(what, *parser, &renumber(valid, &picks))?;
        }
    }

    #[test]
    fn random_bytes_on_disk_are_errors_naming_the_file(bytes in prop::collection::vec(any::<u8>(), 0..200)) {
        let dir = crate::scratch_dir::ScratchDir::new("certicalib-parsers");
        let path = dir.join("random.bin");
        std::fs::write(&path, &bytes).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let named = |e: DataError| e.file == path;
        prop_assert!(calib_gough::files::read_robot(&path).map_or_else(named, |_| true));
        prop_assert!(calib_gough::files::read_uncertainty(&path).map_or_else(named, |_| true));
        prop_assert!(calib_gough::files::read_measurements(&path, 6).map_or_else(named, |_| true));
        prop_assert!(calib_gough::files::read_poses(&path).map_or_else(named, |_| true));
        prop_assert!(calib_gough::workspace::read_workspace(&path).map_or_else(named, |_| true));
        prop_assert!(calib_arm::files::read_robot(&path).map_or_else(named, |_| true));
        prop_assert!(calib_arm::files::read_uncertainty(&path).map_or_else(named, |_| true));
        prop_assert!(calib_arm::files::read_measurements(&path, 6).map_or_else(named, |_| true));
    }
}

/// [`valid_files`], built once for all cases.
fn valid_files_cached() -> &'static [(&'static str, Parser, String)] {
    static FILES: std::sync::OnceLock<Vec<(&'static str, Parser, String)>> =
        std::sync::OnceLock::new();
    FILES.get_or_init(valid_files)
}

#[test]
fn the_valid_files_parse() {
    // The mutations start from files the parsers accept, so they probe past the first line.
    for (what, parser, text) in valid_files_cached() {
        assert!(parser(Path::new(FILE), text).is_ok(), "{what}: {text}");
    }
}

#[test]
fn numbers_beyond_the_limit_are_rejected_with_the_field() {
    for (what, parser, valid) in valid_files_cached() {
        // The first number of the file made huge (1e101 > MAX_MAGNITUDE) or infinite.
        for token in ["1e101", "1e999", "inf", "nan"] {
            let text = {
                // After the first `=` (TOML) or the header line (CSV): past comments and headers.
                let from = valid
                    .find('=')
                    .or_else(|| valid.find('\n'))
                    .expect("a value");
                let i = from
                    + valid[from..]
                        .find(|c: char| c.is_ascii_digit())
                        .expect("a number");
                let j = valid[i..]
                    .find(|c: char| !(c.is_ascii_digit() || ".eE+-".contains(c)))
                    .map_or(valid.len(), |e| i + e);
                format!("{}{token}{}", &valid[..i], &valid[j..])
            };
            let e = parser(Path::new(FILE), &text)
                .expect_err(&format!("{what} accepted {token}: {text}"));
            assert!(e.to_string().starts_with(FILE), "{what}: {e}");
        }
    }
}
