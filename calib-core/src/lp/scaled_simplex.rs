//! The simplex engine for LPs of many variables (long kinematic chains: 27 and more parameters,
//! thousands of rows), used by [`super::DenseSimplex`] above [`super::dense_simplex::SMALL_DIM`]
//! variables. The same two walks as [`super::DenseSimplex`] (cold dual simplex from the box corner,
//! warm primal simplex from the previous optimum), made sturdy for what breaks them there:
//!
//! * **Units.** Millimetres and radians differ by orders of magnitude, so pivot sizes and
//!   violations are not comparable across variables. The engine works on an exactly rescaled copy
//!   ([`Scaled`]: columns to the box, rows to unit size, by powers of two).
//! * **Near ties.** Harris ratio tests take the largest pivot among ratios within a tolerance of the
//!   smallest, so the basis stays well conditioned.
//! * **Degeneracy.** With thousands of nearly parallel rows and a one-coordinate objective, most
//!   multipliers are zero and the plain walks stall for thousands of pivots (measured: 52 of 54 LPs
//!   failed on the arm's late polyhedra). After `2n` degenerate pivots in a row the primal walk
//!   gives up for the dual simplex, and the dual simplex shifts its objective once so that no
//!   multiplier is zero ([`COST_PERTURBATION`]), then falls back to Bland's rule.
//! * **Sequences of similar LPs.** The contraction solves the same `2n` objectives (`±y_j`) over a
//!   sequence of polyhedra that change little: the steps of a fixed point, the boxes of a hull.
//!   The engine remembers the optimal basis of each such objective, its rows by their tags
//!   ([`Polyhedron::begin_group`]: configuration and position, so that a configuration gaining or
//!   losing a row does not shift the others), and starts the next solve of that objective there:
//!   the dual simplex from it when it is still dual feasible, else the dual simplex on an
//!   objective shifted to make it so, then the primal simplex with the true objective from the
//!   vertex reached (measured on the built-in arm: 10-30 pivots instead of ~300).
//!
//! The answers are hints: [`super::safe_lower_bound`] checks the multipliers against the true rows
//! and objective.

use super::basis::{Basis, Constraints};
use super::polyhedron::power_of_two_scale;
use super::{LpMemory, LpStatus, Polyhedron, Remembered};

/// The engine (see the module documentation).
#[derive(Clone, Debug, Default)]
pub(super) struct ScaledSimplex {
    b: Basis,
    /// The objective in scaled coordinates (perturbed when the dual simplex stalls, shifted
    /// when a remembered basis is not dual feasible).
    c: Vec<f64>,
    /// The objective in scaled coordinates, as given.
    c_true: Vec<f64>,
    /// Per constraint, the primal ratio test's step (reused buffer; infinite where the edge does
    /// not approach the constraint).
    ratio: Vec<f64>,
    /// Per constraint, the primal simplex's slack `b_k - a_k·y` at the current vertex and
    /// `a_k·d` along the current edge (the pivot of a finite ratio): slacks follow the walk
    /// (`s_k -= t a_k·d`) instead of a second product per row and pivot, and are recomputed at
    /// every refactorisation.
    slack: Vec<f64>,
    along: Vec<f64>,
    /// The edge direction over the live columns.
    live_direction: Vec<f64>,
    /// The dual simplex's vertex over the live columns, for its pricing.
    live_vertex: Vec<f64>,
    scaled: Scaled,
    /// The polyhedron generation of the last optimal solve (its basis can warm-start the next).
    warm: Option<u64>,
    /// Per unit objective ([`unit_objective_slot`]), the last optimal basis: the contraction solves the same `2n` objectives over a sequence of
    /// similar polyhedra (fixed-point steps, the hull's boxes), where the previous optimum is
    /// usually dual feasible and a few pivots from the new one.
    memory: Vec<Option<Vec<Remembered>>>,
    /// The basis set aside while a remembered one is tried.
    saved: Vec<usize>,
}

/// The polyhedron in scaled coordinates `z_j = y_j / s_j`, each `s_j` the power of two at or above
/// the box's magnitude in `y_j` (so that every `z_j` lies in `[-1, 1]`), with every row rescaled by
/// a power of two to a largest coefficient in `[0.5, 1)`. Both scalings are exact, so the scaled
/// problem is the same LP; they make pivot sizes, violations and multipliers comparable across
/// variables of different units (millimetres and radians). Built once per polyhedron generation.
#[derive(Clone, Debug, Default)]
struct Scaled {
    generation: Option<u64>,
    n: usize,
    /// Column scales `s_j`.
    col: Vec<f64>,
    /// Row scales `r_i`: scaled row `i` is `r_i` times row `i` of `G` in `z`.
    row_scale: Vec<f64>,
    rows: Vec<f64>,
    rhs: Vec<f64>,
    /// Frozen variables: their bound constraints never leave a basis (no row involves them).
    frozen: Vec<bool>,
    /// The other columns, and the rows restricted to them (a frozen column is zero in every
    /// row): the primal ratio test's products `a_k·d` run over these alone.
    live: Vec<usize>,
    compact: Vec<f64>,
}

impl Scaled {
    fn prepare(&mut self, p: &Polyhedron) {
        if self.generation == Some(p.generation()) && self.n == p.dim() {
            return;
        }
        let (n, m) = (p.dim(), p.rows());
        self.generation = Some(p.generation());
        self.n = n;
        self.col.clear();
        self.col.extend((0..n).map(|j| {
            let mag = p.lo()[j].abs().max(p.hi()[j].abs());
            if mag > 0.0 {
                1.0 / power_of_two_scale(mag)
            } else {
                1.0
            }
        }));
        self.frozen.clear();
        self.frozen.extend((0..n).map(|j| p.is_frozen(j)));
        self.rows.clear();
        self.rhs.clear();
        self.row_scale.clear();
        for i in 0..m {
            let start = self.rows.len();
            self.rows
                .extend(p.row(i).iter().zip(&self.col).map(|(a, s)| a * s));
            let max = self.rows[start..]
                .iter()
                .fold(0.0f64, |acc, v| acc.max(v.abs()));
            let r = if max > 0.0 {
                power_of_two_scale(max)
            } else {
                1.0
            };
            self.rows[start..].iter_mut().for_each(|v| *v *= r);
            self.rhs.push(p.rhs(i) * r);
            self.row_scale.push(r);
        }
        self.live.clear();
        self.live.extend((0..n).filter(|&j| !self.frozen[j]));
        self.compact.clear();
        for i in 0..m {
            let row = &self.rows[i * n..(i + 1) * n];
            self.compact.extend(self.live.iter().map(|&j| row[j]));
        }
    }

    /// Row `i` over the live columns.
    fn compact_row(&self, i: usize) -> &[f64] {
        let w = self.live.len();
        &self.compact[i * w..(i + 1) * w]
    }

    fn row(&self, i: usize) -> &[f64] {
        &self.rows[i * self.n..(i + 1) * self.n]
    }

    fn lo(&self, p: &Polyhedron, j: usize) -> f64 {
        p.lo()[j] / self.col[j]
    }

    fn hi(&self, p: &Polyhedron, j: usize) -> f64 {
        p.hi()[j] / self.col[j]
    }

    /// Whether constraint `k` is a bound of a frozen variable.
    fn pinned(&self, k: usize) -> bool {
        let m = self.rhs.len();
        k >= m && self.frozen[(k - m) / 2]
    }
}

/// The scaled constraints of `p`.
struct View<'a> {
    s: &'a Scaled,
    p: &'a Polyhedron,
}

impl Constraints for View<'_> {
    fn constraint(&self, k: usize, a: &mut [f64]) -> f64 {
        constraint(self.s, self.p, k, a)
    }

    fn rhs(&self, k: usize) -> f64 {
        rhs(self.s, self.p, k)
    }
}

/// When the dual simplex stalls (more than `2n` degenerate pivots in a row), the objective is
/// shifted so that every multiplier of the current basis grows by between 0.5 and 1.5 times this
/// (relative to the largest objective coefficient): no multiplier is zero any more, so the walk
/// moves again. The safe bound uses the true objective, so the bound loses at most this relative
/// amount per variable, and only in the solves that stalled.
const COST_PERTURBATION: f64 = 1e-7;

/// A deterministic pseudo-random number in `[0, 1)` from an index (SplitMix64).
fn unit_hash(i: u64) -> f64 {
    let mut z = i.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

/// Violations below this (rows and variables are scaled to magnitude ~1) are accepted as
/// satisfied; the safe bound makes the result rigorous anyway.
const FEASIBILITY_TOL: f64 = 1e-12;
/// A warm-start vertex may violate constraints by at most this much.
const WARM_TOL: f64 = 1e-9;
/// A remembered basis starts the dual simplex if no multiplier is below `-DUAL_START_TOL` times
/// the largest objective coefficient.
const DUAL_START_TOL: f64 = 1e-9;
/// Pivot elements below this are not used in ratio tests.
const PIVOT_TOL: f64 = 1e-9;
/// Harris ratio tests: among the candidates within this of the smallest ratio's bound, the largest
/// pivot is taken (a stable basis rather than the exact minimum).
const HARRIS_TOL: f64 = 1e-10;
/// A dual simplex pivot makes progress when it raises the objective by more than this, relative to
/// `Σ_j |c_j y_j|`.
const PROGRESS_TOL: f64 = 1e-13;
/// The dual simplex gives up (the LP failed: its answer is not used) after this many pivots per
/// variable without progress, perturbation and Bland's rule notwithstanding.
const STALL_PIVOTS_PER_VARIABLE: usize = 20;
/// Recompute `A_W⁻¹` from scratch after this many rank-one updates.
const REFACTOR_EVERY: usize = 16;

/// The coefficient row and right-hand side of constraint `k` (rows first, then the bounds), scaled.
#[inline(always)]
fn constraint(s: &Scaled, p: &Polyhedron, k: usize, a: &mut [f64]) -> f64 {
    let m = s.rhs.len();
    if k < m {
        a.copy_from_slice(s.row(k));
        s.rhs[k]
    } else {
        let j = (k - m) / 2;
        a.iter_mut().for_each(|v| *v = 0.0);
        if (k - m) % 2 == 0 {
            a[j] = 1.0;
            s.hi(p, j)
        } else {
            a[j] = -1.0;
            -s.lo(p, j)
        }
    }
}

/// `b_k`, scaled.
#[inline(always)]
fn rhs(s: &Scaled, p: &Polyhedron, k: usize) -> f64 {
    let m = s.rhs.len();
    if k < m {
        s.rhs[k]
    } else if (k - m) % 2 == 0 {
        s.hi(p, (k - m) / 2)
    } else {
        -s.lo(p, (k - m) / 2)
    }
}

/// `a · b` with four independent accumulators (the pricing loops' inner product: the compiler can
/// keep them in vector registers, which a single running sum forbids).
#[inline(always)]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0f64; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for i in 0..4 {
            acc[i] += x[i] * y[i];
        }
    }
    let tail: f64 = ra.iter().zip(rb).map(|(x, y)| x * y).sum();
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + tail
}

/// `a_k · z - b_k`, scaled.
#[inline(always)]
fn violation(s: &Scaled, p: &Polyhedron, k: usize, z: &[f64]) -> f64 {
    let m = s.rhs.len();
    if k < m {
        dot(s.row(k), z) - s.rhs[k]
    } else {
        let j = (k - m) / 2;
        if (k - m) % 2 == 0 {
            z[j] - s.hi(p, j)
        } else {
            s.lo(p, j) - z[j]
        }
    }
}

/// [`violation`] with the rows' products over the live columns (`z_live`: `z` there), the
/// dual simplex's pricing: every row is zero in the frozen columns.
#[inline(always)]
fn live_violation(s: &Scaled, p: &Polyhedron, k: usize, z: &[f64], z_live: &[f64]) -> f64 {
    if k < s.rhs.len() {
        dot(s.compact_row(k), z_live) - s.rhs[k]
    } else {
        violation(s, p, k, z)
    }
}

/// `a_k · d`, scaled.
#[inline(always)]
fn along(s: &Scaled, k: usize, d: &[f64]) -> f64 {
    let m = s.rhs.len();
    if k < m {
        dot(s.row(k), d)
    } else if (k - m) % 2 == 0 {
        d[(k - m) / 2]
    } else {
        -d[(k - m) / 2]
    }
}

impl ScaledSimplex {
    /// Basis changes made by the last solve.
    pub(super) fn pivots(&self) -> usize {
        self.b.pivots
    }

    /// Writes the multipliers of the original rows (`λ_i r_i`) and the primal point in `y`.
    fn export(&self, m: usize, dual: &mut [f64], primal: &mut [f64]) {
        for (r, &k) in self.b.basis.iter().enumerate() {
            if k < m {
                dual[k] = self.b.lambda[r].max(0.0) * self.scaled.row_scale[k];
            }
        }
        for (j, p) in primal.iter_mut().enumerate() {
            *p = self.b.y[j] * self.scaled.col[j];
        }
    }

    /// The cold-start dual simplex (see the module documentation).
    fn dual_simplex(&mut self, p: &Polyhedron, dual: &mut [f64], primal: &mut [f64]) -> LpStatus {
        let (n, m) = (p.dim(), p.rows());
        for j in 0..n {
            self.b.basis[j] = m + 2 * j + usize::from(self.c[j] > 0.0);
        }
        self.b.set_mask(m + 2 * n);
        self.dual_walk(p, dual, primal)
    }

    /// Prepares the basis in `self.b.basis` (a remembered optimum of an earlier polyhedron) as a
    /// start for the dual simplex: `None` when it is no basis here (a repeated constraint, a
    /// frozen variable's bound missing, a singular matrix). Where its multipliers are negative
    /// (beyond rounding), the objective is shifted so that they become small positive numbers
    /// (cost shifting: `c ← c - A_Wᵀ δ` raises `λ_W` by `δ`); returns whether it was. Leaves
    /// `in_basis` and `inv` set for the basis.
    fn dual_start(&mut self, p: &Polyhedron) -> Option<bool> {
        let (n, m) = (p.dim(), p.rows());
        self.b.set_mask(m + 2 * n);
        let distinct = self.b.in_basis.iter().filter(|&&b| b).count() == n;
        let pins_kept = (0..n)
            .filter(|&j| self.scaled.frozen[j])
            .all(|j| self.b.in_basis[m + 2 * j] || self.b.in_basis[m + 2 * j + 1]);
        if !distinct || !pins_kept || !self.b.invert(&View { s: &self.scaled, p }) {
            return None;
        }
        self.b.multipliers(&self.c);
        let scale = self.c.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let mut shifted = false;
        for r in 0..n {
            let k = self.b.basis[r];
            if self.scaled.pinned(k) || self.b.lambda[r] >= -DUAL_START_TOL * scale {
                continue;
            }
            let delta = COST_PERTURBATION * scale * (0.5 + unit_hash(k as u64)) - self.b.lambda[r];
            constraint(&self.scaled, p, k, &mut self.b.a_k);
            for j in 0..n {
                self.c[j] -= delta * self.b.a_k[j];
            }
            shifted = true;
        }
        Some(shifted)
    }

    /// The solve from a remembered basis: the dual simplex (on the shifted objective when
    /// [`Self::dual_start`] shifted it), then, if the objective was shifted, the primal simplex
    /// with the true objective from the optimal vertex found (primal feasible). `None` when this
    /// path gave no answer (the caller tries the others).
    fn solve_from_remembered(
        &mut self,
        p: &Polyhedron,
        dual: &mut [f64],
        primal: &mut [f64],
    ) -> Option<LpStatus> {
        let shifted = self.dual_start(p)?;
        let status = self.dual_walk(p, dual, primal);
        match status {
            LpStatus::Failed => None,
            // A Farkas ray does not depend on the objective.
            LpStatus::Infeasible => Some(status),
            LpStatus::Optimal if !shifted => Some(status),
            LpStatus::Optimal => {
                self.c.copy_from_slice(&self.c_true);
                dual.iter_mut().for_each(|v| *v = 0.0);
                let status = self.primal_simplex(p, dual, primal);
                if status.is_none() {
                    dual.iter_mut().for_each(|v| *v = 0.0);
                }
                status
            }
        }
    }

    /// The dual simplex from the dual feasible basis in `self.b` (see the module documentation).
    fn dual_walk(&mut self, p: &Polyhedron, dual: &mut [f64], primal: &mut [f64]) -> LpStatus {
        let (n, m) = (p.dim(), p.rows());
        let mut since_refactor = REFACTOR_EVERY;
        let mut degenerate = 0usize;
        let mut best = f64::NEG_INFINITY;
        let max_pivots = 10 * (n + m) + 50;
        let mut status = LpStatus::Failed;
        let mut perturbed = false;
        for _ in 0..max_pivots {
            if since_refactor >= REFACTOR_EVERY {
                if !self.b.invert(&View { s: &self.scaled, p }) {
                    break;
                }
                since_refactor = 0;
            }
            self.b.vertex(&View { s: &self.scaled, p });
            self.b.multipliers(&self.c);
            self.b.lambda.iter_mut().for_each(|l| *l = l.max(0.0));
            // Progress is the objective at the vertex (the dual objective), which the dual simplex
            // never lowers: pivots that do not raise it noticeably are degenerate, whatever
            // their ratio (tiny steps can cycle as surely as zero ones).
            let (objective, size) = self.objective_at_vertex(n);
            if objective > best + PROGRESS_TOL * size {
                best = objective;
                degenerate = 0;
            } else {
                degenerate += 1;
            }
            if degenerate > 2 * n && !perturbed {
                self.perturb_cost(p);
                perturbed = true;
                degenerate = 0;
                best = f64::NEG_INFINITY;
                continue;
            }
            if degenerate > STALL_PIVOTS_PER_VARIABLE * n {
                // Bland's rule is exact only in exact arithmetic: give up rather than cycle.
                break;
            }
            // Most violated constraint outside the basis (Dantzig), or the first violated one once
            // degenerate pivots pile up even after the perturbation (Bland's rule: no cycling).
            let bland = degenerate > 2 * n;
            let Some(k) = self.entering_dual(p, bland) else {
                status = LpStatus::Optimal;
                break;
            };
            let Some(r) = self.leaving_dual(p, k, bland) else {
                self.export_farkas_ray(p, k, dual);
                self.export_primal(primal);
                return LpStatus::Infeasible;
            };
            self.b.replace(r, k);
            since_refactor += 1;
        }
        self.export(m, dual, primal);
        status
    }

    /// The objective at the vertex `y` (the dual objective) and the sum of its terms'
    /// magnitudes, `(Σ_j c_j y_j, Σ_j |c_j y_j|)`: what the dual walk measures progress by.
    fn objective_at_vertex(&self, n: usize) -> (f64, f64) {
        (0..n).fold((0.0, 0.0), |(o, s), j| {
            let t = self.c[j] * self.b.y[j];
            (o + t, s + t.abs())
        })
    }

    /// The dual simplex's entering constraint: the most violated one outside the basis
    /// (Dantzig), or the first violated one with `bland` (Bland's rule: no cycling); `None` at
    /// the optimum (no constraint violated).
    fn entering_dual(&mut self, p: &Polyhedron, bland: bool) -> Option<usize> {
        self.live_vertex.clear();
        self.live_vertex
            .extend(self.scaled.live.iter().map(|&j| self.b.y[j]));
        self.b.most_violated(FEASIBILITY_TOL, bland, |k| {
            live_violation(&self.scaled, p, k, &self.b.y, &self.live_vertex)
        })
    }

    /// The dual simplex's ratio test for entering constraint `k`: with `w = A_W⁻ᵀ a_k`, the basis
    /// constraint with the smallest ratio `λ_r / w_r`, `w_r > 0`, leaves (Harris: the largest
    /// `w_r` among the ratios within tolerance of the smallest; with `bland`, the smallest
    /// index). `None` when no `w_r` is positive: the LP is infeasible (`w` is then the Farkas
    /// ray, [`Self::export_farkas_ray`]).
    fn leaving_dual(&mut self, p: &Polyhedron, k: usize, bland: bool) -> Option<usize> {
        let n = p.dim();
        constraint(&self.scaled, p, k, &mut self.b.a_k);
        self.b.transformed_row();
        let eligible = |r: usize| self.b.w[r] > PIVOT_TOL && !self.scaled.pinned(self.b.basis[r]);
        let bound = (0..n)
            .filter(|&r| eligible(r))
            .map(|r| (self.b.lambda[r] + HARRIS_TOL) / self.b.w[r])
            .fold(f64::INFINITY, f64::min);
        let mut leave: Option<usize> = None;
        for r in (0..n).filter(|&r| eligible(r)) {
            if self.b.lambda[r] / self.b.w[r] > bound {
                continue;
            }
            let better = match leave {
                None => true,
                // Bland: the constraint with the smallest index leaves.
                Some(l) if bland => self.b.basis[r] < self.b.basis[l],
                Some(l) => self.b.w[r] > self.b.w[l],
            };
            if better {
                leave = Some(r);
            }
        }
        leave
    }

    /// The Farkas ray of an infeasible LP into `dual`, after [`Self::leaving_dual`] found no
    /// leaving constraint for `k`: `μ_k = 1`, `μ_W = -w` (`>= 0` up to rounding), in the original
    /// rows.
    fn export_farkas_ray(&self, p: &Polyhedron, k: usize, dual: &mut [f64]) {
        let (n, m) = (p.dim(), p.rows());
        dual.iter_mut().for_each(|v| *v = 0.0);
        if k < m {
            dual[k] = self.scaled.row_scale[k];
        }
        for r in 0..n {
            let kr = self.b.basis[r];
            if kr < m {
                dual[kr] = (-self.b.w[r]).max(0.0) * self.scaled.row_scale[kr];
            }
        }
    }

    /// `c ← c - A_Wᵀ δ`, `δ_r` pseudo-random in `[0.5, 1.5]·COST_PERTURBATION·max|c|` on the basis
    /// constraints that may leave: the multipliers `λ_W = -A_W⁻ᵀ c` grow by `δ`, so the basis stays
    /// dual feasible and no multiplier is zero (see [`COST_PERTURBATION`]).
    fn perturb_cost(&mut self, p: &Polyhedron) {
        let n = p.dim();
        let scale = COST_PERTURBATION * self.c.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        for r in 0..n {
            let k = self.b.basis[r];
            if self.scaled.pinned(k) {
                continue;
            }
            let delta = scale * (0.5 + unit_hash(k as u64));
            constraint(&self.scaled, p, k, &mut self.b.a_k);
            for j in 0..n {
                self.c[j] -= delta * self.b.a_k[j];
            }
        }
    }

    fn export_primal(&self, primal: &mut [f64]) {
        for (j, p) in primal.iter_mut().enumerate() {
            *p = self.b.y[j] * self.scaled.col[j];
        }
    }

    /// The warm-start primal simplex from the current basis; `None` if the basis is not a feasible
    /// vertex of `p` (the caller then runs the dual simplex).
    fn primal_simplex(
        &mut self,
        p: &Polyhedron,
        dual: &mut [f64],
        primal: &mut [f64],
    ) -> Option<LpStatus> {
        let (n, m) = (p.dim(), p.rows());
        if !self.b.invert(&View { s: &self.scaled, p }) {
            return None;
        }
        self.b.vertex(&View { s: &self.scaled, p });
        let total = m + 2 * n;
        self.slack.resize(total, 0.0);
        self.along.resize(total, 0.0);
        self.ratio.resize(total, f64::INFINITY);
        self.refresh_slacks(p);
        if (0..total).any(|k| !self.b.in_basis[k] && -self.slack[k] > WARM_TOL) {
            return None;
        }
        let mut since_refactor = 0;
        let mut degenerate = 0usize;
        let max_pivots = 10 * (n + m) + 50;
        for _ in 0..max_pivots {
            if since_refactor >= REFACTOR_EVERY {
                if !self.b.invert(&View { s: &self.scaled, p }) {
                    return None;
                }
                since_refactor = 0;
                self.b.vertex(&View { s: &self.scaled, p });
                self.refresh_slacks(p);
            }
            self.b.multipliers(&self.c);
            if degenerate > 2 * n {
                // Stalled at a degenerate vertex: the dual simplex (with its perturbation) is the
                // sturdier path.
                return None;
            }
            let Some(r) = self.leaving_primal(n) else {
                self.export(m, dual, primal);
                return Some(LpStatus::Optimal);
            };
            let (k, step) = self.entering_primal(p, r)?;
            degenerate = if step <= 1e-14 { degenerate + 1 } else { 0 };
            self.step_along_edge(n, step);
            self.pivot_primal(p, r, k)?;
            since_refactor += 1;
        }
        None
    }
}

impl ScaledSimplex {
    /// The primal simplex's leaving constraint: the basis constraint with the most negative
    /// multiplier (below `-FEASIBILITY_TOL`; pinned ones never leave). `None` at the optimum.
    fn leaving_primal(&self, n: usize) -> Option<usize> {
        let mut leave = None;
        let mut most = -FEASIBILITY_TOL;
        for r in 0..n {
            if self.scaled.pinned(self.b.basis[r]) {
                continue;
            }
            if self.b.lambda[r] < most {
                most = self.b.lambda[r];
                leave = Some(r);
            }
        }
        leave
    }

    /// The primal simplex's ratio test when basis constraint `r` leaves: along the edge
    /// `d = -A_W⁻¹ e_r` (kept in `b.a_w`; it keeps the other basis constraints active and moves
    /// inside constraint `r`, `c·d = λ_r < 0`), the entering constraint and the step to it.
    /// Harris: the largest `a_k·d` among the ratios within tolerance of the smallest (slacks
    /// relaxed by the tolerance). One pass computes every `a_k·d` (kept in `along`) and ratio;
    /// the second picks among them. `None` when no constraint bounds the edge.
    fn entering_primal(&mut self, p: &Polyhedron, r: usize) -> Option<(usize, f64)> {
        let (n, m) = (p.dim(), p.rows());
        let total = m + 2 * n;
        for j in 0..n {
            self.b.a_w[j] = -self.b.inv[j * n + r];
        }
        let mut bound = f64::INFINITY;
        self.live_direction.clear();
        self.live_direction
            .extend(self.scaled.live.iter().map(|&j| self.b.a_w[j]));
        for k in 0..total {
            self.ratio[k] = f64::INFINITY;
            self.along[k] = 0.0;
            if self.b.in_basis[k] {
                continue;
            }
            let ad = if k < m {
                dot(self.scaled.compact_row(k), &self.live_direction)
            } else {
                along(&self.scaled, k, &self.b.a_w[..n])
            };
            self.along[k] = ad;
            if ad > PIVOT_TOL {
                let slack = self.slack[k].max(0.0);
                self.ratio[k] = slack / ad;
                bound = bound.min((slack + HARRIS_TOL) / ad);
            }
        }
        let mut enter: Option<(usize, f64, f64)> = None;
        for k in 0..total {
            let (t, ad) = (self.ratio[k], self.along[k]);
            if t.is_finite() && t <= bound && enter.is_none_or(|(_, _, best)| ad > best) {
                enter = Some((k, t, ad));
            }
        }
        enter.map(|(k, step, _)| (k, step))
    }

    /// Moves the vertex `step` along the edge of [`Self::entering_primal`]: `y += t d`, and
    /// every slack `s_k -= t a_k·d`.
    fn step_along_edge(&mut self, n: usize, step: f64) {
        for j in 0..n {
            self.b.y[j] += step * self.b.a_w[j];
        }
        for (s, ad) in self.slack.iter_mut().zip(&self.along) {
            *s -= step * ad;
        }
    }

    /// Constraint `k` replaces basis constraint `r`, with the two slacks updated (the leaving
    /// one's recomputed, the entering one's now 0). `None` when the pivot `w_r` is too small to
    /// keep the basis well conditioned.
    fn pivot_primal(&mut self, p: &Polyhedron, r: usize, k: usize) -> Option<()> {
        constraint(&self.scaled, p, k, &mut self.b.a_k);
        self.b.transformed_row();
        if self.b.w[r].abs() < PIVOT_TOL {
            return None;
        }
        let leaving = self.b.basis[r];
        self.slack[leaving] = -violation(&self.scaled, p, leaving, &self.b.y);
        self.slack[k] = 0.0;
        self.b.replace(r, k);
        Some(())
    }

    /// Every constraint's slack `b_k - a_k·y` at the current vertex `y` (scaled).
    fn refresh_slacks(&mut self, p: &Polyhedron) {
        for (k, s) in self.slack.iter_mut().enumerate() {
            *s = -violation(&self.scaled, p, k, &self.b.y);
        }
    }

    /// Approximately solves `min c·y` over `p` (the contract of [`super::LpBackend::minimize`]).
    pub(super) fn minimize(
        &mut self,
        p: &Polyhedron,
        c: &[f64],
        dual: &mut [f64],
        primal: &mut [f64],
    ) -> LpStatus {
        let n = p.dim();
        self.b.resize(n);
        self.c.resize(n, 0.0);
        self.scaled.prepare(p);
        for j in 0..n {
            self.c[j] = c[j] * self.scaled.col[j];
        }
        self.c_true.clear();
        self.c_true.extend_from_slice(&self.c);
        dual.iter_mut().for_each(|v| *v = 0.0);
        self.b.pivots = 0;
        let m = p.rows();
        let total = m + 2 * n;
        let warm = self.warm == Some(p.generation()) && self.b.in_basis.len() == total;
        let slot = unit_objective_slot(c);
        if let Some(slot) = slot {
            if self.recall(p, slot) {
                if let Some(status) = self.solve_from_remembered(p, dual, primal) {
                    self.finish(p, slot, status);
                    return status;
                }
                self.c.copy_from_slice(&self.c_true);
                self.b.basis.copy_from_slice(&self.saved);
                // The basis before the recall is the previous solve's, maybe on a larger
                // polyhedron: only the warm start below reads it, and only when it is this one's.
                if warm {
                    self.b.set_mask(total);
                }
            }
        }
        if warm {
            if let Some(status) = self.primal_simplex(p, dual, primal) {
                self.finish(p, slot.unwrap_or(usize::MAX), status);
                return status;
            }
            dual.iter_mut().for_each(|v| *v = 0.0);
        }
        let status = self.dual_simplex(p, dual, primal);
        self.finish(p, slot.unwrap_or(usize::MAX), status);
        status
    }

    /// Forgets every remembered basis and the last optimum (see [`super::LpBackend::forget`]).
    pub(super) fn forget(&mut self) {
        self.warm = None;
        self.memory.iter_mut().for_each(|m| *m = None);
    }

    /// The remembered bases (see [`super::LpBackend::memory`]).
    pub(super) fn memory(&self) -> LpMemory {
        LpMemory {
            bases: self.memory.clone(),
        }
    }

    /// Forgets, then remembers `memory`'s bases (see [`super::LpBackend::restore`]).
    pub(super) fn restore(&mut self, memory: &LpMemory) {
        self.warm = None;
        self.memory.clone_from(&memory.bases);
    }

    /// Saves the current basis and loads the optimum remembered for objective `slot`, its rows
    /// found again by their tags; false (nothing changed) when there is none, or one of its rows
    /// is not in `p`.
    fn recall(&mut self, p: &Polyhedron, slot: usize) -> bool {
        let (n, m) = (p.dim(), p.rows());
        let Some(Some(stored)) = self.memory.get(slot) else {
            return false;
        };
        if stored.len() != n {
            return false;
        }
        self.saved.clear();
        self.saved.extend_from_slice(&self.b.basis);
        for (r, entry) in stored.iter().enumerate() {
            let k = match *entry {
                Remembered::Row(tag) => p.find_tag(tag),
                Remembered::Bound(b) => Some(m + b),
            };
            let Some(k) = k else {
                self.b.basis.copy_from_slice(&self.saved);
                return false;
            };
            self.b.basis[r] = k;
        }
        true
    }

    /// After a solve: an optimal basis warm-starts the next solve on this polyhedron and is
    /// remembered for its objective `slot` (when the objective is a unit vector).
    fn finish(&mut self, p: &Polyhedron, slot: usize, status: LpStatus) {
        self.warm = (status == LpStatus::Optimal).then_some(p.generation());
        if status != LpStatus::Optimal || slot == usize::MAX {
            return;
        }
        if self.memory.len() <= slot {
            self.memory.resize(slot + 1, None);
        }
        let m = p.rows();
        let entry = self.memory[slot].get_or_insert_with(Vec::new);
        entry.clear();
        entry.extend(self.b.basis.iter().map(|&k| {
            if k < m {
                Remembered::Row(p.tag(k))
            } else {
                Remembered::Bound(k - m)
            }
        }));
    }
}

/// `2j` for the objective `+e_j` (times a positive factor), `2j + 1` for `-e_j`, `None` for any
/// other objective.
pub(super) fn unit_objective_slot(c: &[f64]) -> Option<usize> {
    let mut nonzero = c.iter().enumerate().filter(|(_, v)| **v != 0.0);
    let (j, v) = nonzero.next()?;
    nonzero
        .next()
        .is_none()
        .then_some(2 * j + usize::from(*v < 0.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lp::{safe_lower_bound, ClarabelLp, LpBackend};
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    /// A contraction-like sequence: `groups` groups of rows `|a·y| <= 1` around a random centre,
    /// each step jittering every row a little, some groups losing or gaining a row, and the box
    /// shrinking.
    fn sequence(seed: u64, n: usize, groups: usize, steps: usize) -> Vec<Polyhedron> {
        let mut rng = StdRng::seed_from_u64(seed);
        let rows: Vec<Vec<f64>> = (0..groups * 6)
            .map(|_| (0..n).map(|_| rng.random_range(-1.0..1.0)).collect())
            .collect();
        let mut out = Vec::new();
        let mut width = 4.0;
        for step in 0..steps {
            let mut p = Polyhedron::default();
            p.reset(&vec![-width; n], &vec![width; n]);
            for g in 0..groups {
                p.begin_group(g as u32);
                // From the second step on, every third group has one row fewer.
                let count = if step > 0 && g % 3 == 0 { 5 } else { 6 };
                for a in &rows[g * 6..g * 6 + count] {
                    let jitter: Vec<f64> = a
                        .iter()
                        .map(|v| v * (1.0 + 0.01 * rng.random_range(-1.0..1.0)))
                        .collect();
                    p.push_row(&jitter, 1.0);
                    let neg: Vec<f64> = jitter.iter().map(|v| -v).collect();
                    p.push_row(&neg, 1.0);
                }
            }
            out.push(p);
            width *= 0.8;
        }
        out
    }

    /// The safe bound of every `±y_j` over `p` from `engine`, and its pivots.
    fn bounds(engine: &mut ScaledSimplex, p: &Polyhedron) -> (Vec<f64>, usize) {
        let n = p.dim();
        let (mut dual, mut primal) = (vec![0.0; p.rows()], vec![0.0; n]);
        let (mut out, mut pivots) = (Vec::new(), 0);
        for slot in 0..2 * n {
            let mut c = vec![0.0; n];
            c[slot / 2] = if slot % 2 == 0 { 1.0 } else { -1.0 };
            let status = engine.minimize(p, &c, &mut dual, &mut primal);
            assert_eq!(status, LpStatus::Optimal);
            pivots += engine.pivots();
            out.push(safe_lower_bound(p, &c, &dual));
        }
        (out, pivots)
    }

    #[test]
    fn remembered_bases_give_the_cold_optimum_in_fewer_pivots() {
        for seed in 0..3 {
            let polys = sequence(seed, 24, 40, 5);
            let mut warm = ScaledSimplex::default();
            let (mut warm_pivots, mut cold_pivots) = (0, 0);
            for (step, p) in polys.iter().enumerate() {
                let (w, wp) = bounds(&mut warm, p);
                let (c, cp) = bounds(&mut ScaledSimplex::default(), p);
                let mut reference = ClarabelLp::default();
                let n = p.dim();
                for (slot, (a, b)) in w.iter().zip(&c).enumerate() {
                    assert!(
                        (a - b).abs() <= 1e-7 * (1.0 + b.abs()),
                        "{seed} {step} {slot}"
                    );
                    if step + 1 < polys.len() {
                        continue;
                    }
                    // And both agree with an interior-point solver.
                    let mut obj = vec![0.0; n];
                    obj[slot / 2] = if slot % 2 == 0 { 1.0 } else { -1.0 };
                    let (mut dual, mut y) = (vec![0.0; p.rows()], vec![0.0; n]);
                    reference.minimize(p, &obj, &mut dual, &mut y);
                    let r = safe_lower_bound(p, &obj, &dual);
                    assert!(
                        (a - r).abs() <= 1e-5 * (1.0 + r.abs()),
                        "{a} vs clarabel {r}"
                    );
                }
                if step > 0 {
                    warm_pivots += wp;
                    cold_pivots += cp;
                }
            }
            assert!(
                2 * warm_pivots < cold_pivots,
                "seed {seed}: {warm_pivots} pivots warm, {cold_pivots} cold"
            );
        }
    }

    /// The bases one engine remembers, handed to a fresh engine ([`ScaledSimplex::memory`],
    /// [`ScaledSimplex::restore`], the hull's parent-to-half hand-over), start its solves exactly
    /// as the first engine's own memory does (the same pivots), reaching the cold bounds in fewer
    /// pivots; a restored empty memory forgets.
    #[test]
    fn handed_over_bases_start_another_engine_warm() {
        for seed in 0..3 {
            let polys = sequence(seed, 24, 40, 3);
            let mut parent = ScaledSimplex::default();
            bounds(&mut parent, &polys[0]);
            bounds(&mut parent, &polys[1]);
            let memory = parent.memory();
            assert!(!memory.is_empty());
            let mut child = ScaledSimplex::default();
            child.restore(&memory);
            assert_eq!(child.memory(), memory);
            let (handed, handed_pivots) = bounds(&mut child, &polys[2]);
            let (_, own_pivots) = bounds(&mut parent, &polys[2]);
            let (cold, cold_pivots) = bounds(&mut ScaledSimplex::default(), &polys[2]);
            for (a, b) in handed.iter().zip(&cold) {
                assert!(
                    (a - b).abs() <= 1e-7 * (1.0 + b.abs()),
                    "{seed}: {a} vs {b}"
                );
            }
            assert_eq!(handed_pivots, own_pivots, "seed {seed}");
            assert!(
                2 * handed_pivots < cold_pivots,
                "seed {seed}: {handed_pivots} pivots handed over, {cold_pivots} cold"
            );
            child.restore(&LpMemory::default());
            assert!(child.memory().is_empty());
        }
    }

    /// Columns pinned at 0 and frozen (zero in every row, left out of the ratio tests' products)
    /// give the same bounds as the same columns kept in the rows.
    #[test]
    fn frozen_columns_give_the_bounds_of_pinned_ones() {
        let mut rng = StdRng::seed_from_u64(11);
        let n = 12;
        let pinned = [2usize, 5, 6, 11];
        let (mut lo, mut hi) = (vec![-2.0; n], vec![2.0; n]);
        for &j in &pinned {
            (lo[j], hi[j]) = (0.0, 0.0);
        }
        let rows: Vec<Vec<f64>> = (0..60)
            .map(|_| (0..n).map(|_| rng.random_range(-1.0..1.0)).collect())
            .collect();
        let build = |freeze: bool| {
            let mut p = Polyhedron::default();
            p.reset(&lo, &hi);
            if freeze {
                pinned.iter().for_each(|&j| p.freeze(j, 0.0));
            }
            for a in &rows {
                p.push_row(a, 1.0);
            }
            p
        };
        let (frozen, kept) = (build(true), build(false));
        let (a, _) = bounds(&mut ScaledSimplex::default(), &frozen);
        let (b, _) = bounds(&mut ScaledSimplex::default(), &kept);
        for (slot, (a, b)) in a.iter().zip(&b).enumerate() {
            assert!(
                (a - b).abs() <= 1e-9 * (1.0 + b.abs()),
                "{slot}: {a} vs {b}"
            );
        }
    }
}
