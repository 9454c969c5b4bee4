//! Carrying a calibration over to where the robot works next: the tracker moved, the robot went
//! to a new cell, a month went by. The earlier calibration's certified set (a calibrated file's
//! `[certified_set]`, or the `[carried_set]` that `arm register` copies from it) joins the new
//! measurements in one certification.
//!
//! The earlier rows were measured in the earlier tracker frame, with the tool as it was then: in
//! the two-frame model ([`crate::model::Arm7PointTwoFrames`]) they keep a base and a tool point of
//! their own (parameters 44–52, their prior the earlier set's hull), while the joints' parameters
//! are shared. Every vector consistent with both series is consistent with each, so the result is
//! the intersection of the earlier set (its rows, as certified) with what the new rows allow: the
//! new series narrows it, or proves the two inconsistent (the robot changed, or a bound was
//! wrong) and names the rows that refute it, earlier rows numbered after the new ones.
//!
//! What the run hands on ([`ArmRun::set`]) is the set in this frame: the cover's boxes without
//! the earlier frame's parameters and the new rows' relaxations on them. It holds every
//! parameter vector of the intersection (each satisfies the new rows in its box), so `predict`
//! and `accuracy` over it are sound; its certified points are the two-frame points', consistent
//! with the new rows and, with a base and tool of their own, with the earlier ones.

use crate::certification::{
    check_shape, names, padded_box, padded_index, padded_nominal, point_model_cover, run_model,
    verdict_settings, ArmRun, ArmSet, CertifyRequest, Cover, Job, Padded, ARM_PIECES, NM, NX,
};
use crate::error_scale::ScaleBounds;
use crate::model::Arm7PointTwoFrames;
use crate::params::{self, Unit};
use crate::robot::Arm;
use crate::simulate::{measurement_box, Reading, Uncertainty};
use crate::{Arm7Point, ArmError};
use calib_core::{CertifiedSet, Interval, Status};
use calib_pipeline::error_scale::{search_from_estimate, ErrorScale, ScaledProblem};
use calib_pipeline::identify::Identifiability;
use calib_pipeline::smallest_consistent;
use calib_pipeline::stored_set::StoredSet;
use std::path::Path;

/// Parameters of the two-frame model: the point model's, then the earlier frame's base (6) and
/// tool point (3).
pub const NX2: usize = NX + 9;
/// Measured quantities of the two-frame model: the point model's, then the frame flag.
pub const NM2: usize = NM + 1;

/// A certified set over both series in the two-frame model ([`NX2`] parameters, [`NM2`]
/// measured quantities).
pub type TwoFrameSet = CertifiedSet<NX2, NM2>;

/// Where the point model keeps the base and the tool point (its parameters from here on).
const BASE: usize = 5 * crate::certification::MAX_JOINTS;

/// Certifies `arm` on `readings` together with the rows of the `earlier` set (see the module
/// documentation), as [`crate::certification::certify_request`] does on `readings` alone: the
/// outliers tolerated (counted over both series) and the run, its set in this frame.
pub fn certify_carried(
    arm: &Arm,
    earlier: &ArmSet,
    readings: &[Reading],
    u: &Uncertainty,
    request: &CertifyRequest,
) -> Result<(usize, ArmRun), ArmError> {
    let p = two_frames(arm, earlier, readings, u)?;
    let (settings, options) = request.prepared(p.boxes.len())?;
    let names = names(arm.joints.len());
    let prior: Vec<Interval> = p.index.iter().map(|&i| p.x0[i]).collect();
    smallest_consistent(
        request.max_outliers,
        p.boxes.len(),
        |q| {
            let settings = settings.clone().with_max_outliers(q);
            let job = Job::Certify(options);
            let model = &Arm7PointTwoFrames;
            let (mut run, cover) = run_model(model, &p, names.clone(), &prior, job, &settings);
            if let Some((c, points)) = &cover {
                let set = TwoFrameSet::new(&Arm7PointTwoFrames, c, &p.boxes, points, ARM_PIECES);
                run.two_frame_set = (!set.is_empty()).then_some(set);
            }
            run.set = cover.and_then(|c| this_frame(&c, &p.boxes[..readings.len()]));
            in_this_frame(&mut run.identifiability, names.len());
            Ok(run)
        },
        |run: &ArmRun| run.outcome.status == Status::Empty,
    )
}

/// Only the verdict of [`certify_carried`] (x1, no inner bounds, no conflict search).
pub fn verdict_only_carried(
    arm: &Arm,
    earlier: &ArmSet,
    readings: &[Reading],
    u: &Uncertainty,
) -> Result<Status, ArmError> {
    let p = two_frames(arm, earlier, readings, u)?;
    let (settings, options) = verdict_settings(p.boxes.len())?;
    let prior: Vec<Interval> = p.index.iter().map(|&i| p.x0[i]).collect();
    let names = names(arm.joints.len());
    let job = Job::Certify(options);
    let (run, _) = run_model(&Arm7PointTwoFrames, &p, names, &prior, job, &settings);
    Ok(run.outcome.status)
}

/// [`crate::error_scale::search`] with the `earlier` set's rows: the smallest factor of `which`
/// bounds of the new rows (the earlier rows keep the bounds they were certified with) for which
/// both series are consistent.
pub fn search_carried(
    arm: &Arm,
    earlier: &ArmSet,
    readings: &[Reading],
    u: &Uncertainty,
    which: ScaleBounds,
    on_trial: impl FnMut(f64),
) -> Result<ErrorScale, ArmError> {
    let x0 = two_frames(arm, earlier, readings, u)?.x0;
    let boxes = |s: f64| -> Vec<[Interval; NM2]> {
        // The shape was checked by `two_frames` above: every scaled problem is built.
        two_frames(arm, earlier, readings, &which.scale(u, s))
            .map_or_else(|_| Vec::new(), |p| p.boxes)
    };
    let mask = which.mask(arm.joints.len());
    let problem = ScaledProblem {
        model: &Arm7PointTwoFrames,
        x0,
        boxes: &boxes,
        scaled: core::array::from_fn(|i| i < NM && mask[i]),
    };
    search_from_estimate(
        &[problem],
        |_, s| verdict_only_carried(arm, earlier, readings, &which.scale(u, s)),
        on_trial,
    )
}

/// The rows of the `earlier` set that carry over (0-based, into its measurements): all but those
/// a piece of its cover leaves out, which the earlier certification tolerated as outliers (they
/// hold no proof of anything about the robot).
pub fn carried_rows(earlier: &ArmSet) -> Vec<usize> {
    let cover = earlier.cover();
    let left_out: Vec<usize> = cover
        .subsets
        .iter()
        .flat_map(|&s| cover.dropped[s].iter().copied())
        .collect();
    (0..earlier.measurements().len())
        .filter(|k| !left_out.contains(k))
        .collect()
}

/// The two-frame problem: `arm`'s prior (its joints' parameters within the earlier set's hull),
/// the earlier frame's base and tool within that hull; the new rows (flag 0), then the earlier
/// set's that carry over ([`carried_rows`], flag 1).
fn two_frames(
    arm: &Arm,
    earlier: &ArmSet,
    readings: &[Reading],
    u: &Uncertainty,
) -> Result<Padded<NX2, NM2>, ArmError> {
    check_shape(arm, readings)?;
    let hull = earlier.cover().hull().ok_or(ArmError::EmptySet)?;
    let here = padded_box(arm);
    let mut x0 = [Interval::ZERO; NX2];
    for (i, v) in x0.iter_mut().enumerate() {
        *v = match i {
            i if i < BASE => {
                let both = here[i].intersection(hull[i]);
                if both.is_empty() {
                    return Err(ArmError::CarriedSetOutsidePrior);
                }
                both
            }
            i if i < NX => here[i],
            i => hull[i - NX + BASE],
        };
    }
    let nominal_here = padded_nominal(arm);
    let point = earlier.points().first().ok_or(ArmError::EmptySet)?.x;
    let nominal = core::array::from_fn(|i| match i.checked_sub(NX) {
        None => nominal_here[i],
        Some(k) => point[BASE + k],
    });
    let flagged = |m: &[Interval; NM], flag: f64| -> [Interval; NM2] {
        core::array::from_fn(|i| m.get(i).copied().unwrap_or(Interval::point(flag)))
    };
    let mut boxes: Vec<[Interval; NM2]> = readings
        .iter()
        .map(|r| measurement_box(r, u).map(|m| flagged(&m, 0.0)))
        .collect::<Option<_>>()
        .ok_or(ArmError::TooManyJointReadings)?;
    let stored = earlier.measurements();
    boxes.extend(
        carried_rows(earlier)
            .iter()
            .map(|&k| flagged(&stored[k], 1.0)),
    );
    let joints = arm.joints.len();
    let units: Vec<Unit> = params::names(joints).into_iter().map(|(_, u)| u).collect();
    Ok(Padded {
        x0,
        nominal,
        boxes,
        index: padded_index(joints),
        units,
    })
}

/// The identifiability findings in the arm's `params` parameters (the outcome's): the earlier
/// frame's base and tool (the two-frame model's parameters after the arm's, which the outcome
/// does not show) left out of each combination, a combination of them alone dropped.
fn in_this_frame(id: &mut Identifiability, params: usize) {
    for list in [&mut id.undetermined, &mut id.weak] {
        for c in list.iter_mut() {
            c.members.retain(|&(j, _)| j < params);
        }
        list.retain(|c| !c.members.is_empty());
    }
}

/// The set in this frame of a two-frame cover (module documentation): its boxes without the
/// earlier frame's parameters, over the new rows `here` (their frame flag dropped), the outliers
/// each box tolerated among them kept; `None` when empty.
fn this_frame(certified: &Cover<NX2>, here: &[[Interval; NM2]]) -> Option<ArmSet> {
    let n = here.len();
    let (mut projected, points) = point_model_cover(certified);
    for d in &mut projected.dropped {
        d.retain(|&k| k < n);
    }
    let boxes: Vec<[Interval; NM]> = here
        .iter()
        .map(|m| core::array::from_fn(|i| m[i]))
        .collect();
    let set = ArmSet::new(&Arm7Point, &projected, &boxes, &points, ARM_PIECES);
    (!set.is_empty()).then_some(set)
}

/// The `[carried_set]` table `arm register` ends a registered file with: `set`, the certified
/// set of the robot file `from` (in the tracker frame it was certified in), after a comment that
/// says what it is and who reads it.
pub fn carried_set_toml(from: &Path, set: &StoredSet) -> String {
    format!(
        "\n# [carried_set]: the certified set of {}, in the tracker frame it was certified in (its \
         base and\n# tool are that frame's): `arm certify` joins its rows to the new ones; \
         `accuracy` and `predict` do not read it.{}",
        from.display(),
        set.to_toml("carried_set")
    )
}
