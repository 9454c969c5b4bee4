//! `arm predict`.

use calib_arm::files::{read_calibrated, read_uncertainty};
use calib_arm::predict::{
    predict, predictions_csv, predictions_json, refuting, residuals, OrientationResiduals,
    PointPrediction,
};
use calib_pipeline::{parse_number_table, read_text, write_atomically};
use std::path::{Path, PathBuf};

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
    calib_pipeline::check_outputs(&[
        ("the predictions (CSV)", a.out.as_deref()),
        ("the JSON report", a.json.as_deref()),
    ])?;
    if a.measurements.is_none() {
        a.columns.positions_only("predict --joints")?;
    }
    let (arm, set) = read_calibrated(&a.robot)?;
    let u = read_uncertainty(&a.uncertainty)?;
    let c = Configurations::read(&a, &arm)?;
    let u = c.slack.widen(&u);
    if set.is_none() {
        println!(
            "note: {} has no certified set: the predictions are taken over its boxes (a \
             superset; `arm certify --write-calibrated` writes a file with the set)",
            a.robot.display()
        );
    }
    let bar = super::output::spinner(&format!("predicting {} configurations", c.joints.len()));
    let predictions = predict(&arm, set.as_ref(), &c.joints, &u, c.points.as_deref());
    bar.finish_and_clear();
    print_summary(&c, &predictions);
    let bad = refuting(&predictions);
    if c.points.is_some() {
        print_refuting(&c, &predictions, &bad);
    }
    if let Some(path) = &a.out {
        write_atomically(path, &predictions_csv(&predictions))
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        println!("predictions written to {}", path.display());
    }
    if let Some(path) = &a.json {
        let mut json = predictions_json(&predictions, set.is_some(), c.lines.as_deref());
        if let Some(o) = &c.orientation_errors {
            json["orientation_residuals"] = o.json();
        }
        write_atomically(path, &format!("{json:#}\n"))
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        println!("JSON written to {}", path.display());
    }
    Ok(if bad.is_empty() { 0 } else { 2 })
}

/// The configurations to predict at: --measurements' (with their points) or --joints'.
struct Configurations<'a> {
    joints: Vec<Vec<f64>>,
    /// The measured points (--measurements).
    points: Option<Vec<[f64; 3]>>,
    /// The 1-based file line of each configuration.
    lines: Option<Vec<usize>>,
    /// The file read.
    source: &'a Path,
    slack: calib_arm::files::Slack,
    /// With orientation columns: the measured orientations' residuals.
    orientation_errors: Option<OrientationResiduals>,
}

impl<'a> Configurations<'a> {
    fn read(
        a: &'a Args,
        arm: &calib_arm::Arm,
    ) -> Result<Configurations<'a>, Box<dyn std::error::Error>> {
        let n = arm.joints.len();
        match (&a.measurements, &a.joints) {
            (Some(path), _) => {
                let m = a.columns.read(path, n)?;
                let orientation_errors = match &m.orientations {
                    Some(measured) => Some(OrientationResiduals::of(
                        arm,
                        &a.robot,
                        &m.readings,
                        measured,
                    )?),
                    None => None,
                };
                Ok(Configurations {
                    joints: m.readings.iter().map(|r| r.joints_deg.clone()).collect(),
                    points: Some(m.readings.iter().map(|r| r.point).collect()),
                    lines: Some(m.lines),
                    source: path,
                    slack: m.slack,
                    orientation_errors,
                })
            }
            (None, Some(path)) => {
                let header: Vec<String> = (1..=n).map(|i| format!("q{i}")).collect();
                let table = parse_number_table(path, &read_text(path)?, &header)?;
                Ok(Configurations {
                    joints: table.rows,
                    points: None,
                    lines: Some(table.lines),
                    source: path,
                    slack: calib_arm::files::Slack::default(),
                    orientation_errors: None,
                })
            }
            (None, None) => Err("--joints or --measurements: which configurations".into()),
        }
    }
}

/// The widest certified range and the residuals of the robot file's values.
fn print_summary(c: &Configurations<'_>, predictions: &[PointPrediction]) {
    let widest = predictions
        .iter()
        .flat_map(|p| p.range.iter().map(|v| v.wid()))
        .fold(0.0, f64::max);
    println!(
        "{} configurations of {} predicted: every certified range is at most {widest:.4} mm \
         wide (over every parameter vector the data allow, at exactly the joint readings)",
        predictions.len(),
        c.source.display()
    );
    let attained = calib_pipeline::accuracy::median_attained_percent(
        predictions
            .iter()
            .flat_map(|p| p.range.iter().copied().zip(p.attained)),
    );
    if let Some(share) = attained {
        println!(
            "parameter vectors proved consistent with every measurement reach {share:.0}% of a \
             range's width (median; the rest is enclosed, not shown to be reached)"
        );
    }
    if let Some((rms, max)) = residuals(predictions) {
        println!(
            "the robot file's values predict the measured points with residuals rms {rms:.4} mm, \
             max {max:.4} mm (every coordinate)"
        );
    }
    if let Some(o) = &c.orientation_errors {
        println!(
            "the robot file's values predict the measured orientations with residuals rms \
             {:.4}°, max {:.4}° (the angle between the measured and the predicted frame; from \
             the file's values only: the certified set holds the positions' equations)",
            o.rms_deg, o.max_deg
        );
    }
}

/// Whether the measured points lie within their predictions; the first 20 that do not.
fn print_refuting(c: &Configurations<'_>, predictions: &[PointPrediction], bad: &[usize]) {
    if bad.is_empty() {
        println!(
            "every measured point lies within its prediction widened by the error bounds: \
             the data are consistent with the calibration"
        );
        return;
    }
    println!(
        "{} of {} measured points lie outside their prediction widened by the error \
         bounds: the model or the error bounds are wrong there:",
        bad.len(),
        predictions.len()
    );
    for &k in bad.iter().take(20) {
        let p = &predictions[k];
        let line = c
            .lines
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
            c.source.display(),
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
