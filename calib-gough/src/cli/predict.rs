//! `gough predict`.

use calib_gough::files::{
    leg_sets, prediction_configurations, read_robot_file, read_uncertainty, PredictAt,
};
use calib_gough::predict::{predict, predictions_csv, predictions_json, refuting};
use calib_gough::report::write_atomically;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// The calibrated robot file (`gough certify --write-calibrated`): predictions are taken
    /// over its certified set (a file without one: over its boxes, and the output says so).
    #[arg(long, value_name = "FILE")]
    robot: PathBuf,
    /// The poses to predict the leg readings at: px,py,pz,ax,ay,az,angle_deg (cm, degrees).
    #[arg(long, value_name = "FILE", required_unless_present = "measurements")]
    poses: Option<PathBuf>,
    /// Measured configurations to check (px,py,pz,ax,ay,az,angle_deg,L1..Lk, as `certify`
    /// reads): their poses are predicted, and each reading outside its prediction is named.
    #[arg(long, value_name = "FILE", conflicts_with = "poses")]
    measurements: Option<PathBuf>,
    /// The measurement error bounds (pos, len, axis, angle_deg or q): the predictions a
    /// measurement may show are widened by them.
    #[arg(long, value_name = "FILE")]
    uncertainty: PathBuf,
    /// Write the predictions as CSV (per leg: L_lo, L_hi the certified range, L_min, L_max with
    /// the error bounds, and the measured reading and whether it lies inside).
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Write the predictions as JSON (schema version 1).
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    calib_pipeline::check_outputs(&[
        ("the predictions (CSV)", a.out.as_deref()),
        ("the JSON report", a.json.as_deref()),
    ])?;
    let file = read_robot_file(&a.robot)?;
    let sets = leg_sets(&a.robot, &file)?;
    let u = read_uncertainty(&a.uncertainty)?;
    let legs = file.legs.len();
    let (at, source) = match (&a.measurements, &a.poses) {
        (Some(path), _) => (PredictAt::Measurements(path), path),
        (None, Some(path)) => (PredictAt::Poses(path), path),
        (None, None) => return Err("--poses or --measurements: which poses to predict".into()),
    };
    let (configs, lines) = prediction_configurations(at, legs)?;
    let measured = a.measurements.is_some();
    let over_set: Vec<bool> = sets.iter().map(Option::is_some).collect();
    if !over_set.iter().any(|o| *o) {
        println!(
            "note: {} has no certified set: the predictions are taken over its boxes (a \
             superset; `gough certify --write-calibrated` writes a file with the set)",
            a.robot.display()
        );
    }
    let bar = indicatif::ProgressBar::new_spinner();
    bar.set_message(format!("predicting {} poses × {legs} legs", configs.len()));
    bar.enable_steady_tick(std::time::Duration::from_millis(120));
    let predictions = predict(&file.legs, &sets, &configs, &u, measured);
    bar.finish_and_clear();
    let widest = predictions
        .iter()
        .flat_map(|p| p.legs.iter().map(|l| l.range.wid()))
        .fold(0.0, f64::max);
    println!(
        "{} poses of {} predicted for {legs} legs: every certified range is at most {widest:.5} \
         cm wide (over every geometry the data allow, at exactly the pose)",
        predictions.len(),
        source.display()
    );
    let attained = calib_pipeline::accuracy::median_attained_percent(
        predictions
            .iter()
            .flat_map(|p| p.legs.iter().map(|l| (l.range, l.attained))),
    );
    if let Some(share) = attained {
        println!(
            "geometries proved consistent with every measurement reach {share:.0}% of a range's \
             width (median; the rest is enclosed, not shown to be reached)"
        );
    }
    let bad = refuting(&predictions);
    if measured {
        if bad.is_empty() {
            println!(
                "every measured reading lies within its prediction widened by the error bounds: \
                 the data are consistent with the calibration"
            );
        } else {
            println!(
                "{} measured readings lie outside their prediction widened by the error bounds: \
                 the model or the error bounds are wrong there:",
                bad.len()
            );
            for &(k, i) in &bad {
                let l = &predictions[k].legs[i];
                let line = lines
                    .as_ref()
                    .and_then(|l| l.get(k))
                    .copied()
                    .unwrap_or(k + 2);
                println!(
                    "  row {} ({} line {line}), leg {}: measured {:.5} cm, predicted [{:.5}, \
                     {:.5}] cm",
                    k + 1,
                    source.display(),
                    i + 1,
                    l.measured.unwrap_or(f64::NAN),
                    l.with_errors.inf(),
                    l.with_errors.sup()
                );
            }
        }
    }
    if let Some(path) = &a.out {
        write_atomically(path, &predictions_csv(&predictions, measured))
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        println!("predictions written to {}", path.display());
    }
    if let Some(path) = &a.json {
        let json = predictions_json(&predictions, &over_set, lines.as_deref());
        write_atomically(path, &format!("{json:#}\n"))
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        println!("JSON written to {}", path.display());
    }
    Ok(if bad.is_empty() { 0 } else { 2 })
}
