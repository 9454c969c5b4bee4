//! The tests of `calib_arm::register`.

use calib_arm::register::*;
use calib_arm::robot::Arm;
use calib_arm::simulate::{simulate, Reading, Uncertainty};
use calib_arm::vendor::arm_point;

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
    // Random configurations turn the flange every way: the tool is fitted, nothing said.
    assert!(!r.tool_kept && r.arm.tool_radius == [2.0; 3], "{r:?}");
    assert!(r.separability.spread_deg > 10.0, "{:?}", r.separability);
    assert_eq!(r.separability.reason(), None);
    // Too few configurations is an error, not a guess.
    assert!(register(&nominal, &sim.readings[..2], RegistrationPriors::default()).is_err());
}

/// The builtin arm (UR-like: joints 2, 3 and 4 parallel) with no prior, a far tracker and a tool
/// 93 mm out; and its nominal with neither base nor tool known but a tool guess of `tool`.
fn truth_and_nominal(tool: [f64; 3]) -> (Arm, Arm) {
    let mut truth = calib_arm::builtin_arm().with_radii_scaled(0.0);
    truth.base = [-2500.0, 2600.0, 300.0, 3.0, -4.0, 140.0];
    truth.tool = [5.0, -3.0, 93.0];
    let mut nominal = truth.clone();
    nominal.base = [0.0; 6];
    nominal.tool = tool;
    (truth, nominal)
}

/// Exact readings of `arm` at `joints` (degrees).
fn readings(arm: &Arm, joints: &[[f64; 6]]) -> Vec<Reading> {
    joints
        .iter()
        .map(|q| Reading {
            joints_deg: q.to_vec(),
            point: arm_point(arm, &q.map(f64::to_radians)),
        })
        .collect()
}

/// Configurations of one flange orientation: joints 1, 5 and 6 held, and `q2 + q3 + q4` (the
/// parallel axes') too, while the wrist moves over the arm's plane.
fn one_orientation(k: usize) -> [f64; 6] {
    let (q2, q3) = (-60.0 + 7.0 * (k % 6) as f64, 40.0 + 9.0 * (k / 6) as f64);
    [30.0, q2, q3, -70.0 - q2 - q3, 80.0, 15.0]
}

#[test]
fn one_flange_orientation_keeps_the_files_tool_and_fits_the_base_alone() {
    let (truth, nominal) = truth_and_nominal([0.0, 0.0, 90.0]);
    let joints: Vec<[f64; 6]> = (0..30).map(one_orientation).collect();
    let data = readings(&truth, &joints);
    let r = register(&nominal, &data, RegistrationPriors::default()).expect("registered");
    let s = r.separability;
    assert!(
        s.spread_deg < 1e-6 && s.orientation_range_deg < 1e-4,
        "{s:?}"
    );
    assert!(s.inseparable() && s.rows == 30);
    let reason = s.reason().expect("said");
    assert!(
        reason.contains("the 30 configurations hold one flange orientation")
            && reason.contains("base and tool cannot be told apart"),
        "{reason}"
    );
    // The file's tool point kept and fixed; the base's position takes up the difference, so
    // the rows fit exactly all the same.
    assert!(r.tool_kept, "{r:?}");
    assert_eq!(r.arm.tool, nominal.tool);
    assert_eq!(r.arm.tool_radius, [0.0; 3]);
    assert_eq!(r.arm.base_radius, [2.0, 2.0, 2.0, 0.1, 0.1, 0.1]);
    assert!(r.rms < 1e-6 && r.converged, "{r:?}");
    // Asked to fit the tool anyway: fitted, and still reported inseparable.
    let fit = register_with(
        &nominal,
        &data,
        RegistrationPriors::default(),
        ToolPoint::Fit,
    )
    .expect("registered");
    assert!(!fit.tool_kept && fit.separability.inseparable());
    assert_eq!(fit.arm.tool_radius, [2.0; 3]);
}

#[test]
fn turns_about_one_axis_leave_the_tool_along_it_unseen() {
    // One orientation turned about the flange's axis by joint 6 alone: the tool point's
    // component along that axis stays with the base.
    let (truth, nominal) = truth_and_nominal([0.0; 3]);
    let joints: Vec<[f64; 6]> = (0..30)
        .map(|k| {
            let mut q = one_orientation(k);
            q[5] = -150.0 + 11.0 * k as f64;
            q
        })
        .collect();
    let r = register(
        &nominal,
        &readings(&truth, &joints),
        RegistrationPriors::default(),
    )
    .expect("registered");
    let s = r.separability;
    assert!(
        s.spread_deg < 1e-6 && s.orientation_range_deg > 100.0,
        "{s:?}"
    );
    assert!(s.weakest[2].abs() > 1.0 - 1e-9, "{s:?}");
    let reason = s.reason().expect("said");
    assert!(
        reason.contains("spread 0.0000° across the flange direction (")
            && reason.contains("turns about that axis only"),
        "{reason}"
    );
    assert!(r.tool_kept && r.arm.tool == [0.0; 3] && r.arm.tool_radius == [0.0; 3]);
}

#[test]
fn the_tool_is_kept_when_asked_even_where_it_could_be_fitted() {
    let (truth, nominal) = truth_and_nominal([1.0, 2.0, 80.0]);
    let sim = simulate(&truth, 20, 5, Uncertainty::TRACKER, 0.0, &[]);
    let r = register_with(
        &nominal,
        &sim.readings,
        RegistrationPriors::default(),
        ToolPoint::Keep,
    )
    .expect("registered");
    assert_eq!(r.separability.reason(), None);
    assert!(r.tool_kept && r.arm.tool == nominal.tool && r.arm.tool_radius == [0.0; 3]);
    // A wrong tool at many orientations: the base cannot take it up.
    assert!(r.rms > 1.0, "{r:?}");
}
