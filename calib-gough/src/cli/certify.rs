//! `gough certify`.

use super::DataFiles;
use calib_core::Status;
use calib_gough::accuracy::{accuracy_report, AccuracyProblem, AccuracyReport, AccuracySettings};
use calib_gough::calibrated::{calibrated_robot, robot_toml, CalibratedRobot, Task, TaskFile};
use calib_gough::carry_over::{stored_rows, StoredRows};
use calib_gough::certification::{
    certify_legs_carrying, identifiability, report, CertifyOptions, LegResult,
};
use calib_gough::error_scale::{search, ScaleBounds};
use calib_gough::files::{
    check_uncertainty, parse_measurements, parse_robot_file, parse_uncertainty, read_text,
    RobotFile,
};
use calib_gough::lsq::fit_legs;
use calib_gough::measurement::Uncertainty;
use calib_gough::plot;
use calib_gough::report::{ratios, table, write_atomically};
use calib_gough::report_page::{self, LegEntry, ReportPage};
use calib_gough::verdict::{self, ConfigurationNames};
use calib_gough::workspace::read_workspace;
use calib_gough::PARAMETER_NAMES;
use calib_pipeline::cli::{ErrorScaleArgs, ErrorScaleMode, OutlierArgs};
use calib_pipeline::error_scale::{check_margin, report as scale_report};
use calib_pipeline::OutlierBudget;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    files: DataFiles,
    /// Half-widths of the measurement errors: pos, len, axis and angle_deg (or q).
    #[arg(long, value_name = "FILE")]
    uncertainty: PathBuf,
    /// Only these legs (1-based, comma-separated), e.g. --legs 1,3.
    #[arg(long, value_delimiter = ',', value_name = "LIST")]
    legs: Option<Vec<usize>>,
    /// Only the paper's fixed point x1 (one Newton/LP contraction, milliseconds per leg) instead
    /// of the tight hull: x1 is then the outer box, with its own (looser) inner bounds.
    #[arg(long)]
    fast: bool,
    /// Refine until outer width <= (1 + TOL) × inner width for every parameter.
    #[arg(long, value_name = "TOL", default_value_t = 0.05)]
    tolerance: f64,
    /// Contract at most this many boxes per leg when refining the hull.
    #[arg(long, value_name = "N", default_value_t = 200_000)]
    max_boxes: usize,
    /// Stop refining a leg's hull after this many seconds (the result stays certified; the
    /// ratio reached is reported).
    #[arg(long, value_name = "SECONDS")]
    max_seconds: Option<f64>,
    #[command(flatten)]
    outliers: OutlierArgs,
    /// Also run the paper's 128-box bisection sweep and report its hull x2.
    #[arg(long)]
    sweep: bool,
    /// Also pave the solution set with boxes down to this relative width (e.g. 0.1).
    #[arg(long, value_name = "TOL")]
    pave: Option<f64>,
    /// Write the JSON report (schema version 1) to this file.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Write the calibration certificate to this file: one self-contained HTML page (figures
    /// inline, nothing fetched; open it in any browser, print it to PDF) with the verdicts and
    /// their evidence in words, the input files' SHA-256, the settings, a table and figures per
    /// leg, and each leg's least-squares solution against its certified box.
    #[arg(long, value_name = "FILE")]
    report: Option<PathBuf>,
    /// Write the calibrated robot file a controller loads: per leg a geometry proved consistent
    /// with every measurement (with part of each error bound to spare), chosen towards the
    /// centre of the leg lengths it predicts over the workspace (--workspace, else the measured
    /// poses' range); radii whose boxes contain the certified ones; and the certified set, so
    /// that `gough accuracy` and `gough predict` work over it. Refused (nothing written) when a
    /// leg is proved inconsistent or undecided (no geometry proved consistent).
    #[arg(long, value_name = "FILE")]
    write_calibrated: Option<PathBuf>,
    /// Choose the --write-calibrated geometry for where the robot will work: towards the centre
    /// of the leg lengths it predicts over the task (to first order, the smallest worst
    /// leg-length error there). FILE is a workspace (`workspace.toml`: x, y, z = [lo, hi] cm,
    /// tilt_deg; 300 poses sampled in it stand for it) or a poses CSV
    /// (px,py,pz,ax,ay,az,angle_deg, as `gough design` writes it). Default: --workspace, else the
    /// measured poses' range. The geometry is proved consistent as always.
    #[arg(long, value_name = "FILE", requires = "write_calibrated")]
    task: Option<PathBuf>,
    /// Also certify the accuracy over this workspace (workspace.toml): per leg, how far the
    /// commanded leg length can be from the needed one, calibrated (over the certified set) and
    /// uncalibrated (robot.toml's box), and the platform's pose errors, as in `gough accuracy`;
    /// printed and on the certificate.
    #[arg(long, value_name = "FILE")]
    workspace: Option<PathBuf>,
    /// With --workspace: stop refining the platform's position and orientation upper bounds
    /// after about this many seconds per robot, as in `gough accuracy`.
    #[arg(long, value_name = "S", default_value_t = AccuracySettings::default().pose_seconds)]
    pose_seconds: f64,
    /// With --workspace: examine at most this many boxes of poses per leg over its certified set
    /// (see `gough accuracy --max-set-boxes`).
    #[arg(long, value_name = "N", default_value_t = AccuracySettings::default().max_set_boxes)]
    max_set_boxes: usize,
    /// With --workspace and --report: cells per side of the certificate's map of where the error is large (x–y,
    /// in 3 slabs of heights; each cell is a short proof per leg, so the map's cost grows as the
    /// square).
    #[arg(long, value_name = "N", default_value_t = AccuracySettings::default().map_cells,
          value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=40))]
    map_cells: usize,
    /// Write one SVG per leg into this folder: x0, x1, x2, the outer and the inner box in the
    /// projections (ax, ay), (bx, by) and (az, l).
    #[arg(long, value_name = "DIR")]
    plots: Option<PathBuf>,
    #[command(flatten)]
    scale: ErrorScaleArgs<ScaleBounds>,
}

/// With --error-scale auto: finds the smallest consistent factor of `u`'s bounds for the `legs`,
/// prints it in words, and returns the bracket's JSON, the bounds to certify with, and the words.
/// Stored rows carried over keep their own bounds: the factor scales the new rows'.
fn error_scale(
    a: &Args,
    robot: &[calib_gough::files::LegSpec],
    input: &Files,
    legs: &[usize],
) -> Result<(serde_json::Value, Uncertainty, Vec<String>), Box<dyn std::error::Error>> {
    let (configs, u) = (&input.data.configs, &input.u);
    let margin = a.scale.scale_margin;
    check_margin(margin)?;
    let which = a.scale.scale_bounds;
    let started = Instant::now();
    let bar = indicatif::ProgressBar::new_spinner();
    bar.enable_steady_tick(std::time::Duration::from_millis(120));
    let found = search(robot, &input.stored, legs, configs, u, which, |s| {
        bar.set_message(format!("certifying with the error bounds × {s:.4}"))
    });
    bar.finish_and_clear();
    let seconds = started.elapsed().as_secs_f64();
    let describe = |s: f64| which.describe(u, s);
    let done = scale_report(&found, which.name(), seconds, margin, &describe)?;
    done.words.iter().for_each(|w| println!("{w}"));
    Ok((done.json, which.scale(u, done.certify_at), done.words))
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    calib_pipeline::check_outputs(&[
        ("the JSON report", a.json.as_deref()),
        ("the certificate", a.report.as_deref()),
        ("the calibrated robot file", a.write_calibrated.as_deref()),
    ])?;
    let input = Files::read(&a)?;
    let (robot, data) = (&input.robot, &input.data);
    let options = a.options();
    // Option errors before any work (certify_legs_carrying checks them again), counting the
    // rows carried over as it does.
    let most = input.stored.iter().flatten().map(|s| s.rows.len()).max();
    let (legs, _) = options.validate(robot.len(), data.configs.len() + most.unwrap_or(0))?;
    let carried = carried_words(&a.files.robot, &input.stored, &legs, data.configs.len());
    let (scale_json, u, scale_words) = match a.scale.error_scale {
        Some(ErrorScaleMode::Auto) => {
            let (json, scaled, words) = error_scale(&a, robot, &input, &legs)?;
            println!();
            (Some(json), scaled, words)
        }
        None => (None, input.u, Vec::new()),
    };
    let workspace = a.workspace.as_deref().map(read_workspace).transpose()?;
    let task = a.task.as_deref().map(TaskFile::read).transpose()?;
    let pose_seconds = super::accuracy::checked_pose_seconds(a.pose_seconds)?;
    carried.iter().for_each(|line| println!("{line}"));
    if !carried.is_empty() {
        println!();
    }
    let (results, total) = certify_with_progress(&input, &u, &options, legs.len())?;
    let file = file_name(&a.files.measurements);
    let names = ConfigurationNames {
        file: &file,
        lines: &data.lines,
        carried: None,
    };
    let findings: Vec<Vec<String>> = results
        .iter()
        .map(|r| {
            let stored = r.carried.as_ref().map(|c| &c.stored);
            identifiability(&robot[r.leg], r.leg, &data.configs, &u, stored)
        })
        .collect();
    print_results(&a, &results, &findings, &names, total);
    if let Some(dir) = &a.plots {
        write_plots(dir, &results)?;
    }
    let calibrated = if a.write_calibrated.is_some() || workspace.is_some() {
        let mut cal = calibrated_robot(
            robot,
            &results,
            &data.configs,
            &u,
            task.as_ref()
                .map(TaskFile::task)
                .or(workspace.as_ref().map(Task::Workspace)),
        )?;
        cal.keep_stored_sets(&a.files.robot, &input.robot_file)?;
        Some(cal)
    } else {
        None
    };
    if let (Some(path), Some(cal)) = (&a.write_calibrated, &calibrated) {
        write_calibrated(&a, path, cal, &carried)?;
    }
    let accuracy = match (&workspace, &calibrated) {
        (Some(w), Some(cal)) => Some(certify_accuracy(&a, robot, w, cal, &u, pose_seconds)),
        _ => None,
    };
    if let Some(path) = &a.report {
        let run = Run {
            results: &results,
            findings: &findings,
            u: &u,
            scale_words: &scale_words,
            carried: &carried,
            seconds: total,
            accuracy: accuracy.as_ref(),
        };
        write_certificate(&a, path, &input, &run, names)?;
    }
    if let Some(path) = &a.json {
        write_json(path, &results, total, scale_json)?;
    }
    Ok(if results.iter().any(|r| r.status == Status::Empty) {
        2
    } else {
        0
    })
}

/// The input files, each read once: what is hashed for the certificate is what is parsed.
struct Files {
    robot_text: String,
    data_text: String,
    u_text: String,
    robot: Vec<calib_gough::files::LegSpec>,
    /// The robot file as read, with the certified sets of a calibrated file.
    robot_file: RobotFile,
    /// Per leg, the rows a calibrated robot file carries over (`None`: the leg has no set).
    stored: Vec<Option<StoredRows>>,
    data: calib_gough::files::Measurements,
    u: Uncertainty,
}

impl Files {
    /// Reads and checks --robot, --measurements and --uncertainty.
    fn read(a: &Args) -> Result<Files, Box<dyn std::error::Error>> {
        let texts = [&a.files.robot, &a.files.measurements, &a.uncertainty].map(|p| read_text(p));
        let [robot_text, data_text, u_text] = texts;
        let (robot_text, data_text, u_text) = (robot_text?, data_text?, u_text?);
        let robot_file = parse_robot_file(&a.files.robot, &robot_text)?;
        let robot = robot_file.legs.clone();
        let data = parse_measurements(&a.files.measurements, &data_text, robot.len())?;
        let u = parse_uncertainty(&a.uncertainty, &u_text)?;
        check_uncertainty(&a.uncertainty, &u, data.rodrigues)?;
        let stored = stored_rows(&a.files.robot, &robot_file, data.rodrigues)?;
        Ok(Files {
            robot_text,
            data_text,
            u_text,
            robot,
            robot_file,
            stored,
            data,
            u,
        })
    }
}

/// Certifies the chosen legs with a progress bar (on a terminal only: indicatif draws nothing
/// when stderr is not a terminal); the results and the seconds they took.
fn certify_with_progress(
    input: &Files,
    u: &Uncertainty,
    options: &CertifyOptions,
    legs: usize,
) -> Result<(Vec<LegResult>, f64), Box<dyn std::error::Error>> {
    let start = Instant::now();
    let bar = indicatif::ProgressBar::new(legs as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("certifying legs {bar:30} {pos}/{len} [{elapsed}]")
            .expect("static template"),
    );
    let results = certify_legs_carrying(
        &input.robot,
        &input.stored,
        &input.data.configs,
        u,
        options,
        &|| bar.inc(1),
    )?;
    bar.finish_and_clear();
    Ok((results, start.elapsed().as_secs_f64()))
}

/// Prints every leg's result and identifiability findings, then the total time.
fn print_results(
    a: &Args,
    results: &[LegResult],
    findings: &[Vec<String>],
    names: &ConfigurationNames<'_>,
    total: f64,
) {
    for (r, found) in results.iter().zip(findings) {
        print_leg(r, names, a.outliers.max_outliers);
        for s in found {
            println!("identifiability: {s}");
        }
        println!();
    }
    if findings.iter().any(|f| !f.is_empty()) {
        println!(
            "identifiability: to choose configurations that determine these parameters, run\n  \
             gough design --robot {} --uncertainty {} --extend {} --configs 7 --out next.csv\n\
             (or `gough design` without --extend to plan a new campaign)\n",
            a.files.robot.display(),
            a.uncertainty.display(),
            a.files.measurements.display()
        );
    }
    println!("total: {} legs in {total:.3} s", results.len());
}

/// --plots: one SVG per leg into `dir`.
fn write_plots(dir: &Path, results: &[LegResult]) -> Result<(), Box<dyn std::error::Error>> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: cannot create: {e}", dir.display()))?;
    for r in results {
        let title = format!("leg {}: {}", r.leg + 1, verdict::short_verdict(r.status));
        let svg = plot::nested_boxes(
            &plot::leg_layers(r),
            None,
            &plot::LEG_PROJECTIONS,
            &PARAMETER_NAMES,
            &title,
        )?;
        let path = dir.join(format!("leg{}.svg", r.leg + 1));
        write_atomically(&path, &svg)
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    }
    println!("plots written to {}", dir.display());
    Ok(())
}

/// What a run carries over from a calibrated robot file, in words (nothing when the file has no
/// certified set): one line when every chosen leg carries the same rows, else one per leg; and
/// the stored rows left out (tolerated as outliers by the earlier run).
fn carried_words(
    file: &Path,
    stored: &[Option<StoredRows>],
    legs: &[usize],
    new: usize,
) -> Vec<String> {
    let chosen: Vec<(usize, Option<&StoredRows>)> = legs
        .iter()
        .map(|&i| (i, stored.get(i).and_then(Option::as_ref)))
        .collect();
    if chosen.iter().all(|(_, s)| s.is_none()) {
        return Vec::new();
    }
    let name = file.display();
    let joined = |n: usize| {
        format!(
            "{n} stored configuration{} of {name} join{} the {new} new one{}",
            if n == 1 { "" } else { "s" },
            if n == 1 { "s" } else { "" },
            if new == 1 { "" } else { "s" }
        )
    };
    let first = chosen[0].1.map(|s| &s.rows);
    let mut out = if chosen.iter().all(|(_, s)| s.map(|s| &s.rows) == first) {
        vec![format!(
            "carried over: {} (each leg is certified against both series, from its certified set)",
            joined(first.map_or(0, Vec::len))
        )]
    } else {
        chosen
            .iter()
            .map(|(i, s)| match s {
                Some(s) => format!("carried over to leg {}: {}", i + 1, joined(s.rows.len())),
                None => format!(
                    "leg {}: no certified set in {name}: certified against the {new} new \
                     configurations alone",
                    i + 1
                ),
            })
            .collect()
    };
    for (i, s) in &chosen {
        if let Some(s) = s.filter(|s| !s.left_out.is_empty()) {
            let rows: Vec<String> = s.left_out.iter().map(|k| (k + 1).to_string()).collect();
            out.push(format!(
                "leg {}: stored row{} {} of {name} not carried over: the earlier certification \
                 tolerated {}",
                i + 1,
                if rows.len() == 1 { "" } else { "s" },
                rows.join(", "),
                if rows.len() == 1 {
                    "it as an outlier"
                } else {
                    "them as outliers"
                },
            ));
        }
    }
    out
}

/// --write-calibrated: the calibrated robot file, with a comment saying where it comes from.
fn write_calibrated(
    a: &Args,
    path: &Path,
    cal: &CalibratedRobot,
    carried: &[String],
) -> Result<(), Box<dyn std::error::Error>> {
    let over = match (&a.task, &a.workspace) {
        (Some(task), _) => format!("the task {}", task.display()),
        (None, Some(w)) => format!("the workspace {}", w.display()),
        (None, None) => "the measured poses' range".to_string(),
    };
    let comment = format!(
        "calibrated by certicalib {} from {} and {}:\n\
         a, b, l: per leg, a geometry proved consistent with every measurement ({}),\n\
         chosen towards the centre of the leg lengths it predicts over {over};\n\
         radius: a box around it that contains the certified outer box;\n\
         [leg.certified_set]: the certified set `gough accuracy` and `gough predict` work over",
        calib_pipeline::html::VERSION,
        a.files.robot.display(),
        a.files.measurements.display(),
        margin_words(cal),
    );
    let comment = carried
        .iter()
        .fold(comment, |c, line| format!("{c}\n{line}"));
    write_atomically(path, &robot_toml(&cal.legs, &cal.sets, &comment))
        .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    println!(
        "calibrated robot written to {}: each certified leg's geometry fits every \
         measurement ({}), chosen towards the centre of the leg lengths it predicts over {over}",
        path.display(),
        margin_words(cal)
    );
    Ok(())
}

/// --workspace: the accuracy of the calibrated robot (over its certified sets) against the
/// uncalibrated one, printed.
fn certify_accuracy(
    a: &Args,
    robot: &[calib_gough::files::LegSpec],
    w: &calib_gough::workspace::Workspace,
    cal: &CalibratedRobot,
    u: &Uncertainty,
    pose_seconds: f64,
) -> AccuracyReport {
    let report = super::accuracy::with_spinner(pose_seconds, true, || {
        accuracy_report(
            &AccuracyProblem::over_sets(&cal.legs, &cal.sets, w),
            Some(&AccuracyProblem::new(robot, w)),
            Some(u.len),
            &AccuracySettings {
                pose_seconds,
                max_set_boxes: a.max_set_boxes,
                map_cells: a.map_cells,
                ..AccuracySettings::default()
            },
            a.report.is_some(),
        )
    });
    println!();
    super::accuracy::print_report(&report, "the calibrated robot", &a.workspace_name());
    report
}

/// What the certificate shows of the run.
struct Run<'a> {
    results: &'a [LegResult],
    findings: &'a [Vec<String>],
    /// The error bounds certified with (scaled by --error-scale).
    u: &'a Uncertainty,
    scale_words: &'a [String],
    /// What was carried over from a calibrated robot file, in words.
    carried: &'a [String],
    seconds: f64,
    accuracy: Option<&'a AccuracyReport>,
}

/// --report: the calibration certificate.
fn write_certificate(
    a: &Args,
    path: &Path,
    input: &Files,
    run: &Run<'_>,
    names: ConfigurationNames<'_>,
) -> Result<(), Box<dyn std::error::Error>> {
    let (robot, data) = (&input.robot, &input.data);
    let fits: Vec<[f64; 7]> = fit_legs(robot, &data.configs).iter().map(|f| f.x).collect();
    let file = |role: &str, path: &Path, text: &str| {
        report_page::Input::new(role, &path.display().to_string(), text.as_bytes())
    };
    let inputs = vec![
        file("robot geometry", &a.files.robot, &input.robot_text),
        file("measurements", &a.files.measurements, &input.data_text),
        file("error bounds", &a.uncertainty, &input.u_text),
    ];
    let page = ReportPage {
        title: format!(
            "{}-leg parallel robot, {} configurations",
            robot.len(),
            data.configs.len()
        ),
        command: report_page::command_line(),
        date: report_page::now(),
        inputs,
        configurations: data.configs.len(),
        error_bounds: report_page::error_bounds(run.u, data.rodrigues)
            .into_iter()
            .chain((!run.scale_words.is_empty()).then(|| {
                (
                    "found by --error-scale auto".into(),
                    run.scale_words.join(" "),
                )
            }))
            .collect(),
        settings: settings(a)
            .into_iter()
            .chain(
                (!run.carried.is_empty()).then(|| ("carried over".into(), run.carried.join("; "))),
            )
            .collect(),
        seconds: run.seconds,
        legs: run
            .results
            .iter()
            .zip(run.findings)
            .map(|(r, found)| LegEntry {
                result: r,
                nominal: robot[r.leg].nominal.params(),
                least_squares: std::slice::from_ref(&fits[r.leg]),
                identifiability: found,
            })
            .collect(),
        names,
        sections: run.accuracy.iter().map(|r| r.section()).collect(),
    }
    .to_html()?;
    write_atomically(path, &page)
        .map_err(|e| format!("{}: cannot write the certificate: {e}", path.display()))?;
    println!("certificate written to {}", path.display());
    Ok(())
}

/// --json: the report, with --error-scale's bracket under `error_scale`.
fn write_json(
    path: &Path,
    results: &[LegResult],
    total: f64,
    scale_json: Option<serde_json::Value>,
) -> Result<(), Box<dyn std::error::Error>> {
    let mut value = serde_json::to_value(report(results, total))?;
    if let Some(scale) = scale_json {
        value["error_scale"] = scale;
    }
    let text = serde_json::to_string_pretty(&value)?;
    write_atomically(path, &text)
        .map_err(|e| format!("{}: cannot write the report: {e}", path.display()))?;
    println!("report written to {}", path.display());
    Ok(())
}

/// The margins the calibrated legs keep, in words: "every error bound with 5% to spare".
fn margin_words(cal: &CalibratedRobot) -> String {
    let smallest = cal
        .points
        .iter()
        .flatten()
        .map(|p| p.margin)
        .fold(f64::INFINITY, f64::min);
    if smallest > 0.0 && smallest.is_finite() {
        format!(
            "within every error bound with at least {:.0}% of it to spare",
            100.0 * smallest
        )
    } else {
        "within every error bound".to_string()
    }
}

impl Args {
    /// The certification's options.
    fn options(&self) -> CertifyOptions {
        CertifyOptions {
            legs: self.legs.clone(),
            fast: self.fast,
            sweep: self.sweep,
            pave: self.pave,
            tolerance: self.tolerance,
            max_boxes: self.max_boxes,
            max_seconds: self.max_seconds,
            max_outliers: self.outliers.max_outliers,
        }
    }

    fn workspace_name(&self) -> String {
        self.workspace
            .as_ref()
            .map_or_else(String::new, |p| p.display().to_string())
    }
}

fn print_leg(r: &LegResult, names: &ConfigurationNames<'_>, budget: OutlierBudget) {
    println!(
        "== leg {} — {:?} ({} iterations to x1, {} boxes, {:.3} s)",
        r.leg + 1,
        r.status,
        r.iterations,
        r.boxes,
        r.seconds
    );
    let mut rows = vec![("x0", Some(r.x0)), ("x1", r.x1)];
    if let Some(x2) = r.x2 {
        rows.push(("x2", x2));
    }
    if r.converged.is_some() {
        rows.push(("outer", r.outer));
    }
    if let Some(inner) = r.inner {
        rows.push(("inner", Some(inner)));
    }
    print!("{}", table(&rows));
    if budget == OutlierBudget::Auto {
        println!("{}", verdict::auto_outliers(r.tolerated, r.status));
    }
    for (k, sentence) in verdict::verdict(r, names).iter().enumerate() {
        // The verdict, then its evidence indented under it.
        let indent = if k >= 2 { "  " } else { "" };
        println!("{indent}{sentence}");
    }
    if let (Some(ratio), Some(meaning)) = (verdict::width_ratios(r), verdict::tightness(r)) {
        let which = if r.converged.is_some() { "outer" } else { "x1" };
        println!("{which}/inner width: {}", ratios(&ratio));
        println!("  {meaning}");
    }
    if let Some(line) = verdict::touching_x0(r) {
        println!("note: {line}");
    }
    if let Some(line) = verdict::outliers(r, names) {
        println!("{line}");
    }
    if let Some((n, inner, outer)) = r.paving {
        println!("paving: {n} boxes, inner volume {inner:.3e}, outer volume {outer:.3e}");
    }
}

/// The last component of a path, as shown in messages ("measurements.csv").
fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// The settings of the run, in words, for the certificate.
fn settings(a: &Args) -> Vec<(String, String)> {
    let legs = a.legs.as_ref().map_or("all".into(), |l| {
        l.iter()
            .map(|k| k.to_string())
            .collect::<Vec<_>>()
            .join(", ")
    });
    let mode = if a.fast {
        "the paper's fixed point x1 only (--fast)".to_string()
    } else {
        format!(
            "tight hull: refine until outer width <= {} x inner width (--tolerance {}), at most {} \
             boxes{} per leg",
            1.0 + a.tolerance,
            a.tolerance,
            a.max_boxes,
            a.max_seconds
                .map_or(String::new(), |s| format!(" and {s} s"))
        )
    };
    let yes_no = |b: bool| if b { "yes" } else { "no" }.to_string();
    vec![
        ("legs".into(), legs),
        ("outer box".into(), mode),
        (
            "outliers tolerated per leg".into(),
            match a.outliers.max_outliers {
                OutlierBudget::Fixed(q) => q.to_string(),
                OutlierBudget::Auto => "auto: per leg, the smallest number not proved empty".into(),
            },
        ),
        ("128-box sweep (x2)".into(), yes_no(a.sweep)),
        (
            "paving".into(),
            a.pave
                .map_or("no".into(), |t| format!("to relative width {t}")),
        ),
        ("threads".into(), rayon::current_num_threads().to_string()),
    ]
}
