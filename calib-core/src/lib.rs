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

// The modules group the crate by concept, each using only those before it in this list: number
// types (`num`), models (`model`), linear programs (`lp`), proofs about points and boxes (`proof`),
// the certified kernel (`kernel`), and the certified set with its questions (`set`). They are
// private: every public item is re-exported below, once.
mod kernel;
mod lp;
mod model;
mod num;
mod proof;
mod set;
#[cfg(test)]
mod test_models;

pub use calib_macros::interval_model;

// Number types.
pub use num::affine::Affine;
pub use num::dual::Dual;
pub use num::hessian_jet::Jet2;
pub use num::interval::Interval;
pub use num::jet::Jet;
pub use num::quadratic::Quadratic;
pub use num::scalar::Scalar;

// Models.
pub use model::curvature::{Curvature, MAX_CURVATURE_SYMBOLS};
pub use model::{Evaluation, LinearEnclosure, Model, VectorModel};

// Linear programs.
pub use lp::{
    proves_infeasible, safe_lower_bound, ClarabelLp, DenseSimplex, LpBackend, LpEngine, LpMemory,
    LpStatus, Polyhedron,
};

// Proofs.
pub use proof::chebyshev::{chebyshev_weights, smallest_scale, ScaleEstimate};
pub use proof::consistency::{
    is_certified_consistent, is_consistent_by_corners, is_consistent_point,
};
pub use proof::second_order::{
    combination_lower_bound, second_order_emptiness, SecondOrderCertificate,
};

// The kernel.
pub use kernel::bisection::{pave, split_widest, sweep, Paving, SweepResult};
pub use kernel::certify::{certify, certify_with, Certification, Status};
pub use kernel::contract::{
    contract, contract_from, is_fixed, Contraction, EmptinessProof, Workspace,
};
pub use kernel::cover::Cover;
pub use kernel::hull::{hull, hull_with, Hull};
pub use kernel::outliers::is_spread;
pub use kernel::settings::{Relaxation, Settings};

// The certified set and its questions.
pub use set::calibrated_point::{
    calibrated_point, narrowed, CalibratedPoint, PointRule, POINT_MARGINS,
};
pub use set::certified_set::{
    maximize_over_set, CertifiedPoint, CertifiedSet, LinearFunction, LinearMax, SetMaximum,
    SetMaximumSettings, SetObjective, SetPiece, SetQuery, SlotQueries, DEFAULT_MAX_PIECES,
};
pub use set::curvature_rows::HessianOverBox;
pub use set::least_squares::{least_squares_in_set, SetFit, CROSS_VALIDATION_FOLDS, PRIOR_WEIGHTS};
pub use set::maximum::{
    bracket_ratio, maximize, maximize_over_list, Maximum, MaximumSettings, Objective, Ranked,
};
pub use set::parallelotope::Parallelotope;

/// What the code `#[interval_model]` generates calls: not part of the API, and versioned so that a
/// change in it cannot silently meet code generated for another version. Not for direct use.
#[doc(hidden)]
pub mod __private_v1 {
    pub use crate::model::arithmetic::{add, cos, div, mul, neg, powi, sin, sqr, sqrt, sub, tan};
    pub use crate::model::curvature::{second_derivatives, third_derivatives_along, Third};
    pub use crate::model::{affine_inputs, linear_enclosures};
}
