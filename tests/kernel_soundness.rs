//! Soundness of the certified kernel over many simulated Gough-leg problems: the truth is inside
//! every result box and the verdict is never `Empty` when the data are consistent; inconsistent data
//! are proved `Empty`; `Consistent` witnesses are re-checked independently; exact data converge.
#![allow(clippy::needless_range_loop)] // indices follow the paper (legs, parameters)

use calib_core::LpEngine;
use calib_core::{
    certify, is_consistent_by_corners, pave, sweep, Interval, Model, Relaxation, Settings, Status,
};
use calib_gough::geometry::Pose;
use calib_gough::{builtin_hexapod, leg_boxes, simulate, GoughLeg, GoughLegRodrigues, Uncertainty};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

use crate::support;

use support::{contains, random_problem, x0_of};

#[test]
fn truth_is_inside_every_certified_box_of_random_problems() {
    let mut consistent = 0;
    for seed in 0..16 {
        let sim = random_problem(seed);
        for leg in [0, 3] {
            let boxes = leg_boxes(&sim.measured, &sim.uncertainty, leg);
            let truth = sim.truth[leg].params();
            let relaxation =
                [Relaxation::Krawczyk, Relaxation::Corners, Relaxation::Both][(seed % 3) as usize];
            let r = certify(
                &GoughLeg,
                &x0_of(&sim, leg, 0.1),
                &boxes,
                &Settings::default().with_relaxation(relaxation),
            );
            assert_ne!(
                r.status,
                Status::Empty,
                "seed {seed} leg {leg}: consistent data proved empty"
            );
            assert!(
                contains(&r.outer, &truth),
                "seed {seed} leg {leg}: truth {truth:?} outside {:?}",
                r.outer
            );
            if let Some(w) = r.witness {
                consistent += 1;
                assert!(contains(&r.outer, &w));
                assert!(
                    is_consistent_by_corners(&GoughLeg, &w, &boxes),
                    "seed {seed} leg {leg}: witness fails the re-check"
                );
                let inner = r.inner.expect("inner bounds with a witness");
                for j in 0..7 {
                    assert!(
                        inner[j].is_subset_of(r.outer[j]),
                        "seed {seed} leg {leg} param {j}: inner {} outside outer {} (x0 {})",
                        inner[j],
                        r.outer[j],
                        x0_of(&sim, leg, 0.1)[j]
                    );
                }
            }
        }
    }
    assert!(
        consistent >= 16,
        "only {consistent} of 32 problems certified consistent"
    );
}

#[test]
fn clarabel_backend_is_sound_too() {
    for seed in 100..104 {
        let sim = random_problem(seed);
        let boxes = leg_boxes(&sim.measured, &sim.uncertainty, 1);
        let s = Settings::default().with_lp(LpEngine::Clarabel);
        let r = certify(&GoughLeg, &x0_of(&sim, 1, 0.1), &boxes, &s);
        assert_ne!(r.status, Status::Empty);
        assert!(contains(&r.outer, &sim.truth[1].params()));
    }
}

#[test]
fn zero_width_and_ill_conditioned_measurements_stay_sound() {
    let truth = builtin_hexapod();
    // Zero-width position and orientation boxes (the leg reading keeps 1e-9 to absorb the rounding
    // of the simulated readings).
    let sim = simulate(&truth, 12, 7, Uncertainty::PAPER, 0.0, 0.1);
    for leg in 0..6 {
        let boxes: Vec<[Interval; 8]> = sim
            .poses
            .iter()
            .zip(&sim.exact_lengths)
            .map(|(pose, lengths)| {
                let mut m = [
                    pose.p[0],
                    pose.p[1],
                    pose.p[2],
                    pose.axis[0],
                    pose.axis[1],
                    pose.axis[2],
                    pose.angle_deg,
                    lengths[leg],
                ]
                .map(Interval::point);
                m[7] = Interval::mid_rad(lengths[leg], 1e-9);
                m
            })
            .collect();
        let r = certify(
            &GoughLeg,
            &x0_of(&sim, leg, 0.1),
            &boxes,
            &Settings::default(),
        );
        assert_ne!(r.status, Status::Empty);
        assert!(contains(&r.outer, &truth[leg].params()), "leg {leg}");
    }
    // Nearly degenerate: all configurations within a millimetre and 0.01° of one pose.
    let mut rng = StdRng::seed_from_u64(8);
    let base = Pose {
        p: [1.0, -2.0, 60.0],
        axis: [0.0, 0.6, 0.8],
        angle_deg: 5.0,
    };
    let poses: Vec<Pose> = (0..15)
        .map(|_| Pose {
            p: base.p.map(|v| v + rng.random_range(-0.05..0.05)),
            axis: base.axis,
            angle_deg: base.angle_deg + rng.random_range(-0.01..0.01),
        })
        .collect();
    let u = Uncertainty::PAPER;
    for leg in 0..6 {
        // Rodrigues data (the Rodrigues residual, its unread angle slot the point 0).
        let boxes: Vec<[Interval; 8]> = poses
            .iter()
            .map(|p| {
                let q = p.rodrigues();
                let len = calib_gough::leg_reading(&truth[leg], p);
                [
                    Interval::mid_rad(p.p[0], u.pos),
                    Interval::mid_rad(p.p[1], u.pos),
                    Interval::mid_rad(p.p[2], u.pos),
                    Interval::mid_rad(q[0], 1e-6),
                    Interval::mid_rad(q[1], 1e-6),
                    Interval::mid_rad(q[2], 1e-6),
                    Interval::ZERO,
                    Interval::mid_rad(len, u.len),
                ]
            })
            .collect();
        let x0 = truth[leg]
            .params()
            .map(|v| Interval::new(v - 0.07, v + 0.13));
        let r = certify(&GoughLegRodrigues, &x0, &boxes, &Settings::default());
        assert_ne!(r.status, Status::Empty);
        assert!(contains(&r.outer, &truth[leg].params()));
    }
}

#[test]
fn inconsistent_data_are_proved_empty() {
    let truth = builtin_hexapod();
    let mut sim = simulate(&truth, 21, 3, Uncertainty::PAPER, 1.0, 0.1);
    // Leg 2's reading in configuration 5 moved 2 mm outside its box.
    sim.measured[5].lengths[1] += 0.2;
    let boxes = leg_boxes(&sim.measured, &sim.uncertainty, 1);
    let r = certify(
        &GoughLeg,
        &x0_of(&sim, 1, 0.1),
        &boxes,
        &Settings::default(),
    );
    assert_eq!(r.status, Status::Empty);
    assert!(r.emptiness.is_some() && r.outer.iter().all(|v| v.is_empty()));
    // The other legs are untouched and stay certified.
    let boxes = leg_boxes(&sim.measured, &sim.uncertainty, 0);
    let r = certify(
        &GoughLeg,
        &x0_of(&sim, 0, 0.1),
        &boxes,
        &Settings::default(),
    );
    assert_eq!(r.status, Status::Consistent);
}

#[test]
fn exact_data_converge_to_the_truth() {
    let truth = builtin_hexapod();
    let exact = Uncertainty::uniform(1e-9);
    for seed in [1, 2, 3] {
        let sim = simulate(&truth, 21, seed, exact, 0.0, 0.1);
        for leg in 0..6 {
            let boxes = leg_boxes(&sim.measured, &exact, leg);
            let r = certify(
                &GoughLeg,
                &x0_of(&sim, leg, 0.1),
                &boxes,
                &Settings::default(),
            );
            assert!(contains(&r.outer, &truth[leg].params()));
            let worst = r.outer.iter().map(|v| v.rad()).fold(0.0, f64::max);
            assert!(
                worst <= 1e-5,
                "seed {seed} leg {}: radius {worst:e}",
                leg + 1
            );
            assert_eq!(r.status, Status::Consistent);
        }
    }
}

#[test]
fn sweep_and_paver_keep_the_truth() {
    let truth = builtin_hexapod();
    let sim = simulate(&truth, 21, 4, Uncertainty::PAPER, 1.0, 0.1);
    let boxes = leg_boxes(&sim.measured, &sim.uncertainty, 0);
    let t = truth[0].params();
    let settings = Settings {
        sweep_steps: 2,
        ..Settings::default()
    };
    let s = sweep(&GoughLeg, &x0_of(&sim, 0, 0.1), &boxes, &settings);
    assert!(
        s.boxes.iter().any(|b| contains(b, &t)),
        "no sweep box holds the truth"
    );
    let hull = s.hull.expect("consistent data");
    assert!(contains(&hull, &t));
    assert_eq!(s.volumes.len(), 5);
    assert!(
        s.volumes.windows(2).all(|w| w[1] <= w[0] * (1.0 + 1e-12)),
        "{:?}",
        s.volumes
    );
    let x1 = certify(&GoughLeg, &x0_of(&sim, 0, 0.1), &boxes, &settings).outer;
    for j in 0..7 {
        assert!(hull[j].is_subset_of(x1[j]));
    }
    let p = pave(&GoughLeg, &x0_of(&sim, 0, 0.1), &boxes, &settings, 0.3, 64);
    assert!(
        p.boxes.iter().any(|b| contains(b, &t)),
        "no paving box holds the truth"
    );
    assert!(p.inner_volume <= p.outer_volume);
    // Inconsistent data: every sweep box is proved empty.
    let mut bad = boxes.clone();
    bad[3][6] += Interval::point(0.3);
    let s = sweep(&GoughLeg, &x0_of(&sim, 0, 0.1), &bad, &settings);
    assert!(s.hull.is_none() && s.boxes.is_empty());
}

#[test]
fn certified_boxes_are_at_least_as_tight_as_the_initial_box() {
    let sim = random_problem(42);
    let boxes = leg_boxes(&sim.measured, &sim.uncertainty, 2);
    let x0 = x0_of(&sim, 2, 0.1);
    let r = certify(&GoughLeg, &x0, &boxes, &Settings::default());
    for j in 0..7 {
        assert!(r.outer[j].is_subset_of(x0[j]));
    }
    // The residual at the witness is small compared with the initial spread.
    if let Some(w) = r.witness {
        let m = boxes[0].map(|v| v.mid());
        assert!(GoughLeg.residual(&w, &m).abs() < 1.0);
    }
}

#[test]
fn unbounded_initial_boxes_are_kept_whole_without_panicking() {
    let sim = simulate(&builtin_hexapod(), 9, 12, Uncertainty::PAPER, 1.0, 0.1);
    let boxes = leg_boxes(&sim.measured, &sim.uncertainty, 0);
    let mut x0 = x0_of(&sim, 0, 0.1);
    x0[6] = Interval::new(0.0, f64::INFINITY);
    let r = certify(&GoughLeg, &x0, &boxes, &Settings::default());
    assert_eq!(r.status, Status::Undecided);
    assert_eq!(r.outer, x0);
    let s = sweep(&GoughLeg, &x0, &boxes, &Settings::default());
    assert_eq!(s.hull, Some(x0));
}

#[test]
fn sweep_and_paver_keep_the_truth_over_random_problems() {
    for seed in 200..204 {
        let sim = random_problem(seed);
        let leg = (seed % 6) as usize;
        let boxes = leg_boxes(&sim.measured, &sim.uncertainty, leg);
        let t = sim.truth[leg].params();
        let x0 = x0_of(&sim, leg, 0.1);
        let settings = Settings {
            sweep_steps: 1,
            ..Settings::default()
        };
        let s = sweep(&GoughLeg, &x0, &boxes, &settings);
        assert!(
            s.boxes.iter().any(|b| contains(b, &t)),
            "seed {seed}: sweep lost the truth"
        );
        let p = pave(&GoughLeg, &x0, &boxes, &settings, 0.5, 40);
        assert!(
            p.boxes.iter().any(|b| contains(b, &t)),
            "seed {seed}: paver lost the truth"
        );
        assert!(p.hull.is_some_and(|h| contains(&h, &t)));
    }
}
