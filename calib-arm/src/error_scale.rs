//! `--error-scale auto` for arms: the smallest factor of the uncertainty file's bounds (all of
//! them, the tracker's or the encoders') for which the data are consistent, as a proved bracket
//! ([`calib_pipeline::error_scale`]), each trial a verdict-only certification
//! ([`crate::certification::verdict_only`]).

use crate::certification::verdict_only;
use crate::robot::Arm;
use crate::simulate::{Reading, Uncertainty};
use calib_core::{Interval, Status};
use calib_pipeline::error_scale::{find_error_scale, ErrorScale, ScaleSearch};

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

/// Searches the smallest consistent factor of `which` bounds of `u` for `arm` on `readings`;
/// `on_trial` hears each factor before it is tried (for a progress display).
pub fn search(
    arm: &Arm,
    readings: &[Reading],
    u: &Uncertainty,
    which: ScaleBounds,
    mut on_trial: impl FnMut(f64),
) -> Result<ErrorScale, String> {
    let mut failure = None;
    let found = find_error_scale(&ScaleSearch::default(), |s| {
        on_trial(s);
        match verdict_only(arm, readings, &which.scale(u, s)) {
            Ok(status) => status,
            Err(e) => {
                failure.get_or_insert(e);
                Status::Undecided
            }
        }
    });
    match failure {
        Some(e) => Err(e),
        None => Ok(found),
    }
}

/// The bracket as JSON (the report's `error_scale`): `bounds`, `s_lo`, `s_hi`, `ratio`,
/// `certified_at` (the factor the certification then used), `seconds` and every trial's factor
/// and verdict.
pub fn to_json(
    found: &ErrorScale,
    which: ScaleBounds,
    certified_at: Option<f64>,
    seconds: f64,
) -> serde_json::Value {
    serde_json::json!({
        "bounds": which.name(),
        "s_lo": found.s_lo,
        "s_hi": found.s_hi,
        "ratio": found.ratio(),
        "certified_at": certified_at,
        "certifications": found.trials.len(),
        "seconds": seconds,
        "trials": found.trials.iter().map(|t| serde_json::json!({
            "scale": t.scale,
            "verdict": format!("{:?}", t.status).to_lowercase(),
        })).collect::<Vec<_>>(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_chosen_bounds_scale_and_they_round_up() {
        let u = Uncertainty {
            joint_deg: 0.001,
            pos: 0.05,
        };
        let p = ScaleBounds::Pos.scale(&u, 3.0);
        assert_eq!(p.joint_deg, 0.001);
        assert!(p.pos >= 0.15 && p.pos - 0.15 < 1e-15);
        let j = ScaleBounds::JointDeg.scale(&u, 2.0);
        assert_eq!(j.pos, 0.05);
        assert!(j.joint_deg >= 0.002 && j.joint_deg - 0.002 < 1e-17);
        let a = ScaleBounds::All.scale(&u, 0.1);
        assert!(a.pos >= 0.005 && a.joint_deg >= 0.0001);
        assert_eq!(ScaleBounds::Pos.describe(&u, 2.0), "pos 0.1000 mm");
    }
}
