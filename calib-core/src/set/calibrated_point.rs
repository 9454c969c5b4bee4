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
//!    set's range of the prediction `g_s·x`, over the set linearised around `c`: one linear
//!    program), or the regularised least-squares fit of the residuals within the linearised set
//!    ([`crate::least_squares_in_set`]). Both lie in the linearised set, so that the segment
//!    towards them stays consistent far along it (over the set's own polyhedra, wider than the
//!    set, the centre lay so far out that the segment stopped at 6.5% of it on the real UR10).
//! 3. **The point itself**: the last point of the segment from `c` to `t` proved consistent with
//!    every measurement box *narrowed by a margin* (bisection; 5% of every error bound, or 2%, 1%,
//!    0 when the data leave less room): a vector that fits every measurement with part of each
//!    error bound to spare, so that an independent check in another arithmetic agrees.
//!
//! Every point returned is proved consistent ([`crate::is_consistent_point`]) with the narrowed
//! boxes, hence with the measurement boxes themselves.

use crate::lp::{DenseSimplex, LpBackend, LpStatus, Polyhedron};
use crate::model::coupling::for_each_linearised_row;
use crate::proof::chebyshev::{minimax_point, normalised_misfit};
use crate::proof::consistency::least_squares_point;
use crate::set::least_squares::{least_squares_in_set, SHRINK};
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
            prediction_centre(model, &region, &boxes, &from, set, predictions).unwrap_or(from),
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

/// The Chebyshev centre of the predictions over the set linearised around `from`: the linear
/// program `min τ` over `(δ, τ)` with every row and coupling combination of `measurements`
/// linearised at `from` within [`SHRINK`] of its half-range, `from + δ` in the box `region`, and
/// `hi_s - g_s·(from + δ) <= τ`, `g_s·(from + δ) - lo_s <= τ`, `[lo_s, hi_s]` the set's range of
/// `g_s·x`. A target, not a proof.
fn prediction_centre<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    region: &[Interval; NX],
    measurements: &[[Interval; NM]],
    from: &[f64; NX],
    set: &CertifiedSet<NX, NM>,
    predictions: &[[f64; NX]],
) -> Option<[f64; NX]>
where
    M: VectorModel<NX, NM, NR>,
{
    let mut query = set.query();
    let ranges: Vec<Interval> = predictions.iter().map(|g| query.range(g)).collect();
    let spread = ranges.iter().map(|r| r.wid()).fold(0.0, f64::max);
    let lo: Vec<f64> = (0..NX)
        .map(|j| region[j].inf() - from[j])
        .chain([0.0])
        .collect();
    let hi: Vec<f64> = (0..NX)
        .map(|j| region[j].sup() - from[j])
        .chain([spread.max(1e-300)])
        .collect();
    // `from` outside the box, a NaN or an unbounded range: no program.
    let ordered = |(l, h): (&f64, &f64)| l.is_finite() && h.is_finite() && l <= h;
    if !lo.iter().zip(&hi).all(ordered) {
        return None;
    }
    let mut poly = Polyhedron::default();
    poly.reset(&lo, &hi);
    let mut row = vec![0.0; NX + 1];
    for m in measurements {
        let e = model.evaluate_rows(from, &m.map(|v| v.mid()));
        for_each_linearised_row(&e, &m.map(|v| v.rad()), |value, dx, w| {
            row[..NX].copy_from_slice(dx);
            row[NX] = 0.0;
            poly.push_row(&row, SHRINK * w - value);
            row[..NX].iter_mut().for_each(|v| *v = -*v);
            poly.push_row(&row, SHRINK * w + value);
        });
    }
    for (g, r) in predictions.iter().zip(&ranges) {
        let gf: f64 = g.iter().zip(from).map(|(a, b)| a * b).sum();
        row[..NX].iter_mut().zip(g).for_each(|(v, a)| *v = -a);
        row[NX] = -1.0;
        poly.push_row(&row, gf - r.sup());
        row[..NX].copy_from_slice(g);
        poly.push_row(&row, r.inf() - gf);
    }
    let mut objective = vec![0.0; NX + 1];
    objective[NX] = 1.0;
    let mut dual = vec![0.0; poly.rows()];
    let mut primal = vec![0.0; NX + 1];
    let mut lp = DenseSimplex::default();
    (lp.minimize(&poly, &objective, &mut dual, &mut primal) == LpStatus::Optimal)
        .then(|| core::array::from_fn(|j| from[j] + primal[j]))
}
