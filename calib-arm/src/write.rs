//! Writing the arm's files (the formats [`crate::files`] reads): a simulated data set, or an arm
//! description. Every file is written to a temporary name and renamed, so an interrupted run leaves
//! no half-written file.

use crate::params;
use crate::robot::Arm;
use crate::simulate::{Reading, Simulation, Uncertainty};
use calib_pipeline::write_atomically;
use std::fmt::Write as _;
use std::path::Path;

/// Shortest round-trip text of a number (what the parsers read back exactly).
fn num(v: f64) -> String {
    format!("{v:?}")
}

fn list(v: &[f64]) -> String {
    let items: Vec<String> = v.iter().map(|x| num(*x)).collect();
    format!("[{}]", items.join(", "))
}

/// `robot.toml` for `arm`: one `[[joint]]` table per joint, `[base]`, `[tool]`.
pub fn robot_toml(arm: &Arm) -> String {
    let mut s = String::from(
        "# Serial arm: standard Denavit-Hartenberg + Hayati beta, mm and degrees.\n\
         # radius: prior half-widths (theta, d, a, alpha, beta); 0 fixes a parameter.\n",
    );
    for j in &arm.joints {
        let [theta, d, a, alpha, beta] = j.nominal;
        let _ = write!(
            s,
            "\n[[joint]]\ntheta_deg = {}\nd = {}\na = {}\nalpha_deg = {}\nbeta_deg = {}\nradius = {}\n",
            num(theta),
            num(d),
            num(a),
            num(alpha),
            num(beta),
            list(&j.radius)
        );
    }
    let _ = write!(
        s,
        "\n[base]  # tracker frame to robot base: Trans(xyz) Rz(rz) Ry(ry) Rx(rx)\nxyz = {}\nrpy_deg = {}\nradius = {}\n",
        list(&arm.base[..3]),
        list(&arm.base[3..]),
        list(&arm.base_radius)
    );
    let _ = write!(
        s,
        "\n[tool]  # tracked point in the flange frame\nxyz = {}\nradius = {}\n",
        list(&arm.tool),
        list(&arm.tool_radius)
    );
    if let Some(t) = &arm.tool_rotation {
        let _ = write!(
            s,
            "# the measured frame's rotation on the flange (6-DoF probes): Rz(rz) Ry(ry) Rx(rx)\n\
             rpy_deg = {}\nrotation_radius = {}\n",
            list(&t.rpy_deg),
            list(&t.radius)
        );
    }
    s
}

/// `measurements.csv`: header `q1,…,qN,px,py,pz`, one row per configuration.
pub fn measurements_csv(readings: &[Reading], joints: usize) -> String {
    let mut s: String = (1..=joints).map(|i| format!("q{i},")).collect();
    s.push_str("px,py,pz\n");
    for r in readings {
        let row: Vec<String> = r
            .joints_deg
            .iter()
            .chain(&r.point)
            .map(|v| num(*v))
            .collect();
        s.push_str(&row.join(","));
        s.push('\n');
    }
    s
}

/// `uncertainty.toml`: the half-widths of the error bounds.
pub fn uncertainty_toml(u: &Uncertainty) -> String {
    format!(
        "# Half-widths of the measurement errors: every true value lies within +- these.\n\
         joint_deg = {}  # joint readings, degrees\npos = {}  # tracked coordinates, mm\n",
        num(u.joint_deg),
        num(u.pos)
    )
}

/// `truth.json`: the true parameters by name (degrees and mm).
pub fn truth_json(truth: &[f64], joints: usize) -> String {
    let names = params::names(joints);
    let mut s = String::from("{\n");
    for (i, ((name, _), v)) in names.iter().zip(truth).enumerate() {
        let comma = if i + 1 < truth.len() { "," } else { "" };
        let _ = writeln!(s, "  \"{name}\": {}{comma}", num(*v));
    }
    s.push_str("}\n");
    s
}

/// Writes `robot.toml` (the nominal arm), `measurements.csv`, `uncertainty.toml` and `truth.json`
/// into `dir` (created if missing).
pub fn write_data_set(dir: &Path, arm: &Arm, sim: &Simulation) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let joints = arm.joints.len();
    write_atomically(&dir.join("robot.toml"), &robot_toml(arm))?;
    write_atomically(
        &dir.join("measurements.csv"),
        &measurements_csv(&sim.readings, joints),
    )?;
    write_atomically(
        &dir.join("uncertainty.toml"),
        &uncertainty_toml(&sim.uncertainty),
    )?;
    write_atomically(&dir.join("truth.json"), &truth_json(&sim.truth, joints))
}
