//! The kernel's settings, with the paper's values as defaults.

use crate::lp::LpEngine;

/// Which linear relaxation of the solution set the Newton step builds (paper Section IV-B).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Relaxation {
    /// The paper's: the centred form at the box midpoint (eqs. 6–7) with the Krawczyk split
    /// `A = mid(A) + (A - mid(A))`: two rows per measurement.
    Krawczyk,
    /// Corner linearisations ("X-Newton"): the mean-value form at two opposite corners of the box,
    /// where the sign of `x - corner` is known, so each interval Jacobian entry contributes one of
    /// its bounds: four rows per measurement. The first step uses the lowest and highest corners,
    /// later steps other opposite pairs. The default: on exact simulated Gough data it converges
    /// to radii ~1e-7..3e-6 where the paper's relaxation stalls near 1e-2 on some legs, and on
    /// noisy data it is 5–20% tighter on the well-determined parameters.
    #[default]
    Corners,
    /// Both families of rows in one LP: six rows per measurement; on simulated Gough data at most a
    /// few percent tighter than `Corners` and about 1.5x slower.
    Both,
}

/// Settings of [`crate::certify`], [`crate::hull`], [`crate::sweep`] and [`crate::pave`].
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// Stop the fixed-point iteration when `‖rad(x_j)‖₁ - ‖rad(x_{j+1})‖₁ < delta`
    /// (paper Section IV-A; default `1e-8` as in the paper).
    pub delta: f64,
    /// At most this many Newton/LP contractions per box (default 100).
    pub max_iterations: usize,
    /// The linear relaxation (default [`Relaxation::Corners`]).
    pub relaxation: Relaxation,
    /// The LP engine (default [`LpEngine::DenseSimplex`]).
    pub lp: LpEngine,
    /// Search certified witnesses near each parameter's extremes for inner bounds (default true).
    /// [`crate::hull`] without inner bounds refines the outer box alone until its budget is spent.
    pub inner_bounds: bool,
    /// Bisection steps of the inner-bound search along each segment (default 24).
    pub inner_bisections: usize,
    /// The sweep splits each dimension at this fraction of the width from the lower (then upper)
    /// bound (paper Section V: 5%, default 0.05).
    pub sweep_fraction: f64,
    /// Sweep steps from the lower bounds, then as many from the upper bounds (paper: 4).
    pub sweep_steps: usize,
    /// Contract the boxes of a sweep step, of the paver and of a [`crate::hull`] round in parallel
    /// (rayon; default true).
    pub parallel: bool,
    /// [`crate::hull`] stops refining a parameter once `wid(outer) <= (1 + tol) wid(inner)`
    /// (default 0.05).
    pub hull_tolerance: f64,
    /// [`crate::hull`] contracts at most this many boxes (default 200 000).
    pub hull_max_boxes: usize,
    /// Tolerate up to this many outliers (default 0): [`crate::certify`], [`crate::hull`] and
    /// [`crate::sweep`] then enclose every parameter vector that fits at least `p - q` of the `p`
    /// measurements (the union over every choice of `q` dropped measurements, `C(p, q)` subsets,
    /// at most 20 000 of them; beyond, the initial box is returned undecided).
    pub max_outliers: usize,
    /// [`crate::hull`] stops starting new rounds after this many seconds (default: no limit; a
    /// time limit makes the result depend on the machine's speed).
    pub hull_max_seconds: Option<f64>,
    /// For an `Empty` verdict without outliers tolerated, [`crate::certify`] and [`crate::hull`]
    /// also search a minimal set of conflicting measurements (default true; more certifications
    /// of subsets). Off when only the verdict matters, e.g. while searching the smallest number
    /// of outliers to tolerate.
    pub conflict_sets: bool,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            delta: 1e-8,
            max_iterations: 100,
            relaxation: Relaxation::default(),
            lp: LpEngine::default(),
            inner_bounds: true,
            inner_bisections: 24,
            sweep_fraction: 0.05,
            sweep_steps: 4,
            parallel: true,
            hull_tolerance: 0.05,
            hull_max_boxes: 200_000,
            hull_max_seconds: None,
            max_outliers: 0,
            conflict_sets: true,
        }
    }
}

impl Settings {
    /// The settings with another relaxation.
    pub fn with_relaxation(mut self, relaxation: Relaxation) -> Self {
        self.relaxation = relaxation;
        self
    }

    /// The settings with another LP engine.
    pub fn with_lp(mut self, lp: LpEngine) -> Self {
        self.lp = lp;
        self
    }

    /// The settings with another [`crate::hull`] tolerance (see [`Settings::hull_tolerance`]).
    pub fn with_hull_tolerance(mut self, tol: f64) -> Self {
        self.hull_tolerance = tol;
        self
    }

    /// The settings with other [`crate::hull`] budgets: boxes contracted and seconds.
    pub fn with_hull_budget(mut self, max_boxes: usize, max_seconds: Option<f64>) -> Self {
        self.hull_max_boxes = max_boxes;
        self.hull_max_seconds = max_seconds;
        self
    }

    /// The settings with up to `q` outliers tolerated (see [`Settings::max_outliers`]).
    pub fn with_max_outliers(mut self, q: usize) -> Self {
        self.max_outliers = q;
        self
    }

    /// The settings with the conflict-set search on or off (see [`Settings::conflict_sets`]).
    pub fn with_conflict_sets(mut self, on: bool) -> Self {
        self.conflict_sets = on;
        self
    }

    /// The settings with parallelism switched on or off.
    pub fn with_parallel(mut self, parallel: bool) -> Self {
        self.parallel = parallel;
        self
    }
}
