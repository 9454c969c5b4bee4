//! Predictions to check new measurements against (`arm predict`): per configuration, the
//! certified range of each coordinate of the tracked point over every parameter vector the
//! calibration allows, and the same widened by the measurement error bounds.
//!
//! At joint readings `q`, the model's affine form over the set's outer box `X` (noise symbols
//! `x_j = mid(X_j) + rad(X_j) ε_j` for the parameters and `η_i` for the joint readings,
//! [`calib_core::LinearEnclosure`]) gives each coordinate as
//! `p_r ∈ c + Σ_j (g_j / rad(X_j)) (x_j - mid(X_j)) + Σ_i h_i η_i ± e`: its largest and smallest
//! values over the certified set are bounded by one linear program per piece
//! ([`calib_core::SetQuery::max_linear`], safe bounds), the joint readings' terms by their
//! magnitudes. The **range** takes the readings as exact; **with errors** the joint readings lie
//! within `± joint_deg` and the tracked point within `± pos`: a measured point outside it is
//! impossible unless the model or the error bounds are wrong there — the row refutes them.
//!
//! An arm whose robot file has no certified set is predicted over its box (a superset).

use crate::certification::{padded_box, ArmSet, MAX_JOINTS, NM, NX};
use crate::robot::Arm;
use crate::simulate::Uncertainty;
use crate::units::deg_to_rad;
use crate::Arm7Point;
use calib_core::{Interval, LinearEnclosure, SlotQueries, VectorModel};
use rayon::prelude::*;

/// The prediction at one configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct PointPrediction {
    /// The joint readings (degrees).
    pub joints_deg: Vec<f64>,
    /// Per coordinate, the tracked point at exactly these readings over every consistent
    /// parameter vector (mm, tracker frame).
    pub range: [Interval; 3],
    /// Per coordinate, what a measurement may show: joint readings within their error bound,
    /// the tracker's error added (mm).
    pub with_errors: [Interval; 3],
    /// The tracked point the robot file's values predict (mm, floating point): what a
    /// controller loading the file computes.
    pub calibrated: [f64; 3],
    /// The measured point, when given.
    pub measured: Option<[f64; 3]>,
    /// Whether every measured coordinate lies in `with_errors` (`None` without a measurement):
    /// `false` refutes the model or the error bounds at this row.
    pub inside: Option<bool>,
}

/// The padded measurement box of joint readings `joints_deg` within `± joint_deg` (the tracked
/// point's part exactly 0, so that the residual is the point itself).
fn readings_box(joints_deg: &[f64], joint_deg: f64) -> [Interval; NM] {
    core::array::from_fn(|i| match joints_deg.get(i) {
        Some(q) if i < MAX_JOINTS => deg_to_rad(Interval::mid_rad(*q, joint_deg)),
        _ => Interval::ZERO,
    })
}

/// The linear programs of one worker: per coordinate and sign (and for the readings exact or
/// within their errors), one slot, warm-started from the same slot's previous configuration
/// (neighbouring rows ask nearly the same question).
type Programs<'a> = SlotQueries<'a, NX, NM>;

/// How many slots [`point_range`]'s two calls use.
const SLOTS: usize = 12;

/// The range of each coordinate of the tracked point over the set (or the box `x` without one)
/// at the readings `m`; `first_slot` picks the programs' slots (`first_slot..first_slot + 6`).
fn point_range(
    programs: Option<&mut Programs>,
    x: &[Interval; NX],
    m: &[Interval; NM],
    first_slot: usize,
) -> [Interval; 3] {
    let boxed = Arm7Point.residuals_interval(x, m);
    let (Some(q), Some(forms)) = (programs, Arm7Point.linear_enclosures(x, m)) else {
        return boxed;
    };
    let mid = x.map(|v| v.mid());
    core::array::from_fn(|r| {
        let f: &LinearEnclosure<NX, NM> = &forms[r];
        // x_j - mid_j = rad_j ε_j: the coefficient of (x_j - mid_j) is g_j / rad_j, enclosed.
        let slopes: [Interval; NX] = core::array::from_fn(|j| {
            let rad = x[j].rad();
            if f.gx[j] == 0.0 || rad == 0.0 {
                Interval::ZERO
            } else {
                Interval::point(f.gx[j]) / Interval::point(rad)
            }
        });
        let rest =
            f.gm.iter()
                .fold(Interval::point(f.e), |s, g| s + Interval::point(g.abs()))
                .sup();
        let up = q.max_linear(first_slot + 2 * r, &slopes, &mid);
        let down = q.max_linear(first_slot + 2 * r + 1, &slopes.map(|s| -s), &mid);
        let hi = (Interval::point(f.c) + Interval::point(up) + Interval::point(rest)).sup();
        let lo = (Interval::point(f.c) - Interval::point(down) - Interval::point(rest)).inf();
        let both = if lo.is_finite() && hi.is_finite() && lo <= hi {
            Interval::new(lo, hi).intersection(boxed[r])
        } else {
            boxed[r]
        };
        if both.is_empty() {
            boxed[r]
        } else {
            both
        }
    })
}

/// The predictions of `arm` (over `set` when given, else over the arm's box) at the joint
/// readings `joints_deg`; with `measured`, each row's measured point is checked (see the module
/// documentation).
pub fn predict(
    arm: &Arm,
    set: Option<&ArmSet>,
    joints_deg: &[Vec<f64>],
    u: &Uncertainty,
    measured: Option<&[[f64; 3]]>,
) -> Vec<PointPrediction> {
    let x = set
        .and_then(|s| s.outer())
        .unwrap_or_else(|| padded_box(arm));
    let pos = Interval::new(-u.pos, u.pos);
    let units = crate::params::names(arm.joints.len());
    let values: Vec<f64> = arm
        .nominal()
        .iter()
        .zip(&units)
        .map(|(v, (_, unit))| match unit {
            crate::params::Unit::Deg => crate::units::to_rad(*v),
            crate::params::Unit::Mm => *v,
        })
        .collect();
    joints_deg
        .par_iter()
        .enumerate()
        .map_init(
            || set.map(|s| Programs::new(s, SLOTS)),
            |programs, (k, q)| {
                let range = point_range(programs.as_mut(), &x, &readings_box(q, 0.0), 0);
                let with_errors =
                    point_range(programs.as_mut(), &x, &readings_box(q, u.joint_deg), 6)
                        .map(|v| v + pos);
                let point = measured.and_then(|m| m.get(k)).copied();
                let radians: Vec<f64> = q.iter().map(|d| crate::units::to_rad(*d)).collect();
                let calibrated =
                    crate::model::tracked_point(&values, &radians).unwrap_or([f64::NAN; 3]);
                PointPrediction {
                    joints_deg: q.clone(),
                    range,
                    with_errors,
                    calibrated,
                    measured: point,
                    inside: point.map(|p| (0..3).all(|c| with_errors[c].contains(p[c]))),
                }
            },
        )
        .collect()
}

/// The root mean square and the largest magnitude, over every coordinate of the rows with a
/// measurement, of `measured − calibrated` (mm): how well the robot file's values predict the
/// measurements. `None` without measurements.
pub fn residuals(predictions: &[PointPrediction]) -> Option<(f64, f64)> {
    let errors: Vec<f64> = predictions
        .iter()
        .filter_map(|p| {
            p.measured
                .map(|m| (0..3).map(move |c| m[c] - p.calibrated[c]))
        })
        .flatten()
        .collect();
    if errors.is_empty() {
        return None;
    }
    let rms = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
    Some((rms, errors.iter().fold(0.0, |m, e| m.max(e.abs()))))
}

/// The rows (0-based) whose measured point lies outside its prediction.
pub fn refuting(predictions: &[PointPrediction]) -> Vec<usize> {
    (0..predictions.len())
        .filter(|&k| predictions[k].inside == Some(false))
        .collect()
}

/// The predictions as CSV: `q1..qN`, then `x_lo,x_hi,y_lo,y_hi,z_lo,z_hi` (the ranges),
/// `x_min,x_max,y_min,y_max,z_min,z_max` (with the error bounds) and, with measurements,
/// `px,py,pz,inside` (shortest round-trip decimals, bounds outward).
pub fn predictions_csv(predictions: &[PointPrediction]) -> String {
    let joints = predictions.first().map_or(0, |p| p.joints_deg.len());
    let measured = predictions.iter().any(|p| p.measured.is_some());
    let mut header: Vec<String> = (1..=joints).map(|i| format!("q{i}")).collect();
    for kind in [["lo", "hi"], ["min", "max"]] {
        for c in ["x", "y", "z"] {
            header.extend(kind.map(|k| format!("{c}_{k}")));
        }
    }
    if measured {
        header.extend(["px", "py", "pz", "inside"].map(String::from));
    }
    let mut out = header.join(",") + "\n";
    for p in predictions {
        let mut row: Vec<String> = p.joints_deg.iter().map(|v| format!("{v:?}")).collect();
        for ranges in [&p.range, &p.with_errors] {
            for v in ranges {
                row.push(format!("{:?}", v.inf()));
                row.push(format!("{:?}", v.sup()));
            }
        }
        if measured {
            match p.measured {
                Some(m) => row.extend(m.iter().map(|v| format!("{v:?}"))),
                None => row.extend([String::new(), String::new(), String::new()]),
            }
            row.push(p.inside.map_or(String::new(), |b| b.to_string()));
        }
        out += &(row.join(",") + "\n");
    }
    out
}

/// The predictions as JSON (schema version 1; mm, degrees): `over` (`"certified set"` or
/// `"box"`), per row `joints_deg`, `range` and `with_errors` (per coordinate `[lo, hi]`),
/// `measured`, `inside`; `refuting`: the rows (1-based, with their file lines) whose
/// measurement lies outside its prediction; `calibrated` per row and `residuals` (`rms_mm`,
/// `max_mm`): the robot file's values against the measurements.
pub fn predictions_json(
    predictions: &[PointPrediction],
    over_set: bool,
    lines: Option<&[usize]>,
) -> serde_json::Value {
    let pairs = |v: &[Interval; 3]| v.map(|c| [c.inf(), c.sup()]);
    serde_json::json!({
        "version": 1,
        "over": if over_set { "certified set" } else { "box" },
        "rows": predictions.iter().enumerate().map(|(k, p)| serde_json::json!({
            "row": k + 1,
            "line": lines.and_then(|l| l.get(k)),
            "joints_deg": p.joints_deg,
            "range": pairs(&p.range),
            "with_errors": pairs(&p.with_errors),
            "calibrated": p.calibrated,
            "measured": p.measured,
            "inside": p.inside,
        })).collect::<Vec<_>>(),
        "residuals": residuals(predictions).map(|(rms, max)| serde_json::json!({
            "rms_mm": rms,
            "max_mm": max,
        })),
        "refuting": refuting(predictions).iter().map(|&k| serde_json::json!({
            "row": k + 1,
            "line": lines.and_then(|l| l.get(k)),
        })).collect::<Vec<_>>(),
    })
}

/// Measured orientations checked against a robot file's values: the angle, degrees, between
/// each measured frame and the one the file predicts
/// ([`crate::pose::orientation::orientation_errors_deg`]). From the file's values only, not over
/// a certified set: a 6-DoF calibrated file stores the positions' set.
#[derive(Clone, Debug, PartialEq)]
pub struct OrientationResiduals {
    /// One angle per configuration, degrees.
    pub per_row_deg: Vec<f64>,
    /// Their root mean square, degrees.
    pub rms_deg: f64,
    /// The largest, degrees.
    pub max_deg: f64,
}

impl OrientationResiduals {
    /// The residuals of the measured orientations `euler_xyz_deg` (intrinsic `XYZ`, degrees) at
    /// `readings` against `arm`, the robot file `robot`: an error naming it when it has no tool
    /// frame's rotation (`[tool] rpy_deg`).
    pub fn of(
        arm: &Arm,
        robot: &std::path::Path,
        readings: &[crate::simulate::Reading],
        euler_xyz_deg: &[[f64; 3]],
    ) -> Result<Self, String> {
        use crate::pose::orientation::{orientation_errors_deg, tool_rotation};
        let tool = arm.tool_rotation.ok_or_else(|| {
            format!(
                "{}: [tool] has no rpy_deg: checking measured orientations needs the tool \
                 frame's rotation (a 6-DoF calibration: `arm certify --orientation-columns … \
                 --write-calibrated`)",
                robot.display()
            )
        })?;
        let per_row_deg =
            orientation_errors_deg(arm, &tool_rotation(tool.rpy_deg), readings, euler_xyz_deg);
        let n = per_row_deg.len().max(1) as f64;
        Ok(Self {
            rms_deg: (per_row_deg.iter().map(|a| a * a).sum::<f64>() / n).sqrt(),
            max_deg: per_row_deg.iter().fold(0.0_f64, |m, a| m.max(*a)),
            per_row_deg,
        })
    }

    /// The JSON object `orientation_residuals` of `arm predict --json`.
    pub fn json(&self) -> serde_json::Value {
        serde_json::json!({
            "rms_deg": self.rms_deg,
            "max_deg": self.max_deg,
            "per_row_deg": self.per_row_deg,
        })
    }
}
