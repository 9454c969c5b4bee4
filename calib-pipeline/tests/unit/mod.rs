//! The library's own unit tests, kept out of the library so that `cargo test` compiles it once.

mod accuracy;
mod calibrated;
mod design;
mod error;
mod error_scale;
mod html;
mod identify;
mod lsq;
mod outcome;
mod outlier_budget;
mod output;
mod stored_set;
mod table;
mod verdict;
