//! The tests of `calib_pipeline::verdict`.

use calib_core::{EmptinessProof, Interval, Status};
use calib_pipeline::report::OutcomeReport;
use calib_pipeline::verdict::*;
use calib_pipeline::Outcome;

#[test]
fn factors_below_one_are_not_improvements() {
    // "At least" is printed rounded down, below the quotient's own rounding: 19.8193 / 17.5423
    // is 1.1298 (not "1.13"), and the double nearest 23.9 lies below 23.9.
    assert!(improvement("the error", 19.8193 / 17.5423)
        .starts_with("calibration reduced the error at least 1.12-fold"));
    assert!(
        improvement("the error", 23.9).starts_with("calibration reduced the error at least 23.89")
    );
    assert!(
        improvement("the error", 24.0).starts_with("calibration reduced the error at least 23.99")
    );
    let none = improvement("the error", 0.99);
    assert!(
        none.starts_with("no improvement of the error is proved"),
        "{none}"
    );
}

#[test]
fn auto_outliers_say_what_was_proved() {
    assert!(auto_outliers(0, Status::Consistent).contains("no outlier needed"));
    assert!(auto_outliers(1, Status::Consistent).contains("with every configuration kept"));
    let undecided = auto_outliers(3, Status::Undecided);
    assert!(undecided.contains("undecided with 3") && undecided.contains("2 or fewer"));
    assert!(!auto_outliers(0, Status::Undecided).contains("no outlier needed"));
    assert!(auto_outliers(3, Status::Consistent).contains("with 2 or fewer tolerated"));
    assert!(auto_outliers(4, Status::Empty).contains("empty even with 4"));
}

#[test]
fn configurations_are_named_by_number_and_line() {
    let lines = [2, 3, 5, 6];
    let n = ConfigurationNames {
        file: "m.csv",
        lines: &lines,
        carried: None,
    };
    assert_eq!(n.name(&[2]), "configuration 3 (m.csv line 5)");
    assert_eq!(n.name(&[0, 3]), "configurations 1, 4 (m.csv lines 2, 6)");
    // Past the file's configurations without carried rows: named, but unknown.
    assert_eq!(n.name(&[9]), "configuration 10 (stored row ? of ?)");
    // Rows carried over from a stored set are named by their row there.
    let rows = [1, 2, 4];
    let carried = ConfigurationNames {
        carried: Some(CarriedRows {
            file: "calibrated.toml",
            rows: &rows,
        }),
        ..n
    };
    assert_eq!(
        carried.name(&[1, 6]),
        "configurations 2, 7 (m.csv line 3; stored row 4 of calibrated.toml)"
    );
    assert_eq!(
        carried.name(&[4, 5]),
        "configurations 5, 6 (stored rows 1, 2 of calibrated.toml)"
    );
}

#[test]
fn only_vectors_inside_x0_are_refuted() {
    let x0 = [Interval::new(-1.0, 1.0); 7];
    let outer = [Interval::new(-0.5, 0.5); 7];
    let mut x = [0.0; 7];
    assert_eq!(standing(&x0, Some(&outer), &x), Standing::Inside);
    assert_eq!(standing(&x0, None, &x), Standing::Refuted(vec![]));
    x[6] = 0.75;
    assert_eq!(standing(&x0, Some(&outer), &x), Standing::Refuted(vec![6]));
    x[2] = 3.0;
    assert_eq!(standing(&x0, Some(&outer), &x), Standing::BeyondX0(vec![2]));
    assert_eq!(standing(&x0, None, &x), Standing::BeyondX0(vec![2]));
}

#[test]
fn every_proof_has_words() {
    let names: Vec<String> = (0..7).map(|j| format!("p{j}")).collect();
    for p in [
        Some(EmptinessProof::CheapRejection { measurement: 4 }),
        Some(EmptinessProof::LpInfeasible),
        Some(EmptinessProof::EmptyIntersection { parameter: 6 }),
        Some(EmptinessProof::SecondOrder),
        Some(EmptinessProof::Subdivision),
        Some(EmptinessProof::EverySubset),
        None,
    ] {
        let words = proof_in_words(p, &names);
        assert!(
            !words.contains("Rejection") && !words.contains("Lp"),
            "{words}"
        );
    }
    assert!(proof_in_words(
        Some(EmptinessProof::CheapRejection { measurement: 4 }),
        &names
    )
    .contains("configuration 5"));
    assert!(proof_in_words(
        Some(EmptinessProof::EmptyIntersection { parameter: 6 }),
        &names
    )
    .contains("p6"));
}

/// An empty outcome: a spread misfit (`conflict: None`, not searched) or a conflict set.
fn empty_outcome(conflict: Option<Vec<usize>>, support: Vec<usize>, spread: bool) -> Outcome {
    Outcome {
        names: vec!["a".into()],
        x0: vec![Interval::new(-1.0, 1.0)],
        status: Status::Empty,
        emptiness: Some(EmptinessProof::LpInfeasible),
        x1: None,
        outer: None,
        inner: None,
        witness: None,
        conflict,
        support: Some(support),
        spread,
        outliers: vec![],
        iterations: 1,
        converged: None,
        boxes: 1,
        seconds: 0.0,
    }
}

#[test]
fn a_spread_misfit_points_to_the_error_scale_and_names_no_conflict() {
    let lines: Vec<usize> = (2..14).collect();
    let names = ConfigurationNames {
        file: "m.csv",
        lines: &lines,
        carried: None,
    };
    let spread = verdict(&empty_outcome(None, vec![0, 2, 5, 7, 9], true), &names, 0);
    let text = spread.join("\n");
    assert!(
        text.contains("weighs 5 of the 12 configurations — configurations 1, 3, 6, 8, 10"),
        "{text}"
    );
    assert!(text.contains("too tight for the model"), "{text}");
    assert!(text.contains("--error-scale auto"), "{text}");
    assert!(!text.contains("conflict:"), "{text}");
    // The few-bad-readings case keeps its conflict set and its advice.
    let few = verdict(&empty_outcome(Some(vec![3]), vec![3], false), &names, 0).join("\n");
    assert!(
        few.contains("conflict: configuration 4 (m.csv line 5) alone"),
        "{few}"
    );
    assert!(
        few.contains("--max-outliers 1") && !few.contains("spread"),
        "{few}"
    );

    // The JSON keeps every key and adds `support` (1-based) and `spread`; reports written
    // before read back without them.
    let o = empty_outcome(None, vec![0, 2, 5, 7, 9], true);
    let report = OutcomeReport::new(&o, &["mm".into()], spread, vec![], None);
    let json: serde_json::Value = serde_json::from_str(&report.to_json()).expect("json");
    assert_eq!(json["status"], "empty");
    assert!(json["conflict"].is_null() && json["outliers"] == serde_json::json!([]));
    assert_eq!(json["support"], serde_json::json!([1, 3, 6, 8, 10]));
    assert_eq!(json["spread"], true);
    let mut old = json.clone();
    let fields = old.as_object_mut().expect("an object");
    fields.remove("support");
    fields.remove("spread");
    let back: OutcomeReport = serde_json::from_value(old).expect("an older report");
    assert_eq!((back.support, back.spread), (None, false));
}
