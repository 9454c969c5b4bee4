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
//!
//! The answers are hints: [`super::safe_lower_bound`] checks the multipliers against the true rows
//! and objective.

use super::basis::{Basis, Constraints};
use super::polyhedron::power_of_two_scale;
use super::{LpStatus, Polyhedron};

/// The engine (see the module documentation).
#[derive(Clone, Debug, Default)]
pub(super) struct ScaledSimplex {
    b: Basis,
    /// The objective in scaled coordinates (perturbed when the dual simplex stalls).
    c: Vec<f64>,
    /// Per constraint, the primal ratio test's step and pivot (reused buffers).
    ratio: Vec<f64>,
    pivot: Vec<f64>,
    scaled: Scaled,
    /// The polyhedron generation of the last optimal solve (its basis can warm-start the next).
    warm: Option<u64>,
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
/// Pivot elements below this are not used in ratio tests.
const PIVOT_TOL: f64 = 1e-9;
/// Harris ratio tests: among the candidates within this of the smallest ratio's bound, the largest
/// pivot is taken (a stable basis rather than the exact minimum).
const HARRIS_TOL: f64 = 1e-10;
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
        let mut since_refactor = REFACTOR_EVERY;
        let mut degenerate = 0usize;
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
            if degenerate > 2 * n && !perturbed {
                self.perturb_cost(p);
                perturbed = true;
                degenerate = 0;
                continue;
            }
            // Most violated constraint outside the basis (Dantzig), or the first violated one once
            // degenerate pivots pile up even after the perturbation (Bland's rule: no cycling).
            let bland = degenerate > 2 * n;
            let entering = self.b.most_violated(FEASIBILITY_TOL, bland, |k| {
                violation(&self.scaled, p, k, &self.b.y)
            });
            let Some(k) = entering else {
                status = LpStatus::Optimal;
                break;
            };
            // w = A_W⁻ᵀ a_k; leave the basis constraint with the smallest ratio λ_r / w_r, w_r > 0
            // (Harris: the largest w_r among the ratios within tolerance of the smallest).
            constraint(&self.scaled, p, k, &mut self.b.a_k);
            self.b.transformed_row();
            let eligible =
                |r: usize| self.b.w[r] > PIVOT_TOL && !self.scaled.pinned(self.b.basis[r]);
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
            let Some(r) = leave else {
                // Farkas ray: μ_k = 1, μ_W = -w (>= 0 up to rounding), in the original rows.
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
                self.export_primal(primal);
                return LpStatus::Infeasible;
            };
            degenerate = if self.b.lambda[r] / self.b.w[r] <= 1e-14 {
                degenerate + 1
            } else {
                0
            };
            self.b.replace(r, k);
            since_refactor += 1;
        }
        self.export(m, dual, primal);
        status
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
        if (0..m + 2 * n)
            .any(|k| !self.b.in_basis[k] && violation(&self.scaled, p, k, &self.b.y) > WARM_TOL)
        {
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
            }
            self.b.multipliers(&self.c);
            if degenerate > 2 * n {
                // Stalled at a degenerate vertex: the dual simplex (with its perturbation) is the
                // sturdier path.
                return None;
            }
            // Leave the constraint with the most negative multiplier.
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
            let Some(r) = leave else {
                self.export(m, dual, primal);
                return Some(LpStatus::Optimal);
            };
            // Edge direction d = -A_W⁻¹ e_r: keeps the other basis constraints active and moves
            // inside constraint r; c·d = λ_r < 0.
            for j in 0..n {
                self.b.a_w[j] = -self.b.inv[j * n + r];
            }
            // Harris: the largest step direction among the ratios within tolerance of the
            // smallest (slacks relaxed by the tolerance), then the step to it. One pass computes
            // every `a_k·d` and slack; the second picks among them.
            let total = m + 2 * n;
            self.ratio.resize(total, f64::INFINITY);
            self.pivot.resize(total, 0.0);
            let mut bound = f64::INFINITY;
            for k in 0..total {
                self.ratio[k] = f64::INFINITY;
                if self.b.in_basis[k] {
                    continue;
                }
                let ad = along(&self.scaled, k, &self.b.a_w[..n]);
                if ad > PIVOT_TOL {
                    let slack = (-violation(&self.scaled, p, k, &self.b.y)).max(0.0);
                    self.ratio[k] = slack / ad;
                    self.pivot[k] = ad;
                    bound = bound.min((slack + HARRIS_TOL) / ad);
                }
            }
            let mut enter: Option<(usize, f64, f64)> = None;
            for k in 0..total {
                let (t, ad) = (self.ratio[k], self.pivot[k]);
                if t <= bound && enter.is_none_or(|(_, _, best)| ad > best) {
                    enter = Some((k, t, ad));
                }
            }
            let (k, step, _) = enter?;
            degenerate = if step <= 1e-14 { degenerate + 1 } else { 0 };
            for j in 0..n {
                self.b.y[j] += step * self.b.a_w[j];
            }
            constraint(&self.scaled, p, k, &mut self.b.a_k);
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

impl ScaledSimplex {
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
        dual.iter_mut().for_each(|v| *v = 0.0);
        self.b.pivots = 0;
        if self.warm == Some(p.generation()) && self.b.in_basis.len() == p.rows() + 2 * n {
            if let Some(status) = self.primal_simplex(p, dual, primal) {
                return status;
            }
            dual.iter_mut().for_each(|v| *v = 0.0);
        }
        let status = self.dual_simplex(p, dual, primal);
        self.warm = (status == LpStatus::Optimal).then_some(p.generation());
        status
    }
}
