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
        let mut sum = Interval::ZERO;
        for (t, z) in self.columns.iter().zip(&self.ranges) {
            let mut along = Interval::ZERO;
            for &j in &self.mixed {
                along += slopes[j] * Interval::point(t[j]);
            }
            sum += along * *z;
        }
        let mut mixed = self.mixed.iter().peekable();
        for j in 0..NX {
            if mixed.peek() == Some(&&j) {
                mixed.next();
                sum += slopes[j] * self.rounding[j];
            } else {
                sum += slopes[j] * self.delta[j];
            }
        }
        let up = sum.sup();
        if up.is_nan() {
            f64::INFINITY
        } else {
            up
        }
    }

    /// `max |s·δ|` over the set: the larger of [`Parallelotope::max_linear`] of `s` and of `-s`.
    pub fn max_abs_linear(&self, slopes: &[Interval; NX]) -> f64 {
        self.max_linear(slopes)
            .max(self.max_linear(&slopes.map(|s| -s)))
    }
}
