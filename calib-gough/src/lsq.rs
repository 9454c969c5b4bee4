//! Classical calibration: Levenberg–Marquardt least squares per leg (the paper's comparison), with
//! the `levenberg-marquardt` crate on nalgebra.
//!
//! Minimises `Σ_k f(x, M_k)²` over `x = (a, b, l)` with `M_k` the measured values (box centres),
//! starting from the nominal geometry; the residual and Jacobian come from the generated
//! evaluators of the data's [`crate::LegModel`].

use crate::LegModel;
use calib_core::Model;
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::storage::Owned;
use nalgebra::{Dyn, OMatrix, OVector, U7};

struct LegProblem<'a> {
    x: OVector<f64, U7>,
    model: LegModel,
    measurements: &'a [[f64; 8]],
}

impl LeastSquaresProblem<f64, Dyn, U7> for LegProblem<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, U7>;
    type ParameterStorage = Owned<f64, U7>;

    fn set_params(&mut self, x: &OVector<f64, U7>) {
        self.x.copy_from(x);
    }

    fn params(&self) -> OVector<f64, U7> {
        self.x
    }

    fn residuals(&self) -> Option<OVector<f64, Dyn>> {
        let x: [f64; 7] = self.x.into();
        Some(OVector::<f64, Dyn>::from_iterator(
            self.measurements.len(),
            self.measurements.iter().map(|m| self.model.residual(&x, m)),
        ))
    }

    fn jacobian(&self) -> Option<OMatrix<f64, Dyn, U7>> {
        let x: [f64; 7] = self.x.into();
        let mut j = OMatrix::<f64, Dyn, U7>::zeros(self.measurements.len());
        for (k, m) in self.measurements.iter().enumerate() {
            let d = self.model.jacobian_x(&x, m);
            for (c, v) in d.iter().enumerate() {
                j[(k, c)] = *v;
            }
        }
        Some(j)
    }
}

/// A least-squares fit of one leg.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// The fitted parameters `(a, b, l)`.
    pub x: [f64; 7],
    /// Whether the solver reported convergence.
    pub converged: bool,
    /// Root mean square of the residuals `f(x, M_k)` (cm²).
    pub rms: f64,
    /// Largest leg-length residual `| ||P + R b - a|| - (L + l) |` (cm).
    pub max_length_error: f64,
}

/// Fits one leg from `start` to the measurements (each in the order of `model`'s `M`, e.g.
/// [`crate::leg_values`]).
pub fn fit_leg(start: &[f64; 7], model: LegModel, measurements: &[[f64; 8]]) -> Fit {
    let problem = LegProblem {
        x: OVector::<f64, U7>::from(*start),
        model,
        measurements,
    };
    let (solved, report) = LevenbergMarquardt::new().minimize(problem);
    let x: [f64; 7] = solved.x.into();
    let residuals: Vec<f64> = measurements.iter().map(|m| model.residual(&x, m)).collect();
    let rms = (residuals.iter().map(|r| r * r).sum::<f64>() / residuals.len().max(1) as f64).sqrt();
    // f = d² - (L + l)², so the length error is f / (d + L + l) ≈ f / (2 (L + l)).
    let max_length_error = measurements
        .iter()
        .zip(&residuals)
        .map(|(m, r)| (r / (2.0 * (m[7] + x[6]))).abs())
        .fold(0.0, f64::max);
    Fit {
        x,
        converged: report.termination.was_successful(),
        rms,
        max_length_error,
    }
}

/// Least squares for every leg of `robot` from its nominal geometry (in parallel, in leg order):
/// what `gough lsq` prints.
pub fn fit_legs(robot: &[crate::files::LegSpec], configs: &[crate::Configuration]) -> Vec<Fit> {
    use rayon::prelude::*;
    (0..robot.len())
        .into_par_iter()
        .map(|leg| {
            fit_leg(
                &robot[leg].nominal.params(),
                LegModel::of(configs),
                &crate::leg_values(configs, leg),
            )
        })
        .collect()
}
