//! Measurements as a tracker exports them: joint readings and tracked points picked by column
//! name out of a wider table (`,`, `;` or tab separated, decimal points or commas), in radians or
//! degrees, millimetres or metres, and a range of its rows.
//!
//! Values are converted to the crate's units (degrees, mm) in interval arithmetic: each stored
//! value is the midpoint of the enclosure of the converted reading, and the conversion's largest
//! rounding error is kept ([`Measurements::slack`]) and added to the error bounds
//! ([`Slack::widen`]), so that a converted file certifies what the file says.

use crate::files::Measurements;
use crate::simulate::{Reading, Uncertainty};
use crate::units::rad_to_deg;
use crate::ArmError;
use calib_core::Interval;
use calib_pipeline::{parse_named_columns, DataError};
use std::path::Path;

/// The unit of the joint readings in a file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum JointUnit {
    /// Degrees (the crate's unit).
    Deg,
    /// Radians (robot controllers' and ROS's unit).
    Rad,
}

/// The unit of the tracked coordinates in a file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum LengthUnit {
    /// Millimetres (the crate's unit).
    Mm,
    /// Metres.
    M,
}

/// How a file writes the measured frame's orientation (6-DoF probes, see [`crate::pose`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum OrientationConvention {
    /// Intrinsic Euler angles `XYZ` in degrees, `R = Rx(a) Ry(b) Rz(c)` (Leica's T-Mac).
    EulerXyzDeg,
    /// The same in radians.
    EulerXyzRad,
}

/// Which rows of a file to use: data rows `first..=last`, 1-based (the header is not a row).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RowRange {
    /// The first row used.
    pub first: usize,
    /// The last row used (`None`: to the end).
    pub last: Option<usize>,
}

impl std::str::FromStr for RowRange {
    type Err = ArmError;

    /// `A-B`, `A-` or `A` (1-based data rows, inclusive): `1-60`, `61-`, `7`.
    fn from_str(s: &str) -> Result<Self, ArmError> {
        let bad = || ArmError::Rows(s.to_string());
        let number = |t: &str| t.trim().parse::<usize>().ok().filter(|v| *v >= 1);
        let (first, last) = match s.split_once('-') {
            Some((a, "")) => (number(a).ok_or_else(bad)?, None),
            Some((a, b)) => (number(a).ok_or_else(bad)?, Some(number(b).ok_or_else(bad)?)),
            None => {
                let a = number(s).ok_or_else(bad)?;
                (a, Some(a))
            }
        };
        if last.is_some_and(|l| l < first) {
            return Err(ArmError::RowsReversed(s.to_string()));
        }
        Ok(RowRange { first, last })
    }
}

/// Where the measurements are in a file and in which units.
#[derive(Clone, Debug, PartialEq)]
pub struct MeasurementColumns {
    /// The joint readings' columns, base to flange.
    pub joints: Vec<String>,
    /// The tracked point's `x, y, z` columns.
    pub point: [String; 3],
    /// The joint readings' unit.
    pub joint_unit: JointUnit,
    /// The tracked point's unit.
    pub length_unit: LengthUnit,
    /// The rows to use (`None`: all).
    pub rows: Option<RowRange>,
    /// The measured orientation's three columns and their convention (`None`: positions only).
    pub orientation: Option<([String; 3], OrientationConvention)>,
}

impl MeasurementColumns {
    /// The crate's own layout: `q1..qN` in degrees and `px, py, pz` in mm, every row.
    pub fn standard(joints: usize) -> Self {
        MeasurementColumns {
            joints: (1..=joints).map(|i| format!("q{i}")).collect(),
            point: ["px", "py", "pz"].map(String::from),
            joint_unit: JointUnit::Deg,
            length_unit: LengthUnit::Mm,
            rows: None,
            orientation: None,
        }
    }

    /// The standard layout with the given joint and point columns (the command line's
    /// `--joint-columns`, `--point-columns`; the Python package's `joint_columns`,
    /// `point_columns`) where given: an error (to be prefixed with the option's name) when the
    /// point columns are not three names ([`ArmError::PointColumns`]).
    pub fn with_names(
        joints: usize,
        joint_columns: Option<Vec<String>>,
        point_columns: Option<Vec<String>>,
    ) -> Result<Self, ArmError> {
        let mut c = MeasurementColumns::standard(joints);
        if let Some(j) = joint_columns {
            c.joints = j;
        }
        if let Some(p) = point_columns {
            c.point = <[String; 3]>::try_from(p).map_err(|p| ArmError::PointColumns(p.len()))?;
        }
        Ok(c)
    }
}

impl std::str::FromStr for JointUnit {
    type Err = ArmError;

    /// `deg` or `rad`.
    fn from_str(s: &str) -> Result<Self, ArmError> {
        match s {
            "deg" => Ok(JointUnit::Deg),
            "rad" => Ok(JointUnit::Rad),
            other => Err(ArmError::JointUnit(other.to_string())),
        }
    }
}

impl std::str::FromStr for OrientationConvention {
    type Err = ArmError;

    /// `euler-xyz-deg` or `euler-xyz-rad`.
    fn from_str(s: &str) -> Result<Self, ArmError> {
        match s {
            "euler-xyz-deg" => Ok(OrientationConvention::EulerXyzDeg),
            "euler-xyz-rad" => Ok(OrientationConvention::EulerXyzRad),
            other => Err(ArmError::OrientationConvention(other.to_string())),
        }
    }
}

impl std::str::FromStr for LengthUnit {
    type Err = ArmError;

    /// `mm` or `m`.
    fn from_str(s: &str) -> Result<Self, ArmError> {
        match s {
            "mm" => Ok(LengthUnit::Mm),
            "m" => Ok(LengthUnit::M),
            other => Err(ArmError::LengthUnit(other.to_string())),
        }
    }
}

/// Joint readings larger than this (radians, a little over a turn) are not radians.
const MAX_RADIANS: f64 = 2.0 * std::f64::consts::PI + 0.01;
/// Tracked coordinates in metres beyond this are millimetres (no tracker measures 100 m away).
const MAX_METRES: f64 = 100.0;
/// A file whose every tracked coordinate in mm is within this is in metres.
const MIN_MILLIMETRES: f64 = 20.0;

/// Parses `text` (the contents of `file`) with `columns`: `joints` joint readings and a tracked
/// point per row, converted to degrees and mm. A value that looks like another unit than the one
/// given is an error naming it (a joint reading beyond a turn read as radians; a coordinate beyond
/// 100 m read as metres); every joint reading within a turn read as degrees, or every coordinate
/// within 20 mm read as mm, is a note (a small joint cell or a tracker near the tool look the
/// same).
pub fn parse_tracker_measurements(
    file: &Path,
    text: &str,
    joints: usize,
    columns: &MeasurementColumns,
) -> Result<Measurements, DataError> {
    if columns.joints.len() != joints {
        return Err(DataError::new(
            file,
            None,
            Some("joint columns"),
            format!(
                "{} joint columns given ({}); the arm has {joints} joints",
                columns.joints.len(),
                columns.joints.join(", ")
            ),
        ));
    }
    let names: Vec<String> = columns
        .joints
        .iter()
        .chain(&columns.point)
        .chain(columns.orientation.iter().flat_map(|(o, _)| o))
        .cloned()
        .collect();
    let table = parse_named_columns(file, text, &names)?;
    if table.rows.is_empty() {
        return Err(DataError::new(
            file,
            None,
            None,
            "no configurations; expected one row per measured configuration",
        ));
    }
    let (first, end) = chosen_rows(file, columns.rows, table.rows.len())?;
    let mut out = Measurements {
        readings: Vec::with_capacity(end + 1 - first),
        lines: Vec::with_capacity(end + 1 - first),
        slack: Slack::default(),
        notes: Vec::new(),
        orientations: columns.orientation.as_ref().map(|_| Vec::new()),
    };
    let mut largest_joint: f64 = 0.0;
    let mut largest_coordinate: f64 = 0.0;
    for (row, &line) in table.rows[first - 1..end]
        .iter()
        .zip(&table.lines[first - 1..end])
    {
        let bad = |field: &str, what: String| DataError::new(file, Some(line), Some(field), what);
        let mut joints_deg = Vec::with_capacity(joints);
        for (v, name) in row[..joints].iter().zip(&columns.joints) {
            largest_joint = largest_joint.max(v.abs());
            let deg = joint_deg(*v, columns.joint_unit, |e| bad(name, e))?;
            joints_deg.push(out.slack.keep_joint(deg));
        }
        let mut point = [0.0; 3];
        for ((p, v), name) in point
            .iter_mut()
            .zip(&row[joints..joints + 3])
            .zip(&columns.point)
        {
            largest_coordinate = largest_coordinate.max(v.abs());
            let mm = coordinate_mm(*v, columns.length_unit, |e| bad(name, e))?;
            *p = out.slack.keep_point(mm);
        }
        if let (Some((names, convention)), Some(orientations)) =
            (&columns.orientation, &mut out.orientations)
        {
            let mut angles = [0.0; 3];
            for ((e, v), name) in angles.iter_mut().zip(&row[joints + 3..]).zip(names) {
                *e = orientation_deg(*v, *convention, &mut out.slack, |e| bad(name, e))?;
            }
            orientations.push(angles);
        }
        out.readings.push(Reading { joints_deg, point });
        out.lines.push(line);
    }
    unit_notes(file, columns, largest_joint, largest_coordinate, &mut out);
    Ok(out)
}

/// The data rows `--rows` chooses, 1-based and inclusive, within the file's `rows`.
fn chosen_rows(
    file: &Path,
    chosen: Option<RowRange>,
    rows: usize,
) -> Result<(usize, usize), DataError> {
    let (first, last) = chosen.map_or((1, None), |r| (r.first, r.last.map(|l| l.min(rows))));
    let end = last.unwrap_or(rows);
    if first > end {
        return Err(DataError::new(
            file,
            None,
            Some("rows"),
            format!("no configurations in rows {first}..{end}; the file has {rows} data rows"),
        ));
    }
    Ok((first, end))
}

/// A joint reading `v` in `unit`, in degrees; `bad` of the error's message when it looks like
/// another unit.
fn joint_deg(
    v: f64,
    unit: JointUnit,
    bad: impl FnOnce(String) -> DataError,
) -> Result<Interval, DataError> {
    match unit {
        JointUnit::Deg => Ok(Interval::point(v)),
        JointUnit::Rad if v.abs() > MAX_RADIANS => Err(bad(format!(
            "{v} read as radians is more than a turn: it looks like degrees \
             (use --joint-unit deg)"
        ))),
        JointUnit::Rad => Ok(rad_to_deg(Interval::point(v))),
    }
}

/// A coordinate `v` in `unit`, in mm; `bad` of the error's message when it looks like another
/// unit.
fn coordinate_mm(
    v: f64,
    unit: LengthUnit,
    bad: impl FnOnce(String) -> DataError,
) -> Result<Interval, DataError> {
    match unit {
        LengthUnit::Mm => Ok(Interval::point(v)),
        LengthUnit::M if v.abs() > MAX_METRES => Err(bad(format!(
            "{v} read as metres is more than {MAX_METRES} m: it looks like \
             millimetres (use --length-unit mm)"
        ))),
        LengthUnit::M => Ok(Interval::point(v) * Interval::point(1000.0)),
    }
}

/// An Euler angle `v` written in `convention`, in degrees (a conversion's rounding kept in
/// `slack`); `bad` of the error's message when it is out of range.
fn orientation_deg(
    v: f64,
    convention: OrientationConvention,
    slack: &mut Slack,
    bad: impl FnOnce(String) -> DataError,
) -> Result<f64, DataError> {
    match convention {
        OrientationConvention::EulerXyzDeg if v.abs() > 360.0 => Err(bad(format!(
            "{v}: an Euler angle in degrees within ±360 expected"
        ))),
        OrientationConvention::EulerXyzDeg => Ok(v),
        OrientationConvention::EulerXyzRad if v.abs() > MAX_RADIANS => Err(bad(format!(
            "{v} read as radians is more than a turn: it looks like \
             degrees (use --orientation-convention euler-xyz-deg)"
        ))),
        OrientationConvention::EulerXyzRad => {
            Ok(slack.keep_orientation(rad_to_deg(Interval::point(v))))
        }
    }
}

/// The notes when every value is small enough to be in another unit than the one given.
fn unit_notes(
    file: &Path,
    columns: &MeasurementColumns,
    largest_joint: f64,
    largest_coordinate: f64,
    out: &mut Measurements,
) {
    if columns.length_unit == LengthUnit::Mm
        && largest_coordinate < MIN_MILLIMETRES
        && out.readings.len() > 3
    {
        out.notes.push(format!(
            "{}: every tracked coordinate is within ±{largest_coordinate} read as mm; if they \
             are metres, pass --length-unit m",
            file.display()
        ));
    }
    if columns.joint_unit == JointUnit::Deg
        && largest_joint <= MAX_RADIANS
        && out.readings.len() > 3
    {
        out.notes.push(format!(
            "{}: every joint reading is within ±{largest_joint:.3}, read as degrees; if they are \
             radians, pass --joint-unit rad",
            file.display()
        ));
    }
}

/// The largest rounding error of the unit conversions (0 when nothing was converted).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Slack {
    /// On the joint readings, degrees.
    pub joint_deg: f64,
    /// On the tracked coordinates, mm.
    pub pos: f64,
    /// On the measured Euler angles, degrees.
    pub orient_deg: f64,
}

impl Slack {
    /// The error bounds `u` widened by these rounding errors, rounded up: what converted
    /// readings are certified with.
    pub fn widen(&self, u: &Uncertainty) -> Uncertainty {
        let up = |a: f64, b: f64| (Interval::point(a) + Interval::point(b)).sup();
        Uncertainty {
            joint_deg: up(u.joint_deg, self.joint_deg),
            pos: up(u.pos, self.pos),
        }
    }

    /// The orientation bound `orient_deg` widened by the conversion's rounding error, rounded up.
    pub fn widen_orientation(&self, orient_deg: f64) -> f64 {
        (Interval::point(orient_deg) + Interval::point(self.orient_deg)).sup()
    }

    /// The midpoint of `deg` (an Euler angle), remembering how far its ends are.
    fn keep_orientation(&mut self, deg: Interval) -> f64 {
        let (mid, rad) = mid_and_radius(deg);
        self.orient_deg = self.orient_deg.max(rad);
        mid
    }

    /// The midpoint of `deg`, remembering how far its ends are.
    fn keep_joint(&mut self, deg: Interval) -> f64 {
        let (mid, rad) = mid_and_radius(deg);
        self.joint_deg = self.joint_deg.max(rad);
        mid
    }

    /// The midpoint of `mm`, remembering how far its ends are.
    fn keep_point(&mut self, mm: Interval) -> f64 {
        let (mid, rad) = mid_and_radius(mm);
        self.pos = self.pos.max(rad);
        mid
    }
}

/// A value of `v` and an upper bound of its distance to either end.
fn mid_and_radius(v: Interval) -> (f64, f64) {
    let mid = v.mid();
    let up = (Interval::point(v.sup()) - Interval::point(mid)).sup();
    let down = (Interval::point(mid) - Interval::point(v.inf())).sup();
    (mid, up.max(down))
}
