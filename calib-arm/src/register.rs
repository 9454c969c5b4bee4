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
//!
//! Base and tool can be told apart only when the flange's orientation changes over the rows: with
//! one orientation `R_0`, the tool's `R R_0 t` is a constant the base's position `T` absorbs, and
//! the fit sends the tool anywhere (on 60 real UR10 rows of one orientation, 0.9 m from the
//! flange) for the same residuals. [`separability`] measures it before fitting; below
//! [`SEPARABLE_SPREAD_DEG`] [`register`] keeps the robot file's tool point, fixed (prior
//! half-width 0), and fits the base alone ([`ToolPoint`] chooses otherwise).

use crate::certification::fit_arm;
use crate::pose::orientation::{from_euler_xyz, orientation_errors_deg};
use crate::robot::{Arm, ToolRotation};
use crate::simulate::Reading;
use crate::vendor::{arm_flange, base_frame, base_parameters, Frame};
use crate::ArmError;
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

/// Whether registration fits the tool point or keeps the robot file's.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum ToolPoint {
    /// Fit it when the rows tell it from the base, keep it otherwise.
    #[default]
    Auto,
    /// Fit it, even when the rows cannot tell it from the base.
    Fit,
    /// Keep the robot file's; fit the base alone.
    Keep,
}

/// A registered arm and how well it fits.
#[derive(Clone, Debug, PartialEq)]
pub struct Registration {
    /// The arm with the registered base and tool (and their priors); joints as given. A kept
    /// tool point ([`Registration::tool_kept`]) has the prior half-width 0: where the rows cannot
    /// tell it from the base, neither can a calibration on them.
    pub arm: Arm,
    /// Whether the tool point was kept from the robot file rather than fitted.
    pub tool_kept: bool,
    /// How well the rows tell the tool point from the base ([`separability`]; whether they
    /// cannot, [`Separability::inseparable`], whatever was done about it).
    pub separability: Separability,
    /// Root mean square of every coordinate's residual, mm (nominal joints).
    pub rms: f64,
    /// Largest coordinate residual, mm.
    pub max_abs: f64,
    /// The closed-form start's RMS, mm.
    pub start_rms: f64,
    /// Whether the least-squares refinement reported convergence.
    pub converged: bool,
}

/// How well the rows tell the tool point from the base ([`separability`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Separability {
    /// The flange orientations' spread that the tool point's weakest direction sees, degrees:
    /// `sqrt(λ_min / n)` of the tool's information once the base has taken all it can.
    pub spread_deg: f64,
    /// That weakest direction, a unit vector in the flange frame.
    pub weakest: [f64; 3],
    /// The largest angle between a row's flange orientation and their mean, degrees: below
    /// [`SEPARABLE_SPREAD_DEG`], the rows hold one flange orientation.
    pub orientation_range_deg: f64,
    /// The number of rows.
    pub rows: usize,
}

impl Separability {
    /// Whether the rows are too little to fit the tool point: [`Separability::spread_deg`]
    /// below [`SEPARABLE_SPREAD_DEG`] (or undefined).
    pub fn inseparable(&self) -> bool {
        self.spread_deg.is_nan() || self.spread_deg < SEPARABLE_SPREAD_DEG
    }

    /// Why the rows cannot tell the tool point from the base, a sentence without its final
    /// full stop (`None` when they can).
    pub fn reason(&self) -> Option<String> {
        if !self.inseparable() {
            return None;
        }
        let why = if self.orientation_range_deg < SEPARABLE_SPREAD_DEG {
            format!(
                "the {} configurations hold one flange orientation (all within {:.3}° of it)",
                self.rows, self.orientation_range_deg
            )
        } else {
            let [x, y, z] = self.weakest;
            format!(
                "the {} configurations' flange orientations spread {:.4}° across the flange \
                 direction ({x:.3}, {y:.3}, {z:.3}), below {SEPARABLE_SPREAD_DEG}° (turns about \
                 that axis only, or too few configurations)",
                self.rows, self.spread_deg
            )
        };
        Some(format!("{why}: base and tool cannot be told apart there"))
    }
}

/// The smallest [`Separability::spread_deg`] at which [`register`] fits the tool point, degrees.
///
/// Below it the base's position takes up the tool point: the tool's standard error along its
/// weakest direction is about `rms / (√n · spread)` (the spread in radians), 0.75 mm / (√60 · 0.1°) ≈ 55 mm at
/// this threshold on the real UR10's residuals. Measured on that robot's series B (nominal
/// joints): 60 rows commanded to one orientation spread 0.006° (the fit put the tool 0.9 m
/// away), with one row of another orientation added 0.0075° (the tool 220 mm off along its weak
/// axis); rows cycling through the five commanded orientations 10° apart spread 0.30° to 0.40°
/// over 10 to 20 rows (tool within 9 mm of the others' 93 mm), and rows 1-60, with the home
/// pose, 5.9°. The threshold sits a factor 3 below the least spread that still located the tool.
pub const SEPARABLE_SPREAD_DEG: f64 = 0.1;

/// Alternating steps of the closed-form start.
const START_ITERATIONS: usize = 200;

/// Registers `nominal` (its joints as they are; base and tool found) on `readings`: the tool
/// point is fitted when the rows tell it from the base, and kept from `nominal` otherwise
/// ([`ToolPoint::Auto`] of [`register_with`]).
pub fn register(
    nominal: &Arm,
    readings: &[Reading],
    priors: RegistrationPriors,
) -> Result<Registration, ArmError> {
    register_with(nominal, readings, priors, ToolPoint::Auto)
}

/// Registers `nominal` (its joints as they are) on `readings`: the base found, the tool point
/// fitted or kept as `tool` says. A fitted tool gets the prior half-width `priors.tool_mm`, a
/// kept one 0.
pub fn register_with(
    nominal: &Arm,
    readings: &[Reading],
    priors: RegistrationPriors,
    tool: ToolPoint,
) -> Result<Registration, ArmError> {
    if readings.len() < 3 {
        return Err(ArmError::TooFewConfigurations(readings.len()));
    }
    for (value, prior) in [
        (priors.base_mm, "base position prior"),
        (priors.base_deg, "base rotation prior"),
        (priors.tool_mm, "tool prior"),
    ] {
        if !(value.is_finite() && value >= 0.0) {
            return Err(ArmError::Prior { prior, value });
        }
    }
    let flanges = flange_frames(nominal, readings);
    let measured: Vec<Vector3<f64>> = readings.iter().map(|r| Vector3::from(r.point)).collect();
    let separability = separability(nominal, readings);
    let keep = match tool {
        ToolPoint::Auto => separability.inseparable(),
        ToolPoint::Fit => false,
        ToolPoint::Keep => true,
    };
    let mut t = if keep {
        Vector3::from(nominal.tool)
    } else {
        Vector3::zeros()
    };
    let mut pose = Frame::identity();
    for _ in 0..START_ITERATIONS {
        let points: Vec<Vector3<f64>> = flanges
            .iter()
            .map(|f| (f * Point3::from(t)).coords)
            .collect();
        pose = kabsch(&points, &measured).ok_or(ArmError::Collinear)?;
        if keep {
            break;
        }
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
    free.tool_radius = [if keep { 0.0 } else { 1.0 }; 3];
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
    arm.tool_radius = [if keep { 0.0 } else { priors.tool_mm }; 3];
    Ok(Registration {
        arm,
        tool_kept: keep,
        separability,
        rms: fit.rms,
        max_abs: fit.max_abs,
        start_rms,
        converged: fit.converged,
    })
}

/// The flange frames of `nominal` at each reading's joints (the tracker frame with the file's base).
fn flange_frames(nominal: &Arm, readings: &[Reading]) -> Vec<Frame> {
    readings
        .iter()
        .map(|r| {
            let q: Vec<f64> = r.joints_deg.iter().map(|d| d.to_radians()).collect();
            arm_flange(nominal, &q)
        })
        .collect()
}

/// How well `readings` tell the tool point from the base, with `nominal`'s joints and tool.
///
/// Linearised, a configuration's tracked point moves by `δT + δω × x_k + R_k δt` for a move
/// `δT` of the base's position, `δω` of its rotation and `δt` of the tool point (base frame,
/// `R_k` the flange's rotation and `x_k` the tracked point, both from the nominal joints and the
/// file's tool). Over the readings, the tool's information once the base has taken all it can is
/// the Schur complement `S = N_tt − N_tb N_bb⁻¹ N_bt` of the normal matrix `N = Σ J_kᵀ J_k`
/// (`J_k = [I, −[x_k]×, R_k]`), independent of the units of the base's columns (and of the
/// points' origin, a constant the position's columns take). For the base's
/// position alone it is `Σ (R_k − R̄)ᵀ (R_k − R̄)`, whose smallest eigenvalue is `n` times the
/// mean square spread of the flange orientations about the axes across the tool's weakest
/// direction (radians, small spreads). Hence the spread reported, `sqrt(λ_min(S) / n)` in
/// degrees: 0 when every row has the same flange orientation (or turns it about one axis only,
/// then the tool's component along that axis is what cannot be found).
pub fn separability(nominal: &Arm, readings: &[Reading]) -> Separability {
    let t = Vector3::from(nominal.tool);
    let flanges = flange_frames(nominal, readings);
    // The rotation's columns about the points' centre and in units of their spread: the same
    // span with the position's columns, so the same complement, but a well-conditioned `N_bb`.
    let points: Vec<Vector3<f64>> = flanges
        .iter()
        .map(|f| (f * Point3::from(t)).coords)
        .collect();
    let centre = points.iter().sum::<Vector3<f64>>() / points.len().max(1) as f64;
    let scale = (points
        .iter()
        .map(|x| (x - centre).norm_squared())
        .sum::<f64>()
        / points.len().max(1) as f64)
        .sqrt()
        .max(1e-300);
    let mut n = nalgebra::SMatrix::<f64, 9, 9>::zeros();
    let mut sum = Matrix3::zeros();
    for (f, x) in flanges.iter().zip(&points) {
        let rot = f.rotation.to_rotation_matrix().into_inner();
        sum += rot;
        let mut j = nalgebra::SMatrix::<f64, 3, 9>::zeros();
        j.fixed_view_mut::<3, 3>(0, 0)
            .copy_from(&Matrix3::identity());
        j.fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&(-((x - centre) / scale).cross_matrix()));
        j.fixed_view_mut::<3, 3>(0, 6).copy_from(&rot);
        n += j.transpose() * j;
    }
    let nbb = n.fixed_view::<6, 6>(0, 0).into_owned();
    let nbt = n.fixed_view::<6, 3>(0, 6).into_owned();
    let ntt = n.fixed_view::<3, 3>(6, 6).into_owned();
    // The base's block is singular only when the points do not fix a rigid transform (then
    // registration fails anyway); the pseudo-inverse keeps the test defined there.
    let nbb_inv = nbb
        .pseudo_inverse(1e-12 * nbb.norm().max(1e-300))
        .unwrap_or_else(|_| nalgebra::SMatrix::zeros());
    let s = ntt - nbt.transpose() * nbb_inv * nbt;
    let s = (s + s.transpose()) * 0.5;
    let eig = s.symmetric_eigen();
    let (i, lambda) = eig
        .eigenvalues
        .iter()
        .copied()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0, 0.0));
    let weakest = eig.eigenvectors.column(i).into_owned();
    let orientation_range_deg = match nearest_rotation(&sum) {
        Some(mean) => flanges
            .iter()
            .map(|f| (mean.inverse() * f.rotation.to_rotation_matrix()).angle())
            .fold(0.0_f64, f64::max)
            .to_degrees(),
        None => f64::NAN,
    };
    Separability {
        rows: readings.len(),
        orientation_range_deg,
        spread_deg: (lambda.max(0.0) / readings.len().max(1) as f64)
            .sqrt()
            .to_degrees(),
        weakest: [weakest[0], weakest[1], weakest[2]],
    }
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
) -> Result<(ToolRotation, f64, f64), ArmError> {
    if !(radius_deg.is_finite() && radius_deg >= 0.0) {
        return Err(ArmError::Prior {
            prior: "tool rotation prior",
            value: radius_deg,
        });
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
    let tool = nearest_rotation(&sum).ok_or(ArmError::NoOrientation)?;
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
