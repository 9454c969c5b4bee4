//! What the studies on the real UR10 share (`compliance_study`, `orientation_study`): the tracker
//! file's columns, the arm's parameters in model units, and a least-squares fit that keeps the
//! geometric parameters in their prior box. Measurements, not features: nothing here is certified.

// Each study uses a part of this module.
#![allow(dead_code)]

use calib_arm::params::{self, Unit};
use calib_arm::tracker_file::{JointUnit, LengthUnit, MeasurementColumns};
use calib_arm::Arm;
use nalgebra::{DMatrix, DVector};

/// The UR10 series' joint columns (radians) and the T-Mac's columns `x, y, z` given as `point`
/// (`measurement_x…` in mm, or `measurement_rx…`: degrees, read through the same parser).
pub fn tracker_columns(point: [&str; 3]) -> MeasurementColumns {
    MeasurementColumns {
        joints: [
            "shoulder_pan_joint",
            "shoulder_lift_joint",
            "elbow_joint",
            "wrist_1_joint",
            "wrist_2_joint",
            "wrist_3_joint",
        ]
        .map(String::from)
        .to_vec(),
        point: point.map(String::from),
        joint_unit: JointUnit::Rad,
        length_unit: LengthUnit::Mm,
        rows: None,
        orientation: None,
    }
}

/// Root mean square.
pub fn rms(r: &[f64]) -> f64 {
    (r.iter().map(|v| v * v).sum::<f64>() / r.len() as f64).sqrt()
}

/// The parameters' units in model order.
fn units(arm: &Arm) -> Vec<Unit> {
    params::names(arm.joints.len())
        .into_iter()
        .map(|(_, u)| u)
        .collect()
}

/// The arm's parameters in model order and units (radians, mm), with which are free and their
/// prior half-widths.
pub fn model_parameters(arm: &Arm) -> (Vec<f64>, Vec<bool>, Vec<f64>) {
    let units = units(arm);
    let conv = |v: &[f64]| -> Vec<f64> {
        v.iter()
            .zip(&units)
            .map(|(v, u)| if *u == Unit::Deg { v.to_radians() } else { *v })
            .collect()
    };
    (conv(&arm.nominal()), arm.free(), conv(&arm.radius()))
}

/// The arm with the parameters `x` (model units, as [`model_parameters`]).
pub fn arm_at(arm: &Arm, x: &[f64]) -> Arm {
    let files: Vec<f64> = x
        .iter()
        .zip(units(arm))
        .map(|(v, u)| if u == Unit::Deg { v.to_degrees() } else { *v })
        .collect();
    arm.with_nominal(&files)
}

/// The Jacobian of `residuals` by forward differences over the free parameters (steps 1e-6 of
/// their prior radius) and then the extras (step `extra_step`).
pub fn jacobian(
    x: &[f64],
    c: &[f64],
    vars: &[usize],
    radius: &[f64],
    extra_step: f64,
    residuals: &impl Fn(&[f64], &[f64]) -> Vec<f64>,
) -> DMatrix<f64> {
    let r0 = DVector::from_vec(residuals(x, c));
    let mut jac = DMatrix::zeros(r0.len(), vars.len() + c.len());
    for k in 0..vars.len() + c.len() {
        let (mut xp, mut cp) = (x.to_vec(), c.to_vec());
        let h = if k < vars.len() {
            let h = 1e-6 * radius[vars[k]].max(1e-3);
            xp[vars[k]] += h;
            h
        } else {
            cp[k - vars.len()] += extra_step;
            extra_step
        };
        let rp = DVector::from_vec(residuals(&xp, &cp));
        jac.set_column(k, &((rp - &r0) / h));
    }
    jac
}

/// Levenberg–Marquardt (finite differences, steps projected onto the prior box and kept only
/// when they lower the sum of squares) over the free parameters within their prior box and the
/// unbounded extras `c` (starting values given; finite-difference step `extra_step`).
pub fn fit(
    arm: &Arm,
    mut c: Vec<f64>,
    extra_step: f64,
    residuals: impl Fn(&[f64], &[f64]) -> Vec<f64>,
) -> (Vec<f64>, Vec<f64>) {
    let (mut x, free, radius) = model_parameters(arm);
    let nominal = x.clone();
    let vars: Vec<usize> = (0..x.len()).filter(|&j| free[j]).collect();
    let n = vars.len() + c.len();
    let cost = |x: &[f64], c: &[f64]| residuals(x, c).iter().map(|v| v * v).sum::<f64>();
    let mut damping = 1e-3;
    for _ in 0..200 {
        let r0 = DVector::from_vec(residuals(&x, &c));
        let jac = jacobian(&x, &c, &vars, &radius, extra_step, &residuals);
        let normal = jac.transpose() * &jac;
        let gradient = -(jac.transpose() * &r0);
        let before = r0.norm_squared();
        let mut improved = false;
        for _ in 0..12 {
            let mut damped = normal.clone();
            for k in 0..n {
                damped[(k, k)] += damping * normal[(k, k)].max(1e-12);
            }
            let Some(step) = damped.lu().solve(&gradient) else {
                break;
            };
            let (mut xn, mut cn) = (x.clone(), c.clone());
            for (k, &j) in vars.iter().enumerate() {
                xn[j] = (x[j] + step[k]).clamp(nominal[j] - radius[j], nominal[j] + radius[j]);
            }
            for k in 0..c.len() {
                cn[k] += step[vars.len() + k];
            }
            if cost(&xn, &cn) < before {
                (x, c) = (xn, cn);
                damping = (damping / 3.0).max(1e-9);
                improved = true;
                break;
            }
            damping *= 4.0;
        }
        if !improved {
            break;
        }
    }
    (x, c)
}
