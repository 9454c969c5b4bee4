//! The tests of `calib_pipeline::outcome`.

use calib_core::{Interval, Status};
use calib_pipeline::*;

fn outcome(x0: Vec<Interval>, outer: Vec<Interval>) -> Outcome {
    Outcome {
        names: (0..x0.len()).map(|j| format!("p{j}")).collect(),
        x0,
        status: Status::Consistent,
        emptiness: None,
        x1: Some(outer.clone()),
        outer: Some(outer.clone()),
        inner: Some(
            outer
                .iter()
                .map(|v| Interval::mid_rad(v.mid(), v.rad() / 2.0))
                .collect(),
        ),
        witness: None,
        conflict: None,
        support: None,
        spread: false,
        outliers: vec![],
        iterations: 1,
        converged: Some(true),
        boxes: 1,
        seconds: 0.0,
    }
}

#[test]
fn faces_of_x0_skip_fixed_parameters_and_ratios_divide_widths() {
    let x0 = vec![
        Interval::new(-1.0, 1.0),
        Interval::new(-1.0, 1.0),
        Interval::point(2.0),
    ];
    let outer = vec![
        Interval::new(-1.0, 0.5),
        Interval::new(-0.5, 0.5),
        Interval::point(2.0),
    ];
    let o = outcome(x0, outer);
    assert_eq!(o.x0_faces(), vec![(0, "lower end")]);
    let r = o.width_ratios().expect("inner and outer");
    assert!((r[0] - 2.0).abs() < 1e-12 && (r[1] - 2.0).abs() < 1e-12);
    let doubled = o.map_units(|_, v| v * Interval::point(2.0), |_, v| 2.0 * v);
    assert!(doubled.x0[0].contains(-2.0) && doubled.x0[0].contains(2.0));
    assert!(doubled.x0[0].wid() < 4.0 + 1e-12);
}
