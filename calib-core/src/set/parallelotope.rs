//! A parallelotope around a certified set, aligned with what the data determine: linear
//! functions bounded over the set without a linear program, at the set's scale rather than its
//! box's.
//!
//! # What it is
//!
//! A certified set is thin along the combinations of parameters the measurements fix and wide
//! along the others; its outer box is wide in every coordinate such a combination involves. With
//! `δ = x - x̂` about a point `x̂` (the calibrated vector), a basis `w_1 … w_n` of the free
//! coordinates (the eigenvectors of `Σ Gᵀ G` over the pieces' rows `G`, in coordinates scaled by
//! the outer box, so that the basis follows the data) and the ranges
//!
//! `Z_k ⊇ { w_k·δ : x ∈ S }`
//!
//! each proved by one linear program over the set's polyhedra ([`crate::SetQuery::max_linear`],
//! safe bounds), every consistent `δ` is `T z + (I - T Wᵀ) δ` with `z ∈ Z` and `T ≈ W⁻ᵀ` any
//! matrix: the second term, enclosed in interval arithmetic over the outer box, holds only the
//! rounding of `T`. So
//!
//! `S ⊆ { x̂ + T z + ρ : z ∈ Z, ρ ∈ R }`,
//!
//! and for any slopes `s` (intervals), `s·δ <= Σ_k sup((s·t_k) Z_k) + sup(s·R)`: a bound of a
//! linear function over the set in `O(n²)` operations ([`Parallelotope::max_linear`]). It is
//! exact along each `w_k` and loose only where the set's polyhedra cut corners of the
//! parallelotope — what an accuracy bound needs for its first-order corrections (the variation
//! of a prediction's gradient over a box of inputs), whose main term takes a linear program.

use crate::{CertifiedSet, Interval};
use nalgebra::{DMatrix, SymmetricEigen};

/// A parallelotope containing a [`CertifiedSet`] (module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct Parallelotope<const NX: usize> {
    /// The coordinates the basis mixes (the free ones).
    mixed: Vec<usize>,
    /// Per basis direction `k`, the column `t_k` of `T` (zero outside `mixed`).
    columns: Vec<[f64; NX]>,
    /// Per basis direction `k`, the range `Z_k` of `w_k·δ` over the set.
    ranges: Vec<Interval>,
    /// `δ` over the set's outer box, per coordinate (the bound of the unmixed coordinates).
    delta: [Interval; NX],
    /// `R = (I - T Wᵀ) δ` over the outer box (zero outside `mixed`).
    rounding: [Interval; NX],
}

impl<const NX: usize> Parallelotope<NX> {
    /// The parallelotope of `set` about `about` (module documentation): `2n` linear programs for
    /// `n` free coordinates. `None` for an empty set or when a range could not be bounded.
    pub fn around<const NM: usize>(set: &CertifiedSet<NX, NM>, about: &[f64; NX]) -> Option<Self> {
        Self::around_along(set, about, &[])
    }

    /// [`Parallelotope::around`] with a basis that follows the linear functions `hints` (the
    /// eigenvectors of `Σ h hᵀ` over the hints, each scaled to unit length in the scaled
    /// coordinates, plus a small share of the data's normal matrix to settle the directions no
    /// hint reaches): the parallelotope is then tight along what will be asked of it.
    pub fn around_along<const NM: usize>(
        set: &CertifiedSet<NX, NM>,
        about: &[f64; NX],
        hints: &[[f64; NX]],
    ) -> Option<Self> {
        let outer = set.outer()?;
        let delta: [Interval; NX] = core::array::from_fn(|j| outer[j] - Interval::point(about[j]));
        let first = set.pieces().first()?.polyhedron();
        let mixed: Vec<usize> = (0..NX)
            .filter(|&j| !first.is_frozen(j) && outer[j].wid() > 0.0)
            .collect();
        let n = mixed.len();
        let scale: Vec<f64> = mixed.iter().map(|&j| outer[j].rad().max(1e-300)).collect();
        // Σ Gᵀ G over every piece's rows, in scaled coordinates.
        let mut normal = DMatrix::<f64>::zeros(n, n);
        for piece in set.pieces() {
            let p = piece.polyhedron();
            for r in 0..p.rows() {
                let row = p.row(r);
                let g: Vec<f64> = mixed.iter().zip(&scale).map(|(&j, s)| row[j] * s).collect();
                for a in 0..n {
                    for b in 0..n {
                        normal[(a, b)] += g[a] * g[b];
                    }
                }
            }
        }
        if !hints.is_empty() {
            let trace: f64 = (0..n).map(|a| normal[(a, a)]).sum();
            let share = if trace > 0.0 { 1e-6 / trace } else { 0.0 };
            normal *= share;
            for h in hints {
                let g: Vec<f64> = mixed.iter().zip(&scale).map(|(&j, s)| h[j] * s).collect();
                let len2: f64 = g.iter().map(|v| v * v).sum();
                if !(len2 > 0.0 && len2.is_finite()) {
                    continue;
                }
                for a in 0..n {
                    for b in 0..n {
                        normal[(a, b)] += g[a] * g[b] / len2;
                    }
                }
            }
        }
        let basis = if normal.iter().all(|v| v.is_finite()) {
            SymmetricEigen::new(normal).eigenvectors
        } else {
            DMatrix::identity(n, n)
        };
        // w_k = diag(1/scale) v_k, t_k = diag(scale) v_k.
        let mut rows = Vec::with_capacity(n);
        let mut columns = Vec::with_capacity(n);
        for k in 0..n {
            let mut w = [0.0; NX];
            let mut t = [0.0; NX];
            for (a, &j) in mixed.iter().enumerate() {
                w[j] = basis[(a, k)] / scale[a];
                t[j] = basis[(a, k)] * scale[a];
            }
            rows.push(w);
            columns.push(t);
        }
        let mut query = set.query();
        let mut ranges = Vec::with_capacity(n);
        for w in &rows {
            let slopes = w.map(Interval::point);
            let hi = query.max_linear(&slopes, about).upper;
            let lo = -query.max_linear(&slopes.map(|s| -s), about).upper;
            if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
                return None;
            }
            ranges.push(Interval::new(lo, hi));
        }
        // R_j = Σ_l (I - T Wᵀ)_jl δ_l over the mixed coordinates.
        let mut rounding = [Interval::ZERO; NX];
        for &j in &mixed {
            let mut sum = Interval::ZERO;
            for &l in &mixed {
                let mut e = Interval::point(if j == l { 1.0 } else { 0.0 });
                for k in 0..n {
                    e -= Interval::point(columns[k][j]) * Interval::point(rows[k][l]);
                }
                sum += e * delta[l];
            }
            rounding[j] = sum;
        }
        Some(Parallelotope {
            mixed,
            columns,
            ranges,
            delta,
            rounding,
        })
    }

    /// An upper bound of `Σ_j s_j δ_j` over the set, for slopes `s` enclosing any values
    /// (`+∞` if the bound is not finite).
    pub fn max_linear(&self, slopes: &[Interval; NX]) -> f64 {
        let along = self.columns.iter().map(|t| self.along(t, slopes));
        self.max_split(along, self.rest(slopes))
    }

    /// `s·δ` in the parallelotope's terms: per basis direction `k` the coefficient `s·t_k` of
    /// its range `Z_k`, and the rest (the rounding of `T`, the unmixed coordinates), so that
    /// `s·δ ∈ Σ_k (s·t_k) Z_k + rest` over the set. Linear in `s`: a combination of splits (in
    /// interval arithmetic) is a split of the combination, for [`Parallelotope::max_split`].
    pub fn split(&self, slopes: &[Interval; NX]) -> (Vec<Interval>, Interval) {
        let along = self.columns.iter().map(|t| self.along(t, slopes)).collect();
        (along, self.rest(slopes))
    }

    /// The upper bound of a linear function over the set from its split
    /// ([`Parallelotope::split`]): `sup(Σ_k along_k Z_k + rest)` (`+∞` if not finite).
    pub fn max_split(&self, along: impl IntoIterator<Item = Interval>, rest: Interval) -> f64 {
        let sum = along
            .into_iter()
            .zip(&self.ranges)
            .fold(rest, |sum, (a, z)| sum + a * *z);
        let up = sum.sup();
        if up.is_nan() {
            f64::INFINITY
        } else {
            up
        }
    }

    /// [`Parallelotope::split`] of slopes `s_j ∈ mid_j ± rad_j`, in floating point (many splits
    /// at a fraction of the intervals' cost): per coefficient, then for the rest, a midpoint and
    /// a radius, the radius holding the slopes' radii and every rounding of the sums (an
    /// allowance of `1e-12` of their magnitude, far above `n · 2⁻⁵³` for `n` up to thousands of
    /// terms).
    pub fn split_mid_rad(&self, mid: &[f64; NX], rad: &[f64; NX]) -> (Vec<f64>, Vec<f64>) {
        const ROUNDING: f64 = 1e-12;
        // Σ_j (mid_j ± rad_j) c_j for intervals c_j = cm_j ± cr_j.
        let sum = |terms: &mut dyn Iterator<Item = (usize, f64, f64, f64)>| {
            let (mut m, mut size, mut r) = (0.0f64, 0.0f64, 0.0f64);
            for (j, cm, cr, cmag) in terms {
                m += mid[j] * cm;
                size += (mid[j] * cm).abs();
                r += mid[j].abs() * cr + rad[j] * cmag;
            }
            (
                m,
                (r + ROUNDING * size) * (1.0 + ROUNDING) + f64::MIN_POSITIVE,
            )
        };
        let (mut mids, mut rads): (Vec<f64>, Vec<f64>) = self
            .columns
            .iter()
            .map(|t| sum(&mut self.mixed.iter().map(|&j| (j, t[j], 0.0, t[j].abs()))))
            .unzip();
        let parts = |v: &Interval| {
            let c = v.mid();
            (c, (*v - Interval::point(c)).mag(), v.mag())
        };
        let (m, r) = sum(&mut (0..NX).map(|j| {
            let (c, cr, cmag) = if self.mixed.binary_search(&j).is_ok() {
                parts(&self.rounding[j])
            } else {
                parts(&self.delta[j])
            };
            (j, c, cr, cmag)
        }));
        mids.push(m);
        rads.push(r);
        (mids, rads)
    }

    /// The ranges `Z_k` of the basis directions over the set, in the order of
    /// [`Parallelotope::split`]'s coefficients.
    pub fn ranges(&self) -> &[Interval] {
        &self.ranges
    }

    /// `s·t` over the mixed coordinates.
    fn along(&self, t: &[f64; NX], slopes: &[Interval; NX]) -> Interval {
        self.mixed.iter().fold(Interval::ZERO, |sum, &j| {
            sum + slopes[j] * Interval::point(t[j])
        })
    }

    /// `Σ_j s_j R_j` over the mixed coordinates plus `Σ_j s_j δ_j` over the others.
    fn rest(&self, slopes: &[Interval; NX]) -> Interval {
        let mut sum = Interval::ZERO;
        let mut mixed = self.mixed.iter().peekable();
        for j in 0..NX {
            if mixed.peek() == Some(&&j) {
                mixed.next();
                sum += slopes[j] * self.rounding[j];
            } else {
                sum += slopes[j] * self.delta[j];
            }
        }
        sum
    }

    /// `max |s·δ|` over the set: the larger of [`Parallelotope::max_linear`] of `s` and of `-s`.
    pub fn max_abs_linear(&self, slopes: &[Interval; NX]) -> f64 {
        self.max_linear(slopes)
            .max(self.max_linear(&slopes.map(|s| -s)))
    }
}
