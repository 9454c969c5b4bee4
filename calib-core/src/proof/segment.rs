//! Configurations proved once for the rest of a bisection along a segment.
//!
//! The inner bounds' search ([`crate::proof::consistency::inner_points`]) bisects the segment
//! from a certified point `w` towards a target, testing each point against every configuration.
//! Near the segment's end one or a few configurations bind; the others pass every test with
//! room to spare, and testing them again at each of the 24 steps was most of `gough certify
//! --fast` (`benches/README.md`, issue 52). Here a configuration that passes at a point is also
//! tested over a stretch of the segment holding every point the bisection has left to visit (or
//! those up to a guess of where it stops passing, [`SegmentMemory`]); if it passes there it is not
//! tested again at those points.
//!
//! **The stretch test.** The bisection's points are computed as
//! `at(s) = clamp(w + s·d)` in floating point, `d = target - w` rounded, `s` in `[0, 1]`, clamped
//! into the box `X` (the outer box) that holds the segment. Each lies within `ρ_j` of the line
//! `ℓ(s) = w + s d` in coordinate `j` ([`Segment::new`] bounds `ρ`). With `x̂ = at(t)` a tested
//! point, `S = [lo, hi]` a stretch of parameters holding `t` and a measurement vector `M`, the mean
//! value theorem (on the segment from `x̂` to `at(s)`, inside the convex `X`) gives, for every `s`
//! in `S`,
//!
//! `f(at(s), M) ∈ F(x̂, M) + (S - t) Σ_j G_j d_j + Σ_j G_j [-2ρ_j, 2ρ_j]`
//!
//! where `F(x̂, M)` is the point test's enclosure and `G` encloses `∂f/∂x` over `X` and the
//! measurement box (`at(s) - x̂ = (s - t) d + e(s) - e(t)` with `|e_j| <= ρ_j`). Evaluated in
//! outward-rounded interval arithmetic at the point test's two corners `M⁻, M⁺`, a right-hand side
//! `<= 0` at `M⁻` and `>= 0` at `M⁺` proves the configuration for every point of the stretch, so
//! for every point the bisection can still test when `S` holds its bracket (the brackets nest): the
//! same claim as the point test's, with the same corners. `G` depends only on the configuration
//! and `X`, so it is enclosed once per configuration and search; a stretch test then costs a few
//! interval products.
//!
//! The directional term `(S - t) Σ G_j d_j` is what makes this pass early: along the segment the
//! residual of a configuration that does not bind changes by about its own error band, while a
//! natural interval evaluation over a box around the stretch adds up the large and opposite terms
//! of the residual (`|e|² - (L + l)²` for a Gough leg) coordinate by coordinate and fails until the
//! bracket is tiny.

use crate::num::interval::round::{add_up, mul_up};
use crate::proof::consistency::{sign_test, sign_test_from, sign_test_margin};
use crate::{Interval, VectorModel};

/// A segment `ℓ(s) = w + s d` of the inner bounds' search and how far its computed points stray
/// from it.
pub(crate) struct Segment<const NX: usize> {
    /// The certified start `w`.
    start: [f64; NX],
    /// `target - w`, rounded: the computed points are `clamp(w + s d)`.
    d: [f64; NX],
    /// The box the points are clamped into.
    outer: [Interval; NX],
    /// Per coordinate, `ρ_j`: every computed point `at(s)`, `s` in `[0, 1]`, lies within `ρ_j` of
    /// `ℓ_j(s)`.
    stray: [f64; NX],
}

impl<const NX: usize> Segment<NX> {
    /// The segment from `start` to `target` (both finite), its points clamped into the bounded box
    /// `outer`; `None` when a bound on how far the computed points stray from the line cannot be
    /// given in floating point (an overflow).
    ///
    /// The bound: with `u = 2^-53`, `y = fl(s d_j)` is within `u |d_j|` of `s d_j` and
    /// `z = fl(w_j + y)` within `u (|w_j| + (1 + u) |d_j|)` of `w_j + y`, each up to an underflow
    /// of at most `2^-1075`; the clamp is a projection onto `outer_j`, so it moves `z` at most as
    /// far from `ℓ_j(s)` as `z` was, plus `ℓ_j(s)`'s own distance to `outer_j`, which is convex in
    /// `s` and so at most the larger of its values at `w_j` and `w_j + d_j`. Hence
    /// `ρ_j = 2^-52 (|w_j| + 2 |d_j|) + 2^-1070 + max(dist(w_j), dist(w_j + d_j))`, each operation
    /// rounded up.
    pub(crate) fn new(
        start: &[f64; NX],
        target: &[f64; NX],
        outer: &[Interval; NX],
    ) -> Option<Self> {
        let d: [f64; NX] = core::array::from_fn(|j| target[j] - start[j]);
        let stray: [f64; NX] = core::array::from_fn(|j| {
            let (w, dj, a, b) = (start[j], d[j], outer[j].inf(), outer[j].sup());
            // Distances to [a, b] rounded up: max(a - v, v - b, 0) for v = w and v = w + d.
            let dist_w = add_up(a, -w).max(add_up(w, -b)).max(0.0);
            let dist_end = add_up(add_up(a, -w), -dj)
                .max(add_up(add_up(w, dj), -b))
                .max(0.0);
            let rounding = mul_up(f64::EPSILON, add_up(w.abs(), 2.0 * dj.abs()));
            add_up(add_up(rounding, 2f64.powi(-1070)), dist_w.max(dist_end))
        });
        let finite = |v: &[f64]| v.iter().all(|v| v.is_finite());
        (finite(start) && finite(&d) && finite(&stray) && outer.iter().all(|v| v.is_bounded()))
            .then_some(Segment {
                start: *start,
                d,
                outer: *outer,
                stray,
            })
    }

    /// The computed point at `s`: `clamp(w + s d)` in floating point.
    pub(crate) fn at(&self, s: f64) -> [f64; NX] {
        core::array::from_fn(|i| {
            (self.start[i] + s * self.d[i]).clamp(self.outer[i].inf(), self.outer[i].sup())
        })
    }

    /// The step of a bisection that tests `at(t)` with the bracket `[lo, hi]` around `t`.
    pub(crate) fn step(&self, lo: f64, t: f64, hi: f64) -> Step<'_, NX> {
        Step {
            segment: self,
            point: self.at(t),
            start: self.at(0.0),
            lo,
            t,
            hi,
        }
    }

    /// The margin `min(-sup f(·, M⁻), inf f(·, M⁺))` over the stretch `S` by the mean value form
    /// of the module documentation (non-negative when the configuration is proved for every
    /// point of the stretch), given `offset = S - t`, the point test at `at(t)` (its enclosures
    /// `values` of `f(at(t), M⁻)` and `f(at(t), M⁺)` at the corners `M⁻, M⁺` it picked), and `g`,
    /// an enclosure of `∂f/∂x` over the outer box and the whole measurement box (so for both
    /// corners).
    fn margin(&self, offset: Interval, g: &[Interval; NX], values: &[Interval; 2]) -> f64 {
        // A gradient with no enclosure proves nothing (an empty one would make the change empty).
        if !g.iter().all(|v| v.is_bounded() && !v.is_empty()) {
            return f64::NEG_INFINITY;
        }
        let (mut along, mut aside) = (Interval::ZERO, Interval::ZERO);
        for j in 0..NX {
            let r = 2.0 * self.stray[j];
            along += g[j] * Interval::point(self.d[j]);
            aside += g[j] * Interval::new(-r, r);
        }
        let change = offset * along + aside;
        sign_test_margin(&[values[0] + change, values[1] + change])
    }
}

/// One step of a bisection along a [`Segment`]: the point it tests, `at(t)`, and the bracket
/// `[lo, hi]` around `t` that holds every point still to be tested.
pub(crate) struct Step<'a, const NX: usize> {
    /// The segment.
    segment: &'a Segment<NX>,
    /// The point tested, `at(t)`.
    pub(crate) point: [f64; NX],
    /// The segment's start, `at(0)`.
    pub(crate) start: [f64; NX],
    /// The bracket's lower end.
    lo: f64,
    /// The parameter tested.
    t: f64,
    /// The bracket's upper end.
    hi: f64,
}

/// What the bisections of the segments from one start have learnt about each configuration
/// (see the module documentation).
///
/// A configuration is tested over the stretch `[0, hi]` seen from the segment's start, with the
/// point test there (the same start for every segment of one search, so one point test per
/// configuration and search), the first time a segment's bisection reaches it and then whenever
/// predicted to pass: the margin at the start larger than the shortfall per unit of `hi` that
/// its last failed test from the start showed, times `hi`. Until one passes, the configuration is
/// tested at each step's point, and, when predicted to pass (the same way, per unit of bracket
/// width), over the bracket seen from that point.
///
/// A configuration that binds near the segment's end, or near its upper end `hi`, fails that test
/// (its margin is near zero at the stretch's end). Its point tests on the accepted side of the
/// bisection are what is left; they are replaced by one proof of the stretch `[lo, g]`, seen from
/// `at(g)`, where `g` is just short of `hi` or of where the secant through its margins at the
/// step's point and at its last tested point crosses zero, whichever comes first: along a segment
/// the residual is smooth and nearly linear, so `g` soon lies within the bisection's last steps of
/// the boundary, and the points below `g` need no test of this configuration. A guess beyond the
/// boundary fails its point test and anchors the next secant.
///
/// The predictions only save time: a point is accepted only when each configuration passed its
/// point test there or a stretch test over a box containing it.
pub(crate) struct SegmentMemory<const NX: usize> {
    /// Per configuration: `∂f/∂x` enclosed over the outer box and its measurement box (once
    /// computed).
    slopes: Vec<Option<[Interval; NX]>>,
    /// Per configuration: the point test at the segments' start (once computed).
    start: Vec<Option<[Interval; 2]>>,
    /// Per configuration: at its last failed test over a stretch `[0, hi]` from the start on this
    /// segment, the margin at the start less the stretch margin, over `hi` (0 before the first).
    from_start: Vec<f64>,
    /// Per configuration: proved at every point still to be tested whose parameter is at most
    /// this (`-∞`: none).
    proved_to: Vec<f64>,
    /// Per configuration: at its last failed stretch test over a bracket, the point margin less
    /// the stretch margin, over the bracket width (0 before the first).
    shortfall: Vec<f64>,
    /// Per configuration: the parameter and the point test's enclosures where it was last tested
    /// on this segment.
    last: Vec<Option<(f64, [Interval; 2])>>,
}

impl<const NX: usize> SegmentMemory<NX> {
    /// Nothing learnt, for `p` configurations and segments from one start.
    pub(crate) fn new(p: usize) -> Self {
        SegmentMemory {
            slopes: vec![None; p],
            start: vec![None; p],
            from_start: vec![0.0; p],
            proved_to: vec![f64::NEG_INFINITY; p],
            shortfall: vec![0.0; p],
            last: vec![None; p],
        }
    }

    /// A new segment from the same start in the same outer box, for `p` configurations: forgets
    /// all but the slopes and the point tests at the start.
    pub(crate) fn reset(&mut self, p: usize) {
        if self.start.len() != p {
            *self = SegmentMemory::new(p);
            return;
        }
        self.from_start.fill(0.0);
        self.proved_to.fill(f64::NEG_INFINITY);
        self.shortfall.fill(0.0);
        self.last.fill(None);
    }

    /// Whether configuration `k` (measurement box `m`, bounded) is proved at the step's point
    /// (`point` as intervals): by an earlier stretch test, by a stretch test from the start
    /// (`start`: the segment's start `at(0)` as intervals), or by the point test (followed, when
    /// predicted to pass, by a stretch test for the steps to come). One residual per
    /// configuration (`NR = 1`).
    pub(crate) fn passes<M, const NM: usize, const NR: usize>(
        &mut self,
        model: &M,
        step: &Step<'_, NX>,
        point: &[Interval; NX],
        start: &[Interval; NX],
        k: usize,
        m: &[Interval; NM],
    ) -> bool
    where
        M: VectorModel<NX, NM, NR>,
    {
        let segment = step.segment;
        if step.t <= self.proved_to[k] {
            return true;
        }
        let g =
            *self.slopes[k].get_or_insert_with(|| model.jacobians_x_interval(&segment.outer, m)[0]);
        let at_start = *self.start[k].get_or_insert_with(|| sign_test(model, start, m));
        let margin_start = sign_test_margin(&at_start);
        if margin_start > self.from_start[k] * step.hi {
            let over = segment.margin(Interval::new(0.0, step.hi), &g, &at_start);
            if over >= 0.0 {
                self.proved_to[k] = step.hi;
                return true;
            }
            self.from_start[k] = (margin_start - over) / step.hi;
        }
        // The side that failed last first: a refuted point then costs one evaluation.
        let first = Some(self.last[k].map_or(0, |(_, v)| usize::from(v[1].inf() < 0.0)));
        let values = sign_test_from(model, point, m, first);
        let margin = sign_test_margin(&values);
        let previous = self.last[k].replace((step.t, values));
        if margin < 0.0 {
            return false;
        }
        let width = step.hi - step.lo;
        if margin > self.shortfall[k] * width {
            let near = Interval::new(step.lo, step.hi) - Interval::point(step.t);
            let over = segment.margin(near, &g, &values);
            if over >= 0.0 {
                self.proved_to[k] = step.hi;
                return true;
            }
            self.shortfall[k] = (margin - over) / width;
        }
        if let Some(end) = previous.and_then(|p| guess(p, (step.t, &values), step.hi)) {
            let values_end = sign_test_from(model, &segment.at(end).map(Interval::point), m, first);
            if sign_test_margin(&values_end) >= 0.0 {
                let below = Interval::new(step.lo, end) - Interval::point(end);
                if segment.margin(below, &g, &values_end) >= 0.0 {
                    self.proved_to[k] = end;
                }
            }
            self.last[k] = Some((end, values_end));
        }
        true
    }
}

/// Where a configuration's next proof should end (see [`SegmentMemory`]): just short of `hi` or
/// of the zero of the secant through its margins at its last tested point `previous` and at `t`
/// (the point test's enclosures there, passed), whichever comes first. The secant follows the
/// side that failed at `previous`, else the side with less room at `t`. `None` when the secant
/// does not fall towards zero beyond `t`.
fn guess(previous: (f64, [Interval; 2]), now: (f64, &[Interval; 2]), hi: f64) -> Option<f64> {
    let ((tp, before), (t, values)) = (previous, now);
    // The margin of a side: `f(·, M⁻) <= 0` (`-sup`) or `f(·, M⁺) >= 0` (`inf`).
    let side = |v: &[Interval; 2], below: bool| {
        if below {
            -v[0].sup()
        } else {
            v[1].inf()
        }
    };
    let below = if side(&before, true) < 0.0 {
        true
    } else if side(&before, false) < 0.0 {
        false
    } else {
        side(values, true) <= side(values, false)
    };
    let (a, b) = (side(values, below), side(&before, below));
    let slope = (a - b) / (t - tp);
    if !(slope < 0.0 && a >= 0.0) {
        return None;
    }
    let r = (t - a / slope).min(hi);
    // A little short: the secant of a smooth margin errs by a small share of the bracket, and a
    // guess beyond the boundary costs a test for a better secant.
    let g = t + (r - t) * (1.0 - 1.0 / 1024.0);
    (g > t && g < hi && g.is_finite()).then_some(g)
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_rational::BigRational;
    use num_traits::Signed;
    use rand::{Rng, SeedableRng};

    fn rat(x: f64) -> BigRational {
        BigRational::from_float(x).expect("finite")
    }

    /// A stretch is proved only from enclosures that hold something: an empty value or an
    /// empty or unbounded gradient gives no margin (an empty change would have passed).
    #[test]
    fn empty_enclosures_prove_no_stretch() {
        let outer = [Interval::new(-1.0, 1.0); 2];
        let segment = Segment::new(&[0.0, 0.0], &[0.5, 0.5], &outer).expect("a segment");
        let passing = [Interval::new(-2.0, -1.0), Interval::new(1.0, 2.0)];
        let g = [Interval::new(-0.1, 0.1); 2];
        let offset = Interval::new(0.0, 0.1);
        assert!(segment.margin(offset, &g, &passing) >= 0.0);
        for bad in [Interval::EMPTY, Interval::ENTIRE] {
            assert_eq!(
                segment.margin(offset, &[bad, g[1]], &passing),
                f64::NEG_INFINITY
            );
        }
        let empty_value = [Interval::EMPTY, passing[1]];
        assert_eq!(segment.margin(offset, &g, &empty_value), f64::NEG_INFINITY);
        assert_eq!(
            crate::proof::consistency::sign_test_margin(&empty_value),
            f64::NEG_INFINITY
        );
    }

    /// The stray bound the stretch proofs rest on, checked in exact arithmetic: every computed
    /// point `at(s)` lies within `ρ_j` of the exact line `w + s d`, for boxes of many scales,
    /// starts inside and outside the box, and targets inside it and on its faces.
    #[test]
    fn computed_points_stay_within_the_stray_bound() {
        let mut rng = rand::rngs::StdRng::seed_from_u64(52);
        for case in 0..300 {
            let scale = 10f64.powi(rng.random_range(-3..=3));
            let outer: [Interval; 3] = core::array::from_fn(|_| {
                let lo = rng.random_range(-1.0..1.0) * scale;
                Interval::new(lo, lo + rng.random_range(0.0..1.0) * scale)
            });
            let start: [f64; 3] = core::array::from_fn(|j| {
                outer[j].inf() + rng.random_range(-0.2..1.2) * outer[j].wid()
            });
            let target: [f64; 3] = core::array::from_fn(|j| match case % 3 {
                0 => outer[j].inf(),
                1 => outer[j].sup(),
                _ => outer[j].inf() + rng.random_range(0.0..1.0) * outer[j].wid(),
            });
            let segment = Segment::new(&start, &target, &outer).expect("finite data");
            let params = (0..=32)
                .map(|k| f64::from(k) / 32.0)
                .chain((0..32).map(|_| rng.random_range(0.0..1.0)));
            for s in params {
                let p = segment.at(s);
                for j in 0..3 {
                    let line = rat(segment.start[j]) + rat(s) * rat(segment.d[j]);
                    let off = (rat(p[j]) - line).abs();
                    assert!(
                        off <= rat(segment.stray[j]),
                        "case {case}, s = {s}, coordinate {j}: {p:?} strays beyond {}",
                        segment.stray[j]
                    );
                }
            }
        }
    }
}
