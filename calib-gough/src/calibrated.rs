//! The calibrated geometry (`gough certify --write-calibrated`): the robot file a controller
//! loads after calibration, each parameter at the midpoint of its certified outer box with the
//! outer half-width as its radius, so that the file's boxes contain the certified ones.

use crate::certification::LegResult;
use crate::files::LegSpec;
use crate::geometry::Leg;
use calib_pipeline::calibrated::midpoint_and_radius;
use std::fmt::Write as _;

/// The calibrated legs: per leg, the outer box's midpoint and a radius (rounded up, plus a
/// margin for the decimal text) whose box contains the outer box. Parameters fixed in `robot`
/// (radius 0) keep their value and radius 0. An error naming a leg without an outer box (proved
/// inconsistent): there is no calibrated geometry to write.
pub fn calibrated_robot(robot: &[LegSpec], results: &[LegResult]) -> Result<Vec<LegSpec>, String> {
    let mut out = robot.to_vec();
    for r in results {
        let outer = r.outer.ok_or_else(|| {
            format!(
                "leg {} was proved inconsistent with the data: there is no calibrated geometry \
                 to write (re-measure its conflicting configurations, or tolerate outliers)",
                r.leg + 1
            )
        })?;
        let spec = &robot[r.leg];
        let nominal = spec.nominal.params();
        let mut value = [0.0; 7];
        let mut radius = [0.0; 7];
        for j in 0..7 {
            if spec.radius[j] == 0.0 {
                value[j] = nominal[j];
                continue;
            }
            (value[j], radius[j]) = midpoint_and_radius(outer[j]);
        }
        out[r.leg] = LegSpec {
            nominal: Leg::from_params(&value),
            radius,
        };
    }
    Ok(out)
}

/// `robot.toml` text for `legs` (shortest round-trip decimals; read back bit-identical).
pub fn robot_toml(legs: &[LegSpec], comment: &str) -> String {
    let mut text = String::new();
    for line in comment.lines() {
        let _ = writeln!(text, "# {line}");
    }
    for spec in legs {
        let l = &spec.nominal;
        let _ = writeln!(
            text,
            "\n[[leg]]\na = {:?}\nb = {:?}\nl = {:?}\nradius = {:?}",
            l.a, l.b, l.l, spec.radius
        );
    }
    text
}
