//! Six-degree-of-freedom measurements: a tracker's probe that measures the orientation of the
//! tool frame as well as its position (Leica's T-Mac, a 6-DoF probe), six equations per
//! configuration instead of three (`model`), certified as positions are (`certification`): both
//! with the crate's feature `six-dof` only — the six-row model's kernel takes ~10 minutes of one
//! core to compile, measured, against 76 s for the whole library without it. Always built: the
//! tracker's orientations read ([`crate::tracker_file`]), their Euler angles ([`orientation`]),
//! the tool frame's rotation in the robot file ([`crate::robot::ToolRotation`]) and its
//! registration ([`crate::register::register_tool_rotation`]).

#[cfg(feature = "six-dof")]
pub mod certification;
#[cfg(feature = "six-dof")]
pub mod model;
pub mod orientation;

#[cfg(feature = "six-dof")]
pub use model::Arm7Pose;

use crate::certification::{ArmRun, CertifyRequest};
use crate::robot::Arm;
use crate::simulate::{Reading, Uncertainty};

/// One configuration's 6-DoF measurement: the reading (joints, tracked point) and the measured
/// frame's orientation, intrinsic Euler angles `XYZ` in degrees.
#[derive(Clone, Debug, PartialEq)]
pub struct PoseReading {
    /// Joint readings and tracked point.
    pub reading: Reading,
    /// `a, b, c` of `Rx(a) Ry(b) Rz(c)`, degrees.
    pub euler_xyz_deg: [f64; 3],
}

/// Certifies `arm` against 6-DoF measurements (`certification::certify_pose_request`, with the
/// feature `six-dof`); without the feature, an error saying how to build it.
pub fn certify_pose(
    arm: &Arm,
    readings: &[PoseReading],
    u: &PoseUncertainty,
    request: &CertifyRequest,
) -> Result<(usize, ArmRun), String> {
    #[cfg(feature = "six-dof")]
    {
        certification::certify_pose_request(arm, readings, u, request)
    }
    #[cfg(not(feature = "six-dof"))]
    {
        let _ = (arm, readings, u, request);
        Err(
            "6-DoF certification (--orientation-columns) is not in this build: build `arm` with \
             `--features six-dof` (e.g. `cargo install --path calib-arm --features six-dof`; the \
             six-row model adds ~10 minutes of compile time)"
                .to_string(),
        )
    }
}

/// The error bounds of 6-DoF measurements: the joint readings' and the tracked point's, and the
/// measured orientation's (`uncertainty.toml`'s `orient_deg`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PoseUncertainty {
    /// Joint readings and tracked point.
    pub position: Uncertainty,
    /// Half-width of each measured Euler angle, degrees (`None`: not given).
    pub orient_deg: Option<f64>,
}
