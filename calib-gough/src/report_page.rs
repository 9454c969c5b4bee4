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
use calib_pipeline::html::{
    badge, figure, inputs_section, inward, outward, page_start, section, Provenance, PAGE_END,
};
pub use calib_pipeline::html::{
    command_line, escape, now, sha256_hex, Figure, Input, Section, Table, DECIMALS, VERSION,
};
use std::fmt::Write as _;

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
    /// What these configurations cannot determine, in words (none when all is determined).
    pub identifiability: &'a [String],
}

/// Everything the calibration certificate states: the HTML page `gough certify --report` writes.
#[derive(Clone, Debug)]
pub struct ReportPage<'a> {
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

impl ReportPage<'_> {
    /// The page, as one HTML document.
    pub fn to_html(&self) -> Result<String, PlotError> {
        let mut h = page_start(&self.title, &self.date);
        self.summary(&mut h);
        self.inputs(&mut h);
        for leg in &self.legs {
            self.leg(&mut h, leg)?;
        }
        for s in &self.sections {
            section(&mut h, s);
        }
        h.push_str(READING);
        h.push_str(PAGE_END);
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
        self.findings(h);
        self.leg_table(h);
    }

    /// The summary's list: the widest parameter, empty legs and outliers, boxes reaching x0,
    /// refuted least-squares solutions, the time.
    fn findings(&self, h: &mut String) {
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
                    |c| {
                        format!(
                            "culprit {}",
                            verdict::name_configurations(r, &self.names, c)
                        )
                    },
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
                    escape(&verdict::name_configurations(r, &self.names, &r.outliers)),
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
    }

    /// The summary's table: one row per leg.
    fn leg_table(&self, h: &mut String) {
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
        inputs_section(
            h,
            &Provenance {
                inputs: &self.inputs,
                configurations: self.configurations,
                error_bounds: &self.error_bounds,
                date: &self.date,
                command: &self.command,
                settings: &self.settings,
            },
        );
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
        for s in leg.identifiability {
            let _ = writeln!(
                h,
                "<p class=\"evidence\">Identifiability: {}</p>",
                escape(s)
            );
        }
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
