//! The platform's position and orientation errors: upper bounds proved over the workspace.
//!
//! At a commanded pose `X` the controller sends `L_i(X; θ̂_i)`, the actuators add `e_i` (`|e_i| <=
//! ε`), and the robot, of true geometry `θ*`, reaches the pose connected to `X` along the
//! homotopy `L_i(X + δ; θ*_i) = (1 - t) L_i(X; θ*_i) + t (L_i(X; θ̂_i) + e_i)`, `t` from 0 to 1
//! (see [`super::pose_error`]; `X + δ = (p + d, R(w) R(q))`). Along it every leg's change
//!
//! `G_i(X, δ, θ*) = L_i(X + δ; θ*) - L_i(X; θ*) = t (L_i(X; θ̂) + e_i - L_i(X; θ*))`
//!
//! lies in `[-U_i, U_i]` with `U_i = max |ΔL_i| + ε` over the box of poses — the leg-length error
//! the certificate already bounds. So the path stays in the set `F` of moves `δ` with
//! `|G_i| <= U_i` for some `X` of the box and `θ*` of `Θ`.
//!
//! **The region argument.** Take a region `D` of moves, a neighbourhood of `δ = 0`. If no move on
//! its boundary lies in `F` (for any pose of the box and any geometry), the connected path, which
//! starts at `δ = 0` inside `D`, never leaves it: the reached pose's move is in `D ∩ F`, and
//! `max |d|`, `max 2 atan |w|` over an enclosure of `D ∩ F` bound the position and orientation
//! errors — for every solution connected to `X`, singular or not.
//!
//! **How `D` is closed and `D ∩ F` bounded.** In the coordinates `y = J δ` (`J` the legs'
//! Jacobian at the box's centre and nominal geometry, `δ = M y` with `M ≈ J⁻¹`, proved
//! nonsingular by `‖I - J M‖ < 1`), `F` is close to the box `|y_i| <= U_i`; `D` is the
//! parallelepiped `M · [-R, R]`, `R_i = f U_i` with `f` from 3 down to 1.05 while `D` closes. Each
//! of its 12 faces is paved until every piece is excluded: some leg's `G_i` over the piece (its
//! natural enclosure intersected with the mean-value form `G_i(δ(y_c)) + (∇_δ G_i · M)(y - y_c)`)
//! misses `[-U_i, U_i]`. Inside, `|y_i| <= U_i + |G_i - y_i|` (mean value from `δ = 0`, where
//! `G = 0`) encloses `D ∩ F` in a box, and `|d|`, `|w|` — norms of linear maps of `y`, convex —
//! are largest at one of its 64 vertices. `G_i` is written as `(2 v·u + |u|²) / (|v + u| + |v|)`
//! (`v` the leg vector, `u` the attachment point's displacement): `l` cancels exactly and the
//! enclosure stays relative to the small move.
//!
//! Over the workspace, a branch and bound splits the boxes of poses with the largest
//! bound; a box whose region cannot be closed (the move not enclosed: near a singular pose, or
//! the geometry's box too wide for the legs' directions) is split too, and when it is already
//! small the bound is not proved and the box is named instead.

use super::enclosure::{AccuracyProblem, PoseBox};
use calib_core::bisection::split_widest;
use calib_core::maximum::Ranked;
use calib_core::{interval_model, Interval, Model, Scalar};
use nalgebra::Matrix6;
use rayon::prelude::*;
use std::cmp::Ordering;
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

/// The half-widths of the regions `D = M · [-R, R]` tried, in units of `U`: the widest first
/// (its faces lie farthest from `F`), then narrower ones while they close — each closed region
/// is a proof, and the narrowest gives the tightest bound.
const REGIONS: [f64; 6] = [3.0, 2.0, 1.5, 1.25, 1.1, 1.05];
/// A box of a face of `D` narrower than this fraction of `D` (in every coordinate) that cannot be
/// excluded ends the attempt: the region cannot be closed.
const FINEST_FACE: f64 = 1.0 / 64.0;
/// Rounds of the enclosure of `D ∩ F` by the box `|y_i| <= U_i + r_i`.
const SHRINK_ROUNDS: usize = 3;

/// When to stop [`pose_error_bounds`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PoseBoundSettings {
    /// Stop once each bound is within `1 + rel_tol` of its target (default 0.04).
    pub rel_tol: f64,
    /// Boxes of poses examined at most (default 1500).
    pub max_pose_boxes: usize,
    /// Boxes of `D`'s faces examined at most per box of poses and region (default 300).
    pub max_face_boxes: usize,
    /// A box of poses whose region cannot be closed and which is narrower than this fraction of
    /// the workspace in every coordinate ends the search unproved (default 1/16).
    pub finest_pose: f64,
    /// Stop after about this many seconds (default 30: a safety net behind `max_pose_boxes`,
    /// which keeps results reproducible; the bounds stay valid, or the box of
    /// poses not yet bounded is named).
    pub max_seconds: f64,
}

impl Default for PoseBoundSettings {
    fn default() -> Self {
        PoseBoundSettings {
            rel_tol: 0.04,
            max_pose_boxes: 1500,
            max_face_boxes: 300,
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
    /// Boxes of poses examined.
    pub pose_boxes: usize,
    /// Boxes of the regions' faces examined, over all boxes of poses.
    pub face_boxes: usize,
    /// Whether both bounds met their targets (else a budget ran out; the bounds stay valid).
    pub converged: bool,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// The moves of one box of poses in the coordinates `y = J δ` (see the module documentation).
struct Chart {
    /// Per leg, `m = (X, a, b)` over the box of poses and the leg's geometry box.
    inputs: Vec<[Interval; 12]>,
    /// `M ≈ J⁻¹`, entries as thin intervals.
    m: [[Interval; 6]; 6],
    /// `U_i`, rounded up.
    bound: [f64; 6],
}

impl Chart {
    /// The chart of the box of poses `x`, `None` when `J` is not proved invertible or a leg's
    /// bound is not finite.
    fn new(problem: &AccuracyProblem, x: &PoseBox, eps: f64) -> Option<Chart> {
        if problem.legs() != 6 {
            return None;
        }
        let xc = x.map(|v| v.mid());
        let mut j = Matrix6::zeros();
        for i in 0..6 {
            let n = problem.nominal(i);
            let m: [f64; 12] = core::array::from_fn(|k| if k < 6 { xc[k] } else { n[k - 6] });
            let row = ReachedChange.jacobian_x(&[0.0; 6], &m);
            for k in 0..6 {
                j[(i, k)] = row[k];
            }
        }
        let inv = j.try_inverse()?;
        let m: [[Interval; 6]; 6] =
            core::array::from_fn(|r| core::array::from_fn(|c| Interval::point(inv[(r, c)])));
        // ‖I - J M‖∞ < 1 proves J M, hence M, nonsingular: δ = M y maps D onto a neighbourhood
        // of δ = 0 and D's boundary onto its boundary.
        let residual_norm = (0..6)
            .map(|r| {
                (0..6)
                    .map(|c| {
                        let p = (0..6).fold(Interval::point(0.0), |s, k| {
                            s + Interval::point(j[(r, k)]) * m[k][c]
                        });
                        (Interval::point(if r == c { 1.0 } else { 0.0 }) - p).mag()
                    })
                    .fold(Interval::point(0.0), |s, v| s + Interval::point(v))
                    .sup()
            })
            .fold(0.0, f64::max);
        // NaN fails too.
        if residual_norm.partial_cmp(&1.0) != Some(Ordering::Less) {
            return None;
        }
        let eps = Interval::point(eps.max(0.0).next_up());
        let mut bound = [0.0; 6];
        for (i, b) in bound.iter_mut().enumerate() {
            let u = (Interval::point(problem.leg_bounds(i, x).sup()) + eps).sup();
            if !u.is_finite() {
                return None;
            }
            // A larger U is still a bound; a positive one keeps 0 inside D.
            *b = u.max(1e-12);
        }
        let inputs = (0..6)
            .map(|i| {
                let t = problem.theta(i);
                core::array::from_fn(|k| if k < 6 { x[k] } else { t[k - 6] })
            })
            .collect();
        Some(Chart { inputs, m, bound })
    }

    /// An enclosure of `δ = M y` over the box `y`.
    fn delta(&self, y: &[Interval; 6]) -> [Interval; 6] {
        core::array::from_fn(|r| (0..6).fold(Interval::point(0.0), |s, c| s + self.m[r][c] * y[c]))
    }

    /// Whether no move of the box `y` lies in `F` (a proof: some leg's change misses its bound
    /// for every pose of the box and every geometry).
    /// Leg `first` is tried first (on a face of `D`, the face's own leg usually settles it).
    fn excluded(&self, y: &[Interval; 6], first: usize) -> bool {
        let d = self.delta(y);
        let yc = y.map(|v| Interval::point(v.mid()));
        let dc = self.delta(&yc);
        (0..6).map(|k| (first + k) % 6).any(|i| {
            let inputs = &self.inputs[i];
            let natural = ReachedChange.residual_interval(&d, inputs);
            let grad = ReachedChange.jacobian_x_interval(&d, inputs);
            let mut mv = ReachedChange.residual_interval(&dc, inputs);
            for c in 0..6 {
                let slope = (0..6).fold(Interval::point(0.0), |s, k| s + grad[k] * self.m[k][c]);
                mv += slope * (y[c] - yc[c]);
            }
            let both = natural.intersection(mv);
            let g = if both.is_empty() { natural } else { both };
            let u = self.bound[i];
            !g.is_empty() && (g.inf() > u || g.sup() < -u)
        })
    }

    /// Upper bounds of the position (cm) and orientation (degrees) errors over the box `y`.
    fn errors(&self, y: &[Interval; 6]) -> [f64; 2] {
        let d = self.delta(y);
        let norm = |v: &[Interval]| (v[0].sqr() + v[1].sqr() + v[2].sqr()).sqrt().sup();
        let w = norm(&d[3..]);
        // atan above its libm value by far more than libm's error (a few ulps).
        let angle =
            Interval::point(2.0 * w.atan() * (1.0 + 1e-12)) * Interval::point(180.0) / Interval::PI;
        // A failed enclosure (NaN) bounds nothing.
        [norm(&d[..3]), angle.sup()].map(|v| if v.is_nan() { f64::INFINITY } else { v })
    }

    /// Whether no move on the boundary of `D = M · [-r, r]` lies in `F`: each of the 12 faces
    /// is paved until every piece is [`Chart::excluded`]. `None` when a piece narrower than
    /// [`FINEST_FACE`] of `D` (or the budget) is reached first; else the pieces examined.
    fn closes(&self, r: &[f64; 6], budget: usize) -> Option<usize> {
        let region: [Interval; 6] = r.map(|h| Interval::new(-h, h));
        let mut examined = 0;
        for i in 0..6 {
            for end in [-r[i], r[i]] {
                let mut face = region;
                face[i] = Interval::point(end);
                let mut stack = vec![face];
                while let Some(b) = stack.pop() {
                    examined += 1;
                    if self.excluded(&b, i) {
                        continue;
                    }
                    let fine = (0..6).all(|c| b[c].wid() <= FINEST_FACE * region[c].wid());
                    if fine || examined >= budget {
                        return None;
                    }
                    let (l, h) = split_widest(&b, &region)?;
                    stack.extend([l, h]);
                }
            }
        }
        Some(examined)
    }

    /// Half-widths `h` with `D ∩ F ⊆ [-h, h]` for `D = M · [-r, r]`: on `D`,
    /// `G_i(M y) - y_i = Σ_c (S_ic - [i = c]) y_c` (`S = ∇_δ G · M` over `D`, mean value from
    /// `δ = 0` where `G = 0`), so a move of `F` has `|y_i| <= U_i + |G_i - y_i|`; repeated on the
    /// smaller box, which still holds `D ∩ F`.
    fn enclosing_box(&self, r: &[f64; 6]) -> [f64; 6] {
        let mut h = *r;
        for _ in 0..SHRINK_ROUNDS {
            let y: [Interval; 6] = h.map(|v| Interval::new(-v, v));
            let d = self.delta(&y);
            let next: [f64; 6] = core::array::from_fn(|i| {
                let grad = ReachedChange.jacobian_x_interval(&d, &self.inputs[i]);
                let rest = (0..6).fold(Interval::point(0.0), |s, c| {
                    let slope =
                        (0..6).fold(Interval::point(0.0), |s, k| s + grad[k] * self.m[k][c]);
                    let off = if c == i { slope - 1.0 } else { slope };
                    s + off * y[c]
                });
                let v = (Interval::point(self.bound[i]) + Interval::point(rest.mag())).sup();
                if v.is_nan() {
                    h[i]
                } else {
                    v.min(h[i])
                }
            });
            h = next;
        }
        h
    }

    /// Upper bounds of both errors over the box `[-h, h]` of `y`: `|d|` and `|w|` are norms of
    /// linear maps of `y`, convex, so their largest values are at one of the 64 vertices.
    fn vertex_bound(&self, h: &[f64; 6]) -> [f64; 2] {
        (0..64u32).fold([0.0f64; 2], |acc, pattern| {
            let v: [Interval; 6] = core::array::from_fn(|c| {
                Interval::point(if pattern & (1 << c) != 0 { h[c] } else { -h[c] })
            });
            let e = self.errors(&v);
            [acc[0].max(e[0]), acc[1].max(e[1])]
        })
    }
}

/// `max_k value_k / target_k` (a target of `+∞` asks nothing).
fn key(value: [f64; 2], target: [f64; 2]) -> f64 {
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

/// The bounds over one box of poses (and the boxes of moves examined).
fn bound_pose_box(
    problem: &AccuracyProblem,
    x: &PoseBox,
    eps: f64,
    settings: &PoseBoundSettings,
) -> (BoxBound, usize) {
    if !problem.may_be_feasible(x) {
        return (BoxBound::Empty, 0);
    }
    let Some(chart) = Chart::new(problem, x, eps) else {
        return (BoxBound::Unproved, 0);
    };
    let mut examined = 0;
    let mut closed = None;
    for factor in REGIONS {
        let r = chart.bound.map(|u| factor * u);
        match chart.closes(&r, settings.max_face_boxes) {
            Some(n) => {
                examined += n;
                closed = Some(r);
            }
            None => {
                examined += settings.max_face_boxes;
                break;
            }
        }
    }
    match closed {
        Some(r) => {
            let h = chart.enclosing_box(&r);
            (BoxBound::Bound(chart.vertex_bound(&h)), examined)
        }
        None => (BoxBound::Unproved, examined),
    }
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
    let target = lower.map(|l| {
        if l > 0.0 {
            l * (1.0 + settings.rel_tol)
        } else {
            f64::INFINITY
        }
    });
    let domain = problem.domain();
    let evaluate = |x: [Interval; 6]| {
        let (b, n) = bound_pose_box(problem, &x, eps, settings);
        (x, b, n)
    };
    let mut heap: BinaryHeap<Ranked<([Interval; 6], BoxBound)>> = BinaryHeap::new();
    let (mut pose_boxes, mut face_boxes) = (0, 0);
    let enqueue = |heap: &mut BinaryHeap<_>, x: [Interval; 6], b: BoxBound| match b {
        BoxBound::Empty => {}
        BoxBound::Bound(v) => heap.push(Ranked {
            key: key(v, target),
            item: (x, b),
        }),
        BoxBound::Unproved => heap.push(Ranked {
            key: f64::INFINITY,
            item: (x, b),
        }),
    };
    let (x, b, n) = evaluate(domain);
    enqueue(&mut heap, x, b);
    pose_boxes += 1;
    face_boxes += n;
    let batch = 2 * rayon::current_num_threads().max(1);
    let mut unproved_at = None;
    while pose_boxes < settings.max_pose_boxes
        && start.elapsed().as_secs_f64() < settings.max_seconds
    {
        let mut children = Vec::new();
        while children.len() < batch {
            let Some(top) = heap.pop() else { break };
            if top.key <= 1.0 {
                heap.push(top);
                break;
            }
            let x = top.item.0;
            let fine = (0..6).all(|c| x[c].wid() <= settings.finest_pose * domain[c].wid());
            match split_widest(&x, &domain) {
                Some((l, r)) if !(fine && top.item.1 == BoxBound::Unproved) => {
                    children.extend([l, r]);
                }
                _ => {
                    if top.item.1 == BoxBound::Unproved {
                        unproved_at = Some(x);
                    }
                    heap.push(top);
                    break;
                }
            }
        }
        // Once a box is named unproved no bound is claimed, so the boxes popped in this batch
        // need not be evaluated.
        if children.is_empty() || unproved_at.is_some() {
            break;
        }
        let results: Vec<_> = children.into_par_iter().map(evaluate).collect();
        for (x, b, n) in results {
            enqueue(&mut heap, x, b);
            pose_boxes += 1;
            face_boxes += n;
        }
    }
    if unproved_at.is_none() {
        unproved_at = heap
            .iter()
            .find(|q| q.item.1 == BoxBound::Unproved)
            .map(|q| q.item.0);
    }
    let converged = unproved_at.is_none() && heap.peek().is_none_or(|q| q.key <= 1.0);
    let mut worst = [0.0f64; 2];
    for q in &heap {
        if let BoxBound::Bound(v) = q.item.1 {
            worst = [worst[0].max(v[0]), worst[1].max(v[1])];
        }
    }
    let proved = unproved_at.is_none();
    PoseErrorBounds {
        position: proved.then_some(worst[0]),
        orientation_deg: proved.then_some(worst[1]),
        unproved_at,
        pose_boxes,
        face_boxes,
        converged,
        seconds: start.elapsed().as_secs_f64(),
    }
}
