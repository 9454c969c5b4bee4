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

use calib_core::Status;

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
/// use calib_core::Status;
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
    while out.trials.len() < search.max_trials {
        let (Some(lo), Some(hi)) = (out.s_lo, out.s_hi) else {
            break;
        };
        if hi / lo <= 1.0 + search.tolerance {
            break;
        }
        // Undecided factors outside the bracket are forgotten.
        undecided = undecided.filter(|(a, b)| lo < *a && *b < hi);
        let s = match undecided {
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
        // Gaps that no longer shrink: both sides within the tolerance of an undecided stretch.
        if let (Some((a, b)), Some(lo), Some(hi)) = (undecided, out.s_lo, out.s_hi) {
            let tight = 1.0 + search.tolerance / 4.0;
            if a / lo <= tight && hi / b <= tight {
                break;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn threshold(t: f64) -> impl FnMut(f64) -> Status {
        move |s| {
            if s >= t {
                Status::Consistent
            } else {
                Status::Empty
            }
        }
    }

    #[test]
    fn brackets_the_threshold_within_the_tolerance_from_either_side() {
        for t in [0.0123, 0.547, 1.0, 3.7, 250.0] {
            let s = find_error_scale(&ScaleSearch::default(), threshold(t));
            let (lo, hi) = (s.s_lo.unwrap(), s.s_hi.unwrap());
            assert!(lo < t && t <= hi && hi / lo <= 1.02, "{t}: {lo} {hi}");
            // Every end is a proof of its kind.
            let proved = |v: f64, k: Status| s.trials.iter().any(|r| r.scale == v && r.status == k);
            assert!(proved(lo, Status::Empty) && proved(hi, Status::Consistent));
            assert!(s.trials.len() <= 24);
        }
    }

    #[test]
    fn an_estimate_brackets_in_few_trials_and_a_wrong_one_still_brackets() {
        for (t, estimate) in [(0.547, 0.546), (0.547, 0.549), (0.547, 0.3), (0.547, 3.0)] {
            let s = find_error_scale(&ScaleSearch::from_estimate(estimate), threshold(t));
            let (lo, hi) = (s.s_lo.unwrap(), s.s_hi.unwrap());
            assert!(
                lo < t && t <= hi && hi / lo <= 1.02,
                "{t} from {estimate}: {lo} {hi}"
            );
            if (estimate / t - 1.0f64).abs() < 0.005 {
                assert!(s.trials.len() <= 3, "{estimate}: {:?}", s.trials);
            }
            assert!(s.trials.len() <= 24);
        }
        // No usable estimate: the blind default.
        assert_eq!(ScaleSearch::from_estimate(f64::NAN), ScaleSearch::default());
        assert_eq!(ScaleSearch::from_estimate(0.0), ScaleSearch::default());
    }

    #[test]
    fn undecided_verdicts_never_become_ends() {
        // Undecided from 0.9 to 1.2: the bracket stops at its edges, made of proofs only.
        let s = find_error_scale(&ScaleSearch::default(), |s| {
            if s >= 1.2 {
                Status::Consistent
            } else if s > 0.9 {
                Status::Undecided
            } else {
                Status::Empty
            }
        });
        let (lo, hi) = (s.s_lo.unwrap(), s.s_hi.unwrap());
        assert!(lo <= 0.9 && hi >= 1.2 && hi / lo < 1.4, "{lo} {hi}");
        // Never consistent: no upper end, and the search ends within its range.
        let s = find_error_scale(&ScaleSearch::default(), |_| Status::Empty);
        assert!(s.s_hi.is_none() && s.s_lo.is_some());
        let s = find_error_scale(&ScaleSearch::default(), |_| Status::Undecided);
        assert!(s.s_hi.is_none() && s.s_lo.is_none() && s.trials.len() <= 24);
    }
}
