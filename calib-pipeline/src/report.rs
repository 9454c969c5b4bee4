//! The JSON report of one certified sub-problem, for any robot (schema version 1 of the robots
//! that came after the Gough platform, whose own report keeps its layout):
//!
//! ```json
//! { "status": "consistent" | "empty" | "undecided",
//!   "parameters": [ { "name": "a1", "unit": "mm", "fixed": false,
//!                     "x0": [lo, hi], "x1": [lo, hi] | null, "outer": [lo, hi] | null,
//!                     "inner": [lo, hi] | null, "ratio": r | null, "witness": v | null,
//!                     "lsq": v | null }, ... ],
//!   "conflict": [configuration, ...] | null, "support": [configuration, ...] | null,
//!   "spread": true | false, "outliers": [configuration, ...],
//!   "outliers_tolerated": q (only when q > 0),
//!   "verdict": ["sentence", ...], "identifiability": ["sentence", ...],
//!   "converged": true | false | null, "iterations": n, "boxes": n, "seconds": s }
//! ```
//! Configurations are 1-based (the k-th data row of the CSV is configuration k). `support` (the
//! configurations the certificate of emptiness weighs) and `spread` (it weighs most of what a
//! certificate can: a misfit spread over the data, the bounds too tight for the model, and
//! `conflict` is `null` — not searched) were added without breaking the layout: reports written
//! before read back with `null` and `false`. Bounds are in the
//! units named, written with Rust's shortest round-trip formatting (no bound moves inward by
//! printing).

use crate::outcome::{is_fixed, Outcome};
use serde::{Deserialize, Serialize};

/// One parameter's line.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ParameterReport {
    /// Its name.
    pub name: String,
    /// Its unit.
    pub unit: String,
    /// Fixed in x0 (radius 0).
    pub fixed: bool,
    /// The initial box.
    pub x0: [f64; 2],
    /// The paper's fixed point x1.
    pub x1: Option<[f64; 2]>,
    /// The tightest certified outer bounds.
    pub outer: Option<[f64; 2]>,
    /// Certified inner bounds.
    pub inner: Option<[f64; 2]>,
    /// `wid(outer) / wid(inner)`.
    pub ratio: Option<f64>,
    /// The certified witness's value.
    pub witness: Option<f64>,
    /// The least-squares value, when a fit was made.
    pub lsq: Option<f64>,
}

/// The report of one sub-problem.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct OutcomeReport {
    /// `consistent`, `empty` or `undecided`.
    pub status: String,
    /// One entry per parameter, model order.
    pub parameters: Vec<ParameterReport>,
    /// For an empty sub-problem: a minimal conflicting set of configurations (1-based).
    pub conflict: Option<Vec<usize>>,
    /// For an empty sub-problem: the configurations (1-based) the certificate of emptiness
    /// weighs, when it names them.
    #[serde(default)]
    pub support: Option<Vec<usize>>,
    /// For an empty sub-problem: the support shows a misfit spread over the data (the bounds too
    /// tight for the model); `conflict` is then `null`, not searched.
    #[serde(default)]
    pub spread: bool,
    /// With outliers tolerated: the configurations (1-based) proved to be outliers.
    pub outliers: Vec<usize>,
    /// How many outliers the result tolerates (absent when none).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub outliers_tolerated: usize,
    /// The verdict in words.
    pub verdict: Vec<String>,
    /// The identifiability findings in words.
    pub identifiability: Vec<String>,
    /// Whether the hull met its tolerance (`null` for x1 only).
    pub converged: Option<bool>,
    /// Newton/LP steps to x1.
    pub iterations: usize,
    /// Boxes contracted.
    pub boxes: usize,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// Whether a count is zero (to leave it out of the JSON).
fn is_zero(n: &usize) -> bool {
    *n == 0
}

impl OutcomeReport {
    /// The report of `o` (in the units it is expressed in), with the parameters' `units`, the
    /// sentences already formed, and a least-squares fit if one was made.
    pub fn new(
        o: &Outcome,
        units: &[String],
        verdict: Vec<String>,
        identifiability: Vec<String>,
        lsq: Option<&[f64]>,
    ) -> OutcomeReport {
        let pair = |v: calib_core::Interval| [v.inf(), v.sup()];
        let ratios = o.width_ratios();
        let parameters = (0..o.x0.len())
            .map(|j| ParameterReport {
                name: o.names[j].clone(),
                unit: units.get(j).cloned().unwrap_or_default(),
                fixed: is_fixed(o.x0[j]),
                x0: pair(o.x0[j]),
                x1: o.x1.as_ref().map(|b| pair(b[j])),
                outer: o.outer.as_ref().map(|b| pair(b[j])),
                inner: o.inner.as_ref().map(|b| pair(b[j])),
                ratio: ratios
                    .as_ref()
                    .map(|r| r[j])
                    .filter(|r| r.is_finite() && !is_fixed(o.x0[j])),
                witness: o.witness.as_ref().map(|w| w[j]),
                lsq: lsq.map(|x| x[j]),
            })
            .collect();
        let one_based = |c: &[usize]| c.iter().map(|k| k + 1).collect::<Vec<_>>();
        OutcomeReport {
            status: format!("{:?}", o.status).to_lowercase(),
            parameters,
            conflict: o.conflict.as_deref().map(one_based),
            support: o.support.as_deref().map(one_based),
            spread: o.spread,
            outliers: one_based(&o.outliers),
            outliers_tolerated: 0,
            verdict,
            identifiability,
            converged: o.converged,
            iterations: o.iterations,
            boxes: o.boxes,
            seconds: o.seconds,
        }
    }

    /// The report as pretty-printed JSON (with a final newline).
    pub fn to_json(&self) -> String {
        // Serialising plain numbers, strings and vectors cannot fail.
        let mut text = serde_json::to_string_pretty(self).unwrap_or_default();
        text.push('\n');
        text
    }
}
