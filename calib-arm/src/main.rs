//! `arm`: certified calibration of a serial arm from laser-tracker data.
#![deny(unsafe_code)]

mod cli;

use clap::Parser;

fn main() {
    calib_pipeline::main_with(|| cli::run(cli::Cli::parse()))
}
