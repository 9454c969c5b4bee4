//! The integration binary of calib-pipeline: its unit tests, kept out of the library so that
//! `cargo test` compiles it once.

mod unit;
