//! The tests of `calib_arm::write`.

use calib_arm::files::{parse_measurements, parse_robot, parse_uncertainty};
use calib_arm::simulate::Uncertainty;
use calib_arm::write::*;
use calib_arm::{builtin_arm, simulate};
use std::path::Path;

#[test]
fn written_files_read_back_exactly() {
    let arm = builtin_arm();
    let f = Path::new("robot.toml");
    assert_eq!(parse_robot(f, &robot_toml(&arm)).expect("parses"), arm);
    let sim = simulate(&arm, 5, 2, Uncertainty::TRACKER, 1.0, &[]);
    let m = parse_measurements(f, &measurements_csv(&sim.readings, 6), 6).expect("parses");
    assert_eq!(m.readings, sim.readings);
    assert_eq!(m.lines, vec![2, 3, 4, 5, 6]);
    let u = parse_uncertainty(f, &uncertainty_toml(&sim.uncertainty)).expect("parses");
    assert_eq!(u, sim.uncertainty);
    let truth = truth_json(&sim.truth, 6);
    assert!(truth.contains("\"tool_z\": ") && truth.contains("\"theta1\": "));
}
