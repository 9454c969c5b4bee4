//! # calib-core
//!
//! Rigorous interval arithmetic ([`Interval`]), the [`Scalar`] abstraction residuals are written
//! over, the [`Model`] trait, the `#[interval_model]` code generator that turns one generic
//! residual into specialized point, interval and Jacobian evaluators at compile time, and the
//! certified kernel: [`certify`] (interval Newton / Krawczyk–LP contraction to a fixed point, with
//! certificates), [`hull`] (the tight certified hull: outer and inner bounds refined until they
//! meet within a tolerance), [`sweep`] (the paper's bisection sweep) and [`pave`] (branch and prune).
//!
//! ```
//! use calib_core::{certify, interval_model, Interval, Model, Scalar, Settings, Status};
//!
//! /// Distance of a point `m` from a circle of centre `(x0, x1)` and radius `x2`.
//! #[interval_model]
//! pub fn circle<S: Scalar>(x: &[S; 3], m: &[S; 2]) -> S {
//!     let [cx, cy, r] = *x;
//!     ((m[0] - cx).sqr() + (m[1] - cy).sqr()).sqrt() - r
//! }
//!
//! let xb = [Interval::new(-0.1, 0.1), Interval::new(-0.1, 0.1), Interval::new(0.9, 1.1)];
//! let mb = [Interval::new(0.99, 1.01), Interval::new(-0.01, 0.01)];
//! let f = Circle.residual_interval(&xb, &mb);
//! assert!(f.contains(Circle.residual(&[0.0, 0.0, 1.0], &[1.0, 0.0])));
//!
//! // Points measured (± 1e-3) on the unit circle: certify the centre and radius.
//! let measurements: Vec<[Interval; 2]> = (0..12)
//!     .map(|k| {
//!         let t = k as f64 * 0.5;
//!         [Interval::mid_rad(t.cos(), 1e-3), Interval::mid_rad(t.sin(), 1e-3)]
//!     })
//!     .collect();
//! let r = certify(&Circle, &xb, &measurements, &Settings::default());
//! assert_eq!(r.status, Status::Consistent);
//! assert!(r.outer[2].contains(1.0) && r.outer[2].rad() < 0.01);
//! ```
#![deny(unsafe_code)]
#![warn(missing_docs)]
// Index loops mirror the matrix notation of the paper (rows k, parameters j) in the numeric code.
#![allow(clippy::needless_range_loop)]

pub mod affine;
pub mod bisection;
pub mod calibrated_point;
pub mod certificate;
pub mod certified_set;
mod certify;
pub mod chebyshev;
pub mod contract;
pub mod coupling;
mod dual;
pub mod existence;
mod first_order;
mod hull;
pub mod interval;
mod jet;
mod jet2;
mod linalg;
pub mod lp;
pub mod maximum;
mod model;
pub mod outliers;
pub mod outlined;
mod parallelotope;
mod push;
pub mod quadratic;
mod scalar;
pub mod second_order;
pub mod set_least_squares;
mod settings;
#[cfg(test)]
mod test_models;

pub use affine::Affine;
pub use bisection::{pave, sweep, Paving, SweepResult};
pub use calib_macros::interval_model;
pub use calibrated_point::{calibrated_point, CalibratedPoint, PointRule};
pub use certificate::{is_certified_consistent, is_consistent_by_corners, is_consistent_point};
pub use certified_set::{
    maximize_over_set, CertifiedPoint, CertifiedSet, Cover, LinearFunction, LinearMax, SetMaximum,
    SetMaximumSettings, SetObjective, SetPiece, SetQuery, SlotQueries,
};
pub use certify::{certify, certify_with, Certification, Status};
pub use chebyshev::{smallest_scale, ScaleEstimate};
pub use contract::{contract, contract_from, is_fixed, Contraction, EmptinessProof, Workspace};
pub use dual::Dual;
pub use hull::{hull, hull_with, Hull};
pub use interval::Interval;
pub use jet::Jet;
pub use jet2::Jet2;
pub use maximum::{maximize, Maximum, MaximumSettings, Objective};
pub use model::{Evaluation, LinearEnclosure, Model, VectorModel};
pub use parallelotope::Parallelotope;
pub use quadratic::Quadratic;
pub use scalar::Scalar;
pub use second_order::{second_order_emptiness, Curvature, SecondOrderCertificate};
pub use settings::{Relaxation, Settings};
