//! Identifiability before certifying: the dependent parameter sets of a serial arm are found from
//! the identification Jacobian at the nominal and named; the built-in default set has none.

use calib_arm::certification::{identifiability, names};
use calib_arm::simulate::{simulate, Uncertainty};
use calib_arm::{builtin_arm, Arm};

/// The built-in arm with its base untilted and every parameter of joint 1 and of the base free:
/// `theta1` then turns the chain about the same axis as `base_rz`, and `d1` moves it along the
/// same axis as `base_z`.
fn untilted_with_joint1_free() -> Arm {
    let mut arm = builtin_arm();
    arm.base[3] = 0.0;
    arm.base[4] = 0.0;
    arm.joints[0].radius = [0.05, 0.5, 0.5, 0.05, 0.0];
    arm
}

fn members(arm: &Arm) -> Vec<Vec<String>> {
    let sim = simulate(arm, 40, 3, Uncertainty::TRACKER, 1.0, &[]);
    let id = identifiability(arm, &sim.readings, &sim.uncertainty).expect("6 joints");
    let names = names(arm.joints.len());
    id.undetermined
        .iter()
        .map(|c| {
            let mut m: Vec<String> = c.members.iter().map(|(j, _)| names[*j].clone()).collect();
            m.sort();
            m
        })
        .collect()
}

#[test]
fn dependent_sets_are_named_with_the_parameters_to_fix() {
    let arm = untilted_with_joint1_free();
    let found = members(&arm);
    assert!(
        found.contains(&vec!["base_rz".to_string(), "theta1".to_string()]),
        "{found:?}"
    );
    assert!(
        found.contains(&vec!["base_z".to_string(), "d1".to_string()]),
        "{found:?}"
    );
    let sim = simulate(&arm, 40, 3, Uncertainty::TRACKER, 1.0, &[]);
    let id = identifiability(&arm, &sim.readings, &sim.uncertainty).expect("6 joints");
    let words = id.sentences(&names(6)).join("\n");
    assert!(
        words.contains("not identifiable") && words.contains("fix one of them"),
        "{words}"
    );
}

#[test]
fn the_builtin_parameter_set_is_identifiable() {
    assert_eq!(members(&builtin_arm()), Vec::<Vec<String>>::new());
}
