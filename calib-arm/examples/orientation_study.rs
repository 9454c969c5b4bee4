//! What do the T-Mac's orientations add to a calibration of the real UR10? (issue 35, item 4)
//!
//! The T-Mac measures its orientation as well as its position (intrinsic Euler angles `XYZ`, in
//! degrees, in the tracker frame: `R = Rx(rx) Ry(ry) Rz(rz)`, see `docs/data/ur10_ipa/README.md`).
//! Each configuration then gives six equations: the position as today, and the orientation of the
//! measured frame, `R_base R(q, geometry) R_tool`, with three more unknowns for the T-Mac's
//! rotation on the flange (`R_tool = R_0 exp(c)`, `R_0` the closed-form average of
//! `R(q)ᵀ R_measured` over the configurations). The study compares, on held-out rows:
//!
//! * least squares on positions only (geometric parameters in their prior box);
//! * least squares on positions and orientations, one radian of orientation error weighing as
//!   much as `w` mm of position (`WEIGHTS`);
//!
//! and how much of each parameter's prior the data leave, to first order, with positions only and
//! with orientations (posterior standard deviation over the prior half-width, with 0.5 mm per
//! coordinate — the data's non-geometric level — and 1 mrad per orientation component, near the
//! 0.05–0.065° the fits leave: `w` = 500).
//!
//! ```sh
//! cargo run --release -p calib-arm --example orientation_study -- \
//!     robot.toml docs/data/ur10_ipa/series_b_joint_configurations.csv 60
//! ```
//! (`robot.toml` from tutorial steps 1–2, `docs/src/tutorials/ur10.md`.) A measurement, not a
//! feature: nothing here is certified.

mod study;

use calib_arm::files::{read_robot, read_tracker_measurements};
use calib_arm::model::tracked_point;
use calib_arm::params;
use calib_arm::vendor::arm_flange;
use calib_arm::Arm;
use nalgebra::{DMatrix, Matrix3, Rotation3, UnitQuaternion, Vector3};
use std::path::Path;
use study::{arm_at, fit, jacobian, model_parameters, rms, tracker_columns};

/// Millimetres of position residual that one radian of orientation residual weighs in the fits.
const WEIGHTS: [f64; 3] = [100.0, 500.0, 1000.0];
/// The weight of the first-order shares of the priors: 1 mrad counts as 0.5 mm.
const SHARES_WEIGHT: f64 = 500.0;
/// The data's non-geometric error per coordinate (mm) for the first-order shares of the priors.
const SIGMA_MM: f64 = 0.5;

/// Joint readings (radians), T-Mac positions (mm) and orientations of some rows.
struct Data {
    q: Vec<Vec<f64>>,
    p: Vec<[f64; 3]>,
    r: Vec<UnitQuaternion<f64>>,
}

/// The rotation of intrinsic Euler angles `XYZ` in degrees: `Rx(a) Ry(b) Rz(c)`.
fn euler_xyz_deg(a: [f64; 3]) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::x_axis(), a[0].to_radians())
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), a[1].to_radians())
        * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), a[2].to_radians())
}

/// The flange's orientation (with the base's) of the arm with parameters `x` (model units).
fn flange_rotation(arm: &Arm, x: &[f64], q: &[f64]) -> UnitQuaternion<f64> {
    arm_flange(&arm_at(arm, x), q).rotation
}

/// The tool rotation closest to every `R(q_k)ᵀ R_k` (the projection of their sum onto rotations).
fn tool_rotation_start(arm: &Arm, x: &[f64], d: &Data) -> UnitQuaternion<f64> {
    let sum: Matrix3<f64> =
        d.q.iter()
            .zip(&d.r)
            .map(|(q, r)| {
                (flange_rotation(arm, x, q).inverse() * r)
                    .to_rotation_matrix()
                    .into_inner()
            })
            .sum();
    UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix(&sum))
}

/// Position residuals (mm), then with a weight `w` the orientation residuals (radians × `w`: the
/// rotation vector of `R_kᵀ R_model`), of parameters `x` and tool rotation `tool0 exp(c)` on `d`.
fn residuals(
    arm: &Arm,
    x: &[f64],
    c: &[f64],
    tool0: &UnitQuaternion<f64>,
    d: &Data,
    w: Option<f64>,
) -> Vec<f64> {
    let mut out = Vec::with_capacity(6 * d.q.len());
    for (q, p) in d.q.iter().zip(&d.p) {
        let f = tracked_point(x, q).expect("6 joints");
        out.extend((0..3).map(|r| f[r] - p[r]));
    }
    if let Some(w) = w {
        let tool = tool0 * UnitQuaternion::from_scaled_axis(Vector3::new(c[0], c[1], c[2]));
        for (q, r) in d.q.iter().zip(&d.r) {
            let e = (r.inverse() * flange_rotation(arm, x, q) * tool).scaled_axis();
            out.extend(e.iter().map(|v| v * w));
        }
    }
    out
}

/// Per free parameter (and the tool rotation's three), the first-order posterior standard
/// deviation over the prior half-width: `sqrt(diag((JᵀJ/σ² + diag(1/r²))⁻¹)) / r`.
fn prior_shares(jac: &DMatrix<f64>, radius: &[f64]) -> Vec<f64> {
    let n = radius.len();
    let mut info = jac.transpose() * jac / (SIGMA_MM * SIGMA_MM);
    for k in 0..n {
        info[(k, k)] += 1.0 / (radius[k] * radius[k]);
    }
    let cov = info.try_inverse().expect("the prior makes it invertible");
    (0..n).map(|k| cov[(k, k)].sqrt() / radius[k]).collect()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let [_, robot, measurements, calibrate] = &args[..] else {
        return Err("usage: orientation_study ROBOT.toml MEASUREMENTS.csv CALIBRATION_ROWS".into());
    };
    let calibrate: usize = calibrate.parse()?;
    let arm = read_robot(Path::new(robot))?;
    let file = Path::new(measurements);
    let points = read_tracker_measurements(
        file,
        6,
        &tracker_columns(["measurement_x", "measurement_y", "measurement_z"]),
    )?
    .readings;
    // The orientation columns through the same parser (degrees, no unit conversion).
    let angles = read_tracker_measurements(
        file,
        6,
        &tracker_columns(["measurement_rx", "measurement_ry", "measurement_rz"]),
    )?
    .readings;
    let data = |range: std::ops::Range<usize>| Data {
        q: points[range.clone()]
            .iter()
            .map(|r| r.joints_deg.iter().map(|v| v.to_radians()).collect())
            .collect(),
        p: points[range.clone()].iter().map(|r| r.point).collect(),
        r: angles[range]
            .iter()
            .map(|r| euler_xyz_deg(r.point))
            .collect(),
    };
    let split = calibrate.min(points.len());
    let (dc, dh) = (data(0..split), data(split..points.len()));
    println!(
        "{} configurations to calibrate, {} held out",
        dc.q.len(),
        dh.q.len()
    );
    let (x0, free, radius) = model_parameters(&arm);
    let tool0 = tool_rotation_start(&arm, &x0, &dc);
    let orientation_rms_deg = |x: &[f64], c: &[f64], tool0: &UnitQuaternion<f64>, d: &Data| {
        let r = residuals(&arm, x, c, tool0, d, Some(1.0));
        let angles: Vec<f64> = r[3 * d.q.len()..]
            .chunks(3)
            .map(|e| Vector3::new(e[0], e[1], e[2]).norm().to_degrees())
            .collect();
        rms(&angles)
    };
    let mut shares_fit = None;
    for w in std::iter::once(None).chain(WEIGHTS.map(Some)) {
        let (x, c) = fit(&arm, vec![0.0; 3], 1e-7, |x, c| {
            residuals(&arm, x, c, &tool0, &dc, w)
        });
        // Orientations of the positions-only fit: its own best tool rotation, for comparison.
        let (tool, c) = match w {
            Some(_) => (tool0, c),
            None => (tool_rotation_start(&arm, &x, &dc), vec![0.0; 3]),
        };
        let pos = |d: &Data| rms(&residuals(&arm, &x, &c, &tool, d, None));
        println!(
            "least squares on {}: calibration rms {:.4} mm, held-out rms {:.4} mm per coordinate; \
             orientation error rms {:.4}° (calibration), {:.4}° (held out)",
            match w {
                Some(w) => format!("positions and orientations (1 rad = {w} mm)"),
                None => "positions only".to_string(),
            },
            pos(&dc),
            pos(&dh),
            orientation_rms_deg(&x, &c, &tool, &dc),
            orientation_rms_deg(&x, &c, &tool, &dh),
        );
        if w == Some(SHARES_WEIGHT) {
            shares_fit = Some((x, c, tool));
        }
    }
    // How much of each prior the calibration rows leave, at the 6-DoF fit, to first order.
    let (x, c, tool) = shares_fit.expect("SHARES_WEIGHT is one of WEIGHTS");
    let vars: Vec<usize> = (0..x0.len()).filter(|&j| free[j]).collect();
    let mut r: Vec<f64> = vars.iter().map(|&j| radius[j]).collect();
    r.extend([1.0; 3]);
    let shares = |w: Option<f64>| {
        let jac = jacobian(&x, &c, &vars, &radius, 1e-7, &|x, c| {
            residuals(&arm, x, c, &tool, &dc, w)
        });
        prior_shares(&jac, &r)
    };
    let (three, six) = (shares(None), shares(Some(SHARES_WEIGHT)));
    let names = params::names(arm.joints.len());
    println!(
        "first-order posterior σ / prior half-width (σ = {SIGMA_MM} mm, {} mrad):",
        SIGMA_MM / SHARES_WEIGHT * 1e3
    );
    println!("  parameter   positions   + orientations");
    for (k, &j) in vars.iter().enumerate() {
        println!(
            "  {:<10} {:>9.3} {:>12.3}{}",
            names[j].0,
            three[k],
            six[k],
            if six[k] < 0.5 * three[k] {
                "   determined by the orientations"
            } else {
                ""
            }
        );
    }
    Ok(())
}
