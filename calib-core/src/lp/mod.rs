//! Linear programs over a box: the LP engines and the rigorous bound that turns their answers into
//! proofs.
//!
//! Every LP here has the form `min c·y  s.t.  G y <= g,  lo <= y <= hi` (a [`Polyhedron`]). An engine
//! ([`LpBackend`]) returns a *hint*: a primal point and multipliers `λ` for the rows of `G`. The
//! certified bound comes from [`safe_lower_bound`] (Neumaier–Shcherbina): for any `λ >= 0`,
//! `c·y >= inf((c + Gᵀλ)·[lo, hi]) - sup(λ·g)` for every feasible `y`, evaluated in interval
//! arithmetic. A wrong, inaccurate or failed solve can only weaken the bound, never invalidate it.

mod basis;
mod clarabel_backend;
mod dense_simplex;
mod polyhedron;
mod safe_bound;
mod scaled_simplex;

pub use clarabel_backend::ClarabelLp;
pub use dense_simplex::DenseSimplex;
pub(crate) use dense_simplex::SMALL_DIM;
pub use polyhedron::Polyhedron;
pub use safe_bound::{proves_infeasible, safe_lower_bound};

/// What an LP engine reports. Whatever it says, the caller checks it rigorously.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LpStatus {
    /// An (approximately) optimal primal point and multipliers were written.
    Optimal,
    /// The engine believes the polyhedron is empty and wrote a Farkas ray into the multipliers
    /// (to be checked with [`proves_infeasible`]).
    Infeasible,
    /// The engine did not converge; the multipliers may still be usable (any `λ >= 0` gives a
    /// valid, possibly weak, bound).
    Failed,
}

/// An LP engine: approximately minimises a linear objective over a [`Polyhedron`].
pub trait LpBackend: Send {
    /// A short name for reports.
    fn name(&self) -> &'static str;

    /// Approximately solves `min c·y` over `p`. Writes multipliers for the rows of `G` into
    /// `dual` (length `p.rows()`) and a primal point into `primal` (length `p.dim()`).
    fn minimize(
        &mut self,
        p: &Polyhedron,
        c: &[f64],
        dual: &mut [f64],
        primal: &mut [f64],
    ) -> LpStatus;

    /// Forgets what earlier solves left behind to start later ones from (remembered optimal
    /// bases), so that the next answers depend only on the problems given from now on. The
    /// contraction calls it before each box: boxes reach worker threads in an unpredictable
    /// order, and the results must not depend on it. The default has nothing to forget.
    fn forget(&mut self) {}

    /// What later solves would start from (the remembered optimal bases, rows by their tags), to
    /// start another engine's solves from the same place with [`LpBackend::restore`]: the hull
    /// hands a box's bases to its halves, so that their first Newton/LP step starts warm and the
    /// result still depends only on the box's own history. The default remembers nothing.
    fn memory(&self) -> LpMemory {
        LpMemory::default()
    }

    /// Forgets everything (as [`LpBackend::forget`]) and then starts later solves from `memory`
    /// (from [`LpBackend::memory`] of an engine of the same kind; an empty memory is a plain
    /// forget). The default only forgets.
    fn restore(&mut self, memory: &LpMemory) {
        let _ = memory;
        self.forget();
    }

    /// Whether the contraction should skip an LP whose bound an optimal point of an earlier LP of
    /// the same step already attains (for problems of `dim` variables). Skipping never changes
    /// the box the LP would give, but it changes where the engine's next solve starts: an engine
    /// that walks on from the previous objective's optimum gains, one that remembers a basis per
    /// objective loses (measured: the Gough leg's hull 20-25% faster, the 44-variable arm 20%
    /// slower). The default does not skip.
    fn skips_attained_bounds(&self, _dim: usize) -> bool {
        false
    }
}

/// A constraint of a remembered basis: a row by its tag ([`Polyhedron::begin_group`]), or a box
/// bound by its offset `2j` (upper) or `2j + 1` (lower).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Remembered {
    Row(u64),
    Bound(usize),
}

/// The optimal bases an engine remembers per unit objective `±y_j` (slot `2j`, `2j + 1`), to start
/// later solves of the same objective from ([`LpBackend::memory`], [`LpBackend::restore`]). Only a
/// hint for where a walk starts: the bounds are rigorous whatever it holds (where the walks end,
/// and so the bounds' last digits, may differ).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LpMemory {
    pub(super) bases: Vec<Option<Vec<Remembered>>>,
}

impl LpMemory {
    /// Whether it remembers no basis.
    pub fn is_empty(&self) -> bool {
        self.bases.iter().all(Option::is_none)
    }
}

/// Which LP engine the kernel uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum LpEngine {
    /// A dense active-set dual simplex for tiny problems, cold-started per objective
    /// ([`DenseSimplex`]); allocation-free after warm-up. The default: measured faster (see the
    /// `sweep` benchmark).
    #[default]
    DenseSimplex,
    /// The interior-point solver `clarabel` ([`ClarabelLp`]), built once per polyhedron and updated
    /// per objective; the reference engine.
    Clarabel,
}

impl LpEngine {
    /// A fresh engine of this kind.
    pub fn backend(self) -> Box<dyn LpBackend> {
        match self {
            LpEngine::DenseSimplex => Box::new(DenseSimplex::default()),
            LpEngine::Clarabel => Box::new(ClarabelLp::default()),
        }
    }
}

/// `y in [-1, 1]^2, y0 + y1 <= 1, -y0 + y1 <= 0.5`: the polyhedron of the LP unit tests.
#[cfg(test)]
pub(crate) fn small_test_polyhedron() -> Polyhedron {
    let mut p = Polyhedron::default();
    p.reset(&[-1.0, -1.0], &[1.0, 1.0]);
    p.push_row(&[1.0, 1.0], 1.0);
    p.push_row(&[-1.0, 1.0], 0.5);
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small() -> Polyhedron {
        small_test_polyhedron()
    }

    #[test]
    fn every_engine_solves_small_lps_and_certifies_infeasibility() {
        for engine in [LpEngine::DenseSimplex, LpEngine::Clarabel] {
            let mut lp = engine.backend();
            let p = small();
            let (mut dual, mut y) = ([0.0; 2], [0.0; 2]);
            // max y1: 0.75 at (0.25, 0.75).
            assert_eq!(
                lp.minimize(&p, &[0.0, -1.0], &mut dual, &mut y),
                LpStatus::Optimal
            );
            let b = safe_lower_bound(&p, &[0.0, -1.0], &dual);
            assert!(b <= -0.75 && b > -0.75 - 1e-6, "{}: {b}", lp.name());
            assert!((y[1] - 0.75).abs() < 1e-6, "{}: {y:?}", lp.name());
            // Same polyhedron, new objectives (warm start / solver reuse): min y0 = -1.
            assert_eq!(
                lp.minimize(&p, &[1.0, 0.0], &mut dual, &mut y),
                LpStatus::Optimal
            );
            assert!(safe_lower_bound(&p, &[1.0, 0.0], &dual) <= -1.0 + 1e-6);
            assert!(safe_lower_bound(&p, &[1.0, 0.0], &dual) > -1.0 - 1e-6);
            assert_eq!(
                lp.minimize(&p, &[-1.0, -1.0], &mut dual, &mut y),
                LpStatus::Optimal
            );
            let b = safe_lower_bound(&p, &[-1.0, -1.0], &dual);
            assert!(
                b <= -1.0 && b > -1.0 - 1e-6,
                "{}: max y0 + y1 is 1, bound {b}",
                lp.name()
            );
            // An empty polyhedron: y0 + y1 <= -0.5 and y0 + y1 >= 0.5.
            let mut q = Polyhedron::default();
            q.reset(&[-1.0, -1.0], &[1.0, 1.0]);
            q.push_row(&[1.0, 1.0], -0.5);
            q.push_row(&[-1.0, -1.0], -0.5);
            assert_eq!(
                lp.minimize(&q, &[1.0, 0.0], &mut dual, &mut y),
                LpStatus::Infeasible
            );
            assert!(proves_infeasible(&q, &dual, &[0.0, 0.0]), "{}", lp.name());
        }
    }
}
