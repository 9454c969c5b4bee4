//! Experiment design: which configurations to measure so that every parameter is determined.
//!
//! Robot-agnostic: a robot describes each candidate configuration by the rows it would add to the
//! scaled identification Jacobian of each parameter *group* (the parameters certified together:
//! one leg of a hexapod, the whole arm), as [`crate::identify::identification_jacobian`] builds
//! them — parameter moves in prior half-widths, residuals in their first-order error bounds.
//!
//! **The first-order certified box.** Near the nominal geometry, a configuration with scaled row
//! `r` keeps the parameter moves `δ` (in prior half-widths) with `|r·δ| <= 1`: the residual must
//! stay within its error bound. The certified box of a design is, to first order, the bounding
//! box of the polytope `P = {δ ∈ [-1, 1]^n : |r_k·δ| <= 1 for every chosen row}` — the paper's
//! LP step (Section IV) applied to the linearised problem. Its width along parameter `j`,
//! `2 max{δ_j : δ ∈ P}` (P is symmetric), is what [`linearized_widths`] computes, in units of the
//! prior half-width (2 = nothing learnt).
//!
//! **Criteria.** [`Criterion::Certified`] chooses greedily the candidate that most reduces the sum
//! of the logarithms of these widths over all parameters of all groups (the geometric mean of the
//! certified widths, which is what a calibrator reads off the result); a candidate can only change
//! the width along `j` if it cuts the current optimal vertex of that LP, so most LPs are skipped.
//! [`Criterion::DOptimal`] is the classical index: greedily maximise `Σ_groups ln det(I + JᵀJ)`
//! (the product of the singular values of the prior-regularised information matrix).
//!
//! These are predictions to choose poses by, not proofs; the robot crate checks a design by
//! certifying simulated data measured at it.

use calib_core::{DenseSimplex, LpBackend, LpStatus, Polyhedron};
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

/// The rows one candidate configuration adds to one parameter group's scaled identification
/// Jacobian (one row per residual row; each of the group's `dim` columns a parameter).
pub type CandidateRows = Vec<Vec<f64>>;

/// One group of parameters certified together, and the rows each candidate adds to it.
#[derive(Clone, Debug, PartialEq)]
pub struct Group {
    /// The number of parameters (columns).
    pub dim: usize,
    /// Per candidate, its rows.
    pub rows: Vec<CandidateRows>,
}

/// How to rank designs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Criterion {
    /// The geometric mean of the first-order certified widths (see the module documentation).
    #[default]
    Certified,
    /// The product of the singular values of the prior-regularised information matrix
    /// (classical D-optimality).
    DOptimal,
}

impl std::str::FromStr for Criterion {
    type Err = crate::ParseError;

    fn from_str(s: &str) -> Result<Self, crate::ParseError> {
        match s {
            "certified" => Ok(Criterion::Certified),
            "d-optimal" => Ok(Criterion::DOptimal),
            other => Err(crate::ParseError::Criterion(other.to_string())),
        }
    }
}

/// Rows whose first-order slab `|r·δ| <= 1` is cut by a vertex by more than this are re-solved.
const CUT_TOL: f64 = 1e-9;

/// An LP engine and its polyhedron, reused across solves.
#[derive(Default)]
#[doc(hidden)]
pub struct Solver {
    engine: DenseSimplex,
    poly: Polyhedron,
    c: Vec<f64>,
    dual: Vec<f64>,
    primal: Vec<f64>,
}

impl Solver {
    /// Loads `[-1, 1]^dim` cut by `|r·δ| <= 1` for the rows of the chosen candidates (and the
    /// extra rows).
    fn load<'a>(&mut self, dim: usize, rows: impl Iterator<Item = &'a Vec<f64>>) {
        self.poly.reset(&vec![-1.0; dim], &vec![1.0; dim]);
        for r in rows {
            self.poly.push_row(r, 1.0);
            let neg: Vec<f64> = r.iter().map(|v| -v).collect();
            self.poly.push_row(&neg, 1.0);
        }
    }

    /// `max δ_j` over the loaded polytope, and the maximising vertex.
    fn maximize(&mut self, j: usize) -> (f64, Vec<f64>) {
        let n = self.poly.dim();
        self.c.clear();
        self.c.resize(n, 0.0);
        self.c[j] = -1.0;
        self.dual.clear();
        self.dual.resize(self.poly.rows(), 0.0);
        self.primal.clear();
        self.primal.resize(n, 0.0);
        let status = self
            .engine
            .minimize(&self.poly, &self.c, &mut self.dual, &mut self.primal);
        match status {
            // A prediction: the engine's optimum is used as it is (clamped to the prior).
            LpStatus::Optimal => (self.primal[j].clamp(0.0, 1.0), self.primal.clone()),
            // The polytope contains 0, so it is never empty; a failed solve predicts nothing
            // learnt along j.
            _ => {
                let mut corner = vec![0.0; n];
                corner[j] = 1.0;
                (1.0, corner)
            }
        }
    }
}

/// The first-order certified widths (in prior half-widths, 2 = the prior) of one group's
/// parameters when the candidates `chosen` are measured (see the module documentation).
pub fn linearized_widths(group: &Group, chosen: &[usize]) -> Vec<f64> {
    let mut s = Solver::default();
    s.load(group.dim, chosen.iter().flat_map(|&c| &group.rows[c]));
    (0..group.dim).map(|j| 2.0 * s.maximize(j).0).collect()
}

/// The geometric mean, over all parameters of all groups, of [`linearized_widths`].
pub fn linearized_geometric_mean(groups: &[Group], chosen: &[usize]) -> f64 {
    let (sum, n) = groups.iter().fold((0.0, 0usize), |(s, n), g| {
        let w = linearized_widths(g, chosen);
        (s + w.iter().map(|v| v.ln()).sum::<f64>(), n + w.len())
    });
    if n == 0 {
        2.0
    } else {
        (sum / n as f64).exp()
    }
}

/// Per group and parameter: the half-width `max δ_j` and its optimal vertex.
type Optima = Vec<Vec<(f64, Vec<f64>)>>;

#[doc(hidden)]
pub fn optima(groups: &[Group], chosen: &[usize]) -> Optima {
    groups
        .par_iter()
        .map(|g| {
            let mut s = Solver::default();
            s.load(g.dim, chosen.iter().flat_map(|&c| &g.rows[c]));
            (0..g.dim).map(|j| s.maximize(j)).collect()
        })
        .collect()
}

/// The decrease of `Σ ln(width)` if candidate `c` is added to `chosen`, given the current optima.
#[doc(hidden)]
pub fn certified_gain(
    groups: &[Group],
    chosen: &[usize],
    current: &Optima,
    c: usize,
    s: &mut Solver,
) -> f64 {
    let mut gain = 0.0;
    for (g, opt) in groups.iter().zip(current) {
        let rows = &g.rows[c];
        let mut loaded = false;
        for (j, (half, vertex)) in opt.iter().enumerate() {
            let cut = rows.iter().any(|r| {
                let v: f64 = r.iter().zip(vertex).map(|(a, b)| a * b).sum();
                v.abs() > 1.0 + CUT_TOL
            });
            if !cut {
                continue;
            }
            if !loaded {
                s.load(
                    g.dim,
                    chosen.iter().flat_map(|&k| &g.rows[k]).chain(rows.iter()),
                );
                loaded = true;
            }
            let (new, _) = s.maximize(j);
            if *half > 0.0 && new > 0.0 {
                gain += (half / new).ln();
            }
        }
    }
    gain
}

/// The increase of `Σ ln det(I + JᵀJ)` if candidate `c` is added, given the inverses of the
/// current information matrices: `ln det(I + R M⁻¹ Rᵀ)` per group (matrix determinant lemma).
fn d_gain(groups: &[Group], inverses: &[DMatrix<f64>], c: usize) -> f64 {
    groups
        .iter()
        .zip(inverses)
        .map(|(g, m_inv)| {
            let rows = &g.rows[c];
            if rows.is_empty() {
                return 0.0;
            }
            let r = DMatrix::from_fn(rows.len(), g.dim, |i, j| rows[i][j]);
            let s = DMatrix::identity(rows.len(), rows.len()) + &r * m_inv * r.transpose();
            s.determinant().max(f64::MIN_POSITIVE).ln()
        })
        .sum()
}

/// The information matrices' inverses `(I + JᵀJ)⁻¹` of the chosen candidates, per group.
fn information_inverses(groups: &[Group], chosen: &[usize]) -> Vec<DMatrix<f64>> {
    groups
        .iter()
        .map(|g| {
            let mut m = DMatrix::<f64>::identity(g.dim, g.dim);
            for r in chosen.iter().flat_map(|&c| &g.rows[c]) {
                let v = DVector::from_column_slice(r);
                m += &v * v.transpose();
            }
            m.try_inverse()
                .unwrap_or_else(|| DMatrix::identity(g.dim, g.dim))
        })
        .collect()
}

/// Chooses `count` more candidates greedily by `criterion`, after the candidates `start`
/// (configurations already measured, never chosen again). Returns the chosen candidates in the
/// order chosen (so that every prefix is itself a greedy design). Candidates are the indices of
/// each group's `rows`; every group must have the same number of candidates.
pub fn greedy_design(
    groups: &[Group],
    start: &[usize],
    count: usize,
    criterion: Criterion,
    progress: &(dyn Fn() + Sync),
) -> Vec<usize> {
    let candidates = groups.first().map_or(0, |g| g.rows.len());
    let mut taken = vec![false; candidates];
    for &c in start {
        taken[c] = true;
    }
    let mut chosen: Vec<usize> = start.to_vec();
    let mut picked = Vec::with_capacity(count);
    for _ in 0..count.min(candidates.saturating_sub(start.len())) {
        let free: Vec<usize> = (0..candidates).filter(|&c| !taken[c]).collect();
        let best = match criterion {
            Criterion::Certified => {
                let current = optima(groups, &chosen);
                free.par_iter()
                    .map_init(Solver::default, |s, &c| {
                        (certified_gain(groups, &chosen, &current, c, s), c)
                    })
                    .reduce(|| (f64::NEG_INFINITY, usize::MAX), better)
            }
            Criterion::DOptimal => {
                let inverses = information_inverses(groups, &chosen);
                free.par_iter()
                    .map(|&c| (d_gain(groups, &inverses, c), c))
                    .reduce(|| (f64::NEG_INFINITY, usize::MAX), better)
            }
        };
        let c = best.1;
        if c == usize::MAX {
            break;
        }
        taken[c] = true;
        chosen.push(c);
        picked.push(c);
        progress();
    }
    picked
}

/// `Σ ln(width)` over all parameters of all groups (the certified criterion's objective).
#[doc(hidden)]
pub fn log_widths(groups: &[Group], chosen: &[usize]) -> f64 {
    groups
        .par_iter()
        .map(|g| {
            linearized_widths(g, chosen)
                .iter()
                .map(|w| w.ln())
                .sum::<f64>()
        })
        .sum()
}

/// Improves a design for the certified criterion by exchanges (Fedorov's idea, one pose at a
/// time): each chosen candidate in turn is taken out and the best candidate for the freed place
/// put in, while that lowers `Σ ln(width)`; at most `passes` sweeps over the design. `start`
/// stays. Returns the improved `picked` (same length).
pub fn exchange(groups: &[Group], start: &[usize], picked: &[usize], passes: usize) -> Vec<usize> {
    let mut picked = picked.to_vec();
    let all = |p: &[usize]| -> Vec<usize> { start.iter().chain(p).copied().collect() };
    let mut best = log_widths(groups, &all(&picked));
    let candidates = groups.first().map_or(0, |g| g.rows.len());
    for _ in 0..passes {
        let mut improved = false;
        for i in 0..picked.len() {
            let mut rest = picked.clone();
            let out = rest.remove(i);
            let chosen = all(&rest);
            let current = optima(groups, &chosen);
            let (gain, c) = (0..candidates)
                .into_par_iter()
                .filter(|c| !chosen.contains(c))
                .map_init(Solver::default, |s, c| {
                    (certified_gain(groups, &chosen, &current, c, s), c)
                })
                .reduce(|| (f64::NEG_INFINITY, usize::MAX), better);
            if c == usize::MAX || c == out {
                continue;
            }
            rest.insert(i, c);
            let value = log_widths(groups, &all(&rest));
            // The gain was measured against the design without `out`: keep the swap only if the
            // whole design improves (by more than rounding).
            if value < best - 1e-9 && gain.is_finite() {
                best = value;
                picked = rest;
                improved = true;
            }
        }
        if !improved {
            break;
        }
    }
    picked
}

/// The design of the `certified` criterion: the greedy certified design and the greedy D-optimal
/// one, each improved by [`exchange`] (`passes` sweeps), whichever has the smaller geometric mean
/// of the first-order widths (greedy steps alone can stop short of the D-optimal design). Also
/// returns the greedy certified order (every prefix a greedy design), for prefix questions.
pub fn certified_design(
    groups: &[Group],
    start: &[usize],
    count: usize,
    passes: usize,
    progress: &(dyn Fn() + Sync),
) -> (Vec<usize>, Vec<usize>) {
    let sequence = greedy_design(groups, start, count, Criterion::Certified, progress);
    let d_optimal = greedy_design(groups, start, count, Criterion::DOptimal, &|| {});
    let best = [sequence.clone(), d_optimal]
        .map(|p| exchange(groups, start, &p, passes))
        .into_iter()
        .map(|p| {
            let all: Vec<usize> = start.iter().chain(&p).copied().collect();
            (linearized_geometric_mean(groups, &all), p)
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, p)| p)
        .unwrap_or_default();
    (best, sequence)
}

/// The larger gain; ties go to the lower candidate index (deterministic whatever the threads).
fn better(a: (f64, usize), b: (f64, usize)) -> (f64, usize) {
    match a.0.total_cmp(&b.0) {
        std::cmp::Ordering::Greater => a,
        std::cmp::Ordering::Less => b,
        std::cmp::Ordering::Equal => {
            if a.1 <= b.1 {
                a
            } else {
                b
            }
        }
    }
}
