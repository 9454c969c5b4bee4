//! Orientations as trackers write them: intrinsic Euler angles `XYZ`, `R = Rx(a) Ry(b) Rz(c)`
//! (Leica's T-Mac in the tracker frame).

use crate::robot::Arm;
use crate::simulate::Reading;
use crate::vendor::arm_flange;
use nalgebra::{Rotation3, Vector3};

/// The tool frame's rotation on the flange of `rpy_deg` (`[tool] rpy_deg`: `Rz(rz) Ry(ry) Rx(rx)`,
/// degrees).
pub fn tool_rotation(rpy_deg: [f64; 3]) -> Rotation3<f64> {
    let [r, p, y] = rpy_deg.map(f64::to_radians);
    Rotation3::from_euler_angles(r, p, y)
}

/// The angle, degrees, between each measured orientation (intrinsic Euler angles `XYZ`,
/// degrees) and the one `arm` predicts at its joint readings: the flange's rotation (base and
/// joints as `arm` has them) followed by the tool frame's rotation `tool`.
pub fn orientation_errors_deg(
    arm: &Arm,
    tool: &Rotation3<f64>,
    readings: &[Reading],
    euler_xyz_deg: &[[f64; 3]],
) -> Vec<f64> {
    readings
        .iter()
        .zip(euler_xyz_deg)
        .map(|(r, e)| {
            let q: Vec<f64> = r.joints_deg.iter().map(|d| d.to_radians()).collect();
            let flange = arm_flange(arm, &q).rotation.to_rotation_matrix();
            (flange * tool)
                .angle_to(&from_euler_xyz(e.map(f64::to_radians)))
                .to_degrees()
        })
        .collect()
}

/// The rotation of intrinsic Euler angles `XYZ` (radians): `Rx(a) Ry(b) Rz(c)`.
pub fn from_euler_xyz([a, b, c]: [f64; 3]) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&Vector3::x_axis(), a)
        * Rotation3::from_axis_angle(&Vector3::y_axis(), b)
        * Rotation3::from_axis_angle(&Vector3::z_axis(), c)
}

/// The intrinsic Euler angles `XYZ` (radians) of `r`: `b = asin r₀₂ ∈ [-π/2, π/2]`,
/// `a = atan2(-r₁₂, r₂₂)`, `c = atan2(-r₀₁, r₀₀)` (at `b = ±π/2`, gimbal lock, `c = 0`).
pub fn to_euler_xyz(r: &Rotation3<f64>) -> [f64; 3] {
    let m = r.matrix();
    let b = m[(0, 2)].clamp(-1.0, 1.0).asin();
    if m[(0, 2)].abs() > 1.0 - 1e-12 {
        // Rx(a) Ry(±π/2) Rz(c) depends on a ± c only.
        return [m[(1, 0)].atan2(m[(1, 1)]), b, 0.0];
    }
    [
        (-m[(1, 2)]).atan2(m[(2, 2)]),
        b,
        (-m[(0, 1)]).atan2(m[(0, 0)]),
    ]
}
