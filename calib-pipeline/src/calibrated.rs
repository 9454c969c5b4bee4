//! The calibrated robot file every robot writes (`certify --write-calibrated`): each free
//! parameter at the midpoint of its certified outer box, with a radius whose box contains it.

use calib_core::Interval;

/// The value and radius a robot file writes for the certified box `outer`: the midpoint, and
/// the larger distance to an end rounded up plus a margin for the decimal text (the shortest
/// round-trip decimals read back are within half an ulp of the doubles written), so that
/// `value ± radius` contains `outer`.
pub fn midpoint_and_radius(outer: Interval) -> (f64, f64) {
    let v = outer.mid();
    let (lo, hi) = (Interval::point(outer.inf()), Interval::point(outer.sup()));
    let reach = (Interval::point(v) - lo)
        .sup()
        .max((hi - Interval::point(v)).sup());
    (
        v,
        (reach + 4.0 * f64::EPSILON * v.abs().max(reach)).next_up(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_written_box_contains_the_certified_one() {
        for (lo, hi) in [(-1.0, 1.0), (0.1, 0.3), (52.3, 52.300_000_1), (-1e-9, 7.0)] {
            let (v, r) = midpoint_and_radius(Interval::new(lo, hi));
            // Read back as text, as a controller would.
            let (v, r): (f64, f64) = (
                format!("{v:?}").parse().unwrap(),
                format!("{r:?}").parse().unwrap(),
            );
            assert!(Interval::mid_rad(v, r).inf() <= lo && Interval::mid_rad(v, r).sup() >= hi);
            // No wider than the half-width plus the decimal margin.
            assert!(r <= (hi - lo) / 2.0 + 8.0 * f64::EPSILON * (v.abs() + (hi - lo)));
        }
    }
}
