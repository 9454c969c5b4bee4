//! Experiment design on the arm (the robot-agnostic `calib_pipeline::design` with the arm's
//! identification rows): designed joint configurations give narrower first-order certified widths
//! than random ones of the same number, the widths never exceed the prior, and measuring every
//! candidate bounds every design.

use calib_arm::design::design_arm;
use calib_arm::simulate::{Uncertainty, JOINT_LIMIT_DEG};
use calib_pipeline::design::Criterion;

/// Random candidate configurations the designs choose 12 from.
const CANDIDATES: usize = 110;

fn geometric_mean(w: &[f64]) -> f64 {
    (w.iter().map(|v| v.ln()).sum::<f64>() / w.len() as f64).exp()
}

#[test]
fn designed_configurations_beat_random_ones_to_first_order() {
    let arm = calib_arm::builtin_arm();
    let prior = arm.radius();
    // The D-optimal design once: checked on its own, and as the certified criterion's fallback.
    let d_optimal = design_arm(
        &arm,
        &Uncertainty::TRACKER,
        12,
        CANDIDATES,
        Criterion::DOptimal,
        3,
    )
    .unwrap();
    for criterion in [Criterion::Certified, Criterion::DOptimal] {
        let certified;
        let d = match criterion {
            Criterion::Certified => {
                certified =
                    design_arm(&arm, &Uncertainty::TRACKER, 12, CANDIDATES, criterion, 3).unwrap();
                &certified
            }
            Criterion::DOptimal => &d_optimal,
        };
        assert_eq!(d.joints_deg.len(), 12);
        assert!(d
            .joints_deg
            .iter()
            .flatten()
            .all(|q| q.abs() <= JOINT_LIMIT_DEG));
        let [designed, random, every] = &d.first_order;
        for (k, &p) in d.free.iter().enumerate() {
            assert!(designed[k] <= 2.0 * prior[p] * (1.0 + 1e-9), "{p}");
            assert!(every[k] <= designed[k] * (1.0 + 1e-9), "{p}");
        }
        let (gd, gr) = (geometric_mean(designed), geometric_mean(random));
        println!("{criterion:?}: first-order geometric mean designed {gd:.5}, random {gr:.5}, every candidate {:.5}", geometric_mean(every));
        assert!(gd < 0.8 * gr, "{criterion:?}: designed {gd} random {gr}");
        if criterion == Criterion::Certified {
            // The certified criterion keeps the better of its greedy design and the D-optimal one.
            assert!(gd <= geometric_mean(&d_optimal.first_order[0]) * (1.0 + 1e-12));
        }
    }
}
