//! The library's own unit tests, kept out of the library so that `cargo test` compiles it once.
#![allow(clippy::needless_range_loop)] // indices follow the math, as in the library

mod accuracy_pose_bound;
mod accuracy_pose_error;
mod design;
mod error;
mod error_scale;
mod files;
mod lsq;
mod model;
mod plot;
mod report;
mod verdict;
mod workspace;
