//! The leg functions the accuracy certificate encloses, written once under
//! `#[interval_model]` (point, interval and Jacobian evaluators at compile time).
//!
//! Poses are `X = (p, q)`: the platform centre and the Rodrigues (Gibbs) vector
//! `q = axis · tan(angle / 2)` with `(1 + |q|²) R(q)` the matrix of the paper's Section III.

use calib_core::{interval_model, Scalar};

/// The leg-length error of one leg at a pose: `L(X; θ) - L(X; θ̂)` with
/// `L(X; θ) = ||p + R(q) b - a|| - l` (paper eq. 3). `x = θ = (a, b, l)`, `m = (p, q, θ̂)`.
///
/// Written as `(2 n·Δ + |Δ|²) / (|n + Δ| + |n|) - (l - l̂)` with `n = p + R b̂ - â` and
/// `Δ = R (b - b̂) - (a - â)`: the difference of two nearly equal lengths without cancellation, so
/// that its enclosure over a box of poses stays relative to the small `Δ`.
#[interval_model]
pub fn leg_length_error<S: Scalar>(x: &[S; 7], m: &[S; 13]) -> S {
    let [ax, ay, az, bx, by, bz, l] = *x;
    let [px, py, pz, q1, q2, q3, nax, nay, naz, nbx, nby, nbz, nl] = *m;
    let (s1, s2, s3) = (q1.sqr(), q2.sqr(), q3.sqr());
    let d = 1.0 + s1 + s2 + s3;
    let (r11, r12, r13) = (
        1.0 + s1 - s2 - s3,
        2.0 * (q1 * q2 - q3),
        2.0 * (q1 * q3 + q2),
    );
    let (r21, r22, r23) = (
        2.0 * (q1 * q2 + q3),
        1.0 - s1 + s2 - s3,
        2.0 * (q2 * q3 - q1),
    );
    let (r31, r32, r33) = (
        2.0 * (q1 * q3 - q2),
        2.0 * (q2 * q3 + q1),
        1.0 - s1 - s2 + s3,
    );
    let n1 = px + (r11 * nbx + r12 * nby + r13 * nbz) / d - nax;
    let n2 = py + (r21 * nbx + r22 * nby + r23 * nbz) / d - nay;
    let n3 = pz + (r31 * nbx + r32 * nby + r33 * nbz) / d - naz;
    let (gx, gy, gz) = (bx - nbx, by - nby, bz - nbz);
    let d1 = (r11 * gx + r12 * gy + r13 * gz) / d - (ax - nax);
    let d2 = (r21 * gx + r22 * gy + r23 * gz) / d - (ay - nay);
    let d3 = (r31 * gx + r32 * gy + r33 * gz) / d - (az - naz);
    let num = 2.0 * (n1 * d1 + n2 * d2 + n3 * d3) + d1.sqr() + d2.sqr() + d3.sqr();
    let den = ((n1 + d1).sqr() + (n2 + d2).sqr() + (n3 + d3).sqr()).sqrt()
        + (n1.sqr() + n2.sqr() + n3.sqr()).sqrt();
    num / den - (l - nl)
}

/// The reading of one leg at a pose, `L(X; θ) = ||p + R(q) b - a|| - l` (paper eq. 3):
/// `x = θ = (a, b, l)`, `m = (p, q)`.
#[interval_model]
pub fn leg_reading<S: Scalar>(x: &[S; 7], m: &[S; 6]) -> S {
    let [ax, ay, az, bx, by, bz, l] = *x;
    let [px, py, pz, q1, q2, q3] = *m;
    let (s1, s2, s3) = (q1.sqr(), q2.sqr(), q3.sqr());
    let d = 1.0 + s1 + s2 + s3;
    let e1 = px
        + ((1.0 + s1 - s2 - s3) * bx + 2.0 * (q1 * q2 - q3) * by + 2.0 * (q1 * q3 + q2) * bz) / d
        - ax;
    let e2 = py
        + (2.0 * (q1 * q2 + q3) * bx + (1.0 - s1 + s2 - s3) * by + 2.0 * (q2 * q3 - q1) * bz) / d
        - ay;
    let e3 = pz
        + (2.0 * (q1 * q3 - q2) * bx + 2.0 * (q2 * q3 + q1) * by + (1.0 - s1 - s2 + s3) * bz) / d
        - az;
    (e1.sqr() + e2.sqr() + e3.sqr()).sqrt() - l
}

/// A bound of the curvature term of a leg's reading in its geometry: with `v = p + R(q) b̂ - â`,
/// `û = v / |v|` and `d = R(q) δb - δa` (`δ = θ - θ̂`),
/// `|v + d| - |v| - û·d = |û × d|² / (|v + d| + |v| + û·d)`-like and lies in
/// `[0, |û × d|² / (2 (|v| - |d|))]` when `|d| < |v|` (with `a = |v| + û·d >= |v| - |d| > 0`,
/// `|v + d|² = a² + |û × d|²` and `√(a² + c) <= a + c / 2a`; the lower end is Cauchy–Schwarz).
/// This function is that upper end: `x = δ = (δa, δb, δl)`, `m = (p, q, θ̂)`. So
/// `ΔL = ∇_θ L(X; θ̂)·δ + r` with `0 <= r <=` it, exactly.
#[interval_model]
pub fn leg_curvature<S: Scalar>(x: &[S; 7], m: &[S; 13]) -> S {
    let [da1, da2, da3, db1, db2, db3, _dl] = *x;
    let [px, py, pz, q1, q2, q3, ax, ay, az, bx, by, bz, _l] = *m;
    let (s1, s2, s3) = (q1.sqr(), q2.sqr(), q3.sqr());
    let d = 1.0 + s1 + s2 + s3;
    let (r11, r12, r13) = (
        (1.0 + s1 - s2 - s3) / d,
        2.0 * (q1 * q2 - q3) / d,
        2.0 * (q1 * q3 + q2) / d,
    );
    let (r21, r22, r23) = (
        2.0 * (q1 * q2 + q3) / d,
        (1.0 - s1 + s2 - s3) / d,
        2.0 * (q2 * q3 - q1) / d,
    );
    let (r31, r32, r33) = (
        2.0 * (q1 * q3 - q2) / d,
        2.0 * (q2 * q3 + q1) / d,
        (1.0 - s1 - s2 + s3) / d,
    );
    let v1 = px + r11 * bx + r12 * by + r13 * bz - ax;
    let v2 = py + r21 * bx + r22 * by + r23 * bz - ay;
    let v3 = pz + r31 * bx + r32 * by + r33 * bz - az;
    let n = (v1.sqr() + v2.sqr() + v3.sqr()).sqrt();
    let (u1, u2, u3) = (v1 / n, v2 / n, v3 / n);
    let e1 = r11 * db1 + r12 * db2 + r13 * db3 - da1;
    let e2 = r21 * db1 + r22 * db2 + r23 * db3 - da2;
    let e3 = r31 * db1 + r32 * db2 + r33 * db3 - da3;
    let c1 = u2 * e3 - u3 * e2;
    let c2 = u3 * e1 - u1 * e3;
    let c3 = u1 * e2 - u2 * e1;
    let size = (e1.sqr() + e2.sqr() + e3.sqr()).sqrt();
    (c1.sqr() + c2.sqr() + c3.sqr()) / (2.0 * (n - size))
}
