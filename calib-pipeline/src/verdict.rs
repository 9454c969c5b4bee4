//! An outcome in plain words: the verdict and its evidence, the tightness reached, the outliers,
//! where a parameter vector found by other means stands. The terminal output and the certificates
//! of every robot say the same sentences.

use crate::outcome::Outcome;
use calib_core::{EmptinessProof, Interval, Status};

/// Names configurations by number and by their line in the measurement file.
#[derive(Clone, Copy, Debug)]
pub struct ConfigurationNames<'a> {
    /// The measurement file's name (as shown to the user).
    pub file: &'a str,
    /// The file line of each configuration (1-based lines, in configuration order).
    pub lines: &'a [usize],
    /// The configurations after the file's: rows carried over from an earlier calibration's
    /// certified set (`None` when nothing was carried over).
    pub carried: Option<CarriedRows<'a>>,
}

/// Configurations carried over from an earlier calibration's certified set, numbered after the
/// measurement file's.
#[derive(Clone, Copy, Debug)]
pub struct CarriedRows<'a> {
    /// The robot file that stored them (as shown to the user).
    pub file: &'a str,
    /// Per carried configuration, in order, its 1-based row in that file's stored set.
    pub rows: &'a [usize],
}

impl ConfigurationNames<'_> {
    /// "configurations 4, 8 (measurements.csv lines 5, 9)" for 0-based configurations `[3, 7]`.
    /// Configurations after the file's are named by their row in the stored set they were
    /// carried over from: "configurations 4, 62 (measurements.csv line 5; stored row 2 of
    /// calibrated.toml)" with 60 lines.
    pub fn name(&self, configs: &[usize]) -> String {
        let numbers: Vec<String> = configs.iter().map(|k| (k + 1).to_string()).collect();
        let plural =
            |n: usize, one: &'static str, many: &'static str| if n == 1 { one } else { many };
        let (here, earlier): (Vec<usize>, Vec<usize>) =
            configs.iter().partition(|&&k| k < self.lines.len());
        let mut at = Vec::new();
        if !here.is_empty() {
            let lines: Vec<String> = here.iter().map(|&k| self.lines[k].to_string()).collect();
            let line = plural(here.len(), "line", "lines");
            at.push(format!("{} {line} {}", self.file, lines.join(", ")));
        }
        if !earlier.is_empty() {
            let row_of = |k: usize| {
                let c = self.carried.and_then(|c| c.rows.get(k - self.lines.len()));
                c.map_or("?".to_string(), |r| r.to_string())
            };
            let rows: Vec<String> = earlier.iter().map(|&k| row_of(k)).collect();
            let from = self.carried.map_or("?", |c| c.file);
            let row = plural(earlier.len(), "row", "rows");
            at.push(format!("stored {row} {} of {from}", rows.join(", ")));
        }
        let noun = plural(configs.len(), "configuration", "configurations");
        format!("{noun} {} ({})", numbers.join(", "), at.join("; "))
    }
}

/// For an empty sub-problem whose certificate weighs most of what a certificate can weigh
/// ([`Outcome::spread`]): the misfit is spread over the data — the error bounds are too tight for
/// the model — and what to do next.
fn spread(r: &Outcome, names: &ConfigurationNames<'_>) -> Vec<String> {
    let support = r.support.as_deref().unwrap_or_default();
    let of = if names.lines.is_empty() {
        String::new()
    } else {
        format!(" of the {}", names.lines.len())
    };
    vec![
        format!(
            "spread: the proof of emptiness weighs {}{of} configurations — {} — a misfit spread \
             over the data rather than a few bad readings: the error bounds are too tight for the \
             model (no conflict set was searched: it would name many configurations)",
            support.len(),
            names.name(support)
        ),
        "find the bounds the data need with --error-scale auto; to look for a few bad readings \
         all the same, run with --max-outliers auto"
            .into(),
    ]
}

/// What proved a sub-problem empty, in words (`names`: the parameters' names).
pub fn proof_in_words(proof: Option<EmptinessProof>, names: &[String]) -> String {
    match proof {
        Some(EmptinessProof::CheapRejection { measurement }) => format!(
            "configuration {} fits no parameter vector left after contraction",
            measurement + 1
        ),
        Some(EmptinessProof::LpInfeasible) => {
            "the linear relaxation of the data has no solution (checked Farkas certificate)".into()
        }
        Some(EmptinessProof::EmptyIntersection { parameter }) => format!(
            "the certified lower and upper bounds of {} crossed",
            names.get(parameter).map_or("a parameter", String::as_str)
        ),
        Some(EmptinessProof::SecondOrder) => "a weighted sum of the configurations' residuals \
             is proved positive over the whole contracted box (second-order Farkas certificate)"
            .into(),
        Some(EmptinessProof::Subdivision) => {
            "every piece of a subdivision of x0 was proved empty".into()
        }
        Some(EmptinessProof::EverySubset) => {
            "whichever configurations are dropped, the rest was proved inconsistent".into()
        }
        None => "no proof recorded".into(),
    }
}

/// A short verdict: "consistent", "proved empty" or "undecided".
pub fn short_verdict(status: Status) -> &'static str {
    match status {
        Status::Consistent => "consistent",
        Status::Empty => "proved empty",
        Status::Undecided => "undecided",
    }
}

/// The verdict and its evidence, one sentence per entry: for an empty sub-problem the proof, the
/// conflicting configurations and what to do next.
pub fn verdict(r: &Outcome, names: &ConfigurationNames<'_>, max_outliers: usize) -> Vec<String> {
    match r.status {
        Status::Empty => {
            let tolerated = if max_outliers > 0 {
                format!(", even with {max_outliers} of them tolerated as outliers")
            } else {
                String::new()
            };
            let mut out = vec![format!(
                "verdict: no parameter vector in x0 fits the measurements within their error \
                 bounds{tolerated} — proved: {}",
                proof_in_words(r.emptiness, &r.names)
            )];
            match &r.conflict {
                Some(conflict) => {
                    let named = names.name(conflict);
                    out.push(if conflict.len() == 1 {
                        format!("conflict: {named} alone fits no parameter vector of x0.")
                    } else {
                        format!(
                            "conflict: {named} cannot be fitted together; with any one of them \
                             removed the rest is not proved inconsistent."
                        )
                    });
                    out.push(format!(
                        "re-measure them, or run with --max-outliers {} to tolerate {} bad \
                         configuration{}",
                        max_outliers + 1,
                        max_outliers + 1,
                        if max_outliers == 0 { "" } else { "s" }
                    ));
                }
                None if r.spread => out.extend(spread(r, names)),
                None => out.push(
                    "run with a larger --max-outliers, or check the model and error bounds".into(),
                ),
            }
            out
        }
        Status::Consistent => {
            vec!["verdict: consistent (a certified witness satisfies every measurement box)".into()]
        }
        Status::Undecided => vec![
            "verdict: undecided (no certified witness found; the outer box \
                                   is still a certified enclosure)"
                .into(),
        ],
    }
}

/// What the outer/inner ratios mean for this run: converged, budget spent, or `--fast`.
pub fn tightness(r: &Outcome) -> Option<&'static str> {
    r.width_ratios()?;
    Some(match r.converged {
        Some(true) => {
            "the true range of each parameter lies between inner and outer: outer overstates it \
             by at most the ratio"
        }
        Some(false) => {
            "budget spent before every ratio reached the tolerance (--max-boxes, --max-seconds); \
             both boxes are still certified"
        }
        None => "(--fast: the paper's x1 only; drop --fast for the tight hull)",
    })
}

/// "name (which end)" for each parameter whose outer box reaches a face of x0.
fn named_faces(r: &Outcome) -> Vec<String> {
    r.x0_faces()
        .iter()
        .map(|(j, end)| format!("{} ({end})", r.names[*j]))
        .collect()
}

/// Where the outer box reaches a face of the initial box x0, in words: consistent parameter
/// vectors may then lie beyond x0, which the certificate does not cover.
pub fn touching_x0(r: &Outcome) -> Option<String> {
    let faces = named_faces(r);
    (!faces.is_empty()).then(|| {
        format!(
            "the outer box reaches x0 in {}: consistent parameter vectors may lie beyond x0 there, \
             and the certificate covers x0 only — enlarge the initial box (its radius) to look \
             further",
            faces.join(", ")
        )
    })
}

/// The parameters whose outer box still reaches x0, in words, for robots whose prior box is the
/// question ("is this parameter determined?"): the data then do not determine them — the
/// consistent values may fill the prior box, or extend beyond it.
pub fn not_determined(r: &Outcome) -> Option<String> {
    let faces = named_faces(r);
    (!faces.is_empty()).then(|| {
        format!(
            "not determined by these data: {} — the certified range still reaches the prior box \
             x0 there, so consistent values may lie anywhere up to (and beyond) the prior; more \
             configurations, or a smaller prior, would determine {}",
            faces.join(", "),
            if faces.len() == 1 { "it" } else { "them" }
        )
    })
}

/// What a certificate proves about a parameter vector found by other means (a least-squares fit).
#[derive(Clone, Debug, PartialEq)]
pub enum Standing {
    /// Inside the certified box: not refuted (which alone does not prove it consistent).
    Inside,
    /// Inside x0 but outside the certified box (in these parameters), or anywhere in x0 when x0
    /// was proved empty: it does not fit the measurements within their error bounds.
    Refuted(Vec<usize>),
    /// Outside x0 (in these parameters): the certificate covers x0 only and proves nothing here.
    BeyondX0(Vec<usize>),
}

/// Where `x` stands against a certificate over `x0`: `certified` is the certified box, `None` when
/// x0 was proved to hold no consistent parameter vector.
pub fn standing(x0: &[Interval], certified: Option<&[Interval]>, x: &[f64]) -> Standing {
    let outside =
        |b: &[Interval]| -> Vec<usize> { (0..b.len()).filter(|&j| !b[j].contains(x[j])).collect() };
    let beyond = outside(x0);
    if !beyond.is_empty() {
        return Standing::BeyondX0(beyond);
    }
    match certified {
        None => Standing::Refuted(Vec::new()),
        Some(b) => {
            let refuted = outside(b);
            if refuted.is_empty() {
                Standing::Inside
            } else {
                Standing::Refuted(refuted)
            }
        }
    }
}

/// [`standing`] against an outcome: its outer box, or none when it was proved empty.
pub fn outcome_standing(r: &Outcome, x: &[f64]) -> Standing {
    let certified = match r.status {
        Status::Empty => None,
        _ => Some(r.outer.as_deref().unwrap_or(&r.x0)),
    };
    standing(&r.x0, certified, x)
}

/// With outliers tolerated (`max_outliers > 0`) on a sub-problem that is not empty: which configurations
/// were proved to be outliers.
pub fn outliers(
    r: &Outcome,
    names: &ConfigurationNames<'_>,
    max_outliers: usize,
) -> Option<String> {
    if max_outliers == 0 || r.status == Status::Empty {
        return None;
    }
    Some(if r.outliers.is_empty() {
        format!("outliers (at most {max_outliers} tolerated): no configuration is proved to be one")
    } else {
        format!(
            "outliers (at most {max_outliers} tolerated): {} — every parameter vector that fits \
             the rest misfits {}",
            names.name(&r.outliers),
            if r.outliers.len() == 1 { "it" } else { "them" }
        )
    })
}

/// What `--max-outliers auto` found, for a result certified with `q` outliers tolerated: every
/// smaller number was proved too few (see [`crate::smallest_consistent`]).
pub fn auto_outliers(q: usize, status: Status) -> String {
    match (q, status) {
        (q, Status::Empty) => {
            format!(
                "--max-outliers auto: empty even with {q} outliers tolerated, the most possible"
            )
        }
        (0, Status::Undecided) => "--max-outliers auto: undecided with every configuration kept \
                                    (no outlier was proved needed; none was proved absent either)"
            .into(),
        (0, _) => "--max-outliers auto: no outlier needed (every configuration kept)".into(),
        (1, Status::Undecided) => "--max-outliers auto: undecided with 1 outlier tolerated \
                                    (proved: with every configuration kept, no parameter vector \
                                    of x0 fits; with 1 tolerated, neither a fit nor its absence \
                                    was proved)"
            .into(),
        (q, Status::Undecided) => format!(
            "--max-outliers auto: undecided with {q} outliers tolerated (proved: with {} or fewer \
             tolerated, no parameter vector of x0 fits; with {q}, neither a fit nor its absence \
             was proved)",
            q - 1
        ),
        (1, _) => "--max-outliers auto: 1 outlier tolerated (proved: with every configuration \
                   kept, no parameter vector of x0 fits)"
            .into(),
        (q, _) => format!(
            "--max-outliers auto: {q} outliers tolerated (proved: with {} or fewer tolerated, no \
             parameter vector of x0 fits)",
            q - 1
        ),
    }
}

/// The proved improvement `factor` (the uncalibrated robot's lower bound over the calibrated
/// one's upper bound) of `what` (e.g. "the worst tool-point error") in words: a reduction only
/// when the factor exceeds 1.
pub fn improvement(what: &str, factor: f64) -> String {
    // Printed rounded down, below the quotient's rounding too: "at least" stays true.
    let at_least = crate::html::rounded_to(factor.next_down(), 2, true);
    if factor > 1.0 {
        format!(
            "calibration reduced {what} at least {at_least}-fold (proved: before's lower bound \
             over after's upper bound)"
        )
    } else {
        format!(
            "no improvement of {what} is proved: before's lower bound is {:.2} times \
             after's upper bound (the brackets overlap; tighten them, or calibration did not help)",
            factor
        )
    }
}
