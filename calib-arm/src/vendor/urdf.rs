//! URDF (ROS's robot description): the chain of joints from a base link to a tip link.
//!
//! Reading ([`parse`], with `urdf-rs`): revolute and continuous joints become the chain's joints,
//! fixed joints between them are folded into the next joint's origin, a joint axis other than
//! `z` is turned onto `z` (the turn carried into the next origin), so that
//! `T(q) = F_1 Rz(q_1) ⋯ F_N Rz(q_N)` is the tip link's frame. The tip must be the last moving
//! joint's child link or fixed to it without offset (the tool point is expressed in it). Every
//! number read (the chain's joint origins and axes) must be finite: errors name the joint and
//! the attribute.
//! Writing ([`write()`]): `base_link`, one continuous joint per arm joint (`joint1…`, axis `z`,
//! origins in metres and radians), and a fixed `tool_joint` to a `tool` link at the tool point.

use super::{from_xyz_rpy, to_xyz_rpy, Frame};
use calib_pipeline::{finite_number, DataError};
use nalgebra::{UnitQuaternion, Vector3};
use std::fmt::Write as _;
use std::path::Path;

/// How far the tip may be from the last joint's frame (mm, radians): rounding only.
const TIP_TOLERANCE: f64 = 1e-9;

/// Reads the chain of `text` (a URDF, the contents of `file`) from the link `base` (default: the
/// root link) to the link `tip` (default: the end of the chain when it does not branch). Origins
/// in mm.
pub fn parse(
    file: &Path,
    text: &str,
    base: Option<&str>,
    tip: Option<&str>,
) -> Result<Vec<Frame>, DataError> {
    let err = |field: Option<&str>, m: String| DataError::new(file, None, field, m);
    let robot = urdf_rs::read_from_string(text).map_err(|e| err(None, format!("{e}")))?;
    let parent_joint = |link: &str| -> Option<&urdf_rs::Joint> {
        robot.joints.iter().find(|j| j.child.link == link)
    };
    let root = robot
        .links
        .iter()
        .map(|l| l.name.as_str())
        .find(|l| parent_joint(l).is_none())
        .ok_or_else(|| {
            err(
                None,
                "no root link (every link is some joint's child)".into(),
            )
        })?;
    let base = base.unwrap_or(root);
    if !robot.links.iter().any(|l| l.name == base) {
        return Err(err(Some("base link"), format!("no link `{base}`")));
    }
    let tip = match tip {
        Some(t) => t.to_string(),
        None => only_tip(file, &robot, base)?,
    };
    let joints = chain(file, &robot, base, &tip)?;
    let (origins, pending) = moving_origins(file, &joints)?;
    let off = pending
        .translation
        .vector
        .norm()
        .max(pending.rotation.angle());
    if off > TIP_TOLERANCE {
        return Err(err(
            Some("tip link"),
            format!(
                "`{tip}` is offset from the last moving joint's frame; name that joint's child \
                 link as the tip (the tool point is expressed in it)"
            ),
        ));
    }
    if origins.is_empty() {
        return Err(err(
            None,
            format!("no moving joint between `{base}` and `{tip}`"),
        ));
    }
    Ok(origins)
}

/// The end of the chain below `base` (following the only child joint while there is one); an
/// error at `file`'s tip link when it branches.
fn only_tip(file: &Path, robot: &urdf_rs::Robot, base: &str) -> Result<String, DataError> {
    let mut link = base.to_string();
    loop {
        let children: Vec<&urdf_rs::Joint> = robot
            .joints
            .iter()
            .filter(|j| j.parent.link == link)
            .collect();
        match children.as_slice() {
            [] => return Ok(link),
            [j] => link = j.child.link.clone(),
            _ => {
                return Err(tip_error(
                    file,
                    format!("the chain branches at `{link}`: name the tip link"),
                ))
            }
        }
    }
}

/// The joints from `base` down to `tip`; an error at `file`'s tip link when `tip` is not below
/// `base`.
fn chain<'r>(
    file: &Path,
    robot: &'r urdf_rs::Robot,
    base: &str,
    tip: &str,
) -> Result<Vec<&'r urdf_rs::Joint>, DataError> {
    // From the tip up to the base.
    let mut joints = Vec::new();
    let mut link = tip.to_string();
    while link != base {
        let j = robot
            .joints
            .iter()
            .find(|j| j.child.link == link)
            .ok_or_else(|| {
                tip_error(
                    file,
                    format!("`{tip}` is not below `{base}` (or no link `{tip}`)"),
                )
            })?;
        joints.push(j);
        link = j.parent.link.clone();
    }
    joints.reverse();
    Ok(joints)
}

/// An error `message` at `file`'s tip link (the link the chain ends at).
fn tip_error(file: &Path, message: String) -> DataError {
    DataError::new(file, None, Some("tip link"), message)
}

/// The moving joints' origins (mm), each with its axis turned onto `z`, fixed joints folded into
/// the next; and what is left after the last moving joint (the tip's offset).
fn moving_origins(
    file: &Path,
    joints: &[&urdf_rs::Joint],
) -> Result<(Vec<Frame>, Frame), DataError> {
    let err = |field: Option<&str>, m: String| DataError::new(file, None, field, m);
    let mut origins = Vec::new();
    let mut pending = Frame::identity();
    for j in joints {
        // urdf-rs reads `nan`, `inf` and `1e999` as numbers: refuse them before they reach a
        // frame (a NaN frame passes every tolerance check below and would be written out).
        let finite = |attribute: &str, v: &[f64; 3]| -> Result<[f64; 3], DataError> {
            let field = format!("joint '{}' {attribute}", j.name);
            let mut out = [0.0; 3];
            for (o, &x) in out.iter_mut().zip(v) {
                *o = finite_number(file, None, &field, x)?;
            }
            Ok(out)
        };
        let xyz = finite("origin xyz", &j.origin.xyz)?;
        let rpy = finite("origin rpy", &j.origin.rpy)?;
        let o = from_xyz_rpy(xyz.map(|m| 1000.0 * m), rpy);
        match &j.joint_type {
            urdf_rs::JointType::Fixed => pending *= o,
            urdf_rs::JointType::Revolute | urdf_rs::JointType::Continuous => {
                let a = Vector3::from(finite("axis xyz", &j.axis.xyz)?);
                let norm = a.norm();
                if !(norm > 0.0 && norm.is_finite()) {
                    return Err(err(Some(&j.name), "a joint axis of zero length".into()));
                }
                let onto = UnitQuaternion::rotation_between(&Vector3::z(), &(a / norm))
                    .unwrap_or_else(|| {
                        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
                    });
                let turn = Frame::from_parts(nalgebra::Translation3::identity(), onto);
                origins.push(pending * o * turn);
                pending = turn.inverse();
            }
            other => {
                return Err(err(
                    Some(&j.name),
                    format!("a {other:?} joint: only revolute, continuous and fixed joints"),
                ))
            }
        }
    }
    Ok((origins, pending))
}

/// A URDF of the chain `origins` (mm) named `name`, with the tool point `tool` (mm, in the last
/// joint's frame) as a fixed `tool` link.
pub fn write(name: &str, origins: &[Frame], tool: [f64; 3]) -> String {
    let mut s = format!(
        "<?xml version=\"1.0\"?>\n<!-- written by certicalib: joint origins in metres and \
         radians, every joint about its z axis -->\n<robot name=\"{name}\">\n  <link name=\"base_link\"/>\n"
    );
    let mut parent = "base_link".to_string();
    for (i, o) in origins.iter().enumerate() {
        let (xyz, rpy) = to_xyz_rpy(o);
        let child = format!("link{}", i + 1);
        let _ = write!(
            s,
            "  <link name=\"{child}\"/>\n  <joint name=\"joint{}\" type=\"continuous\">\n    \
             <parent link=\"{parent}\"/>\n    <child link=\"{child}\"/>\n    <origin xyz=\"{:?} \
             {:?} {:?}\" rpy=\"{:?} {:?} {:?}\"/>\n    <axis xyz=\"0 0 1\"/>\n  </joint>\n",
            i + 1,
            xyz[0] / 1000.0,
            xyz[1] / 1000.0,
            xyz[2] / 1000.0,
            rpy[0],
            rpy[1],
            rpy[2]
        );
        parent = child;
    }
    let _ = write!(
        s,
        "  <link name=\"tool\"/>\n  <joint name=\"tool_joint\" type=\"fixed\">\n    <parent \
         link=\"{parent}\"/>\n    <child link=\"tool\"/>\n    <origin xyz=\"{:?} {:?} {:?}\" \
         rpy=\"0 0 0\"/>\n  </joint>\n</robot>\n",
        tool[0] / 1000.0,
        tool[1] / 1000.0,
        tool[2] / 1000.0
    );
    s
}
