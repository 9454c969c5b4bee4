//! # calib-core
//!
//! Rigorous interval arithmetic ([`Interval`]), the [`Scalar`] abstraction residuals are written
//! over, the [`Model`] trait, and the `#[interval_model]` code generator that turns one generic
//! residual into specialized point, interval and Jacobian evaluators at compile time.
//!
//! ```
//! use calib_core::{interval_model, Interval, Model, Scalar};
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
//! ```
#![deny(unsafe_code)]
#![warn(missing_docs)]

mod dual;
pub mod interval;
mod model;
mod scalar;

pub use calib_macros::interval_model;
pub use dual::Dual;
pub use interval::Interval;
pub use model::{Evaluation, Model};
pub use scalar::Scalar;
