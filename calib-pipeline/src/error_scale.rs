//! How much error must the data be allowed? The smallest factor `s` by which error bounds must be
//! multiplied for the measurements to be consistent with the model, as a proved bracket:
//! at `s_lo` the data are **proved inconsistent** (an emptiness proof), at `s_hi` **proved
//! consistent** (a certified witness). Consistency is monotone in `s` (wider bounds admit every
//! parameter vector narrower ones do), so the smallest consistent factor lies in `(s_lo, s_hi]`.
//!
//! The search is a geometric bisection on the verdicts of whole certifications: from `s = 1`
//! (or from an estimate, in small then growing steps), halve or double until both kinds of
//! proof are in hand, then bisect until
//! `s_hi / s_lo <= 1 + tolerance`. An undecided verdict proves nothing; the search then tries
//! between it and each end (closer to `s_lo` an emptiness proof is easier, closer to `s_hi` a
//! witness), and the bracket it reports is only ever made of proofs.
//!
//! [`search_from_estimate`] runs it for a robot made of sub-problems (an arm: one; a Gough
//! platform: one per leg). It starts from the first-order estimate of each
//! ([`calib_core::smallest_scale`], a Chebyshev fit) and, at every factor, first tries each
//! estimate's point: certified consistent against the widened boxes
//! ([`calib_core::is_consistent_point`]), it is the sub-problem's witness without a certification.

use crate::OptionError;
use calib_core::{
    is_consistent_point, smallest_scale, Interval, ScaleEstimate, Status, VectorModel,
};

/// One certification the search ran.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScaleTrial {
    /// The factor tried.
    pub scale: f64,
    /// Its verdict.
    pub status: Status,
}

/// The bracket found.
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorScale {
    /// The largest factor proved inconsistent (`None`: none was, down to the smallest tried).
    pub s_lo: Option<f64>,
    /// The smallest factor proved consistent (`None`: none was, up to the largest tried).
    pub s_hi: Option<f64>,
    /// Every certification, in the order run.
    pub trials: Vec<ScaleTrial>,
    /// The first-order estimate the search started from (a Chebyshev fit,
    /// [`calib_core::smallest_scale`]; not a proof), when it had one.
    pub estimate: Option<f64>,
}

impl ErrorScale {
    /// `s_hi / s_lo` when both ends are proved.
    pub fn ratio(&self) -> Option<f64> {
        Some(self.s_hi? / self.s_lo?)
    }
}

/// The search's limits and where it starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScaleSearch {
    /// Stop at `s_hi / s_lo <= 1 + tolerance`.
    pub tolerance: f64,
    /// At most this many certifications.
    pub max_trials: usize,
    /// Search factors within `[1 / range, range]`.
    pub range: f64,
    /// The first factor tried: 1, or an estimate of the smallest consistent factor (a Chebyshev
    /// fit, [`calib_core::smallest_scale`]).
    pub start: f64,
    /// The first bracketing step: the factor moves by `step`, then `step²`, … (at most 2) until
    /// both kinds of proof are in hand. 2 from a blind start; from an estimate, `1 + tolerance / 2`
    /// brackets it within the tolerance in two trials when the estimate is right.
    pub step: f64,
}

impl Default for ScaleSearch {
    /// Within 2%, at most 24 certifications, factors from 1/1000 to 1000, from 1 by doubling or
    /// halving.
    fn default() -> Self {
        ScaleSearch {
            tolerance: 0.02,
            max_trials: 24,
            range: 1000.0,
            start: 1.0,
            step: 2.0,
        }
    }
}

impl ScaleSearch {
    /// The default search started just above the estimate `s` (at `s (1 + tolerance / 4)`, where
    /// a witness is expected; when `s` is a positive finite number within the range) with steps
    /// of `1 + tolerance / 2`.
    pub fn from_estimate(s: f64) -> Self {
        let d = ScaleSearch::default();
        if s.is_finite() && s > 0.0 && (1.0 / d.range..=d.range).contains(&s) {
            ScaleSearch {
                start: s * (1.0 + d.tolerance / 4.0),
                step: 1.0 + d.tolerance / 2.0,
                ..d
            }
        } else {
            d
        }
    }
}

/// Searches the smallest consistent factor with `decide(s)`, the verdict of the certification
/// with every scaled bound multiplied by `s` (see the module documentation).
///
/// ```
/// use calib_core::{is_consistent_point, smallest_scale, Interval, ScaleEstimate, Status, VectorModel};
/// use calib_pipeline::error_scale::{find_error_scale, ScaleSearch};
/// // Consistent from 0.547 on, undecided within 3% below it.
/// let s = find_error_scale(&ScaleSearch::default(), |s| {
///     if s >= 0.547 { Status::Consistent } else if s > 0.53 { Status::Undecided } else { Status::Empty }
/// });
/// let (lo, hi) = (s.s_lo.unwrap(), s.s_hi.unwrap());
/// assert!(lo <= 0.53 && 0.547 <= hi && hi / lo <= 1.06);
/// ```
pub fn find_error_scale(search: &ScaleSearch, mut decide: impl FnMut(f64) -> Status) -> ErrorScale {
    let mut out = ErrorScale {
        s_lo: None,
        s_hi: None,
        trials: Vec::new(),
        estimate: None,
    };
    let mut run = |s: f64, out: &mut ErrorScale| {
        let status = decide(s);
        out.trials.push(ScaleTrial { scale: s, status });
        match status {
            Status::Empty => out.s_lo = Some(out.s_lo.map_or(s, |l| l.max(s))),
            Status::Consistent => out.s_hi = Some(out.s_hi.map_or(s, |h| h.min(s))),
            Status::Undecided => {}
        }
        status
    };
    // Undecided factors strictly inside the bracket: (lowest, highest).
    let mut undecided: Option<(f64, f64)> = None;
    let mut s = search.start;
    let mut step = search.step.clamp(1.0 + 1e-9, 2.0);
    // Bracketing: down or up by `step`, the step growing to a halving or doubling.
    while out.trials.len() < search.max_trials && (out.s_lo.is_none() || out.s_hi.is_none()) {
        let status = run(s, &mut out);
        if status == Status::Undecided {
            undecided = Some(undecided.map_or((s, s), |(a, b)| (a.min(s), b.max(s))));
        }
        s = match (out.s_lo, out.s_hi) {
            (None, Some(h)) => h.min(undecided.map_or(h, |u| u.0)) / step,
            (Some(l), None) => l.max(undecided.map_or(l, |u| u.1)) * step,
            // Nothing proved yet (undecided at the start): alternate below and above.
            (None, None) => {
                let (a, b) = undecided.unwrap_or((search.start, search.start));
                if out.trials.len() % 2 == 1 {
                    a / step
                } else {
                    b * step
                }
            }
            (Some(_), Some(_)) => break,
        };
        step = (step * step).min(2.0);
        if !(1.0 / search.range..=search.range).contains(&s) {
            break;
        }
    }
    // Bisection.
    let mut tried_goal = false;
    while out.trials.len() < search.max_trials {
        let (Some(lo), Some(hi)) = (out.s_lo, out.s_hi) else {
            break;
        };
        if hi / lo <= 1.0 + search.tolerance {
            break;
        }
        // Undecided factors outside the bracket are forgotten.
        undecided = undecided.filter(|(a, b)| lo < *a && *b < hi);
        // Gaps that no longer shrink: both sides within the tolerance of an undecided stretch.
        // Then one last try where a proof would meet the tolerance: just below `hi / (1 + tol)`.
        let tight = 1.0 + search.tolerance / 4.0;
        let stalled = undecided.is_some_and(|(a, b)| a / lo <= tight && hi / b <= tight);
        let s = match undecided {
            _ if stalled => {
                let goal = hi / (1.0 + search.tolerance) * (1.0 + 1e-6);
                if tried_goal || goal <= lo || undecided.is_some_and(|(a, _)| goal >= a) {
                    break;
                }
                tried_goal = true;
                goal
            }
            None => (lo * hi).sqrt(),
            // Try the wider of the two gaps around the undecided stretch.
            Some((a, b)) => {
                if a / lo >= hi / b {
                    (lo * a).sqrt()
                } else {
                    (b * hi).sqrt()
                }
            }
        };
        if run(s, &mut out) == Status::Undecided {
            undecided = Some(undecided.map_or((s, s), |(a, b)| (a.min(s), b.max(s))));
        }
    }
    out
}

/// One sub-problem of [`search_from_estimate`]: its model, prior box, measurement boxes at a
/// factor `s`, and which measured quantities the factor scales (for the estimate).
pub struct ScaledProblem<'a, M, const NX: usize, const NM: usize> {
    /// The model.
    pub model: &'a M,
    /// The prior box.
    pub x0: [Interval; NX],
    /// The measurement boxes with the chosen error bounds multiplied by `s`.
    pub boxes: &'a dyn Fn(f64) -> Vec<[Interval; NM]>,
    /// The measured quantities whose half-widths the factor multiplies.
    pub scaled: [bool; NM],
}

/// The smallest consistent factor of a robot made of independent `problems` (consistent when
/// every one is): the search of [`find_error_scale`] started from the largest first-order estimate,
/// each trial first trying every estimate's point (see the module documentation), then
/// `certify(i, s)` for the sub-problems it did not prove; `on_trial` hears each factor first.
/// The first error of `certify` ends the search and is returned.
pub fn search_from_estimate<M, E, const NX: usize, const NM: usize, const NR: usize>(
    problems: &[ScaledProblem<'_, M, NX, NM>],
    mut certify: impl FnMut(usize, f64) -> Result<Status, E>,
    mut on_trial: impl FnMut(f64),
) -> Result<ErrorScale, E>
where
    M: VectorModel<NX, NM, NR>,
{
    let estimates: Vec<ScaleEstimate<NX>> = problems
        .iter()
        .map(|p| smallest_scale(p.model, &p.x0, &(p.boxes)(1.0), &p.scaled))
        .collect();
    let estimate = estimates.iter().map(|e| e.scale).fold(0.0, f64::max);
    let mut failure = None;
    let mut found = find_error_scale(&ScaleSearch::from_estimate(estimate), |s| {
        on_trial(s);
        let mut all = true;
        for (i, (p, e)) in problems.iter().zip(&estimates).enumerate() {
            if s >= e.scale && is_consistent_point(p.model, &e.point, &(p.boxes)(s)) {
                continue;
            }
            match certify(i, s) {
                Ok(Status::Empty) => return Status::Empty,
                Ok(Status::Consistent) => {}
                Ok(Status::Undecided) => all = false,
                Err(e) => {
                    failure.get_or_insert(e);
                    return Status::Undecided;
                }
            }
        }
        if all {
            Status::Consistent
        } else {
            Status::Undecided
        }
    });
    found.estimate = (estimate.is_finite() && estimate > 0.0).then_some(estimate);
    match failure {
        Some(e) => Err(e),
        None => Ok(found),
    }
}

/// The bracket as JSON (the report's `error_scale`): `bounds` (which were scaled), `s_lo`,
/// `s_hi`, `ratio`, `estimate` (the first-order Chebyshev fit's factor, not a proof),
/// `certified_at` (the factor the certification then used), `seconds` and every trial's factor
/// and verdict.
pub fn to_json(
    found: &ErrorScale,
    bounds: &str,
    certified_at: Option<f64>,
    seconds: f64,
) -> serde_json::Value {
    serde_json::json!({
        "bounds": bounds,
        "s_lo": found.s_lo,
        "s_hi": found.s_hi,
        "ratio": found.ratio(),
        "estimate": found.estimate,
        "certified_at": certified_at,
        "certifications": found.trials.len(),
        "seconds": seconds,
        "trials": found.trials.iter().map(|t| serde_json::json!({
            "scale": t.scale,
            "verdict": format!("{:?}", t.status).to_lowercase(),
        })).collect::<Vec<_>>(),
    })
}

/// `--scale-margin`'s check: a finite factor of at least 1.
pub fn check_margin(margin: f64) -> Result<(), OptionError> {
    if margin.is_finite() && margin >= 1.0 {
        Ok(())
    } else {
        Err(OptionError::ScaleMargin(margin))
    }
}

/// A search that proved no factor consistent.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ScaleError {
    /// No factor tried, up to `largest`, was proved consistent.
    #[error("the data are not consistent with the model even with the error bounds × {largest}: a model error, or outliers (try --max-outliers auto)")]
    NotConsistent {
        /// The largest factor tried (0 when none was).
        largest: f64,
    },
}

/// What `--error-scale auto` reports once the search is done.
#[derive(Clone, Debug, PartialEq)]
pub struct ScaleReport {
    /// The bracket in words ([`in_words`]).
    pub words: Vec<String>,
    /// The factor to certify with: `s_hi × margin`.
    pub certify_at: f64,
    /// The JSON ([`to_json`]).
    pub json: serde_json::Value,
}

/// The report of a search that took `seconds`, to certify next at `s_hi × margin`; an error
/// (model error or outliers) when no factor was proved consistent.
pub fn report(
    found: &ErrorScale,
    bounds: &str,
    seconds: f64,
    margin: f64,
    describe: &dyn Fn(f64) -> String,
) -> Result<ScaleReport, ScaleError> {
    let Some((words, certify_at)) = in_words(found, bounds, seconds, margin, describe) else {
        return Err(ScaleError::NotConsistent {
            largest: found.trials.iter().map(|t| t.scale).fold(0.0, f64::max),
        });
    };
    Ok(ScaleReport {
        json: to_json(found, bounds, Some(certify_at), seconds),
        words,
        certify_at,
    })
}

/// The bracket in words, one line each, for the terminal and the certificate: what was proved,
/// the bounds the data need against the uncertainty file's (`describe(s)`: the scaled bounds in
/// words, e.g. `pos 0.3846 mm`), the estimate when the bracket is wider than 2%, and the factor
/// certified next (`s_hi × margin`). `None` when no factor was proved consistent.
pub fn in_words(
    found: &ErrorScale,
    bounds: &str,
    seconds: f64,
    margin: f64,
    describe: &dyn Fn(f64) -> String,
) -> Option<(Vec<String>, f64)> {
    let show = |s: Option<f64>| s.map_or("—".to_string(), |v| format!("{v:.4}"));
    let mut words = vec![format!(
        "error scale ({bounds} bounds, {} certifications, {seconds:.1} s): proved inconsistent at × {}, certified consistent at × {}",
        found.trials.len(),
        show(found.s_lo),
        show(found.s_hi)
    )];
    let hi = found.s_hi?;
    words.push(match found.s_lo {
        Some(lo) if hi > 1.0 => format!(
            "these data fit the model only if the error bounds are {} (× {lo:.4} to × {hi:.4}: {} is proved too small); the uncertainty file says {}: the rest is the model's (errors it does not describe: compliance, gears, temperature)",
            describe(hi),
            describe(lo),
            describe(1.0)
        ),
        Some(lo) => format!(
            "these data fit the model with error bounds of {} (× {hi:.4}; × {lo:.4} is proved too small): the uncertainty file's {} are conservative",
            describe(hi),
            describe(1.0)
        ),
        None => format!(
            "these data fit the model with error bounds of {} (× {hi:.4}); no smaller factor was proved inconsistent",
            describe(hi)
        ),
    });
    if let (Some(lo), Some(e)) = (found.s_lo, found.estimate) {
        if found.ratio().is_some_and(|r| r > 1.02) && (lo..=hi).contains(&e) {
            words.push(format!(
                "  the first-order minimax fit needs × {e:.4}, where the smallest consistent bound most likely is; below it, down to × {lo:.4}, the kernel could not decide: its relaxation over the prior box is too loose this close to the threshold (see benches/README.md)"
            ));
        }
    }
    let at = hi * margin;
    words.push(format!(
        "certifying at × {at:.4} ({}){}",
        describe(at),
        if margin > 1.0 {
            format!(", a margin of × {margin} over s_hi")
        } else {
            String::new()
        }
    ));
    Some((words, at))
}
