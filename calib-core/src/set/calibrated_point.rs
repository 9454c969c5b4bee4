//! The calibrated parameter vector: one point of the certified set, proved consistent with every
//! measurement, for a controller to load.
//!
//! The midpoint of the certified box is not a good choice: the set is thin along combinations of
//! parameters the box cannot show (a Gough leg's `a_z + l - b_z`), so the box's midpoint may
//! misfit the measurements many times over. The point chosen here is built in three steps:
//!
//! 1. **The deepest point** `c`: the minimax fit `argmin_x max_k |f_k(x, mid M_k)| / w_k`
//!    ([`crate::proof::consistency`]'s normalised misfit: `w_k` is the first-order half-range of
//!    the residual over the measurement box), by successive linear programs. It is the point that
//!    fits the data with the most room to spare.
//! 2. **A target** `t`, by the [`PointRule`]: the Chebyshev centre of the predictions (the point
//!    that minimises, to first order, the largest distance from its predictions to the extreme
//!    predictions of the set: `min_x max_s max(hi_s - g_s·x, g_s·x - lo_s)`, `[lo_s, hi_s]` the
//!    set's range of the prediction `g_s·x`, one linear program per piece), or the regularised
//!    least-squares fit of the residuals within the linearised set
//!    ([`crate::least_squares_in_set`]).
//! 3. **The point itself**: the last point of the segment from `c` to `t` proved consistent with
//!    every measurement box *narrowed by a margin* (bisection; 5% of every error bound, or 2%, 1%,
//!    0 when the data leave less room): a vector that fits every measurement with part of each
//!    error bound to spare, so that an independent check in another arithmetic agrees.
//!
//! Every point returned is proved consistent ([`crate::is_consistent_point`]) with the narrowed
//! boxes, hence with the measurement boxes themselves.

use crate::lp::{DenseSimplex, LpBackend, LpStatus, Polyhedron};
use crate::proof::chebyshev::{minimax_point, normalised_misfit};
use crate::proof::consistency::least_squares_point;
use crate::set::least_squares::least_squares_in_set;
use crate::{is_consistent_point, CertifiedSet, Interval, VectorModel};

/// How the calibrated point is chosen (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PointRule<'a, const NX: usize> {
    /// Towards the Chebyshev centre of these predictions: each `g_s` is the gradient of a
    /// predicted quantity (a leg length at a pose, a tool-point coordinate at a configuration)
    /// with respect to the parameters. The worst prediction error over the set is then as small
    /// as the set allows (to first order).
    PredictionCentre(&'a [[f64; NX]]),
    /// Towards the regularised least-squares fit of the residuals at the measurements' midpoints
    /// within the set, linearised: residuals in units of their error bounds, the prior box
    /// weighted by cross-validation over the configurations ([`crate::least_squares_in_set`]). On
    /// data with errors the model does not hold (gravity, gears), the best predictor of unseen
    /// configurations among the points the set allows.
    LeastSquares,
}

/// The margins tried, as fractions of every error bound, widest first.
pub const POINT_MARGINS: [f64; 4] = [0.05, 0.02, 0.01, 0.0];

/// The calibrated point and how it was found.
#[derive(Clone, Debug, PartialEq)]
pub struct CalibratedPoint<const NX: usize> {
    /// The parameter vector: proved consistent with every measurement box narrowed by `margin`.
    pub x: [f64; NX],
    /// The fraction of every error bound left to spare (one of [`POINT_MARGINS`]).
    pub margin: f64,
    /// The deepest point `c` (step 1).
    pub deepest: [f64; NX],
    /// `c`'s normalised misfit: to first order, the smallest factor of the error bounds with
    /// which some parameter vector fits the data.
    pub deepest_misfit: f64,
    /// The target `t` (step 2).
    pub target: [f64; NX],
    /// How far along the segment from `c` to `t` the point lies (1: the target itself).
    pub reached: f64,
    /// With [`PointRule::LeastSquares`]: the weight `λ` of the prior box in the target's
    /// regularised fit, chosen by cross-validation ([`crate::least_squares_in_set`]).
    pub prior_weight: Option<f64>,
    /// The measurement subset the point fits (see [`crate::Cover`]).
    pub subset: usize,
}

/// The measurement boxes narrowed to `mid ± (1 - margin) rad`, each inside its box.
pub fn narrowed<const NM: usize>(
    measurements: &[[Interval; NM]],
    margin: f64,
) -> Vec<[Interval; NM]> {
    measurements
        .iter()
        .map(|m| {
            m.map(|v| {
                if margin <= 0.0 {
                    return v;
                }
                let (c, r) = (v.mid(), (1.0 - margin) * v.rad());
                let lo = (c - r).max(v.inf());
                let hi = (c + r).min(v.sup());
                if lo <= hi {
                    Interval::new(lo, hi)
                } else {
                    v
                }
            })
        })
        .collect()
}

/// Chooses the calibrated point of `set` by `rule` (see the module documentation). `None` when no
/// point of the set could be proved consistent (the set may then be empty: an undecided
/// certification hands out no parameter vector).
pub fn calibrated_point<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    set: &mut CertifiedSet<NX, NM>,
    rule: PointRule<'_, NX>,
) -> Option<CalibratedPoint<NX>>
where
    M: VectorModel<NX, NM, NR> + Sync,
{
    let region = set.outer()?;
    // The subset (with outliers tolerated) whose deepest point fits best.
    let subsets: Vec<usize> = {
        let mut s: Vec<usize> = set.pieces().iter().map(|p| p.subset()).collect();
        s.sort_unstable();
        s.dedup();
        s
    };
    let (misfit, deepest, subset) = subsets
        .iter()
        .map(|&s| {
            let kept = set.subset_measurements(s);
            let lsq = least_squares_point(model, &region, &kept);
            let c = minimax_point(model, &region, &kept, &[true; NM], lsq, false);
            (normalised_misfit(model, &c, &kept), c, s)
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))?;
    let kept = set.subset_measurements(subset);
    // The deepest point with the widest margin it is proved to keep; else a held point.
    let mut start = None;
    for margin in POINT_MARGINS {
        let boxes = narrowed(&kept, margin);
        if is_consistent_point(model, &deepest, &boxes) {
            start = Some((deepest, margin, boxes));
            break;
        }
    }
    let (from, margin, boxes) = match start {
        Some(s) => s,
        None => {
            let held = set
                .points()
                .iter()
                .filter(|p| p.subset == subset)
                .map(|p| p.x)
                .min_by(|a, b| {
                    normalised_misfit(model, a, &kept)
                        .total_cmp(&normalised_misfit(model, b, &kept))
                })?;
            (held, 0.0, kept.clone())
        }
    };
    let (target, prior_weight) = match rule {
        PointRule::LeastSquares => {
            let fit = least_squares_in_set(model, &region, &boxes, from);
            (fit.x, Some(fit.prior_weight))
        }
        PointRule::PredictionCentre(predictions) => (
            prediction_centre(set, subset, predictions).unwrap_or(from),
            None,
        ),
    };
    let at =
        |t: f64| -> [f64; NX] { core::array::from_fn(|j| from[j] + t * (target[j] - from[j])) };
    let (mut lo, mut hi, mut best) = (0.0, 1.0, from);
    if is_consistent_point(model, &target, &boxes) {
        (lo, best) = (1.0, target);
    } else {
        for _ in 0..30 {
            let t = 0.5 * (lo + hi);
            let p = at(t);
            if is_consistent_point(model, &p, &boxes) {
                lo = t;
                best = p;
            } else {
                hi = t;
            }
        }
    }
    set.add_point(model, &best);
    Some(CalibratedPoint {
        x: best,
        margin,
        deepest,
        deepest_misfit: misfit,
        target,
        reached: lo,
        prior_weight,
        subset,
    })
}

/// The Chebyshev centre of the predictions over the pieces of `subset`: per piece, the linear
/// program `min τ` over `(y, τ)` with the piece's rows and `hi_s - g_s·x <= τ`,
/// `g_s·x - lo_s <= τ` (`x = c + y`); the best piece's optimum. A target, not a proof.
fn prediction_centre<const NX: usize, const NM: usize>(
    set: &CertifiedSet<NX, NM>,
    subset: usize,
    predictions: &[[f64; NX]],
) -> Option<[f64; NX]> {
    let mut query = set.query();
    let ranges: Vec<Interval> = predictions.iter().map(|g| query.range(g)).collect();
    let mut lp = DenseSimplex::default();
    let mut poly = Polyhedron::default();
    let mut best: Option<(f64, [f64; NX])> = None;
    let mut row = vec![0.0; NX + 1];
    for piece in set.pieces().iter().filter(|p| p.subset() == subset) {
        let p = piece.polyhedron();
        let c = piece.centre();
        let spread = ranges.iter().map(|r| r.wid()).fold(0.0, f64::max);
        let lo: Vec<f64> = p.lo().iter().copied().chain([0.0]).collect();
        let hi: Vec<f64> = p.hi().iter().copied().chain([spread.max(1e-300)]).collect();
        poly.reset(&lo, &hi);
        for i in 0..p.rows() {
            row[..NX].copy_from_slice(p.row(i));
            row[NX] = 0.0;
            poly.push_row(&row, p.rhs(i));
        }
        for (g, r) in predictions.iter().zip(&ranges) {
            let gc: f64 = g.iter().zip(c).map(|(a, b)| a * b).sum();
            // -g·y - τ <= g·c - hi  and  g·y - τ <= lo - g·c
            row[..NX].iter_mut().zip(g).for_each(|(v, a)| *v = -a);
            row[NX] = -1.0;
            poly.push_row(&row, gc - r.sup());
            row[..NX].copy_from_slice(g);
            poly.push_row(&row, r.inf() - gc);
        }
        let mut objective = vec![0.0; NX + 1];
        objective[NX] = 1.0;
        let mut dual = vec![0.0; poly.rows()];
        let mut primal = vec![0.0; NX + 1];
        if lp.minimize(&poly, &objective, &mut dual, &mut primal) != LpStatus::Optimal {
            continue;
        }
        let tau = primal[NX];
        if best.as_ref().is_none_or(|b| tau < b.0) {
            best = Some((tau, core::array::from_fn(|j| c[j] + primal[j])));
        }
    }
    best.map(|b| b.1)
}
