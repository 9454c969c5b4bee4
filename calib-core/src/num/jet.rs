//! [`Jet`]: forward-mode derivatives carried in any [`Scalar`], so that a residual written once
//! also yields enclosures of its gradient in interval or affine arithmetic.
//!
//! A jet is `value + Σ_i grad[i] dε_i` with `dε_i dε_j = 0`; every operation applies its
//! derivative rule (product, quotient, chain rule) with the operations of `S`. When `S` encloses
//! (an [`crate::Interval`], an [`crate::Affine`] form), each gradient entry encloses the exact
//! derivative over the inputs' box, because it is an evaluation, in `S`, of the exact derivative's
//! formula. With `S = Affine<K>` the derivative keeps its first-order dependence on the `K` noise
//! symbols: over a box of width `w` its range is overestimated by `O(w²)`, not `O(w)` as with
//! intervals — what a bound of the form `Σ_j |∂f/∂θ_j| |Δθ_j|` over a box of configurations needs
//! to converge at the true maximum (the arm's accuracy certificate, `calib_arm::accuracy`).

use crate::Scalar;
use core::ops::{Add, Div, Mul, Neg, Sub};

/// A value of `S` and its derivatives with respect to `G` seeds (module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jet<S, const G: usize> {
    /// The value.
    pub value: S,
    /// The derivatives with respect to the `G` seeds.
    pub grad: [S; G],
}

impl<S: Scalar, const G: usize> Jet<S, G> {
    /// A constant (zero gradient).
    pub fn constant(value: S) -> Self {
        Jet {
            value,
            grad: [S::cst(0.0); G],
        }
    }

    /// The `i`-th seed with value `value` (gradient `e_i`).
    ///
    /// # Panics
    /// If `i >= G`.
    pub fn variable(value: S, i: usize) -> Self {
        let mut grad = [S::cst(0.0); G];
        grad[i] = S::cst(1.0);
        Jet { value, grad }
    }

    /// The chain rule for a unary function with value `f` and derivative `df` at `self.value`.
    fn chain(self, f: S, df: S) -> Self {
        Jet {
            value: f,
            grad: self.grad.map(|g| g * df),
        }
    }
}

impl<S: Scalar, const G: usize> Add for Jet<S, G> {
    type Output = Self;
    fn add(self, r: Self) -> Self {
        Jet {
            value: self.value + r.value,
            grad: core::array::from_fn(|i| self.grad[i] + r.grad[i]),
        }
    }
}

impl<S: Scalar, const G: usize> Sub for Jet<S, G> {
    type Output = Self;
    fn sub(self, r: Self) -> Self {
        Jet {
            value: self.value - r.value,
            grad: core::array::from_fn(|i| self.grad[i] - r.grad[i]),
        }
    }
}

impl<S: Scalar, const G: usize> Neg for Jet<S, G> {
    type Output = Self;
    fn neg(self) -> Self {
        Jet {
            value: -self.value,
            grad: self.grad.map(|g| -g),
        }
    }
}

// The product and quotient rules mix operations by nature.
#[allow(clippy::suspicious_arithmetic_impl)]
impl<S: Scalar, const G: usize> Mul for Jet<S, G> {
    type Output = Self;
    fn mul(self, r: Self) -> Self {
        Jet {
            value: self.value * r.value,
            grad: core::array::from_fn(|i| self.grad[i] * r.value + self.value * r.grad[i]),
        }
    }
}

#[allow(clippy::suspicious_arithmetic_impl)]
impl<S: Scalar, const G: usize> Div for Jet<S, G> {
    type Output = Self;
    /// `(u/v)' = (u' - (u/v) v') / v`: with `q ⊇ u/v`, an enclosure of the exact derivative.
    fn div(self, r: Self) -> Self {
        let q = self.value / r.value;
        Jet {
            value: q,
            grad: core::array::from_fn(|i| (self.grad[i] - q * r.grad[i]) / r.value),
        }
    }
}

impl<S: Scalar, const G: usize> Scalar for Jet<S, G> {
    fn cst(v: f64) -> Self {
        Jet::constant(S::cst(v))
    }
    fn enclose(nearest: f64, lo: f64, hi: f64) -> Self {
        Jet::constant(S::enclose(nearest, lo, hi))
    }
    fn sqr(self) -> Self {
        self.chain(self.value.sqr(), S::cst(2.0) * self.value)
    }
    fn powi(self, n: i32) -> Self {
        let d = if n == 0 {
            S::cst(0.0)
        } else {
            S::cst(f64::from(n)) * self.value.powi(n - 1)
        };
        self.chain(self.value.powi(n), d)
    }
    fn sqrt(self) -> Self {
        let s = self.value.sqrt();
        Jet {
            value: s,
            grad: self.grad.map(|g| g / (S::cst(2.0) * s)),
        }
    }
    fn sin(self) -> Self {
        self.chain(self.value.sin(), self.value.cos())
    }
    fn cos(self) -> Self {
        self.chain(self.value.cos(), -self.value.sin())
    }
    fn tan(self) -> Self {
        let t = self.value.tan();
        self.chain(t, S::cst(1.0) + t.sqr())
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::{Affine, Dual, Interval};

    /// Every operation of the trait, through a rotation chain (the case affine forms are for).
    pub(crate) fn f<S: Scalar>(x: [S; 3]) -> S {
        let [a, b, r] = x;
        let (u, v) = (r * a.cos(), r * a.sin());
        let (w, z) = (u * b.cos() - v * b.sin(), u * b.sin() + v * b.cos());
        w * z / (S::cst(3.0) + r.sqr()) + (r * r + S::cst(1.0)).sqrt() + (a * S::cst(0.3)).tan()
            - b.powi(3)
            + S::enclose(0.1, 0.09999999999999999, 0.1)
    }

    /// A rotation chain with products only (affine arithmetic keeps every correlation).
    fn chain<S: Scalar>(x: [S; 3]) -> S {
        let [a, b, r] = x;
        let (u, v) = (r * a.cos(), r * a.sin());
        let (w, z) = (u * b.cos() - v * b.sin(), u * b.sin() + v * b.cos());
        w * z + w * S::cst(0.5)
    }

    fn seeded<S: Scalar>(x: [S; 3]) -> [Jet<S, 3>; 3] {
        core::array::from_fn(|i| Jet::variable(x[i], i))
    }

    #[test]
    fn gradients_enclose_the_exact_derivatives_in_intervals_and_affine_forms() {
        let boxes = [
            [
                Interval::new(0.3, 0.35),
                Interval::new(-1.2, -1.1),
                Interval::new(2.0, 2.5),
            ],
            [
                Interval::new(-1.0, 1.0),
                Interval::new(0.0, 1.5),
                Interval::new(-1.0, 2.0),
            ],
        ];
        for (n, b) in boxes.iter().enumerate() {
            let iv = f(seeded(*b));
            let inputs: [Affine<3>; 3] = core::array::from_fn(|k| Affine::input(b[k], k));
            let af = f(seeded(inputs));
            for s in 0..=500 {
                let p: [f64; 3] = core::array::from_fn(|k| {
                    let t = ((s * (k + 3) * 7919) % 501) as f64 / 500.0;
                    b[k].inf() + t * (b[k].sup() - b[k].inf())
                });
                let d = f(core::array::from_fn(|i| Dual::<3>::variable(p[i], i)));
                let (iv_value, af_value) = (iv.value, af.value.range());
                assert!(iv_value.contains(d.value) && af_value.contains(d.value));
                for i in 0..3 {
                    let (gi, ga) = (iv.grad[i], af.grad[i].range());
                    // The Dual evaluation rounds to nearest: allow its rounding error.
                    let g = Interval::new(d.grad[i] - 1e-12, d.grad[i] + 1e-12);
                    assert!(
                        !gi.intersection(g).is_empty(),
                        "box {n} grad {i}: {} outside {gi}",
                        d.grad[i]
                    );
                    assert!(
                        !ga.intersection(g).is_empty(),
                        "box {n} grad {i}: {} outside {ga}",
                        d.grad[i]
                    );
                }
            }
        }
    }

    #[test]
    fn affine_gradients_shrink_quadratically_beyond_their_true_variation() {
        // Over a box of width w, the interval gradient's excess over the true range is O(w), the
        // affine one's O(w²): halving w twice divides the affine excess by about 16.
        let excess = |w: f64, affine: bool| {
            let b = [
                Interval::new(0.3, 0.3 + w),
                Interval::new(-1.2, -1.2 + w),
                Interval::point(2.0),
            ];
            let range = if affine {
                let inputs: [Affine<3>; 3] = core::array::from_fn(|k| Affine::input(b[k], k));
                chain(seeded(inputs)).grad[0].range()
            } else {
                chain(seeded(b)).grad[0]
            };
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for s in 0..=40 {
                for t in 0..=40 {
                    let p = [
                        b[0].inf() + w * s as f64 / 40.0,
                        b[1].inf() + w * t as f64 / 40.0,
                        2.0,
                    ];
                    let g = chain(core::array::from_fn(|i| Dual::<3>::variable(p[i], i))).grad[0];
                    (lo, hi) = (lo.min(g), hi.max(g));
                }
            }
            range.wid() - (hi - lo)
        };
        let (a1, a4) = (excess(0.04, true), excess(0.01, true));
        let (i1, i4) = (excess(0.04, false), excess(0.01, false));
        assert!(a1 > 0.0 && a4 > 0.0 && i1 > 0.0 && i4 > 0.0);
        assert!(a1 / a4 > 10.0, "affine excess {a1} -> {a4}");
        assert!(i1 / i4 < 6.0, "interval excess {i1} -> {i4}");
        assert!(a4 < i4 / 10.0, "affine {a4} vs interval {i4}");
    }
}
