//! Predictions to check new measurements against (`gough predict`): per pose and leg, the
//! certified range of the leg's reading over every geometry the calibration allows, and the
//! same widened by the measurement error bounds.
//!
//! For leg `i` at pose `X`, with `θ̂` the file's geometry and `S_i` its certified set, the
//! reading is exactly `L_i(X; θ) = L_i(X; θ̂) + G·(θ - θ̂) + r` with `G = ∇_θ L_i(X; θ̂)` and
//! `0 <= r <=` the legs' curvature bound ([`crate::accuracy::LegCurvature`]). The **range** —
//! the reading the leg would show at exactly `X`, for every consistent geometry — brackets
//! `G·θ` over the set with refinement ([`calib_core::maximize_over_set`]: one linear program
//! per piece, the pieces where the bound is attained split and contracted, lower bounds at
//! certified geometries), the set getting finer as the predictions go. With the measurement error bounds, the
//! pose is a box (position ± `pos`, the rotation's box from its axis ± `axis` and angle ±
//! `angle_deg`; the error enclosed over it as in the accuracy certificate,
//! [`crate::accuracy::AccuracyProblem::leg_error`]) and the range is widened by the reading's
//! ± `len`: a **measured** reading outside
//! that is impossible unless the model or the error bounds are wrong there — the row refutes
//! them.
//!
//! A leg whose robot file has no certified set is predicted over its box (a superset).

use crate::accuracy::{AccuracyProblem, LegCurvature, LegReading, PoseBox};
use crate::calibrated::measured_workspace;
use crate::files::LegSpec;
use crate::geometry::rodrigues_box;
use crate::measurement::{measured, Configuration, Orientation, Uncertainty};
use crate::LegModel;
use calib_core::{
    maximize_over_set, CertifiedSet, Interval, LinearFunction, Model, SetMaximumSettings,
    SetObjective,
};
use rayon::prelude::*;

/// One leg's prediction at one pose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LegPrediction {
    /// The reading at exactly the pose, over every consistent geometry (cm).
    pub range: Interval,
    /// The reading a measurement may show: over the pose's error box, widened by the reading's
    /// error bound (cm).
    pub with_errors: Interval,
    /// The measured reading, when given.
    pub measured: Option<f64>,
    /// Whether the measured reading lies in `with_errors` (`None` without one): `false` refutes
    /// the model or the error bounds at this row.
    pub inside: Option<bool>,
}

/// The predictions at one pose.
#[derive(Clone, Debug, PartialEq)]
pub struct PosePrediction {
    /// The pose (a configuration; its readings are the measured ones, when given).
    pub configuration: Configuration,
    /// Per leg.
    pub legs: Vec<LegPrediction>,
}

/// The pose box of a configuration: exactly its values (`u` `None`), or within the error bounds.
fn pose_box(c: &Configuration, u: Option<&Uncertainty>) -> PoseBox {
    let h = |v: f64| u.map_or(0.0, |_| v);
    let u0 = Uncertainty::uniform(0.0);
    let u = u.unwrap_or(&u0);
    let q = match c.orientation {
        Orientation::AxisAngle { axis, angle_deg } => rodrigues_box(
            &axis.map(|v| measured(v, h(u.axis))),
            measured(angle_deg, h(u.angle_deg)),
        ),
        Orientation::Rodrigues(q) => q.map(|v| measured(v, h(u.q))),
    };
    let p = c.p.map(|v| measured(v, h(u.pos)));
    [p[0], p[1], p[2], q[0], q[1], q[2]]
}

/// Refinements of a leg's set per prediction and direction (the refined pieces are kept for the
/// next predictions: a leg's set gets finer where its predictions reach) …
const REFINEMENTS: usize = 16;
/// … until it has this many pieces (each prediction solves a linear program per piece).
const MAX_PIECES: usize = 96;

/// The range of leg `i`'s reading at exactly the pose `x` over its set: `L(X; θ̂) + G·δ + r`
/// with `G = ∇_θ L(X; θ̂)` (exact slopes at a point pose), `G·δ` bracketed over the set with
/// refinement ([`maximize_over_set`] until the bracket is within 1% of the range or the
/// refinements are spent) and `0 <= r <=` the curvature bound ([`crate::accuracy::LegCurvature`]).
fn range_over_set(
    set: &mut CertifiedSet<7, 8>,
    nominal: &[f64; 7],
    x: &[f64; 6],
) -> Option<Interval> {
    let at = LegReading.residual_interval(&nominal.map(Interval::point), &x.map(Interval::point));
    let g = LegReading.jacobian_x(nominal, x);
    let outer = set.outer()?;
    let width = {
        let mut q = set.query();
        q.range(&g).wid()
    };
    let settings = SetMaximumSettings {
        rel_tol: 0.0,
        abs_tol: 0.005 * width,
        max_refinements: if set.pieces().len() < MAX_PIECES {
            REFINEMENTS
        } else {
            0
        },
        ..SetMaximumSettings::default()
    };
    let model = LegModel::of_set(set);
    let up = maximize_over_set(&model, set, &LinearFunction(g), &settings).upper;
    let down = maximize_over_set(&model, set, &LinearFunction(g.map(|v| -v)), &settings).upper;
    let gn = LinearFunction(g).value(&nominal.map(Interval::point));
    let spread: [Interval; 7] = core::array::from_fn(|j| {
        outer[j].hull(Interval::point(nominal[j])) - Interval::point(nominal[j])
    });
    let inputs: [Interval; 13] = core::array::from_fn(|k| {
        if k < 6 {
            Interval::point(x[k])
        } else {
            Interval::point(nominal[k - 6])
        }
    });
    let r = LegCurvature.residual_interval(&spread, &inputs).sup();
    if !(up.is_finite() && down.is_finite() && r.is_finite() && r >= 0.0) {
        return None;
    }
    let lo = (at + Interval::point(-down) - gn).inf();
    let hi = (at + Interval::point(up) - gn + Interval::point(r)).sup();
    (lo <= hi).then(|| Interval::new(lo, hi))
}

/// The predictions of `robot` (each leg over its certified set when `sets` has it) at the poses
/// of `configs`; with `measured`, their readings are checked (see the module documentation).
pub fn predict(
    robot: &[LegSpec],
    sets: &[Option<CertifiedSet<7, 8>>],
    configs: &[Configuration],
    u: &Uncertainty,
    measured_readings: bool,
) -> Vec<PosePrediction> {
    let problem = AccuracyProblem::over_sets(robot, sets, &measured_workspace(configs));
    let legs = robot.len();
    // Per leg (in parallel), its predictions at every pose: its set refined along the way.
    let per_leg: Vec<Vec<LegPrediction>> = (0..legs)
        .into_par_iter()
        .map(|i| {
            let nominal = robot[i].nominal.params();
            let mut set = sets.get(i).cloned().flatten();
            configs
                .iter()
                .map(|c| {
                    let exact = pose_box(c, None);
                    let errors = pose_box(c, Some(u));
                    let boxed = |x: &PoseBox| {
                        LegReading.residual_interval(&nominal.map(Interval::point), x)
                            + problem.leg_error(i, x)
                    };
                    let range = set
                        .as_mut()
                        .and_then(|s| range_over_set(s, &nominal, &exact.map(|v| v.mid())))
                        .map_or_else(|| boxed(&exact), |r| r.intersection(boxed(&exact)));
                    let with_errors = boxed(&errors) + measured(0.0, u.len);
                    let reading = measured_readings
                        .then(|| c.lengths.get(i).copied())
                        .flatten();
                    LegPrediction {
                        range,
                        with_errors,
                        measured: reading,
                        inside: reading.map(|r| with_errors.contains(r)),
                    }
                })
                .collect()
        })
        .collect();
    configs
        .iter()
        .enumerate()
        .map(|(k, c)| PosePrediction {
            configuration: c.clone(),
            legs: per_leg.iter().map(|l| l[k]).collect(),
        })
        .collect()
}

/// The rows (0-based) and legs (0-based) whose measured reading lies outside its prediction.
pub fn refuting(predictions: &[PosePrediction]) -> Vec<(usize, usize)> {
    predictions
        .iter()
        .enumerate()
        .flat_map(|(k, p)| {
            p.legs
                .iter()
                .enumerate()
                .filter(|(_, l)| l.inside == Some(false))
                .map(move |(i, _)| (k, i))
        })
        .collect()
}

/// The predictions as CSV: the pose's columns (`px,py,pz,ax,ay,az,angle_deg`, or the Rodrigues
/// `q1,q2,q3`), then per leg `L{i}_lo,L{i}_hi` (the range), `L{i}_min,L{i}_max` (with the
/// error bounds) and, with measurements, `L{i},L{i}_inside`. Bounds are written outward in
/// shortest round-trip form.
pub fn predictions_csv(predictions: &[PosePrediction], measured_readings: bool) -> String {
    let legs = predictions.first().map_or(0, |p| p.legs.len());
    let rodrigues = predictions
        .first()
        .is_some_and(|p| matches!(p.configuration.orientation, Orientation::Rodrigues(_)));
    let mut header: Vec<String> = if rodrigues {
        ["px", "py", "pz", "q1", "q2", "q3"]
            .map(String::from)
            .to_vec()
    } else {
        crate::files::POSE_COLUMNS.map(String::from).to_vec()
    };
    for i in 1..=legs {
        header.extend([
            format!("L{i}_lo"),
            format!("L{i}_hi"),
            format!("L{i}_min"),
            format!("L{i}_max"),
        ]);
        if measured_readings {
            header.extend([format!("L{i}"), format!("L{i}_inside")]);
        }
    }
    let mut out = header.join(",") + "\n";
    for p in predictions {
        let c = &p.configuration;
        let mut row: Vec<String> = c.p.iter().map(|v| format!("{v:?}")).collect();
        match c.orientation {
            Orientation::AxisAngle { axis, angle_deg } => {
                row.extend(axis.iter().chain([&angle_deg]).map(|v| format!("{v:?}")));
            }
            Orientation::Rodrigues(q) => row.extend(q.iter().map(|v| format!("{v:?}"))),
        }
        for l in &p.legs {
            for v in [l.range, l.with_errors] {
                row.push(format!("{:?}", v.inf()));
                row.push(format!("{:?}", v.sup()));
            }
            if measured_readings {
                row.push(l.measured.map_or(String::new(), |m| format!("{m:?}")));
                row.push(l.inside.map_or(String::new(), |b| b.to_string()));
            }
        }
        out += &(row.join(",") + "\n");
    }
    out
}

/// The predictions as JSON (schema version 1; cm): per row its pose and, per leg, `over`
/// (`"certified set"` or `"box"`), `range`, `with_errors`, `measured`, `inside`; `refuting`
/// lists the rows (1-based) and legs (1-based) whose measurement lies outside its prediction.
pub fn predictions_json(
    predictions: &[PosePrediction],
    over_set: &[bool],
    lines: Option<&[usize]>,
) -> serde_json::Value {
    let pair = |v: Interval| [v.inf(), v.sup()];
    let rows: Vec<serde_json::Value> = predictions
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let c = &p.configuration;
            let rotation = match c.orientation {
                Orientation::AxisAngle { axis, angle_deg } => {
                    serde_json::json!({ "axis": axis, "angle_deg": angle_deg })
                }
                Orientation::Rodrigues(q) => serde_json::json!({ "rodrigues": q }),
            };
            serde_json::json!({
                "row": k + 1,
                "line": lines.and_then(|l| l.get(k)),
                "p": c.p,
                "rotation": rotation,
                "legs": p.legs.iter().enumerate().map(|(i, l)| serde_json::json!({
                    "leg": i + 1,
                    "over": crate::accuracy::over_words(over_set.get(i).copied().unwrap_or(false)),
                    "range": pair(l.range),
                    "with_errors": pair(l.with_errors),
                    "measured": l.measured,
                    "inside": l.inside,
                })).collect::<Vec<_>>(),
            })
        })
        .collect();
    serde_json::json!({
        "version": 1,
        "rows": rows,
        "refuting": refuting(predictions)
            .iter()
            .map(|(k, i)| serde_json::json!({
                "row": k + 1,
                "leg": i + 1,
                "line": lines.and_then(|l| l.get(*k)),
            }))
            .collect::<Vec<_>>(),
    })
}
