//! The tests of `calib_pipeline::lsq`.

use calib_core::Scalar;
use calib_pipeline::lsq::*;

/// A point `(x0 + x2·cos m, x1 + x2·sin m)` observed at angle `m`: centre and radius. (The
/// plain function itself is unused: the macro's evaluators are what the test calls.)
#[allow(dead_code)]
#[calib_core::interval_model]
pub fn circle_point<S: Scalar>(x: &[S; 3], m: &[S; 3]) -> [S; 2] {
    [
        x[0] + x[2] * m[0].cos() - m[1],
        x[1] + x[2] * m[0].sin() - m[2],
    ]
}

#[test]
fn recovers_an_exact_geometry_and_keeps_fixed_parameters() {
    let truth = [0.3, -0.2, 1.5];
    let readings: Vec<[f64; 3]> = (0..8)
        .map(|k| {
            let a = k as f64 * 0.7;
            [
                a,
                truth[0] + truth[2] * a.cos(),
                truth[1] + truth[2] * a.sin(),
            ]
        })
        .collect();
    let fit = least_squares(&CirclePoint, &[0.0, 0.0, 1.0], &[0, 1, 2], &readings);
    assert!(fit.converged);
    for (got, want) in fit.x.iter().zip(truth) {
        assert!((got - want).abs() < 1e-8, "{:?}", fit.x);
    }
    assert!(fit.rms < 1e-8 && fit.max_abs < 1e-8);
    let fixed = least_squares(&CirclePoint, &[0.0, -0.2, 1.5], &[0], &readings);
    assert_eq!(fixed.x[1], -0.2);
    assert_eq!(fixed.x[2], 1.5);
    assert!((fixed.x[0] - 0.3).abs() < 1e-8);
}
