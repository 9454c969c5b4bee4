//! `gough`: certified calibration of a Gough (Stewart) platform from the command line.
#![deny(unsafe_code)]

mod cli;

use clap::Parser;

fn main() {
    calib_pipeline::main_with(|| cli::run(cli::Cli::parse()))
}
