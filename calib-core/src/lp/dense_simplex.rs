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
//! * **Remembered bases** (first choice for a unit objective `±y_j`): the dual simplex from the
//!   basis that was last optimal for the same objective, its rows found again by their tags, when
//!   it is still dual feasible. Each Newton step of a contraction solves the same `2n` objectives
//!   over a polyhedron that moved a little: on the paper's sweep (Gough leg, 84 rows) this took
//!   the pivots from 6,125 to 4,859 per 128 boxes. [`LpBackend::forget`] and
//!   [`LpBackend::restore`] drop them, so that a box's answers depend only on the box.
//!
//! Both switch to Bland's rule after `2n` degenerate pivots (no cycling). `A_W⁻¹` is updated by the
//! Sherman–Morrison formula at each basis change (`n²` flops) and recomputed by Gauss–Jordan
//! elimination with partial pivoting every [`REFACTOR_EVERY`] pivots and at each start. All buffers
//! are reused: no allocation after the first call of a size.

use super::basis::{Basis, Constraints};
use super::scaled_simplex::unit_objective_slot;
use super::scaled_simplex::ScaledSimplex;
use super::{LpBackend, LpMemory, LpStatus, Polyhedron, Remembered};

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
    /// Per unit objective `±y_j` (slot `2j`, `2j + 1`), its last optimal basis ([`Slots`]).
    slots: Slots,
}

/// The last optimal basis of each unit objective `±y_j`, rows by their tags: a contraction solves
/// the same `2n` objectives at every Newton step over a polyhedron that moved a little, so the
/// basis that was optimal for `min y_j` at the previous step is usually still dual feasible and
/// a few dual pivots from optimal, where the walk from the previous objective's optimum (the
/// other end of the polytope for `max y_j` after `min y_j`) or from a box corner takes many.
/// Flat buffers, reused: no allocation once sized.
#[derive(Clone, Debug, Default)]
struct Slots {
    /// `n` entries per slot.
    bases: Vec<Remembered>,
    /// Per slot, whether `bases` holds one.
    valid: Vec<bool>,
}

impl Slots {
    fn clear(&mut self) {
        self.valid.iter_mut().for_each(|v| *v = false);
    }

    fn get(&self, slot: usize, n: usize) -> Option<&[Remembered]> {
        (*self.valid.get(slot)?).then(|| &self.bases[slot * n..(slot + 1) * n])
    }

    fn store(&mut self, slot: usize, n: usize, basis: &[usize], p: &Polyhedron) {
        let m = p.rows();
        if self.valid.len() != 2 * n || self.bases.len() != 2 * n * n {
            self.valid.clear();
            self.valid.resize(2 * n, false);
            self.bases.clear();
            self.bases.resize(2 * n * n, Remembered::Bound(0));
        }
        for (e, &k) in self.bases[slot * n..(slot + 1) * n].iter_mut().zip(basis) {
            *e = if k < m {
                Remembered::Row(p.tag(k))
            } else {
                Remembered::Bound(k - m)
            };
        }
        self.valid[slot] = true;
    }
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
    /// `row.iter().zip(v).map(|(a, v)| a * v).sum()`, up to the sign of a zero sum, which no
    /// comparison sees). Rows go [`ROWS_AT_ONCE`] at a time, their sums held in registers across
    /// the columns: one store per row instead of one load and store per row and column.
    fn products(g: &[f64], v: &[f64], out: &mut [f64]) {
        let m = out.len();
        if m == 0 || v.is_empty() {
            out.iter_mut().for_each(|o| *o = 0.0);
            return;
        }
        let mut chunks = out.chunks_exact_mut(ROWS_AT_ONCE);
        for (c, chunk) in (&mut chunks).enumerate() {
            let i = c * ROWS_AT_ONCE;
            let mut acc = [0.0; ROWS_AT_ONCE];
            for (a, &g) in acc.iter_mut().zip(&g[i..i + ROWS_AT_ONCE]) {
                *a = g * v[0];
            }
            for (j, &vj) in v.iter().enumerate().skip(1) {
                let col = &g[j * m + i..j * m + i + ROWS_AT_ONCE];
                for (a, &g) in acc.iter_mut().zip(col) {
                    *a += g * vj;
                }
            }
            chunk.copy_from_slice(&acc);
        }
        let done = m - chunks.into_remainder().len();
        for i in done..m {
            let mut sum = g[i] * v[0];
            for (j, &vj) in v.iter().enumerate().skip(1) {
                sum += g[j * m + i] * vj;
            }
            out[i] = sum;
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

/// Rows whose products [`Columns::products`] computes together.
const ROWS_AT_ONCE: usize = 8;

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
/// A remembered basis whose multipliers are all above `-DUAL_TOL` starts the dual simplex (the
/// loop clips them at 0; the safe bound makes any multipliers rigorous).
const DUAL_TOL: f64 = 1e-12;
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
        let slot = unit_objective_slot(c).filter(|&s| s < 2 * n);
        if let Some(slot) = slot {
            if let Some(status) = self.dual_from_remembered(p, c, slot, dual, primal) {
                self.finish(p, Some(slot), status);
                return status;
            }
            dual.iter_mut().for_each(|v| *v = 0.0);
        }
        if self.warm == Some(p.generation()) && self.b.in_basis.len() == p.rows() + 2 * n {
            if let Some(status) = self.primal_simplex(p, c, dual, primal) {
                self.finish(p, slot, status);
                return status;
            }
            dual.iter_mut().for_each(|v| *v = 0.0);
        }
        let status = self.dual_simplex(p, c, dual, primal);
        self.finish(p, slot, status);
        status
    }

    /// After a solve: an optimal basis warm-starts the next solve on this polyhedron and is
    /// remembered for its objective's slot.
    fn finish(&mut self, p: &Polyhedron, slot: Option<usize>, status: LpStatus) {
        self.warm = (status == LpStatus::Optimal).then_some(p.generation());
        if let (Some(slot), LpStatus::Optimal) = (slot, status) {
            self.slots.store(slot, p.dim(), &self.b.basis, p);
        }
    }

    /// The dual simplex from the basis remembered for objective `slot`, its rows found again by
    /// their tags; `None` (nothing written but the basis) when there is none, a row is gone, the
    /// basis is singular or not dual feasible for `c` (the caller then starts as before).
    fn dual_from_remembered(
        &mut self,
        p: &Polyhedron,
        c: &[f64],
        slot: usize,
        dual: &mut [f64],
        primal: &mut [f64],
    ) -> Option<LpStatus> {
        let (n, m) = (p.dim(), p.rows());
        let stored = self.slots.get(slot, n)?;
        for (r, entry) in stored.iter().enumerate() {
            self.b.basis[r] = match *entry {
                Remembered::Row(tag) => p.find_tag(tag)?,
                Remembered::Bound(b) if b < 2 * n => m + b,
                Remembered::Bound(_) => return None,
            };
        }
        self.b.set_mask(m + 2 * n);
        if self.b.in_basis.iter().filter(|&&k| k).count() != n || !self.b.invert(&Plain(p)) {
            return None;
        }
        self.b.multipliers(c);
        if self.b.lambda.iter().any(|&l| l < -DUAL_TOL || l.is_nan()) {
            return None;
        }
        Some(self.dual_loop(p, c, dual, primal, 0))
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
        self.slots.clear();
        self.large.forget();
    }

    /// The large engine's remembered bases (the small one keeps its own within a contraction).
    fn memory(&self) -> LpMemory {
        self.large.memory()
    }

    fn restore(&mut self, memory: &LpMemory) {
        self.warm = None;
        self.slots.clear();
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lp::{proves_infeasible, safe_lower_bound, ClarabelLp};
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    /// A contraction-like sequence in 7 variables: 21 groups of 4 rows `a·y <= 1` (so `y = 0` is
    /// feasible), every step jittering each row a little and shrinking the box, some steps
    /// dropping a group's last row (the tags find the others again).
    fn sequence(seed: u64, steps: usize) -> Vec<Polyhedron> {
        let n = 7;
        let mut rng = StdRng::seed_from_u64(seed);
        let rows: Vec<Vec<f64>> = (0..84)
            .map(|_| (0..n).map(|_| rng.random_range(-1.0..1.0)).collect())
            .collect();
        let mut width = 2.0;
        (0..steps)
            .map(|step| {
                let mut p = Polyhedron::default();
                p.reset(&vec![-width; n], &vec![0.8 * width; n]);
                for g in 0..21 {
                    p.begin_group(g);
                    let count = if step % 2 == 1 && g % 5 == 0 { 3 } else { 4 };
                    for a in &rows[4 * g as usize..4 * g as usize + count] {
                        let jitter: Vec<f64> = a
                            .iter()
                            .map(|v| v * (1.0 + 0.02 * rng.random_range(-1.0..1.0)))
                            .collect();
                        p.push_row(&jitter, 1.0);
                    }
                }
                width *= 0.85;
                p
            })
            .collect()
    }

    /// Min and max of every `y_j` over `p` as the contraction runs them (each bound tightened at
    /// once, so later LPs see a smaller box); returns the safe bounds and the pivots.
    fn contract_once(engine: &mut DenseSimplex, p: &mut Polyhedron) -> (Vec<f64>, usize) {
        let n = p.dim();
        let (mut dual, mut y) = (vec![0.0; p.rows()], vec![0.0; n]);
        let (mut out, mut pivots) = (Vec::new(), 0);
        for slot in 0..2 * n {
            let (j, sense) = (slot / 2, if slot % 2 == 0 { 1.0 } else { -1.0 });
            let mut c = vec![0.0; n];
            c[j] = sense;
            let status = engine.minimize(p, &c, &mut dual, &mut y);
            assert_eq!(status, LpStatus::Optimal, "slot {slot}");
            pivots += engine.last_pivots;
            let bound = safe_lower_bound(p, &c, &dual);
            // Sound: y = 0 is feasible.
            assert!(
                bound <= 0.0,
                "slot {slot}: bound {bound} cuts the feasible 0"
            );
            let (lo, hi) = (p.lo()[j], p.hi()[j]);
            if sense > 0.0 {
                p.set_bounds(j, lo.max(bound), hi);
            } else {
                p.set_bounds(j, lo, hi.min(-bound));
            }
            out.push(bound);
        }
        (out, pivots)
    }

    /// The remembered bases (the dual simplex from each objective's last optimal basis) reach
    /// the bounds a cold engine and an interior-point solver reach, in fewer pivots.
    #[test]
    fn remembered_bases_reach_the_cold_bounds_in_fewer_pivots() {
        let (mut warm_pivots, mut cold_pivots) = (0, 0);
        for seed in 0..4 {
            let polys = sequence(seed, 6);
            let mut warm = DenseSimplex::default();
            for (step, p) in polys.iter().enumerate() {
                let (w, wp) = contract_once(&mut warm, &mut p.clone());
                // The cold reference: a fresh engine per LP, on the same shrinking boxes.
                let mut q = p.clone();
                let n = q.dim();
                let mut cp = 0;
                for (slot, &bound) in w.iter().enumerate() {
                    let (j, sense) = (slot / 2, if slot % 2 == 0 { 1.0 } else { -1.0 });
                    let mut c = vec![0.0; n];
                    c[j] = sense;
                    let (mut dual, mut y) = (vec![0.0; q.rows()], vec![0.0; n]);
                    let mut cold = DenseSimplex::default();
                    assert_eq!(cold.minimize(&q, &c, &mut dual, &mut y), LpStatus::Optimal);
                    cp += cold.last_pivots;
                    let reference = safe_lower_bound(&q, &c, &dual);
                    let mut ipm = ClarabelLp::default();
                    ipm.minimize(&q, &c, &mut dual, &mut y);
                    let ipm_bound = safe_lower_bound(&q, &c, &dual);
                    for other in [reference, ipm_bound] {
                        assert!(
                            (bound - other).abs() <= 1e-7 * (1.0 + other.abs()),
                            "seed {seed} step {step} slot {slot}: {bound} vs {other}"
                        );
                    }
                    // The same tightening as the warm run (its bound: they agree to 1e-7).
                    let (lo, hi) = (q.lo()[j], q.hi()[j]);
                    if sense > 0.0 {
                        q.set_bounds(j, lo.max(bound), hi);
                    } else {
                        q.set_bounds(j, lo, hi.min(-bound));
                    }
                }
                if step > 0 {
                    warm_pivots += wp;
                    cold_pivots += cp;
                }
            }
        }
        assert!(
            2 * warm_pivots < cold_pivots,
            "{warm_pivots} pivots warm, {cold_pivots} cold"
        );
    }

    /// A remembered basis on an empty polyhedron: the engine still reports infeasibility with a
    /// Farkas ray that checks, and after `forget` the next solves are cold again (the same
    /// pivots as a fresh engine's).
    #[test]
    fn remembered_bases_prove_emptiness_and_are_forgotten() {
        let polys = sequence(9, 2);
        let mut engine = DenseSimplex::default();
        contract_once(&mut engine, &mut polys[0].clone());
        // The next step's rows with one more that no point of the box satisfies.
        let mut empty = polys[1].clone();
        empty.begin_group(30);
        let mut row = vec![0.0; 7];
        row[0] = -1.0;
        empty.push_row(&row, -10.0);
        let (mut dual, mut y) = (vec![0.0; empty.rows()], vec![0.0; 7]);
        let mut c = vec![0.0; 7];
        c[3] = -1.0;
        assert_eq!(
            engine.minimize(&empty, &c, &mut dual, &mut y),
            LpStatus::Infeasible
        );
        assert!(proves_infeasible(&empty, &dual, &[0.0; 7]));
        engine.forget();
        let mut fresh = DenseSimplex::default();
        let (a, ap) = contract_once(&mut engine, &mut polys[1].clone());
        let (b, bp) = contract_once(&mut fresh, &mut polys[1].clone());
        assert_eq!((a, ap), (b, bp));
    }
}
