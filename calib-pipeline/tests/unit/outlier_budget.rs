//! The tests of `calib_pipeline::outlier_budget`.

use calib_pipeline::*;

#[test]
fn parses_numbers_and_auto() {
    assert_eq!("2".parse(), Ok(OutlierBudget::Fixed(2)));
    assert_eq!(" AUTO ".parse(), Ok(OutlierBudget::Auto));
    let e = "-1".parse::<OutlierBudget>().unwrap_err().to_string();
    assert!(e.contains("`-1`") && e.contains("auto"), "{e}");
    assert!("1.5".parse::<OutlierBudget>().is_err());
    for b in [OutlierBudget::Fixed(3), OutlierBudget::Auto] {
        assert_eq!(b.to_string().parse(), Ok(b));
    }
}

#[test]
fn a_fixed_budget_must_leave_a_configuration() {
    assert!(OutlierBudget::Fixed(2).check(3).is_ok());
    assert!(OutlierBudget::Fixed(3)
        .check(3)
        .unwrap_err()
        .to_string()
        .contains("--max-outliers 3"));
    assert!(OutlierBudget::Auto.check(1).is_ok());
}

/// A sub-problem that is empty below `needed` outliers.
fn search(budget: OutlierBudget, configs: usize, needed: usize) -> (usize, Vec<usize>) {
    let mut tried = Vec::new();
    let (q, r) = smallest_consistent(
        budget,
        configs,
        |q| {
            tried.push(q);
            Ok::<_, ()>(q >= needed)
        },
        |consistent| !consistent,
    )
    .unwrap();
    assert_eq!(r, q >= needed);
    (q, tried)
}

#[test]
fn auto_stops_at_the_first_consistent_q() {
    assert_eq!(search(OutlierBudget::Auto, 10, 0), (0, vec![0]));
    assert_eq!(search(OutlierBudget::Auto, 10, 3), (3, vec![0, 1, 2, 3]));
    // Never every configuration dropped: the last try keeps one.
    assert_eq!(search(OutlierBudget::Auto, 4, 9), (3, vec![0, 1, 2, 3]));
    // A fixed budget is tried once, whatever it gives.
    assert_eq!(search(OutlierBudget::Fixed(1), 10, 3), (1, vec![1]));
}

#[test]
fn errors_stop_the_search() {
    let mut calls = 0;
    let r = smallest_consistent(
        OutlierBudget::Auto,
        10,
        |q| {
            calls += 1;
            if q == 1 {
                Err("failed")
            } else {
                Ok(false)
            }
        },
        |consistent| !consistent,
    );
    assert_eq!(r, Err("failed"));
    assert_eq!(calls, 2);
}
