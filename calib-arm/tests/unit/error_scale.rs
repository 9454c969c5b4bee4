//! The tests of `calib_arm::error_scale`.

use calib_arm::certification::{padded_box, MAX_JOINTS, NM};
use calib_arm::error_scale::*;
use calib_arm::simulate::{measurement_box, Uncertainty};
use calib_arm::Arm7Point;
use calib_core::Interval;
use calib_core::{is_consistent_point, smallest_scale};

#[test]
fn only_the_chosen_bounds_scale_and_they_round_up() {
    let u = Uncertainty {
        joint_deg: 0.001,
        pos: 0.05,
    };
    let p = ScaleBounds::Pos.scale(&u, 3.0);
    assert_eq!(p.joint_deg, 0.001);
    assert!(p.pos >= 0.15 && p.pos - 0.15 < 1e-15);
    let j = ScaleBounds::JointDeg.scale(&u, 2.0);
    assert_eq!(j.pos, 0.05);
    assert!(j.joint_deg >= 0.002 && j.joint_deg - 0.002 < 1e-17);
    let a = ScaleBounds::All.scale(&u, 0.1);
    assert!(a.pos >= 0.005 && a.joint_deg >= 0.0001);
    assert_eq!(ScaleBounds::Pos.describe(&u, 2.0), "pos 0.1000 mm");
}

#[test]
fn the_bracket_holds_the_truth_and_starts_at_the_chebyshev_witness() {
    let arm = calib_arm::builtin_arm();
    let sim = calib_arm::simulate::simulate(&arm, 30, 5, Uncertainty::TRACKER, 1.0, &[]);
    // Bounds four times too tight for the noise: the truth fits at × 4.
    let u = Uncertainty {
        pos: sim.uncertainty.pos / 4.0,
        joint_deg: sim.uncertainty.joint_deg / 4.0,
    };
    let found = search(&arm, &sim.readings, &u, ScaleBounds::All, |_| {}).expect("search");
    let (lo, hi) = (found.s_lo.expect("s_lo"), found.s_hi.expect("s_hi"));
    assert!(lo < hi && lo < 4.0, "{lo} {hi}: the truth fits at × 4");
    // The first trial is just above the Chebyshev estimate; its point proves the upper end
    // within 1%.
    let boxes: Vec<[Interval; NM]> = sim
        .readings
        .iter()
        .filter_map(|r| measurement_box(r, &u))
        .collect();
    let e = smallest_scale(
        &Arm7Point,
        &padded_box(&arm),
        &boxes,
        &ScaleBounds::All.mask(6),
    );
    let first = found.trials[0];
    assert!(
        first.scale > e.scale && first.scale <= 1.006 * e.scale,
        "{first:?}"
    );
    assert!(
        hi <= 1.011 * e.scale,
        "{hi} against the estimate {}",
        e.scale
    );
    let widened: Vec<[Interval; NM]> = sim
        .readings
        .iter()
        .filter_map(|r| measurement_box(r, &ScaleBounds::All.scale(&u, hi)))
        .collect();
    assert!(is_consistent_point(&Arm7Point, &e.point, &widened));
    // Below the first-order estimate the Chebyshev point itself does not fit.
    let narrowed: Vec<[Interval; NM]> = sim
        .readings
        .iter()
        .filter_map(|r| measurement_box(r, &ScaleBounds::All.scale(&u, 0.97 * e.scale)))
        .collect();
    assert!(!is_consistent_point(&Arm7Point, &e.point, &narrowed));
}

#[test]
fn masks_select_the_scaled_quantities() {
    let joints: Vec<usize> = (0..NM)
        .filter(|&i| ScaleBounds::JointDeg.mask(6)[i])
        .collect();
    assert_eq!(joints, vec![0, 1, 2, 3, 4, 5]);
    let pos: Vec<usize> = (0..NM).filter(|&i| ScaleBounds::Pos.mask(6)[i]).collect();
    assert_eq!(pos, vec![MAX_JOINTS, MAX_JOINTS + 1, MAX_JOINTS + 2]);
    assert_eq!(ScaleBounds::All.mask(6).iter().filter(|&&b| b).count(), 9);
}
