//! The tests of `calib_gough::error_scale`.

use calib_core::{Settings, Status};
use calib_gough::certification::leg_prior;
use calib_gough::error_scale::*;
use calib_gough::measurement::{leg_boxes, Uncertainty};
use calib_gough::simulate::{builtin_hexapod, simulate};
use calib_gough::GoughLeg;

#[test]
fn only_the_chosen_bounds_scale() {
    let u = Uncertainty::PAPER;
    let p = ScaleBounds::Pos.scale(&u, 3.0);
    assert!(p.pos >= 3.0 * u.pos && p.len == u.len && p.axis == u.axis);
    let o = ScaleBounds::Orientation.scale(&u, 2.0);
    assert!(o.axis >= 2.0 * u.axis && o.angle_deg >= 2.0 * u.angle_deg && o.pos == u.pos);
    assert_eq!(
        ScaleBounds::Len.mask(),
        [false, false, false, false, false, false, false, true]
    );
    assert_eq!(
        ScaleBounds::Orientation.mask(),
        [false, false, false, true, true, true, true, false]
    );
}

#[test]
fn the_bracket_holds_the_truth_within_two_per_cent() {
    // Noise within the paper's bounds, declared four times too tight: the truth fits at × 4.
    let sim = simulate(&builtin_hexapod(), 21, 3, Uncertainty::PAPER, 1.0, 0.1);
    let robot = crate::support::priors(&sim.nominal);
    let u = ScaleBounds::All.scale(&Uncertainty::PAPER, 0.25);
    let legs: Vec<usize> = (0..6).collect();
    let found = search(
        &robot,
        &[],
        &legs,
        &sim.measured,
        &u,
        ScaleBounds::All,
        |_| {},
    );
    let (lo, hi) = (found.s_lo.expect("s_lo"), found.s_hi.expect("s_hi"));
    assert!(lo < 4.0, "{lo}: the truth fits at × 4");
    assert!(hi / lo <= 1.02, "{lo} {hi}: {:?}", found.trials);
    // The upper end is proved independently: every leg certified consistent there.
    let settings = Settings::default();
    for &leg in &legs {
        let boxes = leg_boxes(&sim.measured, &ScaleBounds::All.scale(&u, hi), leg);
        let c = calib_core::certify(&GoughLeg, &leg_prior(&robot[leg]), &boxes, &settings);
        assert_ne!(c.status, Status::Empty, "leg {leg} at × {hi}");
    }
}
