//! The tests of `calib_arm::simulate`.

use calib_arm::builtin_arm;
use calib_arm::model::tracked_point;
use calib_arm::params::{self, Unit};
use calib_arm::simulate::*;
use calib_arm::units::to_rad;
use calib_core::Interval;

#[test]
fn readings_lie_within_the_error_bounds_of_the_truth() {
    let arm = builtin_arm();
    let sim = simulate(&arm, 20, 3, Uncertainty::TRACKER, 1.0, &[(4, 0.5)]);
    let units = params::names(6);
    let x: Vec<f64> = sim
        .truth
        .iter()
        .zip(&units)
        .map(|(v, (_, u))| if *u == Unit::Deg { to_rad(*v) } else { *v })
        .collect();
    for (k, r) in sim.readings.iter().enumerate() {
        let b: [Interval; 9] = measurement_box(r, &sim.uncertainty).unwrap();
        // With the true joint angles (within the joint boxes) the true point is within 0.01
        // of the reading, except for the outlier.
        let q: Vec<f64> = r.joints_deg.iter().map(|v| to_rad(*v)).collect();
        let p = tracked_point(&x, &q).unwrap();
        let off = (0..3)
            .map(|i| (p[i] - r.point[i]).abs())
            .fold(0.0, f64::max);
        if k == 4 {
            assert!(off > 0.1, "the outlier moved by 0.5 mm");
        } else {
            // The joint noise moves the point by up to ~0.02 mm per joint at this reach.
            assert!(off < 0.2, "configuration {k}: {off}");
        }
        assert!(b[0].contains(q[0]) && b[6].contains(r.point[0]));
    }
    for (v, (n, r)) in sim.truth.iter().zip(arm.nominal().iter().zip(arm.radius())) {
        assert!((v - n).abs() <= 0.8 * r + 1e-12);
    }
}

#[test]
fn boxes_pad_missing_joints_with_exact_zeros() {
    let r = Reading {
        joints_deg: vec![10.0, -20.0, 30.0],
        point: [1.0, 2.0, 3.0],
    };
    let b: [Interval; 10] = measurement_box(&r, &Uncertainty::TRACKER).expect("3 <= 7");
    assert!(b[0].contains(10f64.to_radians()) && b[0].wid() > 0.0);
    for padded in &b[3..7] {
        assert_eq!(*padded, Interval::ZERO);
    }
    assert!(b[7].contains(1.0) && b[9].contains(3.0));
    assert!(measurement_box::<5>(&r, &Uncertainty::TRACKER).is_none());
}
