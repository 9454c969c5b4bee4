//! The tests of `calib_arm::robot`.

use calib_arm::robot::*;

#[test]
fn the_builtin_arm_has_27_free_parameters_and_a_box_around_its_nominal() {
    let arm = builtin_arm();
    assert_eq!(arm.free().iter().filter(|f| **f).count(), 27);
    let b = arm.initial_box();
    assert_eq!(b.len(), 39);
    assert!(b[2].contains(0.0) && b[2].rad() >= 0.5);
    // alpha1 = 90° ± 0.05° in radians.
    assert!(b[3].contains(std::f64::consts::FRAC_PI_2));
    assert!((b[3].rad() - 0.05f64.to_radians()).abs() < 1e-12);
    // theta1 is fixed at 0: a point.
    assert_eq!(b[0].wid(), 0.0);
}
