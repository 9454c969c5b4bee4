//! # certicalib
//!
//! Certified calibration of parallel robots. This facade re-exports the three crates:
//! [`calib_core`] (interval arithmetic, the `#[interval_model]` code generator, the certified kernel)
//! and [`calib_gough`] (the Gough platform model and tools).
//!
//! The README follows (its code examples run as doc tests).
#![doc = include_str!("../README.md")]
#![deny(unsafe_code)]
#![warn(missing_docs)]

pub use calib_core;
pub use calib_gough;
