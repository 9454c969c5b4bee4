//! The arm's accuracy certificate (`arm accuracy`): how far the tool point can be from where the
//! controller computes it, anywhere in a joint-space box, for every geometry the robot file's box
//! allows and every joint error within the encoders' bound.
//!
//! The controller loads the nominal values `θ̂` of a robot file and computes the tool point
//! `p(q; θ̂)` of the commanded joints `q`; the real arm has some `θ*` in the file's box and its
//! joints reach `q + e` with `|e_i| <= joint_deg`. The joint error enters the model exactly like an
//! error of the joint's `theta_i` (`Rz(theta_i + q_i)`), so it widens `theta_i`'s box. The
//! **tool-point error** `max ‖p(q; θ*) - p(q; θ̂)‖` over the joint box `Q` and the geometry box
//! `Θ` (tracker frame, mm) is bracketed between an upper bound proved over all of `Q × Θ` and a
//! lower bound attained by an explicit instance `(q, θ*)`.
//!
//! # The method
//!
//! With `‖v‖ = max_{|u| = 1} u·v`, the error is the maximum over `(q, u)` of
//! `f(q, u) = max_{θ ∈ Θ} u·(p(q; θ) - p(q; θ̂))`. By the mean value theorem in `θ`,
//! `f(q, u) <= h(u) = Σ_j |u·g_j| |Θ_j - θ̂_j|` for every `q` of a joint box, where `g_j` encloses
//! `∂p/∂θ_j` over the joint box and all of `Θ`: no wrapping of the error vector's three
//! coordinates into a box. [`calib_core::maximize`] runs a branch and bound over the joints; for
//! each joint box the enclosures `g_j` are computed once (in intervals, and on small boxes as
//! affine forms in the joints, whose excess is second order in the box's width) and the
//! direction `u` is searched over the whole sphere without evaluating the arm again
//! (`directions`). Lower bounds take the vertex of `Θ` the signs of `u·∂p/∂θ` point to, and a
//! local search in `q`.

use crate::certification::{padded_index, MAX_JOINTS, NM, NX};
use crate::joint_space::JointSpace;
use crate::model::{arm7_point, Arm7Point};
use crate::params::{self, Unit};
use crate::robot::Arm;
use crate::units::{deg_to_rad, rad_to_deg, to_deg, to_rad};
use crate::ArmError;
use calib_core::{
    maximize, maximize_over_list, Interval, Maximum, MaximumSettings, Objective, VectorModel,
};
use directions::{max_over_directions, DirectionCache, Sensitivities};
use serde_json::json;

#[doc(hidden)]
pub mod directions;
pub mod over_set;
mod section;
use std::cell::Cell;
use std::time::Instant;

/// A point of the search: the joints (radians, padded).
pub(crate) type SearchPoint = [f64; MAX_JOINTS];

/// The tool-point accuracy problem of a robot file on a joint space (module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct ToolAccuracyProblem {
    joints: usize,
    /// `θ̂` in the padded model's units (radians), as the controller computes with it.
    nominal: [f64; NX],
    /// `Θ'`: the box (with the joint error in `theta_i`) and `θ̂`, enclosed.
    theta: [Interval; NX],
    /// `Θ' - θ̂`.
    spread: [Interval; NX],
    /// Per parameter, the lower and upper end of the true box moved inward past rounding (the
    /// vertices of instances): a point, or for a fixed angle the enclosure of its value.
    vertex: [[Interval; NX]; 2],
    /// The joint box in radians (outward), padded joints at 0.
    domain: [Interval; MAX_JOINTS],
    /// The joint box in radians moved inward past rounding (where instances are taken).
    inner: [[f64; 2]; MAX_JOINTS],
    /// A joint whose range is one angle: the enclosure of that angle in radians.
    fixed_joint: [Option<Interval>; MAX_JOINTS],
    /// Per parameter with a spread, its index among those (the affine bound's seed).
    seeds: [Option<usize>; NX],
    /// How many parameters have a spread.
    free: usize,
}

/// An explicit instance of the tool-point error.
#[derive(Clone, Debug, PartialEq)]
pub struct ToolInstance {
    /// The commanded joints (degrees, to the nearest double of the radians used).
    pub joints_deg: Vec<f64>,
    /// The commanded joints in radians, inside the joint box (a joint fixed at one angle: the
    /// nearest double; the error is then enclosed over the angle's enclosure).
    pub joints_rad: Vec<f64>,
    /// The true geometry `θ*` in model order and units (radians), the joint error included in
    /// `theta_i`: points inside the box, a fixed angle as the enclosure of its value.
    pub theta: Vec<Interval>,
    /// `p(q; θ*) - p(q; θ̂)` in floating point (mm, tracker frame).
    pub error: [f64; 3],
    /// `‖p(q; θ*) - p(q; θ̂)‖`, rounded down (mm).
    pub value: f64,
}

/// A certified bracket of the tool-point error.
#[derive(Clone, Debug, PartialEq)]
pub struct ToolBracket {
    /// Proved over the whole joint box and geometry box (mm; `+∞` when an enclosure failed).
    pub upper: f64,
    /// Attained by `worst` (mm).
    pub lower: f64,
    /// The worst instance found.
    pub worst: Option<ToolInstance>,
    /// Where a larger error could still hide: the joint box (degrees) that gives `upper`.
    pub frontier_deg: Vec<[f64; 2]>,
    /// Whether `upper <= (1 + rel_tol) lower` was reached (else the box budget ran out).
    pub converged: bool,
    /// Boxes examined.
    pub boxes: usize,
    /// Wall-clock seconds.
    pub seconds: f64,
}

impl ToolBracket {
    /// `upper / lower` (`+∞` without a positive lower bound).
    pub fn ratio(&self) -> f64 {
        calib_core::bracket_ratio(self.upper, self.lower)
    }
}

/// When to stop the branch and bound.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToolAccuracySettings {
    /// Stop at `upper <= (1 + rel_tol) lower` (default 0.04: a bracket within 1.05 with margin).
    pub rel_tol: f64,
    /// Examine at most this many joint boxes (default 20 000: at most about a minute on a
    /// 6-axis arm; a ±10° cell of every joint converges in about 8 000).
    pub max_boxes: usize,
    /// Examine at most this many joint boxes over a certified set (default 300: each takes the
    /// arm's derivatives as second-order models and up to ninety warm-started linear programs,
    /// tens of milliseconds; a box wider than a radian in some joint, the arcs' vertices,
    /// about a tenth of a second).
    pub max_set_boxes: usize,
}

impl Default for ToolAccuracySettings {
    fn default() -> Self {
        ToolAccuracySettings {
            rel_tol: 0.04,
            max_boxes: 20_000,
            max_set_boxes: 300,
        }
    }
}

/// An inward point of `[lo, hi]`'s end (`up`: the upper end) of a box `v ± r` in the files'
/// units, in the model's units: the enclosure of `v` when the end cannot be moved inward safely.
fn inward_end(v: f64, r: f64, up: bool, unit: Unit) -> Interval {
    let to_model = |x: Interval| match unit {
        Unit::Deg => deg_to_rad(x),
        Unit::Mm => x,
    };
    let centre = to_model(Interval::point(v));
    // The end in the files' units, rounded towards v (so between v and the true end).
    let end = if up {
        (Interval::point(v) + Interval::point(r)).inf()
    } else {
        (Interval::point(v) - Interval::point(r)).sup()
    };
    let e = to_model(Interval::point(end));
    let point = if up { e.inf() } else { e.sup() };
    // The point is past the centre's enclosure on the right side: inside the true box.
    let inside = if up {
        point >= centre.sup()
    } else {
        point <= centre.inf()
    };
    if inside && r > 0.0 {
        Interval::point(point)
    } else {
        centre
    }
}

impl ToolAccuracyProblem {
    /// The problem for `arm` (nominal ± radius per parameter) on `space`, with every joint
    /// reaching its command within `joint_deg` degrees. An error when the joint space does not
    /// have one range per joint or the arm has more joints than the model.
    pub fn new(arm: &Arm, space: &JointSpace, joint_deg: f64) -> Result<Self, ArmError> {
        let joints = arm.joints.len();
        if !(3..=MAX_JOINTS).contains(&joints) {
            return Err(ArmError::Joints(joints));
        }
        if space.ranges_deg.len() != joints {
            return Err(ArmError::JointSpaceRanges {
                ranges: space.ranges_deg.len(),
                joints,
            });
        }
        if !(joint_deg.is_finite() && joint_deg >= 0.0) {
            return Err(ArmError::JointError(joint_deg));
        }
        let units: Vec<Unit> = params::names(joints).into_iter().map(|(_, u)| u).collect();
        let index = padded_index(joints);
        let (values, radius) = (arm.nominal(), arm.radius());
        // Padded parameters are 0 exactly (identity joints).
        let mut out = ToolAccuracyProblem {
            joints,
            nominal: [0.0; NX],
            theta: [Interval::ZERO; NX],
            spread: [Interval::ZERO; NX],
            vertex: [[Interval::ZERO; NX]; 2],
            domain: [Interval::ZERO; MAX_JOINTS],
            inner: [[0.0; 2]; MAX_JOINTS],
            fixed_joint: [None; MAX_JOINTS],
            seeds: [None; NX],
            free: 0,
        };
        for (j, &p) in index.iter().enumerate() {
            let (v, unit) = (values[j], units[j]);
            // The joint error moves theta_i like an error of theta_i.
            let extra = if j < 5 * joints && j % 5 == 0 {
                joint_deg
            } else {
                0.0
            };
            let sum = Interval::point(radius[j]) + Interval::point(extra);
            let file_box = Interval::mid_rad(v, sum.sup());
            let model_box = match unit {
                Unit::Deg => deg_to_rad(file_box),
                Unit::Mm => file_box,
            };
            out.nominal[p] = match unit {
                Unit::Deg => to_rad(v),
                Unit::Mm => v,
            };
            out.theta[p] = model_box.hull(Interval::point(out.nominal[p]));
            out.spread[p] = out.theta[p] - Interval::point(out.nominal[p]);
            for (k, up) in [false, true].into_iter().enumerate() {
                // Vertices stay inside the true box: its half-width rounded down.
                out.vertex[k][p] = inward_end(v, sum.inf(), up, unit);
            }
        }
        for (i, &[lo, hi]) in space.ranges_deg.iter().enumerate() {
            let (l, h) = (
                deg_to_rad(Interval::point(lo)),
                deg_to_rad(Interval::point(hi)),
            );
            out.domain[i] = Interval::new(l.inf(), h.sup());
            out.inner[i] = [l.sup().min(h.inf()), h.inf().max(l.sup())];
            if lo == hi {
                // A fixed joint: evaluated over the enclosure of its value (no double is it).
                out.inner[i] = [l.mid(); 2];
                out.fixed_joint[i] = Some(l);
            }
        }
        for j in 0..NX {
            if out.spread[j] != Interval::ZERO {
                out.seeds[j] = Some(out.free);
                out.free += 1;
            }
        }
        Ok(out)
    }

    /// The box searched: the joints (radians; padded joints at 0).
    pub fn domain(&self) -> [Interval; MAX_JOINTS] {
        self.domain
    }

    /// The measured-quantity box of the model for the joints `q` (tracked point 0: the
    /// residual is then the tool point).
    fn joints_box(q: &[Interval; MAX_JOINTS]) -> [Interval; NM] {
        core::array::from_fn(|k| if k < MAX_JOINTS { q[k] } else { Interval::ZERO })
    }

    /// An upper bound of the tool-point error over the joint box `q` and every direction
    /// (module documentation, [`directions`]), refined no further once below `enough`: `+∞` on
    /// failure.
    #[doc(hidden)]
    pub fn upper(&self, q: &[Interval; MAX_JOINTS], cache: &DirectionCache, enough: f64) -> f64 {
        let finest = q.iter().map(|v| v.wid()).fold(0.0, f64::max);
        max_over_directions(&self.sensitivities(q), cache, finest, enough)
    }

    /// The Jacobian's columns over the joint box `q` and `Θ'` ([`directions`]).
    #[doc(hidden)]
    pub fn sensitivities(&self, q: &[Interval; MAX_JOINTS]) -> Sensitivities {
        let rows = Arm7Point.evaluate_rows_interval(&self.theta, &Self::joints_box(q));
        let mut weight = [0.0; NX];
        let mut columns = [[Interval::ZERO; 3]; NX];
        for j in 0..NX {
            if let Some(i) = self.seeds[j] {
                weight[i] = self.spread[j].mag();
                columns[i] = [rows[0].dx[j], rows[1].dx[j], rows[2].dx[j]];
            }
        }
        Sensitivities::new(
            q,
            (self.free, weight),
            columns,
            (&self.theta, &self.seeds),
            arm7_point,
        )
    }

    /// The tool-point error `p(q; θ) - p(q; θ̂)` at the joints `q` (radians, padded), enclosed.
    #[doc(hidden)]
    pub fn error_enclosure(&self, q: &[f64; MAX_JOINTS], theta: &[Interval; NX]) -> [Interval; 3] {
        let m: [Interval; NM] = core::array::from_fn(|k| {
            if k < MAX_JOINTS {
                self.fixed_joint[k].unwrap_or(Interval::point(q[k]))
            } else {
                Interval::ZERO
            }
        });
        let real = Arm7Point.residuals_interval(theta, &m);
        let nominal = Arm7Point.residuals_interval(&self.nominal.map(Interval::point), &m);
        core::array::from_fn(|r| real[r] - nominal[r])
    }

    /// The vertex of the true box where `u·(p(q; θ) - p(q; θ̂))` is largest to first order (the
    /// signs of `u·∂p/∂θ` at `θ̂`).
    #[doc(hidden)]
    pub fn vertex_towards(&self, q: &[f64; MAX_JOINTS], u: [f64; 3]) -> [Interval; NX] {
        let mut m = [0.0; NM];
        m[..MAX_JOINTS].copy_from_slice(q);
        let rows = Arm7Point.evaluate_rows(&self.nominal, &m);
        core::array::from_fn(|j| {
            let g = u[0] * rows[0].dx[j] + u[1] * rows[1].dx[j] + u[2] * rows[2].dx[j];
            self.vertex[usize::from(g > 0.0)][j]
        })
    }

    /// The floating-point error at `q` with the vertex `theta` (for the search).
    fn error_estimate(&self, q: &[f64; MAX_JOINTS], theta: &[Interval; NX]) -> [f64; 3] {
        let mut m = [0.0; NM];
        m[..MAX_JOINTS].copy_from_slice(q);
        let real = Arm7Point.residuals(&theta.map(|v| v.mid()), &m);
        let nominal = Arm7Point.residuals(&self.nominal, &m);
        core::array::from_fn(|r| real[r] - nominal[r])
    }

    /// The vertex with the largest error at `q` found from the direction `u`: alternately the
    /// vertex `u` points to and the direction of its error, until the vertex repeats.
    fn best_vertex(&self, q: &[f64; MAX_JOINTS], u: [f64; 3]) -> ([Interval; NX], f64) {
        let mut theta = self.vertex_towards(q, u);
        let mut e = self.error_estimate(q, &theta);
        for _ in 0..6 {
            let n = norm(e);
            if n == 0.0 {
                break;
            }
            let next = self.vertex_towards(q, e.map(|v| v / n));
            if next == theta {
                break;
            }
            let e2 = self.error_estimate(q, &next);
            if norm(e2) <= n {
                break;
            }
            (theta, e) = (next, e2);
        }
        (theta, norm(e))
    }

    /// The joints of a search point, clamped into the inner joint box.
    fn joints_of(&self, x: &SearchPoint) -> [f64; MAX_JOINTS] {
        core::array::from_fn(|k| x[k].clamp(self.inner[k][0], self.inner[k][1]))
    }

    /// The best vertex at `q` from thirteen first directions (the axes, the diagonals of the
    /// cube's faces and the cube's diagonals: `±u` lead to opposite vertices of equal error), so
    /// that the alternation of [`Self::best_vertex`] starts near the worst direction.
    #[doc(hidden)]
    pub fn best_vertex_any(&self, q: &[f64; MAX_JOINTS]) -> ([Interval; NX], f64) {
        let mut best = ([Interval::ZERO; NX], f64::NEG_INFINITY);
        for c in [-1.0f64, 0.0, 1.0] {
            for b in [-1.0f64, 0.0, 1.0] {
                for a in [0.0f64, 1.0] {
                    // One of each ±u pair: the first non-zero coordinate positive.
                    let u = [a, b, c];
                    let lead = u.iter().find(|v| **v != 0.0).copied().unwrap_or(0.0);
                    if lead <= 0.0 {
                        continue;
                    }
                    let n = norm(u);
                    let candidate = self.best_vertex(q, u.map(|v| v / n));
                    if candidate.1 > best.1 {
                        best = candidate;
                    }
                }
            }
        }
        best
    }

    /// A local search from `x` for the largest error: steps along each joint (a fraction of its
    /// range, halving down to 1e-6 of it), each point's best vertex.
    fn search(&self, x: &SearchPoint) -> ([f64; MAX_JOINTS], [Interval; NX]) {
        let q0 = self.joints_of(x);
        let (t0, v0) = self.best_vertex_any(&q0);
        let u0 = [1.0, 0.0, 0.0];
        let mut best = (q0, t0, v0);
        let widths: [f64; MAX_JOINTS] =
            core::array::from_fn(|k| self.inner[k][1] - self.inner[k][0]);
        let mut step = 0.25;
        while step >= 1e-6 {
            let mut moved = false;
            let e = self.error_estimate(&best.0, &best.1);
            let n = norm(e);
            let u = if n > 0.0 { e.map(|v| v / n) } else { u0 };
            for k in 0..self.joints {
                for sign in [-1.0, 1.0] {
                    let mut q = best.0;
                    q[k] =
                        (q[k] + sign * step * widths[k]).clamp(self.inner[k][0], self.inner[k][1]);
                    let (t, v) = self.best_vertex(&q, u);
                    if v > best.2 {
                        best = (q, t, v);
                        moved = true;
                    }
                }
            }
            if !moved {
                step /= 2.0;
            }
        }
        (best.0, best.1)
    }

    /// The worst instance found from the search point `x` (its joints clamped into the joint
    /// box): a local search, then the error of the vertex found, enclosed.
    pub fn instance(&self, x: &SearchPoint) -> ToolInstance {
        let (q, theta) = self.search(x);
        self.instance_at(&q, &theta)
    }

    /// The instance at the joints `x` themselves (no search away from them): the best vertex of
    /// the box there.
    fn instance_without_search(&self, x: &SearchPoint) -> ToolInstance {
        let q = self.joints_of(x);
        self.instance_at(&q, &self.best_vertex_any(&q).0)
    }

    fn instance_at(&self, q: &[f64; MAX_JOINTS], theta: &[Interval; NX]) -> ToolInstance {
        let e = self.error_enclosure(q, theta);
        let value = (e[0].sqr() + e[1].sqr() + e[2].sqr()).sqrt().inf();
        let index = padded_index(self.joints);
        ToolInstance {
            joints_deg: q[..self.joints].iter().map(|v| to_deg(*v)).collect(),
            joints_rad: q[..self.joints].to_vec(),
            theta: index.iter().map(|&p| theta[p]).collect(),
            error: e.map(|v| v.mid()),
            value: if value.is_nan() { 0.0 } else { value.max(0.0) },
        }
    }

    /// A rigorous lower bound of the error at the joints `q` with the vertex `theta`: its
    /// component along the direction of its floating-point value.
    #[doc(hidden)]
    pub fn dual_value(&self, q: &[f64; MAX_JOINTS], theta: &[Interval; NX]) -> f64 {
        let e = self.error_enclosure(q, theta);
        let m = e.map(|v| v.mid());
        let n = norm(m);
        if n.is_nan() || n <= 0.0 {
            return f64::NEG_INFINITY;
        }
        let u = m.map(|v| Interval::point(v / n));
        let value = (u[0] * e[0] + u[1] * e[1] + u[2] * e[2]).inf();
        if value.is_nan() {
            f64::NEG_INFINITY
        } else {
            value
        }
    }
}

pub(crate) fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// The tool-point error as a function of the joints, for [`maximize`].
struct ToolError<'a> {
    problem: &'a ToolAccuracyProblem,
    /// The largest error proved attained so far, times `1 + rel_tol`: a box whose bound is below
    /// it needs no tighter bound (the search stops there anyway).
    enough: Cell<f64>,
    rel_tol: f64,
    /// The boxes of directions enclosed so far.
    directions: DirectionCache,
}

impl ToolError<'_> {
    /// Records a proved lower bound of the maximum.
    fn record_attained(&self, v: f64) {
        if v.is_finite() {
            self.enough
                .set(self.enough.get().max(v * (1.0 + self.rel_tol)));
        }
    }
}

impl Objective<MAX_JOINTS> for ToolError<'_> {
    fn enclose(&self, q: &[Interval; MAX_JOINTS]) -> Interval {
        // θ̂ ∈ Θ', so the error is >= 0.
        Interval::new(
            0.0,
            self.problem.upper(q, &self.directions, self.enough.get()),
        )
    }

    fn attained(&self, x: &SearchPoint) -> f64 {
        let p = self.problem;
        let q = p.joints_of(x);
        let lower = p.dual_value(&q, &p.best_vertex_any(&q).0);
        if lower.is_nan() || lower < 0.0 || q != *x {
            // Only joints inside the box give a lower bound at x itself.
            return f64::NEG_INFINITY;
        }
        self.record_attained(lower);
        lower
    }

    fn at(&self, x: &SearchPoint) -> Interval {
        let p = self.problem;
        let upper = p.upper(&x.map(Interval::point), &self.directions, self.enough.get());
        let q = p.joints_of(x);
        let lower = p.dual_value(&q, &p.best_vertex_any(&q).0);
        if lower.is_nan() || lower < 0.0 || q != *x {
            // Only joints inside the box give a lower bound at x itself.
            return Interval::new(0.0, upper);
        }
        self.record_attained(lower);
        Interval::new(lower.min(upper), upper)
    }

    /// The joints are refined to the same size in radians, relative to the widest range (a
    /// joint fixed at one angle is never split).
    fn split_reference(&self, domain: &[Interval; MAX_JOINTS]) -> [Interval; MAX_JOINTS] {
        let widest = domain
            .iter()
            .map(|v| v.wid())
            .fold(f64::MIN_POSITIVE, f64::max);
        [Interval::new(0.0, widest); MAX_JOINTS]
    }

    fn improve(&self, x: &SearchPoint) -> Option<(SearchPoint, f64)> {
        let (q, theta) = self.problem.search(x);
        let v = self.problem.dual_value(&q, &theta);
        self.record_attained(v);
        Some((q, v))
    }
}

/// Brackets the tool-point error of `problem` (module documentation).
pub fn certify_tool_accuracy(
    problem: &ToolAccuracyProblem,
    settings: &ToolAccuracySettings,
) -> ToolBracket {
    let start = Instant::now();
    let m = maximize(
        &ToolError {
            problem,
            enough: Cell::new(0.0),
            rel_tol: settings.rel_tol,
            directions: DirectionCache::default(),
        },
        &problem.domain,
        &MaximumSettings {
            rel_tol: settings.rel_tol,
            abs_tol: 0.0,
            max_boxes: settings.max_boxes,
        },
    );
    let worst = problem.instance(&m.argmax);
    bracket_of(problem, &m, worst, settings, start)
}

/// `arm accuracy` as a library step: the calibrated `arm`'s bracket over its certified `set`
/// (over its box without one) and, with `before`, the uncalibrated robot's over its box (in
/// parallel), on the joint box `space` with every joint within `joint_deg` of its command. An
/// error when a robot does not match the joint space or the joint error is not a finite value
/// `>= 0`.
pub fn tool_accuracy(
    arm: &Arm,
    set: Option<crate::certification::ArmSet>,
    before: Option<&Arm>,
    space: JointSpace,
    joint_deg: f64,
    settings: &ToolAccuracySettings,
) -> Result<ToolAccuracyReport, ArmError> {
    let over_set = set.is_some();
    let (after_problem, before_problem) = problems(arm, set, before, &space, joint_deg)?;
    let (after, before) = std::thread::scope(|s| {
        let b = s.spawn(|| {
            before_problem
                .as_ref()
                .map(|p| certify_tool_accuracy(p, settings))
        });
        let after = match &after_problem {
            After::Set(p) => over_set::certify_set_accuracy(p, settings),
            After::Box(p) => certify_tool_accuracy(p, settings),
        };
        (after, b.join().ok().flatten())
    });
    Ok(ToolAccuracyReport {
        space,
        joint_deg,
        after,
        before,
        over_set,
        configurations: None,
    })
}

/// `arm accuracy --task`: [`tool_accuracy`] over a finite list of configurations (degrees, one
/// joint each per joint of the arm) instead of a joint box: the bracket's upper bound is proved
/// at every configuration (the decimal angles enclosed; the joints' error included), its
/// lower bound attained at one of them (at the nearest doubles of its angles) — after
/// calibration over the certified set (or the box), before over the box. The report's joint space is the configurations' hull. An error when a
/// configuration has the wrong number of joints or a joint that is not finite, or the task is
/// empty.
pub fn tool_accuracy_at(
    arm: &Arm,
    set: Option<crate::certification::ArmSet>,
    before: Option<&Arm>,
    configurations_deg: &[Vec<f64>],
    joint_deg: f64,
    settings: &ToolAccuracySettings,
) -> Result<ToolAccuracyReport, ArmError> {
    let joints = arm.joints.len();
    if configurations_deg.is_empty() {
        return Err(ArmError::EmptyTask);
    }
    for (k, q) in configurations_deg.iter().enumerate() {
        let found = q.iter().filter(|v| v.is_finite()).count();
        if q.len() != joints || found != joints {
            return Err(ArmError::TaskConfiguration {
                index: k + 1,
                found,
                joints,
            });
        }
    }
    // The hull, a little wider than rounding: every configuration lies strictly inside the box
    // where instances are taken.
    let space = JointSpace {
        ranges_deg: (0..joints)
            .map(|i| {
                let (lo, hi) = configurations_deg
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), q| {
                        (l.min(q[i]), h.max(q[i]))
                    });
                let pad = 1e-9 * (1.0 + lo.abs().max(hi.abs()));
                [lo - pad, hi + pad]
            })
            .collect(),
    };
    let list: Vec<[Interval; MAX_JOINTS]> = configurations_deg
        .iter()
        .map(|q| {
            core::array::from_fn(|i| match q.get(i) {
                // The decimal the user wrote lies within half an ulp of its double.
                Some(v) => over_set::joint_box(v.next_down(), v.next_up()),
                None => Interval::ZERO,
            })
        })
        .collect();
    let over_set = set.is_some();
    let (after_problem, before_problem) = problems(arm, set, before, &space, joint_deg)?;
    let after = match &after_problem {
        After::Set(p) => over_set::certify_set_accuracy_at(p, &list, settings),
        After::Box(p) => certify_tool_accuracy_at(p, &list, settings),
    };
    let before = before_problem
        .as_ref()
        .map(|p| certify_tool_accuracy_at(p, &list, settings));
    Ok(ToolAccuracyReport {
        space,
        joint_deg,
        after,
        before,
        over_set,
        configurations: Some(configurations_deg.len()),
    })
}

/// [`certify_tool_accuracy`] over the configurations `list` (thin joint boxes, radians, padded)
/// instead of the problem's joint box ([`calib_core::maximize_over_list`]).
fn certify_tool_accuracy_at(
    problem: &ToolAccuracyProblem,
    list: &[[Interval; MAX_JOINTS]],
    settings: &ToolAccuracySettings,
) -> ToolBracket {
    let start = Instant::now();
    let m = maximize_over_list(
        || ToolError {
            problem,
            enough: Cell::new(0.0),
            rel_tol: settings.rel_tol,
            directions: DirectionCache::default(),
        },
        list,
        &MaximumSettings {
            rel_tol: settings.rel_tol,
            abs_tol: 0.0,
            max_boxes: list.len(),
        },
    );
    let worst = problem.instance_without_search(&m.argmax);
    bracket_of(problem, &m, worst, settings, start)
}

/// The bracket of a maximisation by [`ToolError`]: its lower bound re-attained by the instance
/// `worst` (rounded down), its frontier in degrees.
fn bracket_of(
    problem: &ToolAccuracyProblem,
    m: &Maximum<MAX_JOINTS>,
    worst: ToolInstance,
    settings: &ToolAccuracySettings,
    start: Instant,
) -> ToolBracket {
    let lower = worst.value;
    ToolBracket {
        upper: m.upper.max(lower),
        lower,
        worst: Some(worst).filter(|w| w.value > 0.0),
        frontier_deg: frontier_deg(&m.frontier, problem.joints),
        converged: m.converged || lower >= m.upper / (1.0 + settings.rel_tol),
        boxes: m.boxes,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// The problems of [`tool_accuracy`] and [`tool_accuracy_at`] on `space`: the calibrated
/// `arm` over its certified `set` (its box without one) and, with `before`, the uncalibrated
/// robot over its box.
fn problems(
    arm: &Arm,
    set: Option<crate::certification::ArmSet>,
    before: Option<&Arm>,
    space: &JointSpace,
    joint_deg: f64,
) -> Result<(After, Option<ToolAccuracyProblem>), ArmError> {
    let after = match set {
        Some(set) => After::Set(Box::new(over_set::SetToolAccuracy::new(
            arm, set, space, joint_deg,
        )?)),
        None => After::Box(Box::new(ToolAccuracyProblem::new(arm, space, joint_deg)?)),
    };
    let before = before
        .map(|b| ToolAccuracyProblem::new(b, space, joint_deg))
        .transpose()?;
    Ok((after, before))
}

/// A frontier box of padded joints (radians) in degrees, for the arm's `joints`.
pub(crate) fn frontier_deg(frontier: &[Interval; MAX_JOINTS], joints: usize) -> Vec<[f64; 2]> {
    frontier[..joints]
        .iter()
        .map(|v| {
            let d = rad_to_deg(*v);
            [d.inf(), d.sup()]
        })
        .collect()
}

/// The calibrated robot's problem: over its certified set, or over its box.
enum After {
    Set(Box<over_set::SetToolAccuracy>),
    Box(Box<ToolAccuracyProblem>),
}

/// The tool-point accuracy of a robot file after calibration and, when given, before it: what
/// `arm accuracy` reports.
#[derive(Clone, Debug, PartialEq)]
pub struct ToolAccuracyReport {
    /// The joint space (degrees).
    pub space: JointSpace,
    /// The joint error half-width (degrees) added to every `theta_i`.
    pub joint_deg: f64,
    /// The calibrated robot's bracket.
    pub after: ToolBracket,
    /// The uncalibrated robot's bracket.
    pub before: Option<ToolBracket>,
    /// Whether the calibrated robot's bracket is taken over its certified set (else over the
    /// robot file's box: a file without a set).
    pub over_set: bool,
    /// With a task ([`tool_accuracy_at`]): how many configurations were bounded, each as given
    /// (`space` is then their hull, not a box the bounds hold over).
    pub configurations: Option<usize>,
}

impl ToolAccuracyReport {
    /// The joints' error bound (degrees) as printed: as written when short, else rounded up to
    /// six decimals (a bound widened by a conversion's rounding, 0.001000000000113687, prints
    /// 0.001001).
    pub fn joint_error_text(&self) -> String {
        let exact = format!("{}", self.joint_deg);
        if exact.len() <= 10 {
            exact
        } else {
            calib_pipeline::html::rounded_to(self.joint_deg, 6, false)
        }
    }

    /// How much calibration improved the worst tool-point error: `before.lower / after.upper`,
    /// a proved factor (the uncalibrated error reaches `before.lower`, the calibrated one stays
    /// below `after.upper`).
    pub fn improvement(&self) -> Option<f64> {
        let b = self.before.as_ref()?;
        (self.after.upper > 0.0).then(|| b.lower / self.after.upper)
    }

    /// The JSON report: `joint_space` (`q1..qN` as `[lo, hi]` degrees), `joint_error_deg`,
    /// `position` and `before` (each `upper`, `lower`, `ratio`, `converged`, `boxes`, `seconds`,
    /// `frontier_deg` and `worst`: `joints_deg`, `error_mm`, `value` and `theta` by parameter name
    /// in the files' units, the joint error included in `theta_i`), `improvement`.
    pub fn to_json(&self, names: &[String], units: &[Unit]) -> String {
        let finite = |v: f64| if v.is_finite() { json!(v) } else { json!(null) };
        let bracket = |b: &ToolBracket| {
            let worst = b.worst.as_ref().map(|w| {
                let theta: serde_json::Map<String, serde_json::Value> = names
                    .iter()
                    .zip(units)
                    .zip(&w.theta)
                    .map(|((n, u), t)| {
                        let v = match u {
                            Unit::Deg => to_deg(t.mid()),
                            Unit::Mm => t.mid(),
                        };
                        (n.clone(), json!(v))
                    })
                    .collect();
                json!({
                    "joints_deg": w.joints_deg,
                    "error_mm": w.error,
                    "value": w.value,
                    "theta": theta,
                })
            });
            json!({
                "upper": finite(b.upper),
                "lower": b.lower,
                "ratio": finite(b.ratio()),
                "converged": b.converged,
                "boxes": b.boxes,
                "seconds": b.seconds,
                "frontier_deg": b.frontier_deg,
                "worst": worst,
            })
        };
        let space: serde_json::Map<String, serde_json::Value> = self
            .space
            .ranges_deg
            .iter()
            .enumerate()
            .map(|(k, r)| (format!("q{}", k + 1), json!(r)))
            .collect();
        let over = |set: bool| if set { "certified set" } else { "box" };
        let mut position = bracket(&self.after);
        position["over"] = json!(over(self.over_set));
        let before = self.before.as_ref().map(|b| {
            let mut v = bracket(b);
            v["over"] = json!("box");
            v
        });
        let report = json!({
            "joint_space": space,
            "joint_error_deg": self.joint_deg,
            "over": over(self.over_set),
            "position": position,
            "before": before,
            "improvement": self.improvement().map(finite),
        });
        let mut report = report;
        if let Some(n) = self.configurations {
            // The bounds hold at these configurations only; `joint_space` is their hull.
            report["configurations"] = json!(n);
        }
        serde_json::to_string_pretty(&report).unwrap_or_default() + "\n"
    }
}
