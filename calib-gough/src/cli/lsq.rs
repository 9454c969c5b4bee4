//! `gough lsq`.

use super::DataFiles;
use calib_gough::files::{read_measurements, read_robot};
use calib_gough::lsq::fit_legs;
use calib_gough::PARAMETER_NAMES;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    files: DataFiles,
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    let robot = read_robot(&a.files.robot)?;
    let data = read_measurements(&a.files.measurements, robot.len())?;
    let fits = fit_legs(&robot, &data.configs);
    print!("{:<4} {:<9}", "leg", "converged");
    for n in PARAMETER_NAMES {
        print!(" {n:>10}");
    }
    println!(" {:>10} {:>12}", "rms f", "max |dL| cm");
    for (leg, f) in fits.iter().enumerate() {
        print!("{:<4} {:<9}", leg + 1, f.converged);
        for v in f.x {
            print!(" {v:>10.4}");
        }
        println!(" {:>10.2e} {:>12.2e}", f.rms, f.max_length_error);
    }
    Ok(0)
}
