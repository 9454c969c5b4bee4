//! `arm predict`.

use calib_arm::files::{read_calibrated, read_uncertainty};
use calib_arm::predict::{
    predict, predictions_csv, predictions_json, refuting, residuals, OrientationResiduals,
};
use calib_pipeline::{parse_number_table, read_text, write_atomically};
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// The calibrated robot file (`arm certify --write-calibrated`): predictions are taken over
    /// its certified set (a file without one: over its boxes, and the output says so).
    #[arg(long, value_name = "FILE")]
    robot: PathBuf,
    /// The joint readings to predict the tracked point at: q1,…,qN (degrees).
    #[arg(long, value_name = "FILE", required_unless_present = "measurements")]
    joints: Option<PathBuf>,
    /// Measured configurations to check (q1,…,qN,px,py,pz, as `certify` reads): their joint
    /// readings are predicted, and each tracked point outside its prediction is named. With
    /// --orientation-columns (a 6-DoF calibrated file, its tool frame's rotation included) the
    /// measured orientations' residuals against the file's values are reported too.
    #[arg(long, value_name = "FILE", conflicts_with = "joints")]
    measurements: Option<PathBuf>,
    #[command(flatten)]
    columns: super::ColumnArgs,
    /// The measurement error bounds (joint_deg, pos): the predictions a measurement may show
    /// are widened by them.
    #[arg(long, value_name = "FILE")]
    uncertainty: PathBuf,
    /// Write the predictions as CSV (x_lo,x_hi,… the certified ranges; x_min,x_max,… with the
    /// error bounds; the measured point and whether it lies inside).
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Write the predictions as JSON (schema version 1).
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    if a.measurements.is_none() {
        a.columns.positions_only("predict --joints")?;
    }
    let (arm, set) = read_calibrated(&a.robot)?;
    let u = read_uncertainty(&a.uncertainty)?;
    let n = arm.joints.len();
    let mut slack = calib_arm::files::Slack::default();
    let mut orientation_errors = None;
    let (joints, points, lines, source) = match (&a.measurements, &a.joints) {
        (Some(path), _) => {
            let m = a.columns.read(path, n)?;
            slack = m.slack;
            if let Some(measured) = &m.orientations {
                orientation_errors = Some(OrientationResiduals::of(
                    &arm,
                    &a.robot,
                    &m.readings,
                    measured,
                )?);
            }
            let joints = m.readings.iter().map(|r| r.joints_deg.clone()).collect();
            let points: Vec<[f64; 3]> = m.readings.iter().map(|r| r.point).collect();
            (joints, Some(points), Some(m.lines), path)
        }
        (None, Some(path)) => {
            let header: Vec<String> = (1..=n).map(|i| format!("q{i}")).collect();
            let table = parse_number_table(path, &read_text(path)?, &header)?;
            (table.rows, None, Some(table.lines), path)
        }
        (None, None) => return Err("--joints or --measurements: which configurations".into()),
    };
    let u = slack.widen(&u);
    if set.is_none() {
        println!(
            "note: {} has no certified set: the predictions are taken over its boxes (a \
             superset; `arm certify --write-calibrated` writes a file with the set)",
            a.robot.display()
        );
    }
    let bar = super::output::spinner(&format!("predicting {} configurations", joints.len()));
    let predictions = predict(&arm, set.as_ref(), &joints, &u, points.as_deref());
    bar.finish_and_clear();
    let widest = predictions
        .iter()
        .flat_map(|p| p.range.iter().map(|v| v.wid()))
        .fold(0.0, f64::max);
    println!(
        "{} configurations of {} predicted: every certified range is at most {widest:.4} mm \
         wide (over every parameter vector the data allow, at exactly the joint readings)",
        predictions.len(),
        source.display()
    );
    let bad = refuting(&predictions);
    if let Some((rms, max)) = residuals(&predictions) {
        println!(
            "the robot file's values predict the measured points with residuals rms {rms:.4} mm, \
             max {max:.4} mm (every coordinate)"
        );
    }
    if let Some(o) = &orientation_errors {
        println!(
            "the robot file's values predict the measured orientations with residuals rms \
             {:.4}°, max {:.4}° (the angle between the measured and the predicted frame; from \
             the file's values only: the certified set holds the positions' equations)",
            o.rms_deg, o.max_deg
        );
    }
    if points.is_some() {
        if bad.is_empty() {
            println!(
                "every measured point lies within its prediction widened by the error bounds: \
                 the data are consistent with the calibration"
            );
        } else {
            println!(
                "{} of {} measured points lie outside their prediction widened by the error \
                 bounds: the model or the error bounds are wrong there:",
                bad.len(),
                predictions.len()
            );
            for &k in bad.iter().take(20) {
                let p = &predictions[k];
                let line = lines
                    .as_ref()
                    .and_then(|l| l.get(k))
                    .copied()
                    .unwrap_or(k + 2);
                let m = p.measured.unwrap_or([f64::NAN; 3]);
                let w = &p.with_errors;
                println!(
                    "  row {} ({} line {line}): measured ({:.3}, {:.3}, {:.3}) mm, predicted \
                     x [{:.3}, {:.3}], y [{:.3}, {:.3}], z [{:.3}, {:.3}]",
                    k + 1,
                    source.display(),
                    m[0],
                    m[1],
                    m[2],
                    w[0].inf(),
                    w[0].sup(),
                    w[1].inf(),
                    w[1].sup(),
                    w[2].inf(),
                    w[2].sup()
                );
            }
            if bad.len() > 20 {
                println!("  … and {} more (see --out or --json)", bad.len() - 20);
            }
        }
    }
    if let Some(path) = &a.out {
        write_atomically(path, &predictions_csv(&predictions))
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        println!("predictions written to {}", path.display());
    }
    if let Some(path) = &a.json {
        let mut json = predictions_json(&predictions, set.is_some(), lines.as_deref());
        if let Some(o) = &orientation_errors {
            json["orientation_residuals"] = o.json();
        }
        write_atomically(path, &format!("{json:#}\n"))
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        println!("JSON written to {}", path.display());
    }
    Ok(if bad.is_empty() { 0 } else { 2 })
}
