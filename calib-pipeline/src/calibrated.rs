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

#[cfg(test)]
mod tests {
    use super::*;

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
}
