//! The accuracy certificate (`gough accuracy`): how far the leg lengths a controller commands
//! can be from those the real robot needs, anywhere in its workspace, for every geometry its
//! certified box allows.
//!
//! The controller loads the nominal values `θ̂` of a robot file; the real robot has some `θ*` in
//! the file's box (each parameter within its radius). For every pose `X` of the [`Workspace`] the
//! controller commands `L_i(X; θ̂)` while the real leg needs `L_i(X; θ*)`. The **leg-length
//! error** `max |L_i(X; θ*) - L_i(X; θ̂)|` over the workspace and the box is bracketed per leg
//! between an upper bound proved over the whole workspace and a lower bound attained by an
//! explicit instance `(X, θ*)` — the truth is proved to lie between them.
//!
//! Each maximum is a [`calib_core::maximize`] branch and bound over the box of poses `(p, q)`
//! (`q` the Rodrigues vector, `|q| <= tan(tilt/2)`) with the enclosures of [`AccuracyProblem`]: a box
//! proved to hold no pose of the workspace counts as error 0, a box only partly inside is bounded
//! whole (the upper bound may then cover a superset at the workspace's boundary, never less than
//! the workspace).
#[doc(hidden)]
pub mod enclosure;
#[doc(hidden)]
pub mod model;
#[doc(hidden)]
pub(crate) mod over_set;
#[doc(hidden)]
pub mod pose_bound;
#[doc(hidden)]
pub mod pose_chart;
#[doc(hidden)]
pub mod pose_error;

pub use enclosure::{AccuracyProblem, Instance, LegSet, PoseBox, PoseVector, REFINED_SET_PIECES};
pub use model::{
    leg_curvature, leg_length_error, leg_reading, LegCurvature, LegLengthError, LegReading,
};
pub use pose_bound::{
    pose_error_bounds, reached_change, PoseBoundSettings, PoseErrorBounds, ReachedChange,
};
pub use pose_error::{
    pose_error_instances, pose_errors, prove_instance, worst_instance, PoseErrorInstance,
    PoseErrorKind, PoseErrors,
};

use crate::workspace::Workspace;
use calib_core::{maximize, Interval, MaximumSettings, Objective};
use rayon::prelude::*;
use std::time::Instant;

/// One leg's length error as a maximisation over the poses.
struct LegLengthObjective<'a> {
    problem: &'a AccuracyProblem,
    leg: usize,
    /// Whether to raise the lower bound by the local search (it may leave a sub-domain).
    search: bool,
}

impl Objective<6> for LegLengthObjective<'_> {
    fn at(&self, x: &PoseVector) -> Interval {
        let value = self.enclose(&x.map(Interval::point));
        if !self.problem.over_set(self.leg) {
            return value;
        }
        // Over a set the enclosure's lower end is not attained: the catalogue's certified
        // geometries are.
        let attained = self.problem.attained(self.leg, x);
        if self.problem.proved_feasible(x) && attained <= value.sup() {
            Interval::new(attained, value.sup())
        } else {
            Interval::new(0.0, value.sup())
        }
    }

    fn enclose(&self, x: &PoseBox) -> Interval {
        self.enclose_up_to(x, 0.0)
    }

    fn enclose_up_to(&self, x: &PoseBox, enough: f64) -> Interval {
        if !self.problem.may_be_feasible(x) {
            // No pose of the workspace here: it does not raise the error over the workspace.
            return Interval::ZERO;
        }
        // The poses of the workspace in the box lie in its part within the tilt.
        let Some(x) = self.problem.within_tilt(x) else {
            return Interval::ZERO;
        };
        let value = self.problem.leg_bounds_up_to(self.leg, &x, enough);
        if value.sup().is_nan() || value.inf().is_nan() {
            Interval::new(0.0, f64::INFINITY)
        } else {
            value
        }
    }

    fn improve(&self, x: &PoseVector) -> Option<(PoseVector, f64)> {
        if !self.search {
            return None;
        }
        self.problem
            .instance(self.leg, x)
            .map(|i| (i.pose, i.value))
    }
}

/// A certified bracket of one error.
#[derive(Clone, Debug, PartialEq)]
pub struct Bracket {
    /// Proved over the whole workspace (cm).
    pub upper: f64,
    /// Attained by `worst` (0 when no pose of the workspace was found).
    pub lower: f64,
    /// The worst instance found: `lower` is its error.
    pub worst: Option<Instance>,
    /// Where a larger error could still hide: the pose box that gives `upper`.
    pub frontier: PoseBox,
    /// Whether `upper <= (1 + rel_tol) lower` was reached (else the box budget ran out).
    pub converged: bool,
    /// Pose boxes examined.
    pub boxes: usize,
}

impl Bracket {
    /// `upper / lower` (`+∞` without a positive lower bound).
    pub fn ratio(&self) -> f64 {
        calib_core::bracket_ratio(self.upper, self.lower)
    }
}

/// When to stop the branch and bound of each error.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AccuracySettings {
    /// Stop at `upper <= (1 + rel_tol) lower` (default 0.04: brackets within 1.05 with margin).
    pub rel_tol: f64,
    /// Examine at most this many pose boxes per error of a leg over its box (default 300 000).
    pub max_boxes: usize,
    /// Examine at most this many pose boxes per error of a leg over its certified set (default
    /// 1 000: each costs a few dozen small linear programs, where a box costs a few interval
    /// evaluations).
    pub max_set_boxes: usize,
    /// Stop the platform pose errors' upper bounds after about this many seconds per robot
    /// (default 30; [`PoseBoundSettings::max_seconds`]): the bounds stay valid, only less tight.
    pub pose_seconds: f64,
    /// Cells per side of the certificate's error map over `x`–`y` (default [`MAP_CELLS`]; each
    /// cell, in each of [`MAP_SLABS`] slabs of heights, is a short branch and bound per leg).
    pub map_cells: usize,
}

impl Default for AccuracySettings {
    fn default() -> Self {
        AccuracySettings {
            rel_tol: 0.04,
            max_boxes: 300_000,
            max_set_boxes: 1000,
            pose_seconds: PoseBoundSettings::default().max_seconds,
            map_cells: MAP_CELLS,
        }
    }
}

/// The accuracy of a robot file on a workspace.
#[derive(Clone, Debug, PartialEq)]
pub struct Accuracy {
    /// Per leg, the leg-length error (cm).
    pub leg_length: Vec<Bracket>,
    /// The platform's position and orientation errors: proved instances (lower bounds), when
    /// computed (see [`accuracy_report`]).
    pub pose: Option<PoseErrors>,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// Brackets the leg-length error of every leg of the problem (over each leg's certified set, or
/// its box) on its workspace (see the module documentation), the legs in parallel.
pub fn certify_accuracy(problem: &AccuracyProblem, settings: &AccuracySettings) -> Accuracy {
    let start = Instant::now();
    let leg_length = (0..problem.legs())
        .into_par_iter()
        .map(|leg| bracket(problem, leg, settings))
        .collect();
    Accuracy {
        leg_length,
        pose: None,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// What `gough accuracy` computes: the leg-length brackets and the platform's pose errors of
/// the calibrated robot (`after`: over its certified sets, where it has them) and, when given,
/// of the robot `before` calibration (over its boxes), with the actuator error `± len` when
/// known (0 otherwise), and the error map when `map` is set. Both problems share a workspace.
pub fn accuracy_report(
    after: &AccuracyProblem,
    before: Option<&AccuracyProblem>,
    actuator: Option<f64>,
    settings: &AccuracySettings,
    map: bool,
) -> AccuracyReport {
    let eps = actuator.unwrap_or(0.0);
    let assess = |problem: &AccuracyProblem| {
        let mut a = certify_accuracy(problem, settings);
        let pose = pose_errors(
            problem,
            eps,
            &PoseBoundSettings {
                rel_tol: settings.rel_tol,
                max_seconds: settings.pose_seconds,
                ..PoseBoundSettings::default()
            },
        );
        a.seconds += pose.seconds;
        a.pose = Some(pose);
        a
    };
    AccuracyReport {
        workspace: *after.workspace(),
        after: assess(after),
        before: before.map(assess),
        actuator,
        map: map.then(|| error_map(after, settings.map_cells, MAP_SLABS)),
        over_set: (0..after.legs()).map(|i| after.over_set(i)).collect(),
    }
}

/// Brackets the length error of leg `leg` (0-based) over the workspace.
pub fn bracket(problem: &AccuracyProblem, leg: usize, settings: &AccuracySettings) -> Bracket {
    bracket_within(problem, leg, None, settings, true)
}

/// [`bracket`] over the poses whose positions lie in `positions` (the workspace's when `None`),
/// with the local search for instances when `search`.
fn bracket_within(
    problem: &AccuracyProblem,
    leg: usize,
    positions: Option<[Interval; 3]>,
    settings: &AccuracySettings,
    search: bool,
) -> Bracket {
    let mut domain = problem.domain();
    if let Some(p) = positions {
        domain[..3].copy_from_slice(&p);
    }
    if problem.over_set(leg) && search {
        let engine = calib_pipeline::accuracy::BracketSettings {
            rel_tol: settings.rel_tol,
            max_boxes: settings.max_set_boxes,
        };
        if let Some(b) = over_set::bracket_leg_over_set(problem, leg, &domain, &engine) {
            return b;
        }
    }
    let objective = LegLengthObjective {
        problem,
        leg,
        search,
    };
    let m = maximize(
        &objective,
        &domain,
        &MaximumSettings {
            rel_tol: settings.rel_tol,
            abs_tol: 0.0,
            max_boxes: if problem.over_set(leg) {
                settings.max_set_boxes
            } else {
                settings.max_boxes
            },
        },
    );
    let worst = if search {
        problem.instance(leg, &m.argmax).filter(|i| i.value > 0.0)
    } else {
        None
    };
    Bracket {
        upper: m.upper,
        lower: worst
            .as_ref()
            .map_or(m.lower.max(0.0), |i| i.value.max(m.lower)),
        worst,
        frontier: m.frontier,
        converged: m.converged,
        boxes: m.boxes,
    }
}

/// A pose vector as position, unit axis and angle in degrees (axis `z` for no rotation).
pub fn axis_angle(x: &PoseVector) -> ([f64; 3], [f64; 3], f64) {
    let q = [x[3], x[4], x[5]];
    let n = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
    let p = [x[0], x[1], x[2]];
    if n == 0.0 {
        return (p, [0.0, 0.0, 1.0], 0.0);
    }
    (p, q.map(|v| v / n), 2.0 * n.atan().to_degrees())
}

/// A pose in words: `p = (x, y, z) cm rotated A° about (u, v, w)`.
pub fn pose_words(x: &PoseVector) -> String {
    let (p, axis, angle) = axis_angle(x);
    format!(
        "p = ({:.3}, {:.3}, {:.3}) cm rotated {:.3}° about ({:.3}, {:.3}, {:.3})",
        p[0], p[1], p[2], angle, axis[0], axis[1], axis[2]
    )
}

/// Why no upper bound of the platform's pose errors is claimed, in words (`None` when they are
/// proved): a box of poses of the finest size whose reached pose could not be enclosed, or a
/// budget that ended first, with the share of the workspace settled so far. The box is named by
/// its centre, its rotation brought within the workspace's `tilt_deg`.
pub fn unproved_words(b: &PoseErrorBounds, tilt_deg: f64) -> Option<String> {
    if b.position.is_some() && b.orientation_deg.is_some() {
        return None;
    }
    let Some(x) = b.unproved_at else {
        return Some("no box of poses was bounded".to_string());
    };
    let mut centre = x.map(|v| v.mid());
    let q = (centre[3].powi(2) + centre[4].powi(2) + centre[5].powi(2)).sqrt();
    let most = (tilt_deg.to_radians() / 2.0).tan();
    if q > most {
        for c in &mut centre[3..] {
            *c *= most / q;
        }
    }
    let near = pose_words(&centre);
    Some(if b.unprovable {
        format!(
            "the reached pose could not be enclosed for commanded poses near {near}, even in the \
             finest box of poses (a singular pose, or errors so large that the legs' directions \
             change across them): narrower geometry boxes, from more measurements, or a smaller \
             workspace may be bounded"
        )
    } else {
        let share = 100.0 * b.settled_share;
        let settled = if share > 0.0 && share < 0.01 {
            "under 0.01%".to_string()
        } else {
            format!("{share:.2}%")
        };
        format!(
            "the budget ended with {settled} of the workspace settled (by volume of its box of \
             poses; {} boxes of poses), the reached pose not yet enclosed for commanded poses \
             near {near}: a larger budget (`--pose-seconds`), narrower \
             geometry boxes (from more measurements) or a smaller workspace may prove it",
            b.pose_boxes
        )
    })
}

/// The leg-length brackets of a robot file after calibration and, when given, of the robot
/// before it (the design nominal with its prior box): what `gough accuracy` reports.
#[derive(Clone, Debug, PartialEq)]
pub struct AccuracyReport {
    /// The workspace.
    pub workspace: Workspace,
    /// The calibrated robot's accuracy.
    pub after: Accuracy,
    /// The uncalibrated robot's accuracy.
    pub before: Option<Accuracy>,
    /// The actuator error half-width, when known: the length a leg reaches then differs from the
    /// one it needs by at most the leg-length error plus this.
    pub actuator: Option<f64>,
    /// Where in the workspace the error is large (see [`error_map`]), when computed.
    pub map: Option<Vec<MapSlab>>,
    /// Per leg, whether the calibrated robot's errors are taken over its certified set (else
    /// over the robot file's box: a file without a set).
    pub over_set: Vec<bool>,
}

/// How much calibration improved leg `i`: `before.lower / after.upper`, a proved factor (the
/// uncalibrated error is at least `before.lower`, the calibrated one at most `after.upper`).
pub fn improvement(before: &Bracket, after: &Bracket) -> f64 {
    if after.upper > 0.0 {
        before.lower / after.upper
    } else {
        f64::INFINITY
    }
}

/// "reduced the platform's worst position error at least …-fold and …" for the proved factors of
/// [`pose_improvement`], or `None` when neither factor is proved above 1 (a factor below 1 is
/// no improvement).
pub fn improvement_words([position, orientation]: [Option<f64>; 2]) -> Option<String> {
    let parts: Vec<String> = [(position, "position"), (orientation, "orientation")]
        .into_iter()
        .filter_map(|(f, name)| {
            f.filter(|f| *f > 1.0).map(|f| {
                let at_least = calib_pipeline::html::rounded_to(f.next_down(), 1, true);
                format!("worst {name} error at least {at_least}-fold")
            })
        })
        .collect();
    (!parts.is_empty()).then(|| {
        format!(
            "reduced the platform's {} (proved: the uncalibrated robot's lower bound over the \
             calibrated one's upper bound)",
            parts.join(" and ")
        )
    })
}

/// How much calibration improved the platform's position and orientation errors:
/// `before`'s lower bound over `after`'s upper bound, each a proved factor (`None` where either
/// is not proved).
pub fn pose_improvement(before: &PoseErrors, after: &PoseErrors) -> [Option<f64>; 2] {
    let upper = after.bounds.as_ref();
    let factor = |lower: Option<f64>, upper: Option<f64>| match (lower, upper) {
        (Some(l), Some(u)) if u > 0.0 => Some(l / u),
        _ => None,
    };
    [
        factor(
            before.position.as_ref().map(|i| i.position),
            upper.and_then(|b| b.position),
        ),
        factor(
            before.orientation.as_ref().map(|i| i.orientation_deg),
            upper.and_then(|b| b.orientation_deg),
        ),
    ]
}

/// What a bound is taken over, as the JSON says it: `"certified set"` or `"box"`.
pub fn over_words(over_set: bool) -> &'static str {
    if over_set {
        "certified set"
    } else {
        "box"
    }
}

fn bracket_json(leg: usize, b: &Bracket, over_set: bool) -> serde_json::Value {
    let worst = b.worst.as_ref().map(|w| {
        let (p, axis, angle_deg) = axis_angle(&w.pose);
        serde_json::json!({
            "pose": { "p": p, "axis": axis, "angle_deg": angle_deg, "rodrigues": &w.pose[3..] },
            "theta": w.theta.iter().map(|v| v.mid()).collect::<Vec<_>>(),
            "error": w.value,
        })
    });
    serde_json::json!({
        "leg": leg + 1,
        "over": over_words(over_set),
        "upper": b.upper,
        "lower": b.lower,
        "ratio": b.ratio(),
        "converged": b.converged,
        "boxes": b.boxes,
        "worst": worst,
    })
}

/// The JSON of a pose error: `upper` (null when not proved; then `upper_unproved_at` names the
/// box of poses where the reached pose could not be enclosed, and `upper_unproved` says why:
/// `finest`, true when that box is of the finest size, false when the budget ended first, and
/// `settled_share`, the share of the workspace settled), `lower` and `worst` (the commanded
/// pose, the true geometry per leg, the actuator errors, the reached pose).
fn pose_json(
    i: Option<&PoseErrorInstance>,
    unproved: Option<&PoseVector>,
    bounds: Option<&PoseErrorBounds>,
    kind: PoseErrorKind,
    over: &str,
) -> serde_json::Value {
    let worst = i.map(|w| {
        let (p, axis, angle_deg) = axis_angle(&w.commanded);
        let reached: Vec<[f64; 2]> = w.reached.iter().map(|v| [v.inf(), v.sup()]).collect();
        serde_json::json!({
            "pose": { "p": p, "axis": axis, "angle_deg": angle_deg, "rodrigues": &w.commanded[3..] },
            "theta": w.theta.iter().map(|t| t.map(|v| v.mid())).collect::<Vec<_>>(),
            "actuator": w.actuator,
            "reached": { "d": &reached[..3], "w": &reached[3..] },
            "position": w.position,
            "orientation_deg": w.orientation_deg,
        })
    });
    let lower = i.map(|w| match kind {
        PoseErrorKind::Position => w.position,
        PoseErrorKind::Orientation => w.orientation_deg,
    });
    let unproved = unproved.map(|x| {
        let (p, axis, angle_deg) = axis_angle(x);
        serde_json::json!({ "p": p, "axis": axis, "angle_deg": angle_deg, "rodrigues": &x[3..] })
    });
    let upper = bounds.and_then(|b| match kind {
        PoseErrorKind::Position => b.position,
        PoseErrorKind::Orientation => b.orientation_deg,
    });
    let upper_unproved = bounds.and_then(|b| b.unproved_at).map(|x| {
        let range = |v: &[Interval]| v.iter().map(|c| [c.inf(), c.sup()]).collect::<Vec<_>>();
        serde_json::json!({ "p": range(&x[..3]), "rodrigues": range(&x[3..]) })
    });
    let settled = bounds
        .filter(|_| upper.is_none())
        .map(|b| serde_json::json!({ "finest": b.unprovable, "settled_share": b.settled_share }));
    serde_json::json!({
        "over": over,
        "upper": upper,
        "lower": lower,
        "ratio": upper.zip(lower).map(|(u, l)| calib_core::bracket_ratio(u, l)),
        "worst": worst,
        "unproved_at": unproved,
        "upper_unproved_at": upper_unproved,
        "upper_unproved": settled,
    })
}

/// What the platform's pose errors are taken over: `"certified set"` when every leg has one,
/// `"box"` when none has, `"certified set and box"` for a mix.
fn pose_over(over_set: &[bool]) -> &'static str {
    match (over_set.iter().all(|o| *o), over_set.iter().any(|o| *o)) {
        (true, _) => "certified set",
        (false, false) => "box",
        (false, true) => "certified set and box",
    }
}

fn pose_fields(a: &Accuracy, over_set: &[bool]) -> (serde_json::Value, serde_json::Value) {
    let pose = a.pose.as_ref();
    let over = pose_over(over_set);
    (
        pose_json(
            pose.and_then(|p| p.position.as_ref()),
            pose.and_then(|p| p.position_unproved.as_ref()),
            pose.and_then(|p| p.bounds.as_ref()),
            PoseErrorKind::Position,
            over,
        ),
        pose_json(
            pose.and_then(|p| p.orientation.as_ref()),
            pose.and_then(|p| p.orientation_unproved.as_ref()),
            pose.and_then(|p| p.bounds.as_ref()),
            PoseErrorKind::Orientation,
            over,
        ),
    )
}

fn legs_json(a: &Accuracy, over_set: &[bool]) -> Vec<serde_json::Value> {
    a.leg_length
        .iter()
        .enumerate()
        .map(|(i, b)| bracket_json(i, b, over_set.get(i).copied().unwrap_or(false)))
        .collect()
}

impl AccuracyReport {
    /// With the actuator error known: how far a leg's reached length can be from the length it
    /// needs, anywhere in the workspace (the largest upper bound plus the actuator error).
    pub fn reach(&self) -> Option<f64> {
        let worst = self
            .after
            .leg_length
            .iter()
            .fold(0.0f64, |m, b| m.max(b.upper));
        self.actuator
            .map(|len| (Interval::point(worst) + Interval::point(len)).sup())
    }

    /// [`pose_improvement`] of the report's robots, when both were assessed.
    pub fn pose_improvement(&self) -> Option<[Option<f64>; 2]> {
        let before = self.before.as_ref()?.pose.as_ref()?;
        Some(pose_improvement(before, self.after.pose.as_ref()?))
    }

    /// The JSON of `gough accuracy --json` (schema version 1; cm and degrees): `workspace`,
    /// `leg_length` (per leg `upper`, `lower`, `ratio`, `converged`, `boxes` and `worst`: the
    /// pose as `p`, `axis`, `angle_deg` and `rodrigues`, the true geometry `theta` in the order
    /// of [`crate::PARAMETER_NAMES`], its `error`), `position` and `orientation` (`upper`: proved
    /// over the whole workspace, or null with `upper_unproved_at` naming the box of poses where
    /// the reached pose could not be enclosed and `upper_unproved` saying why: `finest` — that
    /// box is of the finest size, else the budget ended first — and `settled_share`, the share
    /// of the workspace settled; `ratio`; `lower`: attained by `worst`, whose
    /// reached pose is proved — the commanded pose, `theta` per leg, `actuator` errors, `reached`
    /// as enclosures of the move `d` and the rotation error's Rodrigues vector `w`; without an
    /// instance, `unproved_at`: the commanded pose whose path could not be proved), `before`
    /// (the same for the uncalibrated robot, or null), `improvement` (per leg, the proved
    /// factor), `pose_improvement` (`position` and `orientation`: the proved factors of
    /// [`pose_improvement`], null where not proved; null without `before`) and `actuator`.
    pub fn json(&self) -> serde_json::Value {
        let w = &self.workspace;
        let (position, orientation) = pose_fields(&self.after, &self.over_set);
        let boxes = vec![false; self.over_set.len()];
        serde_json::json!({
            "version": 1,
            "workspace": {
                "x": w.x, "y": w.y, "z": w.z, "tilt_deg": w.tilt_deg, "stroke": w.stroke,
            },
            "param_order": crate::PARAMETER_NAMES,
            "over": pose_over(&self.over_set),
            "leg_length": legs_json(&self.after, &self.over_set),
            "position": position,
            "orientation": orientation,
            "before": self.before.as_ref().map(|b| {
                let (position, orientation) = pose_fields(b, &boxes);
                serde_json::json!({
                    "over": "box",
                    "leg_length": legs_json(b, &boxes),
                    "position": position,
                    "orientation": orientation,
                })
            }),
            "improvement": self.before.as_ref().map(|b| {
                b.leg_length
                    .iter()
                    .zip(&self.after.leg_length)
                    .map(|(b, a)| improvement(b, a))
                    .collect::<Vec<_>>()
            }),
            "pose_improvement": self.pose_improvement().map(|[p, o]| {
                serde_json::json!({ "position": p, "orientation": o })
            }),
            "actuator": self.actuator,
            "seconds": self.after.seconds + self.before.as_ref().map_or(0.0, |b| b.seconds),
        })
    }
}

impl AccuracyReport {
    /// The certificate's section: the brackets per leg (with the uncalibrated robot's and the
    /// proved improvement when known) and the worst instance, in words.
    pub fn section(&self) -> calib_pipeline::html::Section {
        let mut tables = vec![self.leg_table()];
        if let Some(pose) = &self.after.pose {
            tables.push(self.pose_table(pose));
        }
        calib_pipeline::html::Section {
            heading: "Accuracy over the workspace".to_string(),
            paragraphs: self.paragraphs(),
            tables,
            figures: self
                .error_map()
                .into_iter()
                .chain([self.leg_brackets()])
                .collect(),
        }
    }

    /// The certificate's figure of the legs' brackets after calibration, on one axis.
    fn leg_brackets(&self) -> calib_pipeline::html::Figure {
        let bars: Vec<calib_pipeline::html::BracketBar> = self
            .after
            .leg_length
            .iter()
            .enumerate()
            .map(|(i, b)| calib_pipeline::html::BracketBar {
                label: format!("leg {}", i + 1),
                lower: b.lower,
                upper: b.upper,
            })
            .collect();
        calib_pipeline::html::brackets_figure(
            &bars,
            "cm",
            "Each leg's worst length error after calibration: solid up to what an explicit pose \
             and geometry reach (attained), light from there to the proved upper bound; the worst \
             error lies in the light part.",
        )
    }

    /// The certificate's table of the leg-length brackets: per leg its lower and upper bounds
    /// and their ratio, with the uncalibrated robot's upper bound and the proved improvement
    /// when known.
    fn leg_table(&self) -> (String, calib_pipeline::html::Table) {
        let mut header: Vec<String> = ["leg", "lower (cm)", "upper (cm)", "upper/lower"]
            .map(String::from)
            .to_vec();
        if self.before.is_some() {
            header.extend(["before: upper (cm)", "improvement (proved)"].map(String::from));
        }
        let rows = self
            .after
            .leg_length
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let mut row = vec![
                    (i + 1).to_string(),
                    calib_pipeline::html::rounded(b.lower, true),
                    calib_pipeline::html::rounded(b.upper, false),
                    format!("{:.3}", b.ratio()),
                ];
                if let Some(before) = &self.before {
                    let p = &before.leg_length[i];
                    row.push(calib_pipeline::html::rounded(p.upper, false));
                    row.push(format!(
                        "{}×",
                        calib_pipeline::html::rounded_to(improvement(p, b).next_down(), 1, true)
                    ));
                }
                row
            })
            .collect();
        (
            "Leg-length error per leg: the truth lies between lower and upper.".to_string(),
            calib_pipeline::html::Table { header, rows },
        )
    }

    /// The certificate's words: what the leg-length brackets mean over the workspace and the
    /// geometries, the reach with the actuators' error, what the pose brackets mean, and the
    /// proved improvement.
    fn paragraphs(&self) -> Vec<String> {
        let mut paragraphs = vec![self.workspace_paragraph()];
        if let (Some(len), Some(reach)) = (self.actuator, self.reach()) {
            paragraphs.push(format!(
                "With the actuators' error (± {len} cm), a leg's reached length is within \
                 {reach:.5} cm of the length it needs."
            ));
        }
        paragraphs.push(
            "The platform's position and orientation errors below are bracketed: each lower \
             bound is attained by an explicit instance (a commanded pose of the workspace, a \
             true geometry the data allow, actuator errors within their bounds) whose \
             reached pose is proved by interval Newton along the path from the commanded pose; \
             each upper bound is proved over the whole workspace (no path from a commanded pose \
             can leave a region whose boundary every leg excludes), where the reached pose can \
             be enclosed."
                .to_string(),
        );
        if let Some(words) = self.pose_improvement().and_then(improvement_words) {
            paragraphs.push(format!("Calibration {words}."));
        }
        paragraphs
    }

    /// What the leg-length brackets mean: over which workspace and which geometries the upper
    /// bound is proved and the lower bound attained.
    fn workspace_paragraph(&self) -> String {
        let w = &self.workspace;
        let geometries = match pose_over(&self.over_set) {
            "certified set" => {
                "for every geometry the measurements allow (the certified set: not its box, \
                 whose corners the data rule out)"
            }
            "box" => "for every geometry in the robot file's boxes (the file has no certified set)",
            _ => "for every geometry of the certified set (legs without one: of their boxes)",
        };
        format!(
            "Over the workspace (platform centre x in [{}, {}], y in [{}, {}], z in [{}, {}] cm, \
             rotation up to {}° about any axis{}), {geometries}, the length the controller \
             commands (from the calibrated values) differs from the length the real leg needs \
             by at most the upper bound — proved over the whole workspace — and by at least the \
             lower bound, attained at an explicit pose and a geometry proved consistent with the \
             measurements.",
            w.x[0],
            w.x[1],
            w.y[0],
            w.y[1],
            w.z[0],
            w.z[1],
            w.tilt_deg,
            w.stroke.map_or(String::new(), |[lo, hi]| format!(
                ", leg readings in [{lo}, {hi}] cm"
            ))
        )
    }

    /// The certificate's map of where the leg-length error can be large, when one was made (and
    /// could be drawn).
    fn error_map(&self) -> Option<calib_pipeline::html::Figure> {
        let svg = crate::plot::heat_maps(
            self.map.as_ref()?,
            "Certified upper bound of the worst leg's error",
            "cm",
        )
        .ok()?;
        Some(calib_pipeline::html::Figure {
            caption: "Where the leg-length error can be large: per cell of x–y and slab \
                      of heights, the proved upper bound of the worst leg's error over \
                      every rotation of the workspace (a coarse branch and bound per \
                      cell; white: no pose of the workspace)."
                .to_string(),
            svg,
        })
    }
}

impl AccuracyReport {
    /// The certificate's table of the platform's pose errors (lower bounds, before and after).
    fn pose_table(&self, pose: &PoseErrors) -> (String, calib_pipeline::html::Table) {
        let before = self.before.as_ref().and_then(|b| b.pose.as_ref());
        let cell = |p: &PoseErrors, kind: PoseErrorKind| {
            let (i, upper, unit) = match kind {
                PoseErrorKind::Position => (
                    p.position.as_ref().map(|i| i.position),
                    p.bounds.as_ref().and_then(|b| b.position),
                    " cm",
                ),
                PoseErrorKind::Orientation => (
                    p.orientation.as_ref().map(|i| i.orientation_deg),
                    p.bounds.as_ref().and_then(|b| b.orientation_deg),
                    "°",
                ),
            };
            let upper = upper.map_or("upper bound not proved".to_string(), |u| {
                format!("≤ {u:.4}{unit}")
            });
            let lower = i.map_or("no instance proved".to_string(), |l| {
                format!("≥ {l:.4}{unit}")
            });
            format!("{upper}, {lower}")
        };
        let mut header: Vec<String> = ["error", "after calibration", "at the commanded pose"]
            .map(String::from)
            .to_vec();
        if before.is_some() {
            header.push("before calibration".to_string());
        }
        let rows = [
            ("position", PoseErrorKind::Position),
            ("orientation", PoseErrorKind::Orientation),
        ]
        .map(|(name, kind)| {
            let pick = |p: &PoseErrors| match kind {
                PoseErrorKind::Position => p.position.clone(),
                PoseErrorKind::Orientation => p.orientation.clone(),
            };
            let at = pick(pose);
            let mut row = vec![
                name.to_string(),
                cell(pose, kind),
                at.as_ref()
                    .map_or(String::new(), |i| pose_words(&i.commanded)),
            ];
            if let Some(b) = before {
                row.push(cell(b, kind));
            }
            row
        })
        .to_vec();
        let unproved = pose
            .bounds
            .as_ref()
            .and_then(|b| unproved_words(b, self.workspace.tilt_deg))
            .map_or(String::new(), |why| {
                format!(" After calibration no upper bound is claimed: {why}.")
            });
        (
            format!(
                "Platform pose error: upper bounds proved over the whole workspace (where the \
                 reached pose could be enclosed), lower bounds attained by proved instances at \
                 the commanded poses shown.{unproved}"
            ),
            calib_pipeline::html::Table { header, rows },
        )
    }
}

/// Boxes per leg and cell of the error map (a leg over its box).
const MAP_BOXES: usize = 400;

/// Boxes per leg and cell of the error map, a leg over its set (each costs milliseconds).
const MAP_SET_BOXES: usize = 12;

/// The error map of the certificates: cells per side of the `x`–`y` grid, by default.
pub const MAP_CELLS: usize = 6;
/// The error map of the certificates: slabs of heights.
pub const MAP_SLABS: usize = 3;

/// One panel of the error map: a slab of heights, cut into cells over `x`–`y`.
#[derive(Clone, Debug, PartialEq)]
pub struct MapSlab {
    /// The slab's heights (cm).
    pub z: [f64; 2],
    /// The cells' edges along `x` and `y` (cm).
    pub x_edges: Vec<f64>,
    /// See `x_edges`.
    pub y_edges: Vec<f64>,
    /// Per cell (`[ix][iy]`), the proved upper bound of the largest leg-length error over the
    /// cell, the slab and every rotation of the workspace, any leg (cm; 0 where no pose of the
    /// workspace lies).
    pub upper: Vec<Vec<f64>>,
}

/// The certified upper bound of the worst leg's error per cell of an `n × n` grid over `x`–`y`,
/// in `slabs` slabs of heights: where in the workspace the error is large. Each cell's bound is a
/// short branch and bound of its own (`rel_tol` 0.2, 400 boxes per leg): proved, if coarser than
/// the brackets.
pub fn error_map(problem: &AccuracyProblem, n: usize, slabs: usize) -> Vec<MapSlab> {
    let domain = problem.domain();
    // The last edge is the domain's end exactly: the cells cover the domain.
    let edges = |v: Interval, k: usize| -> Vec<f64> {
        (0..=k)
            .map(|i| {
                if i == k {
                    v.sup()
                } else {
                    v.inf() + (v.sup() - v.inf()) * i as f64 / k as f64
                }
            })
            .collect()
    };
    let (xe, ye, ze) = (
        edges(domain[0], n),
        edges(domain[1], n),
        edges(domain[2], slabs),
    );
    let settings = AccuracySettings {
        rel_tol: 0.2,
        max_boxes: MAP_BOXES,
        max_set_boxes: MAP_SET_BOXES,
        ..AccuracySettings::default()
    };
    (0..slabs)
        .map(|s| {
            let upper = (0..n)
                .into_par_iter()
                .map(|ix| {
                    (0..n)
                        .map(|iy| {
                            let cell = [
                                Interval::new(xe[ix], xe[ix + 1]),
                                Interval::new(ye[iy], ye[iy + 1]),
                                Interval::new(ze[s], ze[s + 1]),
                            ];
                            (0..problem.legs())
                                .map(|leg| {
                                    bracket_within(problem, leg, Some(cell), &settings, false).upper
                                })
                                .fold(0.0, f64::max)
                        })
                        .collect()
                })
                .collect();
            MapSlab {
                z: [ze[s], ze[s + 1]],
                x_edges: xe.clone(),
                y_edges: ye.clone(),
                upper,
            }
        })
        .collect()
}
