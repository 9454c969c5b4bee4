//! [`Jet2`]: second-order forward-mode derivatives with a symmetric Hessian, for the curvature
//! of a residual ([`crate::proof::second_order`]).
//!
//! A jet of jets (`Jet<Jet<S, G>, G>`) also carries second derivatives, but stores and computes
//! all `G²` entries `∂²f/∂z_a∂z_b` although `∂²f/∂z_a∂z_b = ∂²f/∂z_b∂z_a`. This type keeps the
//! `P = G (G + 1) / 2` entries with `a <= b` (row-major upper triangle): about half the memory
//! and half the operations. Every operation applies the exact second-order rule of its derivative
//! with the operations of `S`:
//!
//! * product: `(uv)_ab = u_ab v + u v_ab + u_a v_b + u_b v_a`;
//! * quotient `q = u / v` from `u = q v`: `q_a = (u_a − q v_a) / v`,
//!   `q_ab = (u_ab − q_a v_b − q_b v_a − q v_ab) / v`;
//! * a unary function `f`: `f(u)_a = f'(u) u_a`, `f(u)_ab = f'(u) u_ab + f''(u) u_a u_b`.
//!
//! When `S` encloses ([`crate::Interval`], or a [`crate::Jet`] of intervals), each entry
//! encloses the exact derivative over the inputs' box, as an evaluation in `S` of the exact
//! derivative's formula.

use crate::Scalar;
use core::ops::{Add, Div, Mul, Neg, Sub};

/// A value of `S`, its `G` first derivatives and its `P = G (G + 1) / 2` distinct second
/// derivatives (module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jet2<S, const G: usize, const P: usize> {
    /// The value.
    pub value: S,
    /// `∂f/∂z_a`.
    pub grad: [S; G],
    /// `∂²f/∂z_a∂z_b` for `a <= b`, row-major (see [`Jet2::second`]).
    pub hess: [S; P],
}

impl<S: Scalar, const G: usize, const P: usize> Jet2<S, G, P> {
    /// A constant (zero derivatives).
    pub fn constant(value: S) -> Self {
        const { assert!(P == G * (G + 1) / 2, "P must be G (G + 1) / 2") };
        Jet2 {
            value,
            grad: [S::cst(0.0); G],
            hess: [S::cst(0.0); P],
        }
    }

    /// The `a`-th seed with value `value` (gradient `e_a`, Hessian 0).
    ///
    /// # Panics
    /// If `a >= G`.
    pub fn variable(value: S, a: usize) -> Self {
        let mut v = Self::constant(value);
        v.grad[a] = S::cst(1.0);
        v
    }

    /// `∂²f/∂z_a∂z_b` (either order).
    ///
    /// # Panics
    /// If `a >= G` or `b >= G`.
    pub fn second(&self, a: usize, b: usize) -> S {
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        assert!(b < G, "symbol {b} of {G}");
        self.hess[a * (2 * G - a + 1) / 2 + (b - a)]
    }

    /// Calls `f(k, u_a v_b)` for the entries `k` in storage order.
    fn outer(u: &[S; G], v: &[S; G], mut f: impl FnMut(usize, S)) {
        let mut k = 0;
        for a in 0..G {
            for b in a..G {
                f(k, u[a] * v[b]);
                k += 1;
            }
        }
    }

    /// The chain rule for a unary function with value `f`, first derivative `df` and second
    /// derivative `d2f` at `self.value`.
    fn chain(self, f: S, df: S, d2f: S) -> Self {
        let mut hess = self.hess.map(|h| df * h);
        let mut k = 0;
        for a in 0..G {
            hess[k] = hess[k] + d2f * self.grad[a].sqr();
            k += 1;
            for b in a + 1..G {
                hess[k] = hess[k] + d2f * (self.grad[a] * self.grad[b]);
                k += 1;
            }
        }
        Jet2 {
            value: f,
            grad: self.grad.map(|g| df * g),
            hess,
        }
    }
}

impl<S: Scalar, const G: usize, const P: usize> Add for Jet2<S, G, P> {
    type Output = Self;
    fn add(self, r: Self) -> Self {
        Jet2 {
            value: self.value + r.value,
            grad: core::array::from_fn(|i| self.grad[i] + r.grad[i]),
            hess: core::array::from_fn(|i| self.hess[i] + r.hess[i]),
        }
    }
}

impl<S: Scalar, const G: usize, const P: usize> Sub for Jet2<S, G, P> {
    type Output = Self;
    fn sub(self, r: Self) -> Self {
        Jet2 {
            value: self.value - r.value,
            grad: core::array::from_fn(|i| self.grad[i] - r.grad[i]),
            hess: core::array::from_fn(|i| self.hess[i] - r.hess[i]),
        }
    }
}

impl<S: Scalar, const G: usize, const P: usize> Neg for Jet2<S, G, P> {
    type Output = Self;
    fn neg(self) -> Self {
        Jet2 {
            value: -self.value,
            grad: self.grad.map(|g| -g),
            hess: self.hess.map(|h| -h),
        }
    }
}

// The product and quotient rules mix operations by nature.
#[allow(clippy::suspicious_arithmetic_impl)]
impl<S: Scalar, const G: usize, const P: usize> Mul for Jet2<S, G, P> {
    type Output = Self;
    fn mul(self, r: Self) -> Self {
        let mut hess: [S; P] =
            core::array::from_fn(|k| self.hess[k] * r.value + self.value * r.hess[k]);
        Self::outer(&self.grad, &r.grad, |k, p| hess[k] = hess[k] + p);
        Self::outer(&r.grad, &self.grad, |k, p| hess[k] = hess[k] + p);
        Jet2 {
            value: self.value * r.value,
            grad: core::array::from_fn(|i| self.grad[i] * r.value + self.value * r.grad[i]),
            hess,
        }
    }
}

#[allow(clippy::suspicious_arithmetic_impl)]
impl<S: Scalar, const G: usize, const P: usize> Div for Jet2<S, G, P> {
    type Output = Self;
    fn div(self, r: Self) -> Self {
        let q = self.value / r.value;
        let grad: [S; G] = core::array::from_fn(|i| (self.grad[i] - q * r.grad[i]) / r.value);
        let mut hess: [S; P] = core::array::from_fn(|k| self.hess[k] - q * r.hess[k]);
        Self::outer(&grad, &r.grad, |k, p| hess[k] = hess[k] - p);
        Self::outer(&r.grad, &grad, |k, p| hess[k] = hess[k] - p);
        Jet2 {
            value: q,
            grad,
            hess: hess.map(|h| h / r.value),
        }
    }
}

impl<S: Scalar, const G: usize, const P: usize> Scalar for Jet2<S, G, P> {
    fn cst(v: f64) -> Self {
        Jet2::constant(S::cst(v))
    }
    fn enclose(nearest: f64, lo: f64, hi: f64) -> Self {
        Jet2::constant(S::enclose(nearest, lo, hi))
    }
    fn sqr(self) -> Self {
        let u = self.value;
        self.chain(u.sqr(), S::cst(2.0) * u, S::cst(2.0))
    }
    fn powi(self, n: i32) -> Self {
        let u = self.value;
        let df = match n {
            0 => S::cst(0.0),
            _ => S::cst(f64::from(n)) * u.powi(n - 1),
        };
        let d2f = match n {
            0 | 1 => S::cst(0.0),
            _ => S::cst(f64::from(n) * f64::from(n - 1)) * u.powi(n - 2),
        };
        self.chain(u.powi(n), df, d2f)
    }
    fn sqrt(self) -> Self {
        let s = self.value.sqrt();
        // f' = 1 / (2 √u), f'' = −1 / (4 √u³) = −2 f'³.
        let df = S::cst(1.0) / (S::cst(2.0) * s);
        let d2f = -(S::cst(2.0) * df * df * df);
        self.chain(s, df, d2f)
    }
    fn sin(self) -> Self {
        let (s, c) = (self.value.sin(), self.value.cos());
        self.chain(s, c, -s)
    }
    fn cos(self) -> Self {
        let (s, c) = (self.value.sin(), self.value.cos());
        self.chain(c, -s, -c)
    }
    fn tan(self) -> Self {
        let t = self.value.tan();
        let df = S::cst(1.0) + t.sqr();
        self.chain(t, df, S::cst(2.0) * t * df)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Interval, Jet};

    /// Every operation of the trait: [`Jet`]'s test function, and the powers whose second
    /// derivatives are special cases.
    fn f<S: Scalar>(x: [S; 3]) -> S {
        let [a, b, r] = x;
        crate::num::jet::tests::f(x) + a.powi(2) * b.powi(1) * r.powi(0) - (S::cst(2.0) - r) * a
    }

    type Nested<S> = Jet<Jet<S, 3>, 3>;

    fn nested<S: Scalar>(x: [S; 3]) -> [Nested<S>; 3] {
        core::array::from_fn(|i| {
            let mut grad = [Jet::constant(S::cst(0.0)); 3];
            grad[i] = Jet::constant(S::cst(1.0));
            Jet {
                value: Jet::variable(x[i], i),
                grad,
            }
        })
    }

    #[test]
    fn second_derivatives_match_the_jet_of_jets() {
        for s in 0..200 {
            let t = |k: usize| ((s * (k + 3) * 7919) % 997) as f64 / 997.0;
            let p = [-1.0 + 2.0 * t(0), -1.2 + 2.5 * t(1), 0.2 + 2.0 * t(2)];
            let h = f(core::array::from_fn(|i| {
                Jet2::<f64, 3, 6>::variable(p[i], i)
            }));
            let n = f(nested(p));
            let close = |x: f64, y: f64| (x - y).abs() <= 1e-12 * (1.0 + y.abs());
            assert!(close(h.value, n.value.value));
            for a in 0..3 {
                assert!(close(h.grad[a], n.value.grad[a]), "point {s} grad {a}");
                for b in 0..3 {
                    let (x, y) = (h.second(a, b), n.grad[a].grad[b]);
                    assert!(close(x, y), "point {s} ({a}, {b}): {x} against {y}");
                }
            }
        }
    }

    #[test]
    fn interval_second_derivatives_enclose_the_points_of_their_box() {
        let b = [
            Interval::new(0.3, 0.35),
            Interval::new(-1.2, -1.1),
            Interval::new(2.0, 2.5),
        ];
        let h = f(core::array::from_fn(|i| {
            Jet2::<Interval, 3, 6>::variable(b[i], i)
        }));
        for s in 0..=300 {
            let p: [f64; 3] = core::array::from_fn(|k| {
                let t = ((s * (k + 3) * 7919) % 301) as f64 / 300.0;
                b[k].inf() + t * (b[k].sup() - b[k].inf())
            });
            let d = f(core::array::from_fn(|i| {
                Jet2::<f64, 3, 6>::variable(p[i], i)
            }));
            // The f64 evaluation rounds to nearest: allow its rounding error.
            let near = |v: f64| Interval::new(v - 1e-12, v + 1e-12);
            assert!(!h.value.intersection(near(d.value)).is_empty());
            for a in 0..3 {
                assert!(!h.grad[a].intersection(near(d.grad[a])).is_empty());
                for c in a..3 {
                    let (hi, di) = (h.second(a, c), d.second(a, c));
                    assert!(
                        !hi.intersection(near(di)).is_empty(),
                        "({a}, {c}): {di} outside {hi}"
                    );
                }
            }
        }
    }
}
