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

use super::basis::{Basis, Constraints};
use super::scaled_simplex::ScaledSimplex;
use super::{LpBackend, LpMemory, LpStatus, Polyhedron};

/// The dense simplex engine (see the module documentation).
#[derive(Clone, Debug, Default)]
pub struct DenseSimplex {
    b: Basis,
    /// The engine for LPs of more than [`SMALL_DIM`] variables.
    large: ScaledSimplex,
    /// The polyhedron generation of the last optimal solve (its basis can warm-start the next).
    warm: Option<u64>,
    /// Pivots made by the last call (for profiling).
    pub last_pivots: usize,
    /// The rows of `G` column by column, to price every row at once ([`Columns`]).
    cols: Columns,
}

/// `G` stored column by column (`g[j * m + i] = G_ij`), so that the products `G_i·v` of every row
/// come out of `n` passes of `out_i += G_ij v_j` over contiguous memory, which the compiler
/// vectorises; row by row, each 7-term dot product ran alone. The terms are added in the same
/// order as a row's dot product (`j = 0, 1, …`), so every product is bit-identical to it and the
/// walks (pricing, ratio tests, ties) are unchanged. Rebuilt when the polyhedron changes (its
/// generation and row count: rows are only ever appended after a reset).
#[derive(Clone, Debug, Default)]
struct Columns {
    g: Vec<f64>,
    key: Option<(u64, usize)>,
    /// `G y` for the current vertex `y`.
    activity: Vec<f64>,
    /// `G d` for an edge direction `d`.
    along: Vec<f64>,
}

impl Columns {
    /// Makes `g` the columns of `p`'s rows.
    fn load(&mut self, p: &Polyhedron) {
        let (n, m) = (p.dim(), p.rows());
        let key = Some((p.generation(), m));
        if self.key == key && self.g.len() == n * m {
            return;
        }
        self.g.clear();
        self.g.resize(n * m, 0.0);
        for i in 0..m {
            for (j, &a) in p.row(i).iter().enumerate() {
                self.g[j * m + i] = a;
            }
        }
        self.activity.resize(m, 0.0);
        self.along.resize(m, 0.0);
        self.key = key;
    }

    /// `out_i = G_i·v` for every row, summed in the order `j = 0, 1, …` (the same value as
    /// `row.iter().zip(v).map(|(a, v)| a * v).sum()`).
    fn products(g: &[f64], v: &[f64], out: &mut [f64]) {
        let m = out.len();
        if m == 0 || v.is_empty() {
            out.iter_mut().for_each(|o| *o = 0.0);
            return;
        }
        let (first, rest) = g.split_at(m);
        for (o, &a) in out.iter_mut().zip(first) {
            // The first term alone, as in the sum (up to the sign of a zero sum, which no
            // comparison sees).
            *o = a * v[0];
        }
        for (col, &vj) in rest.chunks_exact(m).zip(&v[1..]) {
            for (o, &a) in out.iter_mut().zip(col) {
                *o += a * vj;
            }
        }
    }

    /// `activity = G y`.
    fn activities(&mut self, y: &[f64]) {
        Self::products(&self.g, y, &mut self.activity);
    }

    /// `along = G d`.
    fn alongs(&mut self, d: &[f64]) {
        Self::products(&self.g, d, &mut self.along);
    }
}

/// LPs with more variables than this go to [`ScaledSimplex`]: the unscaled walk below is measured
/// faster on the 7 variables of a Gough leg and never stalls there, while long kinematic chains (27
/// and more variables, thousands of nearly parallel rows) need scaling and stall handling.
pub const SMALL_DIM: usize = 16;

/// The constraints of `p` as this engine sees them (unscaled).
struct Plain<'a>(&'a Polyhedron);

impl Constraints for Plain<'_> {
    fn constraint(&self, k: usize, a: &mut [f64]) -> f64 {
        constraint(self.0, k, a)
    }

    fn rhs(&self, k: usize) -> f64 {
        rhs(self.0, k)
    }
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

/// [`violation`] with the rows' products `G_i·y` given in `activity`.
#[inline(always)]
fn violation_from(p: &Polyhedron, k: usize, activity: &[f64], y: &[f64]) -> f64 {
    if k < p.rows() {
        activity[k] - p.rhs(k)
    } else {
        violation(p, k, y)
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
    /// The unscaled solve, for at most [`SMALL_DIM`] variables.
    fn minimize_small(
        &mut self,
        p: &Polyhedron,
        c: &[f64],
        dual: &mut [f64],
        primal: &mut [f64],
    ) -> LpStatus {
        let n = p.dim();
        self.b.resize(n);
        dual.iter_mut().for_each(|v| *v = 0.0);
        self.b.pivots = 0;
        if self.warm == Some(p.generation()) && self.b.in_basis.len() == p.rows() + 2 * n {
            if let Some(status) = self.primal_simplex(p, c, dual, primal) {
                return status;
            }
            dual.iter_mut().for_each(|v| *v = 0.0);
        }
        let status = self.dual_simplex(p, c, dual, primal);
        self.warm = (status == LpStatus::Optimal).then_some(p.generation());
        status
    }

    fn export(&self, m: usize, dual: &mut [f64], primal: &mut [f64]) {
        for (r, &k) in self.b.basis.iter().enumerate() {
            if k < m {
                dual[k] = self.b.lambda[r].max(0.0);
            }
        }
        primal.copy_from_slice(&self.b.y);
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
        self.cols.load(p);
        for j in 0..n {
            self.b.basis[j] = m + 2 * j + usize::from(c[j] > 0.0);
        }
        self.b.set_mask(m + 2 * n);
        self.dual_loop(p, c, dual, primal, REFACTOR_EVERY)
    }

    /// The dual simplex's iterations from the dual feasible basis in `self.b` (`A_W⁻¹` already
    /// computed unless `since_refactor` is [`REFACTOR_EVERY`]).
    fn dual_loop(
        &mut self,
        p: &Polyhedron,
        c: &[f64],
        dual: &mut [f64],
        primal: &mut [f64],
        mut since_refactor: usize,
    ) -> LpStatus {
        let (n, m) = (p.dim(), p.rows());
        self.cols.load(p);
        let mut degenerate = 0usize;
        let max_pivots = 10 * (n + m) + 50;
        let mut status = LpStatus::Failed;
        for _ in 0..max_pivots {
            if since_refactor >= REFACTOR_EVERY {
                if !self.b.invert(&Plain(p)) {
                    break;
                }
                since_refactor = 0;
            }
            self.b.vertex(&Plain(p));
            self.b.multipliers(c);
            self.b.lambda.iter_mut().for_each(|l| *l = l.max(0.0));
            self.cols.activities(&self.b.y);
            // Most violated constraint outside the basis (Dantzig), or the first violated one once
            // degenerate pivots pile up (Bland's rule, which cannot cycle).
            let bland = degenerate > 2 * n;
            let activity = &self.cols.activity;
            let entering = self.b.most_violated(FEASIBILITY_TOL, bland, |k| {
                violation_from(p, k, activity, &self.b.y)
            });
            let Some(k) = entering else {
                status = LpStatus::Optimal;
                break;
            };
            // w = A_W⁻ᵀ a_k; leave the basis constraint with the smallest ratio λ_r / w_r, w_r > 0.
            constraint(p, k, &mut self.b.a_k);
            self.b.transformed_row();
            let mut leave: Option<usize> = None;
            let mut best = f64::INFINITY;
            for r in 0..n {
                if self.b.w[r] > PIVOT_TOL {
                    let t = self.b.lambda[r] / self.b.w[r];
                    // Bland: among (near-)ties, the constraint with the smallest index leaves.
                    let tie = bland
                        && leave.is_some_and(|l| {
                            t <= best * (1.0 + 1e-12) + 1e-300 && self.b.basis[r] < self.b.basis[l]
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
                    let kr = self.b.basis[r];
                    if kr < m {
                        dual[kr] = (-self.b.w[r]).max(0.0);
                    }
                }
                primal.copy_from_slice(&self.b.y);
                return LpStatus::Infeasible;
            };
            self.b.replace(r, k);
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
        if !self.b.invert(&Plain(p)) {
            return None;
        }
        self.b.vertex(&Plain(p));
        self.cols.load(p);
        self.cols.activities(&self.b.y);
        let activity = &self.cols.activity;
        if (0..m + 2 * n)
            .any(|k| !self.b.in_basis[k] && violation_from(p, k, activity, &self.b.y) > WARM_TOL)
        {
            return None;
        }
        let mut since_refactor = 0;
        let mut degenerate = 0usize;
        let max_pivots = 10 * (n + m) + 50;
        for _ in 0..max_pivots {
            if since_refactor >= REFACTOR_EVERY {
                if !self.b.invert(&Plain(p)) {
                    return None;
                }
                since_refactor = 0;
                self.b.vertex(&Plain(p));
            }
            self.b.multipliers(c);
            let bland = degenerate > 2 * n;
            // Leave the constraint with the most negative multiplier (Bland: the first negative).
            let mut leave = None;
            let mut most = -FEASIBILITY_TOL;
            for r in 0..n {
                if self.b.lambda[r] < most
                    || (bland && self.b.lambda[r] < -FEASIBILITY_TOL && leave.is_none())
                {
                    most = self.b.lambda[r];
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
                self.b.a_w[j] = -self.b.inv[j * n + r];
            }
            let mut enter = None;
            let mut best = f64::INFINITY;
            self.cols.alongs(&self.b.a_w[..n]);
            self.cols.activities(&self.b.y);
            for k in 0..m + 2 * n {
                if self.b.in_basis[k] {
                    continue;
                }
                let ad = if k < m {
                    self.cols.along[k]
                } else {
                    along(p, k, &self.b.a_w[..n])
                };
                if ad > PIVOT_TOL {
                    let slack = if k < m {
                        -(self.cols.activity[k] - p.rhs(k))
                    } else {
                        -violation_unscaled(p, k, &self.b.y)
                    };
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
                self.b.y[j] += best * self.b.a_w[j];
            }
            constraint(p, k, &mut self.b.a_k);
            self.b.transformed_row();
            if self.b.w[r].abs() < PIVOT_TOL {
                return None;
            }
            self.b.replace(r, k);
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

    fn forget(&mut self) {
        self.warm = None;
        self.large.forget();
    }

    /// The large engine's remembered bases (the small one remembers none).
    fn memory(&self) -> LpMemory {
        self.large.memory()
    }

    fn restore(&mut self, memory: &LpMemory) {
        self.warm = None;
        self.large.restore(memory);
    }

    /// The small engine walks on from the previous objective's optimum; the large one
    /// (the scaled simplex) remembers a basis per objective, which skipped solves would leave
    /// stale.
    fn skips_attained_bounds(&self, dim: usize) -> bool {
        dim <= SMALL_DIM
    }

    fn minimize(
        &mut self,
        p: &Polyhedron,
        c: &[f64],
        dual: &mut [f64],
        primal: &mut [f64],
    ) -> LpStatus {
        let n = p.dim();
        let status = if n > SMALL_DIM {
            self.large.minimize(p, c, dual, primal)
        } else {
            self.minimize_small(p, c, dual, primal)
        };
        self.last_pivots = if n > SMALL_DIM {
            self.large.pivots()
        } else {
            self.b.pivots
        };
        status
    }
}
