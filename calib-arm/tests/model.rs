//! The arm residual against an independent forward kinematics (4×4 homogeneous matrices with
//! nalgebra), its interval evaluators against point values, and its degree/radian handling.

use calib_arm::model::tracked_point;
use calib_arm::pose::orientation::{from_euler_xyz, to_euler_xyz};
use calib_arm::pose::Arm7Pose;
use calib_arm::Arm7Point;
use calib_core::{Interval, VectorModel};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

use crate::common;
use common::forward;

/// A UR5-like geometry (mm, radians) perturbed at random.
fn random_arm(rng: &mut StdRng, joints: usize) -> Vec<f64> {
    let mut x = Vec::new();
    for _ in 0..joints {
        x.extend([
            rng.random_range(-0.1..0.1),
            rng.random_range(0.0..120.0),
            rng.random_range(-450.0..450.0),
            rng.random_range(-1.6..1.6),
            rng.random_range(-0.01..0.01),
        ]);
    }
    x.extend([
        rng.random_range(-1500.0..1500.0),
        rng.random_range(-1500.0..1500.0),
        rng.random_range(-500.0..500.0),
        rng.random_range(-0.2..0.2),
        rng.random_range(-0.2..0.2),
        rng.random_range(-3.0..3.0),
    ]);
    x.extend([
        rng.random_range(-50.0..50.0),
        rng.random_range(-50.0..50.0),
        rng.random_range(0.0..150.0),
    ]);
    x
}

fn check<M: VectorModel<NX, NM, 3>, const NX: usize, const NM: usize>(
    model: &M,
    joints: usize,
    seed: u64,
) {
    let mut rng = StdRng::seed_from_u64(seed);
    for _ in 0..200 {
        let x: [f64; NX] = random_arm(&mut rng, joints).try_into().unwrap();
        let q: Vec<f64> = (0..joints).map(|_| rng.random_range(-3.0..3.0)).collect();
        let p = forward(&x, &q);
        let mut m = [0.0; NM];
        m[..joints].copy_from_slice(&q);
        m[joints..].copy_from_slice(&p);
        let r = model.residuals(&x, &m);
        for k in 0..3 {
            assert!(
                r[k].abs() < 1e-9 * (1.0 + p[k].abs()),
                "row {k}: {r:?} at {p:?}"
            );
        }
        // The interval evaluation over a small box contains the point values.
        let xb = x.map(|v| Interval::mid_rad(v, 1e-6));
        let mb = m.map(|v| Interval::mid_rad(v, 1e-6));
        let ri = model.residuals_interval(&xb, &mb);
        for k in 0..3 {
            assert!(ri[k].contains(r[k]) && ri[k].wid() < 1.0, "{:?}", ri[k]);
        }
    }
}

#[test]
fn the_generated_residual_is_the_forward_kinematics_of_the_chain() {
    check(&Arm7Point, 7, 3);
}

#[test]
fn shorter_arms_padded_with_identity_joints_give_their_own_forward_kinematics() {
    let mut rng = StdRng::seed_from_u64(4);
    for joints in 3..=7 {
        for _ in 0..50 {
            let x = random_arm(&mut rng, joints);
            let q: Vec<f64> = (0..joints).map(|_| rng.random_range(-3.0..3.0)).collect();
            let p = forward(&x, &q);
            let t = tracked_point(&x, &q).unwrap();
            for k in 0..3 {
                assert!(
                    (t[k] - p[k]).abs() < 1e-9 * (1.0 + p[k].abs()),
                    "{joints} joints, row {k}: {t:?} against {p:?}"
                );
            }
        }
    }
    assert_eq!(tracked_point(&[0.0; 24], &[0.0; 2]), None);
    assert_eq!(tracked_point(&[0.0; 23], &[0.0; 3]), None);
}

/// The 6-DoF model's parameters: a random 7-joint arm, then a tool rotation (radians).
fn random_pose_arm(rng: &mut StdRng) -> [f64; 47] {
    let mut x = random_arm(rng, 7);
    x.extend((0..3).map(|_| rng.random_range(-3.0..3.0)));
    x.try_into().unwrap()
}

/// The 6-DoF model's measured quantities at `x`, `q`: the readings, the tracked point and the
/// intrinsic Euler angles `XYZ` of the tool frame, from the independent forward kinematics.
fn pose_measurement(x: &[f64; 47], q: &[f64]) -> [f64; 13] {
    let mut m = [0.0; 13];
    m[..7].copy_from_slice(q);
    m[7..10].copy_from_slice(&forward(&x[..44], q));
    let r = nalgebra::Rotation3::from_matrix_unchecked(common::tool_rotation(x, q));
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
