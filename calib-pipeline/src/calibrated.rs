//! The calibrated robot file every robot writes (`certify --write-calibrated`): each free
//! parameter at the calibrated point (a parameter vector proved consistent with every
//! measurement, [`calib_core::calibrated_point()`]), with a radius whose box around it contains the
//! certified outer box, and the certified set itself ([`crate::stored_set`]).

use calib_core::Interval;

/// The radius a robot file writes for `value` and the certified box `outer`: the larger distance
/// from `value` to an end of `outer`, rounded up, plus a margin for the decimal text (the
/// shortest round-trip decimals read back are within half an ulp of the doubles written), so
/// that `value ± radius` contains `outer`.
pub fn radius_about(value: f64, outer: Interval) -> f64 {
    let v = Interval::point(value);
    let reach = (v - Interval::point(outer.inf()))
        .sup()
        .max((Interval::point(outer.sup()) - v).sup())
        .max(0.0);
    (reach + 4.0 * f64::EPSILON * value.abs().max(reach)).next_up()
}
