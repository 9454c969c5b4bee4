//! The arm's second and third derivatives (`#[interval_model(curvature)]` on the padded model) and
//! the second-order certificate on simulated arms with the real data's priors: derivatives agree
//! with finite differences of the generated Jacobians, and no combination of the residuals, however
//! weighted, is proved positive over a box that holds the truth.

use calib_arm::certification::{padded_box, NM, NX};
use calib_arm::simulate::{measurement_box, simulate, Uncertainty};
use calib_arm::Arm7Point;
use calib_core::chebyshev_weights;
use calib_core::combination_lower_bound;
use calib_core::{smallest_scale, Curvature, Interval, VectorModel};

/// Every parameter of the built-in arm that is free, then its six joint readings.
fn symbols(x0: &[Interval; NX]) -> Vec<usize> {
    (0..NX)
        .filter(|&j| x0[j].rad() > 0.0)
        .chain((0..6).map(|i| NX + i))
        .collect()
}

#[test]
fn the_arms_second_derivatives_match_finite_differences() {
    let arm = calib_arm::builtin_arm();
    let x0 = padded_box(&arm);
    let sim = simulate(&arm, 3, 21, Uncertainty::TRACKER, 1.0, &[]);
    let m: Vec<[f64; NM]> = sim
        .readings
        .iter()
        .filter_map(|r| measurement_box::<NM>(r, &sim.uncertainty))
        .map(|b| b.map(|v| v.mid()))
        .collect();
    let x: [f64; NX] = x0.map(|v| v.mid());
    let symbols = symbols(&x0);
    let n = symbols.len();
    let h = Arm7Point.second_derivatives(&x, &m[0], &symbols).unwrap();
    let gradient = |x: &[f64; NX], m: &[f64; NM]| -> Vec<Vec<f64>> {
        Arm7Point
            .evaluate_rows(x, m)
            .iter()
            .map(|e| {
                symbols
                    .iter()
                    .map(|&s| if s < NX { e.dx[s] } else { e.dm[s - NX] })
                    .collect()
            })
            .collect()
    };
    for (b, &s) in symbols.iter().enumerate() {
        let step = 1e-6;
        let (mut xp, mut xm, mut mp, mut mm) = (x, x, m[0], m[0]);
        if s < NX {
            xp[s] += step;
            xm[s] -= step;
        } else {
            mp[s - NX] += step;
            mm[s - NX] -= step;
        }
        let (gp, gm) = (gradient(&xp, &mp), gradient(&xm, &mm));
        for r in 0..3 {
            for a in 0..n {
                let fd = (gp[r][a] - gm[r][a]) / (2.0 * step);
                let e = h[r * n * n + a * n + b];
                assert!(
                    (e.mid() - fd).abs() <= 1e-4 * fd.abs().max(1.0),
                    "row {r}, symbols {} and {s}: {} against {fd}",
                    symbols[a],
                    e.mid()
                );
            }
        }
    }
}

/// Simulated arms whose readings hold the truth: the combination with the Chebyshev weights of
/// bounds 10% too tight (the weights a proof near the threshold would use), and with their
/// negation, evaluated over the true bounds, is never proved positive.
#[test]
fn no_combination_excludes_the_truth_of_a_simulated_arm() {
    let arm = calib_arm::builtin_arm();
    let x0 = padded_box(&arm);
    for seed in [3, 8] {
        let sim = simulate(&arm, 20, seed, Uncertainty::TRACKER, 1.0, &[]);
        let boxes_at = |f: f64| -> Vec<[Interval; NM]> {
            let u = Uncertainty {
                pos: f * sim.uncertainty.pos,
                joint_deg: f * sim.uncertainty.joint_deg,
            };
            sim.readings
                .iter()
                .filter_map(|r| measurement_box(r, &u))
                .collect()
        };
        let (truth_boxes, tight) = (boxes_at(1.0), boxes_at(0.9));
        let fit = smallest_scale(&Arm7Point, &x0, &tight, &[true; NM]);
        let weights = chebyshev_weights(&Arm7Point, &x0, &tight, &[true; NM], &fit.point).unwrap();
        for w in [
            weights.clone(),
            weights.iter().map(|c| c.map(|v| -v)).collect(),
        ] {
            let bound =
                combination_lower_bound(&Arm7Point, &Arm7Point, &x0, &truth_boxes, &fit.point, &w)
                    .unwrap();
            assert!(
                bound <= 0.0,
                "seed {seed}: {bound} > 0 with the truth inside"
            );
        }
    }
}

/// Both arm models leave the base translation and the tracked point out of the second-order
/// symbols (they enter linearly), and keep every angle and length: the UR10 with its tool frame
/// (31 free parameters, 12 measured quantities) fits within `MAX_CURVATURE_SYMBOLS`.
#[test]
fn the_linear_inputs_of_both_arm_models_are_left_out() {
    use calib_arm::pose::certification::{NM6, NX6};
    use calib_arm::pose::Arm7Pose;
    use calib_core::MAX_CURVATURE_SYMBOLS;
    // Padded indices: base_x, base_y, base_z are 35–37; the tracked point px, py, pz is 7–9.
    for j in 0..NX {
        let linear = (35..38).contains(&j);
        assert_eq!(Arm7Point.curved(j), !linear, "parameter {j}");
        assert_eq!(Arm7Pose.curved(j), !linear, "parameter {j} (pose)");
    }
    for i in 0..NM6 {
        let linear = (7..10).contains(&i);
        if i < NM {
            assert_eq!(Arm7Point.curved(NX + i), !linear, "reading {i}");
        }
        assert_eq!(Arm7Pose.curved(NX6 + i), !linear, "reading {i} (pose)");
    }
    // The tool frame's rotation is curved. The built-in arm's free parameters with a free tool
    // rotation, its six joint readings and three measured angles: within the jets' width.
    assert!((NX..NX6).all(|j| Arm7Pose.curved(j)));
    let x0 = padded_box(&calib_arm::builtin_arm());
    let parameters = (0..NX)
        .filter(|&j| x0[j].rad() > 0.0 && Arm7Pose.curved(j))
        .count()
        + 3;
    let readings = (0..6)
        .chain(NM..NM6)
        .filter(|&i| Arm7Pose.curved(NX6 + i))
        .count();
    assert_eq!(readings, 9);
    assert!(
        parameters + readings <= MAX_CURVATURE_SYMBOLS,
        "{parameters} + {readings}"
    );
}

#[test]
fn the_taylor_remainder_holds_every_sampled_remainder_of_the_tool_point() {
    use calib_pipeline::accuracy::taylor_remainder;
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};
    let arm = calib_arm::builtin_arm();
    let x0 = padded_box(&arm);
    let nominal: [f64; NX] = x0.map(|v| v.mid());
    let spread: [Interval; NX] = core::array::from_fn(|j| x0[j] - Interval::point(nominal[j]));
    let mut rng = StdRng::seed_from_u64(8);
    let curvature = Arm7Point
        .curvature()
        .expect("the arm's model has its derivatives");
    for trial in 0..6 {
        // A joint box of ±5° somewhere in the joint space (the tracked point's slots at 0).
        let mut m = [Interval::ZERO; NM];
        for v in m.iter_mut().take(6) {
            *v = Interval::mid_rad(rng.random_range(-2.5..2.5), 5f64.to_radians());
        }
        let k: [Interval; 3] =
            taylor_remainder(curvature, &nominal, &spread, &m).expect("a remainder");
        // Random geometries, and the prior's vertices along the Hessian's dominant direction
        // (signs of its leading eigenvector in the box's scale), where the remainder is largest.
        let u_mid: [f64; NM] = m.map(|b| b.mid());
        let free: Vec<usize> = (0..NX).filter(|&j| spread[j].mag() > 0.0).collect();
        let h = Arm7Point
            .second_derivatives(&nominal, &u_mid, &free)
            .expect("a Hessian");
        let n = free.len();
        let mut vertices = Vec::new();
        for r in 0..3 {
            let a = |i: usize, j: usize| {
                h[r * n * n + i * n + j].mid() * spread[free[i]].mag() * spread[free[j]].mag()
            };
            let mut v = vec![1.0; n];
            for _ in 0..50 {
                let w: Vec<f64> = (0..n)
                    .map(|i| (0..n).map(|j| a(i, j) * v[j]).sum())
                    .collect();
                let norm = w.iter().map(|x| x * x).sum::<f64>().sqrt().max(1e-300);
                v = w.iter().map(|x| x / norm).collect();
            }
            for sign in [1.0, -1.0] {
                let mut theta = nominal;
                for (i, &j) in free.iter().enumerate() {
                    theta[j] += sign * v[i].signum() * spread[j].mag();
                }
                vertices.push(theta.map(|t| t.clamp(-1e300, 1e300)));
            }
        }
        let mut largest = [0.0f64; 3];
        for s in 0..200 + vertices.len() {
            let theta: [f64; NX] = match vertices.get(s) {
                Some(v) => core::array::from_fn(|j| v[j].clamp(x0[j].inf(), x0[j].sup())),
                None => x0.map(|b| rng.random_range(b.inf()..=b.sup())),
            };
            let u: [f64; NM] = if s < vertices.len() {
                u_mid
            } else {
                m.map(|b| rng.random_range(b.inf()..=b.sup()))
            };
            let (at, base) = (
                Arm7Point.evaluate_rows(&theta, &u),
                Arm7Point.evaluate_rows(&nominal, &u),
            );
            for r in 0..3 {
                let linear: f64 = (0..NX)
                    .map(|j| base[r].dx[j] * (theta[j] - nominal[j]))
                    .sum();
                let rest = at[r].value - base[r].value - linear;
                let slack = 1e-9 * (at[r].value.abs() + 1.0);
                largest[r] = largest[r].max(rest.abs());
                assert!(
                    k[r].inf() - slack <= rest && rest <= k[r].sup() + slack,
                    "trial {trial}, row {r}: remainder {rest} outside {:?}",
                    k[r]
                );
            }
        }
        for r in 0..3 {
            assert!(
                largest[r] >= 0.1 * k[r].mag(),
                "trial {trial}, row {r}: remainders reach {} of a bound {:?}",
                largest[r],
                k[r]
            );
        }
    }
}
