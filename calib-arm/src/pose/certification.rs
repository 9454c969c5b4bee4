//! Certifying an arm on 6-DoF measurements: the point model's padded problem
//! ([`crate::certification`]) with the tool frame's rotation appended to the parameters and the
//! measured Euler angles to each configuration's measured quantities, through [`Arm7Pose`].
//!
//! The run reports the verdict, the outer and inner bounds, identifiability and the
//! least-squares fit as the point model's does, and two certified sets:
//! * the 6-DoF set ([`PoseSet`], in the pose model's parameters): the calibrated vector is chosen
//!   in it and proved consistent with all six equations of every configuration
//!   ([`crate::calibrated::calibrated_pose_arm`]);
//! * its positions' set ([`crate::certification::ArmSet`]), what `predict` and `accuracy` work
//!   over: the polyhedra of the position equations on the cover's boxes without their tool
//!   rotation. Every 6-DoF solution `(x, r)` has its `x` in one of these boxes and fits the
//!   position rows (the pose model's first three rows are [`crate::Arm7Point`]'s on the same
//!   quantities), so the set holds `x`: a sound outer approximation of the 6-DoF set's projection,
//!   narrowed by the orientations through the boxes.

use super::{Arm7Pose, PoseReading, PoseUncertainty};
use crate::certification::{
    check_shape, padded_box, padded_index, padded_nominal, point_model_cover, run_model,
    verdict_settings, ArmRun, ArmSet, CertifyRequest, Cover, Job, Padded, ARM_PIECES, NM, NX,
};
use crate::params::{self, Unit};
use crate::robot::Arm;
use crate::simulate::{measurement_box, Reading};
use crate::units::{deg_to_rad, to_rad};
use crate::{Arm7Point, ArmError};
use calib_core::{CertifiedSet, Interval};
use calib_pipeline::smallest_consistent;

/// Parameters of the padded 6-DoF model: the point model's, then `tool_rx, tool_ry, tool_rz`.
pub const NX6: usize = NX + 3;
/// Measured quantities of the padded 6-DoF model: the point model's, then the Euler angles.
pub const NM6: usize = NM + 3;

/// An arm's certified set on 6-DoF data, in the padded pose model ([`NX6`] parameters: the point
/// model's, then the tool frame's rotation, radians; [`NM6`] measured quantities).
pub type PoseSet = CertifiedSet<NX6, NM6>;

/// The parameter names of an arm with `joints` joints measured in 6-DoF.
pub fn names(joints: usize) -> Vec<String> {
    params::pose_names(joints)
        .into_iter()
        .map(|(n, _)| n)
        .collect()
}

/// Certifies `arm` (which must carry a [`crate::robot::ToolRotation`]) against 6-DoF
/// measurements as [`crate::certification::certify_request`] does against points: with
/// [`calib_pipeline::OutlierBudget::Auto`], with the smallest number of tolerated outliers not
/// proved empty. Returns that number and the run, with both certified sets (see the module's
/// documentation) unless the data were proved inconsistent. `u.orient_deg` must be given.
pub fn certify_pose_request(
    arm: &Arm,
    readings: &[PoseReading],
    u: &PoseUncertainty,
    request: &CertifyRequest,
) -> Result<(usize, ArmRun), ArmError> {
    let p = padded_pose(arm, readings, u)?;
    let (settings, options) = request.prepared(readings.len())?;
    let names = names(arm.joints.len());
    let prior: Vec<Interval> = p.index.iter().map(|&i| p.x0[i]).collect();
    smallest_consistent(
        request.max_outliers,
        readings.len(),
        |q| {
            let settings = settings.clone().with_max_outliers(q);
            let job = Job::Certify(options);
            let (mut run, cover) = run_model(&Arm7Pose, &p, names.clone(), &prior, job, &settings);
            if let Some(cover) = cover {
                (run.set, run.pose_set) = certified_sets(&p.boxes, &cover);
            }
            Ok(run)
        },
        |run: &ArmRun| run.outcome.status == calib_core::Status::Empty,
    )
}

/// The 6-DoF set of a certified `cover` against `boxes` and its positions' set (module
/// documentation), each `None` when empty.
fn certified_sets(
    boxes: &[[Interval; NM6]],
    certified: &Cover<NX6>,
) -> (Option<ArmSet>, Option<PoseSet>) {
    let (cover, points) = certified;
    let pose = PoseSet::new(&Arm7Pose, cover, boxes, points, ARM_PIECES);
    let (projected, point_params) = point_model_cover(certified);
    let point_boxes: Vec<[Interval; NM]> = boxes
        .iter()
        .map(|m| core::array::from_fn(|i| m[i]))
        .collect();
    let positions = ArmSet::new(
        &Arm7Point,
        &projected,
        &point_boxes,
        &point_params,
        ARM_PIECES,
    );
    (
        (!positions.is_empty()).then_some(positions),
        (!pose.is_empty()).then_some(pose),
    )
}

/// Only the verdict of certifying `arm` against 6-DoF `readings` with the error bounds `u` (x1,
/// no inner bounds, no conflict search; see [`crate::certification::verdict_only`]).
pub fn verdict_only_pose(
    arm: &Arm,
    readings: &[PoseReading],
    u: &PoseUncertainty,
) -> Result<calib_core::Status, ArmError> {
    let p = padded_pose(arm, readings, u)?;
    let (settings, options) = verdict_settings(readings.len())?;
    let prior: Vec<Interval> = p.index.iter().map(|&i| p.x0[i]).collect();
    let names = names(arm.joints.len());
    let job = Job::Certify(options);
    let (run, _) = run_model(&Arm7Pose, &p, names, &prior, job, &settings);
    Ok(run.outcome.status)
}

/// The padded 6-DoF problem, or what is missing for it.
pub(crate) fn padded_pose(
    arm: &Arm,
    readings: &[PoseReading],
    u: &PoseUncertainty,
) -> Result<Padded<NX6, NM6>, ArmError> {
    let plain: Vec<Reading> = readings.iter().map(|r| r.reading.clone()).collect();
    check_shape(arm, &plain)?;
    let tool = arm.tool_rotation.ok_or(ArmError::PoseNeedsToolRotation)?;
    let orient_deg = u.orient_deg.ok_or(ArmError::PoseNeedsOrientBound)?;
    let joints = arm.joints.len();
    let base = padded_box(arm);
    let nominal = padded_nominal(arm);
    let x0 = core::array::from_fn(|i| match i.checked_sub(NX) {
        None => base[i],
        Some(k) => deg_to_rad(Interval::mid_rad(tool.rpy_deg[k], tool.radius[k])),
    });
    let nominal = core::array::from_fn(|i| match i.checked_sub(NX) {
        None => nominal[i],
        Some(k) => to_rad(tool.rpy_deg[k]),
    });
    let boxes = readings
        .iter()
        .map(|r| {
            let point: [Interval; NM] =
                measurement_box(&r.reading, &u.position).ok_or(ArmError::TooManyJointReadings)?;
            Ok(core::array::from_fn(|i| match i.checked_sub(NM) {
                None => point[i],
                Some(k) => deg_to_rad(Interval::mid_rad(r.euler_xyz_deg[k], orient_deg)),
            }))
        })
        .collect::<Result<Vec<[Interval; NM6]>, ArmError>>()?;
    let mut index = padded_index(joints);
    index.extend(NX..NX6);
    let units = params::pose_names(joints)
        .into_iter()
        .map(|(_, u)| u)
        .collect::<Vec<Unit>>();
    Ok(Padded {
        x0,
        nominal,
        boxes,
        index,
        units,
    })
}
