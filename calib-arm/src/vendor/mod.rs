//! Vendor kinematics in and out: a chain of joint frames (UR's `kinematics:` YAML, URDF) turned
//! into this crate's Denavit–Hartenberg + Hayati parameters exactly, and back.
//!
//! # Conventions
//! A vendor chain is a list of joint origins `F_1 … F_N` (rigid transforms, each from the previous
//! link's frame to the joint's frame); joint `i` turns about its frame's `z` axis by the reading
//! `q_i`, and the flange frame is the last joint's frame after the turn:
//! `T(q) = F_1 Rz(q_1) F_2 Rz(q_2) ⋯ F_N Rz(q_N)` (UR's YAML and ROS's URDF both mean this; the
//! zero of each joint is the vendor's). This crate's model ([`crate::model`]) is
//! `T_base Rz(q_1) D_1 Rz(q_2) D_2 ⋯ Rz(q_N) D_N` with
//! `D_i = Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i) Ry(beta_i)`.
//!
//! A rotation about and a slide along a joint's axis commute with the joint's turn, so each
//! `F_{i+1}` (with the slide left over from the link before) is split as
//! `D_i · Rz(φ) Tz(s)`, the `Rz(φ) Tz(s)` going into `theta_{i+1}, d_{i+1}`:
//! - axes at more than 45° (**Denavit–Hartenberg**, `beta_i = 0`): `x_i` along the common normal
//!   of the two axes, `d_i` and `a_i` the feet of that normal, `alpha_i` the angle between the axes;
//! - nearly parallel axes (**Hayati**, `d_i = 0`): `x_i` towards where the next axis crosses the
//!   plane `z = 0`, `alpha_i` and `beta_i` the next axis' tilt;
//! - the sign of `x_i` is chosen so that `theta_i` lies in `(−90°, 90°]` (so `a_i` may be negative,
//!   as in UR's published parameters).
//!
//! `F_1` is `Rz(theta_1) Tz(d_1)` when it turns and slides along the base's `z` only (UR's arms);
//! otherwise its rest is kept in `[base]` (the tracker-to-base transform registration finds).
//! The flange frame is the last joint's frame, so the last joint's `a, alpha, beta` are 0.
//! Export inverts this: `F_1 = Rz(theta_1) Tz(d_1)`,
//! `F_{i+1} = Tx(a_i) Rx(alpha_i) Ry(beta_i) Rz(theta_{i+1}) Tz(d_{i+1})`: every joint frame at the
//! foot of its axis' common normal (for UR's nominal geometry, exactly UR's own frames).
//!
//! Which parameters are free (the identifiable set for a tracked point without orientation):
//! `theta_1, d_1` fixed (the base's `rz, z` do the same), `beta` fixed on Denavit–Hartenberg links
//! and `d` on Hayati links, everything of the last joint fixed (it trades off with the tool point).

pub mod ur_yaml;
pub mod urdf;

use crate::robot::{Arm, Joint};
use crate::ArmError;
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};

/// A rigid transform (lengths in mm).
pub type Frame = Isometry3<f64>;

/// Prior half-widths for imported parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImportRadii {
    /// Angles (`theta, alpha, beta`), degrees.
    pub angle_deg: f64,
    /// Lengths (`d, a`), mm.
    pub length_mm: f64,
}

/// `Rz(angle)`.
#[doc(hidden)]
pub fn rz(angle: f64) -> Frame {
    Isometry3::from_parts(
        Translation3::identity(),
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), angle),
    )
}

/// `Rx(angle)`.
#[doc(hidden)]
pub fn rx(angle: f64) -> Frame {
    Isometry3::from_parts(
        Translation3::identity(),
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), angle),
    )
}

/// `Ry(angle)`.
#[doc(hidden)]
pub fn ry(angle: f64) -> Frame {
    Isometry3::from_parts(
        Translation3::identity(),
        UnitQuaternion::from_axis_angle(&Vector3::y_axis(), angle),
    )
}

/// A translation.
#[doc(hidden)]
pub fn trans(x: f64, y: f64, z: f64) -> Frame {
    Isometry3::translation(x, y, z)
}

/// `Rz(theta) Tz(d) Tx(a) Rx(alpha) Ry(beta)` (radians, mm).
pub fn link(theta: f64, d: f64, a: f64, alpha: f64, beta: f64) -> Frame {
    rz(theta) * trans(a, 0.0, d) * rx(alpha) * ry(beta)
}

/// The frame `Trans(xyz) Rz(yaw) Ry(pitch) Rx(roll)` (URDF's `rpy`, radians).
pub fn from_xyz_rpy(xyz: [f64; 3], rpy: [f64; 3]) -> Frame {
    Isometry3::from_parts(
        Translation3::new(xyz[0], xyz[1], xyz[2]),
        UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]),
    )
}

/// The `xyz` and URDF `rpy` (radians) of a frame.
pub fn to_xyz_rpy(f: &Frame) -> ([f64; 3], [f64; 3]) {
    let t = f.translation.vector;
    let (r, p, y) = f.rotation.euler_angles();
    ([t.x, t.y, t.z], [r, p, y])
}

/// The vendor chain's flange frame at joint readings `q` (radians).
pub fn chain_flange(origins: &[Frame], q: &[f64]) -> Frame {
    origins
        .iter()
        .zip(q)
        .fold(Frame::identity(), |t, (f, q)| t * f * rz(*q))
}

/// How far the model's flange frame of `arm` is from the vendor chain's, at most, over
/// `configurations` joint configurations spread over `[-π, π]` for every joint (a
/// golden-ratio sequence, the same every time): the largest distance (mm) and rotation angle
/// (radians) between the two frames, and the configuration where the distance is largest. What
/// `arm import` checks before it writes a robot file: an import is exact only if these are at
/// rounding level.
pub fn agreement(origins: &[Frame], arm: &Arm, configurations: usize) -> (f64, f64, Vec<f64>) {
    let n = origins.len();
    let mut worst = (0.0f64, 0.0f64, vec![0.0; n]);
    for k in 0..configurations {
        let q: Vec<f64> = (0..n)
            .map(|i| {
                let t = ((k as f64 + 0.5) * (0.618_033_988_749_895 * (i as f64 + 1.0))).fract();
                std::f64::consts::PI * (2.0 * t - 1.0)
            })
            .collect();
        let (want, got) = (chain_flange(origins, &q), arm_flange(arm, &q));
        // A non-finite frame is the worst of all.
        let finite_or_worst = |v: f64| if v.is_nan() { f64::INFINITY } else { v };
        let distance = finite_or_worst((got.translation.vector - want.translation.vector).norm());
        let angle = finite_or_worst(got.rotation.angle_to(&want.rotation));
        if distance > worst.0 {
            worst.0 = distance;
            worst.2 = q;
        }
        worst.1 = worst.1.max(angle);
    }
    worst
}

/// The model's flange frame of `arm` (files' units) at joint readings `q` (radians), with the
/// base transform: `T_base Rz(q_1) D_1 ⋯ Rz(q_N) D_N`.
pub fn arm_flange(arm: &Arm, q: &[f64]) -> Frame {
    let b = arm.base;
    let base = trans(b[0], b[1], b[2])
        * rz(b[5].to_radians())
        * ry(b[4].to_radians())
        * rx(b[3].to_radians());
    arm.joints.iter().zip(q).fold(base, |t, (j, q)| {
        let [theta, d, a, alpha, beta] = j.nominal;
        t * rz(*q)
            * link(
                theta.to_radians(),
                d,
                a,
                alpha.to_radians(),
                beta.to_radians(),
            )
    })
}

/// The base parameters `x, y, z, rx, ry, rz` (mm, degrees) of a frame:
/// `Trans(xyz) Rz(rz) Ry(ry) Rx(rx)`.
pub fn base_parameters(f: &Frame) -> [f64; 6] {
    let ([x, y, z], [r, p, yaw]) = to_xyz_rpy(f);
    [x, y, z, r.to_degrees(), p.to_degrees(), yaw.to_degrees()]
}

/// The base frame of base parameters (mm, degrees).
pub fn base_frame(b: &[f64; 6]) -> Frame {
    from_xyz_rpy(
        [b[0], b[1], b[2]],
        [b[3].to_radians(), b[4].to_radians(), b[5].to_radians()],
    )
}

/// How far a frame is from `Rz(φ) Tz(s)`: the largest of its `x, y` offset (mm) and its `z`
/// axis' tilt (radians).
fn off_axis(f: &Frame) -> f64 {
    let t = f.translation.vector;
    let z = f.rotation * Vector3::z();
    t.x.hypot(t.y).max(z.x.hypot(z.y))
}

/// `(φ, s)` of a frame `Rz(φ) Tz(s)`.
fn turn_and_slide(f: &Frame) -> (f64, f64) {
    let x = f.rotation * Vector3::x();
    (x.y.atan2(x.x), f.translation.vector.z)
}

/// How far off-axis the remainder of a split may be (mm or radians): rounding only.
const SPLIT_TOLERANCE: f64 = 1e-9;

/// Splits `g` (from a joint's frame to the next joint's frame) into the five link parameters
/// `theta, d, a, alpha, beta` (radians, mm) and the turn and slide `(φ, s)` about the next axis:
/// `g = link(…) · Rz(φ) Tz(s)` (see the module documentation for the choice).
pub fn split_link(g: &Frame) -> Result<([f64; 5], (f64, f64)), ArmError> {
    let u = g.rotation * Vector3::z();
    let p = g.translation.vector;
    let sin = u.x.hypot(u.y);
    let params = if !is_parallel(g) {
        // Denavit–Hartenberg: x along the common normal, sign so that theta is in (-90°, 90°].
        let mut x = Vector3::z().cross(&u) / sin;
        if x.x < 0.0 || (x.x == 0.0 && x.y < 0.0) {
            x = -x;
        }
        let theta = x.y.atan2(x.x);
        // Feet of the common normal: on the z axis at d, on the next axis at p + t u.
        let (b, dz, e) = (u.z, p.z, u.dot(&p));
        let denom = 1.0 - b * b;
        let d = (dz - b * e) / denom;
        let t = (b * dz - e) / denom;
        let foot = p + t * u;
        let a = (foot - Vector3::new(0.0, 0.0, d)).dot(&x);
        let y = Vector3::z().cross(&x);
        let alpha = (-u.dot(&y)).atan2(u.z);
        [theta, d, a, alpha, 0.0]
    } else {
        // Hayati: the next axis crosses z = 0 at c.
        let c = p - (p.z / u.z) * u;
        let (mut theta, mut a) = (c.y.atan2(c.x), c.x.hypot(c.y));
        if theta > std::f64::consts::FRAC_PI_2 {
            theta -= std::f64::consts::PI;
            a = -a;
        } else if theta <= -std::f64::consts::FRAC_PI_2 {
            theta += std::f64::consts::PI;
            a = -a;
        }
        let v = rz(-theta) * u;
        let beta = v.x.clamp(-1.0, 1.0).asin();
        let alpha = (-v.y).atan2(v.z);
        [theta, 0.0, a, alpha, beta]
    };
    let [theta, d, a, alpha, beta] = params;
    let rest = link(theta, d, a, alpha, beta).inverse() * g;
    let off = off_axis(&rest);
    if off > SPLIT_TOLERANCE * (1.0 + p.norm()) {
        return Err(ArmError::Split(off));
    }
    Ok((params, turn_and_slide(&rest)))
}

/// The arm of a vendor chain `origins` (mm): exact parameters (see the module documentation),
/// priors `radii` on the free ones, the base at the chain's base frame (refined by registration),
/// the tool point at the flange's origin with no prior.
pub fn chain_to_arm(origins: &[Frame], radii: ImportRadii) -> Result<Arm, ArmError> {
    let n = origins.len();
    if !crate::files::JOINTS.contains(&n) {
        return Err(ArmError::ChainJoints(n));
    }
    // F_1 = base · Rz(φ) Tz(s): the base is the identity when F_1 turns and slides along z.
    let (base, mut carry) = if off_axis(&origins[0]) <= SPLIT_TOLERANCE {
        (Frame::identity(), turn_and_slide(&origins[0]))
    } else {
        (origins[0], (0.0, 0.0))
    };
    let mut joints = Vec::with_capacity(n);
    for i in 0..n {
        let next = origins.get(i + 1).copied().unwrap_or_else(Frame::identity);
        let (params, rest) = split_link(&next)?;
        let [theta, d, a, alpha, beta] = params;
        let (theta, d) = (theta + carry.0, d + carry.1);
        let hayati = is_parallel(&next);
        let (ar, lr) = (radii.angle_deg, radii.length_mm);
        let radius = if i + 1 == n {
            [0.0; 5]
        } else if i == 0 {
            if hayati {
                [0.0, 0.0, lr, ar, ar]
            } else {
                [0.0, 0.0, lr, ar, 0.0]
            }
        } else if hayati {
            [ar, 0.0, lr, ar, ar]
        } else {
            [ar, lr, lr, ar, 0.0]
        };
        if i + 1 == n && (a.abs() > SPLIT_TOLERANCE || alpha.abs() > SPLIT_TOLERANCE) {
            return Err(ArmError::FlangeNotLastFrame);
        }
        joints.push(Joint {
            nominal: [
                wrap_deg(theta.to_degrees()),
                d,
                a,
                wrap_deg(alpha.to_degrees()),
                beta.to_degrees(),
            ],
            radius,
        });
        carry = rest;
    }
    let base = base_parameters(&base);
    // The readers refuse non-finite numbers; this keeps a NaN or an infinity from ever being
    // written as an "exact" import, whatever the chain's origin.
    if joints
        .iter()
        .flat_map(|j| j.nominal)
        .chain(base)
        .any(|v| !v.is_finite())
    {
        return Err(ArmError::NonFiniteChain);
    }
    Ok(Arm {
        joints,
        base,
        base_radius: [0.0; 6],
        tool: [0.0; 3],
        tool_radius: [0.0; 3],
        tool_rotation: None,
    })
}

/// Whether the next joint's axis (`g`'s `z`) is within 45° of parallel to this one's (a Hayati
/// link).
fn is_parallel(g: &Frame) -> bool {
    let u = g.rotation * Vector3::z();
    u.z.abs() > std::f64::consts::FRAC_1_SQRT_2
}

/// An angle in `(−180°, 180°]`.
fn wrap_deg(a: f64) -> f64 {
    let w = a.rem_euclid(360.0);
    if w > 180.0 {
        w - 360.0
    } else {
        w
    }
}

/// The vendor chain (mm) of `arm`'s joints, from its base frame (see the module documentation);
/// the last joint's `a, alpha, beta` must be 0 (the flange is its frame).
pub fn arm_to_chain(arm: &Arm) -> Result<Vec<Frame>, ArmError> {
    let n = arm.joints.len();
    let rad = |j: &Joint| {
        let [theta, d, a, alpha, beta] = j.nominal;
        (
            theta.to_radians(),
            d,
            a,
            alpha.to_radians(),
            beta.to_radians(),
        )
    };
    let last = rad(&arm.joints[n - 1]);
    if last.2 != 0.0 || last.3 != 0.0 || last.4 != 0.0 {
        return Err(ArmError::FlangeOffset(n));
    }
    let mut out = Vec::with_capacity(n);
    let mut before = Frame::identity();
    for j in &arm.joints {
        let (theta, d, a, alpha, beta) = rad(j);
        out.push(before * rz(theta) * trans(0.0, 0.0, d));
        before = trans(a, 0.0, 0.0) * rx(alpha) * ry(beta);
    }
    Ok(out)
}

/// The tracked point of `arm` at joint readings `q` (radians), from [`arm_flange`]: for tests
/// against the model's residual.
pub fn arm_point(arm: &Arm, q: &[f64]) -> [f64; 3] {
    let p = arm_flange(arm, q) * Point3::new(arm.tool[0], arm.tool[1], arm.tool[2]);
    [p.x, p.y, p.z]
}
