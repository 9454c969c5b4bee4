//! Helpers shared by the end-to-end tests: run the `gough` binary, simulate a data set, certify it.
// Each test file uses its own subset of the helpers.
#![allow(dead_code)]

use crate::scratch_dir::ScratchDir;
use std::path::Path;
use std::process::{Command, Output};

pub fn gough(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gough"))
        .args(args)
        .output()
        .expect("the gough binary runs")
}

/// A scratch directory for one test, removed when it passes.
pub fn tempdir(name: &str) -> ScratchDir {
    ScratchDir::new(&format!("gough-test-{name}"))
}

pub fn simulate(dir: &Path, seed: u64, extra: &[&str]) {
    simulate_configs(dir, 21, seed, extra);
}

/// `gough simulate --configs CONFIGS --seed SEED --out DIR` and `extra`: the built-in hexapod,
/// so every seed measures the same truth, at other poses with other noise.
pub fn simulate_configs(dir: &Path, configs: usize, seed: u64, extra: &[&str]) {
    let (seed, configs) = (seed.to_string(), configs.to_string());
    let mut args = vec![
        "simulate",
        "--configs",
        &configs,
        "--seed",
        &seed,
        "--out",
        dir.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let out = gough(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

pub fn certify(dir: &Path, extra: &[&str]) -> Output {
    let f = |n: &str| dir.join(n).to_str().unwrap().to_string();
    let (r, m, u, j) = (
        f("robot.toml"),
        f("measurements.csv"),
        f("uncertainty.toml"),
        f("report.json"),
    );
    let mut args = vec![
        "certify",
        "--robot",
        &r,
        "--measurements",
        &m,
        "--uncertainty",
        &u,
        "--json",
        &j,
    ];
    args.extend_from_slice(extra);
    gough(&args)
}

pub fn report(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap()
}

/// The seven true parameters of leg `i` (0-based) from truth.json.
pub fn truth_values(truth: &serde_json::Value, i: usize) -> Vec<f64> {
    let t = &truth["legs"][i];
    t["a"]
        .as_array()
        .unwrap()
        .iter()
        .chain(t["b"].as_array().unwrap())
        .map(|v| v.as_f64().unwrap())
        .chain([t["l"].as_f64().unwrap()])
        .collect()
}

/// A random workspace near the simulator's: ranges of 0.5 to 4 cm about x = y = 0, z = 60 cm,
/// a tilt of 1° to `max_tilt_deg`, a stroke half of the time.
pub fn random_workspace(
    rng: &mut rand::rngs::StdRng,
    max_tilt_deg: f64,
) -> calib_gough::workspace::Workspace {
    use rand::Rng;
    let range = |c: f64, w: f64, rng: &mut rand::rngs::StdRng| {
        let lo = c - rng.random_range(0.5..w);
        [lo, lo + rng.random_range(0.5..w)]
    };
    calib_gough::workspace::Workspace {
        x: range(0.0, 4.0, rng),
        y: range(0.0, 4.0, rng),
        z: range(60.0, 4.0, rng),
        tilt_deg: rng.random_range(1.0..max_tilt_deg),
        stroke: rng.random_bool(0.5).then_some([0.0, 15.0]),
    }
}

/// The prior a test calibrates from: each leg of `nominal` ± 0.1 cm (the simulator's design
/// values, as `gough design` plans without a robot file).
pub fn priors(nominal: &[calib_gough::geometry::Leg]) -> Vec<calib_gough::files::LegSpec> {
    nominal
        .iter()
        .map(|&nominal| calib_gough::files::LegSpec {
            nominal,
            radius: [0.1; 7],
        })
        .collect()
}
