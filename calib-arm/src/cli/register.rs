//! `arm register`.

use super::DataFiles;
use calib_arm::files::parse_robot_and_set;
use calib_arm::register::{
    register_tool_rotation, register_with, Registration, RegistrationPriors, ToolPoint,
};
use calib_arm::robot::ToolRotation;
use calib_pipeline::stored_set::StoredSet;
use calib_pipeline::{read_text, write_atomically};
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    files: DataFiles,
    /// The prior half-widths written around the registered base: position (mm) and rotations
    /// (degrees).
    #[arg(
        long,
        value_name = "MM,DEG",
        value_delimiter = ',',
        num_args = 1,
        default_value = "2,0.1"
    )]
    base_radius: Vec<f64>,
    /// The prior half-width written around the registered tool point (mm) [default: 2, or 0
    /// when the tool point is kept].
    #[arg(long, value_name = "MM")]
    tool_radius: Option<f64>,
    /// Fit the tool point, or keep the --robot file's. `auto` fits it when the rows tell it from
    /// the base (their flange orientations spread at least 0.1° across every direction of the
    /// tool) and otherwise keeps it, fixed (--tool-radius 0), with a warning.
    #[arg(long, value_enum, value_name = "WHICH", default_value = "auto")]
    tool: ToolPoint,
    /// With --orientation-columns: the prior half-width written around the registered tool
    /// frame's rotation (degrees).
    #[arg(long, value_name = "DEG", default_value_t = 0.5)]
    tool_rotation_radius: f64,
    /// The robot file to write: the --robot file's joints with the registered base and tool.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    let [base_mm, base_deg] = <[f64; 2]>::try_from(a.base_radius.clone()).map_err(|v| {
        format!(
            "--base-radius: expected MM,DEG (two numbers), found {}",
            v.len()
        )
    })?;
    let (arm, set) = parse_robot_and_set(&a.files.robot, &read_text(&a.files.robot)?)?;
    let data = a
        .files
        .columns
        .read(&a.files.measurements, arm.joints.len())?;
    let priors = RegistrationPriors {
        base_mm,
        base_deg,
        tool_mm: a.tool_radius.unwrap_or(2.0),
    };
    let mut r = register_with(&arm, &data.readings, priors, a.tool)
        .map_err(|e| format!("{}: {e}", a.files.measurements.display()))?;
    // An explicit --tool-radius is written as asked, around a kept tool point too.
    if let Some(radius) = a.tool_radius {
        r.arm.tool_radius = [radius; 3];
    }
    let rotation = match &data.orientations {
        Some(o) => {
            let (t, rms, max) =
                register_tool_rotation(&r.arm, &data.readings, o, a.tool_rotation_radius)
                    .map_err(|e| format!("{}: {e}", a.files.measurements.display()))?;
            r.arm.tool_rotation = Some(t);
            Some((t, rms, max))
        }
        None => None,
    };
    if let Some(w) = inseparable_warning(&r, &a) {
        println!("{w}");
    }
    print_registration(&a, &r, data.readings.len(), priors, rotation);
    write_registered(&a, &r, set.as_ref())?;
    Ok(0)
}

/// The warning when the rows cannot tell the tool point from the base (`None` when they can):
/// why, and what was done about it.
fn inseparable_warning(r: &Registration, a: &Args) -> Option<String> {
    let why = r.separability.reason()?;
    let robot = a.files.robot.display();
    let done = if !r.tool_kept {
        "The tool point is fitted as asked (--tool fit), but these rows do not determine it: \
         the base's position takes up any move of it"
            .to_string()
    } else {
        let radius = match a.tool_radius {
            Some(radius) if radius > 0.0 => format!(
                "written with the prior ± {radius} mm asked (--tool-radius {radius}), though a \
                 calibration on these rows cannot tell it from the base either"
            ),
            _ => "fixed (--tool-radius 0)".to_string(),
        };
        format!(
            "The tool point is kept from {robot} and {radius}; the base is fitted alone, its \
             position taking up any error of that tool point (right at these orientations, not \
             at others)"
        )
    };
    Some(format!(
        "warning: {why}. {done}. To find the tool point, register on configurations with \
         several flange orientations (turned by degrees about two axes or more){}.",
        if r.tool_kept {
            "; --tool fit fits it anyway"
        } else {
            ""
        }
    ))
}

/// The registration in words: base, tool point (and tool frame), residuals.
fn print_registration(
    a: &Args,
    r: &Registration,
    configurations: usize,
    priors: RegistrationPriors,
    rotation: Option<(ToolRotation, f64, f64)>,
) {
    let (base_mm, base_deg) = (priors.base_mm, priors.base_deg);
    let tool_radius = r.arm.tool_radius[0];
    let b = r.arm.base;
    println!(
        "registered on {} configurations of {}:",
        configurations,
        a.files.measurements.display()
    );
    println!(
        "  base (tracker frame): x {:.3} y {:.3} z {:.3} mm, rx {:.4} ry {:.4} rz {:.4}° (± {base_mm} mm, ± {base_deg}°)",
        b[0], b[1], b[2], b[3], b[4], b[5]
    );
    println!(
        "  tool point (flange frame): {:.3} {:.3} {:.3} mm (± {tool_radius} mm{}), {:.3} mm from \
         the flange",
        r.arm.tool[0],
        r.arm.tool[1],
        r.arm.tool[2],
        if r.tool_kept {
            format!(", kept from {}", a.files.robot.display())
        } else {
            String::new()
        },
        r.arm.tool.iter().map(|v| v * v).sum::<f64>().sqrt()
    );
    if let Some((t, rms, max)) = rotation {
        println!(
            "  tool frame (on the flange, Rz Ry Rx): rx {:.4} ry {:.4} rz {:.4}° (± {}°); \
             orientation residuals rms {rms:.4}°, max {max:.4}°",
            t.rpy_deg[0], t.rpy_deg[1], t.rpy_deg[2], a.tool_rotation_radius
        );
    }
    println!(
        "  residuals with the nominal joints: rms {:.4} mm, max {:.4} mm (closed-form start: rms \
         {:.4} mm; least squares {})",
        r.rms,
        r.max_abs,
        r.start_rms,
        if r.converged {
            "converged"
        } else {
            "did not converge"
        }
    );
    if b[4].abs() > 60.0 {
        println!(
            "  note: the base's ry is {:.1}°, near the rx/rz singularity at ±90°: its prior box \
             is poorly conditioned there",
            b[4]
        );
    }
}

/// --out: the robot file with the base and tool found, and the certified set of --robot (if it
/// has one) as its `[carried_set]`, in the frame it was certified in: `arm certify` joins its
/// rows to the new ones ([`calib_arm::carry`]); `predict` and `accuracy` do not read it.
fn write_registered(
    a: &Args,
    r: &Registration,
    set: Option<&StoredSet>,
) -> Result<(), Box<dyn std::error::Error>> {
    let found = match (r.tool_kept, r.separability.inseparable()) {
        (false, _) => "base and tool found",
        (true, false) => "base found, tool point kept",
        (true, true) => "base found, tool point kept (these rows cannot tell it from the base)",
    };
    let carried = set.map_or_else(String::new, |s| {
        calib_arm::carry::carried_set_toml(&a.files.robot, s)
    });
    let text = format!(
        "# registered by certicalib {} from {} and {}: {found}, joints as given\n{}{carried}",
        env!("CARGO_PKG_VERSION"),
        a.files.robot.display(),
        a.files.measurements.display(),
        calib_arm::write::robot_toml(&r.arm)
    );
    write_atomically(&a.out, &text)
        .map_err(|e| format!("{}: cannot write: {e}", a.out.display()))?;
    println!("wrote {}", a.out.display());
    Ok(())
}
