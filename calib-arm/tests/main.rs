//! Every integration test of this package, one module per file, linked into one binary: each
//! test binary links (and monomorphises the kernel for) its models anew, so one binary instead
//! of one per file keeps `cargo test --workspace` within its budget, and lets the tests of
//! every file share the cores.

mod common;
#[path = "../../calib-core/tests/support/mod.rs"]
mod core_support;
#[path = "../../calib-core/tests/support/scratch_dir.rs"]
mod scratch_dir;

mod accuracy;
mod carry;
mod cli;
mod design;
mod files;
mod identify;
mod kernel;
mod model;
mod pose;
mod real_ur10;
mod unit;
