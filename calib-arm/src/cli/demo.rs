//! `arm demo`: the main job on the embedded default.

use super::output::{print_identifiability, print_outcome, spinner, write_certificate, write_json};
use calib_arm::certification::ArmRun;
use calib_arm::certification::{arm_settings, certify_arm, RunOptions};
use calib_arm::report_page::ArmReportPage;
use calib_arm::simulate::Simulation;
use calib_arm::simulate::{simulate, Uncertainty};
use calib_arm::write::{measurements_csv, robot_toml, uncertainty_toml, write_data_set};
use calib_arm::{builtin_arm, Arm};
use calib_pipeline::html::{command_line, now, Input};
use calib_pipeline::verdict::ConfigurationNames;
use calib_pipeline::Depth;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Number of simulated configurations.
    #[arg(long, default_value_t = 50)]
    configs: usize,
    /// Random seed of the simulation.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Also refine towards the tight hull, for at most --max-seconds.
    #[arg(long)]
    hull: bool,
    /// With --hull: stop refining after this many seconds.
    #[arg(long, value_name = "SECONDS", default_value_t = 120.0)]
    max_seconds: f64,
    /// Write the data set, report.json and certificate.html into this folder.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Write the calibration certificate (one self-contained HTML page) to this file.
    #[arg(long, value_name = "FILE")]
    report: Option<PathBuf>,
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    if a.configs == 0 {
        return Err("--configs: at least one configuration".into());
    }
    let arm = builtin_arm();
    let sim = simulate(&arm, a.configs, a.seed, Uncertainty::TRACKER, 1.0, &[]);
    println!(
        "built-in 6-axis arm (UR5 nominal geometry), {} free parameters; {} simulated \
         configurations (seed {}), tracker ±{} mm per coordinate, encoders ±{}°",
        arm.free().iter().filter(|f| **f).count(),
        a.configs,
        a.seed,
        sim.uncertainty.pos,
        sim.uncertainty.joint_deg
    );
    if let Some(dir) = &a.out {
        write_data_set(dir, &arm, &sim)
            .map_err(|e| format!("{}: cannot write the data set: {e}", dir.display()))?;
    }
    let settings = arm_settings()
        .with_hull_tolerance(0.10)
        .with_hull_budget(10_000, Some(a.max_seconds));
    let options = RunOptions {
        depth: if a.hull { Depth::Hull } else { Depth::Fast },
        lsq: true,
    };
    let bar = spinner("certifying (about ten seconds in a release build; --hull: --max-seconds)");
    let run = certify_arm(&arm, &sim.readings, &sim.uncertainty, options, &settings)?;
    bar.finish_and_clear();
    let lines: Vec<usize> = (2..2 + a.configs).collect();
    let names = ConfigurationNames {
        file: "measurements.csv",
        lines: &lines,
        carried: None,
    };
    print_identifiability(&run);
    print_outcome(&run, &names, 0);
    print_truth(&arm, &sim, &run);
    if let Some(dir) = &a.out {
        let path = dir.join("report.json");
        write_json(&path, &run, &names, 0, serde_json::Map::new())?;
        println!("wrote the data set and report.json to {}", dir.display());
    }
    let pages: Vec<PathBuf> = a
        .out
        .iter()
        .map(|d| d.join("certificate.html"))
        .chain(a.report.clone())
        .collect();
    if !pages.is_empty() {
        let page = certificate(&a, &arm, &sim, &run, names);
        for path in &pages {
            write_certificate(path, &page)?;
        }
    }
    Ok(0)
}

/// Whether the simulated truth lies in the outer box, in words.
fn print_truth(arm: &Arm, sim: &Simulation, run: &ArmRun) {
    let free = arm.free();
    if let Some(outer) = &run.outcome.outer {
        let inside = (0..outer.len())
            .filter(|&j| free[j])
            .filter(|&j| outer[j].contains(sim.truth[j]))
            .count();
        println!(
            "truth (known in a simulation): inside the outer box in {inside} of {} free parameters",
            free.iter().filter(|f| **f).count()
        );
    }
}

/// The certificate of the run, its inputs the files `--out` writes.
fn certificate<'a>(
    a: &Args,
    arm: &Arm,
    sim: &'a Simulation,
    run: &'a ArmRun,
    names: ConfigurationNames<'a>,
) -> ArmReportPage<'a> {
    let joints = arm.joints.len();
    let generated = |what: &str| format!("{what} (built-in arm, simulated, seed {})", a.seed);
    ArmReportPage {
        title: format!(
            "built-in {joints}-axis arm, {} simulated configurations",
            a.configs
        ),
        command: command_line(),
        date: now(),
        inputs: vec![
            Input::new(
                "robot geometry",
                &generated("robot.toml"),
                robot_toml(arm).as_bytes(),
            ),
            Input::new(
                "measurements",
                &generated("measurements.csv"),
                measurements_csv(&sim.readings, joints).as_bytes(),
            ),
            Input::new(
                "error bounds",
                &generated("uncertainty.toml"),
                uncertainty_toml(&sim.uncertainty).as_bytes(),
            ),
        ],
        uncertainty: sim.uncertainty,
        settings: vec![(
            "outer box".into(),
            if a.hull {
                format!(
                    "tight hull: outer width <= 1.1 x inner width, at most {} s",
                    a.max_seconds
                )
            } else {
                "the paper's fixed point x1 with certified inner bounds (no --hull)".into()
            },
        )],
        run,
        names,
        tolerated: 0,
        truth: Some(&sim.truth),
        error_scale: Vec::new(),
    }
}
