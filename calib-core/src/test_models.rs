//! Small models shared by the unit tests.

use crate::{Interval, Model};

/// `m0 x0 + m1 x1 - m2`: a plane whose coefficients are measured quantities and whose value `m2`
/// is known within a bound (a line `y = x0 t + x1 s` through measured points). Linear in `x`: its
/// linearisation is exact.
pub(crate) struct Plane;

impl Model<2, 3> for Plane {
    fn residual(&self, x: &[f64; 2], m: &[f64; 3]) -> f64 {
        m[0] * x[0] + m[1] * x[1] - m[2]
    }
    fn residual_interval(&self, x: &[Interval; 2], m: &[Interval; 3]) -> Interval {
        m[0] * x[0] + m[1] * x[1] - m[2]
    }
    fn jacobian_x(&self, _x: &[f64; 2], m: &[f64; 3]) -> [f64; 2] {
        [m[0], m[1]]
    }
    fn jacobian_m(&self, x: &[f64; 2], _m: &[f64; 3]) -> [f64; 3] {
        [x[0], x[1], -1.0]
    }
    fn jacobian_x_interval(&self, _x: &[Interval; 2], m: &[Interval; 3]) -> [Interval; 2] {
        [m[0], m[1]]
    }
    fn jacobian_m_interval(&self, x: &[Interval; 2], _m: &[Interval; 3]) -> [Interval; 3] {
        [x[0], x[1], Interval::point(-1.0)]
    }
}

/// Parameters of [`Hyperplane`].
pub(crate) const HYPERPLANE_DIM: usize = 20;

/// `Σ_j m_j x_j - m_20`: [`Plane`] in [`HYPERPLANE_DIM`] parameters, more than the small LP
/// engine takes. Linear in `x`.
pub(crate) struct Hyperplane;

impl Model<HYPERPLANE_DIM, { HYPERPLANE_DIM + 1 }> for Hyperplane {
    fn residual(&self, x: &[f64; HYPERPLANE_DIM], m: &[f64; HYPERPLANE_DIM + 1]) -> f64 {
        x.iter().zip(m).map(|(a, b)| a * b).sum::<f64>() - m[HYPERPLANE_DIM]
    }
    fn residual_interval(
        &self,
        x: &[Interval; HYPERPLANE_DIM],
        m: &[Interval; HYPERPLANE_DIM + 1],
    ) -> Interval {
        let mut r = -m[HYPERPLANE_DIM];
        for (a, b) in x.iter().zip(m) {
            r += *a * *b;
        }
        r
    }
    fn jacobian_x(
        &self,
        _x: &[f64; HYPERPLANE_DIM],
        m: &[f64; HYPERPLANE_DIM + 1],
    ) -> [f64; HYPERPLANE_DIM] {
        core::array::from_fn(|j| m[j])
    }
    fn jacobian_m(
        &self,
        x: &[f64; HYPERPLANE_DIM],
        _m: &[f64; HYPERPLANE_DIM + 1],
    ) -> [f64; HYPERPLANE_DIM + 1] {
        core::array::from_fn(|j| if j < HYPERPLANE_DIM { x[j] } else { -1.0 })
    }
    fn jacobian_x_interval(
        &self,
        _x: &[Interval; HYPERPLANE_DIM],
        m: &[Interval; HYPERPLANE_DIM + 1],
    ) -> [Interval; HYPERPLANE_DIM] {
        core::array::from_fn(|j| m[j])
    }
    fn jacobian_m_interval(
        &self,
        x: &[Interval; HYPERPLANE_DIM],
        _m: &[Interval; HYPERPLANE_DIM + 1],
    ) -> [Interval; HYPERPLANE_DIM + 1] {
        core::array::from_fn(|j| {
            if j < HYPERPLANE_DIM {
                x[j]
            } else {
                Interval::point(-1.0)
            }
        })
    }
}
