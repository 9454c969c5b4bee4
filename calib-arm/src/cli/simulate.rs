//! `arm simulate`.

use calib_arm::builtin_arm;
use calib_arm::files::read_robot;
use calib_arm::simulate::{simulate, Uncertainty};
use calib_arm::write::write_data_set;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// The arm to simulate (its nominal and prior radii); the built-in 6-axis arm by default.
    #[arg(long, value_name = "FILE")]
    robot: Option<PathBuf>,
    /// Number of measured configurations (joints uniform within ±170°).
    #[arg(long, default_value_t = 50)]
    configs: usize,
    /// Random seed (the same seed gives the same files).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Error bound of the joint readings (degrees).
    #[arg(long, value_name = "DEG", default_value_t = Uncertainty::TRACKER.joint_deg)]
    joint_deg: f64,
    /// Error bound of each tracked coordinate (mm).
    #[arg(long, value_name = "MM", default_value_t = Uncertainty::TRACKER.pos)]
    pos: f64,
    /// Noise amplitude as a multiple of the error bounds (<= 1 keeps the truth inside the boxes).
    #[arg(long, default_value_t = 1.0)]
    noise_scale: f64,
    /// Move the tracked point of one configuration by DELTA mm in a random direction:
    /// CONFIG:DELTA (1-based configuration). Repeat for several outliers.
    #[arg(long, value_name = "CONFIG:DELTA_MM")]
    outlier: Vec<String>,
    /// Output folder (created if missing).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

fn parse_outlier(s: &str, configs: usize) -> Result<(usize, f64), String> {
    let bad = || format!("--outlier `{s}`: expected CONFIG:DELTA_MM, e.g. 12:0.5");
    let (c, d) = s.split_once(':').ok_or_else(bad)?;
    let c: usize = c.parse().map_err(|_| bad())?;
    let d: f64 = d.parse().map_err(|_| bad())?;
    if c == 0 || c > configs || !d.is_finite() {
        return Err(format!(
            "--outlier `{s}`: configuration must be 1..={configs}, delta finite"
        ));
    }
    Ok((c - 1, d))
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    if a.configs == 0 {
        return Err("--configs: at least one configuration".into());
    }
    for (name, v) in [
        ("--joint-deg", a.joint_deg),
        ("--pos", a.pos),
        ("--noise-scale", a.noise_scale),
    ] {
        if !(v >= 0.0 && v.is_finite()) {
            return Err(format!("{name}: expected a number >= 0, found {v}").into());
        }
    }
    let arm = match &a.robot {
        Some(path) => read_robot(path)?,
        None => builtin_arm(),
    };
    let outliers = a
        .outlier
        .iter()
        .map(|s| parse_outlier(s, a.configs))
        .collect::<Result<Vec<_>, _>>()?;
    let u = Uncertainty {
        joint_deg: a.joint_deg,
        pos: a.pos,
    };
    let sim = simulate(&arm, a.configs, a.seed, u, a.noise_scale, &outliers);
    write_data_set(&a.out, &arm, &sim)
        .map_err(|e| format!("{}: cannot write the data set: {e}", a.out.display()))?;
    println!(
        "wrote {} configurations of a {}-joint arm to {} (robot.toml, measurements.csv, \
         uncertainty.toml, truth.json)",
        a.configs,
        arm.joints.len(),
        a.out.display()
    );
    Ok(0)
}
