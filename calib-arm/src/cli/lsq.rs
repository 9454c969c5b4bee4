//! `arm lsq`.

use super::DataFiles;
use calib_arm::certification::{fit_arm, names, units};
use calib_arm::files::{read_measurements, read_robot};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    files: DataFiles,
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    let arm = read_robot(&a.files.robot)?;
    let data = read_measurements(&a.files.measurements, arm.joints.len())?;
    let fit = fit_arm(&arm, &data.readings)?;
    let units = units(arm.joints.len());
    let nominal = arm.nominal();
    println!(
        "{:<9} {:<4} {:>14} {:>14} {:>12}",
        "parameter", "unit", "nominal", "fit", "change"
    );
    let names = names(arm.joints.len());
    for (j, name) in names.iter().enumerate() {
        if !arm.free()[j] {
            continue;
        }
        println!(
            "{:<9} {:<4} {:>14.5} {:>14.5} {:>12.5}",
            name,
            units[j],
            nominal[j],
            fit.x[j],
            fit.x[j] - nominal[j]
        );
    }
    println!(
        "residuals: rms {:.4} mm, max {:.4} mm over every coordinate of {} configurations ({}, {} evaluations)",
        fit.rms,
        fit.max_abs,
        data.readings.len(),
        if fit.converged { "converged" } else { "did not converge" },
        fit.evaluations
    );
    Ok(0)
}
