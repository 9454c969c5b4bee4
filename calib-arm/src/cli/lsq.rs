//! `arm lsq`.

use super::DataFiles;
use calib_arm::certification::{fit_arm, is_consistent_arm, names, units};
use calib_arm::files::{read_robot, read_uncertainty};
use calib_pipeline::lsq::Fit;
use calib_pipeline::write_atomically;
use std::path::{Path, PathBuf};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    files: DataFiles,
    /// Write the fit as JSON: per parameter nominal, fit and whether it left the prior box;
    /// residual statistics.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Write a robot file with the fitted values (priors as in --robot): e.g. to compare its
    /// predictions on held-out data with `arm predict`. Its header and its `[least_squares]`
    /// table say whether the fit was proved consistent with the measurements (--uncertainty) or
    /// not; `arm export` refuses a fit that was not.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Check the fit against these error bounds (uncertainty.toml): is it proved consistent with
    /// every measurement? Least squares minimises the sum of squares, not the largest misfit, so
    /// it often is not; `arm certify --write-calibrated` writes a vector that is.
    #[arg(long, value_name = "FILE")]
    uncertainty: Option<PathBuf>,
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    a.files.columns.positions_only("lsq")?;
    let arm = read_robot(&a.files.robot)?;
    let data = a
        .files
        .columns
        .read(&a.files.measurements, arm.joints.len())?;
    let fit = fit_arm(&arm, &data.readings)?;
    let table = Table::new(&arm, &fit);
    table.print(&fit, data.readings.len());
    let fitted = arm.with_nominal(&fit.x);
    let consistent = match &a.uncertainty {
        Some(path) => Some(check_consistency(path, &fitted, &data)?),
        None => None,
    };
    if let Some(path) = &a.json {
        write_json(path, &table, &fit, consistent, data.readings.len())?;
    }
    if let Some(path) = &a.out {
        write_fitted(&a, path, &fitted, consistent)?;
    }
    Ok(0)
}

/// The free parameters against their priors.
struct Table {
    names: Vec<String>,
    units: Vec<String>,
    nominal: Vec<f64>,
    radius: Vec<f64>,
    free: Vec<bool>,
    /// The free parameters the fit moved out of their prior box.
    outside: Vec<usize>,
}

impl Table {
    fn new(arm: &calib_arm::Arm, fit: &Fit) -> Table {
        let nominal = arm.nominal();
        let radius = arm.radius();
        let free = arm.free();
        let outside = (0..nominal.len())
            .filter(|&j| free[j] && (fit.x[j] - nominal[j]).abs() > radius[j])
            .collect();
        Table {
            names: names(arm.joints.len()),
            units: units(arm.joints.len()),
            nominal,
            radius,
            free,
            outside,
        }
    }

    /// Prints every free parameter's nominal value, fit and change, the residuals, and a
    /// warning naming the parameters that left their prior box.
    fn print(&self, fit: &Fit, configurations: usize) {
        let (names, units, nominal) = (&self.names, &self.units, &self.nominal);
        println!(
            "{:<9} {:<4} {:>14} {:>14} {:>12}",
            "parameter", "unit", "nominal", "fit", "change"
        );
        for (j, name) in names.iter().enumerate() {
            if !self.free[j] {
                continue;
            }
            println!(
                "{:<9} {:<4} {:>14.5} {:>14.5} {:>12.5}{}",
                name,
                units[j],
                nominal[j],
                fit.x[j],
                fit.x[j] - nominal[j],
                if self.outside.contains(&j) {
                    "  outside the prior"
                } else {
                    ""
                }
            );
        }
        println!(
            "residuals: rms {:.4} mm, max {:.4} mm over every coordinate of {} configurations ({}, {} evaluations)",
            fit.rms,
            fit.max_abs,
            configurations,
            if fit.converged { "converged" } else { "did not converge" },
            fit.evaluations
        );
        if !self.outside.is_empty() {
            let list: Vec<String> = self
                .outside
                .iter()
                .map(|&j| {
                    format!(
                        "{} {:+.3} {} (prior ± {})",
                        names[j],
                        fit.x[j] - nominal[j],
                        units[j],
                        self.radius[j]
                    )
                })
                .collect();
            println!(
                "warning: {} of the fitted parameters left their prior box: {}. Least squares \
                 trades poorly determined parameters against each other to absorb errors the model \
                 does not have; `arm certify` keeps every parameter in its prior.",
                self.outside.len(),
                list.join(", ")
            );
        }
    }
}

/// --uncertainty: whether the fit is proved consistent with every measurement, printed.
fn check_consistency(
    path: &Path,
    fitted: &calib_arm::Arm,
    data: &calib_arm::files::Measurements,
) -> Result<bool, Box<dyn std::error::Error>> {
    let u = data.slack.widen(&read_uncertainty(path)?);
    let proved = is_consistent_arm(fitted, &data.readings, &u);
    println!(
        "{}",
        if proved {
            format!(
                "the fit is proved consistent with every measurement within {}",
                path.display()
            )
        } else {
            format!(
                "the fit is NOT proved consistent with the measurements within {}: a \
                 comparison, not a calibration (`arm certify --write-calibrated` writes \
                 one that is)",
                path.display()
            )
        }
    );
    Ok(proved)
}

/// --json: the fit per parameter and the residual statistics.
fn write_json(
    path: &Path,
    table: &Table,
    fit: &Fit,
    consistent: Option<bool>,
    configurations: usize,
) -> Result<(), Box<dyn std::error::Error>> {
    let json = serde_json::json!({
        "version": 1,
        "consistent": consistent,
        "converged": fit.converged,
        "evaluations": fit.evaluations,
        "rms_mm": fit.rms,
        "max_mm": fit.max_abs,
        "configurations": configurations,
        "parameters": table.names.iter().enumerate().filter(|(j, _)| table.free[*j]).map(|(j, n)| {
            serde_json::json!({
                "name": n,
                "unit": table.units[j],
                "nominal": table.nominal[j],
                "prior_radius": table.radius[j],
                "fit": fit.x[j],
                "outside_prior": table.outside.contains(&j),
            })
        }).collect::<Vec<_>>(),
    });
    write_atomically(path, &format!("{json:#}\n"))
        .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    println!("JSON written to {}", path.display());
    Ok(())
}

/// --out: the robot file with the fitted values, saying whether they were proved consistent.
fn write_fitted(
    a: &Args,
    path: &Path,
    fitted: &calib_arm::Arm,
    consistent: Option<bool>,
) -> Result<(), Box<dyn std::error::Error>> {
    let status = match (consistent, &a.uncertainty) {
        (Some(true), Some(u)) => format!(
            "proved consistent with every measurement within {}; not certified: no set",
            u.display()
        ),
        (Some(false), Some(u)) => format!(
            "NOT proved consistent with the measurements within {}: a comparison, not a \
             calibration",
            u.display()
        ),
        _ => "not checked against error bounds, not certified: a comparison".to_string(),
    };
    let text = format!(
        "# least-squares fit by certicalib {} of {} to {}\n# {status}\n{}{}",
        env!("CARGO_PKG_VERSION"),
        a.files.robot.display(),
        a.files.measurements.display(),
        calib_arm::write::robot_toml(fitted),
        calib_arm::files::least_squares_mark(consistent == Some(true))
    );
    write_atomically(path, &text).map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    println!("fitted robot written to {}", path.display());
    Ok(())
}
