//! # calib-arm
//!
//! Serial arms calibrated from laser-tracker data: the kinematic model (standard
//! Denavit–Hartenberg plus Hayati's `beta`, a base transform and a tool point) written once under
//! `#[interval_model]` as a three-row [`calib_core::VectorModel`] ([`model`]), parameter names
//! and units ([`params`]), and the conversions between the files' degrees and the model's radians
//! ([`units`]); the files read ([`files`]) and written ([`mod@write`]), simulated data ([`mod@simulate`]),
//! and the arm's use of the robot-agnostic pipeline ([`certification`]: identifiability,
//! certification, least squares, in the files' units); the calibrated robot file
//! ([`calibrated`]) and the accuracy certificate over a joint box ([`accuracy`], [`joint_space`]).
//! The library functions report their errors as [`ArmError`] (messages name the option as `arm`
//! spells it, or the file and field). The `arm` binary is the command line.
#![deny(unsafe_code)]
#![warn(missing_docs)]
#![allow(clippy::needless_range_loop)]

pub mod accuracy;
pub mod calibrated;
pub mod carry;
pub mod certification;
pub mod design;
mod error;
pub mod error_scale;
pub mod files;
pub mod joint_space;
pub mod model;
pub mod params;
pub mod pose;
pub mod predict;
pub mod register;
pub mod report_page;
pub mod robot;
pub mod simulate;
pub mod tracker_file;
pub mod units;
pub mod vendor;
pub mod write;

pub use error::ArmError;
pub use model::Arm7Point;
pub use robot::{builtin_arm, Arm, Joint};
pub use simulate::{simulate, Simulation};
