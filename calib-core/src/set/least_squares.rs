//! The regularised least-squares fit *within* the consistent set: the target of the calibrated
//! point's [`crate::PointRule::LeastSquares`] rule.
//!
//! Near the smallest consistent error bound the plain least-squares fit lies outside the set, and
//! the segment towards it stops close to the minimax fit, which predicts unseen configurations
//! poorly. Fitted *inside* the set, least squares overfits instead: the parameters the data hardly
//! determine run to the faces of the box to absorb errors the model does not have (on the real
//! UR10 at 0.6 mm, held-out rms 0.59 mm against 0.33 mm below). The target here is the
//! regularised fit inside the set, the box `x` (the certified outer box: the prior wherever the
//! data leave it) counting as one more measurement of every parameter:
//!
//! `min_δ Σ_r ((f_r + ∂f_r/∂x · δ) / w_r)² + λ Σ_j ((x_j + δ_j - mid x_j) / rad x_j)²`
//! subject to `|f_r + ∂f_r/∂x · δ| <= θ w_r` for every row and coupling combination and `x + δ`
//! in the box,
//!
//! with `w_r` the row's first-order half-range over its measurement box (paper eq. 6) and
//! `θ` = [`SHRINK`] leaving room for the curvature: a convex quadratic program (`clarabel`),
//! repeated from the new point while the objective falls and the point still fits to first order.
//! The weight `λ` of the prior is chosen by [`CROSS_VALIDATION_FOLDS`]-fold cross-validation over
//! the configurations ([`PRIOR_WEIGHTS`], the one-standard-error rule), so that it is the data that
//! say how much the box's centre is worth. A target, never a proof: the calibrated
//! point is the last point of the segment towards it that [`crate::is_consistent_point`] accepts.

use crate::model::coupling::for_each_linearised_row;
use crate::{Evaluation, Interval, VectorModel};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};
use rayon::prelude::*;

/// The fraction of every first-order half-range the quadratic program may use.
pub(crate) const SHRINK: f64 = 0.98;

/// The prior weights `λ` cross-validation chooses from.
pub const PRIOR_WEIGHTS: [f64; 9] = [0.0, 0.01, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0, 30.0];

/// The number of cross-validation folds (configuration `k` is left out in fold `k mod
/// CROSS_VALIDATION_FOLDS`).
pub const CROSS_VALIDATION_FOLDS: usize = 5;

/// At most this many quadratic programs.
const STEPS: usize = 6;

/// The target and the prior weight it was fitted with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SetFit<const NX: usize> {
    /// The regularised least-squares point of the linearised set.
    pub x: [f64; NX],
    /// The prior weight `λ` cross-validation chose.
    pub prior_weight: f64,
}

/// One row of the objective, scaled: `(f_r / w_r, rad x ∘ ∂f_r/∂x / w_r)`.
struct ScaledRow {
    value: f64,
    gradient: Vec<f64>,
}

/// The regularised least-squares point of the set linearised around `start` (see the module
/// documentation), `start` itself when no step improves on it. `start` should fit every
/// measurement to first order (the deepest point does), so that the first program is feasible.
pub fn least_squares_in_set<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
    start: [f64; NX],
) -> SetFit<NX>
where
    M: VectorModel<NX, NM, NR> + Sync,
{
    let live: Vec<usize> = (0..NX).filter(|&j| x[j].wid() > 0.0).collect();
    let prior_weight = cross_validated_weight(model, x, measurements, &start, &live);
    let mut p = start;
    let objective = |q: &[f64; NX]| objective(model, x, measurements, q, prior_weight);
    let Some((mut best, _)) = objective(&p) else {
        return SetFit { x: p, prior_weight };
    };
    for _ in 0..STEPS {
        let Some(step) = quadratic_step(model, x, measurements, &p, &live, prior_weight) else {
            break;
        };
        // The full step, or shorter ones while the point leaves the linearised set or the
        // objective grows (the linearisation's error).
        let mut t = 1.0;
        let mut accepted = None;
        for _ in 0..4 {
            let q: [f64; NX] =
                core::array::from_fn(|j| (p[j] + t * step[j]).clamp(x[j].inf(), x[j].sup()));
            if let Some((s, true)) = objective(&q) {
                if s < best {
                    accepted = Some((s, q));
                    break;
                }
            }
            t *= 0.5;
        }
        let Some((s, q)) = accepted else { break };
        let gain = best - s;
        (best, p) = (s, q);
        if gain <= 1e-9 * best {
            break;
        }
    }
    SetFit { x: p, prior_weight }
}

/// The scaled residual rows of one configuration at `p` (unknowns in units of the box's
/// half-widths over the `live` parameters).
fn scaled_rows<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    m: &[Interval; NM],
    p: &[f64; NX],
    live: &[usize],
) -> Vec<ScaledRow>
where
    M: VectorModel<NX, NM, NR>,
{
    scaled(&model.evaluate_rows(p, &m.map(|v| v.mid())), x, m, live)
}

/// [`scaled_rows`] of the evaluated rows `e` of the configuration `m`.
fn scaled<const NX: usize, const NM: usize, const NR: usize>(
    e: &[Evaluation<f64, NX, NM>; NR],
    x: &[Interval; NX],
    m: &[Interval; NM],
    live: &[usize],
) -> Vec<ScaledRow> {
    e.iter()
        .filter_map(|r| {
            let w: f64 = (0..NM).map(|i| r.dm[i].abs() * m[i].rad()).sum();
            (w > 0.0).then(|| ScaledRow {
                value: r.value / w,
                gradient: live.iter().map(|&j| r.dx[j] * x[j].rad() / w).collect(),
            })
        })
        .collect()
}

/// The objective at `p` and whether `p` fits every row and coupling combination to first order
/// (`|f| <= w`). `None` when a value is not finite.
fn objective<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
    p: &[f64; NX],
    prior_weight: f64,
) -> Option<(f64, bool)>
where
    M: VectorModel<NX, NM, NR>,
{
    let (mut sum, mut fits) = (0.0, true);
    for m in measurements {
        let e = model.evaluate_rows(p, &m.map(|v| v.mid()));
        sum += scaled(&e, x, m, &[])
            .iter()
            .map(|r| r.value * r.value)
            .sum::<f64>();
        for_each_linearised_row(&e, &m.map(|v| v.rad()), |value, _, w| {
            fits &= value.abs() <= w;
        });
    }
    sum += prior_weight * prior_term(x, p);
    sum.is_finite().then_some((sum, fits))
}

/// `Σ_j ((p_j - mid x_j) / rad x_j)²` over the parameters the box leaves free.
fn prior_term<const NX: usize>(x: &[Interval; NX], p: &[f64; NX]) -> f64 {
    (0..NX)
        .filter(|&j| x[j].rad() > 0.0)
        .map(|j| ((p[j] - x[j].mid()) / x[j].rad()).powi(2))
        .sum()
}

/// The prior weight of [`PRIOR_WEIGHTS`] chosen by [`CROSS_VALIDATION_FOLDS`]-fold
/// cross-validation: fold `f` holds a contiguous block of configurations (measured series move
/// along paths: interleaved folds would test each configuration against its neighbours and favour
/// overfitting); each weight's first quadratic program at `p` over the other folds predicts the
/// fold's scaled residuals (linearised at `p`); the score is the mean over the folds of their sums
/// of squares. By the one-standard-error rule, the largest weight whose score is within one
/// standard error of the best. 0 with fewer than two configurations or when no program can be
/// solved.
fn cross_validated_weight<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
    p: &[f64; NX],
    live: &[usize],
) -> f64
where
    M: VectorModel<NX, NM, NR> + Sync,
{
    let n = live.len();
    let folds = CROSS_VALIDATION_FOLDS.min(measurements.len());
    if n == 0 || folds < 2 {
        return 0.0;
    }
    let rows: Vec<Vec<ScaledRow>> = measurements
        .iter()
        .map(|m| scaled_rows(model, x, m, p, live))
        .collect();
    let len = measurements.len();
    // Per weight (in parallel: each is independent of the others): the mean over the folds of
    // each fold's sum of squares, and its standard error.
    let scores: Vec<(f64, f64, f64)> = PRIOR_WEIGHTS
        .par_iter()
        .filter_map(|&weight| {
            let mut errors = Vec::with_capacity(folds);
            for fold in 0..folds {
                let in_fold = |k: usize| k * folds / len == fold;
                let training: Vec<[Interval; NM]> = measurements
                    .iter()
                    .enumerate()
                    .filter(|(k, _)| !in_fold(*k))
                    .map(|(_, m)| *m)
                    .collect();
                let step = quadratic_step(model, x, &training, p, live, weight)?;
                let y: Vec<f64> = live.iter().map(|&j| step[j] / x[j].rad()).collect();
                let error: f64 = (0..len)
                    .filter(|&k| in_fold(k))
                    .flat_map(|k| &rows[k])
                    .map(|row| {
                        let v = row.value + (0..n).map(|a| row.gradient[a] * y[a]).sum::<f64>();
                        v * v
                    })
                    .sum();
                errors.push(error);
            }
            let mean = errors.iter().sum::<f64>() / folds as f64;
            let variance =
                errors.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / (folds - 1) as f64;
            (mean.is_finite() && variance.is_finite())
                .then(|| (weight, mean, (variance / folds as f64).sqrt()))
        })
        .collect();
    // The one-standard-error rule: the largest weight whose score is within one standard error
    // of the best score (the simplest model the folds cannot tell from the best).
    let Some(&(_, best, error)) = scores.iter().min_by(|a, b| a.1.total_cmp(&b.1)) else {
        return 0.0;
    };
    scores
        .iter()
        .filter(|s| s.1 <= best + error + 1e-12 * best)
        .map(|s| s.0)
        .fold(0.0, f64::max)
}

/// One quadratic program at `p` over the `live` parameters: the step `δ` (zero elsewhere), or
/// `None` when the solver does not report a solution. Unknowns in units of the box's half-widths.
fn quadratic_step<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
    p: &[f64; NX],
    live: &[usize],
    prior_weight: f64,
) -> Option<[f64; NX]>
where
    M: VectorModel<NX, NM, NR>,
{
    let n = live.len();
    if n == 0 {
        return None;
    }
    // Objective ½ yᵀ (Gᵀ G + λ I) y + (Gᵀ f + λ offset)·y; constraints A y <= b.
    let mut normal = vec![0.0; n * n];
    let mut linear: Vec<f64> = live
        .iter()
        .map(|&j| prior_weight * (p[j] - x[j].mid()) / x[j].rad())
        .collect();
    let (mut a_rows, mut b_vec): (Vec<Vec<f64>>, Vec<f64>) = (Vec::new(), Vec::new());
    for m in measurements {
        // One evaluation per configuration: the objective's rows and the constraints.
        let e = model.evaluate_rows(p, &m.map(|v| v.mid()));
        for row in scaled(&e, x, m, live) {
            for a in 0..n {
                linear[a] += row.gradient[a] * row.value;
                for b in 0..n {
                    normal[a * n + b] += row.gradient[a] * row.gradient[b];
                }
            }
        }
        // `f + g·y <= θ w` and `-(f + g·y) <= θ w`.
        for_each_linearised_row(&e, &m.map(|v| v.rad()), |value, dx, w| {
            let row: Vec<f64> = live.iter().map(|&j| dx[j] * x[j].rad()).collect();
            a_rows.push(row.clone());
            a_rows.push(row.iter().map(|v| -v).collect());
            b_vec.push(SHRINK * w - value);
            b_vec.push(SHRINK * w + value);
        });
    }
    let scale = (0..n).map(|a| normal[a * n + a]).fold(0.0, f64::max);
    for a in 0..n {
        normal[a * n + a] += prior_weight + 1e-10 * scale + f64::MIN_POSITIVE;
    }
    let constraints = a_rows.len();
    let (mut colptr, mut rowval, mut nzval) = (Vec::new(), Vec::new(), Vec::new());
    let (mut pcol, mut prow, mut pval) = (Vec::new(), Vec::new(), Vec::new());
    for b in 0..n {
        colptr.push(rowval.len());
        for (i, row) in a_rows.iter().enumerate() {
            rowval.push(i);
            nzval.push(row[b]);
        }
        rowval.extend([constraints + 2 * b, constraints + 2 * b + 1]);
        nzval.extend([1.0, -1.0]);
        // The upper triangle of the normal matrix, column by column.
        pcol.push(prow.len());
        for a in 0..=b {
            prow.push(a);
            pval.push(normal[a * n + b]);
        }
    }
    colptr.push(rowval.len());
    pcol.push(prow.len());
    for &j in live {
        b_vec.push((x[j].sup() - p[j]) / x[j].rad());
        b_vec.push((p[j] - x[j].inf()) / x[j].rad());
    }
    if b_vec.iter().chain(&linear).any(|v| !v.is_finite()) {
        return None;
    }
    let rows = constraints + 2 * n;
    let a_mat = CscMatrix::new(rows, n, colptr, rowval, nzval);
    let p_mat = CscMatrix::new(n, n, pcol, prow, pval);
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .build()
        .ok()?;
    let cones = [SupportedConeT::NonnegativeConeT(rows)];
    let mut solver = DefaultSolver::new(&p_mat, &linear, &a_mat, &b_vec, &cones, settings).ok()?;
    solver.solve();
    if !matches!(
        solver.solution.status,
        SolverStatus::Solved | SolverStatus::AlmostSolved
    ) {
        return None;
    }
    let mut step = [0.0; NX];
    for (a, &j) in live.iter().enumerate() {
        step[j] = solver.solution.x[a] * x[j].rad();
    }
    step.iter().all(|v| v.is_finite()).then_some(step)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_models::Plane as Line;
    use crate::{is_consistent_point, Model};

    /// Twelve points `y = 0.5 t + 0.2` with a deterministic ±0.05 zigzag, `y` within `bound`;
    /// `s = 1` (an intercept) or `s = 0` (no data on `x1`).
    fn points(bound: f64, s: f64) -> Vec<[Interval; 3]> {
        (0..12)
            .map(|k| {
                let t = k as f64 / 11.0;
                let y = 0.5 * t + 0.2 * s + if k % 3 == 0 { 0.05 } else { -0.025 };
                let p = Interval::point;
                [p(t), p(s), Interval::new(y - bound, y + bound)]
            })
            .collect()
    }

    fn sum_of_squares(x: &[f64; 2], m: &[[Interval; 3]]) -> f64 {
        m.iter()
            .map(|m| Line.residual(x, &m.map(|v| v.mid())).powi(2))
            .sum()
    }

    /// The unconstrained least-squares fit of `points(_, 1.0)` (normal equations).
    fn least_squares(m: &[[Interval; 3]]) -> [f64; 2] {
        let (mut stt, mut st, mut sty, mut sy) = (0.0, 0.0, 0.0, 0.0);
        for m in m {
            let (t, y) = (m[0].mid(), m[2].mid());
            (stt, st, sty, sy) = (stt + t * t, st + t, sty + t * y, sy + y);
        }
        let n = m.len() as f64;
        let slope = (n * sty - st * sy) / (n * stt - st * st);
        [slope, (sy - slope * st) / n]
    }

    #[test]
    fn a_set_that_holds_the_least_squares_fit_gives_it_back() {
        // Loose bounds and a wide box: the fit is inside the set and the prior term is
        // negligible for every weight.
        let m = points(0.2, 1.0);
        let x = [Interval::new(-1000.0, 1000.0); 2];
        let fit = least_squares_in_set(&Line, &x, &m, [0.45, 0.25]);
        let want = least_squares(&m);
        for j in 0..2 {
            assert!(
                (fit.x[j] - want[j]).abs() < 1e-6,
                "{fit:?} against {want:?}"
            );
        }
    }

    #[test]
    fn a_tight_set_keeps_the_fit_inside_it() {
        // Bounds just above the zigzag's minimax need: the least-squares fit leaves the set.
        let m = points(0.0385, 1.0);
        let x = [Interval::new(-2.0, 2.0); 2];
        let lsq = least_squares(&m);
        assert!(
            !is_consistent_point(&Line, &lsq, &m),
            "the test needs a tight set"
        );
        let start = crate::proof::chebyshev::minimax_point(&Line, &x, &m, &[true; 3], lsq, false);
        assert!(is_consistent_point(&Line, &start, &m), "{start:?}");
        let fit = least_squares_in_set(&Line, &x, &m, start);
        assert!(is_consistent_point(&Line, &fit.x, &m), "{fit:?}");
        let (at_fit, at_start) = (sum_of_squares(&fit.x, &m), sum_of_squares(&start, &m));
        assert!(at_fit < at_start, "{at_fit} against the start's {at_start}");
        assert!(
            at_fit >= sum_of_squares(&lsq, &m),
            "below the least-squares minimum"
        );
    }

    #[test]
    fn cross_validation_weights_the_prior_where_the_data_say_nothing() {
        // `s = 0`: `x1` changes no residual, so every weight predicts the folds equally well,
        // the one-standard-error rule takes the largest, and `x1` goes to the box's centre.
        let m = points(0.2, 0.0);
        let x = [Interval::new(-1000.0, 1000.0), Interval::new(1.0, 3.0)];
        let fit = least_squares_in_set(&Line, &x, &m, [0.5, 2.7]);
        assert_eq!(
            fit.prior_weight,
            PRIOR_WEIGHTS[PRIOR_WEIGHTS.len() - 1],
            "{fit:?}"
        );
        assert!((fit.x[1] - 2.0).abs() < 1e-6, "{fit:?}");
        // And `x0` stays at the data's slope (its box is too wide for the prior term to matter).
        assert!((fit.x[0] - 0.5).abs() < 0.05, "{fit:?}");
    }
}
