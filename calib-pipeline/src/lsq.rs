//! Classical calibration for any model: Levenberg–Marquardt least squares (the `levenberg-marquardt`
//! crate on nalgebra) over the free parameters, from the nominal, with the readings' centres as
//! exact measurements. What certicalib compares against: a least-squares solution is one point,
//! and nothing says it fits the data within their error bounds (the paper's point).

use calib_core::VectorModel;
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::storage::Owned;
use nalgebra::{DMatrix, DVector, Dyn};

/// A least-squares fit.
#[derive(Clone, Debug, PartialEq)]
pub struct Fit {
    /// The fitted parameters (every parameter; fixed ones at their start value).
    pub x: Vec<f64>,
    /// Whether the solver reported convergence.
    pub converged: bool,
    /// Root mean square of every residual row at the fit.
    pub rms: f64,
    /// Largest residual row magnitude at the fit.
    pub max_abs: f64,
    /// Residual evaluations spent.
    pub evaluations: usize,
}

struct Problem<'a, M, const NX: usize, const NM: usize, const NR: usize> {
    model: &'a M,
    x: [f64; NX],
    free: &'a [usize],
    readings: &'a [[f64; NM]],
}

impl<M, const NX: usize, const NM: usize, const NR: usize> LeastSquaresProblem<f64, Dyn, Dyn>
    for Problem<'_, M, NX, NM, NR>
where
    M: VectorModel<NX, NM, NR>,
{
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, p: &DVector<f64>) {
        for (c, &j) in self.free.iter().enumerate() {
            self.x[j] = p[c];
        }
    }

    fn params(&self) -> DVector<f64> {
        DVector::from_iterator(self.free.len(), self.free.iter().map(|&j| self.x[j]))
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        let values = self
            .readings
            .iter()
            .flat_map(|m| self.model.residuals(&self.x, m));
        let r = DVector::from_iterator(self.readings.len() * NR, values);
        r.iter().all(|v| v.is_finite()).then_some(r)
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let mut j = DMatrix::zeros(self.readings.len() * NR, self.free.len());
        for (k, m) in self.readings.iter().enumerate() {
            for (r, e) in self.model.evaluate_rows(&self.x, m).iter().enumerate() {
                for (c, &p) in self.free.iter().enumerate() {
                    j[(k * NR + r, c)] = e.dx[p];
                }
            }
        }
        j.iter().all(|v| v.is_finite()).then_some(j)
    }
}

/// Fits the parameters `free` (indices) from `start` to the readings (one per configuration).
pub fn least_squares<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    start: &[f64; NX],
    free: &[usize],
    readings: &[[f64; NM]],
) -> Fit
where
    M: VectorModel<NX, NM, NR>,
{
    let problem = Problem {
        model,
        x: *start,
        free,
        readings,
    };
    let (problem, report) = LevenbergMarquardt::new()
        .with_patience(200)
        .minimize(problem);
    let x = problem.x;
    let residuals: Vec<f64> = readings
        .iter()
        .flat_map(|m| model.residuals(&x, m))
        .collect();
    let n = residuals.len().max(1) as f64;
    Fit {
        x: x.to_vec(),
        converged: report.termination.was_successful(),
        rms: (residuals.iter().map(|v| v * v).sum::<f64>() / n).sqrt(),
        max_abs: residuals.iter().fold(0.0, |m, v| m.max(v.abs())),
        evaluations: report.number_of_evaluations,
    }
}
