//! Does joint compliance explain what a geometric model leaves on a real UR10? (issue 35, item 6)
//!
//! UR arms bend under gravity. The study adds to each of joints 2–4 (shoulder lift, elbow, wrist 1,
//! whose axes are horizontal) a deflection `c_i τ_i(q)` proportional to the gravity torque `τ_i`
//! of the links beyond it (UR10 link masses from UR's description, each at the middle of its link,
//! 1 kg at the tool point; the coefficients `c_i` absorb any error of scale), and compares on
//! held-out rows:
//!
//! * least squares with the geometric parameters kept in their prior box, without and with the
//!   three coefficients;
//! * the smallest consistent position bound (the Chebyshev fit, its point certified consistent at
//!   the factor printed) with the joint readings as measured and as corrected by the fitted
//!   deflections.
//!
//! ```sh
//! cargo run --release -p calib-arm --example compliance_study -- \
//!     robot.toml docs/data/ur10_ipa/series_b_joint_configurations.csv 60
//! ```
//! (`robot.toml` from tutorial steps 1–2, `docs/src/tutorials/ur10.md`.) A measurement, not a
//! feature: nothing here is certified except the consistency of the Chebyshev points.

mod study;

use calib_arm::certification::{padded_box, NM};
use calib_arm::files::{read_robot, read_tracker_measurements};
use calib_arm::model::tracked_point;
use calib_arm::simulate::{measurement_box, Reading, Uncertainty};
use calib_arm::vendor::link;
use calib_arm::{Arm, Arm7Point};
use calib_core::{is_consistent_point, smallest_scale, Interval};
use nalgebra::{Point3, Vector3};
use std::path::Path;
use study::{fit, rms, tracker_columns};

/// UR10 link masses (kg) from UR's description (`ur_description`): shoulder, upper arm, forearm,
/// wrist 1, 2, 3; and the tracker target at the tool point.
const MASSES: [f64; 6] = [7.778, 12.93, 3.87, 1.96, 1.96, 0.202];
const PAYLOAD: f64 = 1.0;
/// The compliant joints (0-based): shoulder lift, elbow, wrist 1.
const COMPLIANT: [usize; 3] = [1, 2, 3];

/// Gravity torques (N·mm, up to a common factor) about the compliant joints at `q` (radians), in
/// the robot's own base frame (z up), from the nominal geometry.
fn gravity_torques(arm: &Arm, q: &[f64]) -> [f64; 3] {
    // Joint frames: origin and axis of joint i, and link i's end.
    let mut t = nalgebra::Isometry3::identity();
    let mut origins = Vec::new();
    let mut axes = Vec::new();
    for (j, qi) in arm.joints.iter().zip(q) {
        origins.push(t.translation.vector);
        axes.push(t.rotation * Vector3::z());
        let [theta, d, a, alpha, beta] = j.nominal;
        t = t
            * nalgebra::Isometry3::rotation(Vector3::z() * *qi)
            * link(
                theta.to_radians(),
                d,
                a,
                alpha.to_radians(),
                beta.to_radians(),
            );
    }
    origins.push(t.translation.vector);
    let tool = t * Point3::new(arm.tool[0], arm.tool[1], arm.tool[2]);
    let g = Vector3::new(0.0, 0.0, -9.81);
    let mut masses: Vec<(Vector3<f64>, f64)> = (0..arm.joints.len())
        .map(|k| ((origins[k] + origins[k + 1]) / 2.0, MASSES[k]))
        .collect();
    masses.push((tool.coords, PAYLOAD));
    COMPLIANT.map(|i| {
        masses[i..]
            .iter()
            .map(|(c, m)| axes[i].dot(&(c - origins[i]).cross(&(g * *m))))
            .sum()
    })
}

/// Joint readings (radians) corrected by the deflections `c · τ`.
fn deflected(q: &[f64], tau: &[f64; 3], c: &[f64]) -> Vec<f64> {
    let mut q = q.to_vec();
    for (k, &i) in COMPLIANT.iter().enumerate() {
        q[i] += c.get(k).copied().unwrap_or(0.0) * tau[k];
    }
    q
}

struct Data {
    q: Vec<Vec<f64>>,
    tau: Vec<[f64; 3]>,
    p: Vec<[f64; 3]>,
}

fn data(arm: &Arm, readings: &[Reading]) -> Data {
    let q: Vec<Vec<f64>> = readings
        .iter()
        .map(|r| r.joints_deg.iter().map(|v| v.to_radians()).collect())
        .collect();
    Data {
        tau: q.iter().map(|q| gravity_torques(arm, q)).collect(),
        p: readings.iter().map(|r| r.point).collect(),
        q,
    }
}

/// Residuals (mm) of parameters `x` and coefficients `c` on `d`.
fn residuals(x: &[f64], c: &[f64], d: &Data) -> Vec<f64> {
    let mut out = Vec::with_capacity(3 * d.q.len());
    for ((q, tau), p) in d.q.iter().zip(&d.tau).zip(&d.p) {
        let f = tracked_point(x, &deflected(q, tau, c)).expect("6 joints");
        out.extend((0..3).map(|r| f[r] - p[r]));
    }
    out
}

/// The Chebyshev estimate of the smallest consistent position bound (mm) with joint bounds
/// 0.001°, whether its point is certified consistent at 1.001 times it, and the point (padded
/// model).
fn smallest_bound(arm: &Arm, readings: &[Reading]) -> (f64, bool, [f64; 44]) {
    let u = Uncertainty {
        joint_deg: 0.001,
        pos: 0.05,
    };
    let boxes = |pos: f64| -> Vec<[Interval; NM]> {
        let u = Uncertainty { pos, ..u };
        readings
            .iter()
            .filter_map(|r| measurement_box(r, &u))
            .collect()
    };
    let mask: [bool; NM] = core::array::from_fn(|i| i >= NM - 3);
    let e = smallest_scale(&Arm7Point, &padded_box(arm), &boxes(u.pos), &mask);
    let bound = e.scale * u.pos;
    (
        bound,
        is_consistent_point(&Arm7Point, &e.point, &boxes(1.001 * bound)),
        e.point,
    )
}

/// The rms residual (mm) of the padded model's point `x` on `readings`.
fn padded_rms(x: &[f64; 44], readings: &[Reading]) -> f64 {
    use calib_core::VectorModel;
    let u = Uncertainty {
        joint_deg: 0.0,
        pos: 0.0,
    };
    let r: Vec<f64> = readings
        .iter()
        .filter_map(|r| measurement_box::<NM>(r, &u))
        .flat_map(|m| Arm7Point.residuals(x, &m.map(|v| v.mid())))
        .collect();
    rms(&r)
}

/// `readings` with the deflections `c · τ` taken out of the joint readings.
fn corrected(readings: &[Reading], d: &Data, c: &[f64]) -> Vec<Reading> {
    readings
        .iter()
        .zip(d.q.iter().zip(&d.tau))
        .map(|(r, (q, tau))| Reading {
            joints_deg: deflected(q, tau, c)
                .iter()
                .map(|v| v.to_degrees())
                .collect(),
            point: r.point,
        })
        .collect()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let [_, robot, measurements, calibrate] = &args[..] else {
        return Err("usage: compliance_study ROBOT.toml MEASUREMENTS.csv CALIBRATION_ROWS".into());
    };
    let calibrate: usize = calibrate.parse()?;
    let arm = read_robot(Path::new(robot))?;
    let columns = tracker_columns(["measurement_x", "measurement_y", "measurement_z"]);
    let all = read_tracker_measurements(Path::new(measurements), 6, &columns)?.readings;
    let (cal, held) = all.split_at(calibrate.min(all.len()));
    let (dc, dh) = (data(&arm, cal), data(&arm, held));
    println!(
        "{} configurations to calibrate, {} held out",
        cal.len(),
        held.len()
    );
    for compliance in [false, true] {
        let extras = vec![0.0; if compliance { 3 } else { 0 }];
        let (x, c) = fit(&arm, extras, 1e-10, |x, c| residuals(x, c, &dc));
        println!(
            "least squares in the prior box{}: calibration rms {:.4} mm, held-out rms {:.4} mm{}",
            if compliance { " + compliance" } else { "" },
            rms(&residuals(&x, &c, &dc)),
            rms(&residuals(&x, &c, &dh)),
            if compliance {
                let c: Vec<String> = c.iter().map(|v| format!("{v:.3e}")).collect();
                format!(" (c = {} rad per N·mm)", c.join(", "))
            } else {
                String::new()
            }
        );
        // The same data with the fitted deflections taken out of the joint readings.
        let (bound, proved, point) = smallest_bound(&arm, &corrected(cal, &dc, &c));
        println!(
            "  Chebyshev fit{}: held-out rms {:.4} mm; smallest consistent position bound {bound:.4} mm{}",
            if compliance {
                " (readings corrected by the fitted deflections)"
            } else {
                ""
            },
            padded_rms(&point, &corrected(held, &dh, &c)),
            if proved {
                ", its point certified consistent at 1.001 times it"
            } else {
                ", its point not certified"
            }
        );
    }
    Ok(())
}
