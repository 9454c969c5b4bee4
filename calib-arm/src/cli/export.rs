//! `arm export`.

use calib_arm::files::read_exportable_robot;
use calib_arm::vendor::{arm_to_chain, ur_yaml, urdf};
use calib_pipeline::write_atomically;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
#[command(group = clap::ArgGroup::new("target").required(true).multiple(true))]
pub struct Args {
    /// The robot file to export (e.g. `arm certify --write-calibrated`'s). A least-squares fit
    /// (`arm lsq --out`) is refused unless it was proved consistent with its measurements.
    #[arg(long, value_name = "FILE")]
    robot: PathBuf,
    /// Write UR's kinematics YAML (6 joints; the layout the UR driver loads).
    #[arg(long, value_name = "FILE", group = "target")]
    ur_yaml: Option<PathBuf>,
    /// The YAML's `hash` [default: this file's own checksum, `certicalib_…`; the UR driver then
    /// warns that it differs from the controller's calibration, which is true].
    #[arg(long, value_name = "HASH", requires = "ur_yaml")]
    hash: Option<String>,
    /// Write a URDF: base_link, a continuous joint per arm joint, a fixed `tool` link at the
    /// tool point.
    #[arg(long, value_name = "FILE", group = "target")]
    urdf: Option<PathBuf>,
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    let arm = read_exportable_robot(&a.robot)?;
    let chain = arm_to_chain(&arm).map_err(|e| format!("{}: {e}", a.robot.display()))?;
    let source = format!(
        "exported by certicalib {} from {}",
        env!("CARGO_PKG_VERSION"),
        a.robot.display()
    );
    // Check everything before writing anything.
    let yaml = match &a.ur_yaml {
        Some(_) => Some(
            ur_yaml::write(&chain, a.hash.as_deref(), &source)
                .map_err(|e| format!("{}: {e}", a.robot.display()))?,
        ),
        None => None,
    };
    if let (Some(path), Some(text)) = (&a.ur_yaml, yaml) {
        write_atomically(path, &text)
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        println!("wrote {} (UR kinematics YAML)", path.display());
    }
    if let Some(path) = &a.urdf {
        let name = a
            .robot
            .file_stem()
            .map_or("robot".into(), |s| s.to_string_lossy().into_owned());
        write_atomically(path, &urdf::write(&name, &chain, arm.tool))
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        println!("wrote {} (URDF)", path.display());
    }
    if arm.base != [0.0; 6] {
        println!(
            "note: the base transform (tracker frame to robot base) is not part of the exported \
             kinematics: it places the robot in the tracker's frame, not in its own"
        );
    }
    Ok(0)
}
