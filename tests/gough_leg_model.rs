//! The Gough leg residual (paper eq. 3): generated evaluators enclose point values over random boxes
//! around realistic configurations, and its Jacobians agree with finite differences and dual numbers.

use crate::core_support as support;

use calib_core::{Dual, Interval, Model};
use calib_gough::{gough_leg, GoughLeg};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use support::*;

const TABLE_I: [f64; 7] = [-9.7, 9.1, 0.0, -3.0, 7.3, 0.0, 52.2496];

/// A random configuration: position, Rodrigues vector of an up-to-15° rotation, leg reading.
fn configuration(rng: &mut StdRng) -> [f64; 7] {
    let q: [f64; 3] = core::array::from_fn(|_| rng.random_range(-0.13..0.13));
    [
        rng.random_range(-5.0..5.0),
        rng.random_range(-5.0..5.0),
        rng.random_range(55.0..65.0),
        q[0],
        q[1],
        q[2],
        rng.random_range(3.0..13.0),
    ]
}

#[test]
fn interval_evaluators_enclose_point_values() {
    let mut rng = StdRng::seed_from_u64(21);
    for _ in 0..20 {
        let m = configuration(&mut rng);
        assert_encloses(
            &GoughLeg,
            &mut rng,
            &TABLE_I,
            &[0.1; 7],
            &m,
            &[5e-4, 5e-4, 5e-4, 1e-4, 1e-4, 1e-4, 5e-4],
            30,
        );
        // Wide boxes too: the enclosure must hold however loose it gets.
        assert_encloses(
            &GoughLeg,
            &mut rng,
            &TABLE_I,
            &[3.0; 7],
            &m,
            &[1.0, 1.0, 1.0, 0.1, 0.1, 0.1, 1.0],
            10,
        );
    }
}

#[test]
fn jacobians_match_finite_differences_and_dual_numbers() {
    let mut rng = StdRng::seed_from_u64(22);
    for _ in 0..300 {
        let x: [f64; 7] = core::array::from_fn(|i| TABLE_I[i] + rng.random_range(-0.5..0.5));
        let m = configuration(&mut rng);
        assert_jacobians_match_finite_differences(&GoughLeg, &x, &m);
        assert_jacobians_match_dual(&GoughLeg, gough_leg::<Dual<14>>, &x, &m);
    }
}

#[test]
fn known_derivatives() {
    // df/da = -2 (P + R b - a), df/dl = df/dL = -2 (L + l): check at q = 0 (R = identity).
    let x = TABLE_I;
    let m = [1.0, 2.0, 60.0, 0.0, 0.0, 0.0, 8.0];
    let e: [f64; 3] = core::array::from_fn(|i| m[i] + x[3 + i] - x[i]);
    let p = GoughLeg.evaluate(&x, &m);
    for (i, ei) in e.iter().enumerate() {
        assert!((p.dx[i] + 2.0 * ei).abs() < 1e-12);
        assert!((p.dx[3 + i] - 2.0 * ei).abs() < 1e-12);
    }
    assert!((p.dx[6] + 2.0 * (m[6] + x[6])).abs() < 1e-12);
    assert_eq!(p.dx[6], p.dm[6]);
    let iv = GoughLeg.residual_interval(&x.map(Interval::point), &m.map(Interval::point));
    assert!(iv.contains(p.value) && iv.wid() < 1e-9);
}
