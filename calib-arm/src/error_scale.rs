//! `--error-scale auto` for arms: the smallest factor of the uncertainty file's bounds (all of
//! them, the tracker's, the encoders' or, for 6-DoF data, the orientations') for which the data
//! are consistent, as a proved bracket ([`calib_pipeline::error_scale`]), each trial a
//! verdict-only certification ([`crate::certification::verdict_only`]; for 6-DoF data
//! [`crate::pose::certification::verdict_only_pose`]).

use crate::certification::{padded_box, verdict_only, MAX_JOINTS, NM};
use crate::pose::certification::{padded_pose, verdict_only_pose, NM6};
use crate::pose::{Arm7Pose, PoseReading, PoseUncertainty};
use crate::robot::Arm;
use crate::simulate::{measurement_box, Reading, Uncertainty};
use crate::{Arm7Point, ArmError};
use calib_core::Interval;
use calib_pipeline::error_scale::{search_from_estimate, ErrorScale, ScaledProblem};

/// Which error bounds the factor multiplies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ScaleBounds {
    /// Every bound.
    All,
    /// The tracked point's (`pos`).
    Pos,
    /// The joint readings' (`joint_deg`).
    #[value(name = "joint_deg")]
    JointDeg,
    /// The measured orientations' (`orient_deg`; 6-DoF data only).
    #[value(name = "orient_deg")]
    OrientDeg,
}

impl ScaleBounds {
    /// Whether the factor multiplies the tracked point's bound.
    fn scales_pos(self) -> bool {
        matches!(self, ScaleBounds::All | ScaleBounds::Pos)
    }

    /// Whether the factor multiplies the joint readings' bound.
    fn scales_joints(self) -> bool {
        matches!(self, ScaleBounds::All | ScaleBounds::JointDeg)
    }

    /// Whether the factor multiplies the orientations' bound.
    fn scales_orientation(self) -> bool {
        matches!(self, ScaleBounds::All | ScaleBounds::OrientDeg)
    }

    /// `u` with the chosen bounds multiplied by `s` (rounded up).
    pub fn scale(self, u: &Uncertainty, s: f64) -> Uncertainty {
        Uncertainty {
            joint_deg: times_if(self.scales_joints(), u.joint_deg, s),
            pos: times_if(self.scales_pos(), u.pos, s),
        }
    }

    /// 6-DoF bounds `u` with the chosen bounds multiplied by `s` (rounded up).
    pub fn scale_pose(self, u: &PoseUncertainty, s: f64) -> PoseUncertainty {
        PoseUncertainty {
            position: self.scale(&u.position, s),
            orient_deg: u
                .orient_deg
                .map(|o| times_if(self.scales_orientation(), o, s)),
        }
    }

    /// Which of the padded model's measured quantities ([`crate::certification::NM`]: the joint
    /// readings, then the tracked point) an arm of `joints` joints scales.
    pub fn mask(self, joints: usize) -> [bool; NM] {
        core::array::from_fn(|i| {
            if i < MAX_JOINTS {
                self.scales_joints() && i < joints
            } else {
                self.scales_pos()
            }
        })
    }

    /// Which of the padded 6-DoF model's measured quantities
    /// ([`crate::pose::certification::NM6`]: the point model's, then the Euler angles) an arm of
    /// `joints` joints scales.
    pub fn mask_pose(self, joints: usize) -> [bool; NM6] {
        let point = self.mask(joints);
        core::array::from_fn(|i| point.get(i).copied().unwrap_or(self.scales_orientation()))
    }

    /// The name used in the JSON, the messages and the command line.
    pub fn name(self) -> &'static str {
        match self {
            ScaleBounds::All => "all",
            ScaleBounds::Pos => "pos",
            ScaleBounds::JointDeg => "joint_deg",
            ScaleBounds::OrientDeg => "orient_deg",
        }
    }

    /// The bounds scaled by `s`, in words: `pos 0.3851 mm`.
    pub fn describe(self, u: &Uncertainty, s: f64) -> String {
        self.describe_pose(
            &PoseUncertainty {
                position: *u,
                orient_deg: None,
            },
            s,
        )
    }

    /// The 6-DoF bounds scaled by `s`, in words: `pos 0.3851 mm and orientations 0.0500°`.
    pub fn describe_pose(self, u: &PoseUncertainty, s: f64) -> String {
        let b = self.scale_pose(u, s);
        let mut parts = Vec::new();
        if self.scales_pos() {
            parts.push(format!("pos {:.4} mm", b.position.pos));
        }
        if self.scales_joints() {
            parts.push(format!("joints {:.5}°", b.position.joint_deg));
        }
        if let Some(o) = b.orient_deg.filter(|_| self.scales_orientation()) {
            parts.push(format!("orientations {o:.4}°"));
        }
        parts.join(" and ")
    }
}

/// `v × s` rounded up where `scaled`, else `v`.
fn times_if(scaled: bool, v: f64, s: f64) -> f64 {
    if scaled {
        (Interval::point(v) * Interval::point(s)).sup()
    } else {
        v
    }
}

/// The error when `which` scales no bound of these data (orientations without 6-DoF data).
fn check_scaled(which: ScaleBounds, six_dof: bool) -> Result<(), ArmError> {
    if which == ScaleBounds::OrientDeg && !six_dof {
        return Err(ArmError::OrientScaleNeedsPose);
    }
    Ok(())
}

/// Searches the smallest consistent factor of `which` bounds of `u` for `arm` on `readings`
/// ([`calib_pipeline::error_scale::search_from_estimate`]: from the Chebyshev fit, whose point is
/// tried first at every factor, then a verdict-only certification); `on_trial` hears each factor
/// before it is tried (for a progress display).
pub fn search(
    arm: &Arm,
    readings: &[Reading],
    u: &Uncertainty,
    which: ScaleBounds,
    on_trial: impl FnMut(f64),
) -> Result<ErrorScale, ArmError> {
    check_scaled(which, false)?;
    let joints = arm.joints.len();
    if !(3..=MAX_JOINTS).contains(&joints) || readings.iter().any(|r| r.joints_deg.len() != joints)
    {
        // The certification names what is wrong.
        verdict_only(arm, readings, u)?;
    }
    let boxes = |s: f64| -> Vec<[Interval; NM]> {
        let scaled = which.scale(u, s);
        readings
            .iter()
            .filter_map(|r| measurement_box(r, &scaled))
            .collect()
    };
    let problem = ScaledProblem {
        model: &Arm7Point,
        x0: padded_box(arm),
        boxes: &boxes,
        scaled: which.mask(joints),
    };
    search_from_estimate(
        &[problem],
        |_, s| verdict_only(arm, readings, &which.scale(u, s)),
        on_trial,
    )
}

/// [`search`] on 6-DoF measurements: the factor of `which` bounds of `u` (which must give
/// `orient_deg`, and `arm` a tool rotation) for which `arm` fits `readings`' positions and
/// orientations, through [`Arm7Pose`].
pub fn search_pose(
    arm: &Arm,
    readings: &[PoseReading],
    u: &PoseUncertainty,
    which: ScaleBounds,
    on_trial: impl FnMut(f64),
) -> Result<ErrorScale, ArmError> {
    check_scaled(which, true)?;
    let x0 = padded_pose(arm, readings, u)?.x0;
    let boxes = |s: f64| -> Vec<[Interval; NM6]> {
        // The shape was checked by `padded_pose` above: every scaled problem is built.
        padded_pose(arm, readings, &which.scale_pose(u, s)).map_or_else(|_| Vec::new(), |p| p.boxes)
    };
    let problem = ScaledProblem {
        model: &Arm7Pose,
        x0,
        boxes: &boxes,
        scaled: which.mask_pose(arm.joints.len()),
    };
    search_from_estimate(
        &[problem],
        |_, s| verdict_only_pose(arm, readings, &which.scale_pose(u, s)),
        on_trial,
    )
}
