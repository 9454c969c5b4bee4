//! The Gough leg residuals (paper eq. 3), axis–angle and Rodrigues: generated evaluators enclose
//! point values over random boxes around realistic configurations, their Jacobians agree with
//! finite differences and dual numbers, and the axis–angle residual is the Rodrigues residual of
//! the normalised axis's Rodrigues vector (an independent formula: `calib_gough::geometry`).

use crate::core_support as support;

use calib_core::{Dual, Interval, Model};
use calib_gough::geometry::{rotate, Pose};
use calib_gough::{gough_leg, gough_leg_rodrigues, GoughLeg, GoughLegRodrigues, LegModel};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use support::*;

const TABLE_I: [f64; 7] = [-9.7, 9.1, 0.0, -3.0, 7.3, 0.0, 52.2496];

/// A random axis–angle configuration: position, an axis of length within 1% of 1, an angle of up
/// to ±15°, leg reading.
fn axis_angle(rng: &mut StdRng) -> [f64; 8] {
    let v: [f64; 3] = core::array::from_fn(|_| rng.random_range(-1.0..1.0));
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(0.1);
    let s = rng.random_range(0.99..1.01) / n;
    [
        rng.random_range(-5.0..5.0),
        rng.random_range(-5.0..5.0),
        rng.random_range(55.0..65.0),
        v[0] * s,
        v[1] * s,
        v[2] * s,
        rng.random_range(-15.0..15.0),
        rng.random_range(3.0..13.0),
    ]
}

/// A random Rodrigues configuration: position, Rodrigues vector of an up-to-15° rotation, 0 in
/// the (unread) angle slot, leg reading.
fn rodrigues(rng: &mut StdRng) -> [f64; 8] {
    let q: [f64; 3] = core::array::from_fn(|_| rng.random_range(-0.13..0.13));
    [
        rng.random_range(-5.0..5.0),
        rng.random_range(-5.0..5.0),
        rng.random_range(55.0..65.0),
        q[0],
        q[1],
        q[2],
        0.0,
        rng.random_range(3.0..13.0),
    ]
}

#[test]
fn interval_evaluators_enclose_point_values() {
    let mut rng = StdRng::seed_from_u64(21);
    for _ in 0..20 {
        let m = axis_angle(&mut rng);
        // The paper's bounds (and 20 times them), then wide boxes: the enclosure must hold
        // however loose it gets (the axis box stays clear of 0).
        for (x_rad, m_rad, boxes) in [
            (0.1, [5e-4, 5e-4, 5e-4, 5e-6, 5e-6, 5e-6, 1e-3, 5e-4], 30),
            (0.1, [1e-2, 1e-2, 1e-2, 1e-4, 1e-4, 1e-4, 2e-2, 1e-2], 30),
            (3.0, [1.0, 1.0, 1.0, 0.2, 0.2, 0.2, 20.0, 1.0], 10),
        ] {
            assert_encloses(
                &GoughLeg,
                &mut rng,
                &TABLE_I,
                &[x_rad; 7],
                &m,
                &m_rad,
                boxes,
            );
            assert_encloses(
                &LegModel::AxisAngle,
                &mut rng,
                &TABLE_I,
                &[x_rad; 7],
                &m,
                &m_rad,
                boxes / 3,
            );
        }
        let m = rodrigues(&mut rng);
        for (x_rad, m_rad, boxes) in [
            (0.1, [5e-4, 5e-4, 5e-4, 1e-4, 1e-4, 1e-4, 0.0, 5e-4], 30),
            (3.0, [1.0, 1.0, 1.0, 0.1, 0.1, 0.1, 0.0, 1.0], 10),
        ] {
            assert_encloses(
                &GoughLegRodrigues,
                &mut rng,
                &TABLE_I,
                &[x_rad; 7],
                &m,
                &m_rad,
                boxes,
            );
            assert_encloses(
                &LegModel::Rodrigues,
                &mut rng,
                &TABLE_I,
                &[x_rad; 7],
                &m,
                &m_rad,
                boxes / 3,
            );
        }
    }
}

#[test]
fn jacobians_match_finite_differences_and_dual_numbers() {
    let mut rng = StdRng::seed_from_u64(22);
    for _ in 0..300 {
        let x: [f64; 7] = core::array::from_fn(|i| TABLE_I[i] + rng.random_range(-0.5..0.5));
        let m = axis_angle(&mut rng);
        assert_jacobians_match_finite_differences(&GoughLeg, &x, &m);
        assert_jacobians_match_dual(&GoughLeg, gough_leg::<Dual<15>>, &x, &m);
        let m = rodrigues(&mut rng);
        assert_jacobians_match_finite_differences(&GoughLegRodrigues, &x, &m);
        assert_jacobians_match_dual(&GoughLegRodrigues, gough_leg_rodrigues::<Dual<15>>, &x, &m);
        assert_eq!(GoughLegRodrigues.jacobian_m(&x, &m)[6], 0.0);
    }
}

#[test]
fn axis_angle_residual_is_the_rotation_about_the_normalised_axis() {
    let mut rng = StdRng::seed_from_u64(23);
    for _ in 0..300 {
        let x: [f64; 7] = core::array::from_fn(|i| TABLE_I[i] + rng.random_range(-0.5..0.5));
        let m = axis_angle(&mut rng);
        let u = [m[3], m[4], m[5]];
        let n = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
        let pose = Pose {
            p: [m[0], m[1], m[2]],
            axis: u.map(|v| v / n),
            angle_deg: m[6],
        };
        let rb = rotate(&pose.rodrigues(), &[x[3], x[4], x[5]]);
        let d: [f64; 3] = core::array::from_fn(|i| pose.p[i] + rb[i] - x[i]);
        let reference = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - (m[7] + x[6]).powi(2);
        let f = GoughLeg.residual(&x, &m);
        assert!(
            (f - reference).abs() < 1e-9 * (1.0 + reference.abs()),
            "{f} vs {reference}"
        );
        // A longer or shorter axis is the same direction: the same residual.
        let mut scaled = m;
        for v in &mut scaled[3..6] {
            *v *= 1.7;
        }
        assert!((GoughLeg.residual(&x, &scaled) - f).abs() < 1e-9 * (1.0 + f.abs()));
        // And the Rodrigues residual of the same rotation agrees.
        let q = pose.rodrigues();
        let mr = [m[0], m[1], m[2], q[0], q[1], q[2], 0.0, m[7]];
        assert!((GoughLegRodrigues.residual(&x, &mr) - f).abs() < 1e-9 * (1.0 + f.abs()));
    }
}

#[test]
fn the_radians_per_degree_enclosure_holds_pi_over_180() {
    // At 180° about z, a platform point b maps to -b (up to the enclosure of π/180 in cos/sin).
    let x = [0.0, 0.0, 0.0, 1.0, 2.0, 0.0, 0.0];
    let m = [0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 180.0, 0.0];
    let f = GoughLeg.residual_interval(&x.map(Interval::point), &m.map(Interval::point));
    assert!(f.contains(5.0) && f.wid() < 1e-12, "{f}");
    let m = [0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 90.0, 0.0];
    let e = GoughLeg.evaluate(&x, &m);
    // R b = (-2, 1, 0): |R b|^2 = 5; d/dθ moves it tangentially (no change of the norm).
    assert!((e.value - 5.0).abs() < 1e-12);
}

#[test]
fn known_derivatives() {
    // df/da = -2 (P + R b - a), df/dl = df/dL = -2 (L + l): check at angle 0 (R = identity).
    let x = TABLE_I;
    let m = [1.0, 2.0, 60.0, 0.0, 0.0, 1.0, 0.0, 8.0];
    let e: [f64; 3] = core::array::from_fn(|i| m[i] + x[3 + i] - x[i]);
    for model in [LegModel::AxisAngle, LegModel::Rodrigues] {
        let m = match model {
            LegModel::AxisAngle => m,
            LegModel::Rodrigues => [1.0, 2.0, 60.0, 0.0, 0.0, 0.0, 0.0, 8.0],
        };
        let p = model.evaluate(&x, &m);
        for (i, ei) in e.iter().enumerate() {
            assert!((p.dx[i] + 2.0 * ei).abs() < 1e-12);
            assert!((p.dx[3 + i] - 2.0 * ei).abs() < 1e-12);
        }
        assert!((p.dx[6] + 2.0 * (m[7] + x[6])).abs() < 1e-12);
        assert_eq!(p.dx[6], p.dm[7]);
        let iv = model.residual_interval(&x.map(Interval::point), &m.map(Interval::point));
        assert!(iv.contains(p.value) && iv.wid() < 1e-9);
    }
}
