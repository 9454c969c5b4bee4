//! The arm's calibration certificate: one self-contained HTML page (see
//! [`calib_pipeline::html`]) with the verdict and its evidence in words, the identifiability
//! findings, a table and a figure of every free parameter (prior box, certified outer box, inner
//! bounds, least-squares value), the inputs' SHA-256 and the settings. `arm certify --report` and
//! `arm demo --report` write it.

use crate::certification::{units, ArmRun};
use crate::simulate::Uncertainty;
use calib_core::{Interval, Status};
use calib_pipeline::html::{
    badge, escape, figure, inputs_section, inward, outward, page_start, Figure, Input, Provenance,
    DECIMALS, PAGE_END,
};
use calib_pipeline::is_fixed;
use calib_pipeline::verdict::{self, ConfigurationNames, Standing};
use std::fmt::Write as _;

/// Everything the arm's calibration certificate states: the HTML page `arm certify --report` writes.
#[derive(Clone, Debug)]
pub struct ArmReportPage<'a> {
    /// What was calibrated ("6-axis arm, 50 configurations").
    pub title: String,
    /// The command line that produced the run.
    pub command: String,
    /// When the run was made (RFC 3339, UTC).
    pub date: String,
    /// The inputs with their hashes.
    pub inputs: Vec<Input>,
    /// The error bounds the measurements were declared with.
    pub uncertainty: Uncertainty,
    /// The settings of the run, as `(name, value)`.
    pub settings: Vec<(String, String)>,
    /// The certified run.
    pub run: &'a ArmRun,
    /// How configurations are named (file and lines).
    pub names: ConfigurationNames<'a>,
    /// The outliers the run tolerates.
    pub tolerated: usize,
    /// The true parameters, when the data were simulated (shown beside the certified boxes).
    pub truth: Option<&'a [f64]>,
    /// How the error bounds were found (`--error-scale auto`), in words; empty when they were
    /// the uncertainty file's.
    pub error_scale: Vec<String>,
}

impl ArmReportPage<'_> {
    /// The page, as one HTML document.
    pub fn to_html(&self) -> String {
        let mut h = page_start(&self.title, &self.date);
        self.summary(&mut h);
        self.identifiability(&mut h);
        self.parameters(&mut h);
        self.inputs(&mut h);
        h.push_str(READING);
        h.push_str(PAGE_END);
        h
    }

    /// The free parameters (index into the outcome).
    fn free(&self) -> Vec<usize> {
        let o = &self.run.outcome;
        (0..o.x0.len()).filter(|&j| !is_fixed(o.x0[j])).collect()
    }

    fn summary(&self, h: &mut String) {
        let o = &self.run.outcome;
        let _ = writeln!(
            h,
            "<section id=\"summary\" class=\"summary\">\n<h2>Summary {}</h2>",
            badge(o.status)
        );
        let mut sentences = verdict::verdict(o, &self.names, self.tolerated);
        sentences.extend(verdict::outliers(o, &self.names, self.tolerated));
        sentences.extend(verdict::not_determined(o));
        match o.converged {
            None if o.inner.is_some() => sentences.push(
                "Tightness: after one contraction (the paper's x1); --hull refines to the tight \
                 hull."
                    .into(),
            ),
            _ => sentences.extend(verdict::tightness(o).map(|m| format!("Tightness: {m}."))),
        }
        for s in &sentences {
            let _ = writeln!(h, "<p class=\"evidence\">{}</p>", escape(s));
        }
        for s in &self.error_scale {
            let _ = writeln!(
                h,
                "<p class=\"evidence\">Error scale: {}</p>",
                escape(s.trim())
            );
        }
        h.push_str("<ul>\n");
        let free = self.free();
        if let Some(ratios) = o.width_ratios() {
            if let Some(&j) = free
                .iter()
                .max_by(|&&a, &&b| ratios[a].total_cmp(&ratios[b]))
            {
                let _ = writeln!(
                    h,
                    "<li>Largest outer/inner width ratio: <b>{:.3}</b> ({}): the true range of \
                     every parameter lies between its inner and outer bounds.</li>",
                    ratios[j],
                    escape(&o.names[j])
                );
            }
        }
        if let Some(line) = self.least_squares_in_words() {
            let _ = writeln!(h, "<li>{}</li>", escape(&line));
        }
        if let (Some(truth), Some(outer)) = (self.truth, &o.outer) {
            let inside = free
                .iter()
                .filter(|&&j| outer[j].contains(truth[j]))
                .count();
            let _ = writeln!(
                h,
                "<li>Simulated data: the true parameters lie inside the outer box in {inside} of \
                 {} free parameters.</li>",
                free.len()
            );
        }
        let _ = writeln!(
            h,
            "<li>{} free parameters, {} fixed; {} Newton/LP steps, {} box{} contracted, {:.2} s.</li>\n</ul>\n</section>",
            free.len(),
            o.x0.len() - free.len(),
            o.iterations,
            o.boxes,
            if o.boxes == 1 { "" } else { "es" },
            o.seconds
        );
    }

    /// Where the least-squares solution stands against the certificate, in words.
    fn least_squares_in_words(&self) -> Option<String> {
        let o = &self.run.outcome;
        let fit = self.run.fit.as_ref()?;
        let what = format!(
            "The least-squares solution (Levenberg–Marquardt from the nominal, rms residual \
             {:.4} mm)",
            fit.rms
        );
        let named = |p: &[usize]| {
            p.iter()
                .map(|&j| o.names[j].as_str())
                .collect::<Vec<_>>()
                .join(", ")
        };
        let certified = match o.status {
            Status::Empty => None,
            _ => Some(o.outer.as_deref().unwrap_or(&o.x0)),
        };
        Some(match verdict::standing(&o.x0, certified, &fit.x) {
            Standing::Inside => {
                format!("{what} lies inside the certified outer box (which alone does not prove it consistent).")
            }
            Standing::Refuted(p) if p.is_empty() => format!(
                "{what} lies in x0, where no parameter vector fits the measurements: it does not \
                 fit them within their error bounds."
            ),
            Standing::Refuted(p) => format!(
                "{what} lies outside the certified outer box (in {}): it is proved not to fit \
                 the measurements within their error bounds.",
                named(&p)
            ),
            Standing::BeyondX0(p) => format!(
                "{what} lies outside the prior box x0 (in {}), where this certificate proves \
                 nothing.",
                named(&p)
            ),
        })
    }

    fn identifiability(&self, h: &mut String) {
        let id = &self.run.identifiability;
        h.push_str("<section id=\"identifiability\">\n<h2>Identifiability</h2>\n");
        if let (Some(first), Some(last)) = (id.singular_values.first(), id.singular_values.last()) {
            let _ = writeln!(
                h,
                "<p>{} free parameters; singular values of the scaled identification Jacobian at \
                 the nominal geometry from {first:.3e} to {last:.3e}.</p>",
                id.singular_values.len()
            );
        }
        let sentences = id.sentences(&self.run.outcome.names);
        if sentences.is_empty() {
            h.push_str(
                "<p class=\"evidence\">Every free parameter is determined by these \
                 configurations (to first order).</p>\n",
            );
        }
        for s in sentences {
            let _ = writeln!(h, "<p class=\"evidence\">{}</p>", escape(&s));
        }
        h.push_str("</section>\n");
    }

    fn parameters(&self, h: &mut String) {
        let o = &self.run.outcome;
        let units = units(o.names.len().saturating_sub(9) / 5);
        let ratios = o.width_ratios();
        let lsq = self.run.fit.as_ref().map(|f| &f.x);
        h.push_str("<section id=\"parameters\">\n<h2>Parameters</h2>\n<table>\n<tr><th>parameter</th><th>unit</th><th>x0 (prior)</th><th>outer (certified)</th><th>inner</th><th>outer/inner</th>");
        if lsq.is_some() {
            h.push_str("<th>least squares</th>");
        }
        if self.truth.is_some() {
            h.push_str("<th>truth (simulated)</th>");
        }
        h.push_str("</tr>\n");
        let cell = |b: &Option<Vec<Interval>>, j: usize, print: fn(Interval) -> String| {
            b.as_ref().map_or("—".to_string(), |b| print(b[j]))
        };
        for j in self.free() {
            let ratio = ratios
                .as_ref()
                .map_or("—".into(), |r| format!("{:.3}", r[j]));
            let _ = write!(
                h,
                "<tr><td>{}</td><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{ratio}</td>",
                escape(&o.names[j]),
                escape(&units[j]),
                outward(o.x0[j]),
                cell(&o.outer, j, outward),
                cell(&o.inner, j, inward),
            );
            let outside = |v: f64| o.outer.as_ref().is_some_and(|b| !b[j].contains(v));
            for v in lsq
                .map(|x| x[j])
                .into_iter()
                .chain(self.truth.map(|t| t[j]))
            {
                let mark = if outside(v) { " (outside outer)" } else { "" };
                let _ = write!(h, "<td class=\"num\">{v:.DECIMALS$}{mark}</td>");
            }
            h.push_str("</tr>\n");
        }
        let fixed: Vec<&str> = (0..o.x0.len())
            .filter(|&j| is_fixed(o.x0[j]))
            .map(|j| o.names[j].as_str())
            .collect();
        let _ = writeln!(
            h,
            "</table>\n<p class=\"note\">mm and degrees. Certified boxes are printed rounded \
             outward, inner bounds inward, to {DECIMALS} decimals, so the printed boxes keep their \
             meaning; the JSON report has the exact bounds.{}</p>",
            if fixed.is_empty() {
                String::new()
            } else {
                escape(&format!(" Fixed (radius 0): {}.", fixed.join(", ")))
            }
        );
        figure(
            h,
            &Figure {
                caption: "Each free parameter, zoomed on its certified outer box (blue, the \
                          middle two thirds of the row): every consistent value lies in it; the \
                          inner bounds (green) are attained by certified consistent parameter \
                          vectors; the grey line is the prior box x0 where it is in view; the \
                          black tick is the least-squares value, the red one the simulated truth \
                          (ticks at the row's ends lie beyond it)."
                    .into(),
                svg: self.strips(),
            },
        );
        h.push_str("</section>\n");
    }

    /// One horizontal strip per free parameter, scaled to its outer box plus a quarter of its width
    /// on each side (to its prior box when there is no outer box).
    fn strips(&self) -> String {
        let o = &self.run.outcome;
        let free = self.free();
        let (left, width, row) = (90.0, 560.0, 18.0);
        let height = row * free.len() as f64 + 10.0;
        let mut s = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{height}\" \
             viewBox=\"0 0 {w} {height}\" font-family=\"sans-serif\" font-size=\"11\">\n",
            w = left + width + 10.0
        );
        for (k, &j) in free.iter().enumerate() {
            let view = match &o.outer {
                Some(b) if b[j].wid() > 0.0 => {
                    let q = 0.25 * b[j].wid();
                    (b[j].inf() - q, b[j].sup() + q)
                }
                _ => (o.x0[j].inf(), o.x0[j].sup()),
            };
            let at = |v: f64| left + width * ((v - view.0) / (view.1 - view.0)).clamp(0.0, 1.0);
            let y = 5.0 + row * k as f64;
            let (p0, p1) = (at(o.x0[j].inf()), at(o.x0[j].sup()));
            let _ = writeln!(
                s,
                "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\n\
                 <rect x=\"{p0:.2}\" y=\"{}\" width=\"{:.2}\" height=\"2\" fill=\"#bbb\"/>",
                left - 6.0,
                y + 11.0,
                escape(&o.names[j]),
                y + 7.0,
                p1 - p0
            );
            let bar = |s: &mut String, b: &Option<Vec<Interval>>, color: &str, top: f64, h: f64| {
                if let Some(b) = b {
                    let (a, c) = (at(b[j].inf()), at(b[j].sup()));
                    let _ = writeln!(
                        s,
                        "<rect x=\"{a:.2}\" y=\"{:.2}\" width=\"{:.2}\" height=\"{h}\" fill=\"{color}\"/>",
                        y + top,
                        (c - a).max(0.8)
                    );
                }
            };
            bar(&mut s, &o.outer, "#4a78c2", 2.0, 12.0);
            bar(&mut s, &o.inner, "#3f9b46", 5.0, 6.0);
            let ticks = [
                (self.run.fit.as_ref().map(|f| f.x[j]), "#000"),
                (self.truth.map(|t| t[j]), "#c22"),
            ];
            for (v, color) in ticks {
                if let Some(v) = v {
                    let _ = writeln!(
                        s,
                        "<rect x=\"{:.2}\" y=\"{}\" width=\"1.6\" height=\"16\" fill=\"{color}\"/>",
                        at(v) - 0.8,
                        y
                    );
                }
            }
        }
        s.push_str("</svg>\n");
        s
    }

    fn inputs(&self, h: &mut String) {
        let u = &self.uncertainty;
        let bounds = [
            ("joint readings".to_string(), format!("± {} °", u.joint_deg)),
            (
                "tracked point, per coordinate".to_string(),
                format!("± {} mm", u.pos),
            ),
        ];
        inputs_section(
            h,
            &Provenance {
                inputs: &self.inputs,
                configurations: self.names.lines.len(),
                error_bounds: &bounds,
                date: &self.date,
                command: &self.command,
                settings: &self.settings,
            },
        );
    }
}

const READING: &str = "<section id=\"reading\">\n<h2>How to read this certificate</h2>\n\
<p>The model is the tracked point p = T_base · A_1(q_1) ⋯ A_N(q_N) · t, with \
A_i(q) = Rz(theta_i + q) Tz(d_i) Tx(a_i) Rx(alpha_i) Ry(beta_i) (Denavit–Hartenberg plus \
Hayati&#39;s beta), T_base = Trans(base_x, base_y, base_z) Rz(base_rz) Ry(base_ry) Rx(base_rx) \
and t = (tool_x, tool_y, tool_z) in the flange frame; lengths in mm, angles in degrees. \
Each measured configuration gives three equations (x, y, z of the tracked point) that share its \
joint readings.</p>\n\
<p>x0 is the prior box (nominal ± radius). The outer box is certified: every parameter vector in \
x0 for which, in every configuration, one set of joint readings within their error bounds puts \
the tracked point within its error bounds of the measured one, lies in it (interval Newton and \
linear programs with outward rounding; the answers of the LP solver only guide the bounds). The \
inner bounds are attained by parameter vectors proved consistent in that same coupled sense. \
A verdict \u{201c}empty\u{201d} is a proof that no parameter vector of x0 fits the data: the \
data, the error bounds or the model are wrong.</p>\n</section>\n";
