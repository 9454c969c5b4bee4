//! The platform's position and orientation errors: upper bounds proved over the workspace.
//!
//! At a commanded pose `X` the controller sends `L_i(X; θ̂_i)`, the actuators add `e_i` (`|e_i| <=
//! ε`), and the robot, of true geometry `θ*`, reaches the pose connected to `X` along the
//! homotopy `L_i(X + δ; θ*_i) = (1 - t) L_i(X; θ*_i) + t (L_i(X; θ̂_i) + e_i)`, `t` from 0 to 1
//! (see [`super::pose_error`]; `X + δ = (p + d, R(w) R(q))`). Along it every leg's change
//!
//! `G_i(X, δ, θ*) = L_i(X + δ; θ*) - L_i(X; θ*) = t (L_i(X; θ̂) + e_i - L_i(X; θ*))`
//!
//! lies in `[-U⁻_i, U⁺_i]` with `U⁻_i = max ΔL_i + ε`, `U⁺_i = max -ΔL_i + ε` over the box of poses —
//! the leg-length error the certificate already bounds, on each side of zero. So the path stays in
//! the set `F` of moves `δ` with `-U⁻_i <= G_i <= U⁺_i` for some `X` of the box and `θ*` of `Θ`.
//!
//! **The region argument.** Take a region `D` of moves, a neighbourhood of `δ = 0`. If no move on
//! its boundary lies in `F` (for any pose of the box and any geometry), the connected path, which
//! starts at `δ = 0` inside `D`, never leaves it: the reached pose's move is in `D ∩ F`, and
//! `max |d|`, `max 2 atan |w|` over an enclosure of `D ∩ F` bound the position and orientation
//! errors — for every solution connected to `X`, singular or not.
//!
//! **Per box of poses, in one step.** [`super::pose_chart`] closes such a region in the chart
//! that follows the pose, `δ = M(X) y` with `M(X)` the inverse of the legs' Jacobian at each
//! pose, wherever that Jacobian is proved nonsingular across the box: its remainder is first
//! order in the move and the geometry's spread, the chart's enclosure second order in the box's
//! width. Each box's halves start from its legs' bounds `U`, and compute their own only where
//! those do not already meet the target.
//!
//! **Over the workspace**, a best-first branch and bound splits the boxes of poses with the
//! largest bound relative to the errors attained; a box whose region cannot be closed (the move
//! not enclosed: near a singular pose, or errors so large that the legs' Jacobian changes across
//! them) is split too, and when it is already small the bound is not proved and the box is
//! named instead.
//!
//! (A chart fixed per box of poses, with its faces paved and the leg changes inside split by
//! Krawczyk steps, and a paving of the moves by second-order Taylor models, once backed this
//! chart up. Measured over certified sets they proved nothing it does not, and were removed;
//! they closed only where a geometry box of ± 0.1 cm met a workspace of ± 0.05 cm:
//! `benches/README.md`.)

use super::enclosure::{AccuracyProblem, PoseBox};
use super::pose_chart::PoseChart;
use calib_core::split_widest;
use calib_core::Ranked;
use calib_core::{interval_model, Interval, Scalar};
use rayon::prelude::*;
use std::collections::BinaryHeap;

/// The change of a leg's length when the platform moves from `X = (p, q)` by `δ = (d, w)` to
/// `(p + d, R(w) R(q))`: `|v + u| - |v|` with `v = p + R(q) b - a` and
/// `u = d + 2 (w × c + w × (w × c)) / (1 + |w|²)`, `c = R(q) b`, written
/// `(2 v·u + |u|²) / (|v + u| + |v|)` (paper eq. 3; `l` cancels). `x = δ`, `m = (p, q, a, b)`.
#[interval_model]
pub fn reached_change<S: Scalar>(x: &[S; 6], m: &[S; 12]) -> S {
    let [d1, d2, d3, w1, w2, w3] = *x;
    let [px, py, pz, q1, q2, q3, ax, ay, az, bx, by, bz] = *m;
    let (s1, s2, s3) = (q1.sqr(), q2.sqr(), q3.sqr());
    let dq = 1.0 + s1 + s2 + s3;
    let c1 =
        ((1.0 + s1 - s2 - s3) * bx + 2.0 * (q1 * q2 - q3) * by + 2.0 * (q1 * q3 + q2) * bz) / dq;
    let c2 =
        (2.0 * (q1 * q2 + q3) * bx + (1.0 - s1 + s2 - s3) * by + 2.0 * (q2 * q3 - q1) * bz) / dq;
    let c3 =
        (2.0 * (q1 * q3 - q2) * bx + 2.0 * (q2 * q3 + q1) * by + (1.0 - s1 - s2 + s3) * bz) / dq;
    let (k1, k2, k3) = (w2 * c3 - w3 * c2, w3 * c1 - w1 * c3, w1 * c2 - w2 * c1);
    let (h1, h2, h3) = (w2 * k3 - w3 * k2, w3 * k1 - w1 * k3, w1 * k2 - w2 * k1);
    let dw = 1.0 + w1.sqr() + w2.sqr() + w3.sqr();
    let u1 = d1 + 2.0 * (k1 + h1) / dw;
    let u2 = d2 + 2.0 * (k2 + h2) / dw;
    let u3 = d3 + 2.0 * (k3 + h3) / dw;
    let (v1, v2, v3) = (px + c1 - ax, py + c2 - ay, pz + c3 - az);
    let num = 2.0 * (v1 * u1 + v2 * u2 + v3 * u3) + u1.sqr() + u2.sqr() + u3.sqr();
    let den = ((v1 + u1).sqr() + (v2 + u2).sqr() + (v3 + u3).sqr()).sqrt()
        + (v1.sqr() + v2.sqr() + v3.sqr()).sqrt();
    num / den
}

/// When to stop [`pose_error_bounds`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PoseBoundSettings {
    /// Stop once each bound is within `1 + rel_tol` of its target (default 0.04).
    pub rel_tol: f64,
    /// Boxes of poses examined at most (default 40 000).
    pub max_pose_boxes: usize,
    /// A box of poses whose region cannot be closed and which is narrower than this fraction of
    /// the workspace in every coordinate ends the search unproved (default 1/16).
    pub finest_pose: f64,
    /// Stop after about this many seconds (default 30: a safety net behind `max_pose_boxes`,
    /// which keeps results reproducible; the bounds stay valid, or the box of poses not yet
    /// bounded is named).
    pub max_seconds: f64,
}

impl Default for PoseBoundSettings {
    fn default() -> Self {
        PoseBoundSettings {
            rel_tol: 0.04,
            max_pose_boxes: 40_000,
            finest_pose: 1.0 / 16.0,
            max_seconds: 30.0,
        }
    }
}

/// Upper bounds of the platform's pose errors over the workspace.
#[derive(Clone, Debug, PartialEq)]
pub struct PoseErrorBounds {
    /// Proved: the position error `|p' - p|` (cm) never exceeds this (`None`: not proved).
    pub position: Option<f64>,
    /// Proved: the orientation error (degrees) never exceeds this (`None`: not proved).
    pub orientation_deg: Option<f64>,
    /// When not proved: a box of poses where the reached pose could not be enclosed.
    pub unproved_at: Option<PoseBox>,
    /// Whether `unproved_at` is a box of the finest size ([`PoseBoundSettings::finest_pose`])
    /// whose reached pose could not be enclosed, so that a larger budget would not prove the
    /// bounds (else the budget ended first).
    pub unprovable: bool,
    /// The share of the workspace's box of poses (by volume, in the position and the
    /// Rodrigues vector) settled: in boxes of poses whose errors were bounded or that hold no
    /// pose of the workspace. 1 when the bounds are proved; below it, how far the search got.
    pub settled_share: f64,
    /// Boxes of poses examined.
    pub pose_boxes: usize,
    /// Whether both bounds met their targets (else a budget ran out; the bounds stay valid).
    pub converged: bool,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// Per leg, `[U⁻_i, U⁺_i]`: along the path, `G_i = t (L_i(X; θ̂) + e_i - L_i(X; θ*)) = t (e_i -
/// ΔL_i)` stays within `[-U⁻_i, U⁺_i]` with `U⁻_i = max ΔL_i + ε`, `U⁺_i = max -ΔL_i + ε` over
/// the box of poses (rounded up; see the module documentation). `None` when one is not finite.
pub fn leg_change_bounds(problem: &AccuracyProblem, x: &PoseBox, eps: f64) -> Option<ChangeBounds> {
    let eps = Interval::point(eps.max(0.0).next_up());
    let mut bound = [[0.0; 2]; 6];
    for (i, b) in bound.iter_mut().enumerate() {
        let [below, above] = problem.leg_error_reach(i, x)?;
        for (side, reach) in b.iter_mut().zip([above, below]) {
            let v = (Interval::point(reach) + eps).sup();
            if !v.is_finite() {
                return None;
            }
            // A larger bound is still one; a positive one keeps 0 inside D.
            *side = v.max(1e-12);
        }
    }
    Some(bound)
}

/// `|d|²` and `|w|²` of a move `δ = (d, w)` whose components are bounded in magnitude by `comp`.
pub fn squared_norms(comp: &[f64; 6]) -> [f64; 2] {
    let sq = |k: usize| comp[k] * comp[k] + comp[k + 1] * comp[k + 1] + comp[k + 2] * comp[k + 2];
    [sq(0), sq(3)]
}

/// The position error `|d|` (cm) and the orientation error `2 atan |w|` (degrees) from upper
/// bounds of `|d|²` and `|w|²`, rounded up: square roots by far more than their half-ulp error,
/// atan above its libm value by far more than libm's error (a few ulps). A failed enclosure (NaN
/// or infinite) bounds nothing.
pub fn errors_from_squares(squares: [f64; 2]) -> [f64; 2] {
    let [d, w] = squares.map(|v| v.sqrt() * (1.0 + 1e-12));
    let angle =
        Interval::point(2.0 * w.atan() * (1.0 + 1e-12)) * Interval::point(180.0) / Interval::PI;
    [d, angle.sup()].map(|v| if v.is_finite() { v } else { f64::INFINITY })
}

/// `max_k value_k / target_k` (a target of `+∞` asks nothing).
pub fn key(value: [f64; 2], target: [f64; 2]) -> f64 {
    (0..2)
        .map(|k| {
            if target[k].is_finite() {
                value[k] / target[k]
            } else {
                0.0
            }
        })
        .fold(0.0, f64::max)
}

/// The legs' change bounds over a box of poses: leg `i`'s change lies in `[-b[i][0], b[i][1]]`.
pub type ChangeBounds = [[f64; 2]; 6];

/// A box of poses' outcome, the legs' change bounds it used and whether they are its own (else
/// its parent's).
type Evaluated = (BoxBound, Option<ChangeBounds>, bool);

/// A box of poses to evaluate, its parent's legs' change bounds, and whether to compute its own.
type Task = (PoseBox, Option<ChangeBounds>, bool);

/// The outcome for one box of poses.
#[derive(Clone, Copy, Debug, PartialEq)]
enum BoxBound {
    /// No pose of the workspace in the box.
    Empty,
    /// Position and orientation bounds over the box.
    Bound([f64; 2]),
    /// The region could not be closed.
    Unproved,
}

/// The bounds over one box of poses, by the chart that follows the pose when its region
/// closes, and the legs' change bounds `U` used. `inherited` are a parent box's (upper bounds
/// over this box too); unless `own` asks for the box's own (a few linear programs per leg), they
/// are all that is used: most boxes of a search are never split, so their own are never needed.
fn bound_pose_box(
    problem: &AccuracyProblem,
    x: &PoseBox,
    eps: f64,
    inherited: Option<ChangeBounds>,
    own: bool,
) -> Evaluated {
    if !problem.may_be_feasible(x) {
        return (BoxBound::Empty, None, true);
    }
    // The poses of the workspace in the box lie in its part within the tilt.
    let Some(x) = problem.within_tilt(x) else {
        return (BoxBound::Empty, None, true);
    };
    let chart = |u: ChangeBounds| {
        PoseChart::with_leg_bounds(problem, &x, u)
            .and_then(|c| c.bound())
            .map_or(BoxBound::Unproved, BoxBound::Bound)
    };
    if let (Some(u), false) = (inherited, own) {
        return (chart(u), Some(u), false);
    }
    // The parent's bounds when the box's own cannot be had or close no region (a chart's
    // closing is not monotone in U: the others' moves weigh on a leg's narrower region).
    let fallback = |own: BoxBound| match (own, inherited) {
        (BoxBound::Unproved, Some(p)) => chart(p),
        (own, _) => own,
    };
    let Some(computed) = leg_change_bounds(problem, &x, eps) else {
        return (fallback(BoxBound::Unproved), inherited, true);
    };
    let u = match inherited {
        Some(p) => {
            core::array::from_fn(|i| [computed[i][0].min(p[i][0]), computed[i][1].min(p[i][1])])
        }
        None => computed,
    };
    (fallback(chart(u)), Some(u), true)
}

/// A box of poses in the queue of [`pose_error_bounds`] and its bounds.
struct Queued {
    x: PoseBox,
    bound: BoxBound,
    /// The legs' change bounds over the box, when computed (its halves inherit them).
    legs: Option<ChangeBounds>,
    /// Whether `legs` are the box's own (else its parent's: computed before it is split).
    own: bool,
}

/// The share of `domain`'s volume in `x` (a coordinate where `domain` is a point counts as
/// whole): what the search has settled, for the report.
pub fn share_of(x: &PoseBox, domain: &PoseBox) -> f64 {
    (0..6)
        .map(|k| {
            let w = domain[k].wid();
            if w > 0.0 {
                x[k].wid() / w
            } else {
                1.0
            }
        })
        .product()
}

/// Upper bounds of the platform's position and orientation errors over `problem`'s workspace,
/// with actuator errors within `± eps` (see the module documentation). `lower` are the errors
/// already attained (the instances' lower bounds, 0 when none): the search refines until each
/// bound is within `1 + rel_tol` of them or a budget runs out.
pub fn pose_error_bounds(
    problem: &AccuracyProblem,
    eps: f64,
    lower: [f64; 2],
    settings: &PoseBoundSettings,
) -> PoseErrorBounds {
    let start = std::time::Instant::now();
    let search = PoseSearch::new(problem, eps, lower, settings);
    let mut queue = PoseQueue::default();
    let evaluated = search.evaluate(&search.domain, None, true);
    queue.record(search.domain, evaluated, &search);
    let batch = 2 * rayon::current_num_threads().max(1);
    while queue.pose_boxes < settings.max_pose_boxes
        && start.elapsed().as_secs_f64() < settings.max_seconds
    {
        let tasks = queue.next_tasks(batch, &search);
        // Once a box is named unproved no bound is claimed, so the boxes popped in this batch
        // need not be evaluated.
        if tasks.is_empty() || queue.unproved_at.is_some() {
            break;
        }
        let reevaluated = tasks.iter().filter(|t| t.1.is_some() && t.2).count();
        let results: Vec<(PoseBox, Evaluated)> = tasks
            .into_par_iter()
            .map(|(x, legs, own)| (x, search.evaluate(&x, legs, own)))
            .collect();
        for (x, evaluated) in results {
            queue.record(x, evaluated, &search);
        }
        // A box evaluated again with its own legs' bounds is not a new box.
        queue.pose_boxes -= reevaluated;
    }
    queue.into_bounds(&search.domain, start)
}

/// What every evaluation of a box of poses in [`pose_error_bounds`] shares: the problem, the
/// actuator error, the targets the bounds are refined towards, the settings and the workspace's
/// box of poses.
struct PoseSearch<'a> {
    problem: &'a AccuracyProblem,
    eps: f64,
    /// `lower · (1 + rel_tol)` per error; `+∞` (nothing asked) where nothing is attained.
    target: [f64; 2],
    settings: &'a PoseBoundSettings,
    domain: PoseBox,
}

impl<'a> PoseSearch<'a> {
    /// The search of `problem` with actuator errors within `± eps`, towards `lower` (the errors
    /// attained) within `settings.rel_tol`.
    fn new(
        problem: &'a AccuracyProblem,
        eps: f64,
        lower: [f64; 2],
        settings: &'a PoseBoundSettings,
    ) -> Self {
        let target = lower.map(|l| {
            if l > 0.0 {
                l * (1.0 + settings.rel_tol)
            } else {
                f64::INFINITY
            }
        });
        PoseSearch {
            problem,
            eps,
            target,
            settings,
            domain: problem.domain(),
        }
    }

    /// The bounds over the box of poses `x` and the legs' change bounds used: the parent's
    /// `inherited`, or (`own`) the box's own.
    fn evaluate(&self, x: &PoseBox, inherited: Option<ChangeBounds>, own: bool) -> Evaluated {
        bound_pose_box(self.problem, x, self.eps, inherited, own)
    }
}

/// The boxes of poses of [`pose_error_bounds`] still to be split, largest key first, and what
/// the search has counted and found so far.
#[derive(Default)]
struct PoseQueue {
    heap: BinaryHeap<Ranked<Queued>>,
    /// Boxes of poses evaluated.
    pose_boxes: usize,
    /// The share of the workspace's volume proved to hold no pose.
    empty_share: f64,
    /// A box whose bounds could not be proved, once one is named.
    unproved_at: Option<PoseBox>,
    /// Whether that box is as fine as the search goes (no split would prove it).
    unprovable: bool,
}

impl PoseQueue {
    /// Counts an evaluated box and queues it (an unproved one first of all).
    fn record(&mut self, x: PoseBox, (bound, legs, own): Evaluated, search: &PoseSearch<'_>) {
        self.pose_boxes += 1;
        let key = match bound {
            BoxBound::Empty => {
                self.empty_share += share_of(&x, &search.domain);
                return;
            }
            BoxBound::Bound(v) => key(v, search.target),
            BoxBound::Unproved => f64::INFINITY,
        };
        self.heap.push(Ranked {
            key,
            item: Queued {
                x,
                bound,
                legs,
                own,
            },
        });
    }

    /// Up to `batch` boxes to evaluate: the halves of the boxes with the largest keys above 1
    /// (or a box itself, with its own legs' bounds, when its key came from its parent's). A box that cannot be split (or, unproved, is as fine as the search goes) stays in the
    /// queue and ends the batch; an unproved one is named.
    fn next_tasks(&mut self, batch: usize, search: &PoseSearch<'_>) -> Vec<Task> {
        let (domain, finest_pose) = (&search.domain, search.settings.finest_pose);
        let mut tasks = Vec::new();
        while tasks.len() < batch {
            let Some(top) = self.heap.pop() else { break };
            if top.key <= 1.0 {
                self.heap.push(top);
                break;
            }
            let q = &top.item;
            if !q.own {
                // Its parent's bounds gave this key: its own may already settle it.
                tasks.push((q.x, q.legs, true));
                continue;
            }
            let fine = (0..6).all(|c| q.x[c].wid() <= finest_pose * domain[c].wid());
            match split_widest(&q.x, domain) {
                Some((l, r)) if !(fine && q.bound == BoxBound::Unproved) => {
                    tasks.push((l, q.legs, false));
                    tasks.push((r, q.legs, false));
                }
                _ => {
                    if q.bound == BoxBound::Unproved {
                        self.unproved_at = Some(q.x);
                        self.unprovable = true;
                    }
                    self.heap.push(top);
                    break;
                }
            }
        }
        tasks
    }

    /// The bounds the search ends with: the largest left in the queue, claimed only when no box
    /// is unproved, and the share of the workspace `domain` settled.
    fn into_bounds(mut self, domain: &PoseBox, start: std::time::Instant) -> PoseErrorBounds {
        if self.unproved_at.is_none() {
            self.unproved_at = self
                .heap
                .iter()
                .find(|q| q.item.bound == BoxBound::Unproved)
                .map(|q| q.item.x);
        }
        let converged = self.unproved_at.is_none() && self.heap.peek().is_none_or(|q| q.key <= 1.0);
        let mut worst = [0.0f64; 2];
        for q in &self.heap {
            if let BoxBound::Bound(v) = q.item.bound {
                worst = [worst[0].max(v[0]), worst[1].max(v[1])];
            }
        }
        let proved = self.unproved_at.is_none();
        let bounded_share: f64 = self
            .heap
            .iter()
            .filter(|q| matches!(q.item.bound, BoxBound::Bound(_)))
            .map(|q| share_of(&q.item.x, domain))
            .sum();
        PoseErrorBounds {
            position: proved.then_some(worst[0]),
            orientation_deg: proved.then_some(worst[1]),
            unproved_at: self.unproved_at,
            unprovable: self.unprovable,
            settled_share: if proved {
                1.0
            } else {
                (bounded_share + self.empty_share).min(1.0)
            },
            pose_boxes: self.pose_boxes,
            converged,
            seconds: start.elapsed().as_secs_f64(),
        }
    }
}
