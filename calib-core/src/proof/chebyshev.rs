//! Chebyshev (minimax) fits: the point of a box whose worst first-order misfit, measured in
//! error bounds, is smallest, and that misfit — the factor by which error bounds must be
//! multiplied for the point to fit every measurement.
//!
//! At a point `p`, each equation `f` of configuration `k` (each row, and for vector models each
//! coupling combination, [`crate::model::coupling`]) fits the measurement box at first order when
//! `|f(p, mid M_k)| <= w` with `w = Σ_i |∂f/∂M_i| rad(M_{k,i})` (paper eq. 6). Multiplying the
//! half-widths of some quantities by `s` makes `w = w_fixed + s w_scaled`. Successive linear
//! programs in `(δ, t)`, `|f + ∂f/∂x · δ| <= w_fixed + t w_scaled`, minimise `t` over the box.
//!
//! Nothing here is a proof. The fits are candidates: a point is consistent only when
//! [`crate::is_consistent_point`] says so, and a scale is proved too small only by an emptiness
//! proof of the kernel.

use crate::lp::{ClarabelLp, DenseSimplex, LpBackend, LpStatus, Polyhedron};
use crate::model::coupling::for_each_split_row;
use crate::proof::consistency::{is_consistent_point, least_squares_point};
use crate::{Interval, VectorModel};

/// A first-order estimate of the smallest consistent error scale ([`smallest_scale`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScaleEstimate<const NX: usize> {
    /// The Chebyshev point: where the worst scaled misfit is smallest.
    pub point: [f64; NX],
    /// Its worst misfit: to first order, the smallest factor by which the scaled quantities'
    /// half-widths must be multiplied for `point` to fit every measurement box.
    pub scale: f64,
}

/// The Chebyshev fit of the box `x` to the measurement boxes with the half-widths of the `scaled`
/// measured quantities multiplied by a common factor `s` (the others kept): the point minimising
/// the smallest such `s` at first order, from the least-squares point (see the module
/// documentation).
///
/// An estimate, not a proof: `point` is certified consistent at a factor `s` only if
/// [`crate::is_consistent_point`] accepts it against the boxes widened by `s` — which, the
/// linearisation being accurate over a point and small boxes, it does for `s` slightly above
/// `scale`.
pub fn smallest_scale<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
    scaled: &[bool; NM],
) -> ScaleEstimate<NX>
where
    M: VectorModel<NX, NM, NR>,
{
    let start = least_squares_point(model, x, measurements);
    let point = minimax_point(model, x, measurements, scaled, start, false);
    ScaleEstimate {
        point,
        scale: scaled_misfit(model, &point, measurements, scaled),
    }
}

/// The largest normalised residual at `p`: `max_k |f_k(p, mid M_k)| / w_k`, where `w_k` is the
/// first-order half-range of `f(p, ·)` over `M_k` (and, for vector models, of every coupling
/// combination, [`crate::model::coupling`]): to first order, the factor by which every error bound
/// must be multiplied for `p` to fit all measurements (`+∞` where a half-range is 0 and the
/// residual is not).
pub(crate) fn normalised_misfit<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    p: &[f64; NX],
    measurements: &[[Interval; NM]],
) -> f64
where
    M: VectorModel<NX, NM, NR>,
{
    scaled_misfit(model, p, measurements, &[true; NM])
}

/// [`normalised_misfit`] when only the `scaled` measured quantities' half-widths are multiplied:
/// the smallest `s >= 0` with `|f| <= w_fixed + s w_scaled` for every row and coupling combination
/// at `p`, to first order (`+∞` where no factor fits a row).
pub(crate) fn scaled_misfit<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    p: &[f64; NX],
    measurements: &[[Interval; NM]],
    scaled: &[bool; NM],
) -> f64
where
    M: VectorModel<NX, NM, NR>,
{
    let mut worst = 0.0f64;
    for m in measurements {
        let mm = m.map(|v| v.mid());
        let (fixed, varying) = split_radii(m, scaled);
        let e = model.evaluate_rows(p, &mm);
        for_each_split_row(&e, &fixed, &varying, |_, value, _, w_fixed, w_scaled| {
            let excess = value.abs() - w_fixed;
            let r = if excess <= 0.0 {
                0.0
            } else {
                excess / w_scaled
            };
            worst = worst.max(if r.is_nan() { f64::INFINITY } else { r });
        });
    }
    worst
}

/// The half-widths of `m` split into the fixed and the `scaled` quantities'.
fn split_radii<const NM: usize>(m: &[Interval; NM], scaled: &[bool; NM]) -> ([f64; NM], [f64; NM]) {
    let part =
        |want: bool| core::array::from_fn(|i| if scaled[i] == want { m[i].rad() } else { 0.0 });
    (part(false), part(true))
}

/// Builds in `poly` the LP in `(δ, t)` of a Chebyshev step at `p` (see the module documentation):
/// for every row and coupling combination `λ·f` of every configuration,
/// `±(λ·f + λ·∂f/∂x δ) <= w_fixed + w_scaled t`, over `p + δ` in the box, `|δ_j| <= reach ·
/// rad(x_j)` (a trust region; `∞` for the whole box) and `0 <= t <= 1e6`. `origin` is told, for
/// every row kept, where it came from. `false` (nothing built) when `p` is not in the box.
#[allow(clippy::too_many_arguments)]
fn chebyshev_lp<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
    scaled: &[bool; NM],
    p: &[f64; NX],
    reach: f64,
    poly: &mut Polyhedron,
    row: &mut [f64],
    mut origin: impl FnMut(RowOrigin<NR>),
) -> bool
where
    M: VectorModel<NX, NM, NR>,
{
    let step = |j: usize| reach * x[j].rad();
    let lo: Vec<f64> = (0..NX)
        .map(|j| (x[j].inf() - p[j]).max(-step(j)))
        .chain([0.0])
        .collect();
    // t at most 1e6 (the dense simplex answered a wrong "optimal" with a 1e12 bound; the
    // answer is a hint either way, and no error scale beyond 1e6 is searched).
    let hi: Vec<f64> = (0..NX)
        .map(|j| (x[j].sup() - p[j]).min(step(j)))
        .chain([1e6])
        .collect();
    if lo
        .iter()
        .zip(&hi)
        .any(|(l, h)| l > h || !l.is_finite() || !h.is_finite())
    {
        return false;
    }
    poly.reset(&lo, &hi);
    for (config, m) in measurements.iter().enumerate() {
        let mm = m.map(|v| v.mid());
        let (fixed, varying) = split_radii(m, scaled);
        let e = model.evaluate_rows(p, &mm);
        for_each_split_row(&e, &fixed, &varying, |l, value, dx, w_fixed, w_scaled| {
            let w = w_scaled.max(1e-300);
            // f + J δ <= w_fixed + w t  and  -(f + J δ) <= w_fixed + w t
            for sign in [1.0, -1.0] {
                row[..NX]
                    .iter_mut()
                    .zip(dx)
                    .for_each(|(r, d)| *r = sign * d);
                row[NX] = -w;
                if poly.push_row(row, w_fixed - sign * value) {
                    // The polyhedron stores the row times a power of two.
                    let largest = |r: &[f64]| r.iter().fold(0.0f64, |a, v| a.max(v.abs()));
                    let stored = largest(poly.row(poly.rows() - 1)) / largest(row);
                    origin(RowOrigin {
                        config,
                        combination: l.map(|v| sign * v * stored),
                    });
                }
            }
        });
    }
    true
}

/// Where a row of the Chebyshev LP came from: its configuration, and the combination of that
/// configuration's residuals the stored row is the linearisation of (`λ`, times the row's side and
/// the power of two the polyhedron scaled it by).
struct RowOrigin<const NR: usize> {
    config: usize,
    combination: [f64; NR],
}

/// The multipliers of the Chebyshev fit at `point` as weights of the residuals: per
/// configuration `k`, the weight `c_{k,r}` of each row `f_r(x, M_k)`, from the dual of the
/// Chebyshev LP linearised at `point` (its rows are the residuals, their coupling combinations
/// and their sides). At a Chebyshev point the combination `φ(x, M) = Σ_k Σ_r c_{k,r} f_r(x, M_k)`
/// is stationary in `x` (its gradient is what keeps `x` in the box) and its measurement
/// half-ranges add up to 1 per unit of scale: the Farkas certificate of the linearised problem at
/// any scale below the fit's. [`crate::combination_lower_bound`] turns it into a proof. `None` if
/// the LP fails or `point` is not in the box.
pub fn chebyshev_weights<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
    scaled: &[bool; NM],
    point: &[f64; NX],
) -> Option<Vec<[f64; NR]>>
where
    M: VectorModel<NX, NM, NR>,
{
    let mut poly = Polyhedron::default();
    let mut row = vec![0.0; NX + 1];
    let mut origins = Vec::new();
    let whole_box = f64::INFINITY;
    if !chebyshev_lp(
        model,
        x,
        measurements,
        scaled,
        point,
        whole_box,
        &mut poly,
        &mut row,
        |o| origins.push(o),
    ) {
        return None;
    }
    let mut objective = vec![0.0; NX + 1];
    objective[NX] = 1.0;
    let mut dual = vec![0.0; poly.rows()];
    let mut primal = vec![0.0; NX + 1];
    if ClarabelLp::for_hints().minimize(&poly, &objective, &mut dual, &mut primal)
        != LpStatus::Optimal
    {
        return None;
    }
    let mut weights = vec![[0.0; NR]; measurements.len()];
    for (y, o) in dual.iter().zip(&origins) {
        for (w, l) in weights[o.config].iter_mut().zip(&o.combination) {
            *w += y.max(0.0) * l;
        }
    }
    Some(weights)
}

/// A point of the box that minimises the largest normalised residual
/// `max_k |f_k(p, mid M_k)| / w_k` ([`normalised_misfit`]; with a `scaled` mask other than all
/// quantities, [`scaled_misfit`]), a Chebyshev (minimax) fit by successive linearisation and an LP
/// in `(δ, t)`: the point most likely to pass the sign test,
/// since the sign test needs `|f(p, mid M_k)| <= ~w_k` for every `k`. With `until_consistent`,
/// it stops at the first certified consistent point (a witness search); otherwise it runs all
/// its steps (the deepest point of the set). Returns the point with the smallest misfit met.
pub(crate) fn minimax_point<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
    scaled: &[bool; NM],
    start: [f64; NX],
    until_consistent: bool,
) -> [f64; NX]
where
    M: VectorModel<NX, NM, NR>,
{
    let mut p = start;
    let mut best = (scaled_misfit(model, &p, measurements, scaled), p);
    let mut poly = Polyhedron::default();
    let mut lp = DenseSimplex::default();
    let mut dual = vec![0.0; 2 * measurements.len()];
    let mut primal = vec![0.0; NX + 1];
    let mut objective = vec![0.0; NX + 1];
    objective[NX] = 1.0;
    let mut row = vec![0.0; NX + 1];
    // The trust region (a fraction of each half-width): the whole box until a step fails to
    // lower the misfit, then shrunk below that step, so that the fit converges to a stationary
    // point, where the LP's own optimum is the step 0 (what [`chebyshev_weights`] needs).
    let mut reach = f64::INFINITY;
    for _ in 0..if until_consistent { 6 } else { 40 } {
        if until_consistent && is_consistent_point(model, &p, measurements) {
            return p;
        }
        if !chebyshev_lp(
            model,
            x,
            measurements,
            scaled,
            &p,
            reach,
            &mut poly,
            &mut row,
            |_| {},
        ) {
            break;
        }
        dual.resize(poly.rows(), 0.0);
        if lp.minimize(&poly, &objective, &mut dual, &mut primal) != LpStatus::Optimal {
            break;
        }
        let next: [f64; NX] =
            core::array::from_fn(|j| (p[j] + primal[j]).clamp(x[j].inf(), x[j].sup()));
        let misfit = scaled_misfit(model, &next, measurements, scaled);
        if until_consistent || misfit < best.0 {
            p = next;
        }
        if until_consistent {
            continue;
        }
        let predicted_gain = best.0 - primal[NX];
        if predicted_gain <= 1e-9 * best.0 {
            break;
        }
        if misfit < best.0 {
            best = (misfit, next);
            reach *= 2.0;
        } else {
            let longest = (0..NX)
                .filter(|&j| x[j].rad() > 0.0)
                .map(|j| primal[j].abs() / x[j].rad())
                .fold(0.0f64, f64::max);
            reach = 0.25 * longest;
            if reach < 1e-12 {
                break;
            }
        }
    }
    if until_consistent {
        p
    } else {
        best.1
    }
}
