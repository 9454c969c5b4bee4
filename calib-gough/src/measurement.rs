//! Measured configurations, their error bounds, and the measurement boxes `M_k` of one leg.

use crate::geometry::Pose;
use calib_core::Interval;

/// How a configuration's orientation was measured.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Orientation {
    /// A unit axis (not renormalised after measurement) and an angle in degrees.
    AxisAngle {
        /// The measured axis.
        axis: [f64; 3],
        /// The measured angle, degrees.
        angle_deg: f64,
    },
    /// The Rodrigues vector `q = axis * tan(angle / 2)` directly.
    Rodrigues([f64; 3]),
}

/// One measured configuration: platform position, orientation and the leg readings.
#[derive(Clone, Debug, PartialEq)]
pub struct Configuration {
    /// Platform position (cm).
    pub p: [f64; 3],
    /// Platform orientation.
    pub orientation: Orientation,
    /// Leg readings (cm), one per leg.
    pub lengths: Vec<f64>,
}

impl Configuration {
    /// The platform at `pose` with no leg readings (a pose to predict at).
    pub fn at_pose(pose: &Pose) -> Configuration {
        Configuration {
            p: pose.p,
            orientation: Orientation::AxisAngle {
                axis: pose.axis,
                angle_deg: pose.angle_deg,
            },
            lengths: Vec::new(),
        }
    }
}

/// Half-widths of the measurement errors (cm, unitless, degrees).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Uncertainty {
    /// Each position coordinate.
    pub pos: f64,
    /// Each leg reading.
    pub len: f64,
    /// Each component of the rotation axis (axis-angle data).
    pub axis: f64,
    /// The rotation angle in degrees (axis-angle data).
    pub angle_deg: f64,
    /// Each Rodrigues component (Rodrigues data).
    pub q: f64,
}

impl Uncertainty {
    /// The paper's Section V error bounds: 5 µm on positions, leg readings and axis components,
    /// 1e-3 degree on the angle.
    pub const PAPER: Uncertainty = Uncertainty {
        pos: 5e-4,
        len: 5e-4,
        axis: 5e-6,
        angle_deg: 1e-3,
        q: 0.0,
    };

    /// Every half-width set to `h` (for exact-data experiments).
    pub fn uniform(h: f64) -> Uncertainty {
        Uncertainty {
            pos: h,
            len: h,
            axis: h,
            angle_deg: h,
            q: h,
        }
    }
}

/// An enclosure of `[v - h, v + h]` for a value `v` and a half-width `h` read from decimal text
/// (a measurement and its error bound, or a nominal parameter and its radius): `v` and `h` are
/// widened by one ulp first (the decimals may differ from the parsed doubles by half an ulp), then
/// the sum is rounded outward.
pub fn measured(v: f64, h: f64) -> Interval {
    Interval::new(v.next_down(), v.next_up()) + Interval::new(-h.next_up(), h.next_up())
}

/// The boxes `M_k` of leg `leg` (0-based), in the order of [`crate::LegModel`]'s `M`, as the
/// user states them: position ± `pos`; axis–angle data: each axis component ± `axis` and the
/// angle ± `angle_deg`; Rodrigues data: each `q` component ± `q` and the point 0 in the angle slot
/// (not read by [`crate::GoughLegRodrigues`]); the reading ± `len`. All outward rounded.
pub fn leg_boxes(configs: &[Configuration], u: &Uncertainty, leg: usize) -> Vec<[Interval; 8]> {
    configs
        .iter()
        .map(|c| {
            let (r, angle) = match c.orientation {
                Orientation::AxisAngle { axis, angle_deg } => (
                    axis.map(|v| measured(v, u.axis)),
                    measured(angle_deg, u.angle_deg),
                ),
                Orientation::Rodrigues(q) => (q.map(|v| measured(v, u.q)), Interval::ZERO),
            };
            let p = c.p.map(|v| measured(v, u.pos));
            [
                p[0],
                p[1],
                p[2],
                r[0],
                r[1],
                r[2],
                angle,
                measured(c.lengths[leg], u.len),
            ]
        })
        .collect()
}

/// The measured values of leg `leg` (0-based) in the order of [`crate::LegModel`]'s `M` (the
/// centres of [`leg_boxes`]; 0 in a Rodrigues configuration's angle slot).
pub fn leg_values(configs: &[Configuration], leg: usize) -> Vec<[f64; 8]> {
    configs
        .iter()
        .map(|c| {
            let (r, angle) = match c.orientation {
                Orientation::AxisAngle { axis, angle_deg } => (axis, angle_deg),
                Orientation::Rodrigues(q) => (q, 0.0),
            };
            [
                c.p[0],
                c.p[1],
                c.p[2],
                r[0],
                r[1],
                r[2],
                angle,
                c.lengths[leg],
            ]
        })
        .collect()
}
