//! An arm's description: nominal geometry and prior half-widths per parameter (the files' units:
//! mm and degrees), and the initial box in the model's units.

use crate::params;
use crate::units::deg_to_rad;
use calib_core::Interval;

/// One joint: `theta, d, a, alpha, beta` (degrees and mm) and their prior half-widths (0 fixes a
/// parameter at its nominal value).
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// Nominal `theta_deg, d, a, alpha_deg, beta_deg`.
    pub nominal: [f64; 5],
    /// Half-widths in the same order and units.
    pub radius: [f64; 5],
}

/// An arm: joints from base to flange, the base transform and the tool point (mm and degrees).
#[derive(Clone, Debug, PartialEq)]
pub struct Arm {
    /// Joints, base to flange.
    pub joints: Vec<Joint>,
    /// Nominal `x, y, z` (mm) and `rx, ry, rz` (degrees) of the base in the tracker frame.
    pub base: [f64; 6],
    /// Half-widths of the base parameters.
    pub base_radius: [f64; 6],
    /// Nominal tool point in the flange frame (mm).
    pub tool: [f64; 3],
    /// Half-widths of the tool point.
    pub tool_radius: [f64; 3],
    /// The tool frame's rotation on the flange, for 6-DoF measurements ([`crate::pose`]); `None`
    /// for an arm tracked by its point only.
    pub tool_rotation: Option<ToolRotation>,
}

/// The rotation of the measured frame on the flange, `R_tool = Rz(rz) Ry(ry) Rx(rx)` (the base's
/// convention), and its prior: what a 6-DoF probe's orientation adds to the parameters
/// (`tool_rx, tool_ry, tool_rz`, see [`crate::pose`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToolRotation {
    /// Nominal `rx, ry, rz`, degrees.
    pub rpy_deg: [f64; 3],
    /// Their prior half-widths, degrees (0 fixes one).
    pub radius: [f64; 3],
}

impl Arm {
    /// The same arm with every prior half-width (joints, base, tool) multiplied by `factor`: a
    /// tighter or looser prior box around the same nominal geometry.
    ///
    /// ```
    /// let arm = calib_arm::builtin_arm();
    /// let tight = arm.clone().with_radii_scaled(0.05);
    /// assert_eq!(tight.nominal(), arm.nominal());
    /// assert_eq!(tight.joints[0].radius[0], 0.05 * arm.joints[0].radius[0]);
    /// ```
    pub fn with_radii_scaled(mut self, factor: f64) -> Arm {
        for j in &mut self.joints {
            j.radius = j.radius.map(|r| r * factor);
        }
        self.base_radius = self.base_radius.map(|r| r * factor);
        self.tool_radius = self.tool_radius.map(|r| r * factor);
        if let Some(t) = &mut self.tool_rotation {
            t.radius = t.radius.map(|r| r * factor);
        }
        self
    }

    /// The same arm (priors' half-widths, fixed parameters) with the nominal values `x`, in model
    /// order and the files' units (degrees and mm, see [`params::names`]); `x` has
    /// [`params::count`] values.
    pub fn with_nominal(&self, x: &[f64]) -> Arm {
        let mut out = self.clone();
        let n = self.joints.len();
        for (i, j) in out.joints.iter_mut().enumerate() {
            j.nominal.copy_from_slice(&x[5 * i..5 * i + 5]);
        }
        out.base.copy_from_slice(&x[5 * n..5 * n + 6]);
        out.tool.copy_from_slice(&x[5 * n + 6..5 * n + 9]);
        out
    }

    /// Every parameter's nominal value in model order (degrees and mm), see [`params::names`].
    pub fn nominal(&self) -> Vec<f64> {
        self.collect(|j| j.nominal, self.base, self.tool)
    }

    /// Every parameter's prior half-width in model order (degrees and mm).
    pub fn radius(&self) -> Vec<f64> {
        self.collect(|j| j.radius, self.base_radius, self.tool_radius)
    }

    fn collect(
        &self,
        joint: impl Fn(&Joint) -> [f64; 5],
        base: [f64; 6],
        tool: [f64; 3],
    ) -> Vec<f64> {
        let mut v: Vec<f64> = self.joints.iter().flat_map(joint).collect();
        v.extend(base);
        v.extend(tool);
        v
    }

    /// Which parameters are free (a positive prior half-width).
    pub fn free(&self) -> Vec<bool> {
        self.radius().iter().map(|r| *r > 0.0).collect()
    }

    /// The initial box `nominal ± radius` in the model's units (radians for angles), enclosing
    /// the decimal values outward; fixed parameters are point intervals of their nominal value
    /// converted to radians (an interval of a few ulps for angles).
    pub fn initial_box(&self) -> Vec<Interval> {
        let units = params::names(self.joints.len());
        self.nominal()
            .iter()
            .zip(self.radius())
            .zip(&units)
            .map(|((v, r), (_, unit))| {
                let deg = Interval::mid_rad(*v, r);
                match unit {
                    params::Unit::Deg => deg_to_rad(deg),
                    params::Unit::Mm => deg,
                }
            })
            .collect()
    }
}

/// The built-in arm: the public nominal geometry of a common six-axis collaborative arm (three
/// parallel middle axes: a UR5's `d1 = 89.159, a2 = -425, a3 = -392.25, d4 = 109.15,
/// d5 = 94.65, d6 = 82.3` mm), a base 1.2 m from the tracker, a tool point 55 mm out, and the
/// identifiable default parameter set: 27 free parameters. Fixed, and why: `theta1, d1`
/// (indistinguishable from `base_rz, base_z`), `beta1` (joint 2 is not parallel to joint 1),
/// `d2, d3` (consecutive parallel axes: only their sum with `d4` is seen), `beta4, beta5` (the
/// next axis is not parallel), and all of joint 6 (with a tracked point and no orientation, the
/// flange parameters trade off against the tool point).
pub fn builtin_arm() -> Arm {
    let joint = |nominal: [f64; 5], radius: [f64; 5]| Joint { nominal, radius };
    Arm {
        joints: vec![
            joint([0.0, 89.159, 0.0, 90.0, 0.0], [0.0, 0.0, 0.5, 0.05, 0.0]),
            joint([0.0, 0.0, -425.0, 0.0, 0.0], [0.05, 0.0, 0.5, 0.05, 0.05]),
            joint([0.0, 0.0, -392.25, 0.0, 0.0], [0.05, 0.0, 0.5, 0.05, 0.05]),
            joint([0.0, 109.15, 0.0, 90.0, 0.0], [0.05, 0.5, 0.5, 0.05, 0.0]),
            joint([0.0, 94.65, 0.0, -90.0, 0.0], [0.05, 0.5, 0.5, 0.05, 0.0]),
            joint([0.0, 82.3, 0.0, 0.0, 0.0], [0.0; 5]),
        ],
        base: [1200.0, 300.0, -250.0, 0.4, -0.3, 25.0],
        base_radius: [1.0, 1.0, 1.0, 0.1, 0.1, 0.1],
        tool: [15.0, -10.0, 55.0],
        tool_radius: [0.5, 0.5, 0.5],
        tool_rotation: None,
    }
}
