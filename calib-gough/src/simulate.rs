//! Simulated calibration data for a built-in hexapod (paper Section V).

use crate::geometry::{leg_reading, Leg, Pose};
use crate::measurement::{Configuration, Orientation, Uncertainty};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// The built-in hexapod: leg 1 is the paper's Table I, the other legs those of `sample21`.
pub fn builtin_hexapod() -> Vec<Leg> {
    vec![
        Leg {
            a: [-9.7, 9.1, 0.0],
            b: [-3.0, 7.3, 0.0],
            l: 52.2496,
        },
        Leg {
            a: [-9.669, -9.122, 0.0],
            b: [-3.014, -7.279, 0.0],
            l: 52.3871,
        },
        Leg {
            a: [-3.0478, -12.9064, 0.0],
            b: [-4.795, -6.2591, 0.0],
            l: 52.1183,
        },
        Leg {
            a: [12.7568, -3.8374, 0.0],
            b: [7.814, 1.0279, 0.0],
            l: 52.2959,
        },
        Leg {
            a: [12.6928, 3.8414, 0.0],
            b: [7.841, -1.0359, 0.0],
            l: 52.1837,
        },
        Leg {
            a: [-3.0188, 12.9154, 0.0],
            b: [-4.845, 6.2551, 0.0],
            l: 52.3312,
        },
    ]
}

/// A simulated data set: truth, nominal geometry, exact poses and readings, measurements.
#[derive(Clone, Debug, PartialEq)]
pub struct Simulation {
    /// The true legs.
    pub truth: Vec<Leg>,
    /// The nominal legs: truth perturbed uniformly within ± `perturbation`.
    pub nominal: Vec<Leg>,
    /// The exact poses.
    pub poses: Vec<Pose>,
    /// The exact leg readings, per configuration and leg.
    pub exact_lengths: Vec<Vec<f64>>,
    /// The measurements: exact values plus uniform noise within `noise_scale` × the half-widths.
    pub measured: Vec<Configuration>,
    /// The half-widths the measurements are declared with.
    pub uncertainty: Uncertainty,
}

/// A random pose in a realistic workspace: position within ± 5 cm horizontally and 55–65 cm high,
/// rotation up to 15° about a random axis.
pub fn random_pose(rng: &mut StdRng) -> Pose {
    let axis = loop {
        let v: [f64; 3] = core::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if n > 0.2 && n <= 1.0 {
            break v.map(|c| c / n);
        }
    };
    Pose {
        p: [
            rng.random_range(-5.0..5.0),
            rng.random_range(-5.0..5.0),
            rng.random_range(55.0..65.0),
        ],
        axis,
        angle_deg: rng.random_range(0.5..15.0),
    }
}

/// Simulates `configs` configurations of `truth` (paper Section V): exact readings from the inverse
/// kinematics, then measurements with uniform noise within `noise_scale × uncertainty`, and a
/// nominal geometry within ± `perturbation` of the truth (strictly inside, so that nominal ±
/// `perturbation` contains the truth).
pub fn simulate(
    truth: &[Leg],
    configs: usize,
    seed: u64,
    uncertainty: Uncertainty,
    noise_scale: f64,
    perturbation: f64,
) -> Simulation {
    let mut rng = StdRng::seed_from_u64(seed);
    let inside = perturbation * (1.0 - 1e-9);
    let nominal = truth
        .iter()
        .map(|leg| {
            let x = leg.params().map(|v| v + rng.random_range(-inside..=inside));
            Leg::from_params(&x)
        })
        .collect();
    let mut poses = Vec::with_capacity(configs);
    let mut exact_lengths = Vec::with_capacity(configs);
    let mut measured = Vec::with_capacity(configs);
    let mut noise = |h: f64| rng.random_range(-1.0..=1.0) * h * noise_scale;
    let mut pose_rng = StdRng::seed_from_u64(seed.wrapping_add(0x5eed));
    for _ in 0..configs {
        let pose = random_pose(&mut pose_rng);
        let lengths: Vec<f64> = truth.iter().map(|leg| leg_reading(leg, &pose)).collect();
        let noisy = Configuration {
            p: pose.p.map(|v| v + noise(uncertainty.pos)),
            orientation: Orientation::AxisAngle {
                axis: pose.axis.map(|v| v + noise(uncertainty.axis)),
                angle_deg: pose.angle_deg + noise(uncertainty.angle_deg),
            },
            lengths: lengths.iter().map(|v| v + noise(uncertainty.len)).collect(),
        };
        poses.push(pose);
        exact_lengths.push(lengths);
        measured.push(noisy);
    }
    Simulation {
        truth: truth.to_vec(),
        nominal,
        poses,
        exact_lengths,
        measured,
        uncertainty,
    }
}
