//! The accuracy certificate's leg-length brackets: on random robots and workspaces the proved
//! upper bound is never below the error at random poses and geometries of the box (computed by
//! the independent `leg_reading`), the worst instance is rechecked independently (its pose in the
//! workspace, its geometry in the box, its error at least the lower bound), and the bracket meets
//! its tolerance.

use crate::support;

use calib_gough::accuracy::{axis_angle, certify_accuracy, AccuracyProblem, AccuracySettings};
use calib_gough::files::LegSpec;
use calib_gough::geometry::{leg_reading, Leg, Pose};
use calib_gough::simulate::builtin_hexapod;
use calib_gough::workspace::Workspace;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use support::random_workspace;

/// Rounding of the plain floating-point recomputation (the bounds are for exact values).
const SLACK: f64 = 1e-12;

fn random_robot(rng: &mut StdRng) -> Vec<LegSpec> {
    builtin_hexapod()
        .into_iter()
        .map(|nominal| LegSpec {
            nominal,
            radius: core::array::from_fn(|j| {
                // Some parameters fixed, the others between 0.001 and 0.05 cm.
                if j == 2 && rng.random_bool(0.3) {
                    0.0
                } else {
                    rng.random_range(0.001..0.05)
                }
            }),
        })
        .collect()
}

fn pose_of(x: &[f64; 6]) -> Pose {
    let (p, axis, angle_deg) = axis_angle(x);
    Pose { p, axis, angle_deg }
}

#[test]
fn upper_bounds_hold_at_random_poses_and_geometries_and_instances_recheck() {
    let mut rng = StdRng::seed_from_u64(17);
    for case in 0..4 {
        let robot = random_robot(&mut rng);
        let workspace = random_workspace(&mut rng, 20.0);
        let settings = AccuracySettings::default();
        let a = certify_accuracy(&AccuracyProblem::new(&robot, &workspace), &settings);
        let nominal: Vec<Leg> = robot.iter().map(|s| s.nominal).collect();
        for (i, (spec, b)) in robot.iter().zip(&a.leg_length).enumerate() {
            assert!(b.lower <= b.upper, "case {case} leg {i}: {b:?}");
            assert!(b.ratio() <= 1.05, "case {case} leg {i}: {b:?}");
            // The instance, rechecked with the independent inverse kinematics.
            let w = b.worst.as_ref().expect("an instance");
            let pose = pose_of(&w.pose);
            assert!(
                workspace.contains(&pose, &nominal),
                "case {case} leg {i}: {pose:?}"
            );
            let theta: [f64; 7] = core::array::from_fn(|j| w.theta[j].mid());
            let nominal_params = spec.nominal.params();
            for j in 0..7 {
                let r = spec.radius[j];
                assert!(
                    (theta[j] - nominal_params[j]).abs() <= r,
                    "case {case} leg {i} {j}"
                );
            }
            let error = (leg_reading(&Leg::from_params(&theta), &pose)
                - leg_reading(&spec.nominal, &pose))
            .abs();
            assert!(
                error >= b.lower - SLACK && error <= b.upper + SLACK,
                "{error} {b:?}"
            );
        }
        // Random poses of the workspace and geometries of the boxes (vertices half the time).
        for _ in 0..3000 {
            let extremes = rng.random_bool(0.5);
            let Some(pose) = workspace.sample(&mut rng, &nominal, extremes) else {
                continue;
            };
            for (spec, b) in robot.iter().zip(&a.leg_length) {
                let p = spec.nominal.params();
                let vertex = rng.random_bool(0.5);
                let theta: [f64; 7] = core::array::from_fn(|j| {
                    let r = spec.radius[j];
                    if vertex {
                        p[j] + if rng.random_bool(0.5) { r } else { -r }
                    } else {
                        p[j] + rng.random_range(-1.0..=1.0) * r
                    }
                });
                let error = (leg_reading(&Leg::from_params(&theta), &pose)
                    - leg_reading(&spec.nominal, &pose))
                .abs();
                assert!(
                    error <= b.upper + SLACK,
                    "case {case}: {error} > {}",
                    b.upper
                );
            }
        }
    }
}

#[test]
fn a_wider_box_gives_a_proportionally_larger_error() {
    // Before and after: the same robot with a box ten times wider has ten times the error (to
    // first order), and both brackets hold.
    let robot = |r: f64| -> Vec<LegSpec> {
        builtin_hexapod()
            .into_iter()
            .map(|nominal| LegSpec {
                nominal,
                radius: [r; 7],
            })
            .collect()
    };
    let settings = AccuracySettings::default();
    let after = certify_accuracy(
        &AccuracyProblem::new(&robot(0.01), &Workspace::SIMULATOR),
        &settings,
    );
    let before = certify_accuracy(
        &AccuracyProblem::new(&robot(0.1), &Workspace::SIMULATOR),
        &settings,
    );
    for (a, b) in after.leg_length.iter().zip(&before.leg_length) {
        let factor = b.lower / a.upper;
        assert!(factor > 9.0 && b.upper / a.lower < 11.0, "{a:?} {b:?}");
    }
}

#[test]
fn pose_box_enclosures_contain_the_errors_at_their_points() {
    use calib_core::Interval;
    use calib_gough::accuracy::AccuracyProblem;
    let mut rng = StdRng::seed_from_u64(5);
    let robot = random_robot(&mut rng);
    let problem = AccuracyProblem::new(&robot, &Workspace::SIMULATOR);
    let domain = problem.domain();
    for _ in 0..400 {
        let b: [Interval; 6] = core::array::from_fn(|k| {
            let w = domain[k].wid() * rng.random_range(0.001..0.3);
            let lo = domain[k].inf() + rng.random::<f64>() * (domain[k].wid() - w);
            Interval::new(lo, lo + w)
        });
        for (i, spec) in robot.iter().enumerate() {
            let value = problem.leg_bounds(i, &b);
            let p = spec.nominal.params();
            let error = |x: &[f64; 6], theta: &[f64; 7]| {
                let pose = pose_of(x);
                leg_reading(&Leg::from_params(theta), &pose) - leg_reading(&spec.nominal, &pose)
            };
            // f(X) = max over the box's vertices of |ΔL| (ΔL is convex in a, b and affine in l).
            let f = |x: &[f64; 6]| -> f64 {
                (0..128u32)
                    .map(|v| {
                        let t: [f64; 7] = core::array::from_fn(|j| {
                            p[j] + if v & (1 << j) != 0 { 1.0 } else { -1.0 } * spec.radius[j]
                        });
                        error(x, &t).abs()
                    })
                    .fold(0.0, f64::max)
            };
            for _ in 0..5 {
                let x: [f64; 6] =
                    core::array::from_fn(|k| b[k].inf() + rng.random::<f64>() * b[k].wid());
                let fx = f(&x);
                assert!(
                    value.inf() - SLACK <= fx && fx <= value.sup() + SLACK,
                    "leg {i}: f = {fx} outside {value:?} on {b:?}"
                );
            }
        }
    }
}
