//! The tests of `calib_gough::accuracy::pose_bound`.

use calib_core::split_widest;
use calib_core::{Interval, Model};
use calib_gough::accuracy::enclosure::{AccuracyProblem, PoseBox};
use calib_gough::accuracy::pose_bound::*;
use calib_gough::accuracy::pose_chart::PoseChart;
use calib_gough::files::LegSpec;
use calib_gough::simulate::builtin_hexapod;
use calib_gough::workspace::Workspace;
use nalgebra::Matrix6;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// A tightly calibrated built-in hexapod on a small workspace, where the region closes.
fn problem(rng: &mut StdRng) -> AccuracyProblem {
    let radius = rng.random_range(0.0003..0.01);
    let robot: Vec<LegSpec> = builtin_hexapod()
        .into_iter()
        .map(|nominal| LegSpec {
            nominal,
            radius: [radius; 7],
        })
        .collect();
    let h = rng.random_range(0.1..0.3);
    let workspace = Workspace {
        x: [-h, h],
        y: [-h, h],
        z: [60.0 - h, 60.0 + h],
        tilt_deg: rng.random_range(0.2..0.5),
        stroke: None,
    };
    AccuracyProblem::new(&robot, &workspace)
}

/// A random sub-box of `b`, each side a fraction in `[lo, 1]` of `b`'s.
fn sub_box(b: &[Interval; 6], lo: f64, rng: &mut StdRng) -> [Interval; 6] {
    b.map(|v| {
        let w = v.wid() * rng.random_range(lo..1.0);
        let start = v.inf() + rng.random_range(0.0..=(v.wid() - w));
        Interval::new(start, start + w)
    })
}

/// A point of `v`: mostly an end (extremes are where an enclosure is tight).
fn point_in(v: &Interval, rng: &mut StdRng) -> f64 {
    if rng.random_bool(0.8) {
        if rng.random_bool(0.5) {
            v.inf()
        } else {
            v.sup()
        }
    } else if v.wid() > 0.0 {
        rng.random_range(v.inf()..=v.sup())
    } else {
        v.inf()
    }
}

/// The chart that follows the pose: at sampled poses its forms hold the exact `M(X) = M_c -
/// M_c (J(X) - J_c) M_c`, its remainder bounds `|G_i(X, M(X) y, θ*) - y_i|`, and its bound
/// holds every reached move (Newton along `t s`, `s` drawn from `[-U, U]`, mostly corners).
#[test]
fn the_pose_chart_holds_its_chart_remainder_and_reached_moves() {
    let mut rng = StdRng::seed_from_u64(9);
    let (mut checked, mut bounded) = (0, 0);
    for _ in 0..60 {
        let problem = problem(&mut rng);
        let x = sub_box(&problem.domain(), 0.05, &mut rng);
        let Some(chart) = PoseChart::new(&problem, &x, 0.0005) else {
            continue;
        };
        let jc = centre_jacobian(&problem, &x);
        let mc = proved_inverse(&jc).expect("the chart's inverse");
        let f = rng.random_range(1.0..2.0);
        let h = chart.bound.map(|u| f * u);
        let rest = chart.remainder(&h);
        let bound = chart.bound();
        for _ in 0..100 {
            let pose: [f64; 6] = core::array::from_fn(|k| point_in(&x[k], &mut rng));
            let point = PoseBox::from(pose.map(Interval::point));
            let mx = mc - mc * (centre_jacobian(&problem, &point) - jc) * mc;
            for r in 0..6 {
                for c in 0..6 {
                    let form = &chart.m[r][c];
                    let lin = (0..6).fold(form.centre(), |s, k| {
                        let e = if x[k].rad() > 0.0 {
                            (pose[k] - x[k].mid()) / x[k].rad()
                        } else {
                            0.0
                        };
                        s + form.coefficients()[k] * e
                    });
                    let tol = 1e-9 * (1.0 + mx[(r, c)].abs());
                    assert!(
                        (mx[(r, c)] - lin).abs() <= form.error() + tol,
                        "M({r}, {c})"
                    );
                }
            }
            let thetas = leg_inputs(&problem, &pose, |t| point_in(&t, &mut rng));
            let y: [f64; 6] =
                core::array::from_fn(|c| point_in(&Interval::new(-h[c], h[c]), &mut rng));
            let d: [f64; 6] = core::array::from_fn(|r| (0..6).map(|c| mx[(r, c)] * y[c]).sum());
            for i in 0..6 {
                let g = ReachedChange.residual(&d, &thetas[i]);
                assert!(
                    (g - y[i]).abs() <= rest[i] + 1e-12,
                    "leg {i}: |G - y| {} above {}",
                    (g - y[i]).abs(),
                    rest[i]
                );
                checked += 1;
            }
            let Some([pos, ori]) = bound else { continue };
            // A reached move: leg changes s, Newton along t s from δ = 0.
            let s: [f64; 6] = core::array::from_fn(|i| {
                chart.bound[i]
                    * if rng.random_bool(0.5) { 1.0 } else { -1.0 }
                    * if rng.random_bool(0.8) {
                        1.0
                    } else {
                        rng.random_range(0.0..1.0)
                    }
            });
            let mut delta = [0.0; 6];
            let mut ok = true;
            for step in 1..=10 {
                let t = step as f64 / 10.0;
                for _ in 0..20 {
                    let mut a = Matrix6::zeros();
                    let mut g = nalgebra::Vector6::zeros();
                    for i in 0..6 {
                        g[i] = ReachedChange.residual(&delta, &thetas[i]) - t * s[i];
                        let row = ReachedChange.jacobian_x(&delta, &thetas[i]);
                        for k in 0..6 {
                            a[(i, k)] = row[k];
                        }
                    }
                    let Some(step) = a.lu().solve(&g) else {
                        ok = false;
                        break;
                    };
                    for k in 0..6 {
                        delta[k] -= step[k];
                    }
                }
            }
            if !ok {
                continue;
            }
            let p = (delta[0].powi(2) + delta[1].powi(2) + delta[2].powi(2)).sqrt();
            let w = (delta[3].powi(2) + delta[4].powi(2) + delta[5].powi(2)).sqrt();
            assert!(p <= pos * (1.0 + 1e-9), "|d| = {p} above {pos}");
            assert!(
                2.0 * w.atan().to_degrees() <= ori * (1.0 + 1e-9),
                "angle above {ori}"
            );
            bounded += 1;
        }
    }
    assert!(
        checked > 5000 && bounded > 500,
        "{checked} remainders, {bounded} moves checked"
    );
}

/// The halves of a box hold its share of the workspace between them; a coordinate in which
/// the workspace is a point counts whole.
#[test]
fn halves_share_their_parents_volume() {
    let domain: PoseBox = [
        Interval::new(-1.0, 1.0),
        Interval::new(0.0, 4.0),
        Interval::new(59.0, 61.0),
        Interval::new(-0.1, 0.1),
        Interval::new(-0.1, 0.1),
        Interval::ZERO,
    ];
    assert_eq!(share_of(&domain, &domain), 1.0);
    let (l, r) = split_widest(&domain, &domain).expect("splits");
    assert_eq!(share_of(&l, &domain) + share_of(&r, &domain), 1.0);
    let (ll, lr) = split_widest(&l, &domain).expect("splits");
    assert_eq!(share_of(&ll, &domain), 0.25);
    assert_eq!(share_of(&lr, &domain), 0.25);
}
