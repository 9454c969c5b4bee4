//! The certified kernel on random arms (3 to 7 joints, random geometry and data): the truth is
//! always inside, consistent data are never proved empty, every witness and inner point is
//! certified for the coupled set (one joint reading fits x, y and z) and rechecked by an
//! independent search for that reading; a shifted configuration is named.
#![allow(clippy::needless_range_loop)]

use crate::core_support as support;

use calib_arm::certification::{padded_box, padded_index, NX};
use calib_arm::simulate::{measurement_box, Uncertainty};
use calib_arm::{params, simulate, Arm, Arm7Point, Joint};
use calib_core::{certify, is_consistent_point, Interval, Settings, Status};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use support::fits_with_one_reading_all;

/// A random arm of `joints` joints with small priors (so that one Newton step already bites on
/// this nonlinear chain; the large priors of the built-in arm need the tight hull).
pub(crate) fn random_arm(joints: usize, rng: &mut StdRng) -> Arm {
    let joint = |rng: &mut StdRng| Joint {
        nominal: [
            rng.random_range(-5.0..5.0),
            rng.random_range(0.0..150.0),
            rng.random_range(-450.0..450.0),
            [0.0, 90.0, -90.0][rng.random_range(0..3)] + rng.random_range(-1.0..1.0),
            0.0,
        ],
        radius: [2e-4, 0.002, 0.002, 2e-4, 0.0],
    };
    Arm {
        joints: (0..joints).map(|_| joint(rng)).collect(),
        base: [
            rng.random_range(-1500.0..1500.0),
            rng.random_range(-1500.0..1500.0),
            rng.random_range(-500.0..500.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-180.0..180.0),
        ],
        base_radius: [0.005, 0.005, 0.005, 5e-4, 5e-4, 5e-4],
        tool: [
            rng.random_range(-50.0..50.0),
            rng.random_range(-50.0..50.0),
            rng.random_range(0.0..150.0),
        ],
        tool_radius: [0.002; 3],
        tool_rotation: None,
    }
}

/// Truth in model units (radians).
pub(crate) fn truth_in_model_units(arm: &Arm, truth: &[f64]) -> Vec<f64> {
    params::names(arm.joints.len())
        .iter()
        .zip(truth)
        .map(|((_, u), v)| {
            if *u == params::Unit::Deg {
                v.to_radians()
            } else {
                *v
            }
        })
        .collect()
}

/// Certifies simulated data of `arm` through the padded 7-joint model directly (the kernel's
/// result, before the pipeline).
fn check(arm: &Arm, seed: u64, outlier: bool) -> Status {
    let model = &Arm7Point;
    let shift: Vec<(usize, f64)> = if outlier { vec![(2, 0.5)] } else { vec![] };
    let sim = simulate(arm, 10, seed, Uncertainty::TRACKER, 1.0, &shift);
    let data: Vec<[Interval; 10]> = sim
        .readings
        .iter()
        .map(|r| measurement_box(r, &sim.uncertainty).unwrap())
        .collect();
    let x0 = padded_box(arm);
    let mut truth = [0.0; NX];
    for (&p, v) in padded_index(arm.joints.len())
        .iter()
        .zip(truth_in_model_units(arm, &sim.truth))
    {
        truth[p] = v;
    }
    let c = certify(model, &x0, &data, &Settings::default());
    let what = format!("{} joints, seed {seed}", arm.joints.len());
    if outlier {
        assert_eq!(
            c.status,
            Status::Empty,
            "{what}: a 0.5 mm shift was not proved inconsistent"
        );
        assert!(
            c.conflict.as_ref().is_some_and(|k| k.contains(&2)),
            "{what}: {:?}",
            c.conflict
        );
        return c.status;
    }
    assert_ne!(
        c.status,
        Status::Empty,
        "{what}: consistent data proved empty"
    );
    for j in 0..NX {
        assert!(
            c.outer[j].contains(truth[j]),
            "{what}: parameter {j} truth outside {}",
            c.outer[j]
        );
    }
    if let Some(w) = c.witness {
        assert!(is_consistent_point(model, &w, &data));
        assert!(
            fits_with_one_reading_all(model, &w, &data),
            "{what}: witness fails the recheck"
        );
        let inner = c.inner.unwrap();
        assert!((0..NX).all(|j| inner[j].is_subset_of(c.outer[j])));
    }
    c.status
}

#[test]
fn random_arms_keep_the_truth_and_certify_one_reading_per_configuration() {
    // Three-joint arms through the padded 7-joint model, with every witness rechecked; 3 to 7
    // joints through the pipeline's `certify_arm` below.
    let mut consistent = 0;
    for seed in 0..4u64 {
        let mut rng = StdRng::seed_from_u64(seed);
        let arm = random_arm(3, &mut rng);
        consistent += usize::from(check(&arm, seed, false) == Status::Consistent);
    }
    assert!(
        consistent >= 3,
        "only {consistent} of 4 arms certified consistent"
    );
}

#[test]
fn a_shifted_configuration_is_proved_inconsistent_and_named() {
    let mut rng = StdRng::seed_from_u64(77);
    let arm = random_arm(3, &mut rng);
    check(&arm, 77, true);
}

#[test]
fn arms_of_3_to_7_joints_certify_through_the_padded_model() {
    use calib_arm::certification::{certify_arm, RunOptions};
    use calib_pipeline::Depth;
    for joints in 3..=7 {
        let seed = 100 + joints as u64;
        let mut rng = StdRng::seed_from_u64(seed);
        let arm = random_arm(joints, &mut rng);
        let sim = simulate(&arm, 10, seed, Uncertainty::TRACKER, 1.0, &[]);
        let options = RunOptions {
            depth: Depth::Fast,
            lsq: false,
        };
        let run = certify_arm(
            &arm,
            &sim.readings,
            &sim.uncertainty,
            options,
            &Settings::default(),
        )
        .expect("3 to 7 joints");
        let o = &run.outcome;
        assert_ne!(
            o.status,
            Status::Empty,
            "{joints} joints: consistent data proved empty"
        );
        assert_eq!(o.x0.len(), params::count(joints));
        let outer = o.outer.as_ref().expect("not empty");
        for (j, t) in sim.truth.iter().enumerate() {
            // Files' units (degrees, mm), boxes converted outward.
            assert!(
                outer[j].contains(*t),
                "{joints} joints: {} truth {t} outside {}",
                o.names[j],
                outer[j]
            );
            assert!(o.x0[j].contains(*t));
        }
        if let (Some(inner), Some(w)) = (&o.inner, &o.witness) {
            for j in 0..outer.len() {
                assert!(inner[j].is_subset_of(outer[j]) || inner[j].wid() <= 1e-9);
                assert!(outer[j].inf() - 1e-9 <= w[j] && w[j] <= outer[j].sup() + 1e-9);
            }
        }
    }
}
