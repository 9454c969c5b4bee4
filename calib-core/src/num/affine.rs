//! [`Affine`]: rigorous affine arithmetic, a [`Scalar`] that keeps first-order correlations.
//!
//! Natural interval evaluation forgets that two intermediate quantities depend on the same
//! inputs. Through a chain of rotations (a serial arm) this *wrapping effect* makes interval
//! Jacobians 5–40 times wider than their true range, at every box size, and the Newton step of the
//! kernel cannot contract. An affine form
//!
//! `x̂ = c + Σ_i a_i ε_i + e·ε*`,  `ε_i, ε* ∈ [-1, 1]`,
//!
//! carries one noise symbol `ε_i` per input of the box (every parameter and every measured
//! quantity: `N = NX + NM`) and one error radius `e >= 0` that absorbs everything else. Linear
//! operations are exact on the linear part; a product adds the remainder `r_x r_y` (with
//! `r = Σ|a_i| + e`) to `e`; `sin` and `cos` are linearised at the centre `c` with the mean-value
//! remainder `r² + rad(f'(c)) r` (`|f''| <= 1`); reciprocals (hence division) and square roots
//! use the min-range linearisation `α x̂ + ζ ± δ` of Stolfi & de Figueiredo over the form's range
//! `[a, b]` (`1/t` for `0 < a` or `b < 0`; `√t` for `b > 0`), where `ζ ± δ` is a rigorous
//! enclosure of `f(t) - α t` over `[a, b]`; every floating-point rounding of a centre or a
//! coefficient adds a bound of its error (one ulp of the result, plus the smallest subnormal) to
//! `e` — within one operation those bounds are summed in floating point and the sum bounded
//! once (Higham's `γ_n`), which keeps the loop over the coefficients free of branches — and `e`
//! itself is summed with upward rounding. Tangents, powers and reciprocals of forms
//! whose range holds 0 fall back to interval arithmetic on the range (sound, without
//! correlations).
//!
//! **Invariant.** If every input `x_i` of the box is `mid_i + rad_i ε_i`, then for every `ε` in
//! `[-1, 1]^N` the exact real value of the quantity lies in `c + a·ε + [-e, e]`. Hence
//! [`Affine::range`] encloses the quantity over the whole box, and the kernel intersects it with
//! the natural interval evaluation (both are enclosures).

use crate::num::interval::round::{add_up, mul_up};
use crate::{Interval, Scalar};
use core::ops::{Add, Div, Mul, Neg, Sub};

/// An affine form over `N` noise symbols (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Affine<const N: usize> {
    c: f64,
    a: [f64; N],
    e: f64,
}

/// An upper bound of the rounding error of one round-to-nearest operation whose result is `v`.
#[inline(always)]
pub(crate) fn rounding(v: f64) -> f64 {
    mul_up(v.abs(), f64::EPSILON) + f64::from_bits(1)
}

/// An upper bound of the exact sum of `n` nonnegative terms whose floating-point sum (round to
/// nearest, any order) is `s`: `|s - Σ| <= γ_{n-1} Σ` with `γ_k = k u / (1 - k u)` (Higham,
/// *Accuracy and Stability*, §4.2; exact with subnormals, as sums underflow exactly), so
/// `Σ <= s / (1 - γ_{n-1}) <= s (1 + n ε)` for `ε = 2u` and `n ε < 1/2`; the product is rounded
/// up. `+∞` or NaN stays so.
#[inline(always)]
pub(crate) fn sum_up(s: f64, n: usize) -> f64 {
    mul_up(s, 1.0 + n as f64 * f64::EPSILON)
}

/// An upper bound of the rounding errors of `n` round-to-nearest operations whose results `v_k`
/// have `Σ |v_k|` summed to `s` in floating point: `Σ rounding(v_k)` ([`rounding`]) with the
/// sum bounded by [`sum_up`] — one bound for a whole loop, without a branch per term.
#[inline(always)]
pub(crate) fn roundings(s: f64, n: usize) -> f64 {
    add_up(
        mul_up(sum_up(s, n), f64::EPSILON),
        n as f64 * f64::from_bits(1),
    )
}

/// The coefficients `alpha · a_i`, rounded to nearest, and a bound of their rounding errors.
#[inline(always)]
fn scaled<const N: usize>(alpha: f64, a: &[f64; N]) -> ([f64; N], f64) {
    let out = a.map(|v| alpha * v);
    (out, roundings(out.iter().map(|v| v.abs()).sum(), N))
}

impl<const N: usize> Affine<N> {
    /// The input `x` (a bounded interval) as noise symbol `k`: `mid(x) + rad(x) ε_k`.
    pub fn input(x: Interval, k: usize) -> Self {
        let mut a = [0.0; N];
        if !x.is_bounded() || x.is_empty() {
            return Affine {
                c: 0.0,
                a,
                e: f64::INFINITY,
            };
        }
        a[k] = x.rad();
        Affine {
            c: x.mid(),
            a,
            e: 0.0,
        }
    }

    /// The form `mid(x) ± rad(x)` with no correlation (any interval, possibly unbounded).
    pub fn from_interval(x: Interval) -> Self {
        if !x.is_bounded() || x.is_empty() {
            return Affine {
                c: 0.0,
                a: [0.0; N],
                e: f64::INFINITY,
            };
        }
        Affine {
            c: x.mid(),
            a: [0.0; N],
            e: x.rad(),
        }
    }

    /// The centre `c`.
    pub fn centre(&self) -> f64 {
        self.c
    }

    /// The coefficients `a_i` of the noise symbols.
    pub fn coefficients(&self) -> &[f64; N] {
        &self.a
    }

    /// The error radius `e` (everything the linear part does not hold).
    pub fn error(&self) -> f64 {
        self.e
    }

    /// Whether the form is exactly zero (a derivative that does not depend on its seed yet).
    #[inline(always)]
    fn is_zero(&self) -> bool {
        self.c == 0.0 && self.e == 0.0 && self.a.iter().all(|v| *v == 0.0)
    }

    /// `Σ |a_i| + e`, rounded up: the radius of the form.
    pub fn radius(&self) -> f64 {
        sum_up(self.a.iter().fold(self.e, |s, v| s + v.abs()), N + 1)
    }

    /// An interval containing every value of the form.
    pub fn range(&self) -> Interval {
        let r = self.radius();
        if !r.is_finite() || !self.c.is_finite() {
            return Interval::ENTIRE;
        }
        Interval::point(self.c) + Interval::new(-r, r)
    }

    /// `f(self)` through interval arithmetic on the range (no correlation kept).
    fn through_interval(self, f: impl Fn(Interval) -> Interval) -> Self {
        Affine::from_interval(f(self.range()))
    }

    /// The linearisation `f(c) + α (x - c)` of a function with `|f''| <= 1` (sine, cosine), where
    /// `value ⊇ f(c)` and `slope ⊇ f'(c)`.
    fn linearised(self, value: Interval, slope: Interval) -> Self {
        let r = self.radius();
        if !r.is_finite() || !value.is_bounded() || !slope.is_bounded() {
            return Affine::from_interval(Interval::new(-1.0, 1.0));
        }
        let alpha = slope.mid();
        let mut e = value.rad();
        // |f(t) - f(c) - α (t - c)| <= (|f'(ξ) - f'(c)| + |f'(c) - α|) |t - c| <= (r + rad α) r
        e = add_up(e, mul_up(add_up(r, slope.rad()), r));
        e = add_up(e, mul_up(alpha.abs(), self.e));
        let (a, err) = scaled(alpha, &self.a);
        e = add_up(e, err);
        Affine {
            c: value.mid(),
            a,
            e,
        }
    }

    /// `α x̂ + g` with `g ∈ [lo, hi]`: the min-range linearisation of a function `f` whose
    /// `f(t) - α t` lies in `[lo, hi]` over the form's range (see [`Affine::recip`] and the
    /// square root). `None` when an input is not finite.
    fn min_range(self, alpha: f64, lo: f64, hi: f64) -> Option<Self> {
        if !(alpha.is_finite() && lo.is_finite() && hi.is_finite() && lo <= hi) {
            return None;
        }
        let z = lo + 0.5 * (hi - lo);
        // |g - z| over g in [lo, hi], rounded up.
        let spread = (Interval::point(hi) - Interval::point(z))
            .sup()
            .max((Interval::point(z) - Interval::point(lo)).sup());
        let ac = alpha * self.c;
        let c = ac + z;
        let mut e = add_up(mul_up(alpha.abs(), self.e), spread);
        e = add_up(e, add_up(rounding(ac), rounding(c)));
        let (a, err) = scaled(alpha, &self.a);
        e = add_up(e, err);
        (e.is_finite() && c.is_finite()).then_some(Affine { c, a, e })
    }

    /// `1 / x̂`. Over a range `[a, b]` with `0 < a`: `α = -1/b²` and `g(t) = 1/t - α t`, convex,
    /// is largest at `a` or `b` and at least `2 √(-α)` (arithmetic–geometric mean); a negative
    /// range is reflected; a range holding 0 falls back to interval division.
    pub fn recip(self) -> Self {
        let r = self.range();
        if r.sup() < 0.0 {
            return -((-self).recip());
        }
        let fallback = || Affine::from_interval(r.recip());
        if !(r.inf() > 0.0 && r.sup().is_finite()) {
            return fallback();
        }
        let (a, b) = (r.inf(), r.sup());
        let alpha = -1.0 / (b * b);
        // b² overflowing or underflowing leaves nothing to linearise.
        if alpha == 0.0 || !alpha.is_finite() {
            return fallback();
        }
        let al = Interval::point(alpha);
        let g = |t: f64| Interval::point(t).recip() - al * Interval::point(t);
        let hi = g(a).sup().max(g(b).sup());
        let lo = (Interval::point(2.0) * (-al).sqrt()).inf();
        self.min_range(alpha, lo, hi).unwrap_or_else(fallback)
    }

    /// `√x̂` over the form's range `[a, b]` (its negative part outside the domain): `α =
    /// 1/(2√b)` and `g(t) = √t - α t`, concave, is smallest at `max(a, 0)` or `b` and at most
    /// `1/(4α)` (arithmetic–geometric mean: `α t + 1/(4α) >= √t`).
    fn sqrt_min_range(self) -> Self {
        let r = self.range();
        let fallback = || Affine::from_interval(r.sqrt());
        let (a, b) = (r.inf().max(0.0), r.sup());
        if !(b > 0.0 && b.is_finite()) {
            return fallback();
        }
        let alpha = 0.5 / b.sqrt();
        if !(alpha > 0.0 && alpha.is_finite()) {
            return fallback();
        }
        let al = Interval::point(alpha);
        let g = |t: f64| Interval::point(t).sqrt() - al * Interval::point(t);
        let lo = g(a).inf().min(g(b).inf());
        let hi = (Interval::ONE / (Interval::point(4.0) * al)).sup();
        self.min_range(alpha, lo, hi).unwrap_or_else(fallback)
    }
}

impl<const N: usize> Add for Affine<N> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        // x + 0 = x exactly (a derivative not yet reached by its seed costs nothing).
        if o.is_zero() {
            return self;
        }
        if self.is_zero() {
            return o;
        }
        let c = self.c + o.c;
        let mut a = [0.0; N];
        let mut sum = c.abs();
        for i in 0..N {
            a[i] = self.a[i] + o.a[i];
            sum += a[i].abs();
        }
        let e = add_up(add_up(self.e, o.e), roundings(sum, N + 1));
        Affine { c, a, e }
    }
}

impl<const N: usize> Neg for Affine<N> {
    type Output = Self;
    fn neg(self) -> Self {
        Affine {
            c: -self.c,
            a: self.a.map(|v| -v),
            e: self.e,
        }
    }
}

impl<const N: usize> Sub for Affine<N> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        self + (-o)
    }
}

impl<const N: usize> Mul for Affine<N> {
    type Output = Self;
    /// `c_x c_y + c_x L_y + c_y L_x` plus the remainder `|c_x| e_y + |c_y| e_x + r_x r_y`.
    fn mul(self, o: Self) -> Self {
        // x · 0 = 0 exactly, even for an unbounded x (the interval convention).
        if self.is_zero() || o.is_zero() {
            return Affine::from_interval(Interval::ZERO);
        }
        let c = self.c * o.c;
        let mut e = add_up(mul_up(self.c.abs(), o.e), mul_up(o.c.abs(), self.e));
        e = add_up(e, mul_up(self.radius(), o.radius()));
        let mut a = [0.0; N];
        // The rounding of c and of each p, q and p + q: 3N + 1 operations, bounded at once.
        let mut sum = c.abs();
        for i in 0..N {
            let (p, q) = (self.c * o.a[i], o.c * self.a[i]);
            a[i] = p + q;
            sum += p.abs() + q.abs() + a[i].abs();
        }
        e = add_up(e, roundings(sum, 3 * N + 1));
        if !e.is_finite() || !c.is_finite() {
            return Affine::from_interval(self.range() * o.range());
        }
        Affine { c, a, e }
    }
}

impl<const N: usize> Div for Affine<N> {
    type Output = Self;
    /// `x̂ · (1 / ŷ)` ([`Affine::recip`]).
    #[allow(clippy::suspicious_arithmetic_impl)] // a quotient is the product with the reciprocal
    fn div(self, o: Self) -> Self {
        if self.is_zero() {
            return self;
        }
        self * o.recip()
    }
}

impl<const N: usize> Scalar for Affine<N> {
    fn cst(v: f64) -> Self {
        Affine::from_interval(Interval::point(v))
    }
    fn enclose(_nearest: f64, lo: f64, hi: f64) -> Self {
        Affine::from_interval(Interval::new(lo, hi))
    }
    /// `x̂²` centred: with `x̂ = c + L + E` (`L` the linear part, `|E| <= e`, `r = Σ|a_i| + e`),
    /// `x̂² = c² + 2cL + 2cE + (L + E)²` and `(L + E)² ∈ [0, r²]`: the centre moves by `r²/2` and
    /// the error grows by `r²/2`, half of what the product `x̂ · x̂` (which cannot know both
    /// factors are equal) adds.
    fn sqr(self) -> Self {
        if self.is_zero() {
            return self;
        }
        let r = self.radius();
        let half = mul_up(mul_up(r, r), 0.5);
        let cc = self.c * self.c;
        let c = cc + half;
        let mut e = add_up(add_up(rounding(cc), rounding(c)), half);
        e = add_up(e, mul_up(mul_up(2.0, self.c.abs()), self.e));
        let (a, err) = scaled(2.0 * self.c, &self.a);
        e = add_up(e, err);
        if !e.is_finite() || !c.is_finite() {
            return Affine::from_interval(self.range().sqr());
        }
        Affine { c, a, e }
    }
    fn powi(self, n: i32) -> Self {
        self.through_interval(|x| x.powi(n))
    }
    fn sqrt(self) -> Self {
        self.sqrt_min_range()
    }
    fn sin(self) -> Self {
        let c = Interval::point(self.c);
        self.linearised(c.sin(), c.cos())
    }
    fn cos(self) -> Self {
        let c = Interval::point(self.c);
        self.linearised(c.cos(), -c.sin())
    }
    fn tan(self) -> Self {
        self.through_interval(Interval::tan)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Scalar;

    fn chain<S: Scalar>(x: [S; 3]) -> S {
        // A rotation chain: the wrapping effect of intervals, not of affine forms.
        let [a, b, r] = x;
        let (u, v) = (r * a.cos(), r * a.sin());
        let (w, z) = (u * b.cos() - v * b.sin(), u * b.sin() + v * b.cos());
        w * w + z * z - r * r + w * S::cst(0.5) - z / S::cst(3.0)
    }

    #[test]
    fn affine_forms_enclose_point_values_and_beat_intervals_on_rotations() {
        let boxes = [
            [
                Interval::new(0.3, 0.31),
                Interval::new(-1.2, -1.19),
                Interval::new(100.0, 100.5),
            ],
            [
                Interval::new(-2.0, 1.0),
                Interval::new(0.0, 3.0),
                Interval::new(-1.0, 2.0),
            ],
            [
                Interval::point(0.7),
                Interval::new(1.0, 1.0 + 1e-9),
                Interval::new(5.0, 5.0),
            ],
        ];
        for (n, b) in boxes.iter().enumerate() {
            let inputs: [Affine<3>; 3] = core::array::from_fn(|k| Affine::input(b[k], k));
            let aff = chain(inputs).range();
            let iv = chain(*b);
            for s in 0..=1000 {
                let t = s as f64 / 1000.0;
                let p: [f64; 3] = core::array::from_fn(|k| {
                    let f = ((s * (k + 3) * 7919) % 1001) as f64 / 1000.0;
                    b[k].inf() + if k == 0 { t } else { f } * (b[k].sup() - b[k].inf())
                });
                let v = chain(p);
                assert!(aff.contains(v), "box {n}: {v} outside {aff}");
                assert!(iv.contains(v));
            }
            if n == 0 {
                // The true range is about 50 wide; intervals lose the rotation invariance.
                assert!(aff.wid() < 0.5 * iv.wid(), "affine {aff} vs interval {iv}");
            }
        }
    }

    #[test]
    fn zero_forms_add_and_multiply_exactly() {
        let x: Affine<2> = Affine::input(Interval::new(0.1, 0.3), 1) * Affine::cst(3.0);
        let zero = Affine::from_interval(Interval::ZERO);
        assert_eq!(x + zero, x);
        assert_eq!(zero + x, x);
        assert_eq!((x * zero).range(), Interval::ZERO);
        assert_eq!((zero * x).radius(), 0.0);
        assert!(!x.is_zero() && zero.is_zero());
    }

    /// Reciprocals, quotients and square roots enclose every value, keep the correlation (a
    /// narrow range relative to its centre gives a nearly exact linear part), and fall back when
    /// the range holds 0.
    #[test]
    fn reciprocals_and_square_roots_enclose_values_and_keep_correlations() {
        let cases = [
            (50.0, 60.0),
            (3600.0, 3700.0),
            (0.01, 4.0),
            (-7.0, -2.0),
            (0.0, 9.0),
        ];
        for (lo, hi) in cases {
            let x: Affine<2> = Affine::input(Interval::new(lo, hi), 0);
            let y: Affine<2> = Affine::input(Interval::new(1.0, 1.5), 1);
            let forms = [x.recip(), x.sqrt(), y / x, (x * x).sqrt()];
            for s in 0..=200 {
                let e0 = -1.0 + s as f64 / 100.0;
                let e1 = ((s * 7919) % 201) as f64 / 100.0 - 1.0;
                let (xv, yv) = (x.c + x.a[0] * e0, y.c + y.a[1] * e1);
                let exact = [1.0 / xv, xv.sqrt(), yv / xv, (xv * xv).sqrt()];
                for (k, f) in forms.iter().enumerate() {
                    if !exact[k].is_finite() || (k == 1 && xv < 0.0) {
                        continue;
                    }
                    let v = f.c + f.a[0] * e0 + f.a[1] * e1;
                    assert!(
                        (v - exact[k]).abs() <= f.e,
                        "case [{lo}, {hi}], form {k} at ({e0}, {e1}): {} vs {v} ± {}",
                        exact[k],
                        f.e
                    );
                }
            }
        }
        // x in [3600, 3700]: sqrt's true range is 0.83 wide, its curvature tiny; the form
        // keeps its slope on the noise symbol (interval arithmetic would give radius 0.41 as e).
        let x: Affine<1> = Affine::input(Interval::new(3600.0, 3700.0), 0);
        let s = x.sqrt();
        assert!(
            s.e < 0.005 && (s.a[0] - 25.0 / 3700f64.sqrt()).abs() < 1e-9,
            "{s:?}"
        );
        // A range holding 0 cannot be inverted: the form spans everything.
        let z: Affine<1> = Affine::input(Interval::new(-1.0, 1.0), 0);
        assert!(!z.recip().range().is_bounded());
    }

    /// A square encloses every value and is tighter than the product of the form with itself.
    #[test]
    fn squares_enclose_values_and_halve_the_product_remainder() {
        for (lo, hi) in [(-1.0, 3.0), (2.0, 2.5), (-4.0, -3.0), (-1e-3, 1e-3)] {
            let x: Affine<2> = Affine::input(Interval::new(lo, hi), 0)
                + Affine::input(Interval::new(-0.1, 0.2), 1);
            let (s, p) = (x.sqr(), x * x);
            assert!(s.e < p.e, "[{lo}, {hi}]: {s:?} vs {p:?}");
            for k in 0..=400 {
                let e0 = -1.0 + (k % 21) as f64 / 10.0;
                let e1 = -1.0 + (k / 21) as f64 / 10.0;
                let xv = x.c + x.a[0] * e0 + x.a[1] * e1;
                let v = s.c + s.a[0] * e0 + s.a[1] * e1;
                assert!((v - xv * xv).abs() <= s.e, "[{lo}, {hi}] at ({e0}, {e1})");
            }
        }
    }

    #[test]
    fn products_of_correlated_forms_cancel() {
        let x: Affine<1> = Affine::input(Interval::new(1.0, 3.0), 0);
        let d = (x - x).range();
        assert!(d.contains(0.0) && d.wid() < 1e-12, "{d}");
        // x * x over [1, 3]: [-1 + ...]: contains [1, 9].
        let sq = (x * x).range();
        assert!(sq.inf() <= 1.0 && sq.sup() >= 9.0, "{sq}");
    }

    /// `a + b` as an unevaluated sum `hi + lo` (Knuth's TwoSum: exact).
    fn two_sum(a: f64, b: f64) -> (f64, f64) {
        let s = a + b;
        let bb = s - a;
        (s, (a - (s - bb)) + (b - bb))
    }

    /// A double-double sum of double-doubles (error far below one ulp of a double).
    fn dd_add(x: (f64, f64), y: (f64, f64)) -> (f64, f64) {
        let (s, e) = two_sum(x.0, y.0);
        two_sum(s, e + x.1 + y.1)
    }

    /// A double-double product of a double-double and a double (TwoProduct through `mul_add`).
    fn dd_mul(x: (f64, f64), y: f64) -> (f64, f64) {
        let p = x.0 * y;
        let e = x.0.mul_add(y, -p);
        two_sum(p, e + x.1 * y)
    }

    /// `c + Σ a_i ε_i` for `ε_i = ±1`, in double-double.
    fn dd_value<const N: usize>(f: &Affine<N>, signs: &[f64; N]) -> (f64, f64) {
        (0..N).fold((f.centre(), 0.0), |s, i| {
            dd_add(s, (f.coefficients()[i] * signs[i], 0.0))
        })
    }

    #[test]
    fn products_and_sums_bound_their_own_rounding_errors() {
        // With a constant factor and exact inputs, the error radius holds nothing but the bounds
        // of the roundings of centres and coefficients: the exact value (double-double) at the
        // corners where those roundings add up must stay within it.
        use rand::{Rng, SeedableRng};
        let mut rng = rand::rngs::StdRng::seed_from_u64(11);
        let mut worst = 0.0f64;
        for _ in 0..2000 {
            let form = |rng: &mut rand::rngs::StdRng| -> Affine<12> {
                let a: [f64; 12] = core::array::from_fn(|_| {
                    rng.random_range(-1.0..1.0) * 10f64.powi(rng.random_range(-6..3))
                });
                Affine {
                    c: rng.random_range(-100.0..100.0),
                    a,
                    e: 0.0,
                }
            };
            let (x, w) = (form(&mut rng), form(&mut rng));
            let k = rng.random_range(-3.0..3.0) * 10f64.powi(rng.random_range(-3..3));
            let product = x * Affine::from_interval(Interval::point(k));
            let sum = x + w;
            for _ in 0..8 {
                let signs: [f64; 12] =
                    core::array::from_fn(|_| if rng.random_bool(0.5) { 1.0 } else { -1.0 });
                for (exact, got) in [
                    (dd_mul(dd_value(&x, &signs), k), &product),
                    (dd_add(dd_value(&x, &signs), dd_value(&w, &signs)), &sum),
                ] {
                    let lin = dd_value(got, &signs);
                    let off = dd_add(exact, (-lin.0, -lin.1));
                    let off = (off.0 + off.1).abs();
                    assert!(
                        off <= got.error(),
                        "{off:e} beyond the error radius {:e}",
                        got.error()
                    );
                    if got.error() > 0.0 {
                        worst = worst.max(off / got.error());
                    }
                }
            }
        }
        // The bound is not vacuous: somewhere the roundings reach a good part of it.
        assert!(worst > 0.05, "largest rounding off / bound {worst}");
    }
}
