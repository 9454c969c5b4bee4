//! Second-order emptiness proofs (`calib_core::second_order`): the derivatives
//! `#[interval_model(curvature)]` generates agree with finite differences and enclose sampled
//! values; the combination's lower bound never excludes a box that holds the truth, whatever
//! weights and expansion point it is given (a lying LP engine cannot make it prove a consistent
//! data set empty); and near the smallest consistent error bound, where the contraction alone
//! stays undecided, `certify` proves inconsistent data empty with it.
#![allow(clippy::needless_range_loop)]

use calib_core::combination_lower_bound;
use calib_core::{
    certify, contract, hull, interval_model, is_consistent_point, second_order_emptiness,
    smallest_scale, Curvature, EmptinessProof, Interval, Scalar, Settings, Status, VectorModel,
    Workspace,
};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// A planar two-link arm with encoder offsets and an unknown base position and rotation, tracked
/// in the plane: parameters `(l1, l2, o1, o2, bx, by, br)`, measurements `(q1, q2, px, py)`. The
/// base rotation `br` and the first offset `o1` only act through their sum: the data cannot
/// determine their difference (like the UR10's redundant parameters), the consistent set spans the
/// prior along it, and the relaxation keeps the curvature of the whole span.
#[interval_model(curvature)]
pub fn offset_arm<S: Scalar>(x: &[S; 7], m: &[S; 4]) -> [S; 2] {
    let [l1, l2, o1, o2, bx, by, br] = *x;
    let [q1, q2, px, py] = *m;
    let t1 = q1 + o1 + br;
    let t12 = t1 + q2 + o2;
    [
        bx + l1 * t1.cos() + l2 * t12.cos() - px,
        by + l1 * t1.sin() + l2 * t12.sin() - py,
    ]
}

pub(crate) const TRUTH: [f64; 7] = [700.0, 500.0, 0.01, -0.02, 30.0, -40.0, 0.005];

/// The prior: ±2 mm on the lengths and the base, ±0.2° on the offsets, around the truth shifted
/// by a random fraction of the box.
pub(crate) fn prior(rng: &mut StdRng) -> [Interval; 7] {
    let deg = 0.2f64.to_radians();
    let rad = [2.0, 2.0, deg, deg, 2.0, 2.0, deg];
    core::array::from_fn(|j| {
        let centre = TRUTH[j] + rng.random_range(-0.5..0.5) * rad[j];
        Interval::mid_rad(centre, rad[j])
    })
}

/// `n` configurations of the arm at `truth`: joint readings within ±`joint` rad of the true
/// angles and tracked points within ±`pos` mm of the true tip, each reading's box of the same
/// half-widths around the reading (so the truth fits every box).
pub(crate) fn measurements(
    rng: &mut StdRng,
    truth: &[f64; 7],
    n: usize,
    joint: f64,
    pos: f64,
) -> Vec<[Interval; 4]> {
    (0..n)
        .map(|_| {
            let q = [rng.random_range(-1.5..1.5), rng.random_range(-2.0..2.0)];
            let tip = OffsetArm.residuals(truth, &[q[0], q[1], 0.0, 0.0]);
            let read = |v: f64, r: f64, rng: &mut StdRng| v + rng.random_range(-r..r);
            [
                Interval::mid_rad(read(q[0], joint, rng), joint),
                Interval::mid_rad(read(q[1], joint, rng), joint),
                Interval::mid_rad(read(tip[0], pos, rng), pos),
                Interval::mid_rad(read(tip[1], pos, rng), pos),
            ]
        })
        .collect()
}

fn random_in(rng: &mut StdRng, b: Interval) -> f64 {
    rng.random_range(b.inf()..=b.sup())
}

#[test]
fn second_derivatives_match_finite_differences() {
    let mut rng = StdRng::seed_from_u64(11);
    let symbols: Vec<usize> = (0..11).collect();
    for _ in 0..20 {
        let x: [f64; 7] = core::array::from_fn(|j| TRUTH[j] + rng.random_range(-1.0..1.0));
        let m = [
            rng.random_range(-1.5..1.5),
            rng.random_range(-2.0..2.0),
            rng.random_range(-10.0..10.0),
            rng.random_range(-10.0..10.0),
        ];
        let h = OffsetArm.second_derivatives(&x, &m, &symbols).unwrap();
        // ∂/∂z_b of the row's gradient, by central differences of the generated Jacobians.
        let gradient = |x: &[f64; 7], m: &[f64; 4]| -> Vec<[f64; 11]> {
            OffsetArm
                .evaluate_rows(x, m)
                .iter()
                .map(|e| core::array::from_fn(|a| if a < 7 { e.dx[a] } else { e.dm[a - 7] }))
                .collect()
        };
        for b in 0..11 {
            let step = 1e-5 * if b < 7 { x[b].abs().max(1.0) } else { 1.0 };
            let (mut xp, mut mp, mut xm, mut mm) = (x, m, x, m);
            if b < 7 {
                xp[b] += step;
                xm[b] -= step;
            } else {
                mp[b - 7] += step;
                mm[b - 7] -= step;
            }
            let (gp, gm) = (gradient(&xp, &mp), gradient(&xm, &mm));
            for r in 0..2 {
                for a in 0..11 {
                    let fd = (gp[r][a] - gm[r][a]) / (2.0 * step);
                    let e = h[r * 121 + a * 11 + b];
                    assert!(
                        e.rad() <= 1e-9 * e.mag().max(1.0),
                        "not a point enclosure: {e:?}"
                    );
                    assert!(
                        (e.mid() - fd).abs() <= 1e-5 * fd.abs().max(1.0),
                        "row {r}, ∂²/∂z{a}∂z{b}: {} against {fd}",
                        e.mid()
                    );
                }
            }
        }
    }
}

#[test]
fn inputs_that_enter_linearly_are_not_curved() {
    // The base position and the tracked point enter every row linearly; lengths, offsets, the
    // base rotation and the joint readings do not.
    let curved: Vec<bool> = (0..11).map(|s| OffsetArm.curved(s)).collect();
    assert_eq!(
        curved,
        [true, true, true, true, false, false, true, true, true, false, false]
    );
}

#[test]
fn third_derivative_enclosures_contain_sampled_directional_derivatives() {
    let mut rng = StdRng::seed_from_u64(12);
    let symbols: Vec<usize> = (0..11).collect();
    for _ in 0..10 {
        let x = prior(&mut rng);
        let m = [
            Interval::mid_rad(rng.random_range(-1.5..1.5), 0.01),
            Interval::mid_rad(rng.random_range(-2.0..2.0), 0.01),
            Interval::mid_rad(0.0, 0.5),
            Interval::mid_rad(0.0, 0.5),
        ];
        let x0: [f64; 7] = core::array::from_fn(|j| random_in(&mut rng, x[j]));
        let m0: [f64; 4] = core::array::from_fn(|i| random_in(&mut rng, m[i]));
        let t = OffsetArm
            .third_derivatives_along(&x, &m, &x0, &m0, &symbols)
            .unwrap();
        for _ in 0..20 {
            // ξ and z in the boxes: Σ_c T_abc(ξ) (z_c − z0_c) by differences of the Hessian.
            let xi: [f64; 7] = core::array::from_fn(|j| random_in(&mut rng, x[j]));
            let mi: [f64; 4] = core::array::from_fn(|i| random_in(&mut rng, m[i]));
            let u: [f64; 11] = core::array::from_fn(|c| {
                if c < 7 {
                    random_in(&mut rng, x[c]) - x0[c]
                } else {
                    random_in(&mut rng, m[c - 7]) - m0[c - 7]
                }
            });
            let step = 1e-4;
            let shifted = |sign: f64| {
                let xs: [f64; 7] = core::array::from_fn(|j| xi[j] + sign * step * u[j]);
                let ms: [f64; 4] = core::array::from_fn(|i| mi[i] + sign * step * u[7 + i]);
                OffsetArm.second_derivatives(&xs, &ms, &symbols).unwrap()
            };
            let (hp, hm) = (shifted(1.0), shifted(-1.0));
            for k in 0..t.len() {
                let fd = (hp[k].mid() - hm[k].mid()) / (2.0 * step);
                let slack = 1e-6 * (1.0 + fd.abs());
                assert!(
                    t[k].inf() - slack <= fd && fd <= t[k].sup() + slack,
                    "entry {k}: {fd} outside {:?}",
                    t[k]
                );
            }
        }
    }
}

/// Whatever weights and expansion point it is given (random ones, or the Chebyshev fit's), the
/// combination's lower bound over a box that holds the truth is at most 0: a wrong answer of the
/// LP engine cannot turn into a proof of emptiness.
#[test]
fn no_weights_prove_a_box_with_the_truth_empty() {
    let mut rng = StdRng::seed_from_u64(13);
    for trial in 0..12 {
        let x = prior(&mut rng);
        let data = measurements(&mut rng, &TRUTH, 12, 2e-4, 0.05);
        for _ in 0..5 {
            let point: [f64; 7] = core::array::from_fn(|j| random_in(&mut rng, x[j]));
            let weights: Vec<[f64; 2]> = data
                .iter()
                .map(|_| [rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)])
                .collect();
            let bound =
                combination_lower_bound(&OffsetArm, &OffsetArm, &x, &data, &point, &weights)
                    .unwrap();
            assert!(bound <= 0.0, "trial {trial}: lower bound {bound} > 0");
        }
        assert_eq!(
            second_order_emptiness(&OffsetArm, &OffsetArm, &x, &data),
            None,
            "trial {trial}: consistent data proved empty"
        );
    }
}

/// Data whose errors exceed their bounds by 2%: the contraction alone leaves the prior undecided
/// (`o1 + br` spans twice its share of the prior), the second-order certificate proves the
/// contracted box empty, and so does `certify`, naming the proof and its support: a misfit spread
/// over the data, for which no conflict set is searched.
#[test]
fn data_just_below_their_smallest_consistent_bound_are_proved_empty() {
    let mut rng = StdRng::seed_from_u64(14);
    let mut second_order_needed = 0;
    for trial in 0..4 {
        let x = prior(&mut rng);
        let data = measurements(&mut rng, &TRUTH, 16, 2e-4, 0.3);
        // Bounds scaled to 98% of the first-order smallest consistent factor.
        let fit = smallest_scale(&OffsetArm, &x, &data, &[true; 4]);
        let s = 0.98 * fit.scale;
        let scaled: Vec<[Interval; 4]> = data
            .iter()
            .map(|m| m.map(|v| Interval::mid_rad(v.mid(), v.rad() * s)))
            .collect();
        let settings = Settings::default();
        let mut ws = Workspace::new(&settings);
        let contracted = contract(&OffsetArm, &x, &scaled, &settings, &mut ws).result;
        if let Ok(b) = contracted {
            second_order_needed += 1;
            let proof = second_order_emptiness(&OffsetArm, &OffsetArm, &b, &scaled)
                .unwrap_or_else(|| panic!("trial {trial}: not proved at 0.98 s*"));
            assert!(proof.margin > 0.0 && !proof.support.is_empty());
        }
        let c = certify(&OffsetArm, &x, &scaled, &settings);
        assert_eq!(c.status, Status::Empty, "trial {trial}");
        if contracted.is_ok() {
            assert_eq!(c.emptiness, Some(EmptinessProof::SecondOrder));
            // Every configuration misses its bounds by 2%: the certificate weighs most of what it
            // can (7 free parameters: at most 8 configurations), a spread misfit, whose conflict
            // set is not searched.
            let support = c.support.as_ref().expect("the certificate's support");
            assert!(c.spread, "trial {trial}: support {support:?}");
            assert_eq!(c.conflict, None, "trial {trial}");
        }
    }
    assert!(
        second_order_needed > 0,
        "the contraction decided every case: the test does not reach the second-order proof"
    );
}

/// The hull of a model with curvature splits its boxes across the faces they hold and discards the
/// halves the certificate proves empty: on data whose readings hold the truth, at bounds just
/// above their smallest consistent factor, the outer box still contains the truth and the inner
/// box, and every certified point it reports is consistent.
#[test]
fn hulls_with_certificates_keep_the_truth() {
    let mut rng = StdRng::seed_from_u64(15);
    for trial in 0..2 {
        let x = prior(&mut rng);
        let data = measurements(&mut rng, &TRUTH, 16, 2e-4, 0.3);
        let fit = smallest_scale(&OffsetArm, &x, &data, &[true; 4]);
        // Near the threshold, but the readings' own bounds (which hold the truth) at least.
        let s = (1.02 * fit.scale).max(1.0);
        let scaled: Vec<[Interval; 4]> = data
            .iter()
            .map(|m| m.map(|v| Interval::mid_rad(v.mid(), v.rad() * s)))
            .collect();
        let settings = Settings::default().with_hull_budget(60, None);
        let h = hull(&OffsetArm, &x, &scaled, &settings);
        assert_ne!(h.status, Status::Empty, "trial {trial}");
        for j in 0..7 {
            // s >= 1: the widened readings still hold the truth.
            assert!(
                h.outer[j].contains(TRUTH[j]),
                "trial {trial}: truth out of {j}"
            );
            if let Some(inner) = h.inner {
                assert!(
                    inner[j].is_subset_of(h.outer[j]),
                    "trial {trial}: inner {j}"
                );
            }
        }
        if let Some(w) = h.witness {
            assert!(is_consistent_point(&OffsetArm, &w, &scaled));
        }
    }
}
