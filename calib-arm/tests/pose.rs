//! The six-row residual against the independent forward kinematics of `common`, and 6-DoF
//! certification ([`calib_arm::pose`]) on random arms measured in position and orientation,
//! the data made by the independent forward kinematics of `common`: the truth stays inside the
//! outer box, consistent data are not proved empty, the orientations narrow the tool frame's
//! rotation, and a configuration whose orientation is turned is proved inconsistent.

use crate::common::{forward, tool_rotation};
use crate::kernel::random_arm;
use crate::model::random_arm as random_geometry;
use calib_arm::calibrated::{calibrated_arm, read_back, PointChoice};
use calib_arm::certification::{padded_index, CertifyRequest};
use calib_arm::error_scale::{search, search_pose, ScaleBounds};
use calib_arm::params::{self, Unit};
use calib_arm::pose::certification::{certify_pose_request, verdict_only_pose};
use calib_arm::pose::orientation::{from_euler_xyz, to_euler_xyz};
use calib_arm::pose::Arm7Pose;
use calib_arm::pose::{PoseReading, PoseUncertainty};
use calib_arm::robot::ToolRotation;
use calib_arm::simulate::{measurement_box, Reading, Uncertainty};
use calib_arm::units::deg_to_rad;
use calib_arm::{Arm, Arm7Point, ArmError};
use calib_core::{is_certified_consistent, Status};
use calib_core::{Interval, VectorModel};
use nalgebra::Rotation3;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// The error bounds of the simulated data: the tracker's, and 0.002° per Euler angle.
const BOUNDS: PoseUncertainty = PoseUncertainty {
    position: Uncertainty::TRACKER,
    orient_deg: Some(0.002),
};

/// A random arm of 3 joints with a tool frame's rotation and its prior.
fn pose_arm(rng: &mut StdRng) -> Arm {
    let mut arm = random_arm(3, rng);
    arm.tool_rotation = Some(ToolRotation {
        rpy_deg: core::array::from_fn(|_| rng.random_range(-180.0..180.0)),
        radius: [0.01; 3],
    });
    arm
}

/// The truth (files' units: the point model's parameters, then the tool rotation) within 0.8 of
/// each prior half-width, and `configs` readings within the bounds of the true values.
fn simulate(arm: &Arm, configs: usize, rng: &mut StdRng) -> (Vec<f64>, Vec<PoseReading>) {
    let tool = arm.tool_rotation.unwrap();
    let names = params::pose_names(arm.joints.len());
    let nominal: Vec<f64> = arm.nominal().into_iter().chain(tool.rpy_deg).collect();
    let radius: Vec<f64> = arm.radius().into_iter().chain(tool.radius).collect();
    let truth: Vec<f64> = nominal
        .iter()
        .zip(&radius)
        .map(|(v, r)| v + rng.random_range(-0.8..=0.8) * r)
        .collect();
    let model: Vec<f64> = truth
        .iter()
        .zip(&names)
        .map(|(v, (_, u))| if *u == Unit::Deg { v.to_radians() } else { *v })
        .collect();
    let point_parameters = params::count(arm.joints.len());
    let noise = |rng: &mut StdRng, r: f64| rng.random_range(-1.0..=1.0) * r;
    let readings = (0..configs)
        .map(|_| {
            let q: Vec<f64> = (0..arm.joints.len())
                .map(|_| rng.random_range(-170.0..170.0))
                .collect();
            let q_rad: Vec<f64> = q.iter().map(|v| v.to_radians()).collect();
            let p = forward(&model[..point_parameters], &q_rad);
            let r = Rotation3::from_matrix_unchecked(tool_rotation(&model, &q_rad));
            let euler = to_euler_xyz(&r).map(f64::to_degrees);
            let u = &BOUNDS.position;
            PoseReading {
                reading: Reading {
                    joints_deg: q.iter().map(|v| v + noise(rng, u.joint_deg)).collect(),
                    point: p.map(|v| v + noise(rng, u.pos)),
                },
                euler_xyz_deg: euler.map(|v| v + noise(rng, BOUNDS.orient_deg.unwrap())),
            }
        })
        .collect();
    (truth, readings)
}

#[test]
fn six_dof_certification_keeps_the_truth_and_narrows_the_tool_rotation() {
    let mut narrowed = 0;
    for seed in 0..3u64 {
        let mut rng = StdRng::seed_from_u64(100 + seed);
        let arm = pose_arm(&mut rng);
        let (truth, readings) = simulate(&arm, 10, &mut rng);
        let (_, run) =
            certify_pose_request(&arm, &readings, &BOUNDS, &CertifyRequest::default()).unwrap();
        let o = &run.outcome;
        assert_ne!(
            o.status,
            Status::Empty,
            "seed {seed}: consistent data proved empty"
        );
        let outer = o.outer.as_ref().unwrap();
        assert_eq!(outer.len(), truth.len());
        for (j, (b, t)) in outer.iter().zip(&truth).enumerate() {
            assert!(
                b.contains(*t),
                "seed {seed}: {} = {t} outside {b}",
                o.names[j]
            );
        }
        // The tool frame's rotation (the last three) is seen by the orientations only.
        let n = truth.len();
        narrowed += (n - 3..n)
            .filter(|&j| outer[j].wid() < 0.5 * o.x0[j].wid())
            .count();
    }
    assert!(
        narrowed >= 6,
        "the orientations narrowed only {narrowed} of 9 tool rotations"
    );
}

#[test]
fn a_turned_orientation_is_proved_inconsistent() {
    let mut rng = StdRng::seed_from_u64(7);
    let arm = pose_arm(&mut rng);
    let (_, mut readings) = simulate(&arm, 10, &mut rng);
    readings[2].euler_xyz_deg[1] += 0.05;
    let (_, run) =
        certify_pose_request(&arm, &readings, &BOUNDS, &CertifyRequest::default()).unwrap();
    assert_eq!(run.outcome.status, Status::Empty);
}

#[test]
fn the_six_dof_error_scale_brackets_the_bound_the_truth_needs() {
    let mut rng = StdRng::seed_from_u64(11);
    let arm = pose_arm(&mut rng);
    let (_, readings) = simulate(&arm, 10, &mut rng);
    let plain: Vec<Reading> = readings.iter().map(|r| r.reading.clone()).collect();
    for which in [ScaleBounds::All, ScaleBounds::OrientDeg] {
        // The chosen bounds four times too tight for the noise: the truth fits at × 4.
        let tight = which.scale_pose(&BOUNDS, 0.25);
        let found = search_pose(&arm, &readings, &tight, which, |_| {}).expect("search");
        let (lo, hi) = (found.s_lo.expect("s_lo"), found.s_hi.expect("s_hi"));
        assert!(
            lo < hi && lo < 4.0,
            "{which:?}: {lo} {hi}: the truth fits at × 4"
        );
        assert!(
            hi <= 4.0 * 1.02,
            "{which:?}: s_hi {hi} above the truth's × 4"
        );
        let at_hi = which.scale_pose(&tight, hi);
        assert_ne!(
            verdict_only_pose(&arm, &readings, &at_hi).expect("verdict"),
            Status::Empty,
            "{which:?}"
        );
        // The orientations' bound is the only one scaled by orient_deg.
        if which == ScaleBounds::OrientDeg {
            assert_eq!(at_hi.position, BOUNDS.position);
        }
    }
    // Positions alone have no orientation bound to scale.
    let e = search(
        &arm,
        &plain,
        &BOUNDS.position,
        ScaleBounds::OrientDeg,
        |_| {},
    )
    .unwrap_err();
    assert_eq!(e, ArmError::OrientScaleNeedsPose);
    assert!(e.to_string().contains("--orientation-columns"), "{e}");
}

#[test]
fn six_dof_needs_the_tool_rotation_and_its_bound() {
    let mut rng = StdRng::seed_from_u64(8);
    let arm = pose_arm(&mut rng);
    let (_, readings) = simulate(&arm, 4, &mut rng);
    let request = CertifyRequest::default();
    let plain = Arm {
        tool_rotation: None,
        ..arm.clone()
    };
    let e = certify_pose_request(&plain, &readings, &BOUNDS, &request).unwrap_err();
    assert_eq!(e, ArmError::PoseNeedsToolRotation);
    let e = e.to_string();
    assert!(
        e.contains("rpy_deg") && e.contains("rotation_radius"),
        "{e}"
    );
    let no_bound = PoseUncertainty {
        orient_deg: None,
        ..BOUNDS
    };
    let e = certify_pose_request(&arm, &readings, &no_bound, &request).unwrap_err();
    assert_eq!(e, ArmError::PoseNeedsOrientBound);
    assert!(e.to_string().contains("orient_deg"), "{e}");
}

/// The 6-DoF model's parameters: a random 7-joint arm, then a tool rotation (radians).
fn random_pose_arm(rng: &mut StdRng) -> [f64; 47] {
    let mut x = random_geometry(rng, 7);
    x.extend((0..3).map(|_| rng.random_range(-3.0..3.0)));
    x.try_into().unwrap()
}

/// The 6-DoF model's measured quantities at `x`, `q`: the readings, the tracked point and the
/// intrinsic Euler angles `XYZ` of the tool frame, from the independent forward kinematics.
fn pose_measurement(x: &[f64; 47], q: &[f64]) -> [f64; 13] {
    let mut m = [0.0; 13];
    m[..7].copy_from_slice(q);
    m[7..10].copy_from_slice(&forward(&x[..44], q));
    let r = nalgebra::Rotation3::from_matrix_unchecked(tool_rotation(x, q));
    m[10..].copy_from_slice(&to_euler_xyz(&r));
    m
}

#[test]
fn the_six_row_residual_is_the_forward_kinematics_of_the_chain_and_its_orientation() {
    let mut rng = StdRng::seed_from_u64(5);
    for _ in 0..200 {
        let x = random_pose_arm(&mut rng);
        let q: Vec<f64> = (0..7).map(|_| rng.random_range(-3.0..3.0)).collect();
        let m = pose_measurement(&x, &q);
        let r = Arm7Pose.residuals(&x, &m);
        let point = Arm7Point.residuals(&x[..44].try_into().unwrap(), &m[..10].try_into().unwrap());
        assert_eq!(r[..3], point, "the position rows are the point model's");
        for k in 3..6 {
            assert!(r[k].abs() < 1e-8, "row {k}: {r:?}");
        }
        // A small rotation `δ` of the measured frame: the rows are ±500 δ (one sign for all).
        let delta = nalgebra::Vector3::new(
            rng.random_range(-1e-3..1e-3),
            rng.random_range(-1e-3..1e-3),
            rng.random_range(-1e-3..1e-3),
        );
        let measured =
            from_euler_xyz([m[10], m[11], m[12]]) * nalgebra::Rotation3::from_scaled_axis(-delta);
        let mut moved = m;
        moved[10..].copy_from_slice(&to_euler_xyz(&measured));
        let r = Arm7Pose.residuals(&x, &moved);
        let sign = r[3].signum() * delta[0].signum();
        for k in 0..3 {
            assert!(
                (r[3 + k] - sign * 500.0 * delta[k]).abs() < 1e-3,
                "row {}: {} against {}",
                3 + k,
                r[3 + k],
                500.0 * delta[k]
            );
        }
        // The interval evaluation over a small box contains the point values (the orientation
        // rows, 1000 × a chain of 24 quaternion products, widen more than the position rows: up to
        // ~1.1 here, against ~0.03 to first order).
        let xb = x.map(|v| Interval::mid_rad(v, 1e-6));
        let mb = moved.map(|v| Interval::mid_rad(v, 1e-6));
        let ri = Arm7Pose.residuals_interval(&xb, &mb);
        for k in 0..6 {
            assert!(ri[k].contains(r[k]) && ri[k].wid() < 2.0, "{:?}", ri[k]);
        }
    }
}

/// `--write-calibrated` on 6-DoF data: the calibrated vector, tool rotation included, fits all
/// six equations of every configuration as the file writes it (the values read back as decimals
/// of degrees), its radii hold the certified outer box, and the file's set — the positions'
/// set over the 6-DoF cover — holds the truth (the set `predict` works over).
#[test]
fn a_six_dof_calibration_fits_all_six_equations_and_its_set_holds_the_truth() {
    for seed in 0..2u64 {
        let mut rng = StdRng::seed_from_u64(40 + seed);
        let arm = pose_arm(&mut rng);
        let (truth, readings) = simulate(&arm, 10, &mut rng);
        let (_, run) =
            certify_pose_request(&arm, &readings, &BOUNDS, &CertifyRequest::default()).unwrap();
        assert!(run.pose_set.is_some() && run.set.is_some(), "seed {seed}");
        let joints: Vec<Vec<f64>> = readings
            .iter()
            .map(|r| r.reading.joints_deg.clone())
            .collect();
        let c = calibrated_arm(&arm, &run, &joints, PointChoice::Centre).expect("consistent");
        let tool = c.arm.tool_rotation.expect("the tool rotation is written");
        let point = read_back(&c.arm);
        let x: [Interval; 47] = core::array::from_fn(|i| match i.checked_sub(44) {
            None => point[i],
            Some(k) => deg_to_rad(Interval::point(tool.rpy_deg[k])),
        });
        let orient = BOUNDS.orient_deg.unwrap();
        let boxes: Vec<[Interval; 13]> = readings
            .iter()
            .map(|r| {
                let b: [Interval; 10] = measurement_box(&r.reading, &BOUNDS.position).unwrap();
                core::array::from_fn(|i| match i.checked_sub(10) {
                    None => b[i],
                    Some(k) => deg_to_rad(Interval::mid_rad(r.euler_xyz_deg[k], orient)),
                })
            })
            .collect();
        assert!(
            is_certified_consistent(&Arm7Pose, &x, &boxes),
            "seed {seed}: the written 6-DoF calibration is not proved consistent"
        );
        let outer = run.outcome.outer.as_ref().unwrap();
        let n = outer.len();
        for k in 0..3 {
            let (v, r) = (tool.rpy_deg[k], tool.radius[k]);
            assert!(v - r <= outer[n - 3 + k].inf() && outer[n - 3 + k].sup() <= v + r);
        }
        // The truth in the padded point model (radians), inside the file's set.
        let names = params::names(arm.joints.len());
        let mut padded = [0.0; 44];
        for ((&p, v), (_, u)) in padded_index(arm.joints.len())
            .iter()
            .zip(&truth)
            .zip(&names)
        {
            padded[p] = if *u == Unit::Deg { v.to_radians() } else { *v };
        }
        assert!(
            c.set.admits(&padded, 1e-9),
            "seed {seed}: the positions' set lost the truth"
        );
    }
}
