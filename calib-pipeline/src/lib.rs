//! # calib-pipeline
//!
//! The layer between the certified kernel (`calib-core`) and a robot (`calib-gough`,
//! `calib-arm`): what every robot's calibration shares and no robot owns. A robot crate parses its
//! own files, names its parameters and writes its residual; the errors it reports for bad input
//! ([`DataError`]: file, line, field) and the way outputs are written ([`write_atomically`]) are
//! the same for every robot.
#![deny(unsafe_code)]
#![warn(missing_docs)]

pub mod accuracy;
pub mod calibrated;
pub mod cli;
pub mod design;
mod error;
pub mod error_scale;
pub mod html;
pub mod identify;
pub mod lsq;
mod outcome;
mod outlier_budget;
mod output;
pub mod report;
pub mod stored_set;
mod table;
pub mod verdict;

pub use error::{
    finite_number, line_at, read_text, toml_error, DataError, OptionError, ParseError,
    PipelineError, MAX_MAGNITUDE,
};
pub use outcome::{certify_model, is_fixed, Depth, ModelCertification, Outcome};
pub use outlier_budget::{smallest_consistent, OutlierBudget};
#[doc(hidden)] // for the package's tests (tests/unit)
pub use output::is_closed_output;
pub use output::{
    check_hull_options, check_outputs, exit_quietly_when_output_closes, main_with,
    write_atomically, CLOSED_OUTPUT_STATUS,
};
pub use table::{parse_named_columns, parse_number_table, Dialect, NumberTable};
