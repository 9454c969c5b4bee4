//! The library's own unit tests, kept out of the library so that `cargo test` compiles it once.
#![allow(clippy::needless_range_loop)] // indices follow the math, as in the library

mod accuracy_directions;
mod calibrated;
mod error;
mod error_scale;
mod joint_space;
mod params;
mod pose_orientation;
mod register;
mod report_page;
mod robot;
mod second_order;
mod simulate;
mod tracker_file;
mod units;
mod vendor;
mod vendor_ur_yaml;
mod vendor_urdf;
mod write;
