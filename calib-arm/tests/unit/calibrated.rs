//! The tests of `calib_arm::calibrated`.

use calib_arm::calibrated::*;
use calib_arm::certification::NM;
use calib_arm::certification::{certify_arm, RunOptions};
use calib_arm::simulate::{measurement_box, simulate, Uncertainty};
use calib_arm::Arm7Point;
use calib_core::{is_certified_consistent, Interval};
use calib_pipeline::Depth;

#[test]
fn the_calibrated_arm_fits_every_measurement_and_its_box_contains_the_certified_one() {
    let arm = calib_arm::builtin_arm();
    let sim = simulate(&arm, 30, 5, Uncertainty::TRACKER, 1.0, &[]);
    let run = certify_arm(
        &arm,
        &sim.readings,
        &sim.uncertainty,
        RunOptions {
            depth: Depth::Fast,
            lsq: false,
        },
        &calib_arm::certification::arm_settings(),
    )
    .expect("an arm");
    let joints: Vec<Vec<f64>> = sim.readings.iter().map(|r| r.joints_deg.clone()).collect();
    let c = calibrated_arm(&arm, &run, &joints, PointChoice::LeastSquares).expect("consistent");
    let boxes: Vec<[Interval; NM]> = sim
        .readings
        .iter()
        .filter_map(|r| measurement_box(r, &sim.uncertainty))
        .collect();
    assert!(is_certified_consistent(
        &Arm7Point,
        &read_back(&c.arm),
        &boxes
    ));
    let outer = run.outcome.outer.as_ref().expect("outer");
    for ((v, r), (o, r0)) in c
        .arm
        .nominal()
        .iter()
        .zip(c.arm.radius())
        .zip(outer.iter().zip(arm.radius()))
    {
        if r0 == 0.0 {
            assert_eq!(r, 0.0);
        } else {
            assert!(v - r <= o.inf() && o.sup() <= v + r);
        }
    }
}
