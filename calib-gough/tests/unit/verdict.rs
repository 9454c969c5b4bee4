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
