//! The kernel on small models written outside the Gough crate: one and two parameters, consistent
//! and inconsistent data, sweep and paver.

use calib_core::{certify, interval_model, pave, sweep, Interval, Scalar, Settings, Status};

/// A line through the origin: `m1 = x0 * m0`.
#[interval_model]
pub fn slope<S: Scalar>(x: &[S; 1], m: &[S; 2]) -> S {
    x[0] * m[0] - m[1]
}

/// An exponential-free decay model with two parameters: `m1 = x0 / (1 + x1 m0)`.
#[interval_model]
pub fn decay<S: Scalar>(x: &[S; 2], m: &[S; 2]) -> S {
    x[0] / (1.0 + x[1] * m[0]) - m[1]
}

fn boxes(points: &[(f64, f64)], e: f64) -> Vec<[Interval; 2]> {
    points
        .iter()
        .map(|&(a, b)| [Interval::mid_rad(a, e), Interval::mid_rad(b, e)])
        .collect()
}

#[test]
fn one_parameter_consistent_and_inconsistent() {
    let data = boxes(&[(1.0, 2.0), (2.0, 4.0), (3.0, 6.0)], 1e-3);
    let x0 = [Interval::new(0.0, 10.0)];
    let r = certify(&Slope, &x0, &data, &Settings::default());
    assert_eq!(r.status, Status::Consistent);
    assert!(
        r.outer[0].contains(2.0) && r.outer[0].rad() < 0.01,
        "{:?}",
        r.outer
    );
    let w = r.witness.unwrap();
    assert!(r.outer[0].contains(w[0]));
    let bad = boxes(&[(1.0, 2.0), (2.0, 4.0), (3.0, 7.0)], 1e-3);
    let r = certify(&Slope, &x0, &bad, &Settings::default());
    assert_eq!(r.status, Status::Empty);
    let s = sweep(&Slope, &x0, &bad, &Settings::default());
    assert!(s.hull.is_none());
}

#[test]
fn two_parameters_with_division() {
    let truth = [3.0, 0.5];
    let points: Vec<(f64, f64)> = (0..8)
        .map(|k| {
            let t = k as f64 * 0.4;
            (t, truth[0] / (1.0 + truth[1] * t))
        })
        .collect();
    let data = boxes(&points, 1e-4);
    let x0 = [Interval::new(2.0, 4.0), Interval::new(0.1, 1.0)];
    for settings in [
        Settings::default(),
        Settings::default().with_parallel(false),
    ] {
        let r = certify(&Decay, &x0, &data, &settings);
        assert_eq!(r.status, Status::Consistent);
        assert!(r.outer[0].contains(3.0) && r.outer[1].contains(0.5));
        assert!(
            r.outer[0].rad() < 1e-2 && r.outer[1].rad() < 1e-2,
            "{:?}",
            r.outer
        );
        let s = sweep(&Decay, &x0, &data, &settings);
        assert!(s
            .boxes
            .iter()
            .any(|b| b[0].contains(3.0) && b[1].contains(0.5)));
        let p = pave(&Decay, &x0, &data, &settings, 0.01, 500);
        assert!(p
            .boxes
            .iter()
            .any(|b| b[0].contains(3.0) && b[1].contains(0.5)));
        assert!(p.inner_volume <= p.outer_volume);
        // Volumes are never -0 (what summing no terms gives), which prints as "-0".
        assert!(p.inner_volume.is_sign_positive() && p.outer_volume.is_sign_positive());
    }
}
