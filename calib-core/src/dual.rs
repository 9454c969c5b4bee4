//! A forward-mode dual number: value and gradient with respect to `N` seeds.
//!
//! Used to cross-check the Jacobians that `#[interval_model]` generates at compile time against an
//! independent evaluation of the same generic residual.

use crate::Scalar;
use core::ops::{Add, Div, Mul, Neg, Sub};

/// `value + sum_i grad[i] * eps_i` with `eps_i * eps_j = 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dual<const N: usize> {
    /// The value.
    pub value: f64,
    /// The derivatives with respect to the `N` seeds.
    pub grad: [f64; N],
}

impl<const N: usize> Dual<N> {
    /// A constant (zero gradient).
    pub fn constant(value: f64) -> Self {
        Dual {
            value,
            grad: [0.0; N],
        }
    }

    /// The `i`-th independent variable with value `value` (gradient `e_i`).
    ///
    /// # Panics
    /// If `i >= N`.
    pub fn variable(value: f64, i: usize) -> Self {
        let mut grad = [0.0; N];
        grad[i] = 1.0;
        Dual { value, grad }
    }

    /// Chain rule for a unary function with value `f` and derivative `df` at `self.value`.
    fn chain(self, f: f64, df: f64) -> Self {
        Dual {
            value: f,
            grad: self.grad.map(|g| g * df),
        }
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    fn add(self, r: Self) -> Self {
        Dual {
            value: self.value + r.value,
            grad: core::array::from_fn(|i| self.grad[i] + r.grad[i]),
        }
    }
}

impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    fn sub(self, r: Self) -> Self {
        Dual {
            value: self.value - r.value,
            grad: core::array::from_fn(|i| self.grad[i] - r.grad[i]),
        }
    }
}

// The product and quotient rules mix operations by nature.
#[allow(clippy::suspicious_arithmetic_impl)]
impl<const N: usize> Mul for Dual<N> {
    type Output = Self;
    fn mul(self, r: Self) -> Self {
        Dual {
            value: self.value * r.value,
            grad: core::array::from_fn(|i| self.grad[i] * r.value + self.value * r.grad[i]),
        }
    }
}

#[allow(clippy::suspicious_arithmetic_impl)]
impl<const N: usize> Div for Dual<N> {
    type Output = Self;
    fn div(self, r: Self) -> Self {
        let q = self.value / r.value;
        Dual {
            value: q,
            grad: core::array::from_fn(|i| (self.grad[i] - q * r.grad[i]) / r.value),
        }
    }
}

impl<const N: usize> Neg for Dual<N> {
    type Output = Self;
    fn neg(self) -> Self {
        self.chain(-self.value, -1.0)
    }
}

impl<const N: usize> Scalar for Dual<N> {
    fn cst(v: f64) -> Self {
        Dual::constant(v)
    }
    fn enclose(nearest: f64, _lo: f64, _hi: f64) -> Self {
        Dual::constant(nearest)
    }
    fn sqr(self) -> Self {
        self.chain(self.value * self.value, 2.0 * self.value)
    }
    fn powi(self, n: i32) -> Self {
        let d = if n == 0 {
            0.0
        } else {
            f64::from(n) * self.value.powi(n - 1)
        };
        self.chain(self.value.powi(n), d)
    }
    fn sqrt(self) -> Self {
        let s = self.value.sqrt();
        self.chain(s, 0.5 / s)
    }
    fn sin(self) -> Self {
        self.chain(self.value.sin(), self.value.cos())
    }
    fn cos(self) -> Self {
        self.chain(self.value.cos(), -self.value.sin())
    }
    fn tan(self) -> Self {
        let t = self.value.tan();
        self.chain(t, 1.0 + t * t)
    }
}
