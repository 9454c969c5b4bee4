//! The second-order Taylor rows of a certified set's pieces
//! (`CertifiedSet::add_curvature_rows`): every parameter vector consistent with a measurement
//! still satisfies them, anywhere in a wide box (where the rows are tight and the remainder
//! large), and on a curved chain whose prior leaves a combination undetermined they narrow the
//! set where the relaxation's rows were loose.

use super::second_order::{measurements, offset_arm, prior, OffsetArm, TRUTH};
use calib_core::{CertifiedSet, Cover, Interval, Jet2, VectorModel};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Where the rows' Hessians come from.
#[derive(Clone, Copy, Debug)]
enum Rows {
    None,
    /// The model's derivatives (`#[interval_model(curvature)]`).
    Curvature,
    /// The residual over second-order jets of intervals, the way a robot without them supplies
    /// its own (`CertifiedSet::add_second_order_rows`).
    OverBox,
}

/// `offset_arm`'s Hessians over the boxes, per row, for `symbols`.
fn hessian_over(x: &[Interval; 7], m: &[Interval; 4], symbols: &[usize]) -> Option<Vec<Interval>> {
    type J = Jet2<Interval, 11, 66>;
    let jet = |v: Interval, k: usize| match symbols.iter().position(|&s| s == k) {
        Some(a) => J::variable(v, a),
        None => J::constant(v),
    };
    let xs: [J; 7] = core::array::from_fn(|j| jet(x[j], j));
    let ms: [J; 4] = core::array::from_fn(|i| jet(m[i], 7 + i));
    let f = offset_arm(&xs, &ms);
    let n = symbols.len();
    Some(
        f.iter()
            .flat_map(|r| (0..n * n).map(move |k| r.second(k / n, k % n)))
            .collect(),
    )
}

/// The set of one box `x` against `data` (no certified points), with the rows asked for.
fn one_piece(x: [Interval; 7], data: &[[Interval; 4]], rows: Rows) -> CertifiedSet<7, 4> {
    let cover = Cover {
        boxes: vec![x],
        subsets: vec![0],
        dropped: vec![Vec::new()],
    };
    let mut set = CertifiedSet::new(&OffsetArm, &cover, data, &[], 1);
    match rows {
        Rows::None => {}
        Rows::Curvature => set.add_curvature_rows(&OffsetArm),
        Rows::OverBox => set.add_second_order_rows(&OffsetArm, &hessian_over),
    }
    set
}

#[test]
fn every_consistent_vector_satisfies_the_rows_anywhere_in_a_wide_box() {
    let mut rng = StdRng::seed_from_u64(31);
    for trial in 0..300 {
        let rows = if trial % 2 == 0 {
            Rows::Curvature
        } else {
            Rows::OverBox
        };
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
        let set = one_piece(x, &[m], rows);
        assert!(
            !set.is_empty(),
            "trial {trial}: a consistent box proved empty"
        );
        assert!(
            set.admits(&v, 1e-12),
            "trial {trial} ({rows:?}): {v:?} cut off"
        );
    }
}

#[test]
fn the_rows_narrow_the_set_of_a_curved_chain_and_never_widen_it() {
    let mut rng = StdRng::seed_from_u64(5);
    let mut narrower = 0;
    for trial in 0..3 {
        let x = prior(&mut rng);
        let data = measurements(&mut rng, &TRUTH, 16, 2e-4, 0.3);
        let plain = one_piece(x, &data, Rows::None);
        let mut p = plain.query();
        for rows in [Rows::Curvature, Rows::OverBox] {
            let tight = one_piece(x, &data, rows);
            let mut t = tight.query();
            for j in 0..7 {
                for sign in [1.0, -1.0] {
                    let mut w = [0.0; 7];
                    w[j] = sign;
                    let (before, after) = (p.support(&w), t.support(&w));
                    assert!(
                        after <= before + 1e-9 * before.abs().max(1.0),
                        "trial {trial} ({rows:?}): coordinate {j} widened from {before} to {after}"
                    );
                    if after < before - 1e-6 * before.abs().max(1.0) {
                        narrower += 1;
                    }
                }
            }
            // The truth fits the readings: it stays.
            assert!(
                tight.admits(&TRUTH, 1e-12),
                "trial {trial} ({rows:?}): truth cut off"
            );
        }
    }
    assert!(narrower > 0, "the rows narrowed no coordinate");
}
