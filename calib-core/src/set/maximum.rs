//! A certified global maximum of a function over a box: an upper bound proved over the whole box
//! and a lower bound attained at an explicit point, so that the true maximum lies between them.
//!
//! This is the question behind an accuracy certificate ("how far from the commanded pose can the
//! calibrated robot be, anywhere in its workspace and for every parameter vector the data allow?"):
//! the function's inputs are the workspace coordinates, the parameters and the actuator errors,
//! all in one box.
//!
//! # The method (interval branch and bound)
//!
//! The boxes still to examine are kept in a queue ordered by the upper end of `f`'s enclosure
//! over them ([`Objective::enclose`], intersected with the mean-value form when a gradient is
//! available). The lower bound is the largest lower end of `f`'s
//! enclosure at any point evaluated so far ([`Objective::at`]): `f` attains at least that value
//! there. Each step takes the box with the largest upper end, splits it at the midpoint of its
//! widest side (relative to the domain), and for each half
//!
//! * with a gradient enclosure ([`Objective::gradient`]) whose component `j` excludes 0, moves
//!   the half to its face where `f` grows (`f` is monotone in `x_j` on the whole half, so the
//!   maximum over the half is on that face);
//! * drops it when the upper end of its enclosure is below the lower bound (no point in it can be
//!   the maximiser);
//! * evaluates `f` at its midpoint to raise the lower bound, and queues it.
//!
//! **Soundness.** Every point of the domain lies in a queued box or in a dropped one, and a box
//! is dropped only when `f` is below the lower bound everywhere on it, which `f` attains. So
//! `max f <= max(upper ends over the queue)`, which is the reported upper bound, and
//! `max f >= lower`. Failures (a NaN or unbounded enclosure) never drop a box: the upper bound is
//! then `+∞`.

use crate::kernel::bisection::split_widest;
use crate::Interval;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// A function to maximise, evaluated rigorously.
pub trait Objective<const N: usize> {
    /// An enclosure of `f` over the box `x`: every `f(p)` with `p` in `x` lies in it.
    fn enclose(&self, x: &[Interval; N]) -> Interval;

    /// An enclosure of `f` over `x` that may be loose where its upper end is at most `enough`: a
    /// box bounded by `enough` cannot raise the maximum beyond it, so an objective with a cheap
    /// and a costly enclosure may stop at the cheap one there. By default
    /// [`Objective::enclose`].
    fn enclose_up_to(&self, x: &[Interval; N], enough: f64) -> Interval {
        let _ = enough;
        self.enclose(x)
    }

    /// An enclosure of `f` at the point `x` (by default [`Objective::enclose`] of the thin box).
    fn at(&self, x: &[f64; N]) -> Interval {
        self.enclose(&x.map(Interval::point))
    }

    /// An enclosure of `f`'s gradient over the box `x`, when available (it lets the search move a
    /// box to a face where `f` is monotone). By default none.
    fn gradient(&self, _x: &[Interval; N]) -> Option<[Interval; N]> {
        None
    }

    /// A local search from the point `x`: a point of the domain and a value `f` is proved to
    /// reach there (at least), when the objective has a better way to raise the lower bound than
    /// evaluating at the midpoints of boxes (e.g. an ascent to the domain's boundary). By default
    /// none.
    fn improve(&self, _x: &[f64; N]) -> Option<([f64; N], f64)> {
        None
    }

    /// A value `f` is proved to reach at the point `x` (`-∞` for none), for searches that need
    /// only the lower bound there ([`maximize_over_list`]): by default the lower end of
    /// [`Objective::at`]; an objective whose `at` also computes a costly upper end may skip it.
    fn attained(&self, x: &[f64; N]) -> f64 {
        let v = self.at(x);
        if v.is_empty() || v.inf().is_nan() {
            f64::NEG_INFINITY
        } else {
            v.inf()
        }
    }

    /// The widths boxes are split against: each step halves the side widest relative to these.
    /// By default the domain's own (every coordinate refined in proportion to its range); an
    /// objective whose coordinates share a unit (angles, say) may return equal widths so that
    /// they are refined to the same absolute size.
    fn split_reference(&self, domain: &[Interval; N]) -> [Interval; N] {
        *domain
    }

    /// Per coordinate, how much `f` changes per unit of that coordinate over the box `x` (an
    /// estimate: its slope, plus its curvature times the half-width), when the objective has one:
    /// the box is then split where `f` changes most, `width × weight` (the *smear* of interval
    /// global optimisation), rather than at its widest side. Only the choice of split depends on
    /// it, never a bound. By default none.
    fn split_weights(&self, _x: &[Interval; N]) -> Option<[f64; N]> {
        None
    }
}

/// When to stop [`maximize`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaximumSettings {
    /// Stop once `upper - lower <= rel_tol · |lower|` (default 0.01).
    pub rel_tol: f64,
    /// … or `upper - lower <= abs_tol` (default 0).
    pub abs_tol: f64,
    /// Examine at most this many boxes (default 100 000).
    pub max_boxes: usize,
}

impl Default for MaximumSettings {
    fn default() -> Self {
        MaximumSettings {
            rel_tol: 0.01,
            abs_tol: 0.0,
            max_boxes: 100_000,
        }
    }
}

/// The certified bracket of a maximum.
#[derive(Clone, Debug, PartialEq)]
pub struct Maximum<const N: usize> {
    /// Proved: `f(x) <= upper` for every `x` in the domain (`+∞` when an enclosure failed).
    pub upper: f64,
    /// Attained: `f(argmax) >= lower` (proved by an enclosure of `f` at `argmax`).
    pub lower: f64,
    /// A point of the domain where `f >= lower`.
    pub argmax: [f64; N],
    /// The queued box whose enclosure gives `upper`: where a larger value could still hide.
    pub frontier: [Interval; N],
    /// Boxes examined.
    pub boxes: usize,
    /// Whether the tolerance was met (else the box budget ran out; both bounds stay valid).
    pub converged: bool,
}

impl<const N: usize> Maximum<N> {
    /// `upper / lower`: how far the bracket is from the truth (see [`bracket_ratio`]).
    pub fn ratio(&self) -> f64 {
        bracket_ratio(self.upper, self.lower)
    }
}

/// The quality of a bracket `[lower, upper]` of a non-negative maximum: `upper / lower`, `+∞`
/// without a positive lower bound.
pub fn bracket_ratio(upper: f64, lower: f64) -> f64 {
    if lower > 0.0 {
        upper / lower
    } else {
        f64::INFINITY
    }
}

/// An item of a best-first search, ordered by its key alone (`f64::total_cmp`: `+∞` above every
/// number), so that a `BinaryHeap<Ranked<_>>` pops the largest key first. [`maximize`] queues its
/// boxes by the upper end of `f` over them; robot crates use it for their own searches.
#[derive(Clone, Debug)]
pub struct Ranked<B> {
    /// The priority.
    pub key: f64,
    /// What is queued.
    pub item: B,
}

impl<B> PartialEq for Ranked<B> {
    fn eq(&self, other: &Self) -> bool {
        self.key.total_cmp(&other.key) == Ordering::Equal
    }
}
impl<B> Eq for Ranked<B> {}
impl<B> PartialOrd for Ranked<B> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl<B> Ord for Ranked<B> {
    fn cmp(&self, other: &Self) -> Ordering {
        self.key.total_cmp(&other.key)
    }
}

/// The upper end of an enclosure, `+∞` when it failed (NaN or empty): a failure never drops a box.
fn upper_end(v: Interval) -> f64 {
    let s = v.sup();
    if s.is_nan() || v.is_empty() {
        f64::INFINITY
    } else {
        s
    }
}

/// Maximises `f` over `domain` (see the module documentation). `domain` must be bounded and
/// non-empty; otherwise the result is the trivial bracket `[-∞, +∞]` at its midpoint.
///
/// ```
/// use calib_core::{maximize, Interval, MaximumSettings, Objective};
///
/// /// `x (1 - x)`, largest at `x = 1/2`.
/// struct Parabola;
/// impl Objective<1> for Parabola {
///     fn enclose(&self, x: &[Interval; 1]) -> Interval {
///         x[0] * (Interval::point(1.0) - x[0])
///     }
///     fn gradient(&self, x: &[Interval; 1]) -> Option<[Interval; 1]> {
///         Some([Interval::point(1.0) - Interval::point(2.0) * x[0]])
///     }
/// }
/// let m = maximize(&Parabola, &[Interval::new(0.0, 1.0)], &MaximumSettings::default());
/// assert!(m.converged && m.lower <= 0.25 && 0.25 <= m.upper && m.upper <= 0.25 * 1.01);
/// ```
pub fn maximize<O: Objective<N>, const N: usize>(
    f: &O,
    domain: &[Interval; N],
    settings: &MaximumSettings,
) -> Maximum<N> {
    let mid = |b: &[Interval; N]| b.map(|v| v.mid());
    let mut out = Maximum {
        upper: f64::INFINITY,
        lower: f64::NEG_INFINITY,
        argmax: mid(domain),
        frontier: *domain,
        boxes: 0,
        converged: false,
    };
    if domain.iter().any(|v| v.is_empty() || !v.is_bounded()) {
        return out;
    }
    let probe = |p: [f64; N], out: &mut Maximum<N>| {
        let v = f.at(&p);
        // Only a real enclosure proves a value: an empty or NaN one proves nothing.
        if !v.is_empty() && v.inf() > out.lower {
            out.lower = v.inf();
            out.argmax = p;
        }
        // The local search starts only from points that could still beat the lower bound (it
        // may be costly; the branch and bound brings better starting points).
        if v.is_empty() || v.sup().is_nan() || v.sup() > out.lower {
            if let Some((q, v)) = f.improve(&p) {
                if v > out.lower {
                    out.lower = v;
                    out.argmax = q;
                }
            }
        }
    };
    probe(mid(domain), &mut out);
    let mut queue = BinaryHeap::new();
    queue.push(Ranked {
        key: upper_end(enclosure(f, domain, f64::NEG_INFINITY)),
        item: *domain,
    });
    out.boxes = 1;
    // Boxes too small to split keep their bound for good: the largest such bound, and its box.
    let mut settled: Option<Ranked<[Interval; N]>> = None;
    let reference = f.split_reference(domain);
    loop {
        let top = match (queue.peek(), &settled) {
            (Some(q), Some(s)) if s.key > q.key => s,
            (Some(q), _) => q,
            (None, Some(s)) => s,
            (None, None) => {
                // Every box was below the lower bound, which is then the maximum (attained).
                out.upper = out.lower;
                out.converged = true;
                return out;
            }
        };
        out.upper = top.key.max(out.lower);
        out.frontier = top.item;
        let gap = out.upper - out.lower;
        if gap <= settings.abs_tol || gap <= settings.rel_tol * out.lower.abs() {
            out.converged = true;
            return out;
        }
        if out.boxes >= settings.max_boxes {
            return out;
        }
        let Some(Ranked { key: sup, item: b }) = queue.pop() else {
            // Only settled boxes are left and the gap is still open: nothing more to do.
            return out;
        };
        let Some((l, r)) = split_by_weights(f, &b).or_else(|| split_widest(&b, &reference)) else {
            if settled.as_ref().is_none_or(|s| sup > s.key) {
                settled = Some(Ranked { key: sup, item: b });
            }
            continue;
        };
        // A half bounded within the tolerance of the lower bound cannot keep the search open:
        // its enclosure need not be tighter than that.
        let enough = out.lower + settings.rel_tol.max(0.0) * out.lower.abs();
        for half in [l, r] {
            let half = to_rising_faces(f, half);
            out.boxes += 1;
            let sup = upper_end(enclosure(f, &half, enough));
            if sup < out.lower {
                continue;
            }
            probe(mid(&half), &mut out);
            queue.push(Ranked {
                key: sup,
                item: half,
            });
        }
    }
}

/// Brackets `max f` over a finite list of thin boxes (a task's configurations, held-out rows,
/// each the enclosure of a point given in other units) instead of one box: per box, the upper
/// end of [`Objective::enclose_up_to`] (proved over the box; loose only below the lower bound
/// found so far) and [`Objective::attained`] at its midpoint. No point
/// is searched beyond the list ([`Objective::improve`] is not called). Two passes, each shared
/// among the threads with objectives from `objective` (objectives may keep per-thread state; a
/// thread may make more than one): every box's attained value, then every box's enclosure with
/// the largest of them as `enough` — so which boxes get a tight bound does not depend on the
/// threads' schedule. `frontier` is the box with the largest upper end, `argmax` the midpoint attaining
/// `lower`, `boxes` the number of boxes; `converged` when `upper <= (1 + rel_tol) lower` (or
/// within `abs_tol`). An empty list gives the trivial bracket `[-∞, +∞]`; an empty, unbounded or
/// NaN box, or an enclosure that fails, leaves `upper` at `+∞`.
///
/// ```
/// use calib_core::{maximize_over_list, Interval, MaximumSettings, Objective};
///
/// /// `x (1 - x)`.
/// struct Parabola;
/// impl Objective<1> for Parabola {
///     fn enclose(&self, x: &[Interval; 1]) -> Interval {
///         x[0] * (Interval::point(1.0) - x[0])
///     }
/// }
/// let list = [0.1, 0.4, 0.9].map(|v| [Interval::point(v)]);
/// let m = maximize_over_list(|| Parabola, &list, &MaximumSettings::default());
/// assert!(m.lower <= 0.24 && 0.24 <= m.upper && m.argmax == [0.4] && m.converged);
/// ```
pub fn maximize_over_list<O, const N: usize>(
    objective: impl Fn() -> O + Sync,
    boxes: &[[Interval; N]],
    settings: &MaximumSettings,
) -> Maximum<N>
where
    O: Objective<N>,
{
    use rayon::prelude::*;
    let first = boxes.first().copied().unwrap_or([Interval::ZERO; N]);
    let mut out = Maximum {
        upper: f64::INFINITY,
        lower: f64::NEG_INFINITY,
        argmax: first.map(|v| v.mid()),
        frontier: first,
        boxes: boxes.len(),
        converged: false,
    };
    if boxes.is_empty() {
        return out;
    }
    let usable = |b: &[Interval; N]| b.iter().all(|v| !v.is_empty() && v.is_bounded());
    // Per box: the value attained at its midpoint (-∞ for none), then its upper bound (+∞ for
    // a failed enclosure).
    let lowers: Vec<f64> = boxes
        .par_iter()
        .map_init(&objective, |f, b| {
            let v = if usable(b) {
                f.attained(&b.map(|v| v.mid()))
            } else {
                f64::NEG_INFINITY
            };
            if v.is_nan() {
                f64::NEG_INFINITY
            } else {
                v
            }
        })
        .collect();
    let enough = lowers.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let uppers: Vec<f64> = boxes
        .par_iter()
        .map_init(&objective, |f, b| {
            if !usable(b) {
                return f64::INFINITY;
            }
            let v = f.enclose_up_to(b, enough);
            if v.is_empty() || v.sup().is_nan() {
                f64::INFINITY
            } else {
                v.sup()
            }
        })
        .collect();
    out.upper = f64::NEG_INFINITY;
    for ((b, &upper), &lower) in boxes.iter().zip(&uppers).zip(&lowers) {
        if upper > out.upper {
            out.upper = upper;
            out.frontier = *b;
        }
        if lower > out.lower {
            out.lower = lower;
            out.argmax = b.map(|v| v.mid());
        }
    }
    out.upper = out.upper.max(out.lower);
    let gap = out.upper - out.lower;
    // Without an attained value nothing has converged (an infinite gap is not within any share
    // of an infinite lower bound).
    out.converged = out.lower.is_finite()
        && (gap <= settings.abs_tol || gap <= settings.rel_tol * out.lower.abs());
    out
}

/// `b` split at the coordinate of the largest `width × weight` ([`Objective::split_weights`]);
/// `None` without weights or when that coordinate cannot be split.
fn split_by_weights<O: Objective<N>, const N: usize>(
    f: &O,
    b: &[Interval; N],
) -> Option<([Interval; N], [Interval; N])> {
    let w = f.split_weights(b)?;
    let largest = w
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    if largest <= 0.0 {
        return None;
    }
    // Every coordinate keeps a little weight: an estimate of 0 must not freeze a side for good.
    let reference: [Interval; N] = core::array::from_fn(|j| {
        let weight = if w[j].is_finite() { w[j] } else { largest };
        Interval::new(0.0, 1.0 / weight.max(1e-3 * largest))
    });
    split_widest(b, &reference)
}

/// `f` over `b`: [`Objective::enclose_up_to`] with `enough`, intersected with the mean-value form
/// `f(m) + Σ_j g_j (b_j - m_j)` (`m` the midpoint, `g` the gradient's enclosure over `b`) when
/// the gradient is available. Both contain every value of `f` on `b`, so their intersection does;
/// the mean-value form shrinks quadratically with the box, the natural one only linearly.
fn enclosure<O: Objective<N>, const N: usize>(f: &O, b: &[Interval; N], enough: f64) -> Interval {
    let natural = f.enclose_up_to(b, enough);
    let Some(g) = f.gradient(b) else {
        return natural;
    };
    let m = b.map(|v| v.mid());
    let mut mean_value = f.at(&m);
    for j in 0..N {
        mean_value += g[j] * (b[j] - Interval::point(m[j]));
    }
    if natural.is_empty() || mean_value.is_empty() || mean_value.sup().is_nan() {
        return natural;
    }
    natural.intersection(mean_value)
}

/// `b` moved to its faces where `f` grows, in every coordinate where the gradient's enclosure
/// excludes 0 (the maximum over `b` lies on those faces).
fn to_rising_faces<O: Objective<N>, const N: usize>(f: &O, mut b: [Interval; N]) -> [Interval; N] {
    if let Some(g) = f.gradient(&b) {
        for j in 0..N {
            if g[j].inf() > 0.0 {
                b[j] = Interval::point(b[j].sup());
            } else if g[j].sup() < 0.0 {
                b[j] = Interval::point(b[j].inf());
            }
        }
    }
    b
}
