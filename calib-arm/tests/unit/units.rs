//! The tests of `calib_arm::units`.

use calib_arm::units::*;
use calib_core::Interval;

#[test]
fn conversions_enclose_and_round_trip_outward() {
    for d in [-180.0, -90.0, -0.001, 0.0, 0.05, 25.0, 90.0, 179.999] {
        let b = Interval::mid_rad(d, 1e-3);
        let r = deg_to_rad(b);
        assert!(r.contains(to_rad(d)));
        assert!(b.is_subset_of(rad_to_deg(r)));
        assert!(rad_to_deg(r).wid() < b.wid() * (1.0 + 1e-12) + 1e-12);
    }
}
