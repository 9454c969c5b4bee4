//! The leg model of the paper's equation (3), over the measurements as the user states them.
//!
//! Per leg, `x = (a_x, a_y, a_z, b_x, b_y, b_z, l)` (base attachment point `a` in the base frame,
//! platform attachment point `b` in the platform frame, leg offset `l`), and per configuration
//! eight measured quantities `M = (p_x, p_y, p_z, u_1, u_2, u_3, θ, L)`: the platform position,
//! its orientation, the leg sensor reading. The residual is
//!
//! `f(x, M) = ||P + R b - a||^2 - (L + l)^2`.
//!
//! How `R` is read from the orientation depends on how it was measured, so there are two
//! residuals, each written once under `#[interval_model]`:
//! * [`gough_leg`] (axis–angle data): `u` is the measured axis, `θ` the measured angle in degrees,
//!   and `R` the rotation by `θ` about the **unit** axis `u / |u|` (Rodrigues' rotation formula).
//!   The error bound on each axis component makes the axis box hold vectors that are not of unit
//!   length; the residual normalises them, as a user means by an axis (the direction is what is
//!   measured; a measured axis is not renormalised before it is written). Every consistency proof
//!   is then against the axis and angle boxes as written, not against an enclosure of the
//!   Rodrigues vectors they give (which is wider: the paper's `ε_q` deduced from `ε_v`, `ε_a`).
//! * [`gough_leg_rodrigues`] (Rodrigues data, columns `q1..q3`): `(u_1, u_2, u_3)` is the
//!   Rodrigues (Gibbs) vector `q = axis * tan(angle / 2)` with `(1 + |q|^2) R(q)` the matrix of
//!   the paper's Section III; `θ` is not read (its box is the point 0 for such data).
//!
//! [`LegModel`] is the residual of one data kind, chosen from the data
//! ([`LegModel::of`]): both take eight measured quantities, so a certified set, a stored set and
//! every kernel call have one type whatever the data kind.

use crate::measurement::{Configuration, Orientation};
use calib_core::{interval_model, CertifiedSet, Evaluation, Interval, Jet2, Model, Scalar};

/// Names of the seven leg parameters, in the order of `x`.
pub const PARAMETER_NAMES: [&str; 7] = ["ax", "ay", "az", "bx", "by", "bz", "l"];

/// Names of the eight measured quantities of axis–angle data, in the order of `M` (Rodrigues
/// data read `q1, q2, q3` for the axis and do not read the angle).
pub const MEASUREMENT_NAMES: [&str; 8] = ["px", "py", "pz", "ax", "ay", "az", "angle_deg", "L"];

/// The residual of one leg in one configuration measured as a position, an axis and an angle
/// (paper eq. 3 with `R` by Rodrigues' rotation formula about the normalised axis):
/// `R b = cos θ b + sin θ (n × b) + (1 - cos θ)(n · b) n` with `n = u / |u|`.
#[interval_model]
pub fn gough_leg<S: Scalar>(x: &[S; 7], m: &[S; 8]) -> S {
    let [ax, ay, az, bx, by, bz, l] = *x;
    let [px, py, pz, u1, u2, u3, angle_deg, len] = *m;
    // θ in radians: the literal is π/180 to 40 digits (enclosed by the macro; the enclosure
    // holds π/180).
    let theta = angle_deg * 0.0174532925199432957692369076848861271344;
    let (c, s) = (theta.cos(), theta.sin());
    let r2 = u1.sqr() + u2.sqr() + u3.sqr();
    // sin θ / |u| and (1 - cos θ)(u · b) / |u|^2: the axis normalised.
    let sn = s / r2.sqrt();
    let k = (1.0 - c) * (u1 * bx + u2 * by + u3 * bz) / r2;
    let rb1 = c * bx + sn * (u2 * bz - u3 * by) + k * u1;
    let rb2 = c * by + sn * (u3 * bx - u1 * bz) + k * u2;
    let rb3 = c * bz + sn * (u1 * by - u2 * bx) + k * u3;
    let e1 = px + rb1 - ax;
    let e2 = py + rb2 - ay;
    let e3 = pz + rb3 - az;
    e1.sqr() + e2.sqr() + e3.sqr() - (len + l).sqr()
}

/// The residual of one leg in one configuration measured as a position and a Rodrigues vector
/// (paper eq. 3 and the `f` of Section III); the angle slot `m[6]` is not read.
#[interval_model]
pub fn gough_leg_rodrigues<S: Scalar>(x: &[S; 7], m: &[S; 8]) -> S {
    let [ax, ay, az, bx, by, bz, l] = *x;
    let [px, py, pz, q1, q2, q3, _, len] = *m;
    let (s1, s2, s3) = (q1.sqr(), q2.sqr(), q3.sqr());
    let d = 1.0 + s1 + s2 + s3;
    // Rows of (1 + |q|^2) R(q) applied to b.
    let rb1 = (1.0 + s1 - s2 - s3) * bx + 2.0 * (q1 * q2 - q3) * by + 2.0 * (q1 * q3 + q2) * bz;
    let rb2 = 2.0 * (q1 * q2 + q3) * bx + (1.0 - s1 + s2 - s3) * by + 2.0 * (q2 * q3 - q1) * bz;
    let rb3 = 2.0 * (q1 * q3 - q2) * bx + 2.0 * (q2 * q3 + q1) * by + (1.0 - s1 - s2 + s3) * bz;
    let e1 = px + rb1 / d - ax;
    let e2 = py + rb2 / d - ay;
    let e3 = pz + rb3 / d - az;
    e1.sqr() + e2.sqr() + e3.sqr() - (len + l).sqr()
}

/// The leg residual of a data kind: what every certification, certified set and proof of a
/// Gough leg evaluates.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum LegModel {
    /// Position, axis, angle (degrees), reading: [`GoughLeg`].
    #[default]
    AxisAngle,
    /// Position, Rodrigues vector, (unread), reading: [`GoughLegRodrigues`].
    Rodrigues,
}

impl LegModel {
    /// The residual of the configurations' orientation kind (axis–angle when there are none).
    ///
    /// # Panics
    /// When the configurations mix axis–angle and Rodrigues orientations (a data file has one
    /// kind; one residual serves every configuration of a leg).
    pub fn of(configs: &[Configuration]) -> LegModel {
        let rodrigues = |c: &Configuration| matches!(c.orientation, Orientation::Rodrigues(_));
        let kind = configs.first().map_or(LegModel::AxisAngle, |c| {
            if rodrigues(c) {
                LegModel::Rodrigues
            } else {
                LegModel::AxisAngle
            }
        });
        assert!(
            configs
                .iter()
                .all(|c| rodrigues(c) == (kind == LegModel::Rodrigues)),
            "the configurations mix axis-angle and Rodrigues orientations"
        );
        kind
    }

    /// The residual a set's measurement boxes were made for: Rodrigues when every box's angle
    /// slot is the point 0 (what [`crate::leg_boxes`] puts there for Rodrigues data; a measured
    /// angle's box is never a point), axis–angle otherwise.
    pub fn of_measurements(boxes: &[[Interval; 8]]) -> LegModel {
        if !boxes.is_empty() && boxes.iter().all(|m| m[6] == Interval::ZERO) {
            LegModel::Rodrigues
        } else {
            LegModel::AxisAngle
        }
    }

    /// The residual of a certified set (see [`LegModel::of_measurements`]).
    pub fn of_set(set: &CertifiedSet<7, 8>) -> LegModel {
        LegModel::of_measurements(set.measurements())
    }

    /// The measured quantities a file stores for this kind, in the order of `M`: all eight for
    /// axis–angle data, all but the unread angle for Rodrigues data.
    pub fn stored_quantities(self) -> &'static [usize] {
        match self {
            LegModel::AxisAngle => &[0, 1, 2, 3, 4, 5, 6, 7],
            LegModel::Rodrigues => &[0, 1, 2, 3, 4, 5, 7],
        }
    }
}

/// Second-order jets over the leg residual's 15 symbols (7 parameters, 8 measured quantities).
type LegJet2 = Jet2<Interval, 15, 120>;

impl LegModel {
    /// Enclosures of the residual's second derivatives `∂²f/∂z_a∂z_b` over the boxes `x`, `m`
    /// for the `symbols` given (`j < 7` parameter `j`, `7 + i` measured quantity `i`), row-major:
    /// the residual evaluated once over second-order jets of intervals (for the certified set's
    /// Taylor rows, [`CertifiedSet::add_second_order_rows`]).
    pub fn hessian_over(
        self,
        x: &[Interval; 7],
        m: &[Interval; 8],
        symbols: &[usize],
    ) -> Option<Vec<Interval>> {
        if symbols.len() > 15 {
            return None;
        }
        let jet = |v: Interval, k: usize| match symbols.iter().position(|&s| s == k) {
            Some(a) => LegJet2::variable(v, a),
            None => LegJet2::constant(v),
        };
        let xs: [LegJet2; 7] = core::array::from_fn(|j| jet(x[j], j));
        let ms: [LegJet2; 8] = core::array::from_fn(|i| jet(m[i], 7 + i));
        let f = match self {
            LegModel::AxisAngle => gough_leg(&xs, &ms),
            LegModel::Rodrigues => gough_leg_rodrigues(&xs, &ms),
        };
        let n = symbols.len();
        Some(
            (0..n)
                .flat_map(|a| (0..n).map(move |b| (a, b)))
                .map(|(a, b)| f.second(a, b))
                .collect(),
        )
    }
}

/// Calls the residual of the kind.
macro_rules! dispatch {
    ($self:ident, $method:ident($($arg:expr),*)) => {
        match $self {
            LegModel::AxisAngle => GoughLeg.$method($($arg),*),
            LegModel::Rodrigues => GoughLegRodrigues.$method($($arg),*),
        }
    };
}

impl Model<7, 8> for LegModel {
    #[inline]
    fn residual(&self, x: &[f64; 7], m: &[f64; 8]) -> f64 {
        dispatch!(self, residual(x, m))
    }
    #[inline]
    fn residual_interval(&self, x: &[Interval; 7], m: &[Interval; 8]) -> Interval {
        dispatch!(self, residual_interval(x, m))
    }
    #[inline]
    fn jacobian_x(&self, x: &[f64; 7], m: &[f64; 8]) -> [f64; 7] {
        dispatch!(self, jacobian_x(x, m))
    }
    #[inline]
    fn jacobian_m(&self, x: &[f64; 7], m: &[f64; 8]) -> [f64; 8] {
        dispatch!(self, jacobian_m(x, m))
    }
    #[inline]
    fn jacobian_x_interval(&self, x: &[Interval; 7], m: &[Interval; 8]) -> [Interval; 7] {
        dispatch!(self, jacobian_x_interval(x, m))
    }
    #[inline]
    fn jacobian_m_interval(&self, x: &[Interval; 7], m: &[Interval; 8]) -> [Interval; 8] {
        dispatch!(self, jacobian_m_interval(x, m))
    }
    #[inline]
    fn evaluate(&self, x: &[f64; 7], m: &[f64; 8]) -> Evaluation<f64, 7, 8> {
        dispatch!(self, evaluate(x, m))
    }
    #[inline]
    fn evaluate_interval(
        &self,
        x: &[Interval; 7],
        m: &[Interval; 8],
    ) -> Evaluation<Interval, 7, 8> {
        dispatch!(self, evaluate_interval(x, m))
    }
}
