//! `gough`: certified calibration of a Gough (Stewart) platform from the command line.
#![deny(unsafe_code)]

mod cli;

use clap::Parser;

fn main() {
    calib_pipeline::exit_quietly_when_output_closes();
    let args = cli::Cli::parse();
    let code = match cli::run(args) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e}");
            1
        }
    };
    std::process::exit(code);
}
