//! Universal Robots' kinematics YAML (`default_kinematics.yaml`, and the per-robot calibration
//! the UR driver extracts from a controller): under `kinematics:`, one entry per joint —
//! `shoulder, upper_arm, forearm, wrist_1, wrist_2, wrist_3` — with the joint origin's
//! `x, y, z` (metres) and `roll, pitch, yaw` (radians, URDF's `Rz(yaw) Ry(pitch) Rx(roll)`), and
//! `hash`, the controller calibration's checksum.
//!
//! The UR driver compares `hash` with the controller's and warns when they differ: a file written
//! by [`write()`] describes *this* calibration, not the controller's, so its hash is this file's
//! own (`certicalib_…`) unless one is given (e.g. the imported one, to silence the check knowingly).

use super::{from_xyz_rpy, to_xyz_rpy, Frame};
use crate::ArmError;
use calib_pipeline::{finite_number, DataError};
use serde::Deserialize;
use std::fmt::Write as _;
use std::path::Path;

/// The joints of a UR arm, base to flange, as the YAML names them.
pub const JOINT_NAMES: [&str; 6] = [
    "shoulder",
    "upper_arm",
    "forearm",
    "wrist_1",
    "wrist_2",
    "wrist_3",
];

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    kinematics: Kinematics,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Kinematics {
    shoulder: Origin,
    upper_arm: Origin,
    forearm: Origin,
    wrist_1: Origin,
    wrist_2: Origin,
    wrist_3: Origin,
    #[serde(default)]
    hash: Option<String>,
}

#[derive(Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
struct Origin {
    x: f64,
    y: f64,
    z: f64,
    roll: f64,
    pitch: f64,
    yaw: f64,
}

/// A UR kinematics file: the joint origins (mm) and the hash.
#[derive(Clone, Debug, PartialEq)]
pub struct UrKinematics {
    /// The six joint origins, base to flange, in mm.
    pub origins: Vec<Frame>,
    /// The `hash` field, when present.
    pub hash: Option<String>,
}

/// Parses a UR kinematics YAML (`text`, the contents of `file`); errors name the file, line and
/// field.
pub fn parse(file: &Path, text: &str) -> Result<UrKinematics, DataError> {
    let f: File = serde_norway::from_str(text).map_err(|e| {
        let line = e.location().map(|l| l.line());
        DataError::new(
            file,
            line,
            None,
            format!(
                "{e}; expected `kinematics:` with shoulder, upper_arm, forearm, wrist_1, wrist_2, \
                 wrist_3 (x, y, z in metres, roll, pitch, yaw in radians) and hash"
            ),
        )
    })?;
    let k = f.kinematics;
    let entries = [
        k.shoulder,
        k.upper_arm,
        k.forearm,
        k.wrist_1,
        k.wrist_2,
        k.wrist_3,
    ];
    let mut origins = Vec::with_capacity(6);
    for (o, name) in entries.iter().zip(JOINT_NAMES) {
        let values = [o.x, o.y, o.z, o.roll, o.pitch, o.yaw];
        for (&v, key) in values.iter().zip(ORIGIN_KEYS) {
            let field = format!("{name}.{key}");
            let line = line_of(text, name, key);
            // `.nan`, `.inf` and `-.inf` are YAML's spellings of non-finite numbers.
            finite_number(file, line, &field, v)?;
            if v.abs() > 100.0 {
                return Err(DataError::new(
                    file,
                    line,
                    Some(&field),
                    format!("{v}: expected metres and radians of magnitude below 100"),
                ));
            }
        }
        origins.push(from_xyz_rpy(
            [1000.0 * o.x, 1000.0 * o.y, 1000.0 * o.z],
            [o.roll, o.pitch, o.yaw],
        ));
    }
    Ok(UrKinematics {
        origins,
        hash: k.hash,
    })
}

/// The keys of a joint origin, in the order of [`Origin`]'s fields.
const ORIGIN_KEYS: [&str; 6] = ["x", "y", "z", "roll", "pitch", "yaw"];

/// The line (1-based) of `key:` in the entry `joint:` of `text`: a line starting with `key:`
/// among those indented below the line starting with `joint:`, or that line itself (a key not on
/// a line of its own, as in `shoulder: {x: 0, …}`).
fn line_of(text: &str, joint: &str, key: &str) -> Option<usize> {
    let starts = |l: &str, k: &str| {
        l.trim_start()
            .strip_prefix(k)
            .is_some_and(|r| r.starts_with(':'))
    };
    let indent = |l: &str| l.len() - l.trim_start().len();
    let lines: Vec<&str> = text.lines().collect();
    let at = lines.iter().position(|l| starts(l, joint))?;
    let mut line = at;
    for (i, l) in lines.iter().enumerate().skip(at + 1) {
        if l.trim().is_empty() || l.trim_start().starts_with('#') {
            continue;
        }
        if indent(l) <= indent(lines[at]) {
            break;
        }
        if starts(l, key) {
            line = i;
            break;
        }
    }
    Some(line + 1)
}

/// The YAML of six joint origins (mm) in UR's layout, with `hash` (or this file's own checksum
/// when `None`), preceded by the `comment` lines.
pub fn write(origins: &[Frame], hash: Option<&str>, comment: &str) -> Result<String, ArmError> {
    if origins.len() != 6 {
        return Err(ArmError::UrJoints(origins.len()));
    }
    let mut body = String::new();
    for (o, name) in origins.iter().zip(JOINT_NAMES) {
        let (xyz, rpy) = to_xyz_rpy(o);
        let _ = write!(
            body,
            "  {name}:\n    x: {:?}\n    y: {:?}\n    z: {:?}\n    roll: {:?}\n    pitch: {:?}\n    yaw: {:?}\n",
            xyz[0] / 1000.0,
            xyz[1] / 1000.0,
            xyz[2] / 1000.0,
            rpy[0],
            rpy[1],
            rpy[2]
        );
    }
    let hash = match hash {
        Some(h) => h.to_string(),
        None => format!("certicalib_{}", fnv1a(&body)),
    };
    let mut out = String::new();
    for line in comment.lines() {
        let _ = writeln!(out, "# {line}");
    }
    let _ = write!(out, "kinematics:\n{body}  hash: {hash}\n");
    Ok(out)
}

/// The 64-bit FNV-1a checksum of `text` (a stable identifier of the numbers written).
fn fnv1a(text: &str) -> u64 {
    text.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}
