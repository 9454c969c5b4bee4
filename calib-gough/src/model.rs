//! The leg model of the paper's equation (3) with Rodrigues (Gibbs) parameters.
//!
//! Per leg, `x = (a_x, a_y, a_z, b_x, b_y, b_z, l)` (base attachment point `a` in the base frame,
//! platform attachment point `b` in the platform frame, leg offset `l`), and per configuration
//! `M = (p_x, p_y, p_z, q_1, q_2, q_3, L)` (platform position, Rodrigues vector
//! `q = axis * tan(angle / 2)`, leg sensor reading). The residual is
//!
//! `f(x, M) = ||P + R(q) b - a||^2 - (L + l)^2`
//!
//! with `(1 + |q|^2) R(q)` the matrix of the paper's Section III.

use calib_core::{interval_model, Scalar};

/// Names of the seven leg parameters, in the order of `x`.
pub const PARAMETER_NAMES: [&str; 7] = ["ax", "ay", "az", "bx", "by", "bz", "l"];

/// The residual of one leg in one configuration (paper eq. 3 and the `f` of Section III).
#[interval_model]
pub fn gough_leg<S: Scalar>(x: &[S; 7], m: &[S; 7]) -> S {
    let [ax, ay, az, bx, by, bz, l] = *x;
    let [px, py, pz, q1, q2, q3, len] = *m;
    let (s1, s2, s3) = (q1.sqr(), q2.sqr(), q3.sqr());
    let d = 1.0 + s1 + s2 + s3;
    // Rows of (1 + |q|^2) R(q) applied to b.
    let rb1 = (1.0 + s1 - s2 - s3) * bx + 2.0 * (q1 * q2 - q3) * by + 2.0 * (q1 * q3 + q2) * bz;
    let rb2 = 2.0 * (q1 * q2 + q3) * bx + (1.0 - s1 + s2 - s3) * by + 2.0 * (q2 * q3 - q1) * bz;
    let rb3 = 2.0 * (q1 * q3 - q2) * bx + 2.0 * (q2 * q3 + q1) * by + (1.0 - s1 - s2 + s3) * bz;
    let e1 = px + rb1 / d - ax;
    let e2 = py + rb2 / d - ay;
    let e3 = pz + rb3 / d - az;
    e1.sqr() + e2.sqr() + e3.sqr() - (len + l).sqr()
}
