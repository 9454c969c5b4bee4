//! The tests of `calib_pipeline::error_scale`.

use calib_core::Status;
use calib_pipeline::error_scale::*;

fn threshold(t: f64) -> impl FnMut(f64) -> Status {
    move |s| {
        if s >= t {
            Status::Consistent
        } else {
            Status::Empty
        }
    }
}

#[test]
fn brackets_the_threshold_within_the_tolerance_from_either_side() {
    for t in [0.0123, 0.547, 1.0, 3.7, 250.0] {
        let s = find_error_scale(&ScaleSearch::default(), threshold(t));
        let (lo, hi) = (s.s_lo.unwrap(), s.s_hi.unwrap());
        assert!(lo < t && t <= hi && hi / lo <= 1.02, "{t}: {lo} {hi}");
        // Every end is a proof of its kind.
        let proved = |v: f64, k: Status| s.trials.iter().any(|r| r.scale == v && r.status == k);
        assert!(proved(lo, Status::Empty) && proved(hi, Status::Consistent));
        assert!(s.trials.len() <= 24);
    }
}

#[test]
fn an_estimate_brackets_in_few_trials_and_a_wrong_one_still_brackets() {
    for (t, estimate) in [(0.547, 0.546), (0.547, 0.549), (0.547, 0.3), (0.547, 3.0)] {
        let s = find_error_scale(&ScaleSearch::from_estimate(estimate), threshold(t));
        let (lo, hi) = (s.s_lo.unwrap(), s.s_hi.unwrap());
        assert!(
            lo < t && t <= hi && hi / lo <= 1.02,
            "{t} from {estimate}: {lo} {hi}"
        );
        if (estimate / t - 1.0f64).abs() < 0.005 {
            assert!(s.trials.len() <= 3, "{estimate}: {:?}", s.trials);
        }
        assert!(s.trials.len() <= 24);
    }
    // No usable estimate: the blind default.
    assert_eq!(ScaleSearch::from_estimate(f64::NAN), ScaleSearch::default());
    assert_eq!(ScaleSearch::from_estimate(0.0), ScaleSearch::default());
}

#[test]
fn words_say_what_was_proved_and_what_is_certified_next() {
    let found = ErrorScale {
        s_lo: Some(5.88),
        s_hi: Some(7.69),
        trials: Vec::new(),
        estimate: Some(7.6),
    };
    let describe = |s: f64| format!("pos {:.3} mm", 0.05 * s);
    let (words, at) = in_words(&found, "pos", 3.0, 1.1, &describe).expect("proved");
    assert!((at - 7.69 * 1.1).abs() < 1e-12);
    assert!(
        words[1].contains("only if the error bounds are pos 0.385 mm"),
        "{words:?}"
    );
    assert!(
        words[1].contains("pos 0.294 mm is proved too small"),
        "{words:?}"
    );
    assert!(words[2].contains("minimax fit needs × 7.6000"), "{words:?}");
    assert!(words[3].contains("a margin of × 1.1"), "{words:?}");
    let none = ErrorScale {
        s_hi: None,
        ..found
    };
    assert!(in_words(&none, "pos", 3.0, 1.0, &describe).is_none());
}

#[test]
fn undecided_verdicts_never_become_ends() {
    // Undecided from 0.9 to 1.2: the bracket stops at its edges, made of proofs only.
    let s = find_error_scale(&ScaleSearch::default(), |s| {
        if s >= 1.2 {
            Status::Consistent
        } else if s > 0.9 {
            Status::Undecided
        } else {
            Status::Empty
        }
    });
    let (lo, hi) = (s.s_lo.unwrap(), s.s_hi.unwrap());
    assert!(lo <= 0.9 && hi >= 1.2 && hi / lo < 1.4, "{lo} {hi}");
    // Never consistent: no upper end, and the search ends within its range.
    let s = find_error_scale(&ScaleSearch::default(), |_| Status::Empty);
    assert!(s.s_hi.is_none() && s.s_lo.is_some());
    let s = find_error_scale(&ScaleSearch::default(), |_| Status::Undecided);
    assert!(s.s_hi.is_none() && s.s_lo.is_none() && s.trials.len() <= 24);
}

#[test]
fn a_stalled_search_tries_the_factor_that_meets_the_tolerance() {
    // The real UR10's pattern (`benches/README.md`): consistent just above the estimate 7.6917,
    // proved empty up to 0.9806 of it, undecided between. The bisection's gaps stop shrinking at
    // a ratio of 1.0201; one more trial at s_hi / 1.02 closes the bracket.
    let hi = 7.69175;
    let s = find_error_scale(&ScaleSearch::from_estimate(7.6917), |s| {
        if s >= hi {
            Status::Consistent
        } else if s > 0.9806 * hi {
            Status::Undecided
        } else {
            Status::Empty
        }
    });
    let (lo, top) = (s.s_lo.unwrap(), s.s_hi.unwrap());
    assert!(top / lo <= 1.02, "{lo} {top}: {:?}", s.trials);
    // Where no proof can meet the tolerance, the search still ends, with proofs at both ends.
    let s = find_error_scale(&ScaleSearch::from_estimate(7.6917), |s| {
        if s >= hi {
            Status::Consistent
        } else if s > 0.97 * hi {
            Status::Undecided
        } else {
            Status::Empty
        }
    });
    let (lo, top) = (s.s_lo.unwrap(), s.s_hi.unwrap());
    assert!(
        lo <= 0.97 * hi && top >= hi && s.trials.len() <= 24,
        "{:?}",
        s.trials
    );
}
