//! `gough accuracy`.

use calib_gough::accuracy::{
    accuracy_report, improvement, improvement_words, over_words, pose_words, unproved_words,
    Accuracy, AccuracyProblem, AccuracyReport, AccuracySettings, PoseErrorInstance, PoseErrors,
    REFINED_SET_PIECES,
};
use calib_gough::files::{leg_sets, read_robot, read_robot_file, read_uncertainty};
use calib_gough::report::write_atomically;
use calib_gough::workspace::{read_workspace, Workspace};
use calib_gough::GoughError;
use calib_pipeline::html;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// The robot file the controller loads (e.g. from `gough certify --write-calibrated`): its
    /// values are what the controller uses; the real robot's geometry lies in its certified set
    /// (a calibrated file carries it), or in its boxes (a file without a set).
    #[arg(long, value_name = "FILE")]
    robot: PathBuf,
    /// The poses the robot is used at (workspace.toml: x, y, z = [lo, hi] cm, tilt_deg,
    /// optional stroke = [lo, hi] cm).
    #[arg(long, value_name = "FILE")]
    workspace: PathBuf,
    /// The robot file before calibration (the design nominal with its prior box): the same
    /// brackets for it, and the improvement calibration brought as a proved factor.
    #[arg(long, value_name = "FILE")]
    before: Option<PathBuf>,
    /// The measurement error bounds: with them, the leg-length error plus the actuator's
    /// `len` bounds how far a leg's reached length is from the one it needs.
    #[arg(long, value_name = "FILE")]
    uncertainty: Option<PathBuf>,
    /// Stop each bracket at upper <= (1 + TOL) lower.
    #[arg(long, value_name = "TOL", default_value_t = 0.04)]
    tolerance: f64,
    /// Examine at most this many pose boxes per leg-length bracket of a leg without a
    /// certified set (over its box).
    #[arg(long, value_name = "N", default_value_t = AccuracySettings::default().max_boxes)]
    max_boxes: usize,
    /// Examine at most this many pose boxes per leg-length bracket of a leg over its certified
    /// set (each costs a few dozen small linear programs: about 2 ms on one core).
    #[arg(long, value_name = "N", default_value_t = AccuracySettings::default().max_set_boxes)]
    max_set_boxes: usize,
    /// Stop refining the platform's position and orientation upper bounds after about this
    /// many seconds per robot: they stay proved, only less tight (the output says so).
    #[arg(long, value_name = "S", default_value_t = AccuracySettings::default().pose_seconds)]
    pose_seconds: f64,
    /// Refine each leg's certified set where the workspace's leg-length errors are largest
    /// before bounding (to 36 pieces; the bounds use 4 as stored): tighter leg-length and
    /// platform pose bounds, each box of poses costing more. Worth it on a small workspace,
    /// where the errors' directions barely turn; over a wide one the time grows for little
    /// (measurements in benches/README.md).
    #[arg(long)]
    refine_set: bool,
    /// With --report: cells per side of the certificate's map of where the error is large (x–y,
    /// in 3 slabs of heights; each cell is a short proof per leg, so the map's cost grows as the
    /// square).
    #[arg(long, value_name = "N", default_value_t = AccuracySettings::default().map_cells,
          value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=40))]
    map_cells: usize,
    /// Write the brackets, worst instances and improvement as JSON (schema version 1).
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Write the accuracy certificate: one self-contained HTML page with the brackets, the
    /// improvement, a map of where in the workspace the error is large, and the inputs' SHA-256.
    #[arg(long, value_name = "FILE")]
    report: Option<PathBuf>,
}

/// `--pose-seconds` (of `accuracy` and `certify`), refused unless a finite number of seconds
/// above 0.
pub fn checked_pose_seconds(seconds: f64) -> Result<f64, GoughError> {
    if seconds > 0.0 && seconds.is_finite() {
        Ok(seconds)
    } else {
        Err(GoughError::PoseSeconds(seconds))
    }
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    calib_pipeline::check_outputs(&[
        ("the JSON report", a.json.as_deref()),
        ("the certificate", a.report.as_deref()),
    ])?;
    let file = read_robot_file(&a.robot)?;
    let sets = leg_sets(&a.robot, &file)?;
    let workspace = read_workspace(&a.workspace)?;
    let before = a.before.as_deref().map(read_robot).transpose()?;
    let actuator = a
        .uncertainty
        .as_deref()
        .map(read_uncertainty)
        .transpose()?
        .map(|u| u.len);
    if !(a.tolerance > 0.0 && a.tolerance.is_finite()) {
        return Err(format!("--tolerance: expected a number > 0, found {}", a.tolerance).into());
    }
    let settings = AccuracySettings {
        rel_tol: a.tolerance,
        max_boxes: a.max_boxes,
        max_set_boxes: a.max_set_boxes,
        pose_seconds: checked_pose_seconds(a.pose_seconds)?,
        map_cells: a.map_cells,
    };
    if sets.iter().all(Option::is_none) {
        println!(
            "note: {} has no certified set (a robot file written by hand or by an older \
             certicalib): its errors are bounded over its boxes, which contain geometries the \
             measurements rule out; `gough certify --write-calibrated` writes a file whose errors \
             are bounded over the certified set\n",
            a.robot.display()
        );
    }
    let mut problem = AccuracyProblem::over_sets(&file.legs, &sets, &workspace);
    if a.refine_set {
        problem.refine_sets(REFINED_SET_PIECES);
        println!(
            "each leg's certified set refined to {REFINED_SET_PIECES} pieces where the \
             workspace's leg-length errors are largest (--refine-set)\n"
        );
    }
    let report = with_spinner(settings.pose_seconds, before.is_some(), || {
        accuracy_report(
            &problem,
            before
                .as_deref()
                .map(|b| AccuracyProblem::new(b, &workspace))
                .as_ref(),
            actuator,
            &settings,
            a.report.is_some(),
        )
    });
    print_report(
        &report,
        &a.robot.display().to_string(),
        &a.workspace.display().to_string(),
    );
    if let Some(path) = &a.json {
        write_atomically(path, &format!("{:#}\n", report.json()))
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    }
    if let Some(path) = &a.report {
        write_atomically(path, &page(&report, &a)?)
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        println!("accuracy certificate written to {}", path.display());
    }
    Ok(0)
}

/// Runs `work` (an accuracy report) behind a spinner that shows the time spent and the budget of
/// its longest part, the pose errors' upper bounds: `pose_seconds` per robot, two robots with
/// `before` (on a terminal only: indicatif draws nothing when stderr is not a terminal).
pub(crate) fn with_spinner<T>(pose_seconds: f64, before: bool, work: impl FnOnce() -> T) -> T {
    let bar = indicatif::ProgressBar::new_spinner();
    if let Ok(style) = indicatif::ProgressStyle::with_template("{spinner} {msg} [{elapsed}]") {
        bar.set_style(style);
    }
    let robots = if before { "each robot" } else { "the robot" };
    bar.set_message(format!(
        "bracketing the leg-length and platform pose errors (the pose errors' upper bounds take \
         up to about {pose_seconds} s for {robots})"
    ));
    bar.enable_steady_tick(std::time::Duration::from_millis(120));
    let out = work();
    bar.finish_and_clear();
    out
}

/// The accuracy certificate page: the section, then the inputs with their SHA-256.
fn page(report: &AccuracyReport, a: &Args) -> Result<String, Box<dyn std::error::Error>> {
    let mut files = vec![
        ("robot file", a.robot.as_path()),
        ("workspace", a.workspace.as_path()),
    ];
    if let Some(path) = &a.before {
        files.push(("robot before calibration", path));
    }
    if let Some(path) = &a.uncertainty {
        files.push(("error bounds", path));
    }
    Ok(html::section_page(
        "accuracy of a calibrated 6-leg parallel robot",
        &report.section(),
        &files,
    )?)
}

fn describe(w: &Workspace) -> String {
    let stroke = w.stroke.map_or(String::new(), |[lo, hi]| {
        format!(", leg readings in [{lo}, {hi}] cm")
    });
    format!(
        "x in [{}, {}], y in [{}, {}], z in [{}, {}] cm, rotation up to {}°{stroke}",
        w.x[0], w.x[1], w.y[0], w.y[1], w.z[0], w.z[1], w.tilt_deg
    )
}

/// Prints the brackets, the worst instance and the improvement.
pub fn print_report(r: &AccuracyReport, robot: &str, workspace: &str) {
    let over = if r.over_set.iter().all(|o| *o) {
        "the measurements allow (its certified set)".to_string()
    } else if r.over_set.iter().any(|o| *o) {
        let boxed: Vec<String> = (0..r.over_set.len())
            .filter(|&i| !r.over_set[i])
            .map(|i| (i + 1).to_string())
            .collect();
        format!(
            "the measurements allow (its certified set; legs {} over the robot file's box)",
            boxed.join(", ")
        )
    } else {
        "in the robot file's box".to_string()
    };
    println!(
        "leg-length error of {} over the workspace of {}\n({}):\nthe length the controller \
         commands minus the length the real leg needs, for every geometry {over}, proved \
         between lower and upper (cm)\n",
        robot,
        workspace,
        describe(&r.workspace)
    );
    if r.after.leg_length.iter().all(|b| b.worst.is_none()) {
        println!(
            "no pose of the workspace was found (proved inside it): the stroke may exclude \
             every pose at the nominal geometry — check `stroke` in {workspace}; the upper \
             bounds below still hold over whatever the workspace contains\n"
        );
    }
    let mut header = format!(
        "{:<5}{:>10}{:>10}{:>8}{:>15}",
        "leg", "lower", "upper", "ratio", "over"
    );
    if r.before.is_some() {
        header += &format!("{:>16}{:>14}", "before (upper)", "improvement");
    }
    println!("{header}");
    for (i, b) in r.after.leg_length.iter().enumerate() {
        let mut row = format!(
            "{:<5}{:>10}{:>10}{:>8.3}{:>15}",
            i + 1,
            html::rounded(b.lower, true),
            html::rounded(b.upper, false),
            b.ratio(),
            over_words(r.over_set.get(i).copied().unwrap_or(false))
        );
        if let Some(before) = &r.before {
            let p = &before.leg_length[i];
            row += &format!(
                "{:>16}{:>13}×",
                html::rounded(p.upper, false),
                html::rounded_to(improvement(p, b).next_down(), 1, true)
            );
        }
        if !b.converged {
            row += "  (budget spent; the bracket holds)";
        }
        println!("{row}");
    }
    if let (Some(len), Some(reach)) = (r.actuator, r.reach()) {
        println!(
            "\nwith the actuators' error (± {len} cm), a leg's reached length is within \
             {reach:.5} cm of the length it needs"
        );
    }
    print_worst(&r.after, &r.over_set);
    print_pose_errors(r);
    if let Some(before) = &r.before {
        let factor = before
            .leg_length
            .iter()
            .zip(&r.after.leg_length)
            .map(|(b, a)| improvement(b, a))
            .fold(f64::INFINITY, f64::min);
        println!(
            "\n{}",
            calib_pipeline::verdict::improvement("every leg's worst length error", factor)
        );
        if let Some(words) = r.pose_improvement().and_then(improvement_words) {
            println!("calibration {words}");
        }
    }
    let seconds = r.after.seconds + r.before.as_ref().map_or(0.0, |b| b.seconds);
    println!(
        "\nthe upper bounds hold over the whole workspace (boxes at its boundary are bounded \
              whole, a superset); total {seconds:.1} s"
    );
}

/// The upper bounds of the platform's pose errors, or where they could not be proved.
fn print_pose_upper(after: &PoseErrors, tilt_deg: f64) {
    let Some(b) = &after.bounds else {
        return;
    };
    match (b.position, b.orientation_deg) {
        (Some(p), Some(o)) => {
            let ratio = |u: f64, l: Option<f64>| {
                l.map_or(String::new(), |l| {
                    format!(" (bracket {:.2})", calib_core::bracket_ratio(u, l))
                })
            };
            println!(
                "  upper bounds: position ≤ {p:.4} cm{}, orientation ≤ {o:.4}°{} ({} boxes of \
                 poses, {:.1} s{})",
                ratio(p, after.position.as_ref().map(|i| i.position)),
                ratio(o, after.orientation.as_ref().map(|i| i.orientation_deg)),
                b.pose_boxes,
                b.seconds,
                if b.converged {
                    ""
                } else {
                    "; budget reached, bounds valid but not refined further"
                }
            );
        }
        _ => println!(
            "  upper bounds not proved: {}",
            unproved_words(b, tilt_deg).unwrap_or_default()
        ),
    }
}

/// The platform's position and orientation errors: proved instances, before and after.
fn print_pose_errors(r: &AccuracyReport) {
    let Some(after) = &r.after.pose else {
        return;
    };
    println!(
        "\nplatform pose error: at most (proved over the whole workspace: no path from a \
         commanded pose can leave a region whose boundary every leg excludes), at least (an \
         instance whose reached pose is proved by interval Newton along its path)"
    );
    print_pose_upper(after, r.workspace.tilt_deg);
    let before = r.before.as_ref().and_then(|b| b.pose.as_ref());
    for (name, unit, value, at, unproved) in [
        (
            "position",
            "cm",
            (|i: &PoseErrorInstance| i.position) as fn(&PoseErrorInstance) -> f64,
            after.position.as_ref(),
            after.position_unproved,
        ),
        (
            "orientation",
            "°",
            |i: &PoseErrorInstance| i.orientation_deg,
            after.orientation.as_ref(),
            after.orientation_unproved,
        ),
    ] {
        let before_value = before
            .and_then(|b| match name {
                "position" => b.position.as_ref(),
                _ => b.orientation.as_ref(),
            })
            .map_or(String::new(), |i| {
                format!("; before calibration at least {:.4} {unit}", value(i))
            });
        match at {
            Some(i) => println!(
                "  {name:<12}{:>10.4} {unit}  commanded {}{before_value}",
                value(i),
                pose_words(&i.commanded)
            ),
            None => println!(
                "  {name:<12}no instance proved: {}{before_value}",
                unproved.map_or(
                    "no pose of the workspace was found".to_string(),
                    |x| format!(
                    "the path from the commanded pose {} to the reached one may meet a singular \
                     pose",
                    pose_words(&x)
                )
                )
            ),
        }
    }
}

fn print_worst(a: &Accuracy, over_set: &[bool]) {
    let Some((i, b)) = a
        .leg_length
        .iter()
        .enumerate()
        .max_by(|x, y| x.1.lower.total_cmp(&y.1.lower))
    else {
        return;
    };
    let Some(w) = &b.worst else {
        return;
    };
    let geometry = if over_set.get(i).copied().unwrap_or(false) {
        "a true geometry proved consistent with every measurement"
    } else {
        "its true geometry at a corner of its box"
    };
    println!(
        "\nworst: leg {} is {:.5} cm off at {}, with {geometry}",
        i + 1,
        w.value,
        pose_words(&w.pose)
    );
}
