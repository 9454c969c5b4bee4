//! The calibrated arm (`arm certify --write-calibrated`): the robot file a controller loads after
//! calibration, each free parameter at the midpoint of its certified outer box with a radius
//! whose box contains it (so `arm accuracy` bounds the error over every geometry the data allow).

use crate::robot::{Arm, Joint};
use calib_core::Interval;
use calib_pipeline::calibrated::midpoint_and_radius;

/// The calibrated arm from the certified outer box `outer` (the files' units, model order):
/// free parameters at the box's midpoint with a radius containing it, fixed ones (radius 0) as
/// they were. An error when there is no outer box (the data were proved inconsistent) or its
/// length does not match the arm.
pub fn calibrated_arm(arm: &Arm, outer: Option<&[Interval]>) -> Result<Arm, String> {
    let outer = outer.ok_or(
        "the data were proved inconsistent with the model and the error bounds: there is no \
         calibrated geometry to write (re-measure the conflicting configurations, or tolerate \
         outliers)",
    )?;
    let (mut value, mut radius) = (arm.nominal(), arm.radius());
    if outer.len() != value.len() {
        return Err(format!(
            "the certified box has {} parameters; the arm has {}",
            outer.len(),
            value.len()
        ));
    }
    for j in 0..value.len() {
        if radius[j] > 0.0 {
            (value[j], radius[j]) = midpoint_and_radius(outer[j]);
        }
    }
    Ok(with_parameters(arm.joints.len(), &value, &radius))
}

/// The arm with these values and half-widths (model order, the files' units).
fn with_parameters(joints: usize, value: &[f64], radius: &[f64]) -> Arm {
    let five = |v: &[f64], i: usize| -> [f64; 5] { core::array::from_fn(|k| v[5 * i + k]) };
    let tail = |v: &[f64], from: usize| -> Vec<f64> { v[5 * joints + from..].to_vec() };
    let (base, base_r, tool, tool_r) = (
        tail(value, 0),
        tail(radius, 0),
        tail(value, 6),
        tail(radius, 6),
    );
    Arm {
        joints: (0..joints)
            .map(|i| Joint {
                nominal: five(value, i),
                radius: five(radius, i),
            })
            .collect(),
        base: core::array::from_fn(|k| base[k]),
        base_radius: core::array::from_fn(|k| base_r[k]),
        tool: core::array::from_fn(|k| tool[k]),
        tool_radius: core::array::from_fn(|k| tool_r[k]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::builtin_arm;

    #[test]
    fn the_calibrated_arm_keeps_fixed_parameters_and_contains_the_certified_box() {
        let arm = builtin_arm();
        let outer: Vec<Interval> = arm
            .nominal()
            .iter()
            .zip(arm.radius())
            .map(|(v, r)| Interval::new(v - 0.3 * r, v + 0.1 * r))
            .collect();
        let c = calibrated_arm(&arm, Some(&outer)).unwrap();
        for ((o, v), (r, r0)) in outer
            .iter()
            .zip(c.nominal())
            .zip(c.radius().into_iter().zip(arm.radius()))
        {
            if r0 == 0.0 {
                assert_eq!(r, 0.0);
            } else {
                assert!(v - r <= o.inf() && o.sup() <= v + r && r < r0);
            }
        }
        assert!(calibrated_arm(&arm, None).is_err());
        assert!(calibrated_arm(&arm, Some(&outer[1..])).is_err());
    }
}
