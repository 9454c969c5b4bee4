//! What several test files share: an independent forward kinematics of the arm.

use nalgebra::{Matrix3, Matrix4, Vector4};

fn rot_x(a: f64) -> Matrix4<f64> {
    let (c, s) = (a.cos(), a.sin());
    Matrix4::new(
        1.0, 0.0, 0.0, 0.0, 0.0, c, -s, 0.0, 0.0, s, c, 0.0, 0.0, 0.0, 0.0, 1.0,
    )
}
fn rot_y(a: f64) -> Matrix4<f64> {
    let (c, s) = (a.cos(), a.sin());
    Matrix4::new(
        c, 0.0, s, 0.0, 0.0, 1.0, 0.0, 0.0, -s, 0.0, c, 0.0, 0.0, 0.0, 0.0, 1.0,
    )
}
fn rot_z(a: f64) -> Matrix4<f64> {
    let (c, s) = (a.cos(), a.sin());
    Matrix4::new(
        c, -s, 0.0, 0.0, s, c, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
    )
}
fn trans(x: f64, y: f64, z: f64) -> Matrix4<f64> {
    Matrix4::new(
        1.0, 0.0, 0.0, x, 0.0, 1.0, 0.0, y, 0.0, 0.0, 1.0, z, 0.0, 0.0, 0.0, 1.0,
    )
}

/// `T_base · Π A_i(q_i) · t` by matrix products (parameters in the model's order, radians).
pub fn forward(x: &[f64], q: &[f64]) -> [f64; 3] {
    let p = flange(x, q)
        * Vector4::new(
            x[5 * q.len() + 6],
            x[5 * q.len() + 7],
            x[5 * q.len() + 8],
            1.0,
        );
    [p[0], p[1], p[2]]
}

/// The tool frame's rotation `R_base · Π A_i(q_i) · R_tool` by matrix products, for the 6-DoF
/// model's parameters (the point model's, then `tool_rx, tool_ry, tool_rz`: `Rz Ry Rx`).
pub fn tool_rotation(x: &[f64], q: &[f64]) -> Matrix3<f64> {
    let t = &x[5 * q.len() + 9..];
    let r = flange(x, q) * rot_z(t[2]) * rot_y(t[1]) * rot_x(t[0]);
    r.fixed_view::<3, 3>(0, 0).into_owned()
}

/// `T_base · Π A_i(q_i)`.
fn flange(x: &[f64], q: &[f64]) -> Matrix4<f64> {
    let n = q.len();
    let b = &x[5 * n..];
    let mut t = trans(b[0], b[1], b[2]) * rot_z(b[5]) * rot_y(b[4]) * rot_x(b[3]);
    for i in 0..n {
        let [th, d, a, al, be] = [
            x[5 * i],
            x[5 * i + 1],
            x[5 * i + 2],
            x[5 * i + 3],
            x[5 * i + 4],
        ];
        t = t * rot_z(th + q[i]) * trans(0.0, 0.0, d) * trans(a, 0.0, 0.0) * rot_x(al) * rot_y(be);
    }
    t
}
