//! Predictions to check new measurements against (`arm predict`): per configuration, the
//! certified range of each coordinate of the tracked point over every parameter vector the
//! calibration allows, and the same widened by the measurement error bounds.
//!
//! The predictions run on the accuracy engine ([`SetAccuracy::predict`](
//! calib_pipeline::accuracy::SetAccuracy::predict), the tool point as its prediction
//! [`crate::accuracy::over_set::ToolPoint`]): at joint readings `q`, the model's affine form over
//! the set's outer box `X` gives each coordinate as `p_r ∈ c + Σ_j (g_j / rad(X_j)) (x_j -
//! mid(X_j)) + Σ_i h_i η_i ± e`, its largest and smallest values over the certified set bounded
//! by one linear program per piece (safe bounds), the joint readings' terms by their magnitudes;
//! the engine also reports what certified geometries reach (`attained`). The **range** takes the
//! readings as exact; **with errors** the joint readings lie within `± joint_deg` and the
//! tracked point within `± pos`: a measured point outside it is impossible unless the model or
//! the error bounds are wrong there — the row refutes them.
//!
//! An arm whose robot file has no certified set is predicted over its box (a superset).

use crate::accuracy::over_set::{joint_box, tool_point_engine};
use crate::certification::{padded_box, ArmSet, MAX_JOINTS, NM, NX};
use crate::robot::Arm;
use crate::simulate::Uncertainty;
use crate::units::deg_to_rad;
use crate::Arm7Point;
use calib_core::{Interval, VectorModel};
use calib_pipeline::accuracy::Predicted;
use rayon::prelude::*;

/// The prediction at one configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct PointPrediction {
    /// The joint readings (degrees).
    pub joints_deg: Vec<f64>,
    /// Per coordinate, the tracked point at exactly these readings over every consistent
    /// parameter vector (mm, tracker frame).
    pub range: [Interval; 3],
    /// Per coordinate, values that parameter vectors proved consistent with the measurements
    /// give at exactly these readings: some at most its lower end, some at least its upper end
    /// (`None` without a set): how tight `range` is.
    pub attained: [Option<Interval>; 3],
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

/// The padded joint box of the readings `joints_deg` (radians, enclosed: a reading in degrees
/// has no exact radian value).
fn joints_box(joints_deg: &[f64]) -> [Interval; MAX_JOINTS] {
    core::array::from_fn(|i| {
        joints_deg
            .get(i)
            .map_or(Interval::ZERO, |q| joint_box(*q, *q))
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
    // One engine over the rows' joint hull: its catalogue of certified geometries and its
    // parallelotope serve every row.
    let engine = set.and_then(|s| {
        let domain = joints_deg
            .iter()
            .map(|q| joints_box(q))
            .reduce(|a, b| core::array::from_fn(|i| a[i].hull(b[i])))?;
        tool_point_engine(arm, s.clone(), domain, u.joint_deg).ok()
    });
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
            || engine.as_ref().map(|e| (e, e.programs())),
            |programs, (k, q)| {
                // Over the arm's box (the only answer without a set), narrowed by the set's.
                let boxed =
                    |joint_deg: f64| Arm7Point.residuals_interval(&x, &readings_box(q, joint_deg));
                let mut over_set = |errors: bool| {
                    let (e, lps) = programs.as_mut()?;
                    e.predict(&joints_box(q), errors, lps)
                };
                let exact = over_set(false);
                let attained = exact.map_or([None; 3], |p| p.attained.map(|a| a.map(|a| a.range)));
                let range = narrowed(boxed(0.0), exact);
                let with_errors = narrowed(boxed(u.joint_deg), over_set(true)).map(|v| v + pos);
                let point = measured.and_then(|m| m.get(k)).copied();
                let radians: Vec<f64> = q.iter().map(|d| crate::units::to_rad(*d)).collect();
                let calibrated =
                    crate::model::tracked_point(&values, &radians).unwrap_or([f64::NAN; 3]);
                PointPrediction {
                    joints_deg: q.clone(),
                    range,
                    attained,
                    with_errors,
                    calibrated,
                    measured: point,
                    inside: point.map(|p| (0..3).all(|c| with_errors[c].contains(p[c]))),
                }
            },
        )
        .collect()
}

/// The box's enclosure `boxed`, narrowed by the set's (both hold every prediction).
fn narrowed(boxed: [Interval; 3], over_set: Option<Predicted<NX, 3>>) -> [Interval; 3] {
    let Some(p) = over_set else {
        return boxed;
    };
    core::array::from_fn(|r| {
        let both = p.outer[r].intersection(boxed[r]);
        if both.is_empty() {
            boxed[r]
        } else {
            both
        }
    })
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
/// `"box"`), per row `joints_deg`, `range`, `attained` (`[lo, hi]` or `null`) and
/// `with_errors` (per coordinate `[lo, hi]`),
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
            "attained": p.attained.map(|v| v.map(|c| [c.inf(), c.sup()])),
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
    ) -> Result<Self, crate::ArmError> {
        use crate::pose::orientation::{orientation_errors_deg, tool_rotation};
        let tool = arm
            .tool_rotation
            .ok_or_else(|| crate::ArmError::PredictionLacksToolRotation(robot.to_path_buf()))?;
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
