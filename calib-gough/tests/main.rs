//! Every integration test of this package, one module per file, linked into one binary: each
//! test binary links (and monomorphises the kernel for) its models anew, so one binary instead
//! of one per file keeps `cargo test --workspace` within its budget, and lets the tests of
//! every file share the cores.

#[path = "../../calib-core/tests/support/scratch_dir.rs"]
mod scratch_dir;
mod support;

mod accuracy;
mod carry_over;
mod cli;
mod design;
mod pose_error;
mod predict;
mod report_page;
mod stated_bounds;
mod unit;
