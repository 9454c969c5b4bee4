//! Every integration test of this package, one module per file, linked into one binary: each
//! test binary links (and monomorphises the kernel for) its models anew, so one binary instead
//! of one per file keeps `cargo test --workspace` within its budget, and lets the tests of
//! every file share the cores. Modules whose `#[interval_model]` functions are only used through
//! their generated evaluators are `pub`, so that those functions count as used.

mod support;

pub mod certified_set;
mod curvature_rows;
pub mod custom_models;
mod interval_ops;
mod maximum;
pub mod second_order;
pub mod small_models;
pub mod vector_models;
