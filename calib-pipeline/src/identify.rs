//! Identifiability: which parameters (or combinations) the configurations cannot determine,
//! found before certifying from the identification Jacobian at the nominal geometry.
//!
//! Row `i` of the Jacobian is `∂f_i/∂x_j · r_j / w_i`: the change of residual `i` when parameter
//! `j` moves by its prior half-width `r_j`, in units of the residual's first-order measurement
//! half-range `w_i = Σ_k |∂f_i/∂M_k| rad(M_k)` (paper eq. 6). With `J = U Σ Vᵀ`, a right singular
//! vector `v` with singular value `σ` is a combination of parameter moves; scaled so that its
//! largest move reaches the prior box (`v / ‖v‖∞`), it changes residual `i` by
//! `(J v)_i / ‖v‖∞` error bounds, to first order. Its *effect* is the largest of these,
//! `‖J v‖∞ / ‖v‖∞`: the certified set is cut by the rows (each within its own bound), so what
//! matters is the largest change of one residual, not the 2-norm `σ` spread over all of them.
//!
//! * `σ <= NULL_RATIO · σ_max`: the combination does not change the readings at all — the data
//!   cannot determine it, whatever the noise (e.g. `theta1` together with `base_rz`). One of its
//!   parameters must be fixed. Singular vectors of a null space of dimension two or more mix
//!   unrelated sets, so the sets are named otherwise: taking the columns in parameter order, a
//!   column that the columns kept so far reproduce (relative residual of a least-squares fit at
//!   most [`DEPENDENT_RESIDUAL`]) depends on them; the set named is that parameter and the kept
//!   ones its fit leans on (a share of at least a tenth).
//! * effect `< 1`: moving the combination across the prior box changes no residual by more than
//!   its error bound — these configurations barely determine it (more or better-spread
//!   configurations would), and the certified box will reach the prior there.

use crate::outcome::is_fixed;
use calib_core::{Interval, VectorModel};
use nalgebra::DMatrix;

/// Singular values at or below this fraction of the largest are zero (parameters that cannot be
/// told apart): exact dependencies show at rounding level (~1e-15), weak ones far above.
pub const NULL_RATIO: f64 = 1e-8;

/// A parameter's column reproduced by the earlier ones to this relative residual depends on them
/// (exact dependencies leave rounding-level residuals; a base tilted by 0.1° leaves ~2e-3).
pub const DEPENDENT_RESIDUAL: f64 = 1e-6;

/// A combination of parameters: `(parameter index, weight)`, heaviest first, weights of the unit
/// singular vector (in prior half-widths).
#[derive(Clone, Debug, PartialEq)]
pub struct Combination {
    /// The largest change of one residual, in error bounds, when the combination moves across
    /// the prior box (0 for a dependent set).
    pub effect: f64,
    /// The parameters that carry it (weight at least a tenth of the largest).
    pub members: Vec<(usize, f64)>,
}

/// The identifiability of a parameter set on a set of configurations.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Identifiability {
    /// Singular values of the scaled identification Jacobian, largest first.
    pub singular_values: Vec<f64>,
    /// Combinations the data cannot determine at all (see [`NULL_RATIO`]).
    pub undetermined: Vec<Combination>,
    /// Combinations whose effect is below one error bound (see the module documentation).
    pub weak: Vec<Combination>,
}

/// The scaled identification Jacobian over the free parameters (see the module documentation):
/// one row per residual row and configuration, at the parameter vector `x` and the readings'
/// centres, the columns of the parameters whose prior box `x0` is not a point.
pub fn identification_jacobian<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[f64; NX],
    x0: &[Interval; NX],
    boxes: &[[Interval; NM]],
) -> (Vec<usize>, DMatrix<f64>)
where
    M: VectorModel<NX, NM, NR>,
{
    let free: Vec<usize> = (0..NX).filter(|&j| !is_fixed(x0[j])).collect();
    let mut j = DMatrix::zeros(boxes.len() * NR, free.len());
    for (k, m) in boxes.iter().enumerate() {
        let mid = m.map(|v| v.mid());
        let rad = m.map(|v| v.rad());
        for (r, e) in model.evaluate_rows(x, &mid).iter().enumerate() {
            let w: f64 = (0..NM).map(|i| e.dm[i].abs() * rad[i]).sum();
            let w = if w > 0.0 { w } else { 1.0 };
            for (c, &p) in free.iter().enumerate() {
                j[(k * NR + r, c)] = e.dx[p] * x0[p].rad() / w;
            }
        }
    }
    (free, j)
}

/// Analyses the Jacobian of [`identification_jacobian`] (`free`: the parameter of each column).
pub fn analyse(free: &[usize], jacobian: DMatrix<f64>) -> Identifiability {
    if free.is_empty() || jacobian.nrows() == 0 {
        return Identifiability {
            singular_values: Vec::new(),
            undetermined: Vec::new(),
            weak: Vec::new(),
        };
    }
    // Pad to at least as many rows as columns so that V is square.
    let (rows, cols) = jacobian.shape();
    let padded = if rows < cols {
        jacobian.resize_vertically(cols, 0.0)
    } else {
        jacobian
    };
    let svd = padded.clone().svd(false, true);
    let Some(v_t) = svd.v_t else {
        return Identifiability {
            singular_values: Vec::new(),
            undetermined: Vec::new(),
            weak: Vec::new(),
        };
    };
    let sigma: Vec<f64> = svd.singular_values.iter().copied().collect();
    let mut order: Vec<usize> = (0..sigma.len()).collect();
    order.sort_by(|&a, &b| sigma[b].total_cmp(&sigma[a]));
    let largest = sigma.iter().copied().fold(0.0, f64::max);
    let effect = |i: usize| {
        let v = v_t.row(i).transpose();
        let moved = &padded * &v;
        moved.amax() / v.amax()
    };
    let combination = |i: usize| {
        let row: Vec<f64> = (0..cols).map(|c| v_t[(i, c)]).collect();
        let max = row.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let mut members: Vec<(usize, f64)> = row
            .iter()
            .enumerate()
            .filter(|(_, v)| v.abs() >= 0.1 * max)
            .map(|(c, v)| (free[c], *v))
            .collect();
        members.sort_by(|a, b| b.1.abs().total_cmp(&a.1.abs()));
        Combination {
            effect: effect(i),
            members,
        }
    };
    let undetermined = dependent_sets(free, &padded_columns(&padded, rows));
    let weak = order
        .iter()
        .filter(|&&i| sigma[i] > NULL_RATIO * largest)
        .map(|&i| combination(i))
        .filter(|c| c.effect < 1.0)
        .collect();
    Identifiability {
        singular_values: order.iter().map(|&i| sigma[i]).collect(),
        undetermined,
        weak,
    }
}

/// The first `rows` rows of `m` (the Jacobian without its padding).
fn padded_columns(m: &DMatrix<f64>, rows: usize) -> DMatrix<f64> {
    m.rows(0, rows).into_owned()
}

/// The dependent sets, greedily in parameter order (see the module documentation).
fn dependent_sets(free: &[usize], j: &DMatrix<f64>) -> Vec<Combination> {
    let mut kept: Vec<usize> = Vec::new();
    let mut sets = Vec::new();
    for c in 0..j.ncols() {
        let col = j.column(c).into_owned();
        let norm = col.norm();
        if norm == 0.0 {
            sets.push(Combination {
                effect: 0.0,
                members: vec![(free[c], 1.0)],
            });
            continue;
        }
        if !kept.is_empty() {
            let a = j.select_columns(&kept);
            let svd = a.clone().svd(true, true);
            if let Ok(y) = svd.solve(&col, 1e-12 * svd.singular_values.max()) {
                let residual = (&a * &y - &col).norm() / norm;
                if residual <= DEPENDENT_RESIDUAL {
                    let mut members = vec![(free[c], 1.0)];
                    for (i, &k) in kept.iter().enumerate() {
                        let share = y[i].abs() * j.column(k).norm() / norm;
                        if share >= 0.1 {
                            members.push((free[k], -y[i]));
                        }
                    }
                    sets.push(Combination {
                        effect: 0.0,
                        members,
                    });
                    continue;
                }
            }
        }
        kept.push(c);
    }
    sets
}

/// Weak groups with more members are named by their first few.
const MAX_NAMED: usize = 6;

impl Identifiability {
    /// The findings in words (each weak group once, members in model order, smallest groups
    /// first), naming parameters by `names` (all parameters, model order).
    pub fn sentences(&self, names: &[String]) -> Vec<String> {
        let list = |c: &Combination| {
            c.members
                .iter()
                .map(|(j, _)| names.get(*j).map_or("?", String::as_str))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let mut out = Vec::new();
        for c in &self.undetermined {
            out.push(if c.members.len() == 1 {
                format!(
                    "not identifiable: {} does not change the readings at all with these \
                     configurations — fix it (radius 0)",
                    list(c)
                )
            } else {
                format!(
                    "not identifiable: {} change the readings only together (one combination of \
                     them is invisible to any configuration of this kind) — fix one of them \
                     (radius 0)",
                    list(c)
                )
            });
        }
        // Each weak group once, its members in model order, the smallest groups first (a group
        // spanning most parameters says little beyond its size).
        let mut weak: Vec<Combination> = Vec::new();
        for c in &self.weak {
            let mut members = c.members.clone();
            members.sort_by_key(|(j, _)| *j);
            let same = |w: &Combination| {
                w.members.len() == members.len()
                    && w.members.iter().zip(&members).all(|(a, b)| a.0 == b.0)
            };
            if !weak.iter().any(same) {
                weak.push(Combination {
                    effect: c.effect,
                    members,
                });
            }
        }
        weak.sort_by(|a, b| {
            a.members
                .len()
                .cmp(&b.members.len())
                .then(a.effect.total_cmp(&b.effect))
        });
        let shown = |c: &Combination| {
            if c.members.len() <= MAX_NAMED {
                list(c)
            } else {
                let first = Combination {
                    effect: c.effect,
                    members: c.members[..MAX_NAMED].to_vec(),
                };
                format!(
                    "{} parameters ({}, and {} more)",
                    c.members.len(),
                    list(&first),
                    c.members.len() - MAX_NAMED
                )
            }
        };
        for c in &weak {
            let list = shown;
            let (what, them) = if c.members.len() == 1 {
                (format!("moving {} across its prior box", list(c)), "it")
            } else {
                (
                    format!("moving {} together across their prior boxes", list(c)),
                    "them",
                )
            };
            out.push(format!(
                "weakly determined: {what} changes no residual by more than {:.2} of its error \
                 bound — the certified box will reach the prior there; more (or more spread) \
                 configurations would determine {them} better",
                c.effect
            ));
        }
        out
    }
}
