//! `arm certify`.

use super::output::{file_name, print_identifiability, print_outcome, spinner, write_json};
use super::DataFiles;
use calib_arm::certification::{arm_settings, certify_arm, RunOptions};
use calib_arm::files::{read_measurements, read_robot, read_uncertainty};
use calib_core::Status;
use calib_pipeline::verdict::{self, ConfigurationNames};
use calib_pipeline::{smallest_consistent, Depth, OutlierBudget};
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    files: DataFiles,
    /// Half-widths of the measurement errors: joint_deg (degrees) and pos (mm).
    #[arg(long, value_name = "FILE")]
    uncertainty: PathBuf,
    /// Refine to the tight hull (outer width <= (1 + TOL) × inner width) instead of the paper's
    /// fixed point x1. Minutes for a 6-axis arm; bound it with --max-seconds.
    #[arg(long)]
    hull: bool,
    /// With --hull: refine until outer width <= (1 + TOL) × inner width for every parameter.
    #[arg(long, value_name = "TOL", default_value_t = 0.10)]
    tolerance: f64,
    /// With --hull: contract at most this many boxes.
    #[arg(long, value_name = "N", default_value_t = 10_000)]
    max_boxes: usize,
    /// With --hull: stop refining after this many seconds (the result stays certified; the ratio
    /// reached is reported).
    #[arg(long, value_name = "SECONDS")]
    max_seconds: Option<f64>,
    /// Tolerate up to Q bad configurations: the boxes then contain every parameter vector that
    /// fits all but at most Q configurations, and the configurations proved to be outliers are
    /// listed. Costs about C(configurations, Q) certifications. `auto`: the smallest Q that is not
    /// proved empty (tries Q = 0, 1, 2, … in turn; every Q below it is proved too few).
    #[arg(long, value_name = "Q|auto", default_value = "0")]
    max_outliers: OutlierBudget,
    /// Also fit by least squares and show where the fit stands against the certified box.
    #[arg(long)]
    lsq: bool,
    /// Write the JSON report to this file.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    let arm = read_robot(&a.files.robot)?;
    let data = read_measurements(&a.files.measurements, arm.joints.len())?;
    let u = read_uncertainty(&a.uncertainty)?;
    if !(a.tolerance > 0.0 && a.tolerance.is_finite()) {
        return Err(format!(
            "--tolerance: expected a positive number, found {}",
            a.tolerance
        )
        .into());
    }
    if a.max_seconds.is_some_and(|s| s.is_nan() || s <= 0.0) {
        return Err("--max-seconds: expected a positive number".into());
    }
    a.max_outliers.check(data.readings.len())?;
    let settings = arm_settings()
        .with_hull_tolerance(a.tolerance)
        .with_hull_budget(a.max_boxes, a.max_seconds);
    let options = RunOptions {
        depth: if a.hull { Depth::Hull } else { Depth::Fast },
        lsq: a.lsq,
    };
    let bar = spinner(&format!(
        "certifying {} parameters on {} configurations",
        arm.free().iter().filter(|f| **f).count(),
        data.readings.len()
    ));
    let (q, run) = smallest_consistent(
        a.max_outliers,
        data.readings.len(),
        |q| {
            let settings = settings.clone().with_max_outliers(q);
            certify_arm(&arm, &data.readings, &u, options, &settings)
        },
        |run| run.outcome.status == Status::Empty,
    )?;
    bar.finish_and_clear();
    let file = file_name(&a.files.measurements);
    let names = ConfigurationNames {
        file: &file,
        lines: &data.lines,
    };
    print_identifiability(&run);
    if a.max_outliers == OutlierBudget::Auto {
        println!("{}", verdict::auto_outliers(q, run.outcome.status));
    }
    print_outcome(&run, &names, q);
    if let Some(path) = &a.json {
        write_json(path, &run, &names, q)?;
        println!("wrote {}", path.display());
    }
    Ok(if run.outcome.status == Status::Empty {
        2
    } else {
        0
    })
}
