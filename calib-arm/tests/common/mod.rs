//! What several test files share: an independent forward kinematics of the arm.

use nalgebra::{Matrix4, Vector4};

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
    let p = t * Vector4::new(b[6], b[7], b[8], 1.0);
    [p[0], p[1], p[2]]
}
