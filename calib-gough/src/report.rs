//! The JSON report of `gough certify` (schema version 1) and the paper-style tables.
//!
//! ```json
//! { "version": 1,
//!   "legs": [ { "leg": 1, "status": "consistent" | "empty" | "undecided",
//!               "names": ["ax","ay","az","bx","by","bz","l"],
//!               "x0": [[lo, hi], ...], "x1": [[lo, hi], ...], "x2": [[lo, hi], ...] or null,
//!               "outer": [[lo, hi], ...] or null, "inner": [[lo, hi], ...] or null,
//!               "converged": true | false | null, "witness": [..7] or null,
//!               "conflict": [configuration, ...] or null,
//!               "support": [configuration, ...] or null, "spread": true | false,
//!               "outliers": [configuration, ...],
//!               "carried_over": {"file": name, "first": n, "rows": [row, ...]} (or absent),
//!               "iterations": n, "boxes": n, "seconds": s } ],
//!   "seconds": total }
//! ```
//! `outer` is the tightest certified box (the tight hull; `x1` with `--fast`), `inner` the hull of
//! certified consistent parameter vectors: the true range of each parameter lies between them.
//! `conflict` (empty legs) and `outliers` (with `--max-outliers`) are 1-based configuration
//! numbers: the k-th data row of the CSV is configuration k. `converged` says whether the hull refinement met its tolerance (`null` with `--fast`); `x1` is
//! the paper's fixed point. `support` (empty legs) lists the configurations the certificate of
//! emptiness weighs; `spread` says it weighs most of what a certificate can — a misfit spread over
//! the data, the bounds too tight for the model — and then `conflict` is `null` (not searched).
//! `carried_over` (a calibrated robot file certified again with new measurements,
//! [`crate::carry_over`]): configurations `first` onwards are the stored rows `rows` (1-based
//! rows of the file's `leg[i].certified_set.measurements`), certified together with the new
//! ones; `conflict`, `support` and `outliers` number them so.
//! `outer`, `converged`, `conflict`, `outliers`, `support`, `spread` and `carried_over` were added
//! to version 1 without breaking it: reports written before read back with `null` (`false`,
//! absent) there.
//!
//! Bounds are written with Rust's shortest round-trip formatting (serde_json), so reading them back
//! gives the same `f64`s: no bound is moved inward by printing. An empty box is written as `null`
//! bounds.

use calib_core::Interval;
use serde::{Deserialize, Serialize};

/// One leg's result.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LegReport {
    /// 1-based leg number.
    pub leg: usize,
    /// `consistent`, `empty` or `undecided`.
    pub status: String,
    /// Parameter names, in order.
    pub names: Vec<String>,
    /// The initial box.
    pub x0: Vec<[f64; 2]>,
    /// The paper's fixed point x1, a certified box (`null` when empty).
    pub x1: Option<Vec<[f64; 2]>>,
    /// The hull of the sweep (`null` without `--sweep` or when empty).
    pub x2: Option<Vec<[f64; 2]>>,
    /// The tightest certified outer box (`null` when empty).
    #[serde(default)]
    pub outer: Option<Vec<[f64; 2]>>,
    /// Certified inner bounds (`null` without a witness).
    pub inner: Option<Vec<[f64; 2]>>,
    /// Whether the hull refinement met its tolerance (`null` with `--fast`).
    #[serde(default)]
    pub converged: Option<bool>,
    /// For an empty leg: a minimal set of configurations (1-based: the k-th data row of the CSV
    /// is configuration k) that cannot be fitted together.
    #[serde(default)]
    pub conflict: Option<Vec<usize>>,
    /// For an empty leg: the configurations (1-based) the certificate of emptiness weighs, when
    /// it names them.
    #[serde(default)]
    pub support: Option<Vec<usize>>,
    /// For an empty leg: the support shows a misfit spread over the data (the bounds too tight
    /// for the model); `conflict` is then `null`, not searched.
    #[serde(default)]
    pub spread: bool,
    /// With `--max-outliers`: the configurations (1-based) proved to be outliers.
    #[serde(default)]
    pub outliers: Vec<usize>,
    /// How many outliers the leg's result tolerates (with `--max-outliers Q`, Q; with `auto`, the
    /// smallest number not proved empty); absent when none.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub outliers_tolerated: usize,
    /// A certified consistent parameter vector.
    pub witness: Option<Vec<f64>>,
    /// When the robot file was a calibrated one whose stored rows were certified with the new
    /// ones: which configurations they are (absent otherwise).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub carried_over: Option<CarriedReport>,
    /// Newton/LP iterations of the certification.
    pub iterations: usize,
    /// Boxes contracted (1 without sweep or paving).
    pub boxes: usize,
    /// Wall-clock seconds for this leg.
    pub seconds: f64,
}

/// The rows a leg carried over from a calibrated robot file (`carried_over` in the JSON report).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CarriedReport {
    /// The calibrated robot file's name.
    pub file: String,
    /// The 1-based configuration number of the first stored row (the new rows are
    /// configurations 1 to `first - 1`).
    pub first: usize,
    /// Per carried configuration (`first`, `first + 1`, ...), its 1-based row in the file's
    /// `leg[i].certified_set.measurements`.
    pub rows: Vec<usize>,
}

/// The whole report.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Report {
    /// Schema version (1).
    pub version: u32,
    /// One entry per certified leg.
    pub legs: Vec<LegReport>,
    /// Total wall-clock seconds.
    pub seconds: f64,
}

/// `[[lo, hi], ...]` of a box.
pub fn bounds(b: &[Interval; 7]) -> Vec<[f64; 2]> {
    b.iter().map(|v| [v.inf(), v.sup()]).collect()
}

/// A paper-style table (Tables II–IV): per parameter the mid and rad of each named box.
pub fn table(rows: &[(&str, Option<[Interval; 7]>)]) -> String {
    let mut out = String::new();
    out.push_str(&format!("{:<6}", ""));
    for name in crate::PARAMETER_NAMES {
        out.push_str(&format!(" {:>21}", format!("{name}: mid       rad")));
    }
    out.push('\n');
    for (label, b) in rows {
        out.push_str(&format!("{label:<6}"));
        match b {
            Some(b) => {
                for v in b {
                    out.push_str(&format!(" {:>11.4} {:>9.2e}", v.mid(), v.rad()));
                }
            }
            None => out.push_str("  (empty)"),
        }
        out.push('\n');
    }
    out
}

/// `ax 1.93  ay 1.96 ...`: the outer/inner width ratio per parameter.
pub fn ratios(ratio: &[f64; 7]) -> String {
    let cells: Vec<String> = crate::PARAMETER_NAMES
        .iter()
        .zip(ratio)
        .map(|(n, q)| format!("{n} {q:.2}"))
        .collect();
    cells.join("  ")
}

pub use calib_pipeline::write_atomically;

/// Whether a count is zero (to leave default values out of the JSON).
fn is_zero(n: &usize) -> bool {
    *n == 0
}
