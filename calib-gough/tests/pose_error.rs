//! The platform pose-error instances of the accuracy certificate: on random robots and
//! workspaces each instance is rechecked by an independent forward kinematics (rotation vectors
//! and `nalgebra` rotations, Newton with a finite-difference Jacobian along its own homotopy):
//! the commanded pose lies in the workspace, the geometry in the box, the actuator errors within
//! their bound, the reached pose inside the proved enclosure, and its errors at least the lower
//! bounds. The search beats random sampling; a workspace at a singular pose proves nothing.

use crate::support;

use calib_core::{Interval, Model};
use calib_gough::accuracy::{
    accuracy_report, axis_angle, pose_error_bounds, pose_error_instances, pose_errors,
    unproved_words, AccuracyProblem, AccuracySettings, PoseBoundSettings, PoseErrorBounds,
    PoseErrorInstance, ReachedChange,
};
use calib_gough::files::LegSpec;
use calib_gough::geometry::{leg_reading, Leg, Pose};
use calib_gough::simulate::builtin_hexapod;
use calib_gough::workspace::Workspace;
use nalgebra::{Matrix6, Rotation3, Vector3, Vector6};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use support::random_workspace;

fn robot(radius: f64) -> Vec<LegSpec> {
    builtin_hexapod()
        .into_iter()
        .map(|nominal| LegSpec {
            nominal,
            radius: [radius; 7],
        })
        .collect()
}

/// The built-in hexapod (the geometry of `sample21`) with the boxes 21 poses of the simulator's
/// workspace leave: `a_z` and `l` known only to ± 0.1 cm, which its nearly vertical legs turn
/// into centimetres and degrees at the platform.
pub(crate) fn centimetre_robot() -> Vec<LegSpec> {
    builtin_hexapod()
        .into_iter()
        .map(|nominal| LegSpec {
            nominal,
            radius: [0.02, 0.02, 0.1, 0.01, 0.01, 0.05, 0.1],
        })
        .collect()
}

/// The pose `(p + d, Rot(φ) R)` of the commanded pose `(p, R)`, as a [`Pose`].
fn moved(p: &Vector3<f64>, r: &Rotation3<f64>, x: &Vector6<f64>) -> Pose {
    let rot = Rotation3::from_scaled_axis(Vector3::new(x[3], x[4], x[5])) * r;
    let (axis, angle) = rot
        .axis_angle()
        .map_or(([0.0, 0.0, 1.0], 0.0), |(a, t)| ([a.x, a.y, a.z], t));
    Pose {
        p: [p.x + x[0], p.y + x[1], p.z + x[2]],
        axis,
        angle_deg: angle.to_degrees(),
    }
}

/// The reached move `(d, φ)` (`φ` the rotation vector of the rotation error), by Newton along
/// `t ↦ L(X'; θ*) = (1 - t) L(X; θ*) + t (L(X; θ̂) + e)` in 200 steps.
fn reached(spec: &[LegSpec], i: &PoseErrorInstance) -> Vector6<f64> {
    let (p, axis, angle) = axis_angle(&i.commanded);
    let commanded = Pose {
        p,
        axis,
        angle_deg: angle,
    };
    let p = Vector3::from(p);
    let r = Rotation3::from_axis_angle(
        &nalgebra::Unit::new_normalize(Vector3::from(axis)),
        angle.to_radians(),
    );
    let truth: Vec<Leg> = i
        .theta
        .iter()
        .map(|t| Leg::from_params(&t.map(|v| v.mid())))
        .collect();
    let start: Vec<f64> = truth.iter().map(|l| leg_reading(l, &commanded)).collect();
    let end: Vec<f64> = spec
        .iter()
        .zip(&i.actuator)
        .map(|(s, e)| leg_reading(&s.nominal, &commanded) + e)
        .collect();
    let residual = |x: &Vector6<f64>, t: f64| {
        let pose = moved(&p, &r, x);
        Vector6::from_fn(|k, _| {
            leg_reading(&truth[k], &pose) - (start[k] + t * (end[k] - start[k]))
        })
    };
    let mut x = Vector6::zeros();
    for step in 1..=200 {
        let t = step as f64 / 200.0;
        for _ in 0..20 {
            let f = residual(&x, t);
            let mut jac = Matrix6::zeros();
            for k in 0..6 {
                let mut h = Vector6::zeros();
                h[k] = 1e-7;
                let col = (residual(&(x + h), t) - residual(&(x - h), t)) / 2e-7;
                jac.set_column(k, &col);
            }
            let dx = jac.lu().solve(&f).expect("the path is regular");
            x -= dx;
            if dx.norm() < 1e-13 {
                break;
            }
        }
    }
    x
}

fn recheck(spec: &[LegSpec], workspace: &Workspace, eps: f64, i: &PoseErrorInstance) {
    let [px, py, pz, ..] = i.commanded;
    for (v, [lo, hi]) in [(px, workspace.x), (py, workspace.y), (pz, workspace.z)] {
        assert!(lo <= v && v <= hi, "commanded pose outside the workspace");
    }
    let (_, _, angle) = axis_angle(&i.commanded);
    assert!(angle <= workspace.tilt_deg + 1e-9);
    for (s, t) in spec.iter().zip(&i.theta) {
        let n = s.nominal.params();
        for j in 0..7 {
            let v = t[j].mid();
            assert!((v - n[j]).abs() <= s.radius[j] * (1.0 + 1e-12) + 1e-15);
        }
    }
    assert!(i.actuator.iter().all(|e| e.abs() <= eps));
    let x = reached(spec, i);
    // The rotation error's Rodrigues vector: axis · tan(angle / 2).
    let phi = Vector3::new(x[3], x[4], x[5]);
    let w = if phi.norm() > 0.0 {
        phi / phi.norm() * (phi.norm() / 2.0).tan()
    } else {
        phi
    };
    for k in 0..6 {
        let v = if k < 3 { x[k] } else { w[k - 3] };
        let b = i.reached[k];
        assert!(
            b.inf() - 1e-7 <= v && v <= b.sup() + 1e-7,
            "component {k}: {v} outside [{}, {}]",
            b.inf(),
            b.sup()
        );
    }
    let position = Vector3::new(x[0], x[1], x[2]).norm();
    assert!(
        position >= i.position * (1.0 - 1e-9),
        "{position} < {}",
        i.position
    );
    let orientation = phi.norm().to_degrees();
    assert!(orientation >= i.orientation_deg * (1.0 - 1e-9));
}

#[test]
fn instances_recheck_independently_on_random_robots_and_workspaces() {
    let mut rng = StdRng::seed_from_u64(23);
    for _ in 0..4 {
        let spec = robot(rng.random_range(0.005..0.1));
        let workspace = random_workspace(&mut rng, 15.0);
        let eps = rng.random_range(0.0..0.01);
        let problem = AccuracyProblem::new(&spec, &workspace);
        let found = pose_error_instances(&problem, eps);
        let (position, orientation) = (
            found.position.expect("a position instance"),
            found.orientation.expect("an orientation instance"),
        );
        assert!(position.position > 0.0 && orientation.orientation_deg > 0.0);
        recheck(&spec, &workspace, eps, &position);
        recheck(&spec, &workspace, eps, &orientation);
    }
}

/// The largest errors of random commanded poses, geometries at random corners of the boxes and
/// random actuator errors at their bounds (independent forward kinematics).
fn sampled(spec: &[LegSpec], workspace: &Workspace, eps: f64, rng: &mut StdRng) -> (f64, f64) {
    let problem = AccuracyProblem::new(spec, workspace);
    let t = (workspace.tilt_deg.to_radians() / 2.0).tan();
    let (mut position, mut orientation) = (0.0f64, 0.0f64);
    let mut n = 0;
    while n < 150 {
        let x: [f64; 6] = [
            rng.random_range(workspace.x[0]..workspace.x[1]),
            rng.random_range(workspace.y[0]..workspace.y[1]),
            rng.random_range(workspace.z[0]..workspace.z[1]),
            rng.random_range(-t..t),
            rng.random_range(-t..t),
            rng.random_range(-t..t),
        ];
        if !problem.proved_feasible(&x) {
            continue;
        }
        n += 1;
        let theta = spec
            .iter()
            .map(|s| {
                let v = s.nominal.params();
                core::array::from_fn(|j| {
                    let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
                    calib_core::Interval::point(v[j] + sign * s.radius[j] * (1.0 - 1e-9))
                })
            })
            .collect();
        let actuator = (0..6)
            .map(|_| if rng.random_bool(0.5) { eps } else { -eps })
            .collect();
        let i = PoseErrorInstance {
            commanded: x,
            theta,
            actuator,
            reached: [calib_core::Interval::ENTIRE; 6],
            position: 0.0,
            orientation_deg: 0.0,
            segments: 0,
        };
        let m = reached(spec, &i);
        position = position.max(Vector3::new(m[0], m[1], m[2]).norm());
        orientation = orientation.max(Vector3::new(m[3], m[4], m[5]).norm().to_degrees());
    }
    (position, orientation)
}

#[test]
fn the_search_beats_random_sampling() {
    let mut rng = StdRng::seed_from_u64(5);
    let spec = robot(0.05);
    let workspace = Workspace::SIMULATOR;
    let eps = 0.0005;
    let found = pose_error_instances(&AccuracyProblem::new(&spec, &workspace), eps);
    let (position, orientation) = sampled(&spec, &workspace, eps, &mut rng);
    let p = found.position.expect("a position instance").position;
    let o = found
        .orientation
        .expect("an orientation instance")
        .orientation_deg;
    assert!(p >= position, "search {p} < sampled {position}");
    assert!(o >= orientation, "search {o} < sampled {orientation}");
}

#[test]
fn a_workspace_at_a_singular_pose_proves_no_instance() {
    // Every leg vertical at the centre: horizontal moves change no leg length to first order.
    let spec: Vec<LegSpec> = builtin_hexapod()
        .into_iter()
        .map(|leg| {
            let mut nominal = leg;
            nominal.a = [leg.b[0], leg.b[1], leg.a[2]];
            LegSpec {
                nominal,
                radius: [0.05; 7],
            }
        })
        .collect();
    let workspace = Workspace {
        x: [-1e-9, 1e-9],
        y: [-1e-9, 1e-9],
        z: [59.0, 61.0],
        tilt_deg: 1e-7,
        stroke: None,
    };
    let report = accuracy_report(
        &AccuracyProblem::new(&spec, &workspace),
        None,
        Some(0.0005),
        &AccuracySettings {
            rel_tol: 0.04,
            max_boxes: 20_000,
            ..AccuracySettings::default()
        },
        false,
    );
    let pose = report.after.pose.as_ref().expect("computed");
    assert!(pose.position.is_none() && pose.orientation.is_none());
    // The output says where: a commanded pose of the workspace whose path was not proved.
    for at in [pose.position_unproved, pose.orientation_unproved] {
        let x = at.expect("the unproved pose is named");
        assert!(x[0].abs() <= 1e-9 && x[1].abs() <= 1e-9 && (59.0..=61.0).contains(&x[2]));
    }
    let json = report.json();
    assert!(json["position"]["lower"].is_null() && json["position"]["upper"].is_null());
    // No upper bound either: the box of poses where the reached pose was not enclosed is named.
    let bounds = pose.bounds.as_ref().expect("computed");
    assert!(bounds.position.is_none() && bounds.orientation_deg.is_none());
    let at = bounds.unproved_at.expect("named");
    // Even the finest box of poses: a larger budget would not help, and the output says so.
    assert!(bounds.unprovable && bounds.settled_share < 1.0);
    assert_eq!(json["position"]["upper_unproved"]["finest"], true);
    assert!(at[0].inf() <= 1e-9 && at[0].sup() >= -1e-9 && at[2].inf() < 61.0);
    assert!(json["orientation"]["upper"].is_null());
    assert!(json["orientation"]["worst"].is_null());
    // Both the unenclosed box of poses and the unproved commanded pose are written out.
    for key in ["upper_unproved_at", "unproved_at"] {
        let p = json["position"][key]["p"].as_array();
        assert_eq!(p.map(Vec::len), Some(3), "{key}");
    }
}

/// A small workspace about the simulator's centre (half-ranges of 0.2 to 1 cm, a tilt of 0.5°
/// to 2°): where the reached pose of a tightly calibrated robot can be enclosed.
fn small_workspace(rng: &mut StdRng) -> Workspace {
    let mut range = |c: f64| {
        let h = rng.random_range(0.2..1.0);
        [c - h, c + h]
    };
    Workspace {
        x: range(0.0),
        y: range(0.0),
        z: range(60.0),
        tilt_deg: rng.random_range(0.5..2.0),
        stroke: None,
    }
}

#[test]
fn upper_bounds_hold_for_every_sampled_error_and_meet_the_instances() {
    let mut rng = StdRng::seed_from_u64(31);
    let settings = PoseBoundSettings {
        max_pose_boxes: 100,
        max_seconds: f64::INFINITY,
        ..PoseBoundSettings::default()
    };
    for _ in 0..3 {
        let spec = robot(rng.random_range(0.0003..0.001));
        let workspace = small_workspace(&mut rng);
        let eps = rng.random_range(0.0..0.0005);
        let found = pose_errors(&AccuracyProblem::new(&spec, &workspace), eps, &settings);
        let bounds = found.bounds.expect("computed");
        let (p, o) = (
            bounds.position.expect("a proved position bound"),
            bounds.orientation_deg.expect("a proved orientation bound"),
        );
        let (lp, lo) = (
            found.position.expect("a position instance").position,
            found
                .orientation
                .expect("an orientation instance")
                .orientation_deg,
        );
        assert!(
            lp <= p && lo <= o,
            "instances {lp} {lo} above bounds {p} {o}"
        );
        // Independent forward kinematics at random poses, corners and actuator errors.
        let (sp, so) = sampled(&spec, &workspace, eps, &mut rng);
        assert!(sp <= p && so <= o, "sampled {sp} {so} above bounds {p} {o}");
    }
}

#[test]
fn the_leg_change_without_cancellation_matches_an_independent_forward_kinematics() {
    let mut rng = StdRng::seed_from_u64(8);
    for _ in 0..200 {
        let x: [f64; 6] = core::array::from_fn(|k| {
            if k < 3 {
                rng.random_range(-2.0..2.0) + if k == 2 { 60.0 } else { 0.0 }
            } else {
                rng.random_range(-0.2..0.2)
            }
        });
        let d: [f64; 6] =
            core::array::from_fn(|k| rng.random_range(-0.5..0.5) * 0.1f64.powi((k / 3) as i32));
        let theta: [f64; 7] = core::array::from_fn(|k| match k {
            0..=1 => rng.random_range(-40.0..40.0),
            2 => rng.random_range(-2.0..2.0),
            3..=5 => rng.random_range(-20.0..20.0),
            _ => rng.random_range(-1.0..1.0),
        });
        let m: [f64; 12] = core::array::from_fn(|k| if k < 6 { x[k] } else { theta[k - 6] });
        let change = ReachedChange.residual(&d, &m);
        // Independently: nalgebra rotations, the move's rotation vector from its Rodrigues
        // vector `w = axis · tan(angle / 2)`.
        let (p, axis, angle) = axis_angle(&x);
        let r = Rotation3::from_axis_angle(
            &nalgebra::Unit::new_normalize(Vector3::from(axis)),
            angle.to_radians(),
        );
        let w = Vector3::new(d[3], d[4], d[5]);
        let phi = w / w.norm() * 2.0 * w.norm().atan();
        let moved_pose = moved(
            &Vector3::from(p),
            &r,
            &Vector6::new(d[0], d[1], d[2], phi.x, phi.y, phi.z),
        );
        let commanded = Pose {
            p,
            axis,
            angle_deg: angle,
        };
        let leg = Leg::from_params(&theta);
        let difference = leg_reading(&leg, &moved_pose) - leg_reading(&leg, &commanded);
        assert!(
            (change - difference).abs() <= 1e-9,
            "{change} vs {difference}"
        );
        // The interval evaluator encloses the point value over a small box around it.
        let boxed = |v: &[f64]| -> Vec<Interval> {
            v.iter()
                .map(|c| Interval::new(c - 1e-6, c + 1e-6))
                .collect()
        };
        let (bd, bm) = (boxed(&d), boxed(&m));
        let e = ReachedChange.residual_interval(
            &core::array::from_fn(|k| bd[k]),
            &core::array::from_fn(|k| bm[k]),
        );
        assert!(e.contains(change), "{change} outside {e:?}");
    }
}

/// ± 0.1 cm and 0.2° around the centre of the simulator's workspace.
fn centre_workspace() -> Workspace {
    Workspace {
        x: [-0.1, 0.1],
        y: [-0.1, 0.1],
        z: [59.9, 60.1],
        tilt_deg: 0.2,
        stroke: None,
    }
}

/// The claim of the README: on a small workspace of a tightly calibrated robot, the upper bounds
/// meet the instances within the default tolerance (4%), so the truth is bracketed within 1.05.
#[test]
fn a_small_workspace_is_bracketed_within_five_percent() {
    let spec = robot(0.001);
    let workspace = centre_workspace();
    let settings = PoseBoundSettings {
        max_seconds: f64::INFINITY,
        ..PoseBoundSettings::default()
    };
    let found = pose_errors(&AccuracyProblem::new(&spec, &workspace), 0.001, &settings);
    let bounds = found.bounds.expect("computed");
    assert!(bounds.converged, "not converged: {bounds:?}");
    let ratio = [
        bounds.position.expect("a position bound") / found.position.expect("an instance").position,
        bounds.orientation_deg.expect("an orientation bound")
            / found.orientation.expect("an instance").orientation_deg,
    ];
    assert!(
        ratio.iter().all(|&r| (1.0..=1.05).contains(&r)),
        "brackets {ratio:?}"
    );
}

/// Before and after: the proved improvement of the platform's errors is the uncalibrated robot's
/// lower bound over the calibrated one's upper bound, in the JSON, the text and the certificate.
#[test]
fn the_pose_improvement_is_before_lower_over_after_upper() {
    let workspace = centre_workspace();
    let (after, before) = (robot(0.001), robot(0.01));
    let report = accuracy_report(
        &AccuracyProblem::new(&after, &workspace),
        Some(&AccuracyProblem::new(&before, &workspace)),
        Some(0.001),
        &AccuracySettings {
            pose_seconds: 5.0,
            ..AccuracySettings::default()
        },
        false,
    );
    let pose = |a: &calib_gough::accuracy::Accuracy| a.pose.clone().expect("computed");
    let (a, b) = (
        pose(&report.after),
        pose(report.before.as_ref().expect("before")),
    );
    let upper = a.bounds.as_ref().expect("computed");
    let factors = [
        b.position.expect("an instance").position / upper.position.expect("proved"),
        b.orientation.expect("an instance").orientation_deg
            / upper.orientation_deg.expect("proved"),
    ];
    assert!(factors.iter().all(|&f| f > 1.0), "{factors:?}");
    let json = report.json();
    for (key, f) in ["position", "orientation"].into_iter().zip(factors) {
        assert_eq!(json["pose_improvement"][key].as_f64(), Some(f), "{key}");
    }
    let section = report.section();
    assert!(
        section
            .paragraphs
            .iter()
            .any(|p| p.contains(&format!("position error at least {:.1}-fold", factors[0]))),
        "{:?}",
        section.paragraphs
    );
}

/// The built-in hexapod (the geometry of `sample21`) with `a_z` and `l` known only to ± 0.1 cm,
/// as a box (no certified set): its nearly vertical legs turn that into centimetres and degrees
/// at the platform, where the legs' Jacobian changes across the move and no chart closes, even on
/// a workspace of ± 0.05 cm. No bound is claimed; the finest box of poses is named, and the words
/// say why and what would help.
#[test]
fn centimetre_moves_claim_no_bound_and_name_the_box() {
    let spec = centimetre_robot();
    let workspace = Workspace {
        x: [-0.05, 0.05],
        y: [-0.05, 0.05],
        z: [59.95, 60.05],
        tilt_deg: 0.1,
        stroke: None,
    };
    let settings = PoseBoundSettings {
        max_pose_boxes: 2000,
        max_seconds: f64::INFINITY,
        ..PoseBoundSettings::default()
    };
    let found = pose_errors(&AccuracyProblem::new(&spec, &workspace), 0.0005, &settings);
    let lp = found.position.expect("a position instance").position;
    assert!(lp > 1.0, "centimetre errors expected: {lp} cm");
    let bounds = found.bounds.expect("computed");
    assert_eq!((bounds.position, bounds.orientation_deg), (None, None));
    assert!(bounds.unprovable, "the finest box is named: {bounds:?}");
    let at = bounds.unproved_at.expect("a box named");
    let domain = AccuracyProblem::new(&spec, &workspace).domain();
    assert!(
        (0..6).all(|k| domain[k].inf() <= at[k].inf() && at[k].sup() <= domain[k].sup()),
        "{at:?} inside {domain:?}"
    );
    let words = unproved_words(&bounds, workspace.tilt_deg).expect("words");
    assert!(words.contains("even in the finest box of poses"), "{words}");
}

/// A search whose budget ends before its boxes of poses close claims no bound and says so: not
/// at the finest box, how much of the workspace it settled, where it stopped (within the
/// workspace's rotations).
#[test]
fn a_budget_that_ends_first_is_told_apart_from_an_unprovable_box() {
    let spec = centimetre_robot();
    let workspace = Workspace {
        x: [-1.0, 1.0],
        y: [-1.0, 1.0],
        z: [59.0, 61.0],
        tilt_deg: 2.0,
        stroke: None,
    };
    let settings = PoseBoundSettings {
        max_pose_boxes: 3,
        max_seconds: f64::INFINITY,
        ..PoseBoundSettings::default()
    };
    let problem = AccuracyProblem::new(&spec, &workspace);
    let bounds = pose_error_bounds(&problem, 0.0005, [0.0; 2], &settings);
    assert!(bounds.position.is_none() && bounds.orientation_deg.is_none());
    assert!(bounds.unproved_at.is_some() && !bounds.unprovable);
    assert!(
        (0.0..1.0).contains(&bounds.settled_share),
        "settled {}",
        bounds.settled_share
    );
    let words = unproved_words(&bounds, workspace.tilt_deg).expect("not proved");
    assert!(words.contains("the budget ended"), "{words}");
    let angle: f64 = words
        .split("rotated ")
        .nth(1)
        .and_then(|t| t.split('°').next())
        .and_then(|a| a.parse().ok())
        .expect("a rotation named");
    assert!(angle <= 2.0 + 1e-9, "{words}");
}

/// The words name the stopping box by its centre with the rotation brought within the tilt, the
/// share settled, and which of the two reasons holds.
#[test]
fn the_unproved_words_name_a_pose_of_the_workspace_and_the_reason() {
    let q = (1.5f64.to_radians() / 2.0).tan();
    let mut bounds = PoseErrorBounds {
        position: None,
        orientation_deg: None,
        // A box about a 3° rotation, in a workspace tilted at most 2°.
        unproved_at: Some([
            Interval::new(0.0, 1.0),
            Interval::new(-1.0, 0.0),
            Interval::new(60.0, 61.0),
            Interval::new(q, 3.0 * q),
            Interval::ZERO,
            Interval::ZERO,
        ]),
        unprovable: false,
        settled_share: 0.25,
        pose_boxes: 7,
        converged: false,
        seconds: 1.0,
    };
    let words = unproved_words(&bounds, 2.0).expect("not proved");
    assert!(words.contains("budget ended with 25.00%"), "{words}");
    assert!(
        words.contains("p = (0.500, -0.500, 60.500) cm rotated 2.000° about (1.000, 0.000, 0.000)"),
        "{words}"
    );
    bounds.unprovable = true;
    let words = unproved_words(&bounds, 5.0).expect("not proved");
    assert!(words.contains("even in the finest box"), "{words}");
    assert!(words.contains("rotated 2.999°"), "{words}");
    bounds.position = Some(1.0);
    bounds.orientation_deg = Some(1.0);
    assert!(unproved_words(&bounds, 5.0).is_none());
}
