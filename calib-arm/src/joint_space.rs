//! The joint-space file `joints.toml` (degrees): the joint readings a controller may command, one
//! range per joint, base to flange.
//!
//! ```toml
//! q1 = [-170.0, 170.0]
//! q2 = [-170.0, 170.0]
//! q3 = [-150.0, 150.0]
//! q4 = [-170.0, 170.0]
//! q5 = [-120.0, 120.0]
//! q6 = [-170.0, 170.0]
//! ```
//!
//! Keys `q1..qN` are the measurement file's column names; every joint of the arm needs one.

use crate::simulate::JOINT_LIMIT_DEG;
use calib_pipeline::{finite_number, line_at, read_text, toml_error, DataError};
use std::collections::BTreeMap;
use std::path::Path;
use toml::Spanned;

/// The joint ranges (degrees), base to flange.
#[derive(Clone, Debug, PartialEq)]
pub struct JointSpace {
    /// `[lo, hi]` per joint, degrees.
    pub ranges_deg: Vec<[f64; 2]>,
}

impl JointSpace {
    /// The joint space of the simulator (`arm simulate`): every joint within ±170°.
    pub fn simulator(joints: usize) -> JointSpace {
        JointSpace {
            ranges_deg: vec![[-JOINT_LIMIT_DEG, JOINT_LIMIT_DEG]; joints],
        }
    }
}

const FORMAT: &str = "expected q1 = [lo, hi], q2 = [lo, hi], … (degrees), one range per joint";

/// Reads `joints.toml` for an arm with `joints` joints (see [`parse_joint_space`]).
pub fn read_joint_space(file: &Path, joints: usize) -> Result<JointSpace, DataError> {
    parse_joint_space(file, &read_text(file)?, joints)
}

/// Parses `joints.toml`: keys `q1..qN` (`N = joints`), each `[lo, hi]` in degrees with
/// `lo <= hi`, finite. Errors name the file, the line and the field.
pub fn parse_joint_space(file: &Path, text: &str, joints: usize) -> Result<JointSpace, DataError> {
    let table: BTreeMap<Spanned<String>, Spanned<toml::Value>> =
        toml::from_str(text).map_err(|e| toml_error(file, text, &e, FORMAT))?;
    let err = |start: usize, field: &str, message: String| {
        DataError::new(file, Some(line_at(text, start)), Some(field), message)
    };
    let mut ranges = vec![None; joints];
    for (key, value) in &table {
        let name = key.get_ref();
        let index = name
            .strip_prefix('q')
            .and_then(|k| k.parse::<usize>().ok())
            .filter(|k| (1..=joints).contains(k) && name == &format!("q{k}"));
        let Some(k) = index else {
            return Err(err(
                key.span().start,
                name,
                format!("unknown key: the arm has {joints} joints, q1 to q{joints}"),
            ));
        };
        let number = |v: &toml::Value| v.as_float().or_else(|| v.as_integer().map(|i| i as f64));
        let pair = value.get_ref().as_array().and_then(|a| match a.as_slice() {
            [lo, hi] => Some([number(lo)?, number(hi)?]),
            _ => None,
        });
        let Some([lo, hi]) = pair else {
            return Err(err(
                value.span().start,
                name,
                format!("found {}: {FORMAT}", value.get_ref()),
            ));
        };
        let line = Some(line_at(text, value.span().start));
        for t in [lo, hi] {
            finite_number(file, line, name, t)?;
        }
        if lo > hi {
            return Err(err(
                value.span().start,
                name,
                format!("[{lo}, {hi}]: expected [lo, hi] with lo <= hi"),
            ));
        }
        ranges[k - 1] = Some([lo, hi]);
    }
    let ranges_deg = ranges
        .into_iter()
        .enumerate()
        .map(|(k, r)| {
            r.ok_or_else(|| {
                DataError::new(
                    file,
                    None,
                    Some(&format!("q{}", k + 1)),
                    format!("missing: {FORMAT}"),
                )
            })
        })
        .collect::<Result<_, _>>()?;
    Ok(JointSpace { ranges_deg })
}

/// Configurations spread over the joint box that stand for it where a finite list is needed
/// (`arm certify --task joints.toml`): its `2^N` corners, its centre and this many more at
/// golden-ratio fractions of every range.
const TASK_SPREAD: usize = 192;

impl JointSpace {
    /// Configurations spread over the box (degrees): its corners, its centre and
    /// 192 points inside.
    pub fn spread(&self) -> Vec<Vec<f64>> {
        let n = self.ranges_deg.len();
        let corners = (0..1usize << n).map(|bits| {
            (0..n)
                .map(|i| self.ranges_deg[i][bits >> i & 1])
                .collect::<Vec<f64>>()
        });
        let inside = (0..=TASK_SPREAD).map(|k| {
            (0..n)
                .map(|i| {
                    let [lo, hi] = self.ranges_deg[i];
                    let t = if k == 0 {
                        0.5
                    } else {
                        (k as f64 * (i as f64 + 1.0) * 0.618_033_988_7).fract()
                    };
                    lo + t * (hi - lo)
                })
                .collect()
        });
        corners.chain(inside).collect()
    }
}

/// The configurations of a task (`arm certify --task FILE`, degrees): a `.toml` file is a joint
/// box (`joints.toml`, [`parse_joint_space`]) standing for its [`JointSpace::spread`]; any other
/// a CSV of configurations with columns `q1..qN`. Errors name the file, the line and the field.
pub fn read_task(file: &Path, joints: usize) -> Result<Vec<Vec<f64>>, DataError> {
    let text = read_text(file)?;
    if file.extension().is_some_and(|e| e == "toml") {
        return Ok(parse_joint_space(file, &text, joints)?.spread());
    }
    let header: Vec<String> = (1..=joints).map(|i| format!("q{i}")).collect();
    let table = calib_pipeline::parse_number_table(file, &text, &header)?;
    if table.rows.is_empty() {
        return Err(DataError::new(
            file,
            None,
            None,
            "no configurations: expected a header q1..qN and one row per configuration",
        ));
    }
    Ok(table.rows)
}
