//! The tests of `calib_gough::lsq`.

use calib_gough::lsq::*;
use calib_gough::{builtin_hexapod, leg_values, simulate, LegModel, Uncertainty};

#[test]
fn recovers_the_truth_from_exact_data() {
    let truth = builtin_hexapod();
    let sim = simulate(&truth, 21, 9, Uncertainty::uniform(0.0), 0.0, 0.1);
    for leg in 0..6 {
        let m = leg_values(&sim.measured, leg);
        let fit = fit_leg(&sim.nominal[leg].params(), LegModel::of(&sim.measured), &m);
        let t = truth[leg].params();
        assert!(fit.converged);
        for j in 0..7 {
            assert!(
                (fit.x[j] - t[j]).abs() < 1e-6,
                "leg {leg} param {j}: {} vs {}",
                fit.x[j],
                t[j]
            );
        }
        assert!(fit.max_length_error < 1e-9);
    }
}
