//! The tests of `calib_arm::register`.

use calib_arm::register::*;
use calib_arm::simulate::{simulate, Uncertainty};

#[test]
fn a_far_rotated_tracker_and_an_unknown_tool_are_found_from_scratch() {
    // The geometry exactly nominal (no prior): only the base and the tool are unknown.
    let mut truth = calib_arm::builtin_arm().with_radii_scaled(0.0);
    // A tracker 3.6 m away, turned 140° and tilted.
    truth.base = [-2500.0, 2600.0, 300.0, 3.0, -4.0, 140.0];
    truth.tool = [5.0, -3.0, 93.0];
    let sim = simulate(&truth, 30, 11, Uncertainty::TRACKER, 0.0, &[]);
    let mut nominal = truth.clone();
    nominal.base = [0.0; 6];
    nominal.tool = [0.0; 3];
    let r = register(&nominal, &sim.readings, RegistrationPriors::default()).expect("found");
    let close = |a: &[f64], b: &[f64], tol: f64| a.iter().zip(b).all(|(x, y)| (x - y).abs() < tol);
    assert!(close(&r.arm.base, &truth.base, 0.01), "{:?}", r.arm.base);
    assert!(close(&r.arm.tool, &truth.tool, 0.01), "{:?}", r.arm.tool);
    assert!(r.rms < 0.05 && r.converged, "{r:?}");
    assert_eq!(r.arm.base_radius, [2.0, 2.0, 2.0, 0.1, 0.1, 0.1]);
    // Too few configurations is an error, not a guess.
    assert!(register(&nominal, &sim.readings[..2], RegistrationPriors::default()).is_err());
}
