//! Experiment design for a serial arm: which joint configurations to measure so that the
//! certified box of every parameter is small, by the robot-agnostic
//! [`calib_pipeline::design`] — the whole arm is one parameter group, each candidate
//! configuration adds its three scaled identification rows (tracker x, y, z).

use crate::certification::identification_rows;
use crate::model::tracked_point;
use crate::params::{self, Unit};
use crate::robot::Arm;
use crate::simulate::{Reading, Uncertainty, JOINT_LIMIT_DEG};
use crate::units::to_rad;
use crate::ArmError;
use calib_pipeline::design::{
    certified_design, greedy_design, linearized_widths, Criterion, Group,
};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// A design of joint configurations and its first-order certified widths.
#[derive(Clone, Debug, PartialEq)]
pub struct ArmDesign {
    /// The chosen configurations' joint angles (degrees).
    pub joints_deg: Vec<Vec<f64>>,
    /// A random design of the same size (the comparison).
    pub random_deg: Vec<Vec<f64>>,
    /// The free parameters (arm order) the widths are given for.
    pub free: Vec<usize>,
    /// First-order certified widths of the free parameters in the files' units: designed,
    /// random, every candidate measured.
    pub first_order: [Vec<f64>; 3],
}

/// A reading of `arm` at the nominal geometry (exact) for the joint angles `q` (degrees).
fn nominal_reading(arm: &Arm, q: &[f64]) -> Option<Reading> {
    let units = params::names(arm.joints.len());
    let x: Vec<f64> = arm
        .nominal()
        .iter()
        .zip(&units)
        .map(|(v, (_, u))| if *u == Unit::Deg { to_rad(*v) } else { *v })
        .collect();
    let q_rad: Vec<f64> = q.iter().map(|v| to_rad(*v)).collect();
    Some(Reading {
        joints_deg: q.to_vec(),
        point: tracked_point(&x, &q_rad)?,
    })
}

/// Chooses `configs` joint configurations of `arm` among `candidates` random ones (joints
/// uniform within ±[`JOINT_LIMIT_DEG`]) by `criterion` (see
/// [`calib_pipeline::design::certified_design`]). Errors: an arm the model does not take.
pub fn design_arm(
    arm: &Arm,
    u: &Uncertainty,
    configs: usize,
    candidates: usize,
    criterion: Criterion,
    seed: u64,
) -> Result<ArmDesign, ArmError> {
    let mut rng = StdRng::seed_from_u64(seed);
    let mut draw = |n: usize| -> Vec<Vec<f64>> {
        (0..n)
            .map(|_| {
                (0..arm.joints.len())
                    .map(|_| rng.random_range(-JOINT_LIMIT_DEG..=JOINT_LIMIT_DEG))
                    .collect()
            })
            .collect()
    };
    let pool = draw(candidates);
    let random = draw(configs);
    let readings: Vec<Reading> = pool
        .iter()
        .chain(&random)
        .map(|q| nominal_reading(arm, q).ok_or(ArmError::UnsupportedArm))
        .collect::<Result<_, _>>()?;
    let (free, rows) = identification_rows(arm, &readings, u)?;
    let all = Group {
        dim: free.len(),
        rows,
    };
    let candidates_only = Group {
        dim: all.dim,
        rows: all.rows[..candidates].to_vec(),
    };
    let groups = [candidates_only];
    let picked = match criterion {
        Criterion::Certified => certified_design(&groups, &[], configs, 2, &|| {}).0,
        Criterion::DOptimal => greedy_design(&groups, &[], configs, criterion, &|| {}),
    };
    let radius = arm.radius();
    let in_file_units =
        |w: Vec<f64>| -> Vec<f64> { w.iter().zip(&free).map(|(w, &p)| w * radius[p]).collect() };
    let random_rows: Vec<usize> = (candidates..candidates + configs).collect();
    let every: Vec<usize> = (0..candidates).collect();
    Ok(ArmDesign {
        joints_deg: picked.iter().map(|&c| pool[c].clone()).collect(),
        random_deg: random,
        free: free.clone(),
        first_order: [
            in_file_units(linearized_widths(&all, &picked)),
            in_file_units(linearized_widths(&all, &random_rows)),
            in_file_units(linearized_widths(&all, &every)),
        ],
    })
}
