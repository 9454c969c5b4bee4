//! Six-degree-of-freedom measurements: a tracker's probe that measures the orientation of the
//! tool frame as well as its position (Leica's T-Mac, a 6-DoF probe), six equations per
//! configuration instead of three ([`model`]), certified as positions are ([`certification`]).
//! Around them: the tracker's orientations read ([`crate::tracker_file`]), their Euler angles
//! ([`orientation`]), the tool frame's rotation in the robot file ([`crate::robot::ToolRotation`])
//! and its registration ([`crate::register::register_tool_rotation`]).

pub mod certification;
pub mod model;
pub mod orientation;

pub use model::Arm7Pose;

use crate::certification::{ArmRun, CertifyRequest};
use crate::robot::Arm;
use crate::simulate::{Reading, Uncertainty};
use crate::ArmError;

/// One configuration's 6-DoF measurement: the reading (joints, tracked point) and the measured
/// frame's orientation, intrinsic Euler angles `XYZ` in degrees.
#[derive(Clone, Debug, PartialEq)]
pub struct PoseReading {
    /// Joint readings and tracked point.
    pub reading: Reading,
    /// `a, b, c` of `Rx(a) Ry(b) Rz(c)`, degrees.
    pub euler_xyz_deg: [f64; 3],
}

/// Why `arm` and `u` cannot certify 6-DoF measurements, if they cannot: the robot file `robot`
/// needs the measured frame's rotation on the flange (`[tool] rpy_deg`, `rotation_radius`) and
/// the uncertainty file `uncertainty` the orientations' bound (`orient_deg`).
pub fn require_pose_inputs(
    arm: &Arm,
    robot: &std::path::Path,
    u: &PoseUncertainty,
    uncertainty: &std::path::Path,
) -> Result<(), ArmError> {
    if arm.tool_rotation.is_none() {
        return Err(ArmError::RobotLacksToolRotation(robot.to_path_buf()));
    }
    if u.orient_deg.is_none() {
        return Err(ArmError::UncertaintyLacksOrientBound(
            uncertainty.to_path_buf(),
        ));
    }
    Ok(())
}

/// Certifies `arm` against 6-DoF measurements ([`certification::certify_pose_request`]).
pub fn certify_pose(
    arm: &Arm,
    readings: &[PoseReading],
    u: &PoseUncertainty,
    request: &CertifyRequest,
) -> Result<(usize, ArmRun), ArmError> {
    certification::certify_pose_request(arm, readings, u, request)
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
