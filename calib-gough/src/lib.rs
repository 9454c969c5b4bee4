//! # calib-gough
//!
//! The Gough (Stewart) platform: the leg model of the paper's equation (3) written once under
//! `#[interval_model]` per orientation kind ([`GoughLeg`] for axis–angle data,
//! [`GoughLegRodrigues`] for Rodrigues data, [`LegModel`] either), geometry and inverse
//! kinematics, simulated data, and measurement boxes.
#![deny(unsafe_code)]
#![warn(missing_docs)]
// Index loops mirror the paper's notation (legs i, parameters j, configurations k).
#![allow(clippy::needless_range_loop)]

pub mod accuracy;
pub mod calibrated;
pub mod carry_over;
pub mod certification;
pub mod design;
mod error;
pub mod error_scale;
pub mod files;
pub mod geometry;
pub mod lsq;
pub mod measurement;
pub mod model;
pub mod plot;
pub mod predict;
pub mod report;
pub mod report_page;
pub mod simulate;
pub mod verdict;
pub mod workspace;

pub use error::GoughError;
pub use geometry::{leg_reading, Leg, Pose};
pub use measurement::{leg_boxes, leg_values, Configuration, Orientation, Uncertainty};
pub use model::{
    gough_leg, gough_leg_rodrigues, GoughLeg, GoughLegRodrigues, LegModel, MEASUREMENT_NAMES,
    PARAMETER_NAMES,
};
pub use simulate::{builtin_hexapod, simulate, Simulation};
