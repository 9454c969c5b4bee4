//! Certificates: proofs that parameter vectors are consistent with the data, and inner bounds.
//!
//! A point `x*` is *certified consistent* when, for every measurement `k`, two measurement vectors
//! `M⁻, M⁺ ∈ M_k` are found with rigorously evaluated `f(x*, M⁻) <= 0 <= f(x*, M⁺)`: `M_k` is a box
//! (connected) and `f` is continuous, so `f(x*, M) = 0` for some `M ∈ M_k` — `x*` belongs to the
//! solution set `S(M)` of paper eq. (5). Interior contraction alone is not used as a proof: the
//! paper's square-system argument does not carry over to over-determined systems.
//!
//! For a [`crate::VectorModel`] with `NR >= 2` residuals per configuration the two-corner test
//! cannot be applied row by row: each row would be allowed its own reading. A point is then
//! certified by the coupled existence proof of [`crate::proof::existence`] (a parametric Krawczyk
//! test on `NR` of the measured quantities), which exhibits one reading per configuration at which
//! every row vanishes.
//!
//! The same tests with an interval `x` instead of a point prove that a whole box lies in `S(M)`
//! (used by the paver for inner volume). Inner bounds come from certified points near the extremes
//! of each parameter: the hull of `S(M)` lies between the hull of certified points and the outer
//! box.

use crate::num::linalg::gauss_jordan_inverse;
use crate::proof::existence::configuration_fits;
use crate::proof::segment::{Segment, SegmentMemory, Step};
use crate::{Interval, Model, VectorModel};

/// Whether every `x` in the box `x` (a point when the box is degenerate) is consistent with every
/// measurement box: by the sign test described in the module documentation for one residual per
/// configuration, by the coupled existence test (a parametric Krawczyk test) for several.
pub fn is_certified_consistent<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
) -> bool
where
    M: VectorModel<NX, NM, NR>,
{
    bounded(x, measurements)
        && measurements
            .iter()
            .all(|m| configuration_consistent(model, x, m))
}

/// Whether the box and every measurement box are bounded (the corners of an unbounded box are not
/// points: no certificate, and no panic).
fn bounded<const NX: usize, const NM: usize>(
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
) -> bool {
    let bounded = |b: &[Interval]| b.iter().all(|v| v.is_bounded());
    bounded(x) && measurements.iter().all(|m| bounded(m))
}

/// Whether every `x` in the bounded box `x` is consistent with the one bounded measurement box `m`
/// (the test of [`is_certified_consistent`], for one configuration).
fn configuration_consistent<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    m: &[Interval; NM],
) -> bool
where
    M: VectorModel<NX, NM, NR>,
{
    if NR != 1 {
        return configuration_fits(model, x, m);
    }
    sign_test_margin(&sign_test(model, x, m)) >= 0.0
}

/// The sign test of [`configuration_consistent`] for one residual per configuration (`NR = 1`)
/// over the box `x`: enclosures of `f(x, M⁻)` and `f(x, M⁺)` at the two corners `M⁻`, `M⁺` of `m`
/// that the linearisation in `M` at the centre picks (see [`sign_test_margin`]).
pub(crate) fn sign_test<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    m: &[Interval; NM],
) -> [Interval; 2]
where
    M: VectorModel<NX, NM, NR>,
{
    sign_test_from(model, x, m, None)
}

/// [`sign_test`], with `first = Some(side)` evaluating that side first (`0`: `M⁻`, `1`: `M⁺`) and,
/// when it fails, not the other: its enclosure is then returned as `[0, 0]`, which fails neither
/// side, so [`sign_test_margin`] still says the test failed.
pub(crate) fn sign_test_from<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    m: &[Interval; NM],
    first: Option<usize>,
) -> [Interval; 2]
where
    M: VectorModel<NX, NM, NR>,
{
    // The linearisation in M at the centre picks the corners most likely to change the sign.
    let xm = x.map(|v| v.mid());
    let mm = m.map(|v| v.mid());
    let g = model.jacobians_m(&xm, &mm)[0];
    let corner = |up: bool| -> [Interval; NM] {
        core::array::from_fn(|i| {
            let (lo, hi) = (m[i].inf(), m[i].sup());
            Interval::point(if (g[i] > 0.0) == up { hi } else { lo })
        })
    };
    let value = |side: usize| model.residuals_interval(x, &corner(side == 1))[0];
    match first {
        None => [value(0), value(1)],
        Some(side) => {
            let mut values = [Interval::ZERO; 2];
            values[side] = value(side);
            if sign_test_margin(&values) >= 0.0 {
                values[1 - side] = value(1 - side);
            }
            values
        }
    }
}

/// `min(-sup f(x, M⁻), inf f(x, M⁺))` from the enclosures of [`sign_test`]: non-negative exactly
/// when the test passes (`f(x, M⁻) <= 0 <= f(x, M⁺)` over the box), and how much room is left.
/// An empty enclosure (an evaluation with no value, e.g. a square root of a negative range) or
/// one with a NaN end fails: `-∞`.
pub(crate) fn sign_test_margin(values: &[Interval; 2]) -> f64 {
    let usable = |v: &Interval| !v.is_empty() && !v.inf().is_nan() && !v.sup().is_nan();
    if !values.iter().all(usable) {
        return f64::NEG_INFINITY;
    }
    (-values[0].sup()).min(values[1].inf())
}

/// [`is_consistent_point`] for a sequence of nearby points (a bisection, a walk towards a face):
/// the configuration that refuted the last point is tested first. Points near the edge of the
/// solution set are refuted by the same few configurations again and again, so a refutation
/// usually costs one configuration test instead of half of them. The answer is the same as
/// [`is_consistent_point`]'s: every configuration is still tested before a point is accepted.
pub(crate) struct FailFirst {
    order: Vec<usize>,
}

impl FailFirst {
    /// An order for `p` configurations.
    pub(crate) fn new(p: usize) -> Self {
        FailFirst {
            order: (0..p).collect(),
        }
    }

    /// Whether the point `x` is certified consistent (see [`is_consistent_point`]).
    pub(crate) fn is_consistent_point<M, const NX: usize, const NM: usize, const NR: usize>(
        &mut self,
        model: &M,
        x: &[f64; NX],
        measurements: &[[Interval; NM]],
    ) -> bool
    where
        M: VectorModel<NX, NM, NR>,
    {
        let xi = x.map(Interval::point);
        if !x.iter().all(|v| v.is_finite()) || !bounded(&xi, measurements) {
            return false;
        }
        if self.order.len() != measurements.len() {
            *self = FailFirst::new(measurements.len());
        }
        let Some(pos) = self
            .order
            .iter()
            .position(|&k| !configuration_consistent(model, &xi, &measurements[k]))
        else {
            return true;
        };
        self.order[..=pos].rotate_right(1);
        false
    }

    /// [`FailFirst::is_consistent_point`] for the point of a bisection step along a segment (see
    /// [`crate::proof::segment`]): the configurations `memory` proved over an earlier stretch of
    /// the segment are not tested again, and those that pass may be proved for the steps to come.
    /// Returns whether the step's point is certified consistent. Every measurement box must be
    /// bounded (the caller checks them once, not at every step).
    fn is_consistent_on_segment<M, const NX: usize, const NM: usize, const NR: usize>(
        &mut self,
        model: &M,
        step: &Step<'_, NX>,
        memory: &mut SegmentMemory<NX>,
        measurements: &[[Interval; NM]],
    ) -> bool
    where
        M: VectorModel<NX, NM, NR>,
    {
        if NR != 1 {
            return self.is_consistent_point(model, &step.point, measurements);
        }
        if !step.point.iter().all(|v| v.is_finite()) {
            return false;
        }
        let xi = step.point.map(Interval::point);
        let start = step.start.map(Interval::point);
        if self.order.len() != measurements.len() {
            *self = FailFirst::new(measurements.len());
        }
        let Some(pos) = self
            .order
            .iter()
            .position(|&k| !memory.passes(model, step, &xi, &start, k, &measurements[k]))
        else {
            return true;
        };
        self.order[..=pos].rotate_right(1);
        false
    }
}

/// Whether the point `x` is certified consistent.
pub fn is_consistent_point<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[f64; NX],
    measurements: &[[Interval; NM]],
) -> bool
where
    M: VectorModel<NX, NM, NR>,
{
    x.iter().all(|v| v.is_finite())
        && is_certified_consistent(model, &x.map(Interval::point), measurements)
}

/// Whether the point `x` is consistent with every measurement box by an exhaustive test: among the
/// `2^NM` corners of each box, one gives a rigorously non-positive and one a non-negative residual.
/// Slower than [`is_consistent_point`] and independent of the linearisation it uses to pick two
/// corners: meant for checking certified points in tests and measurements.
///
/// # Panics
/// If `NM > 20` (more than a million corners per box).
pub fn is_consistent_by_corners<M: Model<NX, NM>, const NX: usize, const NM: usize>(
    model: &M,
    x: &[f64; NX],
    measurements: &[[Interval; NM]],
) -> bool {
    assert!(NM <= 20, "2^{NM} corners per measurement box is too many");
    let xi = x.map(Interval::point);
    x.iter().all(|v| v.is_finite())
        && measurements.iter().all(|m| {
            let (mut neg, mut pos) = (false, false);
            for mask in 0..1u64 << NM {
                let corner: [Interval; NM] = core::array::from_fn(|i| {
                    Interval::point(if mask >> i & 1 == 1 {
                        m[i].sup()
                    } else {
                        m[i].inf()
                    })
                });
                let f = model.residual_interval(&xi, &corner);
                neg |= f.sup() <= 0.0;
                pos |= f.inf() >= 0.0;
                if neg && pos {
                    return true;
                }
            }
            false
        })
}

/// A Gauss–Newton (Levenberg-damped) least-squares point of `Σ_k f(x, mid M_k)²` started at the
/// box centre and kept inside the box: a good candidate for a witness.
pub(crate) fn least_squares_point<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
) -> [f64; NX]
where
    M: VectorModel<NX, NM, NR>,
{
    let mut p = x.map(|v| v.mid());
    let mut normal = vec![0.0; NX * NX];
    let mut inv = vec![0.0; NX * NX];
    for _ in 0..20 {
        let mut rhs = [0.0; NX];
        normal.iter_mut().for_each(|v| *v = 0.0);
        for m in measurements {
            let mm = m.map(|v| v.mid());
            for e in model.evaluate_rows(&p, &mm) {
                for i in 0..NX {
                    rhs[i] -= e.dx[i] * e.value;
                    for j in 0..NX {
                        normal[i * NX + j] += e.dx[i] * e.dx[j];
                    }
                }
            }
        }
        let scale = (0..NX).map(|i| normal[i * NX + i]).fold(0.0, f64::max);
        for i in 0..NX {
            normal[i * NX + i] += 1e-12 * scale + f64::MIN_POSITIVE;
        }
        if !gauss_jordan_inverse(NX, &mut normal, &mut inv) {
            break;
        }
        let mut step = 0.0;
        for i in 0..NX {
            let d: f64 = (0..NX).map(|j| inv[i * NX + j] * rhs[j]).sum();
            let next = (p[i] + d).clamp(x[i].inf(), x[i].sup());
            step += (next - p[i]).abs();
            p[i] = next;
        }
        if !step.is_finite() || step < 1e-15 {
            break;
        }
    }
    p
}

/// The hull of points, each a degenerate box (empty intervals when there is none): the inner box
/// of certified points.
pub(crate) fn point_hull<'a, const NX: usize>(
    points: impl IntoIterator<Item = &'a [f64; NX]>,
) -> [Interval; NX] {
    points.into_iter().fold([Interval::EMPTY; NX], |h, p| {
        core::array::from_fn(|i| h[i].hull(Interval::point(p[i])))
    })
}

/// Inner bounds: starting from a certified `witness` in the box `outer`, walks towards each `target`
/// (the LP extreme points, clamped into `outer`) by bisection on the segment and returns, per
/// target, the farthest certified point found. Every point tried lies in `outer` (a convex box
/// containing the witness), so the hull of the witness and these points (the inner box) lies in
/// the outer one. A point is accepted when every configuration passed the sign test there or
/// over a stretch of the segment holding it ([`crate::proof::segment`]: the bisection's answer,
/// with most configurations proved once per segment instead of at every step).
pub(crate) fn inner_points<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    witness: &[f64; NX],
    outer: &[Interval; NX],
    targets: &[[f64; NX]],
    measurements: &[[Interval; NM]],
    bisections: usize,
) -> Vec<[f64; NX]>
where
    M: VectorModel<NX, NM, NR>,
{
    let mut order = FailFirst::new(measurements.len());
    let mut memory = SegmentMemory::new(measurements.len());
    let measured = measurements
        .iter()
        .all(|m| m.iter().all(|v| v.is_bounded()));
    let mut points = Vec::new();
    for target in targets {
        let target: &[f64; NX] =
            &core::array::from_fn(|i| target[i].clamp(outer[i].inf(), outer[i].sup()));
        let at = |t: f64| -> [f64; NX] {
            core::array::from_fn(|i| {
                (witness[i] + t * (target[i] - witness[i])).clamp(outer[i].inf(), outer[i].sup())
            })
        };
        let segment = Segment::new(witness, target, outer).filter(|_| measured);
        let mut best = None;
        if order.is_consistent_point(model, target, measurements) {
            best = Some(*target);
        } else {
            memory.reset(measurements.len());
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..bisections {
                let t = 0.5 * (lo + hi);
                let (p, consistent) = match &segment {
                    Some(segment) => {
                        let step = segment.step(lo, t, hi);
                        let ok =
                            order.is_consistent_on_segment(model, &step, &mut memory, measurements);
                        (step.point, ok)
                    }
                    None => {
                        let p = at(t);
                        (p, order.is_consistent_point(model, &p, measurements))
                    }
                };
                if consistent {
                    lo = t;
                    best = Some(p);
                } else {
                    hi = t;
                }
            }
        }
        points.extend(best);
    }
    points
}
