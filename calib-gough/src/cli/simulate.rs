//! `gough simulate`.

use calib_gough::files::read_poses;
use calib_gough::simulate::{write_data_set, write_data_set_at};
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Number of measured configurations (random poses of the default workspace: centre within
    /// ± 5 cm horizontally, 55–65 cm high, rotation up to 15°).
    #[arg(long, default_value_t = 21)]
    configs: usize,
    /// Measure at these poses instead of random ones: a CSV with header
    /// px,py,pz,ax,ay,az,angle_deg (cm, unit axis, degrees), one configuration per row.
    #[arg(long, value_name = "FILE", conflicts_with = "configs")]
    poses: Option<PathBuf>,
    /// Random seed (the same seed gives the same files).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Noise amplitude as a multiple of the error bounds (<= 1 keeps the truth inside the boxes).
    #[arg(long, default_value_t = 1.0)]
    noise_scale: f64,
    /// Move one leg reading: CONFIG:LEG:DELTA (1-based configuration and leg, DELTA in cm).
    /// Repeat for several outliers: --outlier 5:2:0.3 --outlier 9:2:0.05.
    #[arg(long, value_name = "CONFIG:LEG:DELTA")]
    outlier: Vec<String>,
    /// Output folder (created if missing).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

fn parse_outlier(s: &str, configs: usize) -> Result<(usize, usize, f64), String> {
    let parts: Vec<&str> = s.split(':').collect();
    let bad = || format!("--outlier `{s}`: expected CONFIG:LEG:DELTA, e.g. 5:2:0.1");
    let [c, l, d] = parts[..] else {
        return Err(bad());
    };
    let c: usize = c.parse().map_err(|_| bad())?;
    let l: usize = l.parse().map_err(|_| bad())?;
    let d: f64 = d.parse().map_err(|_| bad())?;
    if c == 0 || c > configs || l == 0 || l > 6 || !d.is_finite() {
        return Err(format!(
            "--outlier `{s}`: configuration must be 1..={configs}, leg 1..=6, delta finite"
        ));
    }
    Ok((c - 1, l - 1, d))
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    let poses = a.poses.as_deref().map(read_poses).transpose()?;
    let configs = poses.as_ref().map_or(a.configs, Vec::len);
    let outliers = a
        .outlier
        .iter()
        .map(|s| parse_outlier(s, configs))
        .collect::<Result<Vec<_>, _>>()?;
    match &poses {
        Some(poses) => write_data_set_at(&a.out, poses, a.seed, a.noise_scale, &outliers)?,
        None => write_data_set(&a.out, configs, a.seed, a.noise_scale, &outliers)?,
    };
    println!("wrote {configs} configurations to {}", a.out.display());
    Ok(0)
}
