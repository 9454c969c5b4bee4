//! [`Quadratic`]: rigorous second-order Taylor models, a [`Scalar`] that keeps the quadratic
//! terms of a function exactly where affine forms must box them.
//!
//! An affine form ([`crate::Affine`]) turns every nonlinear term into an error radius of its own:
//! two quantities whose quadratic parts are equal (the legs of a hexapod all lengthen by
//! `|d|² / 2L` when the platform moves sideways by `d`) then carry two independent errors, and a
//! linear combination that would cancel them (the inverse Jacobian mapping leg changes back to
//! moves) adds them instead. A quadratic model
//!
//! `x̂ = c + Σ_k l_k ε_k + Σ_{k <= j} q_kj ε_k ε_j + e·ε*`,  `ε_k, ε* ∈ [-1, 1]`,
//!
//! keeps those terms as coefficients, so that linear combinations of models cancel them exactly
//! and only third-order terms reach the error radius `e`.
//!
//! - Sums and products by constants are exact on the coefficients.
//! - A product keeps `c_x c_y`, the linear terms `c_x l_y + c_y l_x`, and the quadratic terms
//!   `c_x q_y + c_y q_x + l_x ⊗ l_y`; the terms of degree 3 and 4 are bounded by
//!   `|l_x| |q_y| + |q_x| |l_y| + |q_x| |q_y|` (`|·|` the sum of the coefficients' magnitudes)
//!   and the error radii by `e_x M_y + e_y M_x + e_x e_y` (`M` the magnitude without `e`).
//! - Reciprocals and square roots are expanded to second order about the centre `c`:
//!   `f(c + h) = f(c) + f'(c) h + f''(c)/2 h² + f'''(ξ)/6 h³`, `h = x̂ - c` and `h²` as models,
//!   the Taylor coefficients enclosed by interval arithmetic (their radii times the magnitude of
//!   `h` or `h²` go to `e`) and the Lagrange remainder bounded over the hull of the range and `c`
//!   (`|f'''/6| = t⁻⁴` for `1/t`, `t^(-5/2) / 16` for `√t`); a range holding 0 (reciprocal) or
//!   reaching it (root) falls back to interval arithmetic on the range, as do tangents and powers
//!   other than 1 and 2 (sound, without correlations).
//! - Sines and cosines are expanded the same way (`|f'''/6| <= 1/6` everywhere) where the model
//!   deviates from its centre by at most 1; beyond, they go through interval arithmetic.
//! - Every floating-point rounding of a coefficient is bounded as in [`crate::Affine`]: within one
//!   operation the magnitudes of all rounded results are summed and that sum bounded once
//!   (Higham's `γ_n`), plus the smallest subnormal per operation.
//!
//! **Invariant.** If every input `x_k` of the box is `mid_k + rad_k ε_k`, then for every `ε` in
//! `[-1, 1]^N` the exact value of the quantity lies in `c + l·ε + εᵀ q ε + [-e, e]`, so
//! [`Quadratic::range`] encloses it over the whole box.

use crate::num::affine::{roundings, sum_up};
use crate::num::interval::round::{add_up, mul_up};
use crate::{Interval, Scalar};
use core::ops::{Add, Div, Mul, Neg, Sub};

/// `Σ |v|` over a square array, in four lanes: independent chains of additions that the compiler
/// vectorises (one chain of `N²` dependent additions was a fifth of the paving of the moves).
/// Any order of summation stays within the `γ_n` bound of [`sum_up`] and [`roundings`].
#[inline(always)]
fn abs_sum<const N: usize>(rows: &[[f64; N]; N]) -> f64 {
    let mut lanes = [0.0f64; 4];
    for row in rows {
        for (i, v) in row.iter().enumerate() {
            lanes[i % 4] += v.abs();
        }
    }
    (lanes[0] + lanes[1]) + (lanes[2] + lanes[3])
}

/// The largest deviation `|x̂ - c|` of a model whose sine and cosine are expanded to second order
/// (beyond, the cubic remainder `|h|³/6` outgrows an interval evaluation's width).
const TRIG_TAYLOR_REACH: f64 = 1.0;

/// A second-order Taylor model over `N` noise symbols (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quadratic<const N: usize> {
    c: f64,
    l: [f64; N],
    /// `q[k][j]` for `k <= j`; the entries below the diagonal stay 0.
    q: [[f64; N]; N],
    e: f64,
    /// At least the model's degree: 0 when `l` and `q` are 0, 1 when `q` is (the operations
    /// skip the terms that are known to be 0).
    degree: u8,
}

impl<const N: usize> Quadratic<N> {
    /// The input `x` (a bounded interval) as noise symbol `k`: `mid(x) + rad(x) ε_k`.
    pub fn input(x: Interval, k: usize) -> Self {
        let mut out = Self::from_interval(Interval::ZERO);
        if !x.is_bounded() || x.is_empty() {
            out.e = f64::INFINITY;
            return out;
        }
        out.c = x.mid();
        out.l[k] = x.rad();
        out.degree = 1;
        out
    }

    /// The model `mid(x) ± rad(x)` with no correlation (any interval, possibly unbounded).
    pub fn from_interval(x: Interval) -> Self {
        let (c, e) = if !x.is_bounded() || x.is_empty() {
            (0.0, f64::INFINITY)
        } else {
            (x.mid(), x.rad())
        };
        Quadratic {
            c,
            l: [0.0; N],
            q: [[0.0; N]; N],
            e,
            degree: 0,
        }
    }

    /// The centre `c` (the constant coefficient).
    pub fn centre(&self) -> f64 {
        self.c
    }

    /// The linear coefficients `l_k`.
    pub fn linear(&self) -> &[f64; N] {
        &self.l
    }

    /// The quadratic coefficient `q_kj` of `ε_k ε_j` (`k <= j`; 0 otherwise).
    pub fn quadratic(&self, k: usize, j: usize) -> f64 {
        self.q[k][j]
    }

    /// The model without the linear terms of the noise symbols `symbols` (exact: the removed
    /// part is `Σ_{k ∈ symbols} l_k ε_k`).
    pub fn linear_removed(&self, symbols: core::ops::Range<usize>) -> Self {
        let mut out = *self;
        for k in symbols {
            out.l[k] = 0.0;
        }
        out
    }

    /// The error radius `e` (everything the polynomial does not hold).
    pub fn error(&self) -> f64 {
        self.e
    }

    /// Whether the model is the constant 0 (a shortcut: a model whose terms all vanish without
    /// its degree saying so goes through the general operations, with the same result).
    fn is_zero(&self) -> bool {
        self.degree == 0 && self.c == 0.0 && self.e == 0.0
    }

    /// `Σ |l_k|`, rounded up.
    fn linear_mag(&self) -> f64 {
        if self.degree == 0 {
            return 0.0;
        }
        sum_up(self.l.iter().map(|v| v.abs()).sum(), N)
    }

    /// `Σ_{k <= j} |q_kj|`, rounded up.
    fn quadratic_mag(&self) -> f64 {
        if self.degree < 2 {
            return 0.0;
        }
        // The entries below the diagonal are 0.
        sum_up(abs_sum(&self.q), N * N)
    }

    /// `|c| + Σ |l_k| + Σ |q_kj|`, rounded up: a bound of the polynomial part's magnitude.
    fn poly_mag(&self) -> f64 {
        add_up(
            add_up(self.c.abs(), self.linear_mag()),
            self.quadratic_mag(),
        )
    }

    /// A bound of the magnitude of every value of the model.
    fn mag(&self) -> f64 {
        add_up(self.poly_mag(), self.e)
    }

    /// An interval containing every value of the model: `q_kk ε_k² ∈ [min(0, q_kk), max(0,
    /// q_kk)]`, every other term within its coefficient's magnitude.
    pub fn range(&self) -> Interval {
        let mut off: f64 = self.e + self.l.iter().map(|v| v.abs()).sum::<f64>();
        let mut centre = Interval::point(self.c);
        if !self.c.is_finite() {
            return Interval::ENTIRE;
        }
        for k in (0..N).filter(|_| self.degree == 2) {
            let d = self.q[k][k];
            if d > 0.0 {
                centre += Interval::new(0.0, d);
            } else if d < 0.0 {
                centre += Interval::new(d, 0.0);
            }
            off += self.q[k][k + 1..].iter().map(|v| v.abs()).sum::<f64>();
        }
        let r = sum_up(off, N * N + N + 1);
        if !r.is_finite() || centre.is_empty() || !centre.is_bounded() {
            return Interval::ENTIRE;
        }
        centre + Interval::new(-r, r)
    }

    /// `f(self)` through interval arithmetic on the range (no correlation kept).
    fn through_interval(self, f: impl Fn(Interval) -> Interval) -> Self {
        Quadratic::from_interval(f(self.range()))
    }

    /// `α x̂` with `α` a double.
    fn scale(self, alpha: f64) -> Self {
        let c = alpha * self.c;
        let mut out = Quadratic::from_interval(Interval::ZERO);
        let mut sum = c.abs();
        if self.degree >= 1 {
            out.l = self.l.map(|v| alpha * v);
            sum += out.l.iter().map(|v| v.abs()).sum::<f64>();
        }
        if self.degree == 2 {
            out.q = self.q.map(|r| r.map(|v| alpha * v));
            sum += abs_sum(&out.q);
        }
        out.c = c;
        out.e = add_up(mul_up(alpha.abs(), self.e), roundings(sum, 1 + N + N * N));
        out.degree = self.degree;
        out
    }

    /// `x̂ ŷ` with `ŷ = c_y + e_y ε*` of degree 0: `c_y x̂` plus `e_y` times `x̂`'s magnitude.
    fn times_constant(self, y: Self) -> Self {
        let mut out = self.scale(y.c);
        out.e = add_up(out.e, mul_up(y.e, self.mag()));
        if !out.e.is_finite() || !out.c.is_finite() {
            return Quadratic::from_interval(self.range() * y.range());
        }
        out
    }

    /// `f(x̂)` expanded to second order about the centre `c` (module documentation): `f0 ∋
    /// f(c)`, `f1 ∋ f'(c)`, `f2 ∋ f''(c)/2`, and `m3 >= |f'''/6|` over the hull of the range and
    /// `c`; `None` when a bound is not finite.
    fn taylor(self, f0: Interval, f1: Interval, f2: Interval, m3: f64) -> Option<Self> {
        let mut h = self;
        h.c = 0.0;
        let h2 = h * h;
        let (mh, mh2) = (h.mag(), h2.mag());
        let mut out = Quadratic::from_interval(f0) + h.scale(f1.mid()) + h2.scale(f2.mid());
        let mut e = add_up(mul_up(f1.rad(), mh), mul_up(f2.rad(), mh2));
        e = add_up(e, mul_up(m3, mul_up(mh, mul_up(mh, mh))));
        out.e = add_up(out.e, e);
        (out.e.is_finite() && out.c.is_finite()).then_some(out)
    }

    /// `sin x̂` (or `cos x̂`), expanded to second order about the centre `c` where the model's
    /// deviation `h = x̂ - c` is at most [`TRIG_TAYLOR_REACH`] in magnitude: `sin(c + h) = sin c +
    /// cos c h - sin c h²/2 + R`, `|R| <= |h|³/6` (every third derivative of sin and cos is at
    /// most 1 in magnitude), and likewise for `cos`; wider models go through interval arithmetic
    /// on the range (where that is tighter than the cubic remainder).
    fn sin_cos_taylor(self, cosine: bool) -> Self {
        let f = |x: Interval| if cosine { x.cos() } else { x.sin() };
        let deviation = add_up(add_up(self.linear_mag(), self.quadratic_mag()), self.e);
        if !(self.c.is_finite() && deviation <= TRIG_TAYLOR_REACH) {
            return self.through_interval(f);
        }
        let c = Interval::point(self.c);
        let (s, co) = (c.sin(), c.cos());
        // f(c), f'(c), f''(c)/2.
        let (f0, f1, f2) = if cosine {
            (co, -s, -co * Interval::point(0.5))
        } else {
            (s, co, -s * Interval::point(0.5))
        };
        let m3 = (Interval::point(1.0) / Interval::point(6.0)).sup();
        self.taylor(f0, f1, f2, m3)
            .unwrap_or_else(|| self.through_interval(f))
    }

    /// `1 / x̂`, to second order where the range excludes 0 (else interval division).
    pub fn recip(self) -> Self {
        let r = self.range();
        if r.sup() < 0.0 && self.c < 0.0 {
            return -((-self).recip());
        }
        if !(r.inf() > 0.0 && self.c > 0.0 && r.sup().is_finite()) {
            return self.through_interval(Interval::recip);
        }
        let a = r.inf().min(self.c);
        let f0 = Interval::point(self.c).recip();
        let f1 = -f0.sqr();
        let f2 = f0 * f0.sqr();
        let m3 = Interval::point(a).powi(4).recip().sup();
        self.taylor(f0, f1, f2, m3)
            .unwrap_or_else(|| self.through_interval(Interval::recip))
    }

    /// `√x̂`, to second order where the range is positive (else the interval root).
    fn sqrt_taylor(self) -> Self {
        let r = self.range();
        if !(r.inf() > 0.0 && self.c > 0.0 && r.sup().is_finite()) {
            return self.through_interval(Interval::sqrt);
        }
        let a = Interval::point(r.inf().min(self.c));
        let f0 = Interval::point(self.c).sqrt();
        let f1 = Interval::ONE / (Interval::point(2.0) * f0);
        let f2 = -(Interval::ONE / (Interval::point(8.0) * f0 * f0.sqr()));
        let m3 = (Interval::ONE / (Interval::point(16.0) * a.sqr() * a.sqrt())).sup();
        self.taylor(f0, f1, f2, m3)
            .unwrap_or_else(|| self.through_interval(Interval::sqrt))
    }
}

impl<const N: usize> Add for Quadratic<N> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        if o.is_zero() {
            return self;
        }
        if self.is_zero() {
            return o;
        }
        let degree = self.degree.max(o.degree);
        let c = self.c + o.c;
        let mut sum = c.abs();
        let mut l = [0.0; N];
        for k in (0..N).filter(|_| degree >= 1) {
            l[k] = self.l[k] + o.l[k];
            sum += l[k].abs();
        }
        let mut q = [[0.0; N]; N];
        if degree == 2 {
            // Whole rows (below the diagonal 0 + 0 stays 0): no branch, vectorised.
            for (row, (a, b)) in q.iter_mut().zip(self.q.iter().zip(&o.q)) {
                for (v, (x, y)) in row.iter_mut().zip(a.iter().zip(b)) {
                    *v = x + y;
                }
            }
            sum += abs_sum(&q);
        }
        let e = add_up(add_up(self.e, o.e), roundings(sum, 1 + N + N * N));
        Quadratic { c, l, q, e, degree }
    }
}

impl<const N: usize> Neg for Quadratic<N> {
    type Output = Self;
    fn neg(self) -> Self {
        let mut out = self;
        out.c = -self.c;
        if self.degree >= 1 {
            out.l = self.l.map(|v| -v);
        }
        if self.degree == 2 {
            out.q = self.q.map(|r| r.map(|v| -v));
        }
        out
    }
}

impl<const N: usize> Sub for Quadratic<N> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        self + (-o)
    }
}

impl<const N: usize> Mul for Quadratic<N> {
    type Output = Self;
    /// The terms up to degree 2 kept, those of degree 3 and 4 and the error radii bounded
    /// (module documentation).
    fn mul(self, o: Self) -> Self {
        if self.is_zero() || o.is_zero() {
            return Quadratic::from_interval(Interval::ZERO);
        }
        if o.degree == 0 {
            return self.times_constant(o);
        }
        if self.degree == 0 {
            return o.times_constant(self);
        }
        let c = self.c * o.c;
        // Every rounded result's magnitude, and how many there are.
        let mut sum = c.abs();
        let mut l = [0.0; N];
        for k in 0..N {
            let (p, r) = (self.c * o.l[k], o.c * self.l[k]);
            l[k] = p + r;
            sum += p.abs() + r.abs() + l[k].abs();
        }
        let mut q = [[0.0; N]; N];
        // Per entry, the magnitudes of its rounded results (summed in lanes after the loop:
        // no chain through the loop).
        let mut mags = [[0.0; N]; N];
        for k in 0..N {
            let (p, r) = (self.c * o.q[k][k], o.c * self.q[k][k]);
            let (pr, x) = (p + r, self.l[k] * o.l[k]);
            q[k][k] = pr + x;
            mags[k][k] = p.abs() + r.abs() + pr.abs() + x.abs() + q[k][k].abs();
            // Off the diagonal, without a branch (vectorised over `j`).
            for j in k + 1..N {
                let (p, r) = (self.c * o.q[k][j], o.c * self.q[k][j]);
                let (s, t) = (self.l[k] * o.l[j], self.l[j] * o.l[k]);
                let (pr, st) = (p + r, s + t);
                q[k][j] = pr + st;
                mags[k][j] =
                    p.abs() + r.abs() + pr.abs() + s.abs() + t.abs() + st.abs() + q[k][j].abs();
            }
        }
        sum += abs_sum(&mags);
        let ops = 1 + 3 * N + 7 * N * N;
        let (lx, qx, ly, qy) = (
            self.linear_mag(),
            self.quadratic_mag(),
            o.linear_mag(),
            o.quadratic_mag(),
        );
        let (px, py) = (
            add_up(add_up(self.c.abs(), lx), qx),
            add_up(add_up(o.c.abs(), ly), qy),
        );
        let mut e = add_up(mul_up(lx, qy), mul_up(qx, ly));
        e = add_up(e, mul_up(qx, qy));
        e = add_up(e, mul_up(self.e, py));
        e = add_up(e, mul_up(o.e, px));
        e = add_up(e, mul_up(self.e, o.e));
        e = add_up(e, roundings(sum, ops));
        if !e.is_finite() || !c.is_finite() {
            return Quadratic::from_interval(self.range() * o.range());
        }
        Quadratic {
            c,
            l,
            q,
            e,
            degree: 2,
        }
    }
}

impl<const N: usize> Div for Quadratic<N> {
    type Output = Self;
    /// `x̂ · (1 / ŷ)` ([`Quadratic::recip`]).
    #[allow(clippy::suspicious_arithmetic_impl)] // a quotient is the product with the reciprocal
    fn div(self, o: Self) -> Self {
        if self.is_zero() {
            return self;
        }
        self * o.recip()
    }
}

impl<const N: usize> Scalar for Quadratic<N> {
    fn cst(v: f64) -> Self {
        Quadratic::from_interval(Interval::point(v))
    }
    fn enclose(_nearest: f64, lo: f64, hi: f64) -> Self {
        Quadratic::from_interval(Interval::new(lo, hi))
    }
    fn sqr(self) -> Self {
        self * self
    }
    fn powi(self, n: i32) -> Self {
        match n {
            1 => self,
            2 => self * self,
            _ => self.through_interval(|x| x.powi(n)),
        }
    }
    fn sqrt(self) -> Self {
        self.sqrt_taylor()
    }
    fn sin(self) -> Self {
        self.sin_cos_taylor(false)
    }
    fn cos(self) -> Self {
        self.sin_cos_taylor(true)
    }
    fn tan(self) -> Self {
        self.through_interval(Interval::tan)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Affine;
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    /// A leg-like expression: a square root of a sum of squares, a quotient, products.
    fn leg<S: Scalar>(x: [S; 3]) -> S {
        let [a, b, c] = x;
        let v = (S::cst(60.0) + c).sqr() + (S::cst(7.0) + a).sqr() + b.sqr();
        let w = S::cst(3600.0) + S::cst(49.0);
        (v - w) / (v.sqrt() + w.sqrt()) + a * b * c / (S::cst(2.0) + c.sqr())
    }

    /// A random box: centres in `[-3, 3]`, half-widths from `radius`.
    fn random_box(rng: &mut StdRng, radius: impl Fn(&mut StdRng) -> f64) -> [Interval; 3] {
        core::array::from_fn(|_| {
            let c = rng.random_range(-3.0..3.0);
            let r = radius(rng);
            Interval::new(c - r, c + r)
        })
    }

    /// The model's polynomial at the noise values `eps`, in interval arithmetic, widened by `e`.
    fn at<const N: usize>(x: &Quadratic<N>, eps: &[f64; N]) -> Interval {
        let mut v = Interval::point(x.c);
        for k in 0..N {
            v += Interval::point(x.l[k]) * Interval::point(eps[k]);
            for j in k..N {
                v += Interval::point(x.q[k][j]) * Interval::point(eps[k]) * Interval::point(eps[j]);
            }
        }
        v + Interval::new(-x.e, x.e)
    }

    /// A product with a model of degree 0 that is an interval (a decimal literal's enclosure, a
    /// parameter's box) holds every product of a value of the other model at a point of its noise
    /// symbols and a value of the interval, whichever side the interval is on.
    #[test]
    fn products_with_an_uncertain_constant_hold_every_value() {
        let mut rng = StdRng::seed_from_u64(9);
        for _ in 0..200 {
            let b = random_box(&mut rng, |_| 0.5);
            let x = leg(core::array::from_fn(|k| Quadratic::<3>::input(b[k], k)));
            let lo = rng.random_range(-2.0..2.0);
            let y = Interval::new(lo, lo + rng.random_range(0.0..1.0));
            let cy = Quadratic::<3>::from_interval(y);
            for product in [x * cy, cy * x] {
                for _ in 0..20 {
                    let eps: [f64; 3] = core::array::from_fn(|_| rng.random_range(-1.0..=1.0));
                    let (vx, vp) = (at(&x, &eps), at(&product, &eps));
                    for u in [vx.inf(), vx.sup()] {
                        for t in [y.inf(), y.sup()] {
                            let exact = Interval::point(u) * Interval::point(t);
                            assert!(exact.is_subset_of(vp), "{u} * {t} = {exact} outside {vp}");
                        }
                    }
                }
            }
        }
    }

    /// At random points of random boxes (ends and interior), the exact value — enclosed by
    /// interval arithmetic at the point — meets the model's value at the point's noise symbols,
    /// and lies in the model's range.
    #[test]
    fn quadratic_models_enclose_point_values() {
        let mut rng = StdRng::seed_from_u64(5);
        for _ in 0..200 {
            let b = random_box(&mut rng, |rng| 10f64.powf(rng.random_range(-6.0..0.5)));
            let model = leg(core::array::from_fn(|k| Quadratic::<3>::input(b[k], k)));
            let range = model.range();
            for _ in 0..50 {
                let eps: [f64; 3] = core::array::from_fn(|_| match rng.random_range(0..4) {
                    0 => -1.0,
                    1 => 1.0,
                    _ => rng.random_range(-1.0..=1.0),
                });
                // A point of the box (clamped: mid + rad·eps may round outside it).
                let p: [Interval; 3] = core::array::from_fn(|k| {
                    let v = b[k].mid() + b[k].rad() * eps[k];
                    Interval::point(v.clamp(b[k].inf(), b[k].sup()))
                });
                let exact = leg(p);
                assert!(
                    !exact.intersection(range).is_empty(),
                    "{exact} outside the range {range} on {b:?}"
                );
            }
        }
    }

    /// The model's polynomial, evaluated at the noise symbols of a point, meets that point's
    /// value: the coefficients (not only the range) are right.
    #[test]
    fn coefficients_reproduce_the_function_pointwise() {
        let mut rng = StdRng::seed_from_u64(9);
        for _ in 0..200 {
            let b: [Interval; 3] = core::array::from_fn(|_| {
                let c: f64 = rng.random_range(-2.0..2.0);
                let r: f64 = 10f64.powf(rng.random_range(-4.0..0.0));
                // Binary radii and centres: mid + rad·eps is then exact for dyadic eps.
                let (c, r) = (
                    (c * 1024.0).round() / 1024.0,
                    2f64.powi(r.log2().round() as i32),
                );
                Interval::new(c - r, c + r)
            });
            let model = leg(core::array::from_fn(|k| Quadratic::<3>::input(b[k], k)));
            for _ in 0..50 {
                let eps: [f64; 3] =
                    core::array::from_fn(|_| (rng.random_range(-64i32..=64) as f64) / 64.0);
                let p: [Interval; 3] =
                    core::array::from_fn(|k| Interval::point(b[k].mid() + b[k].rad() * eps[k]));
                let exact = leg(p);
                let value = at(&model, &eps);
                assert!(
                    !exact.intersection(value).is_empty(),
                    "{exact} misses the model's {value} at {eps:?} on {b:?}"
                );
            }
        }
    }

    /// Quadratic terms common to two quantities cancel in their difference, where affine forms
    /// add their errors: `(x + y)² - x² - 2xy - y²` is 0, and `√(1 + x²) - 1 - x²/2` is of
    /// fourth order.
    #[test]
    fn common_quadratic_terms_cancel() {
        let b = [Interval::new(-0.3, 0.5), Interval::new(1.0, 1.4)];
        fn zero<S: Scalar>(x: S, y: S) -> S {
            (x + y).sqr() - x.sqr() - S::cst(2.0) * x * y - y.sqr()
        }
        fn fourth<S: Scalar>(x: S) -> S {
            (S::cst(1.0) + x.sqr()).sqrt() - S::cst(1.0) - x.sqr() * S::cst(0.5)
        }
        let q = zero(Quadratic::<2>::input(b[0], 0), Quadratic::input(b[1], 1)).range();
        let a = zero(Affine::<2>::input(b[0], 0), Affine::input(b[1], 1)).range();
        assert!(q.contains(0.0) && q.wid() < 1e-12, "quadratic {q}");
        assert!(a.wid() > 0.5, "affine {a}");
        let x = Interval::new(-0.1, 0.1);
        let q = fourth(Quadratic::<1>::input(x, 0)).range();
        let a = fourth(Affine::<1>::input(x, 0)).range();
        // The true range is [-x⁴/8, 0] ⊂ [-1.25e-5, 0].
        assert!(q.contains(0.0) && q.contains(-1.24e-5), "quadratic {q}");
        assert!(
            q.wid() < 1e-3 && a.wid() > 5.0 * q.wid(),
            "quadratic {q}, affine {a}"
        );
    }

    /// A rounding the coefficients cannot hold reaches the error radius: `(x + 10¹⁶) - 10¹⁶`
    /// is `x`, though both centres round by units.
    #[test]
    fn roundings_reach_the_error_radius() {
        let x = Interval::new(0.1, 0.3);
        let big = Quadratic::<1>::cst(1e16);
        let m = (Quadratic::<1>::input(x, 0) + big) - big;
        let r = m.range();
        assert!(r.inf() <= 0.1 && r.sup() >= 0.3, "{r}");
        let p = (Quadratic::<1>::input(x, 0) * big) * Quadratic::cst(1e-16);
        assert!(p.range().inf() <= 0.1 && p.range().sup() >= 0.3);
    }

    /// Sines and cosines of models (joint-like angles: a sum and a product of inputs), at random
    /// points of random boxes small and large: the model's polynomial at the point's noise
    /// symbols meets the exact value, and the remainder is of third order on small boxes.
    #[test]
    fn sines_and_cosines_hold_every_value_and_keep_second_order_terms() {
        fn angle<S: Scalar>(x: [S; 2]) -> [S; 2] {
            let t = x[0] + x[1] * S::cst(0.5) + x[0] * x[1];
            [t.sin() * x[1].cos(), t.cos() - x[0].sin()]
        }
        let mut rng = StdRng::seed_from_u64(21);
        for _ in 0..300 {
            let b: [Interval; 2] = core::array::from_fn(|_| {
                let c: f64 = rng.random_range(-3.0..3.0);
                let r: f64 = 10f64.powf(rng.random_range(-4.0..0.3));
                // Binary radii and centres: mid + rad·eps is then exact for dyadic eps.
                let (c, r) = (
                    (c * 1024.0).round() / 1024.0,
                    2f64.powi(r.log2().round() as i32),
                );
                Interval::new(c - r, c + r)
            });
            let model = angle(core::array::from_fn(|k| Quadratic::<2>::input(b[k], k)));
            for _ in 0..40 {
                let eps: [f64; 2] =
                    core::array::from_fn(|_| (rng.random_range(-64i32..=64) as f64) / 64.0);
                let p: [Interval; 2] =
                    core::array::from_fn(|k| Interval::point(b[k].mid() + b[k].rad() * eps[k]));
                let exact = angle(p);
                for r in 0..2 {
                    let value = at(&model[r], &eps);
                    assert!(
                        !exact[r].intersection(value).is_empty(),
                        "row {r}: {} misses the model's {value} at {eps:?} on {b:?}",
                        exact[r]
                    );
                }
            }
        }
        // On a box of half-width h the error radius is O(h³): a tenth of the width, about a
        // thousandth of the radius.
        let radius = |h: f64| {
            let b = [Interval::mid_rad(0.7, h), Interval::mid_rad(-0.4, h)];
            angle(core::array::from_fn(|k| Quadratic::<2>::input(b[k], k)))
                .map(|m| m.error())
                .into_iter()
                .fold(0.0, f64::max)
        };
        let (wide, narrow) = (radius(0.1), radius(0.01));
        assert!(narrow < wide / 300.0, "{wide} then {narrow}");
    }

    /// Reciprocals and roots near the edge of their domain, and ranges holding 0, still enclose.
    #[test]
    fn reciprocals_and_roots_enclose_near_zero_and_fall_back_across_it() {
        for (lo, hi) in [
            (0.01, 2.0),
            (1e-3, 1e-2),
            (-3.0, -0.5),
            (-1.0, 1.0),
            (0.0, 4.0),
        ] {
            let x = Quadratic::<1>::input(Interval::new(lo, hi), 0);
            let (r, s) = (x.recip().range(), x.sqrt().range());
            for k in 0..=100 {
                let t = lo + (hi - lo) * k as f64 / 100.0;
                let (ri, si) = (Interval::point(t).recip(), Interval::point(t).sqrt());
                if t != 0.0 {
                    assert!(!r.intersection(ri).is_empty(), "1/{t} = {ri} outside {r}");
                }
                if t >= 0.0 {
                    assert!(!s.intersection(si).is_empty(), "√{t} = {si} outside {s}");
                }
            }
        }
    }
}
