//! `gough certify`.

use super::DataFiles;
use calib_core::{EmptinessProof, Status};
use calib_gough::certification::{certify_legs, report, CertifyOptions, LegResult};
use calib_gough::files::{check_uncertainty, read_measurements, read_robot, read_uncertainty};
use calib_gough::plot;
use calib_gough::report::{ratios, table, write_atomically};
use calib_gough::PARAMETER_NAMES;
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
    /// Tolerate up to Q bad configurations per leg: the boxes then contain every parameter vector
    /// that fits all but at most Q configurations, and the configurations proved to be outliers
    /// are listed. Costs about C(configurations, Q) certifications per leg.
    #[arg(long, value_name = "Q", default_value_t = 0)]
    max_outliers: usize,
    /// Also run the paper's 128-box bisection sweep and report its hull x2.
    #[arg(long)]
    sweep: bool,
    /// Also pave the solution set with boxes down to this relative width (e.g. 0.1).
    #[arg(long, value_name = "TOL")]
    pave: Option<f64>,
    /// Write the JSON report (schema version 1) to this file.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Write one SVG per leg into this folder: x0, x1, x2, the outer and the inner box in the
    /// projections (ax, ay), (bx, by) and (az, l).
    #[arg(long, value_name = "DIR")]
    plots: Option<PathBuf>,
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    let robot = read_robot(&a.files.robot)?;
    let data = read_measurements(&a.files.measurements, robot.len())?;
    let u = read_uncertainty(&a.uncertainty)?;
    check_uncertainty(&a.uncertainty, &u, data.rodrigues)?;
    let options = CertifyOptions {
        legs: a.legs.clone(),
        fast: a.fast,
        sweep: a.sweep,
        pave: a.pave,
        tolerance: a.tolerance,
        max_boxes: a.max_boxes,
        max_seconds: a.max_seconds,
        max_outliers: a.max_outliers,
    };
    // Option errors before any work (certify_legs checks them again).
    let (legs, _) = options.validate(robot.len(), data.configs.len())?;
    let start = Instant::now();
    // Progress on a terminal only (indicatif draws nothing when stderr is not a terminal).
    let bar = indicatif::ProgressBar::new(legs.len() as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("certifying legs {bar:30} {pos}/{len} [{elapsed}]")
            .expect("static template"),
    );
    let results = certify_legs(&robot, &data.configs, &u, &options, &|| bar.inc(1))?;
    bar.finish_and_clear();
    let total = start.elapsed().as_secs_f64();
    let mut any_empty = false;
    for r in &results {
        any_empty |= r.status == Status::Empty;
        print_leg(r, &data.lines, &a.files.measurements, a.max_outliers);
    }
    println!("total: {} legs in {total:.3} s", results.len());
    if let Some(dir) = &a.plots {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("{}: cannot create: {e}", dir.display()))?;
        for r in &results {
            let mut boxes = vec![("x0", "black", r.x0)];
            boxes.extend(r.x1.map(|b| ("x1", "#369", b)));
            boxes.extend(r.x2.flatten().map(|b| ("x2", "#693", b)));
            if !a.fast {
                boxes.extend(r.outer.map(|b| ("outer", "#939", b)));
            }
            boxes.extend(r.inner.map(|b| ("inner", "#c33", b)));
            let title = format!("leg {}: {:?}", r.leg + 1, r.status);
            let svg =
                plot::nested_boxes(&boxes, &[(0, 1), (3, 4), (2, 6)], &PARAMETER_NAMES, &title);
            let path = dir.join(format!("leg{}.svg", r.leg + 1));
            write_atomically(&path, &svg)
                .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        }
        println!("plots written to {}", dir.display());
    }
    if let Some(path) = &a.json {
        let text = serde_json::to_string_pretty(&report(&results, total))?;
        write_atomically(path, &text)
            .map_err(|e| format!("{}: cannot write the report: {e}", path.display()))?;
        println!("report written to {}", path.display());
    }
    Ok(if any_empty { 2 } else { 0 })
}

/// "configurations 4, 8 (measurements.csv lines 5, 9)": configurations named by number and line.
fn name_configurations(configs: &[usize], lines: &[usize], file: &Path) -> String {
    let file = file
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let numbers: Vec<String> = configs.iter().map(|k| (k + 1).to_string()).collect();
    let at: Vec<String> = configs
        .iter()
        .map(|&k| lines.get(k).map_or("?".into(), |l| l.to_string()))
        .collect();
    let (noun, line) = if configs.len() == 1 {
        ("configuration", "line")
    } else {
        ("configurations", "lines")
    };
    format!(
        "{noun} {} ({file} {line} {})",
        numbers.join(", "),
        at.join(", ")
    )
}

/// What proved a leg empty, in words.
fn proof_in_words(proof: Option<EmptinessProof>) -> String {
    match proof {
        Some(EmptinessProof::CheapRejection { measurement }) => format!(
            "configuration {} fits no parameter vector left after contraction",
            measurement + 1
        ),
        Some(EmptinessProof::LpInfeasible) => {
            "the linear relaxation of the data has no solution (checked Farkas certificate)".into()
        }
        Some(EmptinessProof::EmptyIntersection { parameter }) => format!(
            "the certified lower and upper bounds of {} crossed",
            PARAMETER_NAMES.get(parameter).unwrap_or(&"a parameter")
        ),
        Some(EmptinessProof::Subdivision) => {
            "every piece of a subdivision of x0 was proved empty".into()
        }
        Some(EmptinessProof::EverySubset) => {
            "whichever configurations are dropped, the rest was proved inconsistent".into()
        }
        None => "no proof recorded".into(),
    }
}

fn print_leg(r: &LegResult, lines: &[usize], file: &Path, max_outliers: usize) {
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
    match r.status {
        Status::Empty => {
            let tolerated = if max_outliers > 0 {
                format!(", even with {max_outliers} of them tolerated as outliers")
            } else {
                String::new()
            };
            println!(
                "verdict: no parameter vector in x0 fits the measurements within their error \
                 bounds{tolerated} — proved: {}",
                proof_in_words(r.emptiness)
            );
            if let Some(conflict) = &r.conflict {
                let named = name_configurations(conflict, lines, file);
                if conflict.len() == 1 {
                    println!("conflict: {named} alone fits no parameter vector of x0.");
                } else {
                    println!(
                        "conflict: {named} cannot be fitted together; with any one of them \
                         removed the rest is not proved inconsistent."
                    );
                }
                println!(
                    "  re-measure them, or run with --max-outliers {} to tolerate {} bad \
                     configuration{}",
                    max_outliers + 1,
                    max_outliers + 1,
                    if max_outliers == 0 { "" } else { "s" }
                );
            } else {
                println!("  run with a larger --max-outliers, or check the model and error bounds");
            }
        }
        Status::Consistent => {
            println!("verdict: consistent (a certified witness satisfies every measurement box)")
        }
        Status::Undecided => println!(
            "verdict: undecided (no certified witness found; the outer box is still a certified \
             enclosure)"
        ),
    }
    if let (Some(outer), Some(inner)) = (r.outer, r.inner) {
        let ratio: [f64; 7] = core::array::from_fn(|j| outer[j].wid() / inner[j].wid());
        let which = if r.converged.is_some() { "outer" } else { "x1" };
        println!("{which}/inner width: {}", ratios(&ratio));
        match r.converged {
            Some(true) => println!(
                "  the true range of each parameter lies between inner and outer: outer overstates \
                 it by at most the ratio"
            ),
            Some(false) => println!(
                "  budget spent before every ratio reached the tolerance (--max-boxes, \
                 --max-seconds); both boxes are still certified"
            ),
            None => println!("  (--fast: the paper's x1 only; drop --fast for the tight hull)"),
        }
    }
    if max_outliers > 0 && r.status != Status::Empty {
        if r.outliers.is_empty() {
            println!(
                "outliers (at most {max_outliers} tolerated): no configuration is proved to be one"
            );
        } else {
            println!(
                "outliers (at most {max_outliers} tolerated): {} — every parameter vector that \
                 fits the rest misfits {}",
                name_configurations(&r.outliers, lines, file),
                if r.outliers.len() == 1 { "it" } else { "them" }
            );
        }
    }
    if let Some((n, inner, outer)) = r.paving {
        println!("paving: {n} boxes, inner volume {inner:.3e}, outer volume {outer:.3e}");
    }
    println!();
}
