//! The building blocks of a calibration certificate, for any robot: one self-contained HTML page
//! (inline SVG figures and styles, no scripts, fonts, images or links to fetch) that says what was
//! proved, from which data, with which software and settings.
//!
//! Pages built from these blocks are well-formed XML as well as HTML (every element closed, every
//! attribute quoted, no named entities), so that they can be checked by an XML parser.
//!
//! Printed bounds are rounded so that the printed boxes keep their meaning: initial and outer
//! boxes outward ([`outward`]: the printed box contains the certified one), inner bounds inward
//! ([`inward`]: every printed inner bound is still attained by a certified consistent parameter
//! vector).

use crate::error::DataError;
use calib_core::{Interval, Status};
use sha2::{Digest, Sha256};
use std::fmt::Write as _;
use std::path::Path;

/// One input of a run, identified by its SHA-256.
#[derive(Clone, Debug, PartialEq)]
pub struct Input {
    /// What the input is ("robot geometry", "measurements", ...).
    pub role: String,
    /// Its name as given (a path, or a description of generated data).
    pub name: String,
    /// The SHA-256 of its bytes, in lowercase hexadecimal.
    pub sha256: String,
    /// Its size in bytes.
    pub bytes: usize,
}

impl Input {
    /// The input `name` with contents `bytes`.
    pub fn new(role: &str, name: &str, bytes: &[u8]) -> Input {
        Input {
            role: role.into(),
            name: name.into(),
            sha256: sha256_hex(bytes),
            bytes: bytes.len(),
        }
    }
}

/// The SHA-256 of `bytes` in lowercase hexadecimal (what `sha256sum` prints).
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .fold(String::with_capacity(64), |mut s, b| {
            let _ = write!(s, "{b:02x}");
            s
        })
}

/// A figure on the page: an inline SVG and its caption.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// What the figure shows.
    pub caption: String,
    /// The SVG document.
    pub svg: String,
}

/// A plain table: a header row and rows of cells (text, escaped on output).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    /// Column headings.
    pub header: Vec<String>,
    /// Rows of cells.
    pub rows: Vec<Vec<String>>,
}

/// An extra section after the legs (e.g. the comparison with the paper in `gough reproduce`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Section {
    /// The heading.
    pub heading: String,
    /// Paragraphs of text.
    pub paragraphs: Vec<String>,
    /// Tables, each with a caption.
    pub tables: Vec<(String, Table)>,
    /// Figures.
    pub figures: Vec<Figure>,
}

/// The certicalib version that writes the certificate.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The current time in RFC 3339 (UTC, whole seconds), for the date a certificate states.
pub fn now() -> String {
    humantime::format_rfc3339_seconds(std::time::SystemTime::now()).to_string()
}

/// The command line as typed (arguments with spaces quoted), for the certificate.
pub fn command_line() -> String {
    let args: Vec<String> = std::env::args()
        .map(|a| {
            if a.is_empty() || a.contains(char::is_whitespace) {
                format!("'{a}'")
            } else {
                a
            }
        })
        .collect();
    args.join(" ")
}

/// `text` with the five XML special characters escaped.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// Decimals printed for bounds: 1e-5 of the unit (0.1 µm for cm, 0.01 µm for mm, 0.036" for
/// degrees), below any error bound a calibration works with.
pub const DECIMALS: usize = 5;

/// `v` printed with [`DECIMALS`] decimals, rounded down (`down`) or up: the printed number is
/// `<= v` (or `>= v`) exactly, checked on the parsed text.
#[doc(hidden)]
pub fn rounded(v: f64, down: bool) -> String {
    rounded_to(v, DECIMALS, down)
}

/// `v` printed with `decimals` decimals, rounded down (`down`) or up: the printed number is
/// `<= v` (or `>= v`) exactly, checked on the parsed text. What a proved factor ("at least
/// 1.12-fold") or a proved bound prints.
pub fn rounded_to(v: f64, decimals: usize, down: bool) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    let step = 10f64.powi(-(decimals as i32));
    let mut x = v;
    for _ in 0..8 {
        let s = format!("{x:.decimals$}");
        let p: f64 = s.parse().unwrap_or(v);
        let ok = if down { p <= v } else { p >= v };
        if ok {
            return s;
        }
        x = if down { p - step } else { p + step };
    }
    // Unreachable for finite values; fall back to the exact shortest representation.
    format!("{v:?}")
}

/// `[lo, hi]` rounded outward: the printed interval contains `v`.
pub fn outward(v: Interval) -> String {
    if v.is_empty() {
        return "empty".into();
    }
    format!("[{}, {}]", rounded(v.inf(), true), rounded(v.sup(), false))
}

/// `[lo, hi]` rounded inward: the printed interval lies inside `v`; exact (shortest round-trip
/// digits) when `v` is too narrow for rounded bounds.
pub fn inward(v: Interval) -> String {
    if v.is_empty() {
        return "empty".into();
    }
    let (lo, hi) = (rounded(v.inf(), false), rounded(v.sup(), true));
    match (lo.parse::<f64>(), hi.parse::<f64>()) {
        (Ok(a), Ok(b)) if a <= b => format!("[{lo}, {hi}]"),
        _ => format!("[{:?}, {:?}]", v.inf(), v.sup()),
    }
}

/// The page's style sheet (inline: the page fetches nothing).
pub const STYLE: &str = "
body { font-family: sans-serif; max-width: 1240px; margin: 1.5em auto; padding: 0 1em; color: #222; line-height: 1.4; }
h1 { margin-bottom: 0.1em; } .subtitle { color: #555; margin-top: 0; }
h2 { border-bottom: 2px solid #ddd; padding-bottom: 0.2em; margin-top: 1.8em; }
table { border-collapse: collapse; margin: 0.6em 0 1em; font-size: 0.92em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: left; vertical-align: top; }
th { background: #f2f2f2; }
td.num { font-family: monospace; text-align: right; white-space: nowrap; }
code, .hash { font-family: monospace; font-size: 0.92em; word-break: break-all; }
.badge { display: inline-block; padding: 0.05em 0.55em; border-radius: 0.7em; color: white; font-size: 0.85em; vertical-align: middle; }
.consistent { background: #2a7d2a; } .empty { background: #b52a2a; } .undecided { background: #b07800; }
.summary { background: #f7f7f4; border: 1px solid #ddd; padding: 0.2em 1.2em 0.6em; }
.summary h2 { margin-top: 0.5em; }
.evidence { margin: 0.2em 0; } .note { color: #555; font-size: 0.9em; }
figure { margin: 1em 0; } figcaption { color: #444; font-size: 0.9em; }
svg { max-width: 100%; height: auto; }
@media print { .leg, .section { page-break-before: always; } body { max-width: none; } }
";

/// The verdict as a coloured badge.
pub fn badge(status: Status) -> String {
    let class = match status {
        Status::Consistent => "consistent",
        Status::Empty => "empty",
        Status::Undecided => "undecided",
    };
    format!(
        "<span class=\"badge {class}\">{}</span>",
        crate::verdict::short_verdict(status)
    )
}

/// A two-column table of `(name, value)` rows under `header`.
pub fn pairs(h: &mut String, header: &[&str; 2], rows: &[(String, String)]) {
    let _ = writeln!(
        h,
        "<table>\n<tr><th>{}</th><th>{}</th></tr>",
        header[0], header[1]
    );
    for (k, v) in rows {
        let _ = writeln!(h, "<tr><td>{}</td><td>{}</td></tr>", escape(k), escape(v));
    }
    h.push_str("</table>\n");
}

/// A figure: its SVG and caption.
pub fn figure(h: &mut String, f: &Figure) {
    let _ = writeln!(
        h,
        "<figure>\n{}\n<figcaption>{}</figcaption>\n</figure>",
        f.svg.trim(),
        escape(&f.caption)
    );
}

/// An extra section: heading, paragraphs, tables, figures.
pub fn section(h: &mut String, s: &Section) {
    let _ = writeln!(
        h,
        "<section class=\"section\">\n<h2>{}</h2>",
        escape(&s.heading)
    );
    for p in &s.paragraphs {
        let _ = writeln!(h, "<p>{}</p>", escape(p));
    }
    for (caption, t) in &s.tables {
        let _ = writeln!(
            h,
            "<p class=\"note\">{}</p>\n<table>\n<tr>",
            escape(caption)
        );
        for c in &t.header {
            let _ = write!(h, "<th>{}</th>", escape(c));
        }
        h.push_str("</tr>\n");
        for row in &t.rows {
            h.push_str("<tr>");
            for c in row {
                let _ = write!(h, "<td class=\"num\">{}</td>", escape(c));
            }
            h.push_str("</tr>\n");
        }
        h.push_str("</table>\n");
    }
    for f in &s.figures {
        figure(h, f);
    }
    h.push_str("</section>\n");
}

/// A page of its own for one section (an accuracy certificate): `title`, the section, then the
/// input files, each named by its role and path with its SHA-256, the software and the command
/// line. The files are read here; one that cannot be read is an error naming it.
pub fn section_page(
    title: &str,
    section: &Section,
    files: &[(&str, &Path)],
) -> Result<String, DataError> {
    let mut h = page_start(title, &now());
    self::section(&mut h, section);
    let mut rows = Vec::new();
    for (role, path) in files {
        let bytes = std::fs::read(path)
            .map_err(|e| DataError::new(path, None, None, format!("cannot read: {e}")))?;
        rows.push((
            format!("{role}: {}", path.display()),
            format!("SHA-256 {}", sha256_hex(&bytes)),
        ));
    }
    rows.push(("software".into(), format!("certicalib {VERSION}")));
    rows.push(("command".into(), command_line()));
    h.push_str("<section id=\"inputs\">\n<h2>Inputs</h2>\n");
    pairs(&mut h, &["input", "identity"], &rows);
    h.push_str("</section>\n");
    h.push_str(PAGE_END);
    Ok(h)
}

/// One bracket of a worst error, for [`brackets_figure`]: the error is proved at most `upper`
/// and attained at `lower`.
#[derive(Clone, Debug, PartialEq)]
pub struct BracketBar {
    /// What the bracket is of ("after", "before", "leg 3").
    pub label: String,
    /// The attained lower bound.
    pub lower: f64,
    /// The proved upper bound (`+∞` or NaN when none was proved: drawn as an open bar).
    pub upper: f64,
}

/// Brackets as horizontal bars on one axis from 0: solid up to the attained lower bound (errors
/// that certainly occur), light from there to the proved upper bound (where the worst error
/// lies), an open arrow where no upper bound was proved. `unit` labels the axis.
pub fn brackets_figure(bars: &[BracketBar], unit: &str, caption: &str) -> Figure {
    let (left, width, row) = (110.0, 520.0, 26.0);
    let proved = |b: &BracketBar| b.upper.is_finite().then_some(b.upper);
    let top = bars
        .iter()
        .filter_map(|b| proved(b).or(Some(b.lower)))
        .filter(|v| v.is_finite())
        .fold(0.0_f64, f64::max);
    let scale_max = if top >= f64::MIN_POSITIVE {
        nice_ceiling(top)
    } else {
        1.0
    };
    let at = |v: f64| left + width * (v / scale_max).clamp(0.0, 1.0);
    let height = row * bars.len() as f64 + 40.0;
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{height}\" \
         viewBox=\"0 0 {w} {height}\" font-family=\"sans-serif\" font-size=\"11\">\n",
        w = left + width + 30.0
    );
    for (k, b) in bars.iter().enumerate() {
        let y = 6.0 + row * k as f64;
        let lower = if b.lower.is_finite() { b.lower } else { 0.0 };
        let _ = writeln!(
            s,
            "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{}</text>",
            left - 6.0,
            y + 13.0,
            escape(&b.label)
        );
        match proved(b) {
            Some(upper) => {
                let _ = writeln!(
                    s,
                    "<rect x=\"{:.2}\" y=\"{y:.1}\" width=\"{:.2}\" height=\"18\" fill=\"#c9d8f0\" \
                     stroke=\"#4a78c2\"/>",
                    at(lower),
                    (at(upper) - at(lower)).max(0.8)
                );
            }
            None => {
                let _ = writeln!(
                    s,
                    "<path d=\"M{:.2} {y:.1} H{:.2} l8 9 l-8 9 H{:.2} Z\" fill=\"none\" \
                     stroke=\"#c22\" stroke-dasharray=\"4 3\"/>",
                    at(lower),
                    left + width,
                    at(lower)
                );
            }
        }
        let _ = writeln!(
            s,
            "<rect x=\"{left}\" y=\"{y:.1}\" width=\"{:.2}\" height=\"18\" fill=\"#4a78c2\"/>",
            at(lower) - left
        );
    }
    let axis = 6.0 + row * bars.len() as f64 + 4.0;
    let _ = writeln!(
        s,
        "<line x1=\"{left}\" y1=\"{axis:.1}\" x2=\"{:.1}\" y2=\"{axis:.1}\" stroke=\"#333\"/>",
        left + width
    );
    for i in 0..=4 {
        let v = scale_max * f64::from(i) / 4.0;
        let x = at(v);
        let _ = writeln!(
            s,
            "<line x1=\"{x:.1}\" y1=\"{axis:.1}\" x2=\"{x:.1}\" y2=\"{:.1}\" stroke=\"#333\"/>\n\
             <text x=\"{x:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{}</text>",
            axis + 4.0,
            axis + 16.0,
            escape(&tick_label(v))
        );
    }
    let _ = writeln!(
        s,
        "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{}</text>",
        left + width,
        axis + 30.0,
        escape(unit)
    );
    s.push_str("</svg>\n");
    Figure {
        caption: caption.to_string(),
        svg: s,
    }
}

/// The smallest of 1, 2, 2.5 or 5 times a power of ten at least `v` (> 0): an axis's end; `v`
/// itself where that is not a finite number at least `v` (subnormal or huge values).
fn nice_ceiling(v: f64) -> f64 {
    let p = 10f64.powf(v.log10().floor());
    let nice = [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|m| m * p)
        .find(|&c| c >= v)
        .unwrap_or(10.0 * p);
    if nice.is_finite() && nice >= v && nice > 0.0 {
        nice
    } else {
        v
    }
}

/// An axis tick's label: `v` to twelve significant digits, in plain decimals.
fn tick_label(v: f64) -> String {
    format!("{v:.11e}")
        .parse::<f64>()
        .map_or(format!("{v}"), |t| format!("{t}"))
}

/// What a run was made from, for the "Inputs and settings" section.
#[derive(Clone, Copy, Debug)]
pub struct Provenance<'a> {
    /// The inputs with their hashes.
    pub inputs: &'a [Input],
    /// Number of measured configurations.
    pub configurations: usize,
    /// The measurement error bounds in words: `(what, "± value unit")`.
    pub error_bounds: &'a [(String, String)],
    /// When the run was made.
    pub date: &'a str,
    /// The command line.
    pub command: &'a str,
    /// The run's settings, as `(name, value)`.
    pub settings: &'a [(String, String)],
}

/// The "Inputs and settings" section: each input with its SHA-256 and size, the error bounds,
/// the software version, date, command and settings.
pub fn inputs_section(h: &mut String, p: &Provenance<'_>) {
    h.push_str("<section id=\"inputs\">\n<h2>Inputs and settings</h2>\n");
    h.push_str("<table>\n<tr><th>input</th><th>file</th><th>SHA-256</th><th>bytes</th></tr>\n");
    for i in p.inputs {
        let _ = writeln!(
            h,
            "<tr><td>{}</td><td><code>{}</code></td><td class=\"hash\">{}</td><td class=\"num\">{}</td></tr>",
            escape(&i.role),
            escape(&i.name),
            i.sha256,
            i.bytes
        );
    }
    let _ = writeln!(
        h,
        "</table>\n<p>{} measured configurations. Measurement error bounds (half-widths of \
         the measurement boxes):</p>",
        p.configurations
    );
    pairs(h, &["error", "bound"], p.error_bounds);
    let mut settings = vec![
        ("software".to_string(), format!("certicalib {VERSION}")),
        ("date".to_string(), p.date.to_string()),
        ("command".to_string(), p.command.to_string()),
    ];
    settings.extend(p.settings.iter().cloned());
    pairs(h, &["setting", "value"], &settings);
    h.push_str("</section>\n");
}

/// The start of a certificate page up to its `<h1>` and subtitle (`title` names what was
/// calibrated; `date` is [`now`]).
pub fn page_start(title: &str, date: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"/>\n\
         <meta name=\"generator\" content=\"certicalib {VERSION}\"/>\n\
         <title>Calibration certificate — {t}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n\
         <h1>Calibration certificate</h1>\n<p class=\"subtitle\">{t} · certicalib {VERSION} · {d}</p>\n",
        t = escape(title),
        d = escape(date)
    )
}

/// The end of a certificate page.
pub const PAGE_END: &str = "</body>\n</html>\n";
