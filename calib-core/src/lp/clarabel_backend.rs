//! The reference LP engine: the interior-point solver `clarabel`.
//!
//! The problem `min c·y, G y <= g, lo <= y <= hi` is passed as `A y + s = b, s >= 0` with `A` the rows
//! of `G` followed by `±I` for the box. The solver is built once per polyhedron (its
//! [`Polyhedron::generation`]) and only the objective is updated (`update_q`) for the `2n` solves over
//! the same polyhedron. Its dual `z` restricted to the rows of `G` is the multiplier hint; tiny
//! interior-point multipliers of inactive rows are kept (any `λ >= 0` is valid for the safe bound).

use super::{LpBackend, LpStatus, Polyhedron};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};

/// The `clarabel` engine (see the module documentation).
#[derive(Default)]
pub struct ClarabelLp {
    solver: Option<(u64, DefaultSolver<f64>)>,
    /// Whether iterative refinement is off ([`ClarabelLp::for_hints`]).
    hints_only: bool,
}

impl ClarabelLp {
    /// An engine whose answers serve only as hints checked elsewhere (the candidate points of the
    /// hull's pushes, each certified afterwards): the KKT solves skip iterative refinement, and
    /// the iterations stop at gaps and infeasibilities of 1e-6 instead of 1e-8: on the arm's hull,
    /// the same boxes and ratios sooner without refinement, and more boxes with tighter ratios in
    /// the same time with the looser tolerances (1e-4 was far worse; `benches/README.md` has the
    /// measurements). Its multipliers still give rigorous bounds through
    /// [`super::safe_lower_bound`], only possibly weaker ones.
    pub fn for_hints() -> Self {
        ClarabelLp {
            solver: None,
            hints_only: true,
        }
    }
}

fn settings(hints_only: bool) -> DefaultSettings<f64> {
    DefaultSettingsBuilder::default()
        .verbose(false)
        .presolve_enable(false)
        .input_sparse_dropzeros(false)
        .iterative_refinement_enable(!hints_only)
        .tol_gap_abs(if hints_only { 1e-6 } else { 1e-8 })
        .tol_gap_rel(if hints_only { 1e-6 } else { 1e-8 })
        .tol_feas(if hints_only { 1e-6 } else { 1e-8 })
        .build()
        .expect("static clarabel settings are valid")
}

fn build(p: &Polyhedron, c: &[f64], hints_only: bool) -> Option<DefaultSolver<f64>> {
    let (n, m) = (p.dim(), p.rows());
    let rows = m + 2 * n;
    // Column-major (CSC) A: column j holds G[i][j] for all i, then +1 at m + 2j, -1 at m + 2j + 1.
    let mut colptr = Vec::with_capacity(n + 1);
    let mut rowval = Vec::with_capacity((m + 2) * n);
    let mut nzval = Vec::with_capacity((m + 2) * n);
    for j in 0..n {
        colptr.push(rowval.len());
        for i in 0..m {
            rowval.push(i);
            nzval.push(p.row(i)[j]);
        }
        rowval.push(m + 2 * j);
        nzval.push(1.0);
        rowval.push(m + 2 * j + 1);
        nzval.push(-1.0);
    }
    colptr.push(rowval.len());
    let a = CscMatrix::new(rows, n, colptr, rowval, nzval);
    let mut b: Vec<f64> = (0..m).map(|i| p.rhs(i)).collect();
    for j in 0..n {
        b.push(p.hi()[j]);
        b.push(-p.lo()[j]);
    }
    let pmat = CscMatrix::zeros((n, n));
    let cones = [SupportedConeT::NonnegativeConeT(rows)];
    DefaultSolver::new(&pmat, c, &a, &b, &cones, settings(hints_only)).ok()
}

impl LpBackend for ClarabelLp {
    fn name(&self) -> &'static str {
        "clarabel"
    }

    fn minimize(
        &mut self,
        p: &Polyhedron,
        c: &[f64],
        dual: &mut [f64],
        primal: &mut [f64],
    ) -> LpStatus {
        dual.iter_mut().for_each(|v| *v = 0.0);
        let reuse = matches!(&self.solver, Some((g, _)) if *g == p.generation());
        if reuse {
            let (_, solver) = self.solver.as_mut().expect("checked above");
            if solver.update_q(&c.to_vec()).is_err() {
                self.solver = None;
            }
        }
        if !matches!(&self.solver, Some((g, _)) if *g == p.generation()) {
            match build(p, c, self.hints_only) {
                Some(s) => self.solver = Some((p.generation(), s)),
                None => return LpStatus::Failed,
            }
        }
        let (_, solver) = self.solver.as_mut().expect("built above");
        solver.solve();
        let sol = &solver.solution;
        let m = p.rows();
        dual[..m].copy_from_slice(&sol.z[..m]);
        primal.copy_from_slice(&sol.x);
        match sol.status {
            SolverStatus::Solved | SolverStatus::AlmostSolved => LpStatus::Optimal,
            SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
                LpStatus::Infeasible
            }
            _ => LpStatus::Failed,
        }
    }
}
