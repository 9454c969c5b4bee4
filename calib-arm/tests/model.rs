//! The arm residual against an independent forward kinematics (4×4 homogeneous matrices with
//! nalgebra), its interval evaluators against point values, and its degree/radian handling.

use calib_arm::model::tracked_point;
use calib_arm::Arm7Point;
use calib_core::{Interval, VectorModel};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

use crate::common;
use common::forward;

/// A UR5-like geometry (mm, radians) perturbed at random.
pub(crate) fn random_arm(rng: &mut StdRng, joints: usize) -> Vec<f64> {
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

#[test]
fn each_joint_enters_the_tool_point_through_its_cosine_and_sine_only() {
    // The accuracy engine's wide boxes rest on it (`ToolPoint`'s `ANGULAR_INPUTS`): for fixed
    // parameters and other joints, the point and its derivatives are `A cos q + B sin q + C`:
    // fitted at 0, π/2 and π, the fit holds at any other angle.
    let mut rng = StdRng::seed_from_u64(12);
    let half_pi = std::f64::consts::FRAC_PI_2;
    for _ in 0..100 {
        let x: [f64; 44] = random_arm(&mut rng, 7).try_into().unwrap();
        let m: [f64; 10] = core::array::from_fn(|k| {
            if k < 7 {
                rng.random_range(-3.0..3.0)
            } else {
                0.0
            }
        });
        for joint in 0..7 {
            let at = |q: f64| {
                let mut a = m;
                a[joint] = q;
                let rows = Arm7Point.evaluate_rows(&x, &a);
                let mut out = Vec::new();
                for r in &rows {
                    out.push(r.value);
                    out.extend_from_slice(&r.dx);
                    out.extend_from_slice(&r.dm[..7]);
                }
                out
            };
            let (f0, f1, f2) = (at(0.0), at(half_pi), at(2.0 * half_pi));
            let q = rng.random_range(-3.0..3.0);
            let fq = at(q);
            for k in 0..fq.len() {
                let c = (f0[k] + f2[k]) / 2.0;
                let (a, b) = ((f0[k] - f2[k]) / 2.0, f1[k] - c);
                let fit = a * q.cos() + b * q.sin() + c;
                let size = 1.0 + a.abs() + b.abs() + c.abs();
                assert!(
                    (fq[k] - fit).abs() <= 1e-9 * size,
                    "joint {joint}, entry {k}: {} against the fit's {fit}",
                    fq[k]
                );
            }
        }
    }
}
