//! Carrying a certified set over to a new tracker frame (`calib_arm::carry`): the two-frame
//! model against an independent forward kinematics, the truth kept, the joints narrowed by the
//! earlier rows, and a robot that changed proved inconsistent.

use crate::common::forward;
use crate::kernel::{random_arm, truth_in_model_units};
use calib_arm::carry::{certify_carried, NM2, NX2};
use calib_arm::certification::{certify_request, padded_index, ArmSet, CertifyRequest};
use calib_arm::model::Arm7PointTwoFrames;
use calib_arm::simulate::{Reading, Uncertainty};
use calib_arm::{params, simulate, Arm};
use calib_core::{Interval, Status, VectorModel};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Where the arm's parameters put the base (files' and model order alike).
fn base_at(arm: &Arm) -> usize {
    5 * arm.joints.len()
}

/// Readings of the parameters `x` (model units) at `n` random configurations, within `u`.
fn readings(x: &[f64], joints: usize, n: usize, u: Uncertainty, rng: &mut StdRng) -> Vec<Reading> {
    (0..n)
        .map(|_| {
            let q: Vec<f64> = (0..joints)
                .map(|_| rng.random_range(-170.0..170.0))
                .collect();
            let q_rad: Vec<f64> = q.iter().map(|v: &f64| v.to_radians()).collect();
            let p = forward(x, &q_rad);
            let mut noise = |r: f64| rng.random_range(-0.9..0.9) * r;
            Reading {
                joints_deg: q.iter().map(|v| v + noise(u.joint_deg)).collect(),
                point: p.map(|v| v + noise(u.pos)),
            }
        })
        .collect()
}

/// `x` (files' units) with the base moved 250 mm and turned 15° about z.
fn moved(arm: &Arm, x: &[f64]) -> Vec<f64> {
    let mut y = x.to_vec();
    let b = base_at(arm);
    y[b] += 250.0;
    y[b + 5] += 15.0;
    y
}

/// `arm` with its base's nominal at the base of `x` (files' units), prior unchanged.
fn registered_at(arm: &Arm, x: &[f64]) -> Arm {
    let mut here = arm.clone();
    let b = base_at(arm);
    here.base.copy_from_slice(&x[b..b + 6]);
    here
}

/// A random 4-joint arm whose priors the data narrow (20 times the kernel tests').
fn arm(rng: &mut StdRng) -> Arm {
    let mut arm = random_arm(4, rng);
    for j in &mut arm.joints {
        j.radius = j.radius.map(|r| 20.0 * r);
    }
    arm.base_radius = arm.base_radius.map(|r| 20.0 * r);
    arm.tool_radius = arm.tool_radius.map(|r| 20.0 * r);
    arm
}

/// What the earlier calibration found (files' units).
struct Earlier {
    truth: Vec<f64>,
    set: ArmSet,
    prior: Vec<Interval>,
    outer: Vec<Interval>,
}

/// The earlier calibration of `arm` on 12 simulated configurations.
fn earlier(arm: &Arm, seed: u64) -> Earlier {
    let sim = simulate(arm, 12, seed, Uncertainty::TRACKER, 0.9, &[]);
    let (_, run) = certify_request(arm, &sim.readings, &sim.uncertainty, &Default::default())
        .expect("a 4-joint arm");
    Earlier {
        truth: sim.truth,
        prior: run.outcome.x0.clone(),
        outer: run
            .outcome
            .outer
            .clone()
            .expect("consistent simulated data"),
        set: run.set.expect("a certified set"),
    }
}

#[test]
fn the_two_frame_model_is_the_point_model_in_either_frame() {
    let mut rng = StdRng::seed_from_u64(5);
    let arm = random_arm(7, &mut rng);
    let truth = truth_in_model_units(&arm, &arm.nominal());
    let other = truth_in_model_units(&arm, &moved(&arm, &arm.nominal()));
    let mut x = [0.0; NX2];
    for (&p, (&v, &w)) in padded_index(7).iter().zip(truth.iter().zip(&other)) {
        x[p] = v;
        if p >= 35 {
            // The earlier frame's base and tool (parameters 44–52) are `other`'s.
            x[p + 9] = w;
        }
    }
    for _ in 0..20 {
        let q: Vec<f64> = (0..7).map(|_| rng.random_range(-3.0..3.0)).collect();
        for (flag, params) in [(0.0, &truth), (1.0, &other)] {
            let p = forward(params, &q);
            let mut m = [0.0; NM2];
            m[..7].copy_from_slice(&q);
            m[7..10].copy_from_slice(&p);
            m[10] = flag;
            let r = Arm7PointTwoFrames.residuals(&x, &m);
            for v in r {
                assert!(v.abs() < 1e-8, "flag {flag}: residual {v}");
            }
        }
    }
}

#[test]
fn carried_sets_keep_the_truth_and_narrow_the_joints() {
    for seed in [11u64, 12] {
        let mut rng = StdRng::seed_from_u64(seed);
        let arm = arm(&mut rng);
        let before = earlier(&arm, seed);
        let there = moved(&arm, &before.truth);
        let here = registered_at(&arm, &there);
        let new = readings(
            &truth_in_model_units(&arm, &there),
            4,
            6,
            Uncertainty::TRACKER,
            &mut rng,
        );
        let u = Uncertainty::TRACKER;
        let request = CertifyRequest::default();
        let (_, carried) =
            certify_carried(&here, &before.set, &new, &u, &request).expect("4 joints");
        let (_, alone) = certify_request(&here, &new, &u, &request).expect("4 joints");
        let outer = carried.outcome.outer.clone().expect("consistent");
        let outer_alone = alone.outcome.outer.clone().expect("consistent");
        let names = params::names(4);
        for (j, t) in there.iter().enumerate() {
            assert!(
                outer[j].contains(*t),
                "seed {seed}: {} {t} outside {}",
                names[j].0,
                outer[j]
            );
        }
        assert!(carried.set.is_some(), "seed {seed}: no set handed on");
        // The joints' parameters: no wider than the earlier set's box allows, and narrower
        // together than the new rows alone make them.
        let joints = base_at(&arm);
        let mut sum = (0.0, 0.0);
        for j in 0..joints {
            assert!(
                outer[j].wid() <= before.outer[j].wid() * (1.0 + 1e-9) + 1e-12,
                "seed {seed}: {} {} wider than the earlier {}",
                names[j].0,
                outer[j],
                before.outer[j]
            );
            sum.0 += outer[j].wid();
            sum.1 += outer_alone[j].wid();
        }
        assert!(
            sum.0 < 0.9 * sum.1,
            "seed {seed}: widths {} vs alone {}",
            sum.0,
            sum.1
        );
    }
}

#[test]
fn a_robot_that_changed_refutes_its_earlier_set() {
    let seed = 21;
    let mut rng = StdRng::seed_from_u64(seed);
    let arm = arm(&mut rng);
    let before = earlier(&arm, seed);
    // The joint parameter the earlier rows pin best, moved outside their box but inside the
    // prior: the new rows alone are consistent, with the earlier set they are not.
    let (prior, outer_before) = (&before.prior, &before.outer);
    let room = |j: usize| {
        let above = prior[j].sup() - outer_before[j].sup();
        let below = outer_before[j].inf() - prior[j].inf();
        (above.max(below) / prior[j].wid(), above >= below)
    };
    let j = (0..base_at(&arm))
        .filter(|&j| prior[j].wid() > 0.0)
        .max_by(|&a, &b| room(a).0.total_cmp(&room(b).0))
        .expect("a free joint parameter");
    let mut changed = moved(&arm, &before.truth);
    changed[j] = if room(j).1 {
        0.5 * (outer_before[j].sup() + prior[j].sup())
    } else {
        0.5 * (outer_before[j].inf() + prior[j].inf())
    };
    assert!(!outer_before[j].contains(changed[j]) && prior[j].contains(changed[j]));
    let here = registered_at(&arm, &changed);
    let u = Uncertainty::TRACKER;
    let new = readings(&truth_in_model_units(&arm, &changed), 4, 12, u, &mut rng);
    let request = CertifyRequest::default();
    let (_, alone) = certify_request(&here, &new, &u, &request).expect("4 joints");
    assert_ne!(
        alone.outcome.status,
        Status::Empty,
        "the changed robot's own rows"
    );
    let (_, carried) = certify_carried(&here, &before.set, &new, &u, &request).expect("4 joints");
    assert_eq!(
        carried.outcome.status,
        Status::Empty,
        "a changed robot kept its set"
    );
    assert!(carried.set.is_none());
}
