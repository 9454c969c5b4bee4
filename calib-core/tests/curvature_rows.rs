//! The second-order Taylor rows of a certified set's pieces
//! (`CertifiedSet::add_curvature_rows`): every parameter vector consistent with a measurement
//! still satisfies them, anywhere in a wide box (where the rows are tight and the remainder
//! large), and on a curved chain whose prior leaves a combination undetermined they narrow the
//! set where the relaxation's rows were loose.

use super::second_order::{measurements, prior, OffsetArm, TRUTH};
use calib_core::{CertifiedSet, Cover, Interval, VectorModel};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// The set of one box `x` against `data` (no certified points), with or without the rows.
fn one_piece(x: [Interval; 7], data: &[[Interval; 4]], rows: bool) -> CertifiedSet<7, 4> {
    let cover = Cover {
        boxes: vec![x],
        subsets: vec![0],
        dropped: vec![Vec::new()],
    };
    let mut set = CertifiedSet::new(&OffsetArm, &cover, data, &[], 1);
    if rows {
        set.add_curvature_rows(&OffsetArm);
    }
    set
}

#[test]
fn every_consistent_vector_satisfies_the_rows_anywhere_in_a_wide_box() {
    let mut rng = StdRng::seed_from_u64(31);
    for trial in 0..300 {
        // A box far wider than any set (±5 mm, ±3°), a vector anywhere in it, and a reading it
        // fits exactly: its tracked point shifted onto the vector's tip, its boxes a hair wide.
        let x: [Interval; 7] = core::array::from_fn(|j| {
            let r = if matches!(j, 2 | 3 | 6) {
                3f64.to_radians()
            } else {
                5.0
            };
            Interval::mid_rad(TRUTH[j] + rng.random_range(-0.5..0.5) * r, r)
        });
        let v: [f64; 7] = x.map(|b| rng.random_range(b.inf()..=b.sup()));
        let q = [rng.random_range(-1.5..1.5), rng.random_range(-2.0..2.0)];
        let tip = OffsetArm.residuals(&v, &[q[0], q[1], 0.0, 0.0]);
        let hair = 1e-9;
        let m = [
            Interval::mid_rad(q[0], hair),
            Interval::mid_rad(q[1], hair),
            Interval::mid_rad(tip[0], hair),
            Interval::mid_rad(tip[1], hair),
        ];
        let set = one_piece(x, &[m], true);
        assert!(
            !set.is_empty(),
            "trial {trial}: a consistent box proved empty"
        );
        assert!(set.admits(&v, 1e-12), "trial {trial}: {v:?} cut off");
    }
}

#[test]
fn the_rows_narrow_the_set_of_a_curved_chain_and_never_widen_it() {
    let mut rng = StdRng::seed_from_u64(5);
    let mut narrower = 0;
    for trial in 0..3 {
        let x = prior(&mut rng);
        let data = measurements(&mut rng, &TRUTH, 16, 2e-4, 0.3);
        let (plain, tight) = (one_piece(x, &data, false), one_piece(x, &data, true));
        let (mut p, mut t) = (plain.query(), tight.query());
        for j in 0..7 {
            for sign in [1.0, -1.0] {
                let mut w = [0.0; 7];
                w[j] = sign;
                let (before, after) = (p.support(&w), t.support(&w));
                assert!(
                    after <= before + 1e-9 * before.abs().max(1.0),
                    "trial {trial}: coordinate {j} widened from {before} to {after}"
                );
                if after < before - 1e-6 * before.abs().max(1.0) {
                    narrower += 1;
                }
            }
        }
        // The truth fits the readings: it stays.
        assert!(tight.admits(&TRUTH, 1e-12), "trial {trial}: truth cut off");
    }
    assert!(narrower > 0, "the rows narrowed no coordinate");
}
