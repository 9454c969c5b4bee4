//! The tests of `calib_arm::params`.

use calib_arm::params::*;

#[test]
fn six_joints_have_the_issue_s_39_names_in_order() {
    let n = names(6);
    assert_eq!(n.len(), 39);
    assert_eq!(n[0].0, "theta1");
    assert_eq!(n[29].0, "beta6");
    assert_eq!(n[30].0, "base_x");
    assert_eq!(n[35], ("base_rz".to_string(), Unit::Deg));
    assert_eq!(n[38], ("tool_z".to_string(), Unit::Mm));
}

#[test]
fn every_parameter_name_has_its_unit_and_6dof_adds_the_tool_rotation() {
    let n = pose_names(6);
    assert_eq!(n.len(), 42);
    assert_eq!(n[39], ("tool_rx".to_string(), Unit::Deg));
    for (name, unit) in n.iter().chain(&names(7)) {
        assert_eq!(unit_of(name), Some(*unit), "{name}");
    }
    assert_eq!(unit_of("theta"), None);
    assert_eq!(unit_of("tool_w"), None);
    assert_eq!(unit_of("d12"), Some(Unit::Mm));
}
