//! `arm import`.

use calib_arm::vendor::{agreement, chain_to_arm, ur_yaml, urdf, ImportRadii};
use calib_pipeline::{read_text, write_atomically};
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
#[command(group = clap::ArgGroup::new("source").required(true))]
pub struct Args {
    /// UR's kinematics YAML (`default_kinematics.yaml`, or the calibration the UR driver
    /// extracts from a controller): x, y, z (m), roll, pitch, yaw (rad) per joint.
    #[arg(long, value_name = "FILE", group = "source")]
    ur_yaml: Option<PathBuf>,
    /// A URDF: the chain of revolute joints from --base-link to --tip-link.
    #[arg(long, value_name = "FILE", group = "source")]
    urdf: Option<PathBuf>,
    /// With --urdf: the chain's first link [default: the root link].
    #[arg(long, value_name = "LINK", requires = "urdf")]
    base_link: Option<String>,
    /// With --urdf: the chain's last link, the last moving joint's child [default: the end of
    /// the chain].
    #[arg(long, value_name = "LINK", requires = "urdf")]
    tip_link: Option<String>,
    /// The prior half-width of every free angle (theta, alpha, beta), degrees.
    #[arg(long, value_name = "DEG", default_value_t = 0.1)]
    angle_radius: f64,
    /// The prior half-width of every free length (d, a), mm.
    #[arg(long, value_name = "MM", default_value_t = 1.0)]
    length_radius: f64,
    /// The robot file to write (robot.toml): the joints' exact parameters and priors; base and
    /// tool at the vendor's base and flange, unknown until `arm register`.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
}

/// Joint configurations at which the import's forward kinematics are compared with the vendor's.
const AGREEMENT_CONFIGURATIONS: usize = 64;
/// The largest flange distance (mm) an exact import may show: rounding of metre-scale chains.
const AGREEMENT_MM: f64 = 1e-6;
/// The largest flange rotation (radians) an exact import may show.
const AGREEMENT_RAD: f64 = 1e-9;

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    for (v, name) in [
        (a.angle_radius, "--angle-radius"),
        (a.length_radius, "--length-radius"),
    ] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(format!("{name} {v}: expected a finite half-width >= 0").into());
        }
    }
    let (origins, source) = match (&a.ur_yaml, &a.urdf) {
        (Some(p), _) => (ur_yaml::parse(p, &read_text(p)?)?.origins, p),
        (None, Some(p)) => (
            urdf::parse(
                p,
                &read_text(p)?,
                a.base_link.as_deref(),
                a.tip_link.as_deref(),
            )?,
            p,
        ),
        (None, None) => return Err("--ur-yaml or --urdf: which file to import".into()),
    };
    let radii = ImportRadii {
        angle_deg: a.angle_radius,
        length_mm: a.length_radius,
    };
    let arm = chain_to_arm(&origins, radii).map_err(|e| format!("{}: {e}", source.display()))?;
    // The claim the file's header makes, checked: the model reproduces the vendor's flange.
    let (distance, angle, at) = agreement(&origins, &arm, AGREEMENT_CONFIGURATIONS);
    if distance > AGREEMENT_MM || angle > AGREEMENT_RAD {
        let q: Vec<String> = at
            .iter()
            .map(|v| format!("{:.1}", v.to_degrees()))
            .collect();
        return Err(format!(
            "{}: the imported parameters do not reproduce the vendor's forward kinematics: the \
             flanges differ by up to {distance:.3e} mm and {:.3e}° (at q = ({})°); nothing written",
            source.display(),
            angle.to_degrees(),
            q.join(", ")
        )
        .into());
    }
    let text = format!(
        "# imported by certicalib {} from {} (exact: the flanges agree within {distance:.1e} mm \
         and {:.1e}° at {AGREEMENT_CONFIGURATIONS} configurations)\n\
         # base and tool: placeholders until `arm register` finds them from measurements.\n{}",
        env!("CARGO_PKG_VERSION"),
        source.display(),
        angle.to_degrees(),
        calib_arm::write::robot_toml(&arm)
    );
    write_atomically(&a.out, &text)
        .map_err(|e| format!("{}: cannot write: {e}", a.out.display()))?;
    println!(
        "{} joints imported from {}: {} free joint parameters (±{}° angles, ±{} mm lengths)",
        arm.joints.len(),
        source.display(),
        arm.joints
            .iter()
            .flat_map(|j| j.radius)
            .filter(|r| *r > 0.0)
            .count(),
        a.angle_radius,
        a.length_radius
    );
    println!(
        "{:<6} {:>10} {:>10} {:>10} {:>10} {:>10}",
        "joint", "theta °", "d mm", "a mm", "alpha °", "beta °"
    );
    for (i, j) in arm.joints.iter().enumerate() {
        let [t, d, aa, al, b] = j.nominal;
        println!(
            "{:<6} {t:>10.4} {d:>10.4} {aa:>10.4} {al:>10.4} {b:>10.4}",
            i + 1
        );
    }
    println!(
        "the model's flange agrees with the vendor's within {distance:.1e} mm and {:.1e}° at \
         {AGREEMENT_CONFIGURATIONS} configurations spread over ±180° per joint",
        angle.to_degrees()
    );
    println!(
        "wrote {}; next: `arm register --robot {} --measurements …` finds the tracker-to-base \
         transform and the tool point",
        a.out.display(),
        a.out.display()
    );
    Ok(0)
}
