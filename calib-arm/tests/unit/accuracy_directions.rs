//! The tests of `calib_arm::accuracy::directions`.

use calib_arm::accuracy::directions::*;
use calib_arm::accuracy::ToolAccuracyProblem;
use calib_arm::certification::MAX_JOINTS;
use calib_arm::joint_space::JointSpace;
use calib_core::Interval;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// The built-in arm with every prior half-width scaled by `s`, on ±170° joints.
fn problem(s: f64) -> ToolAccuracyProblem {
    let arm = calib_arm::builtin_arm().with_radii_scaled(s);
    ToolAccuracyProblem::new(&arm, &JointSpace::simulator(6), 0.001).expect("problem")
}

/// A box of width `w` containing a random point of `[lo, hi]`.
fn around(rng: &mut StdRng, lo: f64, hi: f64, w: f64) -> Interval {
    let c: f64 = rng.random_range(lo..hi);
    let start = c - w * rng.random_range(0.0..1.0);
    Interval::new(start, start + w)
}

/// `u·(p(q; θ) - p(q; θ̂))` at sampled joints, directions and vertices, enclosed.
fn sampled(
    p: &ToolAccuracyProblem,
    rng: &mut StdRng,
    q: &[Interval; MAX_JOINTS],
    phi: Interval,
    lambda: Interval,
) -> f64 {
    let mut best = f64::NEG_INFINITY;
    for _ in 0..200 {
        let x: [f64; MAX_JOINTS] =
            core::array::from_fn(|k| q[k].inf() + q[k].wid() * rng.random_range(0.0..=1.0));
        let (f, l) = (
            phi.inf() + phi.wid() * rng.random_range(0.0..=1.0),
            lambda.inf() + lambda.wid() * rng.random_range(0.0..=1.0),
        );
        let u = [l.cos() * f.cos(), l.cos() * f.sin(), l.sin()];
        let theta = p.vertex_towards(&x, u);
        let e = p.error_enclosure(&x, &theta);
        let v = (0..3).fold(Interval::ZERO, |s, r| s + Interval::point(u[r]) * e[r]);
        best = best.max(v.inf());
    }
    best
}

#[test]
fn every_direction_box_bounds_the_errors_along_its_directions() {
    let mut rng = StdRng::seed_from_u64(5);
    for case in 0..40 {
        let p = problem([0.02, 0.3, 1.0][case % 3]);
        let w = [0.002, 0.02, 0.1, 0.3, 0.6][case % 5];
        let q: [Interval; MAX_JOINTS] = core::array::from_fn(|k| {
            if k < 6 {
                around(&mut rng, -2.6, 2.6, w)
            } else {
                Interval::ZERO
            }
        });
        let s = p.sensitivities(&q);
        assert_eq!(s.affine.is_some(), w <= AFFINE_WIDTH, "case {case}");
        for _ in 0..5 {
            let dw = rng.random_range(0.001..0.5);
            let (phi, lambda) = (
                around(&mut rng, -3.0, 2.5, dw),
                around(&mut rng, -1.4, 1.0, dw),
            );
            let d = DirectionBox::new(phi, lambda);
            let bound = s.bound(&d);
            let seen = sampled(&p, &mut rng, &q, phi, lambda);
            assert!(seen <= bound, "case {case}: {seen} above the bound {bound}");
            if let Some(columns) = &s.affine {
                let affine = s.affine_bound(columns, &d);
                assert!(
                    seen <= affine,
                    "case {case}: {seen} above the affine {affine}"
                );
            }
        }
    }
}

#[test]
fn the_product_with_a_box_of_directions_encloses_every_value() {
    // Columns with exact linear parts (no error radius): g(ε) = c + a·ε exactly, so every
    // value u(φ, λ)·g(ε) must lie in the product's form at the noise of (ε, φ, λ).
    let mut rng = StdRng::seed_from_u64(3);
    for case in 0..200 {
        let g = Column::new(core::array::from_fn(|_| {
            let mut f = JointForm::from_interval(Interval::point(rng.random_range(-50.0..50.0)));
            for k in 0..6 {
                let w = rng.random_range(0.0..20.0);
                f = f + JointForm::input(Interval::new(-w, w), k);
            }
            f
        }));
        let dw = [0.01, 0.3, 1.0][case % 3];
        let (phi, lambda) = (
            around(&mut rng, -3.0, 2.0, dw),
            around(&mut rng, -1.5, 0.5, dw),
        );
        let d = Directional::new(&g, &DirectionBox::new(phi, lambda));
        for _ in 0..200 {
            let eps: [f64; MAX_JOINTS] = core::array::from_fn(|k| {
                if k < 6 {
                    rng.random_range(-1.0..=1.0)
                } else {
                    0.0
                }
            });
            let eta = [rng.random_range(-1.0..=1.0), rng.random_range(-1.0..=1.0)];
            let (f, l) = (
                phi.mid() + eta[0] * phi.rad(),
                lambda.mid() + eta[1] * lambda.rad(),
            );
            let u = [l.cos() * f.cos(), l.cos() * f.sin(), l.sin()];
            let exact: f64 = (0..3)
                .map(|r| {
                    let gr = g.c[r] + (0..MAX_JOINTS).map(|k| g.a[r][k] * eps[k]).sum::<f64>();
                    u[r] * gr
                })
                .sum();
            let linear = d.c
                + (0..MAX_JOINTS).map(|k| d.a[k] * eps[k]).sum::<f64>()
                + d.b[0] * eta[0]
                + d.b[1] * eta[1];
            let slack = 1e-9 * (1.0 + d.mag);
            assert!(
                (exact - linear).abs() <= d.e + slack,
                "case {case}: {exact} vs {linear} ± {}",
                d.e
            );
        }
    }
}

#[test]
fn on_a_small_joint_box_the_bound_over_all_directions_is_tight() {
    // Second order in the box's width: a 0.5° box of every joint is bracketed within 1%
    // (the interval Jacobian alone leaves about 2% there).
    let mut rng = StdRng::seed_from_u64(8);
    let p = problem(0.05);
    for case in 0..4 {
        let q: [Interval; MAX_JOINTS] = core::array::from_fn(|k| {
            if k < 6 {
                around(&mut rng, -2.6, 2.6, 0.5f64.to_radians())
            } else {
                Interval::ZERO
            }
        });
        let upper = p.upper(&q, &DirectionCache::default(), 0.0);
        // The error over so small a box is largest at a corner: the largest corner's.
        let lower = (0..64u32)
            .map(|c| {
                let x: [f64; MAX_JOINTS] = core::array::from_fn(|k| match k {
                    6 => 0.0,
                    _ if c >> k & 1 == 1 => q[k].sup(),
                    _ => q[k].inf(),
                });
                p.dual_value(&x, &p.best_vertex_any(&x).0)
            })
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(
            lower > 0.0 && upper >= lower,
            "case {case}: {lower} {upper}"
        );
        assert!(upper <= 1.01 * lower, "case {case}: {upper} vs {lower}");
    }
}
