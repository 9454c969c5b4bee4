//! # certicalib
//!
//! Certified calibration of robots — Gough (Stewart) platforms and serial arms: for measurements
//! known within error bounds, the set of kinematic parameters consistent with the data, proved
//! (an outer box containing every consistent parameter vector, inner bounds spanned by vectors
//! each proved consistent, or a proof that the data are inconsistent). This facade re-exports
//! every crate of the workspace:
//!
//! - [`calib_core`], the kernel: rigorous interval and affine arithmetic, the [`Model`] and
//!   [`VectorModel`] traits with the `#[interval_model]` code generator (from `calib-macros`,
//!   re-exported as [`calib_core::interval_model`]), and the certified methods: `certify` (the
//!   paper's interval Newton / Krawczyk–LP contraction), `hull` (the tight certified hull),
//!   `sweep`, `pave`, `maximize`, the certified set and its queries;
//! - [`calib_pipeline`], the robot-agnostic layer: a certified sub-problem and its verdict in
//!   words, identifiability, least squares, the error scale, outlier budgets, measurement design,
//!   JSON reports and HTML certificates, data-file errors that name file, line and field;
//! - [`calib_gough`], the Gough (Stewart) platform, a parallel robot: the leg model of the
//!   paper's equation (3), its files, simulation, least squares, predictions and accuracy over
//!   the workspace (the `gough` command);
//! - [`calib_arm`], serial arms (Denavit–Hartenberg plus Hayati parameters, base transform, tool
//!   point; 3 to 7 joints; 6-DoF probes): laser-tracker files, UR's YAML and URDF, registration,
//!   predictions and accuracy over the joint space (the `arm` command).
//!
//! The guide (tutorials, concepts, how-to guides, the command reference, the architecture) is the
//! mdBook in the repository's `docs/`. The README follows; its code example runs as a doc test.
//!
//! [`Model`]: calib_core::Model
//! [`VectorModel`]: calib_core::VectorModel
#![doc = include_str!("../README.md")]
#![deny(unsafe_code)]
#![warn(missing_docs)]

pub use calib_arm;
pub use calib_core;
pub use calib_gough;
pub use calib_pipeline;

/// The guide's page on writing a model (`docs/src/howto/own-model.md`): its examples run as doc
/// tests, so the page cannot drift from the code. Compiled only when collecting doc tests.
#[cfg(doctest)]
#[doc = include_str!("../docs/src/howto/own-model.md")]
mod guide_own_model {}
