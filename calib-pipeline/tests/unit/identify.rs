//! The tests of `calib_pipeline::identify`.

use calib_pipeline::identify::*;
use nalgebra::DMatrix;

#[test]
fn weak_groups_are_named_once_in_order_smallest_first() {
    let names: Vec<String> = (0..12).map(|i| format!("p{i}")).collect();
    let group = |m: &[usize], effect: f64| Combination {
        effect,
        members: m.iter().map(|&j| (j, 1.0)).collect(),
    };
    let id = Identifiability {
        singular_values: vec![],
        undetermined: vec![],
        weak: vec![
            group(&[0, 1, 2, 3, 4, 5, 6, 7, 8], 0.5),
            group(&[3, 1], 0.2),
            group(&[1, 3], 0.3),
        ],
    };
    let s = id.sentences(&names);
    assert_eq!(s.len(), 2, "{s:?}");
    assert!(s[0].contains("moving p1, p3 together"), "{}", s[0]);
    assert!(
        s[1].contains("9 parameters (p0, p1, p2, p3, p4, p5, and 3 more)"),
        "{}",
        s[1]
    );
}

#[test]
fn a_dependent_pair_is_named_and_a_clean_set_is_not() {
    // Columns 0 and 2 always act together (p0 + p2), column 1 alone.
    let j = DMatrix::from_row_slice(
        4,
        3,
        &[
            1.0, 2.0, 1.0, //
            2.0, -1.0, 2.0, //
            -1.0, 3.0, -1.0, //
            0.5, 1.0, 0.5,
        ],
    );
    let a = analyse(&[0, 4, 7], j);
    assert_eq!(a.undetermined.len(), 1);
    let mut members: Vec<usize> = a.undetermined[0].members.iter().map(|m| m.0).collect();
    members.sort();
    assert_eq!(members, vec![0, 7]);
    let names: Vec<String> = (0..8).map(|j| format!("p{j}")).collect();
    let words = a.sentences(&names).join("\n");
    assert!(words.contains("p0") && words.contains("p7"), "{words}");
    assert!(!words.contains("p4"), "{words}");

    let clean = DMatrix::from_row_slice(3, 2, &[10.0, 0.0, 0.0, 10.0, 5.0, 5.0]);
    let a = analyse(&[0, 1], clean);
    assert!(a.undetermined.is_empty() && a.weak.is_empty());
}

#[test]
fn a_parameter_that_moves_the_readings_less_than_the_noise_is_weak() {
    let j = DMatrix::from_row_slice(3, 2, &[10.0, 0.01, 5.0, -0.02, 7.0, 0.0]);
    let a = analyse(&[0, 1], j);
    assert!(a.undetermined.is_empty());
    assert_eq!(a.weak.len(), 1);
    assert_eq!(a.weak[0].members[0].0, 1);
}
