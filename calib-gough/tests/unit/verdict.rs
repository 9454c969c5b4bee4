//! The tests of `calib_gough::verdict`.

use calib_core::Status;
use calib_gough::certification::LegResult;
use calib_gough::verdict::*;

#[test]
fn faces_of_x0_reached_by_the_outer_box_are_named() {
    let x0 = [calib_core::Interval::new(-1.0, 1.0); 7];
    let mut outer = [calib_core::Interval::new(-0.5, 0.5); 7];
    outer[2] = calib_core::Interval::new(-1.0, 0.5);
    outer[6] = x0[6];
    let r = LegResult {
        leg: 0,
        x0,
        status: Status::Consistent,
        emptiness: None,
        x1: Some(outer),
        outer: Some(outer),
        inner: None,
        witness: None,
        conflict: None,
        support: None,
        spread: false,
        outliers: vec![],
        tolerated: 0,
        iterations: 1,
        converged: Some(true),
        x2: None,
        paving: None,
        boxes: 1,
        seconds: 0.0,
        cover: calib_core::Cover::single(outer),
        points: vec![],
        carried: None,
    };
    let words = touching_x0(&r).expect("two faces reached");
    assert!(words.contains("az (lower end), l (both ends)"), "{words}");
    let inside = LegResult {
        outer: Some([calib_core::Interval::new(-0.5, 0.5); 7]),
        ..r.clone()
    };
    assert_eq!(touching_x0(&inside), None);
}

#[test]
fn stored_rows_are_named_by_their_row_in_the_calibrated_file() {
    use calib_gough::carry_over::{Carried, StoredRows};
    let x0 = [calib_core::Interval::new(-1.0, 1.0); 7];
    let mut r = LegResult {
        leg: 0,
        x0,
        status: Status::Consistent,
        emptiness: None,
        x1: Some(x0),
        outer: Some(x0),
        inner: None,
        witness: None,
        conflict: None,
        support: None,
        spread: false,
        outliers: vec![],
        tolerated: 0,
        iterations: 1,
        converged: Some(true),
        x2: None,
        paving: None,
        boxes: 1,
        seconds: 0.0,
        cover: calib_core::Cover::single(x0),
        points: vec![],
        carried: None,
    };
    let names = ConfigurationNames {
        file: "measurements.csv",
        lines: &[2, 3, 5],
        carried: None,
    };
    assert_eq!(
        name_configurations(&r, &names, &[0, 2]),
        "configurations 1, 3 (measurements.csv lines 2, 5)"
    );
    // Three new rows, then the stored rows 1, 2 and 4 (row 3 was an outlier, left out).
    r.carried = Some(Carried {
        first: 3,
        stored: StoredRows {
            file: "calibrated.toml".into(),
            rows: vec![0, 1, 3],
            left_out: vec![2],
            boxes: vec![],
            hull: x0,
        },
    });
    assert_eq!(
        name_configurations(&r, &names, &[1]),
        "configuration 2 (measurements.csv line 3)"
    );
    assert_eq!(
        name_configurations(&r, &names, &[1, 5]),
        "configurations 2, 6 (measurements.csv line 3; stored row 4 of calibrated.toml)"
    );
    assert_eq!(
        name_configurations(&r, &names, &[3, 4]),
        "configurations 4, 5 (stored rows 1, 2 of calibrated.toml)"
    );
    r.status = Status::Empty;
    r.conflict = Some(vec![0, 4]);
    let words = verdict(&r, &names).join("\n");
    assert!(
        words.contains(
            "conflict: configurations 1, 5 (measurements.csv line 2; stored row 2 of \
             calibrated.toml) cannot be fitted together"
        ),
        "{words}"
    );
}
