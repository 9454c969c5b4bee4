//! Certified points pushed along a direction: the local search behind the inner bounds of
//! [`crate::hull`] and the extreme points of a [`crate::CertifiedSet`].
//!
//! At a certified point `p`, with `f_k = f(p, mid M_k)`, `g_k = ∂f/∂x (p, mid M_k)` and
//! `w_k = Σ_i |∂f/∂M_i| rad(M_{k,i})` (the first-order half-range of `f(p, ·)` over `M_k`, paper
//! eq. 6; for vector models also every coupling combination, [`crate::coupling`]), a linear
//! program maximises `c·d` subject to `|f_k + g_k·d| <= θ w_k` and `p + d` in the region; the
//! point `p + d` is kept only when it is certified consistent ([`crate::is_consistent_point`]).
//! The margin `θ < 1` absorbs the linearisation error and is lowered when a step fails. Every
//! point returned is certified, whatever the LP engine answered.

use crate::certificate::FailFirst;
use crate::coupling::for_each_linearised_row;
use crate::lp::{DenseSimplex, LpBackend, LpStatus, Polyhedron};
use crate::{Interval, VectorModel};

/// Local maximisation of `direction·x` over the solution set: from `start`, successive linear
/// programs move along `direction` inside `region` (see the module documentation); each step is
/// kept only when the new point is certified consistent. Returns the most extreme certified point
/// found (`None` when no point was certified).
pub(crate) fn push_towards<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    lp: &mut DenseSimplex,
    start: &[f64; NX],
    direction: &[f64; NX],
    region: &[Interval; NX],
    measurements: &[[Interval; NM]],
) -> Option<[f64; NX]>
where
    M: VectorModel<NX, NM, NR>,
{
    lp.forget();
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
    let mut dual = vec![0.0; 2 * measurements.len()];
    let mut primal = [0.0; NX];
    let mut rows: Vec<LinearisedRow<NX>> = Vec::new();
    for _ in 0..12 {
        let lo: [f64; NX] = core::array::from_fn(|j| region[j].inf() - p[j]);
        let hi: [f64; NX] = core::array::from_fn(|j| region[j].sup() - p[j]);
        if lo
            .iter()
            .zip(&hi)
            .any(|(l, h)| l.partial_cmp(h).is_none_or(|o| o.is_gt()))
        {
            break;
        }
        rows.clear();
        for m in measurements {
            let mm = m.map(|v| v.mid());
            let rad = m.map(|v| v.rad());
            let e = model.evaluate_rows(&p, &mm);
            let mut count = 0;
            for_each_linearised_row(&e, &rad, |value, dx, w| {
                rows.push(LinearisedRow {
                    value,
                    dx: *dx,
                    w: (1.0 - margin) * w,
                    active: count < NR,
                });
                count += 1;
            });
        }
        let lp_step = PushLp {
            lp: &mut *lp,
            poly: &mut poly,
            lo: &lo,
            hi: &hi,
            objective: &objective,
            dual: &mut dual,
            primal: &mut primal,
        };
        if !lp_step.solve(&mut rows) {
            margin = (2.0 * margin).min(0.9);
            continue;
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
            if gain <= 1e-12 * (1.0 + reach(&q).abs()) {
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
    lp: &'a mut DenseSimplex,
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
    fn solve(self, rows: &mut [LinearisedRow<NX>]) -> bool {
        let mut row = [0.0; NX];
        for _ in 0..ROW_GENERATION_ROUNDS {
            self.poly.reset(self.lo, self.hi);
            for (g, r) in rows.iter().enumerate().filter(|(_, r)| r.active) {
                // Tags that name the row, so that a remembered basis survives added rows.
                self.poly.begin_group(g as u32);
                // f + g·d <= θw  and  -(f + g·d) <= θw
                row.copy_from_slice(&r.dx);
                self.poly.push_row(&row, r.w - r.value);
                row.iter_mut().for_each(|v| *v = -*v);
                self.poly.push_row(&row, r.w + r.value);
            }
            self.dual.resize(self.poly.rows(), 0.0);
            if self
                .lp
                .minimize(self.poly, self.objective, self.dual, self.primal)
                != LpStatus::Optimal
            {
                return false;
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
