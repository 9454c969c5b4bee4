//! The calibration certificate: one self-contained HTML page (inline SVG figures and styles, no
//! scripts, fonts, images or links to fetch) that says what was proved, from which data, with which
//! software and settings. `gough certify --report` and `gough reproduce --out` write it.
//!
//! The page is well-formed XML as well as HTML (every element closed, every attribute quoted, no
//! named entities), so that it can be checked by an XML parser and embedded or post-processed.
//!
//! Printed bounds are rounded so that the printed boxes keep their meaning: x0, x1, x2 and the
//! outer box outward (the printed box contains the certified one), the inner bounds inward (every
//! printed inner bound is still attained by a certified consistent parameter vector). The JSON
//! report keeps the exact bounds.

use crate::certification::LegResult;
use crate::measurement::Uncertainty;
use crate::plot::{self, PlotError, Points};
use crate::verdict::{self, ConfigurationNames, Standing};
use crate::PARAMETER_NAMES;
use calib_core::{Interval, Status};
use sha2::{Digest, Sha256};
use std::fmt::Write as _;

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

/// The measurement error bounds in words, with units: `(what, "± value unit")`.
pub fn error_bounds(u: &Uncertainty, rodrigues: bool) -> Vec<(String, String)> {
    let mut rows = vec![
        (
            "platform position (each coordinate)",
            format!("± {} cm", u.pos),
        ),
        ("leg reading", format!("± {} cm", u.len)),
    ];
    if rodrigues {
        rows.push(("Rodrigues vector (each component)", format!("± {}", u.q)));
    } else {
        rows.push(("rotation axis (each component)", format!("± {}", u.axis)));
        rows.push(("rotation angle", format!("± {}°", u.angle_deg)));
    }
    rows.into_iter().map(|(k, v)| (k.to_string(), v)).collect()
}

/// One leg on the certificate.
#[derive(Clone, Copy, Debug)]
pub struct LegEntry<'a> {
    /// The certified result.
    pub result: &'a LegResult,
    /// The nominal parameters (the centre of x0, as given).
    pub nominal: [f64; 7],
    /// Least-squares solutions for this leg, when least squares was run (none otherwise).
    pub least_squares: &'a [[f64; 7]],
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

/// Everything the certificate states.
#[derive(Clone, Debug)]
pub struct Certificate<'a> {
    /// What was calibrated ("hexapod, 21 configurations").
    pub title: String,
    /// The command line that produced the run.
    pub command: String,
    /// When the run was made (RFC 3339, UTC).
    pub date: String,
    /// The inputs with their hashes.
    pub inputs: Vec<Input>,
    /// Number of measured configurations.
    pub configurations: usize,
    /// The measurement error bounds, in words ([`error_bounds`]).
    pub error_bounds: Vec<(String, String)>,
    /// The settings of the run, as `(name, value)`.
    pub settings: Vec<(String, String)>,
    /// Total wall-clock seconds.
    pub seconds: f64,
    /// The legs, in order.
    pub legs: Vec<LegEntry<'a>>,
    /// How configurations are named (file and lines).
    pub names: ConfigurationNames<'a>,
    /// Sections after the legs.
    pub sections: Vec<Section>,
}

/// The certicalib version that writes the certificate.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The current time in RFC 3339 (UTC, whole seconds), for [`Certificate::date`].
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

/// Decimals printed for bounds: 1e-5 cm (0.1 µm), well below the paper's 5 µm error bounds.
const DECIMALS: usize = 5;

/// `v` printed with [`DECIMALS`] decimals, rounded down (`down`) or up: the printed number is
/// `<= v` (or `>= v`) exactly, checked on the parsed text.
fn rounded(v: f64, down: bool) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    let step = 10f64.powi(-(DECIMALS as i32));
    let mut x = v;
    for _ in 0..8 {
        let s = format!("{x:.DECIMALS$}");
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
fn outward(v: Interval) -> String {
    if v.is_empty() {
        return "empty".into();
    }
    format!("[{}, {}]", rounded(v.inf(), true), rounded(v.sup(), false))
}

/// `[lo, hi]` rounded inward: the printed interval lies inside `v`; exact (shortest round-trip
/// digits) when `v` is too narrow for rounded bounds.
fn inward(v: Interval) -> String {
    if v.is_empty() {
        return "empty".into();
    }
    let (lo, hi) = (rounded(v.inf(), false), rounded(v.sup(), true));
    match (lo.parse::<f64>(), hi.parse::<f64>()) {
        (Ok(a), Ok(b)) if a <= b => format!("[{lo}, {hi}]"),
        _ => format!("[{:?}, {:?}]", v.inf(), v.sup()),
    }
}

const STYLE: &str = "
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

impl Certificate<'_> {
    /// The page, as one HTML document.
    pub fn to_html(&self) -> Result<String, PlotError> {
        let mut h = String::new();
        let _ = write!(
            h,
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n\
             <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"/>\n\
             <meta name=\"generator\" content=\"certicalib {VERSION}\"/>\n\
             <title>Calibration certificate — {}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n\
             <h1>Calibration certificate</h1>\n<p class=\"subtitle\">{} · certicalib {VERSION} · {}</p>\n",
            escape(&self.title),
            escape(&self.title),
            escape(&self.date)
        );
        self.summary(&mut h);
        self.inputs(&mut h);
        for leg in &self.legs {
            self.leg(&mut h, leg)?;
        }
        for s in &self.sections {
            section(&mut h, s);
        }
        h.push_str(READING);
        h.push_str("</body>\n</html>\n");
        Ok(h)
    }

    fn summary(&self, h: &mut String) {
        let count = |s: Status| self.legs.iter().filter(|l| l.result.status == s).count();
        let (ok, empty, undecided) = (
            count(Status::Consistent),
            count(Status::Empty),
            count(Status::Undecided),
        );
        h.push_str("<section id=\"summary\" class=\"summary\">\n<h2>Summary</h2>\n");
        let _ = writeln!(
            h,
            "<p><b>{} of {} legs certified consistent, {empty} proved empty, {undecided} \
             undecided.</b> {}</p>",
            ok,
            self.legs.len(),
            if empty == 0 {
                "For every leg, every parameter vector that fits all measurements within their \
                 error bounds lies in the outer box reported below."
            } else {
                "A leg proved empty has no parameter vector in its initial box that fits all its \
                 measurements within their error bounds: the data, the error bounds or the model \
                 are wrong for it."
            }
        );
        h.push_str("<ul>\n");
        if let Some((leg, j, w)) = self.widest() {
            let inner = leg
                .result
                .inner
                .map(|b| {
                    format!(
                        "; the true range is at least {:.5} cm wide (inner bounds)",
                        b[j].wid()
                    )
                })
                .unwrap_or_default();
            let _ = writeln!(
                h,
                "<li>Widest certified parameter: <b>{}</b> of leg {}, {w:.5} cm wide (outer box{})</li>",
                PARAMETER_NAMES[j],
                leg.result.leg + 1,
                escape(&inner)
            );
        }
        for leg in &self.legs {
            let r = leg.result;
            if r.status == Status::Empty {
                let culprit = r.conflict.as_ref().map_or_else(
                    || "no small set of culprit configurations was isolated".to_string(),
                    |c| format!("culprit {}", self.names.name(c)),
                );
                let _ = writeln!(
                    h,
                    "<li>Leg {} proved empty: {}.</li>",
                    r.leg + 1,
                    escape(&culprit)
                );
            }
            if !r.outliers.is_empty() && r.status != Status::Empty {
                let _ = writeln!(
                    h,
                    "<li>Leg {}: {} proved to be outlier{} and tolerated.</li>",
                    r.leg + 1,
                    escape(&self.names.name(&r.outliers)),
                    if r.outliers.len() == 1 { "" } else { "s" }
                );
            }
        }
        let reaching: Vec<String> = self
            .legs
            .iter()
            .filter_map(|l| {
                let faces = verdict::x0_faces(l.result);
                let names: Vec<&str> = faces.iter().map(|(j, _)| PARAMETER_NAMES[*j]).collect();
                (!names.is_empty())
                    .then(|| format!("leg {} ({})", l.result.leg + 1, names.join(", ")))
            })
            .collect();
        if !reaching.is_empty() {
            let _ = writeln!(
                h,
                "<li>The outer box reaches the initial box x0 in {}: consistent parameter vectors \
                 may lie beyond x0 there (the certificate covers x0 only).</li>",
                reaching.join("; ")
            );
        }
        let outside: Vec<String> = self
            .legs
            .iter()
            .filter_map(|l| {
                let (_, n, _) = tally(l);
                (n > 0).then(|| {
                    format!(
                        "leg {} ({n} of {})",
                        l.result.leg + 1,
                        l.least_squares.len()
                    )
                })
            })
            .collect();
        if !outside.is_empty() {
            let _ = writeln!(
                h,
                "<li>Least-squares solutions in x0 but outside the certified box, hence proved \
                 not to fit the measurements within their error bounds: {}.</li>",
                outside.join(", ")
            );
        }
        let _ = writeln!(h, "<li>Computed in {:.2} s.</li>\n</ul>", self.seconds);
        h.push_str("<table>\n<tr><th>leg</th><th>verdict</th><th>widest parameter (outer)</th><th>largest outer/inner width ratio</th><th>boxes contracted</th><th>seconds</th></tr>\n");
        for leg in &self.legs {
            let r = leg.result;
            let widest = r.outer.map_or("—".into(), |b| {
                let j = widest_index(&b);
                format!("{} {:.5} cm", PARAMETER_NAMES[j], b[j].wid())
            });
            let ratio = verdict::width_ratios(r).map_or("—".into(), |q| {
                format!("{:.3}", q.iter().copied().fold(0.0, f64::max))
            });
            let _ = writeln!(
                h,
                "<tr><td><a href=\"#leg-{n}\">{n}</a></td><td>{}</td><td>{widest}</td><td class=\"num\">{ratio}</td><td class=\"num\">{}</td><td class=\"num\">{:.3}</td></tr>",
                badge(r.status),
                r.boxes,
                r.seconds,
                n = r.leg + 1
            );
        }
        h.push_str("</table>\n</section>\n");
    }

    /// The leg and parameter with the widest outer box.
    fn widest(&self) -> Option<(&LegEntry<'_>, usize, f64)> {
        self.legs
            .iter()
            .filter_map(|l| {
                let b = l.result.outer?;
                let j = widest_index(&b);
                Some((l, j, b[j].wid()))
            })
            .max_by(|a, b| a.2.total_cmp(&b.2))
    }

    fn inputs(&self, h: &mut String) {
        h.push_str("<section id=\"inputs\">\n<h2>Inputs and settings</h2>\n");
        h.push_str("<table>\n<tr><th>input</th><th>file</th><th>SHA-256</th><th>bytes</th></tr>\n");
        for i in &self.inputs {
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
            self.configurations
        );
        pairs(h, &["error", "bound"], &self.error_bounds);
        let mut settings = vec![
            ("software".to_string(), format!("certicalib {VERSION}")),
            ("date".to_string(), self.date.clone()),
            ("command".to_string(), self.command.clone()),
        ];
        settings.extend(self.settings.iter().cloned());
        pairs(h, &["setting", "value"], &settings);
        h.push_str("</section>\n");
    }

    fn leg(&self, h: &mut String, leg: &LegEntry<'_>) -> Result<(), PlotError> {
        let r = leg.result;
        let _ = writeln!(
            h,
            "<section class=\"leg\" id=\"leg-{n}\">\n<h2>Leg {n} {}</h2>",
            badge(r.status),
            n = r.leg + 1
        );
        for sentence in verdict::verdict(r, &self.names) {
            let _ = writeln!(h, "<p class=\"evidence\">{}</p>", escape(&sentence));
        }
        if let (Some(ratio), Some(meaning)) = (verdict::width_ratios(r), verdict::tightness(r)) {
            let worst = ratio.iter().copied().fold(0.0, f64::max);
            let _ = writeln!(
                h,
                "<p class=\"evidence\">Tightness: outer/inner width at most {worst:.3}; {}.</p>",
                escape(meaning)
            );
        }
        if let Some(line) = verdict::touching_x0(r) {
            let _ = writeln!(h, "<p class=\"evidence\">Note: {}.</p>", escape(&line));
        }
        if let Some(line) = verdict::outliers(r, &self.names) {
            let _ = writeln!(h, "<p class=\"evidence\">{}</p>", escape(&line));
        }
        if let Some(w) = r.witness {
            let _ = writeln!(
                h,
                "<p class=\"evidence\">A certified consistent parameter vector (witness, exact \
                 digits): <code>{}</code></p>",
                w.map(|v| format!("{v:?}")).join(", ")
            );
        }
        if let Some((n, inner, outer)) = r.paving {
            let _ = writeln!(
                h,
                "<p class=\"evidence\">Paving: {n} boxes; volume certified inside the solution set \
                 {inner:.3e}, volume of the boxes that may hold solutions {outer:.3e} (cm^7).</p>"
            );
        }
        least_squares_in_words(h, leg);
        self.parameter_table(h, leg);
        let layers = plot::leg_layers(r);
        let points = (!leg.least_squares.is_empty()).then_some(Points {
            label: if leg.least_squares.len() == 1 {
                "least squares"
            } else {
                "least-squares solutions"
            },
            colour: plot::LEAST_SQUARES,
            points: leg.least_squares,
        });
        let title = format!("Leg {}: boxes in three projections", r.leg + 1);
        figure(
            h,
            &Figure {
                caption: "The boxes projected on (ax, ay), (bx, by) and (az, l), in cm: every \
                          consistent parameter vector lies in the outer box; the shaded inner box \
                          is spanned by certified consistent ones."
                    .into(),
                svg: plot::nested_boxes(
                    &layers,
                    points,
                    &plot::LEG_PROJECTIONS,
                    &PARAMETER_NAMES,
                    &title,
                )?,
            },
        );
        if layers.len() > 1 {
            figure(
                h,
                &Figure {
                    caption:
                        "Each parameter's range relative to its nominal value: the initial box \
                          x0, the certified boxes and the inner bounds."
                            .into(),
                    svg: plot::parameter_ranges(
                        &layers,
                        &leg.nominal,
                        &PARAMETER_NAMES,
                        &format!("Leg {}: parameter ranges", r.leg + 1),
                    )?,
                },
            );
        }
        h.push_str("</section>\n");
        Ok(())
    }

    fn parameter_table(&self, h: &mut String, leg: &LegEntry<'_>) {
        let r = leg.result;
        let mut columns: Vec<(&str, Option<[Interval; 7]>, bool)> =
            vec![("x0", Some(r.x0), true), ("x1", r.x1, true)];
        if let Some(x2) = r.x2 {
            columns.push(("x2 (sweep)", x2, true));
        }
        if r.converged.is_some() {
            columns.push(("outer", r.outer, true));
        }
        columns.push(("inner", r.inner, false));
        h.push_str("<table>\n<tr><th>parameter</th><th>nominal</th>");
        for (name, _, _) in &columns {
            let _ = write!(h, "<th>{name}</th>");
        }
        let _ = writeln!(
            h,
            "<th>{}/inner width</th></tr>",
            if r.converged.is_some() { "outer" } else { "x1" }
        );
        let ratio = verdict::width_ratios(r);
        for j in 0..7 {
            let _ = write!(
                h,
                "<tr><th>{}</th><td class=\"num\">{:.5}</td>",
                PARAMETER_NAMES[j], leg.nominal[j]
            );
            for (_, b, outer) in &columns {
                let cell = match b {
                    Some(b) if *outer => outward(b[j]),
                    Some(b) => inward(b[j]),
                    None => "—".into(),
                };
                let _ = write!(h, "<td class=\"num\">{cell}</td>");
            }
            let q = ratio.map_or("—".into(), |q| format!("{:.3}", q[j]));
            let _ = writeln!(h, "<td class=\"num\">{q}</td></tr>");
        }
        let _ = writeln!(
            h,
            "</table>\n<p class=\"note\">cm. Certified boxes are printed rounded outward, inner \
             bounds inward, to {DECIMALS} decimals, so the printed boxes keep their meaning.</p>"
        );
    }
}

/// Index of the widest component of a box.
fn widest_index(b: &[Interval; 7]) -> usize {
    (0..7)
        .max_by(|&i, &j| b[i].wid().total_cmp(&b[j].wid()))
        .unwrap_or(0)
}

/// A leg's least-squares solutions counted by standing: inside the certified box, refuted (in x0,
/// outside the certified box), beyond x0.
fn tally(leg: &LegEntry<'_>) -> (usize, usize, usize) {
    leg.least_squares.iter().fold((0, 0, 0), |(i, r, b), x| {
        match verdict::leg_standing(leg.result, x) {
            Standing::Inside => (i + 1, r, b),
            Standing::Refuted(_) => (i, r + 1, b),
            Standing::BeyondX0(_) => (i, r, b + 1),
        }
    })
}

fn names_of(params: &[usize]) -> String {
    params
        .iter()
        .map(|&j| PARAMETER_NAMES[j])
        .collect::<Vec<_>>()
        .join(", ")
}

fn least_squares_in_words(h: &mut String, leg: &LegEntry<'_>) {
    let text = match leg.least_squares {
        [] => return,
        [x] => {
            let what = "The least-squares solution (Levenberg–Marquardt from the nominal geometry)";
            match verdict::leg_standing(leg.result, x) {
                Standing::Inside => format!(
                    "{what} lies inside the certified outer box (which alone does not prove it \
                     consistent)."
                ),
                Standing::Refuted(p) if p.is_empty() => format!(
                    "{what} lies in x0, where no parameter vector fits the measurements: it does \
                     not fit them within their error bounds."
                ),
                Standing::Refuted(p) => format!(
                    "{what} lies in x0 but outside the certified outer box (in {}): it does not \
                     fit the measurements within their error bounds.",
                    names_of(&p)
                ),
                Standing::BeyondX0(p) => format!(
                    "{what} lies outside x0 (in {}), where this certificate proves nothing.",
                    names_of(&p)
                ),
            }
        }
        all => {
            let (inside, refuted, beyond) = tally(leg);
            let mut parts = Vec::new();
            if inside > 0 {
                parts.push(format!("{inside} lie inside the certified outer box"));
            }
            if refuted > 0 {
                parts.push(format!(
                    "{refuted} lie in x0 but outside the certified box: they do not fit the \
                     measurements within their error bounds"
                ));
            }
            if beyond > 0 {
                parts.push(format!(
                    "{beyond} lie outside x0, where this certificate proves nothing"
                ));
            }
            format!(
                "Of {} least-squares solutions, {}.",
                all.len(),
                parts.join("; ")
            )
        }
    };
    let _ = writeln!(h, "<p class=\"evidence\">{}</p>", escape(&text));
}

fn badge(status: Status) -> String {
    let class = match status {
        Status::Consistent => "consistent",
        Status::Empty => "empty",
        Status::Undecided => "undecided",
    };
    format!(
        "<span class=\"badge {class}\">{}</span>",
        verdict::short_verdict(status)
    )
}

fn pairs(h: &mut String, header: &[&str; 2], rows: &[(String, String)]) {
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

fn figure(h: &mut String, f: &Figure) {
    let _ = writeln!(
        h,
        "<figure>\n{}\n<figcaption>{}</figcaption>\n</figure>",
        f.svg.trim(),
        escape(&f.caption)
    );
}

fn section(h: &mut String, s: &Section) {
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

const READING: &str = "<section id=\"reading\">\n<h2>How to read this certificate</h2>\n\
<p>Per leg, the unknowns are the base attachment point a = (ax, ay, az), the platform attachment \
point b = (bx, by, bz) and the leg offset l, in cm (Daney, Papegay &amp; Neumaier, ICRA 2004). \
x0 is the initial box (nominal ± radius). x1 is the paper's fixed point of interval Newton / \
linear-programming contractions; x2 the hull of its 128-box bisection sweep. The outer box is the \
tightest certified box: every parameter vector that fits every measurement within its error \
bounds lies in it, proved with outward rounding. The inner bounds are spanned by parameter \
vectors each proved to fit every measurement: the true range of each parameter covers at least \
the inner interval, so it lies between inner and outer, and the outer/inner width ratio bounds \
how much the outer box overstates it. A leg proved empty has no consistent parameter vector in \
x0: a proof that the data, the error bounds or the model are wrong for that leg.</p>\n</section>\n";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sha256_matches_known_digests() {
        assert_eq!(
            sha256_hex(b""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"
        );
        assert_eq!(
            sha256_hex(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
    }

    #[test]
    fn printed_bounds_keep_their_meaning() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand::rngs::StdRng::seed_from_u64(11);
        for _ in 0..20_000 {
            let lo: f64 = rng.random_range(-100.0..100.0);
            let hi = lo + rng.random_range(0.0..0.01) * rng.random_range(0.0..1.0f64).powi(4);
            let v = Interval::new(lo, hi);
            let parse = |s: &str| -> (f64, f64) {
                let inner = s.trim_start_matches('[').trim_end_matches(']');
                let (a, b) = inner.split_once(", ").unwrap();
                (a.parse().unwrap(), b.parse().unwrap())
            };
            let (a, b) = parse(&outward(v));
            assert!(a <= lo && hi <= b, "{v:?} printed {}", outward(v));
            let text = inward(v);
            let (a, b) = parse(&text);
            assert!(lo <= a && b <= hi && a <= b, "{v:?} printed {text}");
        }
        assert_eq!(outward(Interval::new(1.0, 2.0)), "[1.00000, 2.00000]");
        assert_eq!(rounded(0.123456, true), "0.12345");
        assert_eq!(rounded(0.123451, false), "0.12346");
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }
}
