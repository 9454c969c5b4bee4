//! Gough platform geometry: legs, poses, Rodrigues rotations, inverse kinematics (paper eq. 3).

use calib_core::Interval;

/// One leg: base attachment point `a` (base frame), platform attachment point `b` (platform frame)
/// and length offset `l` (cm). As a parameter vector: `(a_x, a_y, a_z, b_x, b_y, b_z, l)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Leg {
    /// Base attachment point.
    pub a: [f64; 3],
    /// Platform attachment point.
    pub b: [f64; 3],
    /// Leg length offset.
    pub l: f64,
}

impl Leg {
    /// The parameter vector `x = (a, b, l)`.
    pub fn params(&self) -> [f64; 7] {
        [
            self.a[0], self.a[1], self.a[2], self.b[0], self.b[1], self.b[2], self.l,
        ]
    }

    /// The leg from a parameter vector.
    pub fn from_params(x: &[f64; 7]) -> Leg {
        Leg {
            a: [x[0], x[1], x[2]],
            b: [x[3], x[4], x[5]],
            l: x[6],
        }
    }
}

/// A platform pose: position `p` (cm) and rotation as a unit `axis` and an `angle_deg`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// Platform position in the base frame.
    pub p: [f64; 3],
    /// Rotation axis (unit length).
    pub axis: [f64; 3],
    /// Rotation angle in degrees.
    pub angle_deg: f64,
}

impl Pose {
    /// The Rodrigues (Gibbs) vector `q = axis * tan(angle / 2)`.
    pub fn rodrigues(&self) -> [f64; 3] {
        let t = (self.angle_deg.to_radians() / 2.0).tan();
        self.axis.map(|v| v * t)
    }
}

/// `R(q) v` with `(1 + |q|^2) R(q)` the matrix of the paper's Section III.
pub fn rotate(q: &[f64; 3], v: &[f64; 3]) -> [f64; 3] {
    let [q1, q2, q3] = *q;
    let d = 1.0 + q1 * q1 + q2 * q2 + q3 * q3;
    let r = [
        [
            1.0 + q1 * q1 - q2 * q2 - q3 * q3,
            2.0 * (q1 * q2 - q3),
            2.0 * (q1 * q3 + q2),
        ],
        [
            2.0 * (q1 * q2 + q3),
            1.0 - q1 * q1 + q2 * q2 - q3 * q3,
            2.0 * (q2 * q3 - q1),
        ],
        [
            2.0 * (q1 * q3 - q2),
            2.0 * (q2 * q3 + q1),
            1.0 - q1 * q1 - q2 * q2 + q3 * q3,
        ],
    ];
    core::array::from_fn(|i| (r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2]) / d)
}

/// The sensor reading of `leg` at `pose`: `L = ||P + R b - a|| - l` (paper eq. 3).
pub fn leg_reading(leg: &Leg, pose: &Pose) -> f64 {
    let rb = rotate(&pose.rodrigues(), &leg.b);
    let d: [f64; 3] = core::array::from_fn(|i| pose.p[i] + rb[i] - leg.a[i]);
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() - leg.l
}

/// An enclosure of the Rodrigues vectors `axis * tan(angle / 2)` for every axis in the box `axis`
/// and every angle (degrees) in `angle_deg` (outward rounded; `π/180` enclosed).
pub fn rodrigues_box(axis: &[Interval; 3], angle_deg: Interval) -> [Interval; 3] {
    let half_angle = angle_deg * Interval::PI / Interval::point(360.0);
    let t = half_angle.tan();
    axis.map(|a| a * t)
}
