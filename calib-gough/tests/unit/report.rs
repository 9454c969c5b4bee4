//! The tests of `calib_gough::report`.

use calib_core::Interval;
use calib_gough::report::*;

#[test]
fn the_json_schema_round_trips_exactly() {
    let b: [Interval; 7] =
        core::array::from_fn(|j| Interval::new(0.1 * j as f64 - 1e-17, 0.1 * j as f64 + 1.0 / 3.0));
    let r = Report {
        version: 1,
        legs: vec![LegReport {
            leg: 1,
            status: "consistent".into(),
            names: calib_gough::PARAMETER_NAMES
                .iter()
                .map(|s| s.to_string())
                .collect(),
            x0: bounds(&b),
            x1: Some(bounds(&b)),
            x2: None,
            outer: Some(bounds(&b)),
            inner: Some(bounds(&b)),
            converged: Some(true),
            conflict: Some(vec![3, 9]),
            support: Some(vec![3, 9, 12]),
            spread: false,
            outliers: vec![9],
            outliers_tolerated: 1,
            witness: Some(vec![0.1; 7]),
            carried_over: Some(CarriedReport {
                file: "calibrated.toml".into(),
                first: 22,
                rows: (1..=21).collect(),
            }),
            iterations: 3,
            boxes: 1,
            seconds: 0.25,
        }],
        seconds: 0.5,
    };
    let text = serde_json::to_string_pretty(&r).unwrap();
    let back: Report = serde_json::from_str(&text).unwrap();
    assert_eq!(back, r, "bounds must read back bit-identical");
}
