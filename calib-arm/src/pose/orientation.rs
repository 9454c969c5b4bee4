//! Orientations as trackers write them: intrinsic Euler angles `XYZ`, `R = Rx(a) Ry(b) Rz(c)`
//! (Leica's T-Mac in the tracker frame).

use nalgebra::{Rotation3, Vector3};

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
