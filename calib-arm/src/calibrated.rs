//! The calibrated arm (`arm certify --write-calibrated`): the robot file a controller loads after
//! calibration, and the certified set it comes from.
//!
//! The file holds
//! * the **calibrated parameters**: a parameter vector proved consistent with every
//!   measurement (with part of every error bound to spare where the data allow), chosen by a
//!   [`PointRule`] ([`calib_core::calibrated_point()`]) — by default towards the Chebyshev centre
//!   of the tool points it predicts at the measured configurations and at configurations spread
//!   over their joint ranges, so that the worst prediction error is as small as the data allow;
//!   the value written (degrees, shortest decimals) is proved consistent again as read back;
//! * `radius`: a box around it containing the certified outer box (a reader that knows only
//!   boxes still holds every consistent parameter vector);
//! * `[certified_set]`: the measurement boxes, the cover and certified points from which the set
//!   is rebuilt ([`calib_pipeline::stored_set`], in the arm's own parameters in model order,
//!   radians and mm), so that `arm accuracy` and `arm predict` work over it from the file alone.

use crate::carry::NX2;
use crate::certification::{padded_index, padded_quantities, ArmRun, ArmSet, MAX_JOINTS, NM, NX};
use crate::model::Arm7PointTwoFrames;
use crate::params::{self, Unit};
use crate::pose::certification::NX6;
use crate::pose::Arm7Pose;
use crate::robot::{Arm, Joint, ToolRotation};
use crate::units::{deg_to_rad, rad_to_deg, to_deg};
use crate::{Arm7Point, ArmError};
use calib_core::{
    calibrated_point, is_certified_consistent, CalibratedPoint, Interval, PointRule, VectorModel,
};
use calib_pipeline::calibrated::radius_about;
use calib_pipeline::stored_set::StoredSet;
use rand::{Rng, SeedableRng};

/// How the calibrated parameter vector is chosen (see [`calib_core::calibrated_point()`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PointChoice {
    /// Towards the Chebyshev centre of the predicted tool points: the worst prediction error
    /// over the certified set is as small as the data allow.
    Centre,
    /// The default (as `arm certify --calibrated-point lsq`): towards the least-squares fit
    /// within the set, regularised towards the certified box's
    /// centre by a weight chosen by cross-validation (`calib_core::set_least_squares`): on
    /// held-out data with errors the model does not hold (gravity, gears), the best predictor
    /// (real UR10 at 0.6 mm: held-out rms 0.330 mm, against 0.612 mm towards the centre).
    #[default]
    LeastSquares,
    /// Towards the Chebyshev centre of the tool points predicted at exactly the configurations
    /// given (the task's, `arm certify --task`): the worst prediction error over the set, there,
    /// is as small as the data allow.
    Task,
}

/// Random configurations (besides the measured ones) whose tool points the centre rule predicts.
const PREDICTION_CONFIGURATIONS: usize = 50;

/// A calibrated arm: the file's arm and the certified set it comes from.
#[derive(Clone, Debug)]
pub struct CalibratedArm {
    /// The arm a controller loads: the calibrated parameters (files' units), radii whose boxes
    /// contain the certified outer box.
    pub arm: Arm,
    /// The certified set (padded model, radians).
    pub set: ArmSet,
    /// How the parameters were chosen.
    pub point: CalibratedPoint<NX>,
}

/// The padded joint readings (radians) of a configuration in degrees.
fn padded_joints(joints_deg: &[f64]) -> [f64; NM] {
    let mut m = [0.0; NM];
    for (i, q) in joints_deg.iter().enumerate().take(MAX_JOINTS) {
        m[i] = q.to_radians();
    }
    m
}

/// The gradients `∂p/∂θ` (three rows per configuration) at `at` the rule `choice` predicts at:
/// for [`PointChoice::Task`] the configurations `joints`, else the measured configurations
/// `joints` and [`PREDICTION_CONFIGURATIONS`] random ones within their joint ranges.
fn predictions(choice: PointChoice, joints: &[Vec<f64>], at: &[f64; NX]) -> Vec<[f64; NX]> {
    if choice == PointChoice::Task {
        return gradients(joints, at);
    }
    let n = joints.first().map_or(0, Vec::len);
    let range: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            joints
                .iter()
                .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], q| {
                    [lo.min(q[i]), hi.max(q[i])]
                })
        })
        .collect();
    let mut rng = rand::rngs::StdRng::seed_from_u64(0xa7);
    let random: Vec<Vec<f64>> = (0..PREDICTION_CONFIGURATIONS)
        .map(|_| {
            range
                .iter()
                .map(|[lo, hi]| lo + (hi - lo) * rng.random::<f64>())
                .collect()
        })
        .collect();
    gradients(&[joints, &random[..]].concat(), at)
}

/// The gradients `∂p/∂θ` at `at`, three rows per configuration of `joints`.
fn gradients(joints: &[Vec<f64>], at: &[f64; NX]) -> Vec<[f64; NX]> {
    joints
        .iter()
        .flat_map(|q| Arm7Point.evaluate_rows(at, &padded_joints(q)).map(|e| e.dx))
        .collect()
}

/// The calibrated arm of a certified run (see the module documentation). An error when the data
/// were proved inconsistent, or when no parameter vector was proved consistent (undecided). A
/// 6-DoF run ([`ArmRun::pose_set`]) goes to [`calibrated_pose_arm`].
pub fn calibrated_arm(
    arm: &Arm,
    run: &ArmRun,
    joints_deg: &[Vec<f64>],
    choice: PointChoice,
) -> Result<CalibratedArm, ArmError> {
    if run.pose_set.is_some() {
        return calibrated_pose_arm(arm, run, joints_deg, choice);
    }
    if run.two_frame_set.is_some() {
        return calibrated_carried_arm(arm, run, joints_deg, choice);
    }
    let outer = certified_outer(run)?;
    let mut set = run.set.clone().ok_or(ArmError::Undecided)?;
    let joints = arm.joints.len();
    let index = padded_index(joints);
    if outer.len() != index.len() {
        return Err(ArmError::CertifiedBoxSize {
            found: outer.len(),
            expected: index.len(),
        });
    }
    // Where the rule's predictions are linearised (a target, not a proof): a certified point, or
    // the set's centre when none was kept (a carried-over set's points are proved in another
    // model, and one at the edge of a bound may not be proved again here).
    let witness = match set.points().first() {
        Some(p) => p.x,
        None => set.outer().ok_or(ArmError::Undecided)?.map(|v| v.mid()),
    };
    let preds = predictions(choice, joints_deg, &witness);
    let point =
        calibrated_point(&Arm7Point, &mut set, rule(choice, &preds)).ok_or(ArmError::Undecided)?;

    // The point as the file writes it, proved again as a controller reads it back; else the
    // deepest point, which keeps the most room.
    let kept = set.subset_measurements(point.subset);
    let written = [point.x, point.deepest]
        .into_iter()
        .map(|x| with_point(arm, outer, &x))
        .find(|a| is_certified_consistent(&Arm7Point, &read_back(a), &kept))
        .ok_or(ArmError::Undecided)?;
    Ok(CalibratedArm {
        arm: written,
        set,
        point,
    })
}

/// The calibrated arm of a run with a certified set carried over ([`crate::carry`]): the
/// parameter vector is chosen in the set over both series ([`ArmRun::two_frame_set`]) by the same
/// rules, and proved, as the file writes it, consistent with every new row and, with the earlier
/// frame's base and tool it was chosen with, every earlier row; the file's `[certified_set]` is
/// the run's set in this frame ([`ArmRun::set`]), to which the written vector is added.
fn calibrated_carried_arm(
    arm: &Arm,
    run: &ArmRun,
    joints_deg: &[Vec<f64>],
    choice: PointChoice,
) -> Result<CalibratedArm, ArmError> {
    let outer = certified_outer(run)?;
    let mut both = run.two_frame_set.clone().ok_or(ArmError::Undecided)?;
    let mut set = run.set.clone().ok_or(ArmError::Undecided)?;
    let witness = match both.points().first() {
        Some(p) => head(&p.x),
        None => head(&both.outer().ok_or(ArmError::Undecided)?.map(|v| v.mid())),
    };
    // The earlier frame's columns 0: the tool points predicted in this frame.
    let preds: Vec<[f64; NX2]> = widened(&predictions(choice, joints_deg, &witness));
    let point = calibrated_point(&Arm7PointTwoFrames, &mut both, rule(choice, &preds))
        .ok_or(ArmError::Undecided)?;
    let kept = both.subset_measurements(point.subset);
    let (written, x) = [point.x, point.deepest]
        .into_iter()
        .map(|x| (with_point(arm, outer, &head(&x)), x))
        .find(|(a, x)| {
            let here = read_back(a);
            let read: [Interval; NX2] = core::array::from_fn(|i| match i.checked_sub(NX) {
                None => here[i],
                Some(_) => Interval::point(x[i]),
            });
            is_certified_consistent(&Arm7PointTwoFrames, &read, &kept)
        })
        .ok_or(ArmError::Undecided)?;
    // The written vector fits the new rows: the file's set holds it as a certified point.
    let written_point = read_back(&written).map(|v| v.mid());
    set.add_point(&Arm7Point, &written_point);
    Ok(CalibratedArm {
        arm: written,
        set,
        point: in_point_model(&point, &x),
    })
}

/// The calibrated arm of a certified 6-DoF run: the parameter vector, tool rotation included, is
/// chosen in the 6-DoF set ([`ArmRun::pose_set`]) by the same rules (the centre rule over the
/// predicted tool points) and proved consistent with all six equations of every configuration as
/// the file writes it; the file's `[certified_set]` is the run's positions' set ([`ArmRun::set`],
/// see [`crate::pose::certification`]), which holds every 6-DoF solution's parameters.
pub fn calibrated_pose_arm(
    arm: &Arm,
    run: &ArmRun,
    joints_deg: &[Vec<f64>],
    choice: PointChoice,
) -> Result<CalibratedArm, ArmError> {
    let outer = certified_outer(run)?;
    let mut pose_set = run.pose_set.clone().ok_or(ArmError::Undecided)?;
    let set = run.set.clone().ok_or(ArmError::Undecided)?;
    let tool = arm
        .tool_rotation
        .ok_or(ArmError::CalibrationNeedsToolRotation)?;
    let index = padded_index(arm.joints.len());
    if outer.len() != index.len() + 3 {
        return Err(ArmError::PoseCertifiedBoxSize {
            found: outer.len(),
            expected: index.len() + 3,
        });
    }
    let witness = pose_set
        .points()
        .first()
        .map(|p| head(&p.x))
        .ok_or(ArmError::Undecided)?;
    // The position rows' gradients, the tool rotation's columns 0: the tool points predicted.
    let preds: Vec<[f64; NX6]> = widened(&predictions(choice, joints_deg, &witness));
    let point = calibrated_point(&Arm7Pose, &mut pose_set, rule(choice, &preds))
        .ok_or(ArmError::Undecided)?;
    let kept = pose_set.subset_measurements(point.subset);
    let (outer_point, outer_tool) = outer.split_at(index.len());
    let written = [point.x, point.deepest]
        .into_iter()
        .map(|x| {
            let mut a = with_point(arm, outer_point, &head(&x));
            // As `with_point`: a fixed angle keeps its decimal, a free one takes the point's.
            let free = |k: usize| tool.radius[k] > 0.0;
            let rpy_deg: [f64; 3] = core::array::from_fn(|k| {
                if free(k) {
                    to_deg(x[NX + k])
                } else {
                    tool.rpy_deg[k]
                }
            });
            a.tool_rotation = Some(ToolRotation {
                rpy_deg,
                radius: core::array::from_fn(|k| {
                    if free(k) {
                        radius_about(rpy_deg[k], outer_tool[k])
                    } else {
                        0.0
                    }
                }),
            });
            a
        })
        .find(|a| read_back_pose(a).is_some_and(|x| is_certified_consistent(&Arm7Pose, &x, &kept)))
        .ok_or(ArmError::Undecided)?;
    Ok(CalibratedArm {
        arm: written,
        set,
        point: in_point_model(&point, &point.x),
    })
}

/// The certified outer box, or why there is none (the data were proved inconsistent).
fn certified_outer(run: &ArmRun) -> Result<&[Interval], ArmError> {
    run.outcome.outer.as_deref().ok_or(ArmError::Inconsistent)
}

/// The point rule of `choice`, with the predicted tool points' gradients `preds`.
fn rule<const X: usize>(choice: PointChoice, preds: &[[f64; X]]) -> PointRule<'_, X> {
    match choice {
        PointChoice::Centre | PointChoice::Task => PointRule::PredictionCentre(preds),
        PointChoice::LeastSquares => PointRule::LeastSquares,
    }
}

/// The point model's gradients `preds` in a model that extends it (its first [`NX`] parameters
/// are the point model's), the columns after those 0.
fn widened<const X: usize>(preds: &[[f64; NX]]) -> Vec<[f64; X]> {
    preds
        .iter()
        .map(|g| core::array::from_fn(|i| g.get(i).copied().unwrap_or(0.0)))
        .collect()
}

/// A point chosen in a model that extends the point model, in the point model's parameters; `x`
/// the vector written (its chosen point or its deepest).
fn in_point_model<const X: usize>(point: &CalibratedPoint<X>, x: &[f64; X]) -> CalibratedPoint<NX> {
    CalibratedPoint {
        x: head(x),
        deepest: head(&point.deepest),
        target: head(&point.target),
        margin: point.margin,
        deepest_misfit: point.deepest_misfit,
        reached: point.reached,
        prior_weight: point.prior_weight,
        subset: point.subset,
    }
}

/// The point model's parameters of a pose model's vector (without the tool rotation).
fn head<const X: usize>(x: &[f64; X]) -> [f64; NX] {
    core::array::from_fn(|i| x[i])
}

/// The padded pose model's box of the values a controller reads from `arm` ([`read_back`], then
/// the tool rotation's degrees enclosed in radians); `None` without a tool rotation.
fn read_back_pose(arm: &Arm) -> Option<[Interval; NX6]> {
    let point = read_back(arm);
    let tool = arm.tool_rotation?;
    Some(core::array::from_fn(|i| match i.checked_sub(NX) {
        None => point[i],
        Some(k) => deg_to_rad(Interval::point(tool.rpy_deg[k])),
    }))
}

/// The arm with its free parameters at the padded model's point `x` (files' units, shortest
/// decimals) and radii whose boxes contain `outer` and the point.
fn with_point(arm: &Arm, outer: &[Interval], x: &[f64; NX]) -> Arm {
    let joints = arm.joints.len();
    let units: Vec<Unit> = params::names(joints).into_iter().map(|(_, u)| u).collect();
    let (mut value, mut radius) = (arm.nominal(), arm.radius());
    for (j, &p) in padded_index(joints).iter().enumerate() {
        if radius[j] > 0.0 {
            value[j] = match units[j] {
                Unit::Deg => to_deg(x[p]),
                Unit::Mm => x[p],
            };
            radius[j] = radius_about(value[j], outer[j]);
        }
    }
    Arm {
        // Positions alone say nothing of the tool frame's rotation: kept as it was.
        tool_rotation: arm.tool_rotation,
        ..with_parameters(joints, &value, &radius)
    }
}

/// The padded model's box of the values a controller reads from `arm` (each decimal in degrees
/// enclosed in radians).
#[doc(hidden)]
pub fn read_back(arm: &Arm) -> [Interval; NX] {
    let joints = arm.joints.len();
    let units: Vec<Unit> = params::names(joints).into_iter().map(|(_, u)| u).collect();
    let mut x = [Interval::ZERO; NX];
    for ((j, &p), v) in padded_index(joints).iter().enumerate().zip(arm.nominal()) {
        x[p] = match units[j] {
            Unit::Deg => deg_to_rad(Interval::point(v)),
            Unit::Mm => Interval::point(v),
        };
    }
    x
}

/// `robot.toml` text of a calibrated arm: the arm, then its `[certified_set]`.
pub fn calibrated_toml(c: &CalibratedArm, comment: &str) -> String {
    let joints = c.arm.joints.len();
    let stored = StoredSet::of(&c.set, &padded_index(joints), &padded_quantities(joints));
    format!(
        "{comment}{}{}",
        crate::write::robot_toml(&c.arm),
        stored.to_toml("certified_set")
    )
}

/// The certified set's outer box in the files' units (degrees, outward), arm order.
pub fn outer_in_file_units(arm: &Arm, set: &ArmSet) -> Option<Vec<Interval>> {
    let o = set.outer()?;
    let joints = arm.joints.len();
    let units: Vec<Unit> = params::names(joints).into_iter().map(|(_, u)| u).collect();
    Some(
        padded_index(joints)
            .iter()
            .zip(&units)
            .map(|(&p, u)| match u {
                Unit::Deg => rad_to_deg(o[p]),
                Unit::Mm => o[p],
            })
            .collect(),
    )
}

/// The arm with these values and half-widths (model order, the files' units).
fn with_parameters(joints: usize, value: &[f64], radius: &[f64]) -> Arm {
    let five = |v: &[f64], i: usize| -> [f64; 5] { core::array::from_fn(|k| v[5 * i + k]) };
    let tail = |v: &[f64], from: usize| -> Vec<f64> { v[5 * joints + from..].to_vec() };
    let (base, base_r, tool, tool_r) = (
        tail(value, 0),
        tail(radius, 0),
        tail(value, 6),
        tail(radius, 6),
    );
    Arm {
        joints: (0..joints)
            .map(|i| Joint {
                nominal: five(value, i),
                radius: five(radius, i),
            })
            .collect(),
        base: core::array::from_fn(|k| base[k]),
        base_radius: core::array::from_fn(|k| base_r[k]),
        tool: core::array::from_fn(|k| tool[k]),
        tool_radius: core::array::from_fn(|k| tool_r[k]),
        tool_rotation: None,
    }
}
