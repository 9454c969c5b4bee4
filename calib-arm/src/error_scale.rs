//! `--error-scale auto` for arms: the smallest factor of the uncertainty file's bounds (all of
//! them, the tracker's or the encoders') for which the data are consistent, as a proved bracket
//! ([`calib_pipeline::error_scale`]), each trial a verdict-only certification
//! ([`crate::certification::verdict_only`]).

use crate::certification::{padded_box, verdict_only, MAX_JOINTS, NM};
use crate::robot::Arm;
use crate::simulate::{measurement_box, Reading, Uncertainty};
use crate::Arm7Point;
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
}

impl ScaleBounds {
    /// `u` with the chosen bounds multiplied by `s` (rounded up).
    pub fn scale(self, u: &Uncertainty, s: f64) -> Uncertainty {
        let times = |v: f64| (Interval::point(v) * Interval::point(s)).sup();
        Uncertainty {
            joint_deg: if self == ScaleBounds::Pos {
                u.joint_deg
            } else {
                times(u.joint_deg)
            },
            pos: if self == ScaleBounds::JointDeg {
                u.pos
            } else {
                times(u.pos)
            },
        }
    }

    /// Which of the padded model's measured quantities ([`crate::certification::NM`]: the joint
    /// readings, then the tracked point) an arm of `joints` joints scales.
    pub fn mask(self, joints: usize) -> [bool; NM] {
        core::array::from_fn(|i| {
            let joint = i < MAX_JOINTS;
            match self {
                ScaleBounds::All => !joint || i < joints,
                ScaleBounds::Pos => !joint,
                ScaleBounds::JointDeg => joint && i < joints,
            }
        })
    }

    /// The name used in the JSON, the messages and the command line.
    pub fn name(self) -> &'static str {
        match self {
            ScaleBounds::All => "all",
            ScaleBounds::Pos => "pos",
            ScaleBounds::JointDeg => "joint_deg",
        }
    }

    /// The bounds scaled by `s`, in words: `pos 0.3851 mm`.
    pub fn describe(self, u: &Uncertainty, s: f64) -> String {
        let b = self.scale(u, s);
        match self {
            ScaleBounds::All => format!("pos {:.4} mm and joints {:.5}°", b.pos, b.joint_deg),
            ScaleBounds::Pos => format!("pos {:.4} mm", b.pos),
            ScaleBounds::JointDeg => format!("joints {:.5}°", b.joint_deg),
        }
    }
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
) -> Result<ErrorScale, String> {
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
