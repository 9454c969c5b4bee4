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
//! natural enclosure intersected with the mean-value form `G_i(δ(y_c)) + (∇_δ G_i · M)(y - y_c)`,
//! or for the face's own leg its affine form) misses `[-U_i, U_i]`. Inside, `|y_i| <= U_i +
//! |G_i - y_i|` (mean value from `δ = 0`, where `G = 0`, or the affine form, whichever is
//! smaller) encloses `D ∩ F` in a box, and `|d|`, `|w|` — norms of linear maps of `y`, convex —
//! are largest at one of its 64 vertices. The affine forms ([`calib_core::Affine`], noise symbols
//! for `y` and for the pose) keep `δ = M y` exact and `G_i`'s first-order dependence on the move
//! and the pose, so that only its second-order remainder is overestimated: where the legs'
//! Jacobian wraps the intervals, a face closes in far fewer pieces. `G_i` is written as `(2 v·u + |u|²) / (|v + u| + |v|)`
//! (`v` the leg vector, `u` the attachment point's displacement): `l` cancels exactly and the
//! enclosure stays relative to the small move.
//!
//! **Refined in the leg changes.** That box overstates the errors by the whole nonlinear
//! remainder `|G_i - y_i|` at once. In the leg changes `s = G(X, δ, θ*)` themselves `F` is
//! exactly the box `[-U, U]`, so a best-first branch and bound splits it into boxes `p` and
//! encloses the moves of `D ∩ F` reaching each: from `(p ± ρ) ∩ [-h, h]` (`ρ` the remainder
//! over the box above) by Krawczyk steps for every pose, geometry and `s ∈ p` at once — every
//! solution in a box stays in its Krawczyk image, no uniqueness needed. The pose enters
//! `G(X, M ỹ, θ*)` through a centred form whose part `C ∇_X G (X - X_c)` is mapped to the moves
//! as one matrix, `-(M C ∇_X G)(X - X_c)`: the reached move shifts with the pose far less than
//! each leg's change does, and the box of that shift (in `d` and `w`, added to the vertices'
//! values) keeps it so. Boxes near the worst corner are split until each is within its target
//! ([`PoseBoundSettings::max_content_boxes`]).
//!
//! **First, in one step.** Each box of poses is first bounded by the chart that follows the pose
//! ([`super::pose_chart`]): `δ = M(X) y` with `M(X)` the first-order inverse of the legs'
//! Jacobian at each pose, where a region closes at once when the Jacobian changes little across
//! the box and the move, and whose bound tends to the truth as the box shrinks (its remainder is
//! second order). Only a box where it cannot close goes through the faces and pieces above.
//!
//! **Last, without a chart.** Where neither closes and the moves reach beyond 1% of the
//! platform's distance from the base (centimetres, where the legs' directions turn across the
//! move), the moves themselves are paved with second-order Taylor models
//! ([`super::move_paving`]). Such a paving's pieces hold for every sub-box of its box of poses:
//! a box whose paving still gains is refined (the paving continued) before it is split, and its
//! halves start from its pieces, also when its closing ran out of budget.
//!
//! Over the workspace, a branch and bound splits the boxes of poses with the largest bound; a
//! box whose region cannot be closed (the move not enclosed: near a singular pose, or errors so
//! large that the legs' Jacobian changes across them) is split too, and when it is already small
//! the bound is not proved and the box is named instead.

use super::enclosure::{AccuracyProblem, PoseBox};
use super::move_paving::{MovePaving, Paved};
use super::pose_chart::PoseChart;
use calib_core::split_widest;
use calib_core::Ranked;
use calib_core::{interval_model, Affine, Interval, Model, Scalar};
use nalgebra::Matrix6;
use rayon::prelude::*;
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::sync::Arc;

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
pub const REGIONS: [f64; 6] = [3.0, 2.0, 1.5, 1.25, 1.1, 1.05];
/// A box of a face of `D` narrower than this fraction of `D` (in every coordinate) that cannot be
/// excluded ends the attempt: the region cannot be closed.
const FINEST_FACE: f64 = 1.0 / 64.0;
/// Rounds of the enclosure of `D ∩ F` by the box `|y_i| <= U_i + r_i`.
const SHRINK_ROUNDS: usize = 3;
/// The relative margin added to a floating-point sum of six products (at most `7u` off, `u =
/// 2⁻⁵³`): see [`Chart::vertex_value`].
const ERROR_MARGIN: f64 = 1e-13;
/// Boxes of leg changes between two checks of [`Chart::content_bound`]'s progress.
const CONTENT_ROUND: usize = 100;
/// The relative fall of the largest value per round below which [`Chart::content_bound`] stops.
const CONTENT_STALL: f64 = 0.005;
/// Krawczyk steps per box of leg changes in [`Chart::piece`].
const KRAWCZYK_STEPS: usize = 5;
/// A Krawczyk step that narrows the box by less than this fraction (summed widths, relative to
/// `p`'s) is the last.
const KRAWCZYK_STALL: f64 = 0.1;

/// A box of poses whose paving of the moves lowered its key by at least this fraction in its
/// last evaluation is refined (its paving continued with twice the boxes of moves) rather than
/// split: where the moves' pieces are still coarse, halving the poses only repeats them.
const REFINE_GAIN: f64 = 0.01;
/// Refinements at most per box of poses (the last with `2^REFINE_ROUNDS` times
/// [`PoseBoundSettings::max_move_boxes`]).
const REFINE_ROUNDS: usize = 6;

/// Boxes of moves per second of [`PoseBoundSettings::max_seconds`]: about 35% below what two
/// cores examine in the paving of the moves (11,000 a second on `sample21`'s ± 1 cm workspace),
/// so that the count, not the clock, ends a search.
const MOVE_BOXES_PER_SECOND: f64 = 7000.0;

/// When to stop [`pose_error_bounds`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PoseBoundSettings {
    /// Stop once each bound is within `1 + rel_tol` of its target (default 0.04).
    pub rel_tol: f64,
    /// Boxes of poses examined at most (default 40 000).
    pub max_pose_boxes: usize,
    /// Boxes of `D`'s faces examined at most per box of poses and region (default 300).
    pub max_face_boxes: usize,
    /// Boxes of leg changes examined at most per box of poses, to bound the errors over
    /// `D ∩ F` (default 1000).
    pub max_content_boxes: usize,
    /// Boxes of moves examined at most per box of poses by the paving of the moves (second-order
    /// Taylor models, where neither chart closes and the moves are large; default 2000) in its
    /// first evaluation; a paving that keeps gaining is continued with twice as many, up to six
    /// times, before its box of poses is split.
    pub max_move_boxes: usize,
    /// A box of poses whose region cannot be closed and which is narrower than this fraction of
    /// the workspace in every coordinate ends the search unproved (default 1/16).
    pub finest_pose: f64,
    /// Stop after about this many seconds (default 30: a safety net behind `max_pose_boxes`,
    /// which keeps results reproducible; the bounds stay valid, or the box of
    /// poses not yet bounded is named). Each second also allows 7,000 boxes of moves, counted
    /// (a reproducible budget for the paving of the moves).
    pub max_seconds: f64,
}

impl Default for PoseBoundSettings {
    fn default() -> Self {
        PoseBoundSettings {
            rel_tol: 0.04,
            max_pose_boxes: 40_000,
            max_face_boxes: 300,
            max_content_boxes: 1000,
            max_move_boxes: 2000,
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
    /// Boxes of moves examined over all boxes of poses: pieces of the regions' faces, and boxes
    /// of leg changes inside them.
    pub move_boxes: usize,
    /// Whether both bounds met their targets (else a budget ran out; the bounds stay valid).
    pub converged: bool,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// The legs' Jacobian `J = ∇_δ G` at `δ = 0`, at the centre of the box of poses `x` and the
/// nominal geometry (floating point: any matrix serves as a chart once its inverse is proved).
pub fn centre_jacobian(problem: &AccuracyProblem, x: &PoseBox) -> Matrix6<f64> {
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
    j
}

/// The floating-point inverse `M` of `j`, when `‖I - j M‖∞ < 1` proves it (hence `j`)
/// nonsingular: `δ = M y` then maps a region `D` onto a neighbourhood of `δ = 0` and `D`'s
/// boundary onto its boundary.
pub fn proved_inverse(j: &Matrix6<f64>) -> Option<Matrix6<f64>> {
    let inv = j.try_inverse()?;
    let residual_norm = (0..6)
        .map(|r| {
            (0..6)
                .map(|c| {
                    let p = (0..6).fold(Interval::point(0.0), |s, k| {
                        s + Interval::point(j[(r, k)]) * Interval::point(inv[(k, c)])
                    });
                    (Interval::point(if r == c { 1.0 } else { 0.0 }) - p).mag()
                })
                .fold(Interval::point(0.0), |s, v| s + Interval::point(v))
                .sup()
        })
        .fold(0.0, f64::max);
    // NaN fails too.
    (residual_norm.partial_cmp(&1.0) == Some(Ordering::Less)).then_some(inv)
}

/// `U_i = max |ΔL_i| + ε` over the box of poses `x`, rounded up: every leg's change along the
/// path stays within `[-U_i, U_i]` (module documentation). `None` when one is not finite.
pub fn leg_change_bounds(problem: &AccuracyProblem, x: &PoseBox, eps: f64) -> Option<[f64; 6]> {
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
    Some(bound)
}

/// Per leg, the inputs `m = (X, a, b)` of [`reached_change`]: the pose `pose` and the leg's
/// geometry box, each coordinate of which `geometry` turns into a `T`.
pub fn leg_inputs<T: Copy>(
    problem: &AccuracyProblem,
    pose: &[T; 6],
    mut geometry: impl FnMut(Interval) -> T,
) -> Vec<[T; 12]> {
    (0..6)
        .map(|i| {
            let t = problem.theta(i);
            core::array::from_fn(|k| if k < 6 { pose[k] } else { geometry(t[k - 6]) })
        })
        .collect()
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

/// The moves of one box of poses in the coordinates `y = J δ` (see the module documentation).
pub struct Chart {
    /// Per leg, `m = (X, a, b)` over the box of poses and the leg's geometry box.
    inputs: Vec<[Interval; 12]>,
    /// `M ≈ J⁻¹`, entries as thin intervals.
    pub m: [[Interval; 6]; 6],
    /// The same `M`, as floats.
    m_float: [[f64; 6]; 6],
    /// Per leg, the centre of `inputs`.
    centres: Vec<[f64; 12]>,
    /// `U_i`, rounded up.
    pub bound: [f64; 6],
}

/// The reached moves of a box of leg changes ([`Chart::piece`]).
pub struct Piece {
    /// Their enclosure in `y`.
    pub y: [Interval; 6],
    /// The same, split as `δ = M y + t`: `y` in the first box (for the pose box's centre), `t`
    /// in the second (in `δ`: the pose's part). `None` when that enclosure failed.
    split: Option<([Interval; 6], [Interval; 6])>,
}

impl Chart {
    /// The chart of the box of poses `x`, `None` when `J` is not proved invertible or a leg's
    /// bound is not finite.
    pub fn new(problem: &AccuracyProblem, x: &PoseBox, eps: f64) -> Option<Chart> {
        if problem.legs() != 6 {
            return None;
        }
        let inv = proved_inverse(&centre_jacobian(problem, x))?;
        let m: [[Interval; 6]; 6] =
            core::array::from_fn(|r| core::array::from_fn(|c| Interval::point(inv[(r, c)])));
        let bound = leg_change_bounds(problem, x, eps)?;
        let inputs = leg_inputs(problem, x, |t| t);
        let centres = inputs.iter().map(|m| m.map(|v| v.mid())).collect();
        Some(Chart {
            inputs,
            m,
            m_float: core::array::from_fn(|r| core::array::from_fn(|c| inv[(r, c)])),
            centres,
            bound,
        })
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
            if !g.is_empty() && (g.inf() > u || g.sup() < -u) {
                return true;
            }
            if i != first {
                return false;
            }
            // Where intervals cannot tell, the affine form of the face's own leg keeps the
            // first-order dependence on the move and the pose (most of a face of `D` is
            // settled here).
            let a = self.affine_change(i, y).range();
            !a.is_empty() && (a.inf() > u || a.sup() < -u)
        })
    }

    /// Leg `i`'s change `G_i(X, M y, θ*)` over the box `y` in affine arithmetic: noise symbols
    /// `0..6` for `y`, `6..12` for the pose (the geometry without correlation), so that `δ = M y`
    /// is exact and `G_i` keeps its first-order dependence on both.
    pub fn affine_change(&self, i: usize, y: &[Interval; 6]) -> Affine<12> {
        let zero = Affine::from_interval(Interval::ZERO);
        let ya: [Affine<12>; 6] = core::array::from_fn(|c| Affine::input(y[c], c));
        let delta: [Affine<12>; 6] = core::array::from_fn(|r| {
            (0..6).fold(zero, |s, c| s + Affine::from_interval(self.m[r][c]) * ya[c])
        });
        let m = &self.inputs[i];
        let inputs: [Affine<12>; 12] = core::array::from_fn(|k| {
            if k < 6 {
                Affine::input(m[k], 6 + k)
            } else {
                Affine::from_interval(m[k])
            }
        });
        reached_change(&delta, &inputs)
    }

    /// Upper bounds of the position (cm) and orientation (degrees) errors over the moves
    /// `δ = M y + t`, `y` in the box `y`, `t` in the box `shift`: `|d|` and `|w|` are norms of
    /// linear maps, convex, so their largest values are at one of the box's 64 vertices, and
    /// `|a + t|² = Σ (a_k + t_k)²` is largest with each `t_k` at one of its ends.
    /// Each vertex is evaluated in floating point; a component `Σ_c M_kc y_c` is off by at most
    /// `γ_6 Σ_c |M_kc| |y_c|` (`γ_6 < 7u`), and `ERROR_MARGIN` (far above it) is added to every
    /// component's magnitude before the norms, which are rounded up.
    pub fn vertex_value(&self, y: &[Interval; 6], shift: &[Interval; 6]) -> [f64; 2] {
        let ends = y.map(|v| [v.inf(), v.sup()]);
        let scale: [f64; 6] = core::array::from_fn(|r| {
            (0..6).map(|c| self.m[r][c].mag() * y[c].mag()).sum::<f64>() * ERROR_MARGIN
        });
        let mut best = [0.0f64; 2];
        for pattern in 0..64u32 {
            let v: [f64; 6] = core::array::from_fn(|c| ends[c][(pattern >> c & 1) as usize]);
            let comp: [f64; 6] = core::array::from_fn(|r| {
                let a = (0..6).map(|c| self.m_float[r][c] * v[c]).sum::<f64>();
                // |a + t| over t in the shift's interval, each end rounded up.
                let lo = (Interval::point(a) + Interval::point(shift[r].inf())).mag();
                let hi = (Interval::point(a) + Interval::point(shift[r].sup())).mag();
                lo.max(hi) + scale[r]
            });
            let sq = squared_norms(&comp);
            best = [best[0].max(sq[0]), best[1].max(sq[1])];
        }
        errors_from_squares(best)
    }

    /// Whether no move on the boundary of `D = M · [-r, r]` lies in `F`: each of the 12 faces
    /// is paved until every piece is [`Chart::excluded`]. `None` when a piece narrower than
    /// [`FINEST_FACE`] of `D` (or the budget) is reached first; else the pieces examined.
    pub fn closes(&self, r: &[f64; 6], budget: usize) -> Option<usize> {
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

    /// Per leg, a bound of the nonlinear remainder `|G_i(M y) - y_i|` over the box `[-h, h]`
    /// of `y`: `G_i(M y) - y_i = Σ_c (S_ic - [i = c]) y_c` (`S = ∇_δ G · M` over the box, mean
    /// value from `δ = 0`, where `G = 0`). NaN where the enclosure failed.
    pub fn remainder(&self, h: &[f64; 6]) -> [f64; 6] {
        let y: [Interval; 6] = h.map(|v| Interval::new(-v, v));
        let d = self.delta(&y);
        core::array::from_fn(|i| {
            let grad = ReachedChange.jacobian_x_interval(&d, &self.inputs[i]);
            let natural = (0..6)
                .fold(Interval::point(0.0), |s, c| {
                    let slope =
                        (0..6).fold(Interval::point(0.0), |s, k| s + grad[k] * self.m[k][c]);
                    let off = if c == i { slope - 1.0 } else { slope };
                    s + off * y[c]
                })
                .mag();
            // The affine form of `G_i - y_i`: its linear part nearly cancels, what is left is
            // the second-order remainder (both are bounds; the smaller is kept).
            let a = (self.affine_change(i, &y) - Affine::input(y[i], i))
                .range()
                .mag();
            if a.is_nan() {
                natural
            } else {
                natural.min(a)
            }
        })
    }

    /// Half-widths `h` with `D ∩ F ⊆ [-h, h]` for `D = M · [-r, r]`: a move of `F` has
    /// `|y_i| <= U_i + |G_i - y_i|` ([`Chart::remainder`]); repeated on the smaller box, which
    /// still holds `D ∩ F`.
    pub fn enclosing_box(&self, r: &[f64; 6]) -> [f64; 6] {
        let mut h = *r;
        for _ in 0..SHRINK_ROUNDS {
            let rest = self.remainder(&h);
            h = core::array::from_fn(|i| {
                let v = (Interval::point(self.bound[i]) + Interval::point(rest[i])).sup();
                if v.is_nan() {
                    h[i]
                } else {
                    v.min(h[i])
                }
            });
        }
        h
    }

    /// An enclosure, in `y`, of the reached moves of `D ∩ F` whose leg changes `s = G(X, δ,
    /// θ*)` lie in the box `p` (for every pose of the box and geometry), `None` only when there
    /// are proved to be none. Such a move has `y ∈ Y₀ = (p + [-ρ, ρ]) ∩ [-h, h]` (`ρ` the [`Chart::remainder`]
    /// over `[-h, h] ⊇ D ∩ F`); then Krawczyk steps `Y ← Y ∩ K(Y)`,
    /// `K(Y) = ỹ - C (G(X, M ỹ, θ*) - p) + (I - C A(Y)) (Y - ỹ)`, keep every solution of `Y`
    /// (mean value: `G(M y) - G(M ỹ) = A (y - ỹ)` with `A ∈ ∇_δ G(M Y) · M`). `ỹ` solves the
    /// centre's equations in floating point and `C ≈ A(ỹ)⁻¹`. `G(X, M ỹ, θ*)` is centred in
    /// the pose and geometry, `G(m_c) + ∇_m G (m - m_c)`, and the pose's part is multiplied
    /// by `C` as one matrix: the legs' changes move together with the pose, and the box of
    /// `K` keeps that.
    pub fn piece(&self, p: &[Interval; 6], rho: &[f64; 6], h: &[f64; 6]) -> Option<Piece> {
        let y: [Interval; 6] = core::array::from_fn(|i| {
            (p[i] + Interval::new(-rho[i], rho[i])).intersection(Interval::new(-h[i], h[i]))
        });
        if y.iter().any(|v| v.is_empty()) {
            return None;
        }
        // Without a floating-point solution or preconditioner, `Y₀` itself encloses them.
        let Some((centre, preconditioner)) = self.centre_solution(p) else {
            return Some(Piece { y, split: None });
        };
        let krawczyk = Krawczyk::new(self, p, &centre, &preconditioner);
        let y = krawczyk.contract(y, p)?;
        // The same enclosure with the pose's part kept apart and mapped to the moves as one
        // matrix: how the reached move itself shifts with the pose.
        let core = krawczyk.without_pose(&y);
        let shift = krawczyk.pose_shift();
        let split =
            (!enclosure_failed(&core) && !enclosure_failed(&shift)).then_some((core, shift));
        Some(Piece { y, split })
    }

    /// `ỹ` and `C` of [`Chart::piece`]: three floating-point Newton steps for
    /// `G(X_c, M ỹ, θ_c) = mid p` from `mid p`, and the inverse of the last Jacobian
    /// `A = ∇_δ G · M`. `None` when a step or the inverse fails or is not finite.
    fn centre_solution(&self, p: &[Interval; 6]) -> Option<([f64; 6], Matrix6<f64>)> {
        let (centres, mf) = (&self.centres, &self.m_float);
        let to_delta = |y: &[f64; 6]| -> [f64; 6] {
            core::array::from_fn(|r| (0..6).map(|c| mf[r][c] * y[c]).sum())
        };
        let mut yt: [f64; 6] = p.map(|v| v.mid());
        let mut a = Matrix6::zeros();
        for _ in 0..3 {
            let d = to_delta(&yt);
            let mut g = nalgebra::Vector6::zeros();
            for i in 0..6 {
                g[i] = ReachedChange.residual(&d, &centres[i]) - p[i].mid();
                let row = ReachedChange.jacobian_x(&d, &centres[i]);
                for c in 0..6 {
                    a[(i, c)] = (0..6).map(|k| row[k] * mf[k][c]).sum();
                }
            }
            let step = a.lu().solve(&g)?;
            for c in 0..6 {
                yt[c] -= step[c];
            }
        }
        let cm = a.try_inverse()?;
        if !yt.iter().chain(cm.iter()).all(|v| v.is_finite()) {
            return None;
        }
        Some((yt, cm))
    }

    /// Upper bounds of both errors over a [`Piece`]: the smaller of [`Chart::vertex_value`]
    /// over its box and over its pose-free box shifted by the pose's part.
    pub fn piece_value(&self, piece: &Piece) -> [f64; 2] {
        let whole = self.vertex_value(&piece.y, &[Interval::ZERO; 6]);
        match &piece.split {
            Some((core, shift)) => {
                let apart = self.vertex_value(core, shift);
                [whole[0].min(apart[0]), whole[1].min(apart[1])]
            }
            None => whole,
        }
    }

    /// Upper bounds of both errors over `D ∩ F ⊆ [-h, h]` (in `y`), refined towards `target`:
    /// a best-first branch and bound over boxes `p` of the leg changes `s ∈ [-U, U]` — the exact
    /// shape of `F` in these coordinates — each bounded by [`Chart::piece_value`] of its
    /// [`Chart::piece`], splitting the box with the largest value (relative to `target`) until
    /// each box left is within its target, `budget` boxes have been examined, or the largest
    /// value stops falling ([`CONTENT_STALL`] per [`CONTENT_ROUND`] boxes: the box of poses is
    /// then too wide); the bound is the largest value left.
    fn content_bound(&self, h: &[f64; 6], target: [f64; 2], budget: usize) -> ([f64; 2], usize) {
        let rho = self.remainder(h);
        if rho.iter().any(|v| v.is_nan()) {
            return (
                self.vertex_value(&h.map(|v| Interval::new(-v, v)), &[Interval::ZERO; 6]),
                1,
            );
        }
        let root: [Interval; 6] = self.bound.map(|u| Interval::new(-u, u));
        let ranked = |p: [Interval; 6]| {
            self.piece(&p, &rho, h).map(|piece| {
                let v = self.piece_value(&piece);
                Ranked {
                    key: key(v, target),
                    item: (p, v),
                }
            })
        };
        let mut heap: BinaryHeap<_> = ranked(root).into_iter().collect();
        let mut examined = 1;
        let mut last = f64::INFINITY;
        while examined < budget {
            let Some(top) = heap.pop() else { break };
            // The largest key falls by less than CONTENT_STALL over CONTENT_ROUND boxes: what is
            // left is the box of poses' own width, which only splitting it narrows.
            if examined % CONTENT_ROUND < 2 {
                if top.key > last * (1.0 - CONTENT_STALL) {
                    heap.push(top);
                    break;
                }
                last = top.key;
            }
            let split = (top.key > 1.0)
                .then(|| split_widest(&top.item.0, &root))
                .flatten();
            let Some((l, r)) = split else {
                heap.push(top);
                break;
            };
            examined += 2;
            heap.extend([l, r].into_iter().filter_map(&ranked));
        }
        let bound = heap.iter().fold([0.0f64; 2], |acc, q| {
            [acc[0].max(q.item.1[0]), acc[1].max(q.item.1[1])]
        });
        (bound, examined)
    }
}

/// Whether an enclosure failed (a NaN bound): it proves nothing.
fn enclosure_failed(v: &[Interval; 6]) -> bool {
    v.iter().any(|k| k.inf().is_nan() || k.sup().is_nan())
}

/// The Krawczyk operator of [`Chart::piece`] for one box `p` of leg changes, at the centre `ỹ`
/// with the preconditioner `C`: `G(X, M ỹ, θ*)` centred in the pose and geometry, the pose's
/// part kept as one matrix.
struct Krawczyk<'a> {
    chart: &'a Chart,
    /// `C ≈ A(ỹ)⁻¹`, entries as thin intervals.
    c: [[Interval; 6]; 6],
    /// `ỹ`, as thin intervals.
    centre: [Interval; 6],
    /// Per leg, `e_i ∋ G_i(X, M ỹ, θ*) - s_i` without the pose's part.
    e: [Interval; 6],
    /// Per leg, `∂G_i/∂X_k` at `M ỹ` over the box of poses.
    x_part: [[Interval; 6]; 6],
    /// The box of poses about its centre, `X - X_c`.
    dx: [Interval; 6],
}

impl<'a> Krawczyk<'a> {
    /// The operator of `chart` for the box `p` of leg changes, at `centre` (`ỹ`) with
    /// `preconditioner` (`C`).
    fn new(
        chart: &'a Chart,
        p: &[Interval; 6],
        centre: &[f64; 6],
        preconditioner: &Matrix6<f64>,
    ) -> Self {
        let c: [[Interval; 6]; 6] = core::array::from_fn(|r| {
            core::array::from_fn(|i| Interval::point(preconditioner[(r, i)]))
        });
        let yti = centre.map(Interval::point);
        let dt = chart.delta(&yti);
        let mut e = [Interval::ZERO; 6];
        let mut x_part = [[Interval::ZERO; 6]; 6];
        for i in 0..6 {
            let m = &chart.inputs[i];
            let mc = chart.centres[i].map(Interval::point);
            let gm = ReachedChange.jacobian_m_interval(&dt, m);
            let mut v = ReachedChange.residual_interval(&dt, &mc) - p[i];
            for k in 6..12 {
                v += gm[k] * (m[k] - mc[k]);
            }
            e[i] = v;
            x_part[i] = core::array::from_fn(|k| gm[k]);
        }
        let dx: [Interval; 6] =
            core::array::from_fn(|k| chart.inputs[0][k] - chart.inputs[0][k].mid());
        Krawczyk {
            chart,
            c,
            centre: yti,
            e,
            x_part,
            dx,
        }
    }

    /// The pose's part, `C ∇_X G (X - X_c)`, as one matrix.
    fn pose_term(&self) -> [Interval; 6] {
        let (c, x_part, dx) = (&self.c, &self.x_part, &self.dx);
        core::array::from_fn(|r| {
            (0..6).fold(Interval::ZERO, |s, k| {
                let ck = (0..6).fold(Interval::ZERO, |s, i| s + c[r][i] * x_part[i][k]);
                s + ck * dx[k]
            })
        })
    }

    /// `K(Y)` without the pose's part: `ỹ - C e + (I - C A(Y)) (Y - ỹ)`.
    fn without_pose(&self, y: &[Interval; 6]) -> [Interval; 6] {
        let (chart, c, e, yti) = (self.chart, &self.c, &self.e, &self.centre);
        let d = chart.delta(y);
        let slope: [[Interval; 6]; 6] = core::array::from_fn(|i| {
            let grad = ReachedChange.jacobian_x_interval(&d, &chart.inputs[i]);
            core::array::from_fn(|col| {
                (0..6).fold(Interval::ZERO, |s, k| s + grad[k] * chart.m[k][col])
            })
        });
        core::array::from_fn(|r| {
            let mut k = yti[r];
            for i in 0..6 {
                k -= c[r][i] * e[i];
            }
            for col in 0..6 {
                let ca = (0..6).fold(Interval::ZERO, |s, i| s + c[r][i] * slope[i][col]);
                let id = Interval::point(if r == col { 1.0 } else { 0.0 });
                k += (id - ca) * (y[col] - yti[col]);
            }
            k
        })
    }

    /// Krawczyk steps `Y ← Y ∩ K(Y)` from `y` (at most [`KRAWCZYK_STEPS`], until the widths of
    /// `Y` fall by less than [`KRAWCZYK_STALL`] of those of `p`, or an enclosure fails and the
    /// box is kept as it is). `None` when `Y` becomes empty: no solution in the box, which
    /// holds them all.
    fn contract(&self, mut y: [Interval; 6], p: &[Interval; 6]) -> Option<[Interval; 6]> {
        let pose_term = self.pose_term();
        for _ in 0..KRAWCZYK_STEPS {
            let core = self.without_pose(&y);
            let k: [Interval; 6] = core::array::from_fn(|r| core[r] - pose_term[r]);
            if enclosure_failed(&k) {
                break;
            }
            let next: [Interval; 6] = core::array::from_fn(|r| y[r].intersection(k[r]));
            if next.iter().any(|v| v.is_empty()) {
                return None;
            }
            let gain: f64 = (0..6).map(|c| y[c].wid() - next[c].wid()).sum();
            y = next;
            if gain < KRAWCZYK_STALL * p.iter().map(|v| v.wid()).sum::<f64>() {
                break;
            }
        }
        Some(y)
    }

    /// How the reached move shifts with the pose: `-(M C ∇_X G)(X - X_c)`.
    fn pose_shift(&self) -> [Interval; 6] {
        let (m, c, x_part, dx) = (&self.chart.m, &self.c, &self.x_part, &self.dx);
        let mc: [[Interval; 6]; 6] = core::array::from_fn(|r| {
            core::array::from_fn(|i| (0..6).fold(Interval::ZERO, |s, k| s + m[r][k] * c[k][i]))
        });
        core::array::from_fn(|r| {
            (0..6).fold(Interval::ZERO, |s, k| {
                let rk = (0..6).fold(Interval::ZERO, |s, i| s + mc[r][i] * x_part[i][k]);
                s - rk * dx[k]
            })
        })
    }
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

/// The bounds over one box of poses, refined towards `target`, the boxes of moves examined, and
/// what a paving of the moves proved for the box and its sub-boxes. `budget`: boxes of moves for
/// the paving; `parent`: that of `x` or of a box of poses containing it, whose paving then
/// continues (the charts failed there, and would here).
fn bound_pose_box(
    problem: &AccuracyProblem,
    x: &PoseBox,
    eps: f64,
    target: [f64; 2],
    budget: usize,
    settings: &PoseBoundSettings,
    parent: Option<&Paved>,
) -> (BoxBound, usize, Option<Paved>) {
    if !problem.may_be_feasible(x) {
        return (BoxBound::Empty, 0, None);
    }
    let pave = |paving: MovePaving, parent: Option<&Paved>, examined: usize| {
        let (bound, n, paved) = paving.bound(target, budget, parent);
        let outcome = bound.map_or(BoxBound::Unproved, BoxBound::Bound);
        (outcome, examined + n, paved)
    };
    if let Some(paving) = parent.and_then(|p| MovePaving::new(problem, x, eps, Some(p))) {
        return pave(paving, parent, 0);
    }
    // The chart that follows the pose bounds the box in one step where the Jacobian changes
    // little across it and the move; the fixed chart's faces and pieces are the fallback.
    if let Some(bound) = PoseChart::new(problem, x, eps).and_then(|c| c.bound()) {
        return (BoxBound::Bound(bound), 0, None);
    }
    let Some(chart) = Chart::new(problem, x, eps) else {
        return (BoxBound::Unproved, 0, None);
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
            let (bound, n) = chart.content_bound(&h, target, settings.max_content_boxes);
            (BoxBound::Bound(bound), examined + n, None)
        }
        // The last resort: the paving of the moves (second-order models, no chart).
        None => match MovePaving::new(problem, x, eps, None) {
            Some(paving) => pave(paving, None, examined),
            None => (BoxBound::Unproved, examined, None),
        },
    }
}

/// A box of poses in the queue of [`pose_error_bounds`].
struct Queued {
    x: PoseBox,
    bound: BoxBound,
    /// Its paving of the moves, kept while the box may be refined or split.
    paved: Option<Arc<Paved>>,
    /// The relative fall of its key in its last evaluation (from its parent's key, or from its
    /// own before a refinement).
    gain: f64,
    /// Refinements of its paving so far.
    round: usize,
}

/// A box of poses to evaluate: the paving it starts from (its own or its parent's), the key
/// before, and the round (0: a new box).
type Task = (PoseBox, Option<Arc<Paved>>, f64, usize);

/// An evaluated [`Task`]: the box, its bounds, the boxes of moves examined, its paving, and the
/// task's key before and round.
type Evaluated = (PoseBox, BoxBound, usize, Option<Paved>, f64, usize);

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
    let whole = (search.domain, None, f64::INFINITY, 0);
    queue.record(search.evaluate(whole, settings.max_move_boxes), &search);
    let batch = 2 * rayon::current_num_threads().max(1);
    // The seconds also set a budget of boxes of moves, counted, so that a search the paving of
    // the moves keeps busy ends at the same place on every run of a machine.
    let move_budget = settings.max_seconds * MOVE_BOXES_PER_SECOND;
    while queue.pose_boxes < settings.max_pose_boxes
        && (queue.move_boxes as f64) < move_budget
        && start.elapsed().as_secs_f64() < settings.max_seconds
    {
        let tasks = queue.next_tasks(batch, &search);
        // Once a box is named unproved no bound is claimed, so the boxes popped in this batch
        // need not be evaluated.
        if tasks.is_empty() || queue.unproved_at.is_some() {
            break;
        }
        let share = move_share(move_budget, queue.move_boxes, tasks.len(), settings);
        let results: Vec<Evaluated> = tasks
            .into_par_iter()
            .map(|t| search.evaluate(t, share))
            .collect();
        for r in results {
            queue.record(r, &search);
        }
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

    /// Evaluates a [`Task`] (a box of poses, the paving it starts from, its key before and its
    /// round), examining at most `share` boxes of moves.
    fn evaluate(&self, (x, parent, before, round): Task, share: usize) -> Evaluated {
        let budget = (self.settings.max_move_boxes << round).min(share);
        let (b, n, paved) = bound_pose_box(
            self.problem,
            &x,
            self.eps,
            self.target,
            budget,
            self.settings,
            parent.as_deref(),
        );
        (x, b, n, paved, before, round)
    }
}

/// The boxes of poses of [`pose_error_bounds`] still to be refined or split, largest key first,
/// and what the search has counted and found so far.
#[derive(Default)]
struct PoseQueue {
    heap: BinaryHeap<Ranked<Queued>>,
    /// New boxes of poses evaluated (a refinement is not a new box).
    pose_boxes: usize,
    /// Boxes of moves examined.
    move_boxes: usize,
    /// The share of the workspace's volume proved to hold no pose.
    empty_share: f64,
    /// A box whose bounds could not be proved, once one is named.
    unproved_at: Option<PoseBox>,
    /// Whether that box is as fine as the search goes (no split would prove it).
    unprovable: bool,
}

impl PoseQueue {
    /// Counts an evaluated box and queues it. A paving's pieces are kept only for boxes still
    /// to be refined or split (an unproved box's too: its halves continue its closing).
    fn record(&mut self, evaluated: Evaluated, search: &PoseSearch<'_>) {
        let (x, b, n, paved, before, round) = evaluated;
        // A box refined is not a new box.
        if round == 0 {
            self.pose_boxes += 1;
        }
        self.move_boxes += n;
        if b == BoxBound::Empty {
            self.empty_share += share_of(&x, &search.domain);
        }
        match b {
            BoxBound::Empty => {}
            BoxBound::Bound(v) => {
                let key = key(v, search.target);
                let paved = paved.filter(|_| key > 1.0).map(Arc::new);
                self.heap.push(Ranked {
                    key,
                    item: Queued {
                        x,
                        bound: b,
                        paved,
                        gain: 1.0 - key / before,
                        round,
                    },
                })
            }
            BoxBound::Unproved => self.heap.push(Ranked {
                key: f64::INFINITY,
                item: Queued {
                    x,
                    bound: b,
                    paved: paved.map(Arc::new),
                    gain: 0.0,
                    round,
                },
            }),
        }
    }

    /// Up to `batch` tasks from the boxes with the largest keys above 1: a box whose paving is
    /// still gaining is refined on its own (twice the boxes of moves), any other is split and
    /// its halves start from its pieces. A box that cannot be split (or, unproved, is as fine as
    /// the search goes) stays in the queue and ends the batch; an unproved one is named.
    fn next_tasks(&mut self, batch: usize, search: &PoseSearch<'_>) -> Vec<Task> {
        let (domain, finest_pose) = (&search.domain, search.settings.finest_pose);
        let mut tasks: Vec<Task> = Vec::new();
        while tasks.len() < batch {
            let Some(top) = self.heap.pop() else { break };
            if top.key <= 1.0 {
                self.heap.push(top);
                break;
            }
            let q = &top.item;
            if q.paved.is_some() && q.gain >= REFINE_GAIN && q.round < REFINE_ROUNDS {
                tasks.push((q.x, q.paved.clone(), top.key, q.round + 1));
                continue;
            }
            let fine = (0..6).all(|c| q.x[c].wid() <= finest_pose * domain[c].wid());
            match split_widest(&q.x, domain) {
                Some((l, r)) if !(fine && q.bound == BoxBound::Unproved) => {
                    tasks.push((l, q.paved.clone(), top.key, 0));
                    tasks.push((r, q.paved.clone(), top.key, 0));
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
            move_boxes: self.move_boxes,
            converged,
            seconds: start.elapsed().as_secs_f64(),
        }
    }
}

/// The boxes of moves each of `tasks` tasks may examine: an equal share of what is left of the
/// counted `move_budget` after `move_boxes`, at least a first evaluation's, so that the search
/// ends near `max_seconds`.
fn move_share(
    move_budget: f64,
    move_boxes: usize,
    tasks: usize,
    settings: &PoseBoundSettings,
) -> usize {
    let left = (move_budget - move_boxes as f64).max(0.0) / tasks as f64;
    if left.is_finite() {
        (left as usize).max(settings.max_move_boxes)
    } else {
        usize::MAX
    }
}
