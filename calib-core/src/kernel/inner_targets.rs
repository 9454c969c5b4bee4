//! Targets for inner bounds: the extreme points of the consistent set to first order about a
//! certified point.
//!
//! The inner bound of parameter `j` is the farthest certified point found on a segment from the
//! witness `w` towards a target ([`crate::proof::consistency`]). The contraction's LP extreme
//! points are natural targets when its relaxation is tight; where it carries slack (a wide prior:
//! the affine remainders of a 27-parameter arm over its prior are a third to a half of the error
//! bound, see `benches/README.md`) they lie on the prior's faces in directions the data exclude,
//! and the segment leaves the set after a few per cent of the way: measured on a real UR10, inner
//! bounds of 5-12% of the prior where the consistent set spans 31-100% of it.
//!
//! This module computes the extremes of the *linearised* set at `w` instead:
//!
//! `min / max x_j  s.t.  |f_r(w, m̄_k) + ∂f_r/∂x (w, m̄_k) · (x - w)| <= Σ_i |∂f_r/∂M_i| rad(M_k,i)`
//!
//! for every row `r` of every configuration `k` (`m̄_k` the box's midpoint), `x` in the outer box;
//! each row may use its own reading (the rows of a configuration are decoupled). The whole error
//! bound is used: near the smallest consistent bound, a share of it (0.9 was tried) leaves an
//! empty linearised set. The segment search then stops where the nonlinear terms take the
//! points out (50-88% of the way to these targets on the real UR10, against 0.4-9% of the way to
//! the contraction's extremes). Nothing here is a proof: the points are only targets, and every
//! inner point is certified on its own by the existence tests.

use crate::lp::{DenseSimplex, LpBackend, LpStatus, Polyhedron};
use crate::proof::consistency::{inner_points, point_hull};
use crate::{Interval, VectorModel};

/// A side of the inner box is searched again when more than this share of the outer width lies
/// between it and the outer face: where the contraction's extremes already took the inner box
/// near the outer one (a tight relaxation), the extra searches would cost time for nothing (the
/// same bounds, a slower `arm demo`; `benches/README.md`).
pub(crate) const SHORT_SIDE: f64 = 0.2;

/// Rounds of [`wider_inner_points`] after the first: each starts from the farthest certified
/// point of a side and linearises there, nearer the boundary than the witness.
pub(crate) const MORE_ROUNDS: usize = 1;

/// More inner points (see the module documentation): from the certified point `w`, towards the
/// first-order extremes of each side of the box `outer` where the hull of `w` and `found` (the
/// inner points found so far) stops more than [`SHORT_SIDE`] of the outer width from the outer
/// face; then, [`MORE_ROUNDS`] times, for each side still short, from that side's farthest point
/// towards the extreme of the linearisation there. Every point returned is certified consistent
/// ([`inner_points`]: each segment starts at a certified point).
pub(crate) fn wider_inner_points<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    w: &[f64; NX],
    outer: &[Interval; NX],
    measurements: &[[Interval; NM]],
    found: &[[f64; NX]],
    bisections: usize,
) -> Vec<[f64; NX]>
where
    M: VectorModel<NX, NM, NR>,
{
    let mut all: Vec<[f64; NX]> = found.to_vec();
    all.push(*w);
    let hull = point_hull(&all);
    let targets = first_order_extremes(model, w, outer, measurements, |j, u| {
        is_short(outer, &hull, j, u)
    });
    let mut points = inner_points(model, w, outer, &targets, measurements, bisections);
    for _ in 0..MORE_ROUNDS {
        all.extend_from_slice(&points);
        let hull = point_hull(&all);
        let mut more = Vec::new();
        for j in 0..NX {
            for upper in [false, true] {
                if !is_short(outer, &hull, j, upper) {
                    continue;
                }
                // The side's farthest certified point.
                let side = |p: &&[f64; NX]| if upper { p[j] } else { -p[j] };
                let Some(origin) = all.iter().max_by(|a, b| side(a).total_cmp(&side(b))) else {
                    continue;
                };
                let target = first_order_extremes(model, origin, outer, measurements, |i, u| {
                    i == j && u == upper
                });
                more.extend(inner_points(
                    model,
                    origin,
                    outer,
                    &target,
                    measurements,
                    bisections,
                ));
            }
        }
        points.extend(more);
    }
    points
}

/// Whether the side of `inner` (`upper`: the greatest values) along parameter `j` stops more than
/// [`SHORT_SIDE`] of the outer width from the face of `outer`.
fn is_short<const NX: usize>(
    outer: &[Interval; NX],
    inner: &[Interval; NX],
    j: usize,
    upper: bool,
) -> bool {
    let gap = if upper {
        outer[j].sup() - inner[j].sup()
    } else {
        inner[j].inf() - outer[j].inf()
    };
    gap > SHORT_SIDE * outer[j].wid()
}

/// The first-order extreme points about the certified point `w` in the box `outer` (see the
/// module documentation): for each parameter not fixed by `outer` and each side (`true`: the
/// greatest value) that `wanted` asks for, the extreme point, where the LP engine found it (an LP
/// that fails gives no point).
pub(crate) fn first_order_extremes<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    w: &[f64; NX],
    outer: &[Interval; NX],
    measurements: &[[Interval; NM]],
    wanted: impl Fn(usize, bool) -> bool,
) -> Vec<[f64; NX]>
where
    M: VectorModel<NX, NM, NR>,
{
    // Unknowns `z_j = (x_j - w_j) / s_j`, `s_j` the outer half-width: every column in the
    // same units (the simplex misjudges feasibility on columns of mixed units).
    let s: [f64; NX] = core::array::from_fn(|j| outer[j].rad());
    let live: Vec<usize> = (0..NX)
        .filter(|&j| s[j] > 0.0 && s[j].is_finite() && (wanted(j, false) || wanted(j, true)))
        .collect();
    if live.is_empty() || !w.iter().all(|v| v.is_finite()) {
        return Vec::new();
    }
    let lo: [f64; NX] = core::array::from_fn(|j| {
        if s[j] > 0.0 {
            (outer[j].inf() - w[j]) / s[j]
        } else {
            0.0
        }
    });
    let hi: [f64; NX] = core::array::from_fn(|j| {
        if s[j] > 0.0 {
            (outer[j].sup() - w[j]) / s[j]
        } else {
            0.0
        }
    });
    if (0..NX).any(|j| !(lo[j] <= hi[j] && lo[j].is_finite() && hi[j].is_finite())) {
        return Vec::new();
    }
    let mut poly = Polyhedron::default();
    poly.reset(&lo, &hi);
    let mut row = [0.0; NX];
    for m in measurements {
        let mid = m.map(|v| v.mid());
        for e in model.evaluate_rows(w, &mid) {
            let room: f64 =
                e.dm.iter()
                    .zip(m)
                    .map(|(d, b)| d.abs() * b.rad())
                    .sum::<f64>();
            for j in 0..NX {
                row[j] = e.dx[j] * s[j];
            }
            poly.push_row(&row, room - e.value);
            let neg = row.map(|v| -v);
            poly.push_row(&neg, room + e.value);
        }
    }
    let mut engine = DenseSimplex::default();
    let mut dual = vec![0.0; poly.rows()];
    let mut primal = vec![0.0; NX];
    let mut points = Vec::with_capacity(2 * live.len());
    let mut c = [0.0; NX];
    for &j in &live {
        for upper in [false, true].into_iter().filter(|&u| wanted(j, u)) {
            // The least value of `±z_j`: the lower side for `+`, the upper for `-`.
            c[j] = if upper { -1.0 } else { 1.0 };
            if engine.minimize(&poly, &c, &mut dual, &mut primal) == LpStatus::Optimal {
                let p: [f64; NX] = core::array::from_fn(|i| {
                    (w[i] + primal[i] * s[i]).clamp(outer[i].inf(), outer[i].sup())
                });
                if p.iter().all(|v| v.is_finite()) {
                    points.push(p);
                }
            }
            c[j] = 0.0;
        }
    }
    points
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::is_consistent_point;
    use crate::test_models::Plane;

    /// `|x0 + x1 - 1| <= 0.1` and `|x0 - x1| <= 0.1`: a square turned by 45°, `[0.4, 0.6]` in
    /// each coordinate, inside a wide outer box.
    fn square() -> (Vec<[Interval; 3]>, [Interval; 2]) {
        let p = Interval::point;
        let m = vec![
            [p(1.0), p(1.0), Interval::new(0.9, 1.1)],
            [p(1.0), p(-1.0), Interval::new(-0.1, 0.1)],
        ];
        (m, [Interval::new(-2.0, 2.0); 2])
    }

    #[test]
    fn first_order_extremes_of_a_linear_model_are_the_set_s_extremes() {
        let (m, outer) = square();
        let points = first_order_extremes(&Plane, &[0.5, 0.5], &outer, &m, |_, _| true);
        assert_eq!(points.len(), 4, "{points:?}");
        // In order: x0 least, x0 greatest, x1 least, x1 greatest.
        for (k, p) in points.iter().enumerate() {
            let want = if k % 2 == 0 { 0.4 } else { 0.6 };
            assert!((p[k / 2] - want).abs() < 1e-9, "{k}: {p:?}");
        }
        // Only the sides asked for.
        let upper = first_order_extremes(&Plane, &[0.5, 0.5], &outer, &m, |j, u| j == 1 && u);
        assert_eq!(upper.len(), 1);
        assert!((upper[0][1] - 0.6).abs() < 1e-9, "{upper:?}");
    }

    #[test]
    fn wider_inner_points_are_certified_and_reach_the_set_s_sides() {
        let (m, outer) = square();
        let w = [0.5, 0.5];
        // The witness alone: every side is short, searched towards its first-order extreme.
        let points = wider_inner_points(&Plane, &w, &outer, &m, &[], 20);
        assert!(!points.is_empty());
        for p in &points {
            assert!(
                is_consistent_point(&Plane, p, &m),
                "{p:?} is not consistent"
            );
            assert!(outer[0].contains(p[0]) && outer[1].contains(p[1]));
        }
        let hull = point_hull(&points);
        for h in hull {
            assert!(h.inf() < 0.4 + 1e-4 && h.sup() > 0.6 - 1e-4, "{hull:?}");
        }
        // Sides that the points found so far take within a fifth of the outer width of the outer
        // face are not searched again.
        let tight = [Interval::new(0.35, 0.65); 2];
        let near = [
            [0.4 + 1e-3, 0.5],
            [0.6 - 1e-3, 0.5],
            [0.5, 0.4 + 1e-3],
            [0.5, 0.6 - 1e-3],
        ];
        assert!(wider_inner_points(&Plane, &w, &tight, &m, &near, 20).is_empty());
        assert_eq!(
            wider_inner_points(&Plane, &w, &tight, &m, &near[..3], 20).len(),
            1,
            "the upper side of x1 alone"
        );
    }
}
