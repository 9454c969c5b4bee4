//! The tests of `calib_pipeline::calibrated`.

use calib_core::Interval;
use calib_pipeline::calibrated::*;

#[test]
fn the_written_box_contains_the_certified_one() {
    for (lo, hi, t) in [
        (-1.0, 1.0, 0.5),
        (0.1, 0.3, 0.1),
        (52.3, 52.300_000_1, 0.75),
        (-1e-9, 7.0, 0.0),
    ] {
        let v = lo + t * (hi - lo);
        let r = radius_about(v, Interval::new(lo, hi));
        // Read back as text, as a controller would.
        let (v, r): (f64, f64) = (
            format!("{v:?}").parse().unwrap(),
            format!("{r:?}").parse().unwrap(),
        );
        let written = Interval::mid_rad(v, r);
        assert!(written.inf() <= lo && written.sup() >= hi);
        // No wider than the larger distance plus the decimal margin.
        let reach = (v - lo).max(hi - v);
        assert!(r <= reach + 8.0 * f64::EPSILON * (v.abs() + (hi - lo)));
    }
}
