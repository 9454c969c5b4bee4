//! The tool-point accuracy certificate against an independent forward kinematics: on random
//! arms, joint boxes and joint errors, no sampled error exceeds the proved upper bound, the worst
//! instance is rechecked and lies in the boxes, and a single configuration is bracketed tightly.

use calib_arm::accuracy::{
    certify_tool_accuracy, ToolAccuracyProblem, ToolAccuracySettings, ToolBracket,
};
use calib_arm::joint_space::JointSpace;
use calib_arm::params::{self, Unit};
use calib_arm::{builtin_arm, Arm};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

use crate::common;
use common::forward;

/// Parameters in the model's units (radians for angles).
fn to_model(arm: &Arm, values: &[f64]) -> Vec<f64> {
    params::names(arm.joints.len())
        .iter()
        .zip(values)
        .map(|((_, u), v)| match u {
            Unit::Deg => v.to_radians(),
            Unit::Mm => *v,
        })
        .collect()
}

/// Whether parameter `j` is a joint's `theta` (where the joint error goes).
fn is_theta(arm: &Arm, j: usize) -> bool {
    j < 5 * arm.joints.len() && j % 5 == 0
}

fn norm(e: [f64; 3]) -> f64 {
    (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt()
}

/// The bracket's worst instance, its error recomputed by matrix products (at least its value)
/// at joints inside the joint space; its geometry in model units.
fn rechecked_worst<'a>(
    b: &'a ToolBracket,
    controller: &[f64],
    space: &JointSpace,
) -> (&'a calib_arm::accuracy::ToolInstance, Vec<f64>) {
    let w = b.worst.as_ref().expect("an instance");
    let theta: Vec<f64> = w.theta.iter().map(|v| v.mid()).collect();
    let (p, p0) = (
        forward(&theta, &w.joints_rad),
        forward(controller, &w.joints_rad),
    );
    let e = norm([p[0] - p0[0], p[1] - p0[1], p[2] - p0[2]]);
    assert!(e >= w.value * (1.0 - 1e-9), "{e} < {}", w.value);
    for (q, [lo, hi]) in w.joints_deg.iter().zip(&space.ranges_deg) {
        assert!(*lo - 1e-9 <= *q && *q <= *hi + 1e-9, "q {q}");
    }
    (w, theta)
}

/// The built-in arm simulated at 30 configurations (seed `seed`), certified in one contraction
/// and calibrated: the arm, the simulation, the calibrated file's arm and set.
fn calibrated_simulation(
    seed: u64,
) -> (
    Arm,
    calib_arm::Simulation,
    calib_arm::calibrated::CalibratedArm,
) {
    use calib_arm::calibrated::{calibrated_arm, PointChoice};
    use calib_arm::certification::{arm_settings, certify_arm, RunOptions};
    use calib_arm::simulate::{simulate, Uncertainty};
    let arm = builtin_arm();
    let sim = simulate(&arm, 30, seed, Uncertainty::TRACKER, 1.0, &[]);
    let run = certify_arm(
        &arm,
        &sim.readings,
        &sim.uncertainty,
        RunOptions {
            depth: calib_pipeline::Depth::Fast,
            lsq: false,
        },
        &arm_settings(),
    )
    .expect("an arm");
    let joints: Vec<Vec<f64>> = sim.readings.iter().map(|r| r.joints_deg.clone()).collect();
    let c = calibrated_arm(&arm, &run, &joints, PointChoice::LeastSquares).expect("consistent");
    (arm, sim, c)
}

/// The geometries known to be consistent (model units, unpadded): the simulated truth and the
/// certified set's points.
fn consistent_geometries(
    arm: &Arm,
    sim: &calib_arm::Simulation,
    c: &calib_arm::calibrated::CalibratedArm,
) -> Vec<Vec<f64>> {
    let index = calib_arm::certification::padded_index(arm.joints.len());
    let mut geometries = vec![to_model(arm, &sim.truth)];
    geometries.extend(
        c.set
            .points()
            .iter()
            .map(|p| index.iter().map(|&k| p.x[k]).collect::<Vec<f64>>()),
    );
    geometries
}

#[test]
fn the_upper_bound_holds_and_the_worst_instance_is_rechecked() {
    let mut rng = StdRng::seed_from_u64(11);
    // One random arm and joint space per joint error: none, 0.001° and 0.01°.
    for case in 0..3 {
        let arm = builtin_arm().with_radii_scaled(rng.random_range(0.05..1.5));
        let ranges_deg: Vec<[f64; 2]> = (0..arm.joints.len())
            .map(|_| {
                let c: f64 = rng.random_range(-150.0..150.0);
                let h: f64 = rng.random_range(1.0..20.0);
                [c - h, c + h]
            })
            .collect();
        let joint_deg = [0.0, 0.001, 0.01][case % 3];
        let space = JointSpace { ranges_deg };
        let problem = ToolAccuracyProblem::new(&arm, &space, joint_deg).expect("problem");
        let b = certify_tool_accuracy(
            &problem,
            &ToolAccuracySettings {
                rel_tol: 0.04,
                max_boxes: 600,
                ..ToolAccuracySettings::default()
            },
        );
        assert!(
            b.upper.is_finite() && b.upper >= b.lower && b.lower > 0.0,
            "{b:?}"
        );
        let (nominal, radius) = (arm.nominal(), arm.radius());
        let controller = to_model(&arm, &nominal);
        // Every geometry of the box, every joint error: random points and random vertices.
        let mut largest: f64 = 0.0;
        for k in 0..400 {
            let q: Vec<f64> = space
                .ranges_deg
                .iter()
                .map(|[lo, hi]| rng.random_range(*lo..=*hi).to_radians())
                .collect();
            let real: Vec<f64> = (0..nominal.len())
                .map(|j| {
                    let r = radius[j] + if is_theta(&arm, j) { joint_deg } else { 0.0 };
                    let t: f64 = if k % 2 == 0 {
                        rng.random_range(-1.0..=1.0)
                    } else if rng.random_bool(0.5) {
                        1.0
                    } else {
                        -1.0
                    };
                    nominal[j] + t * r
                })
                .collect();
            let (p, p0) = (
                forward(&to_model(&arm, &real), &q),
                forward(&controller, &q),
            );
            let e = norm([p[0] - p0[0], p[1] - p0[1], p[2] - p0[2]]);
            largest = largest.max(e);
            assert!(
                e <= b.upper * (1.0 + 1e-9) + 1e-9,
                "case {case}: error {e} above the proved {}",
                b.upper
            );
        }
        // The instance, rechecked by matrix products, inside the joint and geometry boxes.
        let (w, theta) = rechecked_worst(&b, &controller, &space);
        assert_eq!(w.value, b.lower, "case {case}");
        for (j, (t, u)) in theta
            .iter()
            .zip(params::names(arm.joints.len()))
            .enumerate()
        {
            let r = radius[j] + if is_theta(&arm, j) { joint_deg } else { 0.0 };
            let v = match u.1 {
                Unit::Deg => t.to_degrees(),
                Unit::Mm => *t,
            };
            assert!(
                (v - nominal[j]).abs() <= r * (1.0 + 1e-9) + 1e-9,
                "case {case}: {} = {v} outside {} ± {r}",
                u.0,
                nominal[j]
            );
        }
        // The search finds at least what random sampling does.
        assert!(
            b.lower >= 0.97 * largest,
            "case {case}: lower {} below a sampled {largest}",
            b.lower
        );
    }
}

#[test]
fn a_single_configuration_is_bracketed_tightly() {
    // One configuration: only the direction is searched, so the bracket closes.
    let arm = builtin_arm();
    let space = JointSpace {
        ranges_deg: [10.0, -80.0, 95.0, -100.0, 85.0, 30.0]
            .iter()
            .map(|q| [*q, *q])
            .collect(),
    };
    let problem = ToolAccuracyProblem::new(&arm, &space, 0.001).expect("problem");
    let b = certify_tool_accuracy(&problem, &ToolAccuracySettings::default());
    assert!(b.converged && b.ratio() <= 1.05, "{b:?}");
}

#[test]
fn a_cell_of_every_joint_is_bracketed_within_five_percent() {
    // A ±3° cell of all six joints: the joint branch and bound with affine Jacobians and the
    // direction searched per joint box converges within the default budget.
    let arm = builtin_arm().with_radii_scaled(0.05);
    let space = JointSpace {
        ranges_deg: [10.0, -80.0, 95.0, -100.0, 85.0, 30.0]
            .iter()
            .map(|q| [*q - 3.0, *q + 3.0])
            .collect(),
    };
    let problem = ToolAccuracyProblem::new(&arm, &space, 0.001).expect("problem");
    let b = certify_tool_accuracy(&problem, &ToolAccuracySettings::default());
    assert!(b.converged && b.ratio() <= 1.05, "{b:?}");
}

#[test]
fn a_joint_space_of_the_wrong_size_is_refused() {
    let arm = builtin_arm();
    let e = ToolAccuracyProblem::new(&arm, &JointSpace::simulator(5), 0.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("5 ranges") && e.contains("6 joints"), "{e}");
    assert!(ToolAccuracyProblem::new(&arm, &JointSpace::simulator(6), f64::NAN).is_err());
}

#[test]
fn over_the_certified_set_no_consistent_geometry_exceeds_the_bound() {
    use calib_arm::accuracy::over_set::{certify_set_accuracy, SetToolAccuracy};
    let (arm, sim, c) = calibrated_simulation(3);
    let mut rng = StdRng::seed_from_u64(5);
    let ranges_deg: Vec<[f64; 2]> = (0..arm.joints.len())
        .map(|_| {
            let centre: f64 = rng.random_range(-120.0..120.0);
            [centre - 4.0, centre + 4.0]
        })
        .collect();
    let space = JointSpace { ranges_deg };
    let joint_deg = sim.uncertainty.joint_deg;
    let problem =
        SetToolAccuracy::new(&c.arm, c.set.clone(), &space, joint_deg).expect("a problem");
    let b = certify_set_accuracy(
        &problem,
        &ToolAccuracySettings {
            rel_tol: 0.04,
            max_set_boxes: 15,
            ..ToolAccuracySettings::default()
        },
    );
    assert!(
        b.upper.is_finite() && b.upper >= b.lower && b.lower > 0.0,
        "{b:?}"
    );
    // The geometries known to be consistent: the simulated truth and the set's certified points
    // (model units, unpadded), each with random joint errors; errors by an independent forward
    // kinematics, at random joints of the box.
    let controller = to_model(&c.arm, &c.arm.nominal());
    let geometries = consistent_geometries(&arm, &sim, &c);
    let mut largest: f64 = 0.0;
    for k in 0..2000 {
        let q: Vec<f64> = space
            .ranges_deg
            .iter()
            .map(|[lo, hi]| rng.random_range(*lo..=*hi).to_radians())
            .collect();
        let mut real = geometries[k % geometries.len()].clone();
        for (j, v) in real.iter_mut().enumerate() {
            if is_theta(&arm, j) {
                *v += rng.random_range(-1.0..=1.0) * joint_deg.to_radians();
            }
        }
        let (p, p0) = (forward(&real, &q), forward(&controller, &q));
        let e = norm([p[0] - p0[0], p[1] - p0[1], p[2] - p0[2]]);
        largest = largest.max(e);
        assert!(
            e <= b.upper * (1.0 + 1e-9) + 1e-12,
            "error {e} above the proved {}",
            b.upper
        );
    }
    // The worst instance, rechecked by matrix products, is attained in the box.
    rechecked_worst(&b, &controller, &space);
    assert!(
        b.lower >= 0.9 * largest,
        "lower {} below a sampled {largest}",
        b.lower
    );
}

/// At a task's configurations (a finite list, `tool_accuracy_at`): no consistent geometry with
/// any joint error exceeds the upper bound at any of them (by an independent forward
/// kinematics), the worst instances after and before calibration are rechecked at one of the
/// task's configurations, and a malformed task is refused.
#[test]
fn at_a_tasks_configurations_no_consistent_geometry_exceeds_the_bound() {
    use calib_arm::accuracy::tool_accuracy_at;
    let (arm, sim, c) = calibrated_simulation(8);
    let mut rng = StdRng::seed_from_u64(9);
    let task: Vec<Vec<f64>> = (0..25)
        .map(|_| {
            (0..arm.joints.len())
                .map(|_| rng.random_range(-170.0..170.0))
                .collect()
        })
        .collect();
    let joint_deg = sim.uncertainty.joint_deg;
    let settings = ToolAccuracySettings::default();
    let r = tool_accuracy_at(
        &c.arm,
        Some(c.set.clone()),
        Some(&arm),
        &task,
        joint_deg,
        &settings,
    )
    .expect("a report");
    let (after, before) = (&r.after, r.before.as_ref().expect("before"));
    for b in [after, before] {
        assert!(
            b.upper.is_finite() && b.upper >= b.lower && b.lower > 0.0,
            "{b:?}"
        );
        assert_eq!(b.boxes, task.len());
    }
    let controller = to_model(&c.arm, &c.arm.nominal());
    let geometries = consistent_geometries(&arm, &sim, &c);
    for (k, q) in task.iter().cycle().take(1500).enumerate() {
        let q: Vec<f64> = q.iter().map(|v| v.to_radians()).collect();
        let mut real = geometries[k % geometries.len()].clone();
        for (j, v) in real.iter_mut().enumerate() {
            if is_theta(&arm, j) {
                *v += rng.random_range(-1.0..=1.0) * joint_deg.to_radians();
            }
        }
        let (p, p0) = (forward(&real, &q), forward(&controller, &q));
        let e = norm([p[0] - p0[0], p[1] - p0[1], p[2] - p0[2]]);
        assert!(
            e <= after.upper * (1.0 + 1e-9) + 1e-12,
            "{e} above {}",
            after.upper
        );
    }
    // The worst instances are attained at one of the task's configurations.
    for (b, robot) in [(after, &c.arm), (before, &arm)] {
        let (w, _) = rechecked_worst(b, &to_model(robot, &robot.nominal()), &r.space);
        assert!(
            task.iter().any(|q| q
                .iter()
                .zip(&w.joints_deg)
                .all(|(a, b)| (a - b).abs() <= 1e-9 * (1.0 + a.abs()))),
            "{:?} is not a configuration of the task",
            w.joints_deg
        );
    }
    assert!(r.improvement().is_some_and(|f| f > 1.0), "{r:?}");
    // A configuration with a joint too few, one that is not finite, or none: refused.
    let mut short = task.clone();
    short[3].pop();
    let mut nan = task.clone();
    nan[0][2] = f64::NAN;
    for bad in [short, nan] {
        let e = tool_accuracy_at(&c.arm, None, None, &bad, joint_deg, &settings);
        assert!(
            matches!(e, Err(calib_arm::ArmError::TaskConfiguration { .. })),
            "{e:?}"
        );
    }
    let e = tool_accuracy_at(&c.arm, None, None, &[], joint_deg, &settings);
    assert!(matches!(e, Err(calib_arm::ArmError::EmptyTask)), "{e:?}");
}
