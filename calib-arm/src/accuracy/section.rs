//! The accuracy certificate's section (`arm accuracy --report`): what calibration bought, in
//! words, two tables and a figure, over the joint space the user gave.

use super::{ToolAccuracyReport, ToolBracket};
use calib_pipeline::html::{brackets_figure, rounded, BracketBar, Section, Table};

impl ToolAccuracyReport {
    /// The certificate's section: the brackets of the worst tool-point error after calibration
    /// (and before, with the proved improvement), the configurations where they are reached, and
    /// where a larger error could still hide when a box budget ran out.
    pub fn section(&self) -> Section {
        let mut paragraphs = vec![self.claim()];
        if let Some(factor) = self.improvement() {
            let words = calib_pipeline::verdict::improvement("the worst tool-point error", factor);
            paragraphs.push(format!("{}.", capitalised(&words)));
        }
        for (name, b) in self.brackets() {
            if !b.converged && self.configurations.is_none() {
                paragraphs.push(format!(
                    "{}: the box budget ran out before the bracket closed; a larger error could \
                     still hide near {}° (the joint box giving the upper bound). Raise \
                     --max-set-boxes or --max-boxes to tighten it.",
                    capitalised(name),
                    ranges(&b.frontier_deg)
                ));
            }
        }
        let bars: Vec<BracketBar> = self
            .brackets()
            .map(|(name, b)| BracketBar {
                label: name.to_string(),
                lower: b.lower,
                upper: b.upper,
            })
            .collect();
        Section {
            heading: match self.configurations {
                Some(_) => "What calibration bought: the tool-point error at the task's \
                            configurations"
                    .to_string(),
                None => {
                    "What calibration bought: the tool-point error over the joint space".to_string()
                }
            },
            paragraphs,
            tables: vec![self.bracket_table(), self.worst_table()],
            figures: vec![brackets_figure(
                &bars,
                "mm",
                "The worst tool-point error, per robot: solid up to what an explicit \
                 configuration and geometry reach (attained), light from there to the proved \
                 upper bound; the worst error lies in the light part.",
            )],
        }
    }

    /// The robots' brackets: the calibrated one, then the one before calibration.
    fn brackets(&self) -> impl Iterator<Item = (&'static str, &ToolBracket)> {
        core::iter::once(("after calibration", &self.after))
            .chain(self.before.as_ref().map(|b| ("before calibration", b)))
    }

    /// What the bounds mean, over which joints and geometries.
    fn claim(&self) -> String {
        let geometries = if self.over_set {
            "every geometry θ* the measurements allow (the certified set: not its box, whose \
             corners the data rule out)"
        } else {
            "every geometry θ* in the robot file's box (the file has no certified set)"
        };
        let place = match self.configurations {
            Some(n) => format!(
                "at each of the task's {n} configurations as given (not between them; their hull \
                 is {}°)",
                ranges(&self.space.ranges_deg)
            ),
            None => format!(
                "over the whole joint space {}°",
                ranges(&self.space.ranges_deg)
            ),
        };
        format!(
            "For every joint within ±{}° of its reading and {geometries}, \
             the tool point the controller computes from the calibrated values, p(q; θ̂), differs \
             from where the real robot puts it, p(q; θ*), by at most the upper bound — proved \
             {place} — and by at least the lower bound, attained at an explicit configuration by \
             a geometry proved consistent with the measurements.{}",
            self.joint_error_text(),
            if self.before.is_some() {
                " Before calibration: the same error of the uncalibrated file's values, over \
                 every geometry in its prior box."
            } else {
                ""
            }
        )
    }

    /// Per robot: upper, lower, their ratio, boxes and seconds.
    fn bracket_table(&self) -> (String, Table) {
        let header = [
            "robot",
            "upper (proved, rounded up), mm",
            "lower (attained, rounded down), mm",
            "upper/lower",
            "boxes",
            "seconds",
        ]
        .map(String::from)
        .to_vec();
        let rows = self
            .brackets()
            .map(|(name, b)| {
                vec![
                    name.to_string(),
                    finite_or(b.upper, "not proved", |v| rounded(v, false)),
                    rounded(b.lower, true),
                    finite_or(b.ratio(), "—", |v| format!("{v:.3}")),
                    b.boxes.to_string(),
                    format!("{:.2}", b.seconds),
                ]
            })
            .collect();
        (
            "The worst tool-point error |p(q; θ*) − p(q; θ̂)|: the truth lies between lower and \
             upper."
                .to_string(),
            Table { header, rows },
        )
    }

    /// Per robot, the configuration and error of its lower bound.
    fn worst_table(&self) -> (String, Table) {
        let joints = self.space.ranges_deg.len();
        let mut header = vec!["robot".to_string()];
        header.extend((1..=joints).map(|k| format!("q{k} (°)")));
        header.extend(["error x, y, z (mm)", "|error| (mm)"].map(String::from));
        let rows = self
            .brackets()
            .filter_map(|(name, b)| b.worst.as_ref().map(|w| (name, w)))
            .map(|(name, w)| {
                let mut row = vec![name.to_string()];
                row.extend(w.joints_deg.iter().map(|q| format!("{q:.3}")));
                row.push(format!(
                    "{:.4}, {:.4}, {:.4}",
                    w.error[0], w.error[1], w.error[2]
                ));
                row.push(format!("{:.4}", w.value));
                row
            })
            .collect();
        (
            "Where each lower bound is reached: the commanded joints and the error there."
                .to_string(),
            Table { header, rows },
        )
    }
}

/// `q1 [lo, hi], q2 […]` for joint ranges in degrees.
fn ranges(r: &[[f64; 2]]) -> String {
    r.iter()
        .enumerate()
        .map(|(k, [lo, hi])| format!("q{} [{lo}, {hi}]", k + 1))
        .collect::<Vec<_>>()
        .join(", ")
}

/// `show(v)` for a finite `v`, else `otherwise`.
fn finite_or(v: f64, otherwise: &str, show: impl Fn(f64) -> String) -> String {
    if v.is_finite() {
        show(v)
    } else {
        otherwise.to_string()
    }
}

/// `words` with its first letter upper-case.
fn capitalised(words: &str) -> String {
    let mut c = words.chars();
    c.next()
        .map(|f| f.to_uppercase().chain(c).collect())
        .unwrap_or_default()
}
