//! A dense active-set simplex for tiny LPs with many rows and few variables.
//!
//! The constraints are the rows `G_i·y <= g_i` and the box bounds `y_j <= hi_j`, `-y_j <= -lo_j`.
//! A basis is a set `W` of `n` constraints whose matrix `A_W` is invertible; its vertex is
//! `y = A_W⁻¹ b_W` and its multipliers solve `A_Wᵀ λ_W = -c`.
//!
//! * **Dual simplex** (cold start): the start is the box corner chosen by the signs of `c`, which is
//!   dual feasible (`λ >= 0`) for any objective. Each iteration enters the most violated constraint
//!   `k` and leaves the basis constraint that keeps `λ >= 0` (the dual ratio test); no leaving
//!   candidate means a Farkas ray, i.e. an empty polyhedron. Every iterate is dual feasible, so even
//!   an interrupted solve yields multipliers that [`super::safe_lower_bound`] turns into a valid
//!   bound.
//! * **Primal simplex** (warm start): the `2n` objectives of a contraction share one polyhedron, so
//!   after an optimal solve the next objective starts from the previous optimal vertex (still
//!   feasible: the kernel only tightens bounds up to the optima it found) and moves along edges,
//!   leaving the constraint with the most negative multiplier, until `λ >= 0`. If the vertex is not
//!   feasible any more, or the walk fails, the solve falls back to the cold dual simplex.
//!
//! Both switch to Bland's rule after `2n` degenerate pivots (no cycling). `A_W⁻¹` is updated by the
//! Sherman–Morrison formula at each basis change (`n²` flops) and recomputed by Gauss–Jordan
//! elimination with partial pivoting every [`REFACTOR_EVERY`] pivots and at each start. All buffers
//! are reused: no allocation after the first call of a size.

use super::{LpBackend, LpStatus, Polyhedron};
use crate::linalg::gauss_jordan_inverse;

/// The dense simplex engine (see the module documentation).
#[derive(Clone, Debug, Default)]
pub struct DenseSimplex {
    basis: Vec<usize>,
    in_basis: Vec<bool>,
    a_w: Vec<f64>,
    inv: Vec<f64>,
    y: Vec<f64>,
    lambda: Vec<f64>,
    w: Vec<f64>,
    a_k: Vec<f64>,
    /// The polyhedron generation of the last optimal solve (its basis can warm-start the next).
    warm: Option<u64>,
    /// Pivots made by the last call (for profiling).
    pub last_pivots: usize,
}

/// Violations below this (relative to the row scale, rows are normalised to max |coef| ~ 1) are
/// accepted as satisfied; the safe bound makes the result rigorous anyway.
const FEASIBILITY_TOL: f64 = 1e-12;
/// A warm-start vertex may violate constraints by at most this much.
const WARM_TOL: f64 = 1e-9;
/// Pivot elements below this are not used in ratio tests.
const PIVOT_TOL: f64 = 1e-11;
/// Recompute `A_W⁻¹` from scratch after this many rank-one updates.
const REFACTOR_EVERY: usize = 16;

/// The coefficient row and right-hand side of constraint `k` (rows first, then the bounds).
#[inline(always)]
fn constraint(p: &Polyhedron, k: usize, a: &mut [f64]) -> f64 {
    let m = p.rows();
    if k < m {
        a.copy_from_slice(p.row(k));
        p.rhs(k)
    } else {
        let j = (k - m) / 2;
        a.iter_mut().for_each(|v| *v = 0.0);
        if (k - m) % 2 == 0 {
            a[j] = 1.0;
            p.hi()[j]
        } else {
            a[j] = -1.0;
            -p.lo()[j]
        }
    }
}

/// `b_k`.
#[inline(always)]
fn rhs(p: &Polyhedron, k: usize) -> f64 {
    let m = p.rows();
    if k < m {
        p.rhs(k)
    } else if (k - m) % 2 == 0 {
        p.hi()[(k - m) / 2]
    } else {
        -p.lo()[(k - m) / 2]
    }
}

/// `a_k · y - b_k` (bounds scaled like [`DenseSimplex`]'s violation test).
#[inline(always)]
fn violation(p: &Polyhedron, k: usize, y: &[f64]) -> f64 {
    let m = p.rows();
    if k < m {
        p.row(k).iter().zip(y).map(|(a, y)| a * y).sum::<f64>() - p.rhs(k)
    } else {
        let j = (k - m) / 2;
        let scale = 1.0 + p.hi()[j].abs().max(p.lo()[j].abs());
        if (k - m) % 2 == 0 {
            (y[j] - p.hi()[j]) / scale
        } else {
            (p.lo()[j] - y[j]) / scale
        }
    }
}

/// `a_k · d`.
#[inline(always)]
fn along(p: &Polyhedron, k: usize, d: &[f64]) -> f64 {
    let m = p.rows();
    if k < m {
        p.row(k).iter().zip(d).map(|(a, d)| a * d).sum()
    } else if (k - m) % 2 == 0 {
        d[(k - m) / 2]
    } else {
        -d[(k - m) / 2]
    }
}

impl DenseSimplex {
    fn resize(&mut self, n: usize) {
        self.basis.resize(n, 0);
        self.a_w.resize(n * n, 0.0);
        self.inv.resize(n * n, 0.0);
        self.y.resize(n, 0.0);
        self.lambda.resize(n, 0.0);
        self.w.resize(n, 0.0);
        self.a_k.resize(n, 0.0);
    }

    fn set_basis_mask(&mut self, constraints: usize) {
        self.in_basis.clear();
        self.in_basis.resize(constraints, false);
        for &k in &self.basis {
            self.in_basis[k] = true;
        }
    }

    /// Recomputes `inv = A_W⁻¹`; false if `A_W` is (numerically) singular.
    fn invert(&mut self, p: &Polyhedron) -> bool {
        let n = p.dim();
        for r in 0..n {
            constraint(p, self.basis[r], &mut self.a_k);
            self.a_w[r * n..(r + 1) * n].copy_from_slice(&self.a_k);
        }
        gauss_jordan_inverse(n, &mut self.a_w, &mut self.inv)
    }

    /// `y = A_W⁻¹ b_W`.
    fn vertex(&mut self, p: &Polyhedron) {
        let n = p.dim();
        for j in 0..n {
            self.y[j] = (0..n)
                .map(|r| self.inv[j * n + r] * rhs(p, self.basis[r]))
                .sum();
        }
    }

    /// `λ_W = -A_W⁻ᵀ c` (not clipped).
    fn multipliers(&mut self, n: usize, c: &[f64]) {
        for r in 0..n {
            self.lambda[r] = -(0..n).map(|j| self.inv[j * n + r] * c[j]).sum::<f64>();
        }
    }

    /// `w = A_W⁻ᵀ a_k` for the constraint in `self.a_k`.
    fn transformed_row(&mut self, n: usize) {
        for r in 0..n {
            self.w[r] = (0..n).map(|j| self.inv[j * n + r] * self.a_k[j]).sum();
        }
    }

    /// Replaces basis position `r` by constraint `k` (with `w` already computed for `a_k`):
    /// `inv' = inv - inv e_r (w - e_r)ᵀ / w_r` (Sherman–Morrison).
    fn replace(&mut self, n: usize, r: usize, k: usize) {
        let wr = self.w[r];
        for j in 0..n {
            let u = self.inv[j * n + r];
            if u != 0.0 {
                for col in 0..n {
                    let v = if col == r {
                        self.w[col] - 1.0
                    } else {
                        self.w[col]
                    };
                    self.inv[j * n + col] -= u * v / wr;
                }
            }
        }
        self.in_basis[self.basis[r]] = false;
        self.in_basis[k] = true;
        self.basis[r] = k;
        self.last_pivots += 1;
    }

    fn export(&self, m: usize, dual: &mut [f64], primal: &mut [f64]) {
        for (r, &k) in self.basis.iter().enumerate() {
            if k < m {
                dual[k] = self.lambda[r].max(0.0);
            }
        }
        primal.copy_from_slice(&self.y);
    }

    /// The cold-start dual simplex (see the module documentation).
    fn dual_simplex(
        &mut self,
        p: &Polyhedron,
        c: &[f64],
        dual: &mut [f64],
        primal: &mut [f64],
    ) -> LpStatus {
        let (n, m) = (p.dim(), p.rows());
        for j in 0..n {
            self.basis[j] = m + 2 * j + usize::from(c[j] > 0.0);
        }
        self.set_basis_mask(m + 2 * n);
        let mut since_refactor = REFACTOR_EVERY;
        let mut degenerate = 0usize;
        let max_pivots = 10 * (n + m) + 50;
        let mut status = LpStatus::Failed;
        for _ in 0..max_pivots {
            if since_refactor >= REFACTOR_EVERY {
                if !self.invert(p) {
                    break;
                }
                since_refactor = 0;
            }
            self.vertex(p);
            self.multipliers(n, c);
            self.lambda.iter_mut().for_each(|l| *l = l.max(0.0));
            // Most violated constraint outside the basis (Dantzig), or the first violated one once
            // degenerate pivots pile up (Bland's rule, which cannot cycle).
            let bland = degenerate > 2 * n;
            let mut entering = None;
            let mut worst = FEASIBILITY_TOL;
            for k in 0..m + 2 * n {
                if self.in_basis[k] {
                    continue;
                }
                let v = violation(p, k, &self.y);
                if v > worst {
                    worst = v;
                    entering = Some(k);
                    if bland {
                        break;
                    }
                }
            }
            let Some(k) = entering else {
                status = LpStatus::Optimal;
                break;
            };
            // w = A_W⁻ᵀ a_k; leave the basis constraint with the smallest ratio λ_r / w_r, w_r > 0.
            constraint(p, k, &mut self.a_k);
            self.transformed_row(n);
            let mut leave: Option<usize> = None;
            let mut best = f64::INFINITY;
            for r in 0..n {
                if self.w[r] > PIVOT_TOL {
                    let t = self.lambda[r] / self.w[r];
                    // Bland: among (near-)ties, the constraint with the smallest index leaves.
                    let tie = bland
                        && leave.is_some_and(|l| {
                            t <= best * (1.0 + 1e-12) + 1e-300 && self.basis[r] < self.basis[l]
                        });
                    if t < best || tie {
                        best = best.min(t);
                        leave = Some(r);
                    }
                }
            }
            degenerate = if best <= 1e-14 { degenerate + 1 } else { 0 };
            let Some(r) = leave else {
                // Farkas ray: μ_k = 1, μ_W = -w (>= 0 up to rounding).
                dual.iter_mut().for_each(|v| *v = 0.0);
                if k < m {
                    dual[k] = 1.0;
                }
                for r in 0..n {
                    let kr = self.basis[r];
                    if kr < m {
                        dual[kr] = (-self.w[r]).max(0.0);
                    }
                }
                primal.copy_from_slice(&self.y);
                return LpStatus::Infeasible;
            };
            self.replace(n, r, k);
            since_refactor += 1;
        }
        self.export(m, dual, primal);
        status
    }

    /// The warm-start primal simplex from the current basis; `None` if the basis is not a feasible
    /// vertex of `p` (the caller then runs the dual simplex).
    fn primal_simplex(
        &mut self,
        p: &Polyhedron,
        c: &[f64],
        dual: &mut [f64],
        primal: &mut [f64],
    ) -> Option<LpStatus> {
        let (n, m) = (p.dim(), p.rows());
        if !self.invert(p) {
            return None;
        }
        self.vertex(p);
        if (0..m + 2 * n).any(|k| !self.in_basis[k] && violation(p, k, &self.y) > WARM_TOL) {
            return None;
        }
        let mut since_refactor = 0;
        let mut degenerate = 0usize;
        let max_pivots = 10 * (n + m) + 50;
        for _ in 0..max_pivots {
            if since_refactor >= REFACTOR_EVERY {
                if !self.invert(p) {
                    return None;
                }
                since_refactor = 0;
                self.vertex(p);
            }
            self.multipliers(n, c);
            let bland = degenerate > 2 * n;
            // Leave the constraint with the most negative multiplier (Bland: the first negative).
            let mut leave = None;
            let mut most = -FEASIBILITY_TOL;
            for r in 0..n {
                if self.lambda[r] < most
                    || (bland && self.lambda[r] < -FEASIBILITY_TOL && leave.is_none())
                {
                    most = self.lambda[r];
                    leave = Some(r);
                    if bland {
                        break;
                    }
                }
            }
            let Some(r) = leave else {
                self.export(m, dual, primal);
                return Some(LpStatus::Optimal);
            };
            // Edge direction d = -A_W⁻¹ e_r: keeps the other basis constraints active and moves
            // inside constraint r; c·d = λ_r < 0.
            for j in 0..n {
                self.a_w[j] = -self.inv[j * n + r];
            }
            let mut enter = None;
            let mut best = f64::INFINITY;
            for k in 0..m + 2 * n {
                if self.in_basis[k] {
                    continue;
                }
                let ad = along(p, k, &self.a_w[..n]);
                if ad > PIVOT_TOL {
                    let slack = -violation_unscaled(p, k, &self.y);
                    let t = slack.max(0.0) / ad;
                    if t < best
                        || (bland && t <= best * (1.0 + 1e-12) && enter.is_some_and(|e| k < e))
                    {
                        best = best.min(t);
                        enter = Some(k);
                    }
                }
            }
            let k = enter?;
            degenerate = if best <= 1e-14 { degenerate + 1 } else { 0 };
            for j in 0..n {
                self.y[j] += best * self.a_w[j];
            }
            constraint(p, k, &mut self.a_k);
            self.transformed_row(n);
            if self.w[r].abs() < PIVOT_TOL {
                return None;
            }
            self.replace(n, r, k);
            since_refactor += 1;
        }
        None
    }
}

/// `a_k · y - b_k` without the bound scaling (a true slack for ratio tests).
#[inline(always)]
fn violation_unscaled(p: &Polyhedron, k: usize, y: &[f64]) -> f64 {
    let m = p.rows();
    if k < m {
        violation(p, k, y)
    } else {
        let j = (k - m) / 2;
        if (k - m) % 2 == 0 {
            y[j] - p.hi()[j]
        } else {
            p.lo()[j] - y[j]
        }
    }
}

impl LpBackend for DenseSimplex {
    fn name(&self) -> &'static str {
        "dense-simplex"
    }

    fn minimize(
        &mut self,
        p: &Polyhedron,
        c: &[f64],
        dual: &mut [f64],
        primal: &mut [f64],
    ) -> LpStatus {
        let n = p.dim();
        self.resize(n);
        dual.iter_mut().for_each(|v| *v = 0.0);
        self.last_pivots = 0;
        if self.warm == Some(p.generation()) && self.in_basis.len() == p.rows() + 2 * n {
            if let Some(status) = self.primal_simplex(p, c, dual, primal) {
                return status;
            }
            dual.iter_mut().for_each(|v| *v = 0.0);
        }
        let status = self.dual_simplex(p, c, dual, primal);
        self.warm = (status == LpStatus::Optimal).then_some(p.generation());
        status
    }
}
