//! # calib-gough
//!
//! The Gough (Stewart) platform: the leg model of the paper's equation (3) written once under
//! `#[interval_model]` ([`GoughLeg`]).
#![deny(unsafe_code)]
#![warn(missing_docs)]

pub mod model;

pub use model::{gough_leg, GoughLeg, PARAMETER_NAMES};
