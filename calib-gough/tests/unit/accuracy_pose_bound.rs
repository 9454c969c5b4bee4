//! The tests of `calib_gough::accuracy::pose_bound`.

use calib_core::split_widest;
use calib_core::{Interval, Model};
use calib_gough::accuracy::enclosure::{AccuracyProblem, PoseBox};
use calib_gough::accuracy::pose_bound::*;
use calib_gough::accuracy::pose_chart::{scaled_norm, PoseChart};
use calib_gough::files::LegSpec;
use calib_gough::simulate::builtin_hexapod;
use calib_gough::workspace::Workspace;
use nalgebra::Matrix6;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// A calibrated built-in hexapod (every parameter within a random radius) on a random workspace,
/// from a few millimetres and tenths of a degree to a few centimetres and degrees, and its legs.
fn problem(rng: &mut StdRng) -> (AccuracyProblem, Vec<LegSpec>) {
    // From a tight calibration to boxes as wide as an undetermined direction leaves them.
    let radius = 10f64.powf(rng.random_range(-3.5..-0.7));
    let robot: Vec<LegSpec> = builtin_hexapod()
        .into_iter()
        .map(|nominal| LegSpec {
            nominal,
            radius: [radius; 7],
        })
        .collect();
    let h = if rng.random_bool(0.5) {
        rng.random_range(0.1..0.3)
    } else {
        rng.random_range(1.0..3.0)
    };
    let workspace = Workspace {
        x: [-h, h],
        y: [-h, h],
        z: [60.0 - h, 60.0 + h],
        tilt_deg: h * rng.random_range(1.0..2.5),
        stroke: None,
    };
    (AccuracyProblem::new(&robot, &workspace), robot)
}

/// The legs' Jacobian `∇_δ G` at `δ = 0` at the pose `pose` and the nominal geometry, in floating
/// point (independently of the chart's affine forms).
fn jacobian(robot: &[LegSpec], pose: &[f64; 6]) -> Matrix6<f64> {
    Matrix6::from_fn(|i, k| {
        let n = robot[i].nominal.params();
        let m: [f64; 12] = core::array::from_fn(|j| if j < 6 { pose[j] } else { n[j - 6] });
        ReachedChange.jacobian_x(&[0.0; 6], &m)[k]
    })
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

/// The chart that follows the pose: at sampled poses its forms hold the exact inverse `M(X) =
/// J(X)⁻¹`, its remainder bounds `|G_i(X, M(X) y, θ*) - y_i|` for geometries of the legs' boxes,
/// and its bound holds every reached move (Newton along `t s`, `s` drawn from `[-U, U]`, mostly
/// corners) — on boxes of poses up to centimetres and degrees wide.
#[test]
fn the_pose_chart_holds_its_inverse_remainder_and_reached_moves() {
    let mut rng = StdRng::seed_from_u64(9);
    let (mut checked, mut bounded, mut wide) = (0, 0, 0);
    for _ in 0..80 {
        let (problem, robot) = problem(&mut rng);
        let x = sub_box(&problem.domain(), 0.05, &mut rng);
        let Some(chart) = PoseChart::new(&problem, &x, 0.0005) else {
            continue;
        };
        // Small moves too, where the geometry's part of the remainder dominates the moves'.
        let f = 10f64.powf(rng.random_range(-2.0..0.45));
        let h = chart.bound.map(|[below, above]| f * below.max(above));
        let rest = chart.remainder_over(&h).expect("a remainder within 3 U");
        let bound = chart.bound();
        if bound.is_some() && x[0].wid() > 0.5 {
            wide += 1;
        }
        for _ in 0..100 {
            let pose: [f64; 6] = core::array::from_fn(|k| point_in(&x[k], &mut rng));
            let mx = jacobian(&robot, &pose)
                .try_inverse()
                .expect("J(X) nonsingular");
            for r in 0..6 {
                for c in 0..6 {
                    let lin = (0..6).fold(chart.centre[r][c], |s, k| {
                        let e = if x[k].rad() > 0.0 {
                            (pose[k] - x[k].mid()) / x[k].rad()
                        } else {
                            0.0
                        };
                        s + chart.slope[k][r][c] * e
                    });
                    let tol = 1e-9 * (1.0 + mx[(r, c)].abs());
                    assert!(
                        (mx[(r, c)] - lin).abs() <= chart.slack[r][c] + tol,
                        "M({r}, {c}): {} against {lin} ± {}",
                        mx[(r, c)],
                        chart.slack[r][c]
                    );
                }
            }
            let thetas: Vec<[f64; 12]> = (0..6)
                .map(|i| {
                    let t = problem.theta(i);
                    core::array::from_fn(|k| {
                        if k < 6 {
                            pose[k]
                        } else {
                            point_in(&t[k - 6], &mut rng)
                        }
                    })
                })
                .collect();
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
            // A reached move: leg changes s within [-U⁻, U⁺], Newton along t s from δ = 0.
            let s: [f64; 6] = core::array::from_fn(|i| {
                let [below, above] = chart.bound[i];
                let side = if rng.random_bool(0.5) { above } else { -below };
                side * if rng.random_bool(0.8) {
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
        checked > 5000 && bounded > 500 && wide >= 3,
        "{checked} remainders, {bounded} moves checked, {wide} wide boxes bounded"
    );
}

/// A scaled norm bounds the spectral radius where the plain one cannot: a matrix mixing scales
/// (entries `s / 2` and `1 / 2s` off the diagonal) has radius 1/2 whatever `s`, its plain norm
/// `s / 2`.
#[test]
fn the_scaled_norm_bounds_the_spectral_radius_across_scales() {
    for s in [1.0, 10.0, 1e3] {
        let mut a = [[0.0; 6]; 6];
        a[0][1] = 0.5 * s;
        a[1][0] = 0.5 / s;
        a[2][2] = 0.25;
        let (sigma, v) = scaled_norm(&a);
        assert!((0.5..0.5 + 1e-9).contains(&sigma), "σ = {sigma} at s = {s}");
        assert!(v.iter().all(|w| *w > 0.0));
    }
    let mut nan = [[0.0; 6]; 6];
    nan[3][4] = f64::NAN;
    assert_eq!(scaled_norm(&nan).0, f64::INFINITY);
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
