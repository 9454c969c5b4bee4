//! `arm accuracy`.

use super::output::spinner;
use calib_arm::accuracy::{
    tool_accuracy, tool_accuracy_at, ToolAccuracyReport, ToolAccuracySettings, ToolBracket,
};
use calib_arm::certification::names;
use calib_arm::files::{read_calibrated, read_robot, read_uncertainty};
use calib_arm::joint_space::{read_joint_space, read_task, JointSpace};
use calib_arm::params;
use calib_arm::simulate::JOINT_LIMIT_DEG;
use calib_pipeline::{html, write_atomically};
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// The robot file the controller loads (e.g. from `arm certify --write-calibrated`): its
    /// values are what the controller computes with; the real geometry lies in its certified
    /// set (a calibrated file carries it), or in its boxes (a file without a set).
    #[arg(long, value_name = "FILE")]
    robot: PathBuf,
    /// The joint space: q1 = [lo, hi], q2 = …, one range per joint (degrees). Default: every
    /// joint within ±170° (the simulator's).
    #[arg(long, value_name = "FILE", conflicts_with_all = ["task", "measurements"])]
    joints: Option<PathBuf>,
    /// Instead of a joint box, the configurations a task uses: a CSV with columns q1..qN
    /// (degrees), one row per configuration. Each is bounded as given (no configuration
    /// between them), so the brackets say what calibration bought where the robot works.
    #[arg(long, value_name = "FILE", conflicts_with = "measurements")]
    task: Option<PathBuf>,
    /// Instead of a joint box, the joint readings of measured configurations (a file `certify`
    /// reads, e.g. held-out rows with --rows; the tracked points are not used): each
    /// configuration is bounded as given, as with --task.
    #[arg(long, value_name = "FILE")]
    measurements: Option<PathBuf>,
    #[command(flatten)]
    columns: super::ColumnArgs,
    /// The error bounds (uncertainty.toml): joint_deg, how far a joint may be from its command,
    /// widens every theta_i. Default: exact joints.
    #[arg(long, value_name = "FILE")]
    uncertainty: Option<PathBuf>,
    /// The robot before calibration (design nominal with its prior box), for the improvement
    /// calibration brought.
    #[arg(long, value_name = "FILE")]
    before: Option<PathBuf>,
    /// Stop at upper <= (1 + TOL) × lower.
    #[arg(long, value_name = "TOL", default_value_t = 0.04)]
    tolerance: f64,
    /// Examine at most this many joint boxes per bound over a box (the bracket stays proved; its
    /// ratio is reported). Each costs a few milliseconds on a 6-axis arm.
    #[arg(long, value_name = "N", default_value_t = 20_000)]
    max_boxes: usize,
    /// Examine at most this many joint boxes over a certified set (each costs tens of
    /// milliseconds on a 6-axis arm: its derivatives as second-order models in the joints, and
    /// up to ninety linear programs over the set, warm-started; a box wider than a radian in
    /// some joint about a tenth of a second: its joints' arcs enclosed by triangles, the error
    /// bounded at their 729 vertices).
    #[arg(long, value_name = "N", default_value_t = ToolAccuracySettings::default().max_set_boxes)]
    max_set_boxes: usize,
    /// Write the JSON report to this file.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Write the accuracy certificate to this file: one self-contained HTML page (figure inline,
    /// nothing fetched; print it to PDF) with the brackets before and after calibration, the
    /// proved improvement, the configurations where the worst errors are reached, and the input
    /// files' SHA-256.
    #[arg(long, value_name = "FILE")]
    report: Option<PathBuf>,
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    calib_pipeline::check_outputs(&[
        ("the JSON report", a.json.as_deref()),
        ("the certificate", a.report.as_deref()),
    ])?;
    if !(a.tolerance.is_finite() && a.tolerance > 0.0) {
        return Err(format!("--tolerance {}: expected a number > 0", a.tolerance).into());
    }
    if a.max_boxes == 0 {
        return Err("--max-boxes 0: expected at least 1".into());
    }
    let (arm, set) = read_calibrated(&a.robot)?;
    let joints = arm.joints.len();
    let before = a.before.as_deref().map(read_robot).transpose()?;
    if let Some(b) = &before {
        if b.joints.len() != joints {
            return Err(format!(
                "--before has {} joints; --robot has {joints}",
                b.joints.len()
            )
            .into());
        }
    }
    // The column options describe the file of --measurements; with a task or a joint box they
    // would be ignored (a task's `--joint-unit rad`, its `--rows`), so they are refused.
    if a.measurements.is_none() {
        if let Some(flag) = a.columns.first_given() {
            let list = if a.task.is_some() {
                "--task reads q1..qN in degrees, every row"
            } else {
                "the joint box comes from --joints (default: every joint within ±170°)"
            };
            return Err(format!(
                "{flag} describes the file of --measurements, which is not given: {list}"
            )
            .into());
        }
    }
    // The configurations of a task, read before any work (a bad file is named at once).
    // Readings converted from radians carry their rounding (`slack`), added to the joints' error.
    let (task, reading_slack) = match (&a.task, &a.measurements) {
        (Some(path), _) => {
            if path.extension().is_some_and(|e| e == "toml") {
                return Err(format!(
                    "{}: --task takes a CSV of configurations (q1..qN, degrees); a joint box \
                     (joints.toml) goes to --joints, where the bounds hold over all of it",
                    path.display()
                )
                .into());
            }
            (Some(read_task(path, joints)?), 0.0)
        }
        (None, Some(path)) => {
            a.columns.positions_only("accuracy --measurements")?;
            let m = a.columns.read(path, joints)?;
            let slack = m.slack.joint_deg;
            (
                Some(m.readings.into_iter().map(|r| r.joints_deg).collect()),
                slack,
            )
        }
        (None, None) => (None, 0.0),
    };
    let space = match &a.joints {
        Some(path) => read_joint_space(path, joints)?,
        None => JointSpace::simulator(joints),
    };
    let joint_deg = a
        .uncertainty
        .as_deref()
        .map(read_uncertainty)
        .transpose()?
        .map_or(0.0, |u| u.joint_deg);
    let joint_deg = if reading_slack > 0.0 {
        (joint_deg + reading_slack).next_up()
    } else {
        joint_deg
    };
    let settings = ToolAccuracySettings {
        rel_tol: a.tolerance,
        max_boxes: a.max_boxes,
        max_set_boxes: a.max_set_boxes,
    };
    let over_set = set.is_some();
    if !over_set {
        println!(
            "note: {} has no certified set (a robot file written by hand or by an older \
             certicalib): the error is bounded over its boxes, which contain geometries the \
             measurements rule out; `arm certify --write-calibrated` writes a file whose error is \
             bounded over the certified set\n",
            a.robot.display()
        );
    }
    let report = match &task {
        Some(list) => {
            let bar = spinner(&format!(
                "bounding the tool-point error at {} configurations",
                list.len()
            ));
            let report = tool_accuracy_at(&arm, set, before.as_ref(), list, joint_deg, &settings);
            bar.finish_and_clear();
            report
        }
        None => {
            let bar = spinner(&format!(
                "bounding the tool-point error over the joint space ({} boxes at most per \
                 robot)",
                a.max_boxes
            ));
            let report = tool_accuracy(&arm, set, before.as_ref(), space, joint_deg, &settings);
            bar.finish_and_clear();
            report
        }
    };
    let report = report?;
    print_report(&report, &a, task.as_ref().map(Vec::len));
    if let Some(path) = &a.json {
        let units: Vec<params::Unit> = params::names(joints).into_iter().map(|(_, u)| u).collect();
        write_atomically(path, &report.to_json(&names(joints), &units))
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        println!("wrote {}", path.display());
    }
    if let Some(path) = &a.report {
        write_atomically(path, &page(&report, &a)?)
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(0)
}

/// The accuracy certificate page: the section, then the input files with their SHA-256.
fn page(report: &ToolAccuracyReport, a: &Args) -> Result<String, Box<dyn std::error::Error>> {
    let mut files = vec![("robot file", a.robot.as_path())];
    for (role, path) in [
        ("joint space", &a.joints),
        ("task", &a.task),
        ("measured configurations", &a.measurements),
        ("robot before calibration", &a.before),
        ("error bounds", &a.uncertainty),
    ] {
        if let Some(path) = path {
            files.push((role, path.as_path()));
        }
    }
    Ok(html::section_page(
        "accuracy of a calibrated serial arm",
        &report.section(),
        &files,
    )?)
}

/// The report in the terminal; `task`: how many configurations, when the error was bounded at a
/// task's configurations rather than over a joint box.
fn print_report(r: &ToolAccuracyReport, a: &Args, task: Option<usize>) {
    let space: Vec<String> = r
        .space
        .ranges_deg
        .iter()
        .enumerate()
        .map(|(k, [lo, hi])| format!("q{} [{lo}, {hi}]", k + 1))
        .collect();
    let over = if r.over_set {
        "every geometry θ* the measurements allow (the certified set)"
    } else {
        "every geometry θ* in the robot file's box"
    };
    match task {
        Some(n) => println!(
            "tool-point error |p(q; θ*) - p(q; θ̂)| (mm, tracker frame) at the {n} configurations \
             of {} (each as given; their hull {}°), {over}, joint error ±{}°:",
            a.task
                .as_ref()
                .or(a.measurements.as_ref())
                .map_or(String::new(), |p| p.display().to_string()),
            space.join(", "),
            r.joint_error_text()
        ),
        None => println!(
            "tool-point error |p(q; θ*) - p(q; θ̂)| (mm, tracker frame) over the joint space \
             {}°{}, {over}, joint error ±{}°:",
            space.join(", "),
            if a.joints.is_none() {
                format!(" (the default: ±{JOINT_LIMIT_DEG}° per joint)")
            } else {
                String::new()
            },
            r.joint_error_text()
        ),
    }
    println!(
        "  {:<8} {:>14} {:>16} {:>7} {:>9} {:>8}",
        "robot", "upper (proved)", "lower (attained)", "ratio", "boxes", "seconds"
    );
    let row = |name: &str, b: &ToolBracket| {
        println!(
            "  {:<8} {:>14} {:>16} {:>7.3} {:>9} {:>8.2}{}",
            name,
            html::rounded_to(b.upper, 4, false),
            html::rounded_to(b.lower, 4, true),
            b.ratio(),
            b.boxes,
            b.seconds,
            match (b.converged, task) {
                (true, _) => "",
                (false, None) => {
                    "  (box budget reached: raise --max-boxes / --max-set-boxes to tighten)"
                }
                (false, Some(_)) => "  (each configuration bounded once: the bracket holds)",
            }
        )
    };
    row("after", &r.after);
    if let Some(b) = &r.before {
        row("before", b);
    }
    if let Some(f) = r.improvement() {
        println!(
            "{}",
            calib_pipeline::verdict::improvement("the worst tool-point error", f)
        );
    }
    if let Some(w) = &r.after.worst {
        let q: Vec<String> = w.joints_deg.iter().map(|v| format!("{v:.3}")).collect();
        println!(
            "worst instance found: q = ({})°, error ({:.4}, {:.4}, {:.4}) mm, |error| >= {:.4} mm",
            q.join(", "),
            w.error[0],
            w.error[1],
            w.error[2],
            w.value
        );
    }
    if task.is_some() {
        let q: Vec<String> = r
            .after
            .frontier_deg
            .iter()
            .map(|[lo, hi]| format!("{:.3}", 0.5 * (lo + hi)))
            .collect();
        println!(
            "the upper bound after calibration is largest at q = ({})° (its bound there)",
            q.join(", ")
        );
    } else if !r.after.converged {
        let f: Vec<String> = r
            .after
            .frontier_deg
            .iter()
            .enumerate()
            .map(|(k, [lo, hi])| format!("q{} [{lo:.1}, {hi:.1}]", k + 1))
            .collect();
        println!(
            "a larger error could still hide near {}° (the box giving the upper bound)",
            f.join(", ")
        );
    }
}
