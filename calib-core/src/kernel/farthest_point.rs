//! Certified points pushed along a direction: the local search behind the inner bounds of
//! [`crate::hull`] and the extreme points of a [`crate::CertifiedSet`].
//!
//! At a certified point `p`, with `f_k = f(p, mid M_k)`, `g_k = ∂f/∂x (p, mid M_k)` and
//! `w_k = Σ_i |∂f/∂M_i| rad(M_{k,i})` (the first-order half-range of `f(p, ·)` over `M_k`, paper
//! eq. 6; for vector models also every coupling combination, [`crate::model::coupling`]), a linear
//! program maximises `c·d` subject to `|f_k + g_k·d| <= θ w_k` and `p + d` in the region; the
//! point `p + d` is kept only when it is certified consistent ([`crate::is_consistent_point`]).
//! The margin `θ < 1` absorbs the linearisation error and is lowered when a step fails to
//! certify; the push ends when an LP fails. Every point returned is certified, whatever the LP
//! engine answered.
//!
//! The LPs are posed over the parameters the region leaves free ([`PushEngines`]); above
//! [`SMALL_DIM`] of them they go to the interior-point engine ([`ClarabelLp::for_hints`]). Its
//! optimum lies inside the optimal face rather than at one of its vertices, and the thin slabs
//! `|f_k + g_k·d| <= θ w_k` (hundreds of pairs of nearly parallel rows) do not stall it.
//! On the built-in arm's hull the simplex failed a large share of the push LPs and the pushes it
//! finished stopped short; with the interior-point engine none failed and the first pushes alone
//! reach a tighter hull (see `benches/README.md`).

use crate::lp::{ClarabelLp, DenseSimplex, LpBackend, LpStatus, Polyhedron, SMALL_DIM};
use crate::model::coupling::for_each_linearised_row;
use crate::proof::consistency::FailFirst;
use crate::{Interval, VectorModel};

/// Local maximisation of `direction·x` over the solution set: from `start`, successive linear
/// programs move along `direction` inside `region` (see the module documentation); each step is
/// kept only when the new point is certified consistent. Returns the most extreme certified point
/// found (`None` when no point was certified).
pub(crate) fn push_towards<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    lp: &mut PushEngines,
    start: &[f64; NX],
    direction: &[f64; NX],
    region: &[Interval; NX],
    measurements: &[[Interval; NM]],
) -> Option<[f64; NX]>
where
    M: VectorModel<NX, NM, NR>,
{
    let mut p: [f64; NX] =
        core::array::from_fn(|j| start[j].clamp(region[j].inf(), region[j].sup()));
    let mut order = FailFirst::new(measurements.len());
    let mut best = order
        .is_consistent_point(model, &p, measurements)
        .then_some(p);
    // θ = 1 - margin: the margin starts tiny (the LP optimum should reach the face) and doubles
    // whenever a step fails to certify.
    let mut margin = 1e-3;
    let mut poly = Polyhedron::default();
    let objective: [f64; NX] = direction.map(|v| -v);
    let reach = |x: &[f64; NX]| -> f64 { direction.iter().zip(x).map(|(d, v)| d * v).sum() };
    // The region's extent along the direction: steps that gain less than `MIN_GAIN` of it end
    // the push.
    let span = extent(region, direction);
    let mut dual = vec![0.0; 2 * measurements.len()];
    let mut primal = [0.0; NX];
    let mut rows: Vec<LinearisedRow<NX>> = Vec::new();
    // Which rows the LPs hold: the coupling rows an earlier step's optimum violated stay in (the
    // steps move the point little, so the same rows bind).
    let mut active: Vec<bool> = Vec::new();
    for _ in 0..12 {
        let Some((lo, hi)) = step_box(region, &p) else {
            break;
        };
        linearise(model, &p, measurements, margin, &active, &mut rows);
        let lp_step = PushLp {
            lp: &mut *lp,
            poly: &mut poly,
            lo: &lo,
            hi: &hi,
            objective: &objective,
            dual: &mut dual,
            primal: &mut primal,
        };
        let solved = lp_step.solve(&mut rows);
        active.clear();
        active.extend(rows.iter().map(|r| r.active));
        if !solved {
            // A larger margin or more active rows only shrink this LP's feasible set: from the
            // same point, if this one was infeasible, every later one is too. On the real UR10
            // most of a hull's push steps were such LPs (`benches/README.md`).
            break;
        }
        let q: [f64; NX] =
            core::array::from_fn(|j| (p[j] + primal[j]).clamp(region[j].inf(), region[j].sup()));
        if order.is_consistent_point(model, &q, measurements) {
            let gain = match &best {
                None => f64::INFINITY,
                Some(b) => reach(&q) - reach(b),
            };
            p = q;
            best = Some(q);
            if gain <= 1e-12 * (1.0 + reach(&q).abs()) || gain <= MIN_GAIN * span {
                break;
            }
        } else {
            // Linearisation error: a larger margin, from the last certified point.
            margin = (2.0 * margin).min(0.9);
            if let Some(b) = best {
                p = b;
            } else {
                p = q;
            }
        }
    }
    best
}

/// `Σ_j wid(region_j) |direction_j|`: the extent of `region` along `direction`.
fn extent<const NX: usize>(region: &[Interval; NX], direction: &[f64; NX]) -> f64 {
    region
        .iter()
        .zip(direction)
        .map(|(r, d)| r.wid() * d.abs())
        .sum()
}

/// The steps `d` that keep `p + d` in `region`: the box `[inf(region) - p, sup(region) - p]`
/// as its lower and upper corners (`None` when a lower corner is above its upper one or either is
/// not a number).
fn step_box<const NX: usize>(
    region: &[Interval; NX],
    p: &[f64; NX],
) -> Option<([f64; NX], [f64; NX])> {
    let lo: [f64; NX] = core::array::from_fn(|j| region[j].inf() - p[j]);
    let hi: [f64; NX] = core::array::from_fn(|j| region[j].sup() - p[j]);
    if lo
        .iter()
        .zip(&hi)
        .any(|(l, h)| l.partial_cmp(h).is_none_or(|o| o.is_gt()))
    {
        return None;
    }
    Some((lo, hi))
}

/// Replaces `rows` by the linearised rows of every configuration at `p` (see the module
/// documentation), their half-ranges scaled by `θ = 1 - margin`. A configuration's `NR` residual
/// rows are always active; a coupling row is active when the row at its index in `active` (the
/// previous step's rows) was.
fn linearise<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    p: &[f64; NX],
    measurements: &[[Interval; NM]],
    margin: f64,
    active: &[bool],
    rows: &mut Vec<LinearisedRow<NX>>,
) where
    M: VectorModel<NX, NM, NR>,
{
    rows.clear();
    for m in measurements {
        let mm = m.map(|v| v.mid());
        let rad = m.map(|v| v.rad());
        let e = model.evaluate_rows(p, &mm);
        let mut count = 0;
        for_each_linearised_row(&e, &rad, |value, dx, w| {
            let k = rows.len();
            rows.push(LinearisedRow {
                value,
                dx: *dx,
                w: (1.0 - margin) * w,
                active: count < NR || active.get(k).copied().unwrap_or(false),
            });
            count += 1;
        });
    }
}

/// The LP engines of the pushes, reused from push to push: the dense simplex (walking on from
/// the previous optimum) up to [`SMALL_DIM`] free parameters, where it is measured faster, and the
/// interior-point engine above (see the module documentation).
pub(crate) struct PushEngines {
    small: DenseSimplex,
    large: ClarabelLp,
}

impl Default for PushEngines {
    fn default() -> Self {
        PushEngines {
            small: DenseSimplex::default(),
            large: ClarabelLp::for_hints(),
        }
    }
}

impl PushEngines {
    /// The engine for LPs of `dim` variables.
    fn engine(&mut self, dim: usize) -> &mut dyn LpBackend {
        if dim > SMALL_DIM {
            &mut self.large
        } else {
            &mut self.small
        }
    }
}

/// A push ends at a step that gains less than this fraction of the region's extent along the
/// direction. On the built-in arm's hull, after the first certified step, most steps gained less
/// than that, nothing the hull's tolerances (ratios of widths, the region within them of the inner
/// width) can see; ending there saves steps and time for the same boxes and ratios
/// (`benches/README.md`).
const MIN_GAIN: f64 = 1e-4;

/// One linearised scalar equation of a push (see [`push_outward`]): `|value + dx·d| <= w`.
struct LinearisedRow<const NX: usize> {
    value: f64,
    dx: [f64; NX],
    w: f64,
    /// Whether the LP holds it: every residual row from the start, coupling rows once violated.
    active: bool,
}

/// The LP of one push step, `min ±d_j` over the active rows and the box `[lo, hi]`.
struct PushLp<'a, const NX: usize> {
    lp: &'a mut PushEngines,
    poly: &'a mut Polyhedron,
    lo: &'a [f64; NX],
    hi: &'a [f64; NX],
    objective: &'a [f64; NX],
    dual: &'a mut Vec<f64>,
    primal: &'a mut [f64; NX],
}

/// At most this many LPs per push step: each adds the coupling rows its optimum violates.
const ROW_GENERATION_ROUNDS: usize = 6;

impl<const NX: usize> PushLp<'_, NX> {
    /// Solves over every row by row generation: the residual rows first, then the coupling rows
    /// (up to `MAX_DIRECTIONS` per configuration, most of them never binding) that the optimum
    /// violates, until it violates none or [`ROW_GENERATION_ROUNDS`] LPs were solved. False when
    /// an LP failed. With one row per configuration (no coupling rows) this is the single LP
    /// over every row. The optimum is a candidate only: the push certifies it.
    ///
    /// The LP is posed over the live columns only (`lo_j < hi_j`); a pinned one keeps `d_j = lo_j`.
    fn solve(self, rows: &mut [LinearisedRow<NX>]) -> bool {
        let (live, pinned): (Vec<usize>, Vec<usize>) =
            (0..NX).partition(|&j| self.lo[j] < self.hi[j]);
        for &j in &pinned {
            self.primal[j] = self.lo[j];
        }
        let pick = |v: &[f64; NX]| -> Vec<f64> { live.iter().map(|&j| v[j]).collect() };
        let (lo, hi, objective) = (pick(self.lo), pick(self.hi), pick(self.objective));
        let mut row = vec![0.0; live.len()];
        let mut primal = vec![0.0; live.len()];
        for _ in 0..ROW_GENERATION_ROUNDS {
            self.poly.reset(&lo, &hi);
            for r in rows.iter().filter(|r| r.active) {
                // f + g·d <= θw  and  -(f + g·d) <= θw, with the pinned columns' share moved
                // to the right-hand side.
                let value = r.value + pinned.iter().map(|&j| r.dx[j] * self.lo[j]).sum::<f64>();
                for (c, &j) in row.iter_mut().zip(&live) {
                    *c = r.dx[j];
                }
                self.poly.push_row(&row, r.w - value);
                row.iter_mut().for_each(|v| *v = -*v);
                self.poly.push_row(&row, r.w + value);
            }
            self.dual.resize(self.poly.rows(), 0.0);
            if self
                .lp
                .engine(live.len())
                .minimize(self.poly, &objective, self.dual, &mut primal)
                != LpStatus::Optimal
            {
                return false;
            }
            for (&j, v) in live.iter().zip(&primal) {
                self.primal[j] = *v;
            }
            let mut added = false;
            for r in rows.iter_mut().filter(|r| !r.active) {
                let v = r.value
                    + r.dx
                        .iter()
                        .zip(self.primal.iter())
                        .map(|(a, d)| a * d)
                        .sum::<f64>();
                if v.abs() > r.w {
                    r.active = true;
                    added = true;
                }
            }
            if !added {
                break;
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lp::safe_lower_bound;
    use crate::proof::consistency::is_consistent_point;
    use crate::test_models::{Hyperplane, HYPERPLANE_DIM as N};
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    /// Pushes over more than [`SMALL_DIM`] free parameters (the interior-point engine), some of
    /// them pinned by the region: every point returned is certified, the pinned ones stay put,
    /// and the push reaches (nearly) the set's extreme, which for a linear model with exact
    /// coefficients is an LP's optimum.
    #[test]
    fn pushes_over_many_parameters_reach_the_extreme_and_keep_pinned_ones() {
        let mut rng = StdRng::seed_from_u64(5);
        let truth: [f64; N] = core::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let pinned = [3usize, 8, 15];
        let region: [Interval; N] = core::array::from_fn(|j| {
            if pinned.contains(&j) {
                Interval::point(truth[j])
            } else {
                Interval::new(truth[j] - 0.5, truth[j] + 0.5)
            }
        });
        let w = 0.01;
        let measurements: Vec<[Interval; N + 1]> = (0..80)
            .map(|_| {
                let a: [f64; N] = core::array::from_fn(|_| rng.random_range(-1.0..1.0));
                let v: f64 = a.iter().zip(&truth).map(|(p, q)| p * q).sum::<f64>()
                    + rng.random_range(-0.5 * w..0.5 * w);
                core::array::from_fn(|j| {
                    if j < N {
                        Interval::point(a[j])
                    } else {
                        Interval::new(v - w, v + w)
                    }
                })
            })
            .collect();
        assert!(is_consistent_point(&Hyperplane, &truth, &measurements));
        let mut engines = PushEngines::default();
        for j in [0usize, 7, 19] {
            for sign in [1.0, -1.0] {
                let mut direction = [0.0; N];
                direction[j] = sign;
                let p = push_towards(
                    &Hyperplane,
                    &mut engines,
                    &truth,
                    &direction,
                    &region,
                    &measurements,
                )
                .expect("the start is certified");
                assert!(is_consistent_point(&Hyperplane, &p, &measurements));
                for &k in &pinned {
                    assert_eq!(p[k], truth[k], "pinned parameter {k} moved");
                }
                // The extreme: max sign·x_j over |a·x - v| <= w and the region.
                let mut poly = Polyhedron::default();
                let lo = region.map(|r| r.inf());
                let hi = region.map(|r| r.sup());
                poly.reset(&lo, &hi);
                for m in &measurements {
                    let a: Vec<f64> = m[..N].iter().map(|c| c.mid()).collect();
                    poly.push_row(&a, m[N].sup());
                    let neg: Vec<f64> = a.iter().map(|c| -c).collect();
                    poly.push_row(&neg, -m[N].inf());
                }
                let mut objective = [0.0; N];
                objective[j] = -sign;
                let (mut dual, mut primal) = (vec![0.0; poly.rows()], [0.0; N]);
                let mut lp = ClarabelLp::default();
                lp.minimize(&poly, &objective, &mut dual, &mut primal);
                let most = -safe_lower_bound(&poly, &objective, &dual);
                let (start, reached) = (sign * truth[j], sign * p[j]);
                assert!(reached <= most + 1e-9, "{j} {sign}: beyond the extreme");
                assert!(
                    reached - start >= 0.95 * (most - start),
                    "{j} {sign}: reached {reached}, extreme {most}, start {start}"
                );
            }
        }
    }
}
