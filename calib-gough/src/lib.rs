//! # calib-gough
//!
//! The Gough (Stewart) platform: the leg model of the paper's equation (3) written once under
//! `#[interval_model]` ([`GoughLeg`]), geometry and inverse kinematics, simulated data, and
//! measurement boxes.
#![deny(unsafe_code)]
#![warn(missing_docs)]

pub mod geometry;
pub mod measurement;
pub mod model;
pub mod simulate;

pub use geometry::{leg_reading, Leg, Pose};
pub use measurement::leg_boxes;
pub use model::{gough_leg, GoughLeg, PARAMETER_NAMES};
pub use simulate::{builtin_hexapod, simulate, Configuration, Simulation, Uncertainty};
