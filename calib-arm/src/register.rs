//! Registration: where the robot stands in the tracker's frame and where the tracked point sits
//! on the flange, from scratch (any rotation, any distance).
//!
//! With the nominal joints, configuration `k`'s flange frame in the robot's base frame is
//! `(R_k, o_k)` and the tracker measures `p_k ≈ R (R_k t + o_k) + T`: unknown the rigid transform
//! `(R, T)` (tracker to base) and the tool point `t`. The start is closed-form and alternating:
//! for a fixed `t`, `(R, T)` is the best rigid fit of the points `R_k t + o_k` onto the `p_k`
//! (Kabsch: one 3×3 SVD); for a fixed `(R, T)`, `t` is linear least squares
//! (`t = mean_k (R R_k)ᵀ (p_k − T − R o_k)`, the `R R_k` being rotations); from `t = 0`. Both steps
//! lower the same sum of squares. Then Levenberg–Marquardt refines the nine base and tool
//! parameters together ([`crate::certification::fit_arm`]).

use crate::certification::fit_arm;
use crate::pose::orientation::{from_euler_xyz, orientation_errors_deg};
use crate::robot::{Arm, ToolRotation};
use crate::simulate::Reading;
use crate::vendor::{arm_flange, base_frame, base_parameters, Frame};
use nalgebra::{Matrix3, Point3, Rotation3, Translation3, UnitQuaternion, Vector3};

/// Prior half-widths written around the registered base and tool.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegistrationPriors {
    /// The base's position, mm.
    pub base_mm: f64,
    /// The base's rotations, degrees.
    pub base_deg: f64,
    /// The tool point, mm.
    pub tool_mm: f64,
}

impl Default for RegistrationPriors {
    /// ±2 mm and ±0.1° for the base, ±2 mm for the tool point.
    fn default() -> Self {
        RegistrationPriors {
            base_mm: 2.0,
            base_deg: 0.1,
            tool_mm: 2.0,
        }
    }
}

/// A registered arm and how well it fits.
#[derive(Clone, Debug, PartialEq)]
pub struct Registration {
    /// The arm with the registered base and tool (and their priors); joints as given.
    pub arm: Arm,
    /// Root mean square of every coordinate's residual, mm (nominal joints).
    pub rms: f64,
    /// Largest coordinate residual, mm.
    pub max_abs: f64,
    /// The closed-form start's RMS, mm.
    pub start_rms: f64,
    /// Whether the least-squares refinement reported convergence.
    pub converged: bool,
}

/// Alternating steps of the closed-form start.
const START_ITERATIONS: usize = 200;

/// Registers `nominal` (its joints as they are; base and tool found) on `readings`.
pub fn register(
    nominal: &Arm,
    readings: &[Reading],
    priors: RegistrationPriors,
) -> Result<Registration, String> {
    if readings.len() < 3 {
        return Err(format!(
            "registration needs at least 3 configurations, found {}",
            readings.len()
        ));
    }
    for (v, name) in [
        (priors.base_mm, "base position prior"),
        (priors.base_deg, "base rotation prior"),
        (priors.tool_mm, "tool prior"),
    ] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(format!("{name} {v}: expected a finite half-width >= 0"));
        }
    }
    let flanges: Vec<Frame> = readings
        .iter()
        .map(|r| {
            let q: Vec<f64> = r.joints_deg.iter().map(|d| d.to_radians()).collect();
            arm_flange(nominal, &q)
        })
        .collect();
    let measured: Vec<Vector3<f64>> = readings.iter().map(|r| Vector3::from(r.point)).collect();
    let mut t = Vector3::zeros();
    let mut pose = Frame::identity();
    for _ in 0..START_ITERATIONS {
        let points: Vec<Vector3<f64>> = flanges
            .iter()
            .map(|f| (f * Point3::from(t)).coords)
            .collect();
        pose = kabsch(&points, &measured)
            .ok_or("the configurations' points are collinear: registration needs a spread")?;
        let next = flanges
            .iter()
            .zip(&measured)
            .map(|(f, p)| {
                let r = (pose.rotation * f.rotation).to_rotation_matrix();
                r.transpose() * (p - pose.translation.vector - pose.rotation * f.translation.vector)
            })
            .sum::<Vector3<f64>>()
            / readings.len() as f64;
        let moved = (next - t).norm();
        t = next;
        if moved < 1e-10 {
            break;
        }
    }
    let start_rms = rms(&flanges, &measured, &pose, &t);
    let mut arm = nominal.clone();
    arm.base = base_parameters(&(pose * base_frame(&nominal.base)));
    arm.tool = t.into();
    // Least squares over the base and tool only.
    let mut free = arm.clone();
    for j in &mut free.joints {
        j.radius = [0.0; 5];
    }
    free.base_radius = [1.0; 6];
    free.tool_radius = [1.0; 3];
    let fit = fit_arm(&free, readings)?;
    let n = 5 * arm.joints.len();
    arm.base.copy_from_slice(&fit.x[n..n + 6]);
    arm.tool.copy_from_slice(&fit.x[n + 6..n + 9]);
    arm.base_radius = [
        priors.base_mm,
        priors.base_mm,
        priors.base_mm,
        priors.base_deg,
        priors.base_deg,
        priors.base_deg,
    ];
    arm.tool_radius = [priors.tool_mm; 3];
    Ok(Registration {
        arm,
        rms: fit.rms,
        max_abs: fit.max_abs,
        start_rms,
        converged: fit.converged,
    })
}

/// The rigid transform taking the points `from` onto `to` best in least squares (Kabsch), `None`
/// when the points do not determine it.
fn kabsch(from: &[Vector3<f64>], to: &[Vector3<f64>]) -> Option<Frame> {
    let n = from.len() as f64;
    let cf = from.iter().sum::<Vector3<f64>>() / n;
    let ct = to.iter().sum::<Vector3<f64>>() / n;
    let h: Matrix3<f64> = from
        .iter()
        .zip(to)
        .map(|(a, b)| (a - cf) * (b - ct).transpose())
        .sum();
    let mut s = h.singular_values();
    s.as_mut_slice().sort_by(|a, b| b.total_cmp(a));
    if s[1] <= 1e-9 * s[0].max(1e-300) {
        return None;
    }
    // The rotation R maximising Σ (b - ct)·R(a - cf) = tr(R H) is the one nearest to Hᵀ.
    let r = nearest_rotation(&h.transpose())?;
    let rotation = UnitQuaternion::from_rotation_matrix(&r);
    let translation = ct - rotation * cf;
    Some(Frame::from_parts(Translation3::from(translation), rotation))
}

/// The rotation nearest to `m` in the Frobenius norm: `U diag(1, 1, det(U Vᵀ)) Vᵀ` for
/// `m = U Σ Vᵀ` (`None` when the SVD fails).
fn nearest_rotation(m: &Matrix3<f64>) -> Option<Rotation3<f64>> {
    let svd = m.svd(true, true);
    let (u, v_t) = (svd.u?, svd.v_t?);
    let d = (u * v_t).determinant().signum();
    Some(Rotation3::from_matrix_unchecked(
        u * Matrix3::from_diagonal(&Vector3::new(1.0, 1.0, d)) * v_t,
    ))
}

/// RMS over every coordinate of `pose · flange_k · t − p_k`.
fn rms(flanges: &[Frame], measured: &[Vector3<f64>], pose: &Frame, t: &Vector3<f64>) -> f64 {
    let sum: f64 = flanges
        .iter()
        .zip(measured)
        .map(|(f, p)| ((pose * f * Point3::from(*t)).coords - p).norm_squared())
        .sum();
    (sum / (3.0 * flanges.len() as f64)).sqrt()
}

/// The measured frame's rotation on the flange of a registered `arm` (its base and joints as
/// they are), from the measured orientations (intrinsic Euler angles `XYZ`, degrees, one per
/// reading): the rotation nearest, in the Frobenius norm, to every `R_kᵀ M_k` (`R_k` the
/// flange's rotation with the base, `M_k` the measured one) — the projection of their sum onto
/// the rotations by an SVD — with the prior half-width `radius_deg` around it. Also the
/// orientation residuals' RMS and largest angle, degrees.
pub fn register_tool_rotation(
    arm: &Arm,
    readings: &[Reading],
    euler_xyz_deg: &[[f64; 3]],
    radius_deg: f64,
) -> Result<(ToolRotation, f64, f64), String> {
    if !(radius_deg.is_finite() && radius_deg >= 0.0) {
        return Err(format!(
            "tool rotation prior {radius_deg}: expected a finite half-width >= 0"
        ));
    }
    let pairs: Vec<(Rotation3<f64>, Rotation3<f64>)> = readings
        .iter()
        .zip(euler_xyz_deg)
        .map(|(r, e)| {
            let q: Vec<f64> = r.joints_deg.iter().map(|d| d.to_radians()).collect();
            let flange = arm_flange(arm, &q).rotation.to_rotation_matrix();
            (flange, from_euler_xyz(e.map(f64::to_radians)))
        })
        .collect();
    let sum: Matrix3<f64> = pairs
        .iter()
        .map(|(f, m)| (f.inverse() * m).into_inner())
        .sum();
    let tool = nearest_rotation(&sum).ok_or("no orientation to register the tool frame from")?;
    let angles = orientation_errors_deg(arm, &tool, readings, euler_xyz_deg);
    let rms = (angles.iter().map(|a| a * a).sum::<f64>() / angles.len().max(1) as f64).sqrt();
    let max = angles.iter().fold(0.0_f64, |a, b| a.max(*b));
    let (roll, pitch, yaw) = tool.euler_angles();
    let rotation = ToolRotation {
        rpy_deg: [roll.to_degrees(), pitch.to_degrees(), yaw.to_degrees()],
        radius: [radius_deg; 3],
    };
    Ok((rotation, rms, max))
}
