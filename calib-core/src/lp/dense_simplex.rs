//! A dense active-set dual simplex for tiny LPs with many rows and few variables.
//!
//! The constraints are the rows `G_i·y <= g_i` and the box bounds `y_j <= hi_j`, `-y_j <= -lo_j`.
//! A basis is a set `W` of `n` constraints whose matrix `A_W` is invertible; its vertex is
//! `y = A_W⁻¹ b_W` and its multipliers solve `A_Wᵀ λ_W = -c`. The start is the box corner chosen by
//! the signs of `c`, which is dual feasible (`λ >= 0`) for any objective. Each iteration enters the
//! most violated constraint `k` and leaves the basis constraint that keeps `λ >= 0` (the dual ratio
//! test); no leaving candidate means a Farkas ray, i.e. an empty polyhedron. Every iterate is dual
//! feasible, so even an interrupted solve yields multipliers that [`super::safe_lower_bound`] turns
//! into a valid bound. `A_W⁻¹` is updated by the Sherman–Morrison formula at each basis change (`n²`
//! flops) and recomputed by Gauss–Jordan elimination with partial pivoting every
//! [`REFACTOR_EVERY`] pivots and at the start. All buffers are reused: no allocation after the
//! first call of a size.

use super::{LpBackend, LpStatus, Polyhedron};
use crate::linalg::gauss_jordan_inverse;

/// The dense dual simplex engine (see the module documentation).
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
    /// Pivots made by the last call (for profiling).
    pub last_pivots: usize,
}

/// Violations below this (relative to the row scale, rows are normalised to max |coef| ~ 1) are
/// accepted as satisfied; the safe bound makes the result rigorous anyway.
const FEASIBILITY_TOL: f64 = 1e-12;
/// Pivot elements below this are not used in the ratio test.
const PIVOT_TOL: f64 = 1e-11;
/// Recompute `A_W⁻¹` from scratch after this many rank-one updates.
const REFACTOR_EVERY: usize = 16;

impl DenseSimplex {
    fn resize(&mut self, n: usize, constraints: usize) {
        self.basis.resize(n, 0);
        self.in_basis.clear();
        self.in_basis.resize(constraints, false);
        self.a_w.resize(n * n, 0.0);
        self.inv.resize(n * n, 0.0);
        self.y.resize(n, 0.0);
        self.lambda.resize(n, 0.0);
        self.w.resize(n, 0.0);
        self.a_k.resize(n, 0.0);
    }

    /// The coefficient row and right-hand side of constraint `k` (rows first, then the bounds).
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

    /// Recomputes `inv = A_W⁻¹`; false if `A_W` is (numerically) singular.
    fn invert(&mut self, p: &Polyhedron) -> bool {
        let n = p.dim();
        for r in 0..n {
            let k = self.basis[r];
            let row = &mut self.a_k;
            let b = Self::constraint(p, k, row);
            let _ = b;
            self.a_w[r * n..(r + 1) * n].copy_from_slice(row);
        }
        gauss_jordan_inverse(n, &mut self.a_w, &mut self.inv)
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
        let (n, m) = (p.dim(), p.rows());
        self.resize(n, m + 2 * n);
        dual.iter_mut().for_each(|v| *v = 0.0);
        // Dual feasible start: the box corner that minimises c over the box.
        for j in 0..n {
            self.basis[j] = m + 2 * j + usize::from(c[j] > 0.0);
            self.in_basis[self.basis[j]] = true;
        }
        let mut since_refactor = REFACTOR_EVERY;
        let mut degenerate = 0usize;
        let max_pivots = 10 * (n + m) + 50;
        let mut status = LpStatus::Failed;
        self.last_pivots = 0;
        for _ in 0..max_pivots {
            if since_refactor >= REFACTOR_EVERY {
                if !self.invert(p) {
                    break;
                }
                since_refactor = 0;
            }
            // y = A_W⁻¹ b_W and λ_W = -A_W⁻ᵀ c.
            for j in 0..n {
                let mut s = 0.0;
                for r in 0..n {
                    let k = self.basis[r];
                    let b = if k < m {
                        p.rhs(k)
                    } else if (k - m) % 2 == 0 {
                        p.hi()[(k - m) / 2]
                    } else {
                        -p.lo()[(k - m) / 2]
                    };
                    s += self.inv[j * n + r] * b;
                }
                self.y[j] = s;
            }
            for r in 0..n {
                let mut s = 0.0;
                for j in 0..n {
                    s += self.inv[j * n + r] * c[j];
                }
                self.lambda[r] = (-s).max(0.0);
            }
            // Most violated constraint outside the basis (Dantzig), or the first violated one once
            // degenerate pivots pile up (Bland's rule, which cannot cycle).
            let bland = degenerate > 2 * n;
            let mut entering = None;
            let mut worst = FEASIBILITY_TOL;
            for i in 0..m {
                let row = p.row(i);
                let v = row.iter().zip(&self.y).map(|(a, y)| a * y).sum::<f64>() - p.rhs(i);
                if v > worst && !self.in_basis[i] {
                    worst = v;
                    entering = Some(i);
                    if bland {
                        break;
                    }
                }
            }
            if entering.is_none() || !bland {
                for j in 0..n {
                    let scale = 1.0 + p.hi()[j].abs().max(p.lo()[j].abs());
                    let up = (self.y[j] - p.hi()[j]) / scale;
                    let down = (p.lo()[j] - self.y[j]) / scale;
                    for (k, v) in [(m + 2 * j, up), (m + 2 * j + 1, down)] {
                        if v > worst && !self.in_basis[k] && !(bland && entering.is_some()) {
                            worst = v;
                            entering = Some(k);
                        }
                    }
                }
            }
            let Some(k) = entering else {
                status = LpStatus::Optimal;
                break;
            };
            // w = A_W⁻ᵀ a_k; leave the basis constraint with the smallest ratio λ_r / w_r, w_r > 0.
            let _ = Self::constraint(p, k, &mut self.a_k);
            for r in 0..n {
                let mut s = 0.0;
                for j in 0..n {
                    s += self.inv[j * n + r] * self.a_k[j];
                }
                self.w[r] = s;
            }
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
            if best <= 1e-14 {
                degenerate += 1;
            } else {
                degenerate = 0;
            }
            let Some(r) = leave else {
                // Farkas ray: μ_k = 1, μ_W = -w (>= 0 up to rounding).
                for i in 0..m {
                    dual[i] = 0.0;
                }
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
            // Row r of A_W becomes a_k: inv' = inv - inv e_r (w - e_r)ᵀ / w_r (Sherman–Morrison).
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
            since_refactor += 1;
        }
        for r in 0..n {
            let k = self.basis[r];
            if k < m {
                dual[k] = self.lambda[r];
            }
        }
        primal.copy_from_slice(&self.y[..n]);
        status
    }
}

#[cfg(test)]
mod tests {
    use super::super::safe_lower_bound;
    use super::*;

    #[test]
    fn solves_a_small_lp() {
        let mut p = Polyhedron::default();
        p.reset(&[-1.0, -1.0], &[1.0, 1.0]);
        p.push_row(&[1.0, 1.0], 1.0);
        p.push_row(&[-1.0, 1.0], 0.5);
        let mut s = DenseSimplex::default();
        let (mut dual, mut y) = ([0.0; 2], [0.0; 2]);
        assert_eq!(
            s.minimize(&p, &[0.0, -1.0], &mut dual, &mut y),
            LpStatus::Optimal
        );
        assert!(
            (y[1] - 0.75).abs() < 1e-12 && (y[0] - 0.25).abs() < 1e-12,
            "{y:?}"
        );
        let b = safe_lower_bound(&p, &[0.0, -1.0], &dual);
        assert!(b <= -0.75 && b > -0.75 - 1e-12);
        assert_eq!(
            s.minimize(&p, &[1.0, 0.0], &mut dual, &mut y),
            LpStatus::Optimal
        );
        assert!((y[0] + 1.0).abs() < 1e-12);
    }

    #[test]
    fn detects_infeasibility_with_a_ray() {
        let mut p = Polyhedron::default();
        p.reset(&[-1.0, -1.0], &[1.0, 1.0]);
        p.push_row(&[1.0, 1.0], -0.5);
        p.push_row(&[-1.0, -1.0], -0.5);
        let mut s = DenseSimplex::default();
        let (mut dual, mut y) = ([0.0; 2], [0.0; 2]);
        assert_eq!(
            s.minimize(&p, &[1.0, 0.0], &mut dual, &mut y),
            LpStatus::Infeasible
        );
        assert!(super::super::proves_infeasible(&p, &dual, &[0.0, 0.0]));
    }
}
