//! Coupling the rows of one configuration: the directions `λ` along which the `NR` residuals of a
//! vector model are combined into scalar equations.
//!
//! A configuration `k` of a [`crate::VectorModel`] gives `NR` equations `f_r(x, M) = 0` that hold
//! for **one** `M ∈ M_k`. Every combination `λ·f(x, M) = 0` holds for that same `M`, so each is a
//! valid scalar calibration equation, and the scalar relaxations of the kernel apply to it. Taken
//! one at a time (the unit vectors `λ = e_r`), the rows forget that they share `M`: each row may
//! use its own reading, and the enclosure is the solution set of the *decoupled* system.
//!
//! The coupling is recovered by the right directions. Linearised at a point, the residuals that
//! one `M ∈ M_k` can produce form the zonotope `Z = {B e : |e_i| <= rad(M_i)}` with
//! `B = ∂f/∂M` (`NR × NM`): its generators are the columns `g_i = B_i rad(M_i)`. A zonotope is the
//! intersection of the slabs of its facets, and the facet normals of `Z` are the generalised cross
//! products of `NR - 1` generators (for `NR = 2` the perpendiculars of the generators, for
//! `NR = 3` the cross products of pairs). For such a normal `λ`, the scalar equation `λ·f` has
//! exactly the support `Σ_i |λ·B_i| rad(M_i)` of `Z` in direction `λ` as its measurement
//! half-range, so the rows of all facet normals together describe the coupled linearisation
//! exactly, where the unit rows only describe its bounding box.
//!
//! Any set of directions is sound (every row holds for every solution); the choice only decides
//! how tight the relaxation is. [`coupling_directions`] returns the facet normals of the zonotope
//! spanned by the largest generators, at most [`MAX_DIRECTIONS`] of them.

use crate::Evaluation;

/// At most this many coupling directions per configuration (every facet normal of a zonotope with
/// 9 generators in 3 dimensions: a tracked point with 6 joint readings and 3 tracker coordinates).
pub(crate) const MAX_DIRECTIONS: usize = 36;

/// Coupling directions of one configuration, stored without allocation.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Directions<const NR: usize> {
    list: [[f64; NR]; MAX_DIRECTIONS],
    len: usize,
}

impl<const NR: usize> Directions<NR> {
    /// No directions.
    pub const fn new() -> Self {
        Directions {
            list: [[0.0; NR]; MAX_DIRECTIONS],
            len: 0,
        }
    }

    /// The directions.
    pub fn as_slice(&self) -> &[[f64; NR]] {
        &self.list[..self.len]
    }

    /// Adds `d` unless it is (nearly) parallel to a direction already held or the list is full.
    fn push_distinct(&mut self, d: [f64; NR]) {
        let norm = d.iter().map(|v| v * v).sum::<f64>().sqrt();
        if self.len == MAX_DIRECTIONS || norm <= 0.0 || !norm.is_finite() {
            return;
        }
        let unit = d.map(|v| v / norm);
        let parallel = self.as_slice().iter().any(|o| {
            let c: f64 = o.iter().zip(&unit).map(|(a, b)| a * b).sum();
            c.abs() > 1.0 - 1e-9
        });
        // A unit vector is one of the rows themselves: nothing to add.
        let axis = unit.iter().any(|v| v.abs() > 1.0 - 1e-12);
        if !parallel && !axis {
            self.list[self.len] = unit;
            self.len += 1;
        }
    }
}

impl<const NR: usize> Default for Directions<NR> {
    fn default() -> Self {
        Self::new()
    }
}

/// The facet normals (unit length, up to sign) of the zonotope with generators
/// `g_i = b[·][i] · rad[i]` (see the module documentation), from the largest generators so that
/// at most [`MAX_DIRECTIONS`] are formed. Generators below `1e-6` of the largest are ignored, and
/// so are normals along an axis (they are the unit rows). Empty for `NR = 1`.
pub(crate) fn coupling_directions<const NR: usize, const NM: usize>(
    b: &[[f64; NM]; NR],
    rad: &[f64; NM],
) -> Directions<NR> {
    let mut out = Directions::new();
    if NR < 2 {
        return out;
    }
    let gen: [[f64; NR]; NM] = core::array::from_fn(|i| core::array::from_fn(|r| b[r][i] * rad[i]));
    let norm = |g: &[f64; NR]| g.iter().map(|v| v * v).sum::<f64>().sqrt();
    let mut order: [usize; NM] = core::array::from_fn(|i| i);
    order.sort_by(|&a, &c| norm(&gen[c]).total_cmp(&norm(&gen[a])));
    let largest = norm(&gen[order[0]]);
    if largest <= 0.0 || !largest.is_finite() {
        return out;
    }
    let mut kept = order
        .iter()
        .take_while(|&&i| norm(&gen[i]) > 1e-6 * largest)
        .count();
    while kept > NR - 1 && binomial(kept, NR - 1) > MAX_DIRECTIONS {
        kept -= 1;
    }
    if kept < NR - 1 {
        return out;
    }
    // Every (NR - 1)-subset of the kept generators, in lexicographic order.
    let mut subset: Vec<usize> = (0..NR - 1).collect();
    loop {
        let vectors: Vec<[f64; NR]> = subset.iter().map(|&s| gen[order[s]]).collect();
        out.push_distinct(generalised_cross(&vectors));
        let Some(i) = (0..NR - 1).rev().find(|&i| subset[i] < kept - (NR - 1) + i) else {
            return out;
        };
        subset[i] += 1;
        for k in i + 1..NR - 1 {
            subset[k] = subset[k - 1] + 1;
        }
    }
}

/// The scalar equations of one configuration linearised at a point, as the searches for certified
/// points use them: each row `r` and each coupling direction `λ` (from the point Jacobian `∂f/∂M`)
/// is passed to `emit(value, ∂/∂x, w)`, where `w = Σ_i |∂/∂M_i| rad(M_i)` is the first-order
/// half-range of the equation over the measurement box (paper eq. 6). With every facet normal, the
/// constraints `|value + ∂/∂x · d| <= θ w` describe exactly the parameter steps `d` for which one
/// reading within `θ` of the half-widths fits all rows at first order.
pub(crate) fn for_each_linearised_row<const NX: usize, const NM: usize, const NR: usize>(
    e: &[Evaluation<f64, NX, NM>; NR],
    rad: &[f64; NM],
    mut emit: impl FnMut(f64, &[f64; NX], f64),
) {
    for_each_split_row(e, &[0.0; NM], rad, |_, value, dx, _, w| emit(value, dx, w));
}

/// [`for_each_linearised_row`] with the measurement half-widths split in two parts,
/// `rad = fixed + scaled`: `emit(value, ∂/∂x, w_fixed, w_scaled)` receives the half-range of each
/// part, so that the half-range with the `scaled` part multiplied by `s` is `w_fixed + s w_scaled`
/// (the facet normals of a Minkowski sum of zonotopes do not depend on the factor `s > 0`). The
/// first argument of `emit` is the combination `λ` of the rows (a unit vector for a row itself).
pub(crate) fn for_each_split_row<const NX: usize, const NM: usize, const NR: usize>(
    e: &[Evaluation<f64, NX, NM>; NR],
    fixed: &[f64; NM],
    scaled: &[f64; NM],
    mut emit: impl FnMut(&[f64; NR], f64, &[f64; NX], f64, f64),
) {
    let half_range = |g: &dyn Fn(usize) -> f64, rad: &[f64; NM]| -> f64 {
        (0..NM).map(|i| g(i).abs() * rad[i]).sum::<f64>()
    };
    for (row, r) in e.iter().enumerate() {
        let g = |i: usize| r.dm[i];
        let unit: [f64; NR] = core::array::from_fn(|i| if i == row { 1.0 } else { 0.0 });
        emit(
            &unit,
            r.value,
            &r.dx,
            half_range(&g, fixed),
            half_range(&g, scaled),
        );
    }
    if NR < 2 {
        return;
    }
    let b: [[f64; NM]; NR] = core::array::from_fn(|r| e[r].dm);
    let rad: [f64; NM] = core::array::from_fn(|i| fixed[i] + scaled[i]);
    for l in coupling_directions(&b, &rad).as_slice() {
        let value: f64 = (0..NR).map(|r| l[r] * e[r].value).sum();
        let dx: [f64; NX] = core::array::from_fn(|j| (0..NR).map(|r| l[r] * e[r].dx[j]).sum());
        let g = |i: usize| (0..NR).map(|r| l[r] * e[r].dm[i]).sum::<f64>();
        emit(l, value, &dx, half_range(&g, fixed), half_range(&g, scaled));
    }
}

/// `C(n, k)`.
fn binomial(n: usize, k: usize) -> usize {
    (0..k).fold(1, |acc, i| acc * (n - i) / (i + 1))
}

/// The vector orthogonal to the `NR - 1` given vectors whose entries are the signed maximal minors
/// (the cross product for `NR = 3`, the perpendicular for `NR = 2`).
fn generalised_cross<const NR: usize>(v: &[[f64; NR]]) -> [f64; NR] {
    let n = NR - 1;
    let mut minor = vec![0.0; n * n];
    core::array::from_fn(|r| {
        // The minor without column r.
        for (i, row) in v.iter().enumerate() {
            let mut c = 0;
            for (col, value) in row.iter().enumerate() {
                if col != r {
                    minor[i * n + c] = *value;
                    c += 1;
                }
            }
        }
        let sign = if r % 2 == 0 { 1.0 } else { -1.0 };
        sign * determinant(n, &mut minor)
    })
}

/// The determinant of the `n × n` row-major matrix `a` (overwritten) by Gaussian elimination with
/// partial pivoting.
fn determinant(n: usize, a: &mut [f64]) -> f64 {
    let mut det = 1.0;
    for col in 0..n {
        let pivot = (col..n)
            .max_by(|&p, &q| a[p * n + col].abs().total_cmp(&a[q * n + col].abs()))
            .unwrap_or(col);
        if a[pivot * n + col] == 0.0 {
            return 0.0;
        }
        if pivot != col {
            for k in 0..n {
                a.swap(pivot * n + k, col * n + k);
            }
            det = -det;
        }
        let p = a[col * n + col];
        det *= p;
        for row in col + 1..n {
            let factor = a[row * n + col] / p;
            for k in col..n {
                a[row * n + k] -= factor * a[col * n + k];
            }
        }
    }
    det
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dot<const N: usize>(a: &[f64; N], b: &[f64; N]) -> f64 {
        a.iter().zip(b).map(|(x, y)| x * y).sum()
    }

    #[test]
    fn normals_are_orthogonal_to_their_generators() {
        let v = [[1.0, 2.0, 0.5], [-0.3, 0.7, 2.0]];
        let n = generalised_cross(&v);
        assert!(dot(&n, &v[0]).abs() < 1e-12 && dot(&n, &v[1]).abs() < 1e-12);
        let w = [
            [1.0, 2.0, 0.5, 0.1],
            [-0.3, 0.7, 2.0, 1.0],
            [0.2, -1.0, 0.3, 0.4],
        ];
        let n4 = generalised_cross(&w);
        for g in &w {
            assert!(dot(&n4, g).abs() < 1e-12, "{n4:?}");
        }
        assert!(n4.iter().any(|c| c.abs() > 0.1));
    }

    #[test]
    fn a_tracked_point_gets_every_facet_of_its_zonotope() {
        // Three tracker coordinates (the identity) and six joint columns: 9 generators, 36 pairs;
        // the three pairs of axes give axis normals, which are the unit rows.
        let b = [
            [-1.0, 0.0, 0.0, 0.3, -0.2, 0.1, 0.05, 0.4, 0.02],
            [0.0, -1.0, 0.0, 0.1, 0.5, -0.3, 0.2, 0.01, 0.3],
            [0.0, 0.0, -1.0, 0.6, 0.1, 0.2, -0.4, 0.2, 0.1],
        ];
        let rad = [0.01, 0.01, 0.01, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0];
        let d = coupling_directions(&b, &rad);
        for n in d.as_slice() {
            assert!((dot(n, n) - 1.0).abs() < 1e-12);
        }
        // Every pair's normal is there (up to sign; parallel ones once).
        let gen: Vec<[f64; 3]> = (0..9)
            .map(|i| core::array::from_fn(|r| b[r][i] * rad[i]))
            .collect();
        let mut pairs = 0;
        for i in 0..9 {
            for j in i + 1..9 {
                let n = generalised_cross(&[gen[i], gen[j]]);
                let len = dot(&n, &n).sqrt();
                if n.iter().filter(|v| v.abs() > 1e-12 * len).count() == 1 {
                    continue; // an axis: a unit row
                }
                pairs += 1;
                let found = d
                    .as_slice()
                    .iter()
                    .any(|u| dot(u, &n).abs() > len * (1.0 - 1e-9));
                assert!(found, "normal of generators {i}, {j} missing");
            }
        }
        assert_eq!(pairs, 33);
        assert!(d.as_slice().len() <= pairs);
        // One scalar residual: no coupling.
        assert!(coupling_directions(&[[1.0, 2.0]], &[1.0, 1.0])
            .as_slice()
            .is_empty());
    }

    #[test]
    fn the_largest_generators_are_kept_when_there_are_too_many() {
        // 12 generators in 3 dimensions: C(12, 2) = 66 > 36, so only the 9 largest are used.
        let b: [[f64; 12]; 3] = core::array::from_fn(|r| {
            core::array::from_fn(|i| ((i * 7 + r * 3) % 5) as f64 - 2.0 + 0.1 * i as f64)
        });
        let rad: [f64; 12] = core::array::from_fn(|i| 1.0 + i as f64);
        let d = coupling_directions(&b, &rad);
        assert!(!d.as_slice().is_empty() && d.as_slice().len() <= MAX_DIRECTIONS);
    }
}
