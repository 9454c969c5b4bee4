//! The tight certified hull: sound (the truth is always inside `outer`, `inner ⊆ outer`), its inner
//! bound made of rechecked solutions, tight on the paper's setting, and able to start from large
//! prior boxes.

use crate::support;

use calib_core::{
    certify, hull, is_consistent_by_corners, EmptinessProof, Interval, Settings, Status,
};
use calib_gough::{builtin_hexapod, leg_boxes, simulate, GoughLeg, Uncertainty};
use support::{contains, extreme, random_problem, x0_of};

/// A box budget that keeps the random-problem tests quick; soundness holds whatever the budget.
fn budgeted() -> Settings {
    Settings::default().with_hull_budget(1500, None)
}

#[test]
fn hull_keeps_the_truth_and_nests_its_bounds_over_random_problems() {
    for seed in 100..116 {
        let sim = random_problem(seed);
        let leg = (seed % 6) as usize;
        let boxes = leg_boxes(&sim.measured, &sim.uncertainty, leg);
        let x0 = x0_of(&sim, leg, 0.1);
        let truth = sim.truth[leg].params();
        let h = hull(&GoughLeg, &x0, &boxes, &budgeted());
        assert_ne!(h.status, Status::Empty, "seed {seed}: consistent data");
        assert!(contains(&h.outer, &truth), "seed {seed}: truth cut off");
        let x1 = h.x1.expect("x0 is not empty");
        for j in 0..7 {
            assert!(h.outer[j].is_subset_of(x1[j]) && x1[j].is_subset_of(x0[j]));
            if let Some(inner) = h.inner {
                assert!(
                    inner[j].is_subset_of(h.outer[j]),
                    "seed {seed}: inner {:?} sticks out of outer {:?} in {j}",
                    inner[j],
                    h.outer[j]
                );
            }
        }
        assert!(h.boxes_contracted <= 1500 + 2 * 14, "budget respected");
    }
}

/// The outer box is the hull of the cover *and* the inner box, so a cover that lost solutions could
/// hide behind the inner points (they span ~95% of the true hull), and a piece lost inside the
/// cover does not change its hull. Without inner bounds the outer box is the cover's hull alone,
/// refined until the budget: the truth and independently found extreme solutions (pushed from
/// the truth towards each face) must all be inside.
#[test]
fn the_cover_alone_keeps_every_extreme_solution_over_random_problems() {
    let mut settings = Settings::default().with_hull_budget(800, None);
    settings.inner_bounds = false;
    for seed in 200..212 {
        let sim = random_problem(seed);
        let leg = (seed % 6) as usize;
        let boxes = leg_boxes(&sim.measured, &sim.uncertainty, leg);
        let x0 = x0_of(&sim, leg, 0.1);
        let h = hull(&GoughLeg, &x0, &boxes, &settings);
        assert!(h.inner.is_none() && !h.converged);
        assert_ne!(h.status, Status::Empty, "seed {seed}: consistent data");
        let truth = sim.truth[leg].params();
        assert!(
            contains(&h.outer, &truth),
            "seed {seed}: the cover lost the truth"
        );
        for j in 0..7 {
            for sign in [1.0, -1.0] {
                let p = extreme(truth, j, sign, &x0, &boxes);
                assert!(is_consistent_by_corners(&GoughLeg, &p, &boxes));
                assert!(
                    contains(&h.outer, &p),
                    "seed {seed}: the cover lost a solution at the {sign} face of {j}: {p:?}"
                );
            }
        }
        let x1 = h.x1.expect("x0 is not empty");
        assert!((0..7).all(|j| h.outer[j].is_subset_of(x1[j])));
    }
}

#[test]
fn inner_bounds_are_attained_by_rechecked_solutions() {
    let sim = simulate(&builtin_hexapod(), 21, 11, Uncertainty::PAPER, 1.0, 0.1);
    for leg in [0, 2, 5] {
        let boxes = leg_boxes(&sim.measured, &sim.uncertainty, leg);
        let x0 = x0_of(&sim, leg, 0.1);
        let h = hull(&GoughLeg, &x0, &boxes, &Settings::default());
        assert_eq!(h.status, Status::Consistent);
        let inner = h.inner.expect("a consistent leg has inner bounds");
        assert_eq!(h.inner_points.len(), 14);
        for (slot, p) in h.inner_points.iter().enumerate() {
            assert!(
                is_consistent_by_corners(&GoughLeg, p, &boxes),
                "leg {leg}: inner point {slot} is not a solution"
            );
            assert!(contains(&x0, p), "leg {leg}: inner point outside x0");
            let j = slot / 2;
            let bound = if slot % 2 == 0 {
                inner[j].inf()
            } else {
                inner[j].sup()
            };
            assert_eq!(p[j], bound, "leg {leg}: point {slot} attains its face");
        }
        let w = h.witness.expect("witness");
        assert!(is_consistent_by_corners(&GoughLeg, &w, &boxes));
    }
}

#[test]
fn the_paper_setting_reaches_the_tolerance_and_beats_x1() {
    for seed in [0, 1] {
        let sim = simulate(&builtin_hexapod(), 21, seed, Uncertainty::PAPER, 1.0, 0.1);
        for leg in 0..6 {
            let boxes = leg_boxes(&sim.measured, &sim.uncertainty, leg);
            let x0 = x0_of(&sim, leg, 0.1);
            let h = hull(&GoughLeg, &x0, &boxes, &Settings::default());
            assert!(h.converged, "seed {seed} leg {leg}: budget ran out");
            assert!(contains(&h.outer, &sim.truth[leg].params()));
            for j in 0..7 {
                assert!(
                    h.ratio[j] <= 1.0 + Settings::default().hull_tolerance + 1e-9,
                    "seed {seed} leg {leg} parameter {j}: outer/inner {}",
                    h.ratio[j]
                );
            }
            // The same data, the paper's x1 alone: the hull is never looser.
            let c = certify(&GoughLeg, &x0, &boxes, &Settings::default());
            assert!((0..7).all(|j| h.outer[j].is_subset_of(c.outer[j])));
        }
    }
}

#[test]
fn a_one_centimetre_prior_contracts_to_the_same_bracket() {
    let sim = simulate(&builtin_hexapod(), 21, 4, Uncertainty::PAPER, 1.0, 1.0);
    let leg = 1;
    let boxes = leg_boxes(&sim.measured, &sim.uncertainty, leg);
    let x0 = x0_of(&sim, leg, 1.0);
    // x1 alone does not get below a few millimetres on the poorly determined parameters ...
    let h = hull(&GoughLeg, &x0, &boxes, &Settings::default());
    assert_eq!(h.status, Status::Consistent);
    assert!(h.converged);
    assert!(contains(&h.outer, &sim.truth[leg].params()));
    for j in 0..7 {
        assert!(
            h.ratio[j] <= 1.0 + 0.05 + 1e-9,
            "parameter {j}: {}",
            h.ratio[j]
        );
        // ... the hull pins a_x, a_y, b_x, b_y down to well under a millimetre.
        if [0, 1, 3, 4].contains(&j) {
            assert!(h.outer[j].wid() < 0.1, "parameter {j}: {:?}", h.outer[j]);
        }
    }
}

#[test]
fn a_five_centimetre_prior_still_gives_a_certified_result() {
    let sim = simulate(&builtin_hexapod(), 21, 6, Uncertainty::PAPER, 1.0, 5.0);
    let leg = 4;
    let boxes = leg_boxes(&sim.measured, &sim.uncertainty, leg);
    let x0 = x0_of(&sim, leg, 5.0);
    let h = hull(&GoughLeg, &x0, &boxes, &budgeted());
    assert_ne!(h.status, Status::Empty);
    assert!(contains(&h.outer, &sim.truth[leg].params()));
    assert!((0..7).all(|j| h.outer[j].is_subset_of(x0[j])));
}

#[test]
fn inconsistent_data_are_proved_empty_and_the_other_legs_are_not() {
    let mut sim = simulate(&builtin_hexapod(), 21, 3, Uncertainty::PAPER, 1.0, 1.0);
    // Leg 2's reading in configuration 5 moved 2 mm outside its box.
    sim.measured[5].lengths[1] += 0.2;
    let boxes = leg_boxes(&sim.measured, &sim.uncertainty, 1);
    let h = hull(
        &GoughLeg,
        &x0_of(&sim, 1, 1.0),
        &boxes,
        &Settings::default(),
    );
    assert_eq!(h.status, Status::Empty);
    assert!(h.outer.iter().all(|v| v.is_empty()) && h.inner.is_none());
    assert!(matches!(
        h.emptiness,
        Some(EmptinessProof::Subdivision) | Some(EmptinessProof::CheapRejection { .. })
    ));
    // The verdict, not the tightness, is checked for leg 1: a budgeted hull decides it.
    let boxes = leg_boxes(&sim.measured, &sim.uncertainty, 0);
    let h = hull(&GoughLeg, &x0_of(&sim, 0, 1.0), &boxes, &budgeted());
    assert_eq!(h.status, Status::Consistent);
}

#[test]
fn the_result_does_not_depend_on_the_number_of_threads() {
    let sim = simulate(&builtin_hexapod(), 21, 9, Uncertainty::PAPER, 1.0, 0.5);
    let boxes = leg_boxes(&sim.measured, &sim.uncertainty, 2);
    let x0 = x0_of(&sim, 2, 0.5);
    let parallel = hull(&GoughLeg, &x0, &boxes, &budgeted());
    let serial = hull(&GoughLeg, &x0, &boxes, &budgeted().with_parallel(false));
    assert_eq!(parallel.outer, serial.outer);
    assert_eq!(parallel.inner, serial.inner);
    assert_eq!(parallel.boxes_contracted, serial.boxes_contracted);
}

#[test]
fn unbounded_prior_boxes_are_kept_whole() {
    let sim = simulate(&builtin_hexapod(), 9, 2, Uncertainty::PAPER, 1.0, 0.1);
    let boxes = leg_boxes(&sim.measured, &sim.uncertainty, 0);
    let mut x0 = x0_of(&sim, 0, 0.1);
    x0[6] = Interval::ENTIRE;
    let h = hull(&GoughLeg, &x0, &boxes, &Settings::default());
    assert_ne!(h.status, Status::Empty);
    assert!(contains(&h.outer, &sim.truth[0].params()));
}
