//! The certified set of Gough legs on simulated data: the true geometry lies in it (a piece
//! admits it, every support bound holds it) over many data sets, the set is tens of times
//! narrower than its box along `a_z + l - b_z`, and the calibrated geometry fits every
//! measurement by an exhaustive corner test (independent of the kernel's linearisations), where
//! the box's midpoint does not.

use calib_core::{
    calibrated_point, hull, is_consistent_by_corners, CertifiedSet, Interval, PointRule, Settings,
};
use calib_gough::{builtin_hexapod, leg_boxes, simulate, GoughLeg, Uncertainty};
use rand::{Rng, SeedableRng};

#[test]
fn the_truth_lies_in_the_certified_set_of_every_leg_over_many_data_sets() {
    let truth = builtin_hexapod();
    let mut midpoints_misfit = 0;
    for seed in 0..8u64 {
        let sim = simulate(&truth, 21, seed, Uncertainty::PAPER, 1.0, 0.1);
        let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
        for leg in [seed as usize % 6, (seed as usize + 3) % 6] {
            let boxes = leg_boxes(&sim.measured, &sim.uncertainty, leg);
            let x0 = sim.nominal[leg].params().map(|v| Interval::mid_rad(v, 0.1));
            let h = hull(&GoughLeg, &x0, &boxes, &Settings::default());
            let mut points = h.inner_points.clone();
            points.extend(h.witness);
            let mut set = CertifiedSet::new(&GoughLeg, &h.cover, &boxes, &points, 8);
            let t = truth[leg].params();
            assert!(
                set.admits(&t, 1e-12),
                "seed {seed} leg {leg}: truth in no piece"
            );
            let mut q = set.query();
            for _ in 0..50 {
                let w: [f64; 7] = core::array::from_fn(|_| rng.random_range(-1.0..1.0));
                let wt: f64 = w.iter().zip(&t).map(|(a, b)| a * b).sum();
                assert!(q.range(&w).contains(wt), "seed {seed} leg {leg}: {w:?}");
            }
            // Thin where the box is wide: a_z + l - b_z.
            let w = [0.0, 0.0, 1.0, 0.0, 0.0, -1.0, 1.0];
            let thin = q.range(&w);
            let outer = set.outer().expect("consistent");
            let boxed = outer[2] + outer[6] - outer[5];
            assert!(
                thin.wid() * 20.0 < boxed.wid(),
                "{thin:?} against {boxed:?}"
            );
            // The calibrated geometry fits every measurement (exhaustive corners).
            let p = calibrated_point(&GoughLeg, &mut set, PointRule::LeastSquares)
                .expect("consistent data");
            assert!(
                is_consistent_by_corners(&GoughLeg, &p.x, &boxes),
                "seed {seed} leg {leg}: {p:?}"
            );
            let mid = h.outer.map(|v| v.mid());
            midpoints_misfit += usize::from(!is_consistent_by_corners(&GoughLeg, &mid, &boxes));
        }
    }
    // What the calibrated file wrote before: the box's midpoint misfits the data on most legs.
    assert!(
        midpoints_misfit >= 12,
        "{midpoints_misfit} of 16 midpoints misfit"
    );
}
