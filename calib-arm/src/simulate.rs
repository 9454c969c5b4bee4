//! Simulated tracker data: a true geometry near the nominal, random configurations within the
//! joint limits, readings within the error bounds of the true values (uniform), optional
//! outliers.

use crate::model::tracked_point;
use crate::params::{self, Unit};
use crate::robot::Arm;
use crate::units::{deg_to_rad, to_rad};
use calib_core::Interval;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Half-widths of the measurement errors: every true value lies within ± these of its reading.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Uncertainty {
    /// Joint readings, degrees.
    pub joint_deg: f64,
    /// Tracked coordinates, mm.
    pub pos: f64,
}

impl Uncertainty {
    /// The laser tracker and encoders: ±0.01 mm per coordinate, ±0.001°.
    pub const TRACKER: Uncertainty = Uncertainty {
        joint_deg: 0.001,
        pos: 0.01,
    };
}

/// One measured configuration: joint readings (degrees) and the tracked point (mm).
#[derive(Clone, Debug, PartialEq)]
pub struct Reading {
    /// `q_1..q_N` in degrees.
    pub joints_deg: Vec<f64>,
    /// `px, py, pz` in mm, tracker frame.
    pub point: [f64; 3],
}

/// A simulated data set.
#[derive(Clone, Debug, PartialEq)]
pub struct Simulation {
    /// The true parameters in model order (degrees and mm).
    pub truth: Vec<f64>,
    /// The readings (with noise and outliers).
    pub readings: Vec<Reading>,
    /// The error bounds the noise respects.
    pub uncertainty: Uncertainty,
}

/// The joint range of the simulated configurations (degrees).
pub const JOINT_LIMIT_DEG: f64 = 170.0;

/// Simulates `configs` configurations of `arm`: the truth is the nominal plus up to `0.8` of each
/// prior half-width (uniform), the joints uniform within ±[`JOINT_LIMIT_DEG`], the noise uniform
/// within `noise_scale ×` the error bounds; `outliers` moves the tracked point of configuration
/// `k` (0-based) by `delta` mm in a random direction.
pub fn simulate(
    arm: &Arm,
    configs: usize,
    seed: u64,
    uncertainty: Uncertainty,
    noise_scale: f64,
    outliers: &[(usize, f64)],
) -> Simulation {
    let mut rng = StdRng::seed_from_u64(seed);
    let truth: Vec<f64> = arm
        .nominal()
        .iter()
        .zip(arm.radius())
        .map(|(v, r)| v + rng.random_range(-0.8..=0.8) * r)
        .collect();
    let units = params::names(arm.joints.len());
    let truth_model: Vec<f64> = truth
        .iter()
        .zip(&units)
        .map(|(v, (_, u))| if *u == Unit::Deg { to_rad(*v) } else { *v })
        .collect();
    let mut readings = Vec::with_capacity(configs);
    for k in 0..configs {
        let q: Vec<f64> = (0..arm.joints.len())
            .map(|_| rng.random_range(-JOINT_LIMIT_DEG..=JOINT_LIMIT_DEG))
            .collect();
        let q_rad: Vec<f64> = q.iter().map(|v| to_rad(*v)).collect();
        let p = tracked_point(&truth_model, &q_rad).expect("3 to 7 joints");
        let mut noise = |r: f64| rng.random_range(-1.0..=1.0) * r * noise_scale;
        let joints_deg = q.iter().map(|v| v + noise(uncertainty.joint_deg)).collect();
        let mut point = p.map(|v| v + noise(uncertainty.pos));
        for &(_, delta) in outliers.iter().filter(|(c, _)| *c == k) {
            let dir = random_direction(&mut rng);
            for i in 0..3 {
                point[i] += delta * dir[i];
            }
        }
        readings.push(Reading { joints_deg, point });
    }
    Simulation {
        truth,
        readings,
        uncertainty,
    }
}

fn random_direction(rng: &mut StdRng) -> [f64; 3] {
    loop {
        let v: [f64; 3] = core::array::from_fn(|_| rng.random_range(-1.0..=1.0));
        let n = v.iter().map(|c| c * c).sum::<f64>().sqrt();
        if n > 0.1 && n <= 1.0 {
            return v.map(|c| c / n);
        }
    }
}

/// The measurement box of a reading in model units, for a model of `NM - 3` joints: `q_i ±
/// joint_deg` in radians (enclosed outward), joints the reading does not have (an arm padded with
/// identity joints) exactly 0, then `p ± pos` in mm. `None` when the reading has more joints than
/// the model.
pub fn measurement_box<const NM: usize>(r: &Reading, u: &Uncertainty) -> Option<[Interval; NM]> {
    let model_joints = NM.checked_sub(3)?;
    let n = r.joints_deg.len();
    if n > model_joints {
        return None;
    }
    Some(core::array::from_fn(|i| {
        if i < n {
            deg_to_rad(Interval::mid_rad(r.joints_deg[i], u.joint_deg))
        } else if i < model_joints {
            Interval::ZERO
        } else {
            Interval::mid_rad(r.point[i - model_joints], u.pos)
        }
    }))
}
