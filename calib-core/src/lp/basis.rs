//! The basis algebra shared by the simplex engines: a basis `W` of `n` constraints, the inverse of
//! its matrix `A_W`, its vertex and its multipliers.
//!
//! The constraints are indexed `0..m` for the rows of `G`, then `m + 2j` for `y_j <= hi_j` and
//! `m + 2j + 1` for `-y_j <= -lo_j`; a [`Constraints`] view says what each one is (in whatever
//! coordinates the engine works in).

use crate::num::linalg::gauss_jordan_inverse;

/// The constraints of an LP as an engine sees them.
pub(super) trait Constraints {
    /// Writes the coefficients of constraint `k` into `a` and returns its right-hand side.
    fn constraint(&self, k: usize, a: &mut [f64]) -> f64;
    /// The right-hand side of constraint `k`.
    fn rhs(&self, k: usize) -> f64;
}

/// A basis and its factorisation, in reusable buffers.
#[derive(Clone, Debug, Default)]
pub(super) struct Basis {
    /// The constraint at each basis position.
    pub basis: Vec<usize>,
    /// Per constraint, whether it is in the basis.
    pub in_basis: Vec<bool>,
    /// `A_W` (row-major), also a scratch vector for edge directions.
    pub a_w: Vec<f64>,
    /// `A_W⁻¹` (row-major).
    pub inv: Vec<f64>,
    /// The vertex `A_W⁻¹ b_W`.
    pub y: Vec<f64>,
    /// The multipliers of the basis constraints.
    pub lambda: Vec<f64>,
    /// `A_W⁻ᵀ a_k` for the constraint in `a_k`.
    pub w: Vec<f64>,
    /// A constraint's coefficients.
    pub a_k: Vec<f64>,
    /// The right-hand sides `b_W` of the basis constraints (scratch for [`Basis::vertex`]).
    b_w: Vec<f64>,
    /// Basis changes made by the current solve.
    pub pivots: usize,
}

impl Basis {
    /// Sizes the buffers for `n` variables.
    pub fn resize(&mut self, n: usize) {
        self.basis.resize(n, 0);
        self.a_w.resize(n * n, 0.0);
        self.inv.resize(n * n, 0.0);
        self.y.resize(n, 0.0);
        self.lambda.resize(n, 0.0);
        self.w.resize(n, 0.0);
        self.a_k.resize(n, 0.0);
        self.b_w.resize(n, 0.0);
    }

    /// Rebuilds `in_basis` for `constraints` constraints from `basis`. A basis entry beyond the
    /// constraints (a stale basis of a larger problem) marks nothing: the mask then holds fewer
    /// than `n` constraints, which every start from a remembered basis checks.
    pub fn set_mask(&mut self, constraints: usize) {
        self.in_basis.clear();
        self.in_basis.resize(constraints, false);
        for &k in &self.basis {
            if let Some(slot) = self.in_basis.get_mut(k) {
                *slot = true;
            }
        }
    }

    /// Recomputes `inv = A_W⁻¹`; false if `A_W` is (numerically) singular.
    pub fn invert(&mut self, c: &impl Constraints) -> bool {
        let n = self.basis.len();
        for r in 0..n {
            c.constraint(self.basis[r], &mut self.a_k);
            self.a_w[r * n..(r + 1) * n].copy_from_slice(&self.a_k);
        }
        gauss_jordan_inverse(n, &mut self.a_w, &mut self.inv)
    }

    /// `y = A_W⁻¹ b_W`.
    pub fn vertex(&mut self, c: &impl Constraints) {
        let n = self.basis.len();
        // Each right-hand side once, not once per coordinate (the same values and sums).
        self.b_w.resize(n, 0.0);
        for r in 0..n {
            self.b_w[r] = c.rhs(self.basis[r]);
        }
        for j in 0..n {
            self.y[j] = (0..n).map(|r| self.inv[j * n + r] * self.b_w[r]).sum();
        }
    }

    /// `λ_W = -A_W⁻ᵀ c` for the objective `c` (not clipped).
    pub fn multipliers(&mut self, objective: &[f64]) {
        let n = self.basis.len();
        for r in 0..n {
            self.lambda[r] = -(0..n)
                .map(|j| self.inv[j * n + r] * objective[j])
                .sum::<f64>();
        }
    }

    /// `w = A_W⁻ᵀ a_k` for the constraint in `self.a_k`.
    pub fn transformed_row(&mut self) {
        let n = self.basis.len();
        for r in 0..n {
            self.w[r] = (0..n).map(|j| self.inv[j * n + r] * self.a_k[j]).sum();
        }
    }

    /// The dual simplex's entering constraint: outside the basis, the largest `violation(k)` above
    /// `tolerance` (Dantzig), or the first one above it with `bland` (Bland's rule, which cannot
    /// cycle); `None` when none is violated (the vertex is optimal).
    pub fn most_violated(
        &self,
        tolerance: f64,
        bland: bool,
        violation: impl Fn(usize) -> f64,
    ) -> Option<usize> {
        let mut entering = None;
        let mut worst = tolerance;
        for k in (0..self.in_basis.len()).filter(|&k| !self.in_basis[k]) {
            let v = violation(k);
            if v > worst {
                worst = v;
                entering = Some(k);
                if bland {
                    break;
                }
            }
        }
        entering
    }

    /// Replaces basis position `r` by constraint `k` (with `w` already computed for `a_k`):
    /// `inv' = inv - inv e_r (w - e_r)ᵀ / w_r` (Sherman–Morrison).
    pub fn replace(&mut self, r: usize, k: usize) {
        let n = self.basis.len();
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
        self.pivots += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::Basis;

    /// A stale basis naming constraints of a larger problem (found on a 6-DoF arm's hull, where
    /// it indexed past the mask) marks only the constraints there are.
    #[test]
    fn a_stale_basis_marks_only_existing_constraints() {
        let mut b = Basis {
            basis: vec![0, 9, 3],
            ..Basis::default()
        };
        b.set_mask(5);
        assert_eq!(b.in_basis, [true, false, false, true, false]);
        assert_eq!(b.in_basis.iter().filter(|&&k| k).count(), 2);
    }
}
