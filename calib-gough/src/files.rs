//! Reading the data files: `robot.toml`, `uncertainty.toml`, `measurements.csv` (units: cm and
//! degrees). Every malformed input is a [`DataError`] naming the file, the line and the field.

use crate::geometry::{Leg, Pose};
use crate::measurement::{Configuration, Orientation, Uncertainty};
use crate::LegModel;
use calib_core::{CertifiedSet, Interval};
use calib_pipeline::finite_number;
use calib_pipeline::stored_set::StoredSet;
use serde::Deserialize;
use std::path::Path;
use toml::Spanned;

pub use calib_pipeline::{line_at, read_text, DataError, MAX_MAGNITUDE};

fn error(
    file: &Path,
    line: Option<usize>,
    field: Option<&str>,
    message: impl Into<String>,
) -> DataError {
    DataError::new(file, line, field, message)
}

/// One leg of `robot.toml`: nominal geometry and the radius of the initial box per parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct LegSpec {
    /// The nominal geometry.
    pub nominal: Leg,
    /// The initial box is `nominal ± radius` (order `ax, ay, az, bx, by, bz, l`).
    pub radius: [f64; 7],
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RobotEntries {
    leg: Vec<LegEntry>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LegEntry {
    a: Spanned<[f64; 3]>,
    b: Spanned<[f64; 3]>,
    l: Spanned<f64>,
    radius: Spanned<Radius>,
    certified_set: Option<StoredSet>,
}

/// A robot file as read: the legs and, in a calibrated file (`gough certify
/// --write-calibrated`), each certified leg's stored set.
#[derive(Clone, Debug, PartialEq)]
pub struct RobotFile {
    /// The legs: nominal geometry (a calibrated file's calibrated geometry) and radii.
    pub legs: Vec<LegSpec>,
    /// Per leg, its `[leg.certified_set]` table (`None` in a robot file that has none).
    pub sets: Vec<Option<StoredSet>>,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum Radius {
    One(f64),
    Each([f64; 7]),
}

/// Reads `robot.toml`: one `[[leg]]` table per leg with `a = [x, y, z]`, `b = [x, y, z]`,
/// `l = offset` and `radius = r` or `radius = [7 values]`.
pub fn read_robot(file: &Path) -> Result<Vec<LegSpec>, DataError> {
    parse_robot(file, &read_text(file)?)
}

/// [`read_robot`] on text already in memory; `file` names it in errors (e.g. an array).
pub fn parse_robot(file: &Path, text: &str) -> Result<Vec<LegSpec>, DataError> {
    Ok(parse_robot_file(file, text)?.legs)
}

/// Reads a robot file with the certified sets a calibrated file carries (see [`RobotFile`]).
pub fn read_robot_file(file: &Path) -> Result<RobotFile, DataError> {
    parse_robot_file(file, &read_text(file)?)
}

/// The certified sets of a robot file, rebuilt (per leg; `None` for a leg without one): the
/// stored measurement boxes, cover and points checked (errors name the leg's field), the
/// polyhedra recomputed by the Newton step's relaxation, the points proved consistent again. An
/// error when a stored set holds no piece or no point proved consistent (the file was edited).
pub fn leg_sets(
    file: &Path,
    robot: &RobotFile,
) -> Result<Vec<Option<CertifiedSet<7, 8>>>, DataError> {
    let all: Vec<usize> = (0..7).collect();
    robot
        .sets
        .iter()
        .enumerate()
        .map(|(i, stored)| {
            let Some(stored) = stored else {
                return Ok(None);
            };
            let field = |f: &str| format!("leg[{}].certified_set.{f}", i + 1);
            // Eight quantities per configuration: axis–angle data; seven: Rodrigues data (and
            // every file written before the axis and angle were measurement inputs: its boxes
            // are the Rodrigues vectors' hull, and the set was certified against them).
            let model = match stored.measurements.first().map(Vec::len) {
                Some(7) => LegModel::Rodrigues,
                _ => LegModel::AxisAngle,
            };
            let restored = stored
                .restore::<7, 8>(
                    &all,
                    model.stored_quantities(),
                    &[Interval::ZERO; 7],
                    &[Interval::ZERO; 8],
                )
                .map_err(|(f, m)| error(file, None, Some(&field(&f)), m))?;
            // A measured angle's box is never the point 0 (that marks Rodrigues data, whose
            // angle is not read; `LegModel::of_measurements`).
            if LegModel::of_measurements(&restored.measurements) != model {
                return Err(error(
                    file,
                    None,
                    Some(&field("measurements")),
                    "every angle is the point [0.0, 0.0]: a measured angle has a box of positive \
                     width (was the file edited?): recalibrate with `gough certify \
                     --write-calibrated`",
                ));
            }
            let set = CertifiedSet::new(
                &model,
                &restored.cover,
                &restored.measurements,
                &restored.points,
                usize::MAX,
            );
            if set.is_empty() || set.points().is_empty() {
                return Err(error(
                    file,
                    None,
                    Some(&field("points")),
                    "the stored set holds no geometry proved consistent with its measurements \
                     (was the file edited?): recalibrate with `gough certify --write-calibrated`",
                ));
            }
            Ok(Some(set))
        })
        .collect()
}

/// [`read_robot_file`] on text already in memory.
pub fn parse_robot_file(file: &Path, text: &str) -> Result<RobotFile, DataError> {
    let parsed: RobotEntries = toml::from_str(text).map_err(|e| {
        let line = e.span().map(|s| line_at(text, s.start));
        error(file, line, None, format!("{}; expected [[leg]] tables with a = [x, y, z], b = [x, y, z], l = offset, radius = r", e.message()))
    })?;
    if parsed.leg.is_empty() {
        return Err(error(
            file,
            None,
            Some("leg"),
            "no [[leg]] table; expected one per leg",
        ));
    }
    parsed
        .leg
        .iter()
        .enumerate()
        .map(|(i, e)| {
            let field = |name: &str| format!("leg[{}].{name}", i + 1);
            let line = |span: std::ops::Range<usize>| Some(line_at(text, span.start));
            // Each parameter, named as `PARAMETER_NAMES` does, at the line of its value.
            let params = (e.a.get_ref().iter().map(|&v| (v, e.a.span())))
                .chain(e.b.get_ref().iter().map(|&v| (v, e.b.span())))
                .chain([(*e.l.get_ref(), e.l.span())]);
            for ((v, span), name) in params.zip(crate::PARAMETER_NAMES) {
                finite_number(file, line(span), &field(name), v)?;
            }
            let nominal = Leg { a: *e.a.get_ref(), b: *e.b.get_ref(), l: *e.l.get_ref() };
            let radius = match e.radius.get_ref() {
                Radius::One(r) => [*r; 7],
                Radius::Each(r) => *r,
            };
            for r in radius {
                if finite_number(file, line(e.radius.span()), &field("radius"), r)? < 0.0 {
                    return Err(error(
                        file,
                        line(e.radius.span()),
                        Some(&field("radius")),
                        "the initial box nominal ± radius must contain the nominal value: expected finite radii >= 0",
                    ));
                }
            }
            Ok(LegSpec { nominal, radius })
        })
        .collect::<Result<Vec<LegSpec>, DataError>>()
        .map(|legs| RobotFile {
            legs,
            sets: parsed.leg.iter().map(|e| e.certified_set.clone()).collect(),
        })
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct UncertaintyFile {
    pos: Spanned<f64>,
    len: Spanned<f64>,
    axis: Option<Spanned<f64>>,
    angle_deg: Option<Spanned<f64>>,
    q: Option<Spanned<f64>>,
}

/// Reads `uncertainty.toml`: half-widths `pos`, `len`, and `axis` + `angle_deg` (axis-angle data) or
/// `q` (Rodrigues data). Missing values are NaN here and rejected by [`check_uncertainty`].
pub fn read_uncertainty(file: &Path) -> Result<Uncertainty, DataError> {
    parse_uncertainty(file, &read_text(file)?)
}

/// [`read_uncertainty`] on text already in memory; `file` names it in errors (e.g. an array).
pub fn parse_uncertainty(file: &Path, text: &str) -> Result<Uncertainty, DataError> {
    let u: UncertaintyFile = toml::from_str(text).map_err(|e| {
        let line = e.span().map(|s| line_at(text, s.start));
        error(
            file,
            line,
            None,
            format!(
                "{}; expected pos, len and axis + angle_deg (or q) half-widths",
                e.message()
            ),
        )
    })?;
    let half_width = |v: &Spanned<f64>, name: &str| -> Result<f64, DataError> {
        let line = Some(line_at(text, v.span().start));
        let x = finite_number(file, line, name, *v.get_ref())?;
        if x < 0.0 {
            return Err(error(
                file,
                line,
                Some(name),
                format!("expected a finite half-width >= 0, found {x}"),
            ));
        }
        Ok(x)
    };
    let optional = |v: &Option<Spanned<f64>>, name: &str| -> Result<f64, DataError> {
        v.as_ref().map_or(Ok(f64::NAN), |v| half_width(v, name))
    };
    Ok(Uncertainty {
        pos: half_width(&u.pos, "pos")?,
        len: half_width(&u.len, "len")?,
        axis: optional(&u.axis, "axis")?,
        angle_deg: optional(&u.angle_deg, "angle_deg")?,
        q: optional(&u.q, "q")?,
    })
}

/// Checks that the half-widths needed by the orientation format of the measurements are present.
pub fn check_uncertainty(file: &Path, u: &Uncertainty, rodrigues: bool) -> Result<(), DataError> {
    let needed: &[(&str, f64)] = if rodrigues {
        &[("q", u.q)]
    } else {
        &[("axis", u.axis), ("angle_deg", u.angle_deg)]
    };
    for (name, v) in needed {
        if v.is_nan() {
            let what = if rodrigues {
                "the measurements give q1,q2,q3"
            } else {
                "the measurements give an axis and an angle"
            };
            return Err(error(
                file,
                None,
                Some(name),
                format!("missing: {what}, so `{name}` is required"),
            ));
        }
    }
    Ok(())
}

/// The measurements: configurations and whether they give the orientation as a Rodrigues vector.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurements {
    /// The configurations, in file order.
    pub configs: Vec<Configuration>,
    /// Whether the file had `q1,q2,q3` columns (else `ax,ay,az,angle_deg`).
    pub rodrigues: bool,
    /// The 1-based file line of each configuration (for messages that name a configuration).
    pub lines: Vec<usize>,
}

/// Reads `measurements.csv` with header `px,py,pz,ax,ay,az,angle_deg,L1..Lk` or
/// `px,py,pz,q1,q2,q3,L1..Lk`, where `k` must equal `legs`; at least 7 rows (one per unknown of a
/// leg); axes within 1e-3 of unit length.
pub fn read_measurements(file: &Path, legs: usize) -> Result<Measurements, DataError> {
    parse_measurements(file, &read_text(file)?, legs)
}

/// [`read_measurements`] on text already in memory; `file` names it in errors (e.g. an array).
pub fn parse_measurements(file: &Path, text: &str, legs: usize) -> Result<Measurements, DataError> {
    parse_measurements_at_least(file, text, legs, MIN_CONFIGURATIONS)
}

/// The fewest configurations a calibration takes: one per unknown parameter of a leg.
pub const MIN_CONFIGURATIONS: usize = 7;

/// [`parse_measurements`] with at least `least` configurations (held-out data to check
/// predictions against may have fewer than a calibration needs).
pub fn parse_measurements_at_least(
    file: &Path,
    text: &str,
    legs: usize,
    least: usize,
) -> Result<Measurements, DataError> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| error(file, Some(1), None, format!("cannot read the header: {e}")))?
        .iter()
        .map(str::to_string)
        .collect();
    let (rodrigues, columns) = measurement_columns(file, &header, legs)?;
    let mut configs = Vec::new();
    let mut lines = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| record_error(file, &e))?;
        let line = record.position().map(|p| p.line() as usize);
        configs.push(configuration(file, line, &columns, &record, rodrigues)?);
        lines.push(line.unwrap_or(configs.len() + 1));
    }
    enough_configurations(file, configs.len(), least)?;
    Ok(Measurements {
        configs,
        rodrigues,
        lines,
    })
}

/// The columns of a measurements file with `legs` legs, chosen by its header: whether the
/// rotations are Rodrigues vectors (`q1` fourth), and the column names the header must have
/// (`px,py,pz,ax,ay,az,angle_deg` or `px,py,pz,q1,q2,q3`, then `L1..Lk`). An error on line 1
/// when the header differs, saying so when it has another number of leg columns.
fn measurement_columns(
    file: &Path,
    header: &[String],
    legs: usize,
) -> Result<(bool, Vec<String>), DataError> {
    let axis_angle = ["px", "py", "pz", "ax", "ay", "az", "angle_deg"];
    let rodrigues_cols = ["px", "py", "pz", "q1", "q2", "q3"];
    let rodrigues = header.get(3).map(String::as_str) == Some("q1");
    let fixed: &[&str] = if rodrigues {
        &rodrigues_cols
    } else {
        &axis_angle
    };
    let expected: Vec<String> = fixed
        .iter()
        .map(|c| c.to_string())
        .chain((1..=legs).map(|i| format!("L{i}")))
        .collect();
    if header != expected.as_slice() {
        let found_legs = header.iter().filter(|h| h.starts_with('L')).count();
        let hint = if found_legs != legs && header.len() > fixed.len() {
            format!(" (the file has {found_legs} leg columns, robot.toml has {legs} legs)")
        } else {
            String::new()
        };
        return Err(error(
            file,
            Some(1),
            None,
            format!(
                "unexpected header `{}`; expected `{}`{hint}",
                header.join(","),
                expected.join(",")
            ),
        ));
    }
    Ok((rodrigues, expected))
}

/// A row the CSV reader could not read, as a [`DataError`] on its line (a wrong number of
/// columns says how many were expected and found).
fn record_error(file: &Path, e: &csv::Error) -> DataError {
    let line = e.position().map(|p| p.line() as usize);
    let message = match e.kind() {
        csv::ErrorKind::UnequalLengths {
            expected_len, len, ..
        } => {
            format!("expected {expected_len} columns, found {len}")
        }
        _ => e.to_string(),
    };
    error(file, line, None, message)
}

/// The configuration in `record`, a row of a measurements file on `line`: a finite number in each
/// of the `columns` (from [`measurement_columns`]); an axis-angle rotation's axis within 1e-3 of
/// unit length.
fn configuration(
    file: &Path,
    line: Option<usize>,
    columns: &[String],
    record: &csv::StringRecord,
    rodrigues: bool,
) -> Result<Configuration, DataError> {
    let mut values = Vec::with_capacity(columns.len());
    for (field, raw) in columns.iter().zip(record.iter()) {
        let v: f64 = raw.parse().map_err(|_| {
            error(
                file,
                line,
                Some(field),
                format!("expected a number, found `{raw}`"),
            )
        })?;
        values.push(finite_number(file, line, field, v)?);
    }
    let p = [values[0], values[1], values[2]];
    let (orientation, rest) = if rodrigues {
        (
            Orientation::Rodrigues([values[3], values[4], values[5]]),
            &values[6..],
        )
    } else {
        let axis = [values[3], values[4], values[5]];
        let norm = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
        if (norm - 1.0).abs() > 1e-3 {
            return Err(error(
                file,
                line,
                Some("ax,ay,az"),
                format!("the rotation axis has length {norm}; expected a unit vector"),
            ));
        }
        (
            Orientation::AxisAngle {
                axis,
                angle_deg: values[6],
            },
            &values[7..],
        )
    };
    Ok(Configuration {
        p,
        orientation,
        lengths: rest.to_vec(),
    })
}

/// An error unless there are at least `least` configurations (saying why when it is the
/// calibration's [`MIN_CONFIGURATIONS`]).
fn enough_configurations(file: &Path, count: usize, least: usize) -> Result<(), DataError> {
    if count >= least {
        return Ok(());
    }
    let why = if least == MIN_CONFIGURATIONS {
        " (one per unknown parameter of a leg)"
    } else {
        ""
    };
    Err(error(
        file,
        None,
        None,
        format!("{count} configurations; at least {least} are needed{why}"),
    ))
}

/// The columns of a poses file: the platform centre (cm, base frame) and the rotation as a unit
/// axis and an angle in degrees — the measurement columns without the leg readings.
pub const POSE_COLUMNS: [&str; 7] = ["px", "py", "pz", "ax", "ay", "az", "angle_deg"];

/// Reads a poses file (see [`parse_poses`]).
pub fn read_poses(file: &Path) -> Result<Vec<Pose>, DataError> {
    parse_poses(file, &read_text(file)?)
}

/// Parses a poses file: header `px,py,pz,ax,ay,az,angle_deg` ([`POSE_COLUMNS`]), one pose per
/// row, at least 7 rows; each axis within 1e-3 of unit length (normalised on reading).
pub fn parse_poses(file: &Path, text: &str) -> Result<Vec<Pose>, DataError> {
    parse_poses_at_least(file, text, MIN_CONFIGURATIONS)
}

/// Where `gough predict` predicts: the poses of a measurement file (whose readings are then
/// checked) or of a poses file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PredictAt<'a> {
    /// A measurement file (`measurements.csv`'s layout).
    Measurements(&'a Path),
    /// A poses file (`gough design`'s layout).
    Poses(&'a Path),
}

/// The configurations to predict at `at` for a robot of `legs` legs (at least one), and, for a
/// measurement file, each configuration's line: a poses file's configurations carry no readings.
pub fn prediction_configurations(
    at: PredictAt<'_>,
    legs: usize,
) -> Result<(Vec<Configuration>, Option<Vec<usize>>), DataError> {
    match at {
        PredictAt::Measurements(path) => {
            let m = parse_measurements_at_least(path, &read_text(path)?, legs, 1)?;
            Ok((m.configs, Some(m.lines)))
        }
        PredictAt::Poses(path) => {
            let poses = parse_poses_at_least(path, &read_text(path)?, 1)?;
            Ok((poses.iter().map(Configuration::at_pose).collect(), None))
        }
    }
}

/// [`parse_poses`] with at least `least` poses.
pub fn parse_poses_at_least(file: &Path, text: &str, least: usize) -> Result<Vec<Pose>, DataError> {
    let header: Vec<String> = POSE_COLUMNS.iter().map(|c| c.to_string()).collect();
    let table = calib_pipeline::parse_number_table(file, text, &header)?;
    let mut poses = Vec::with_capacity(table.rows.len());
    for (row, &line) in table.rows.iter().zip(&table.lines) {
        let axis = [row[3], row[4], row[5]];
        let norm = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
        if norm.is_nan() || (norm - 1.0).abs() > 1e-3 {
            return Err(error(
                file,
                Some(line),
                Some("ax,ay,az"),
                format!("the rotation axis has length {norm}; expected a unit vector"),
            ));
        }
        poses.push(Pose {
            p: [row[0], row[1], row[2]],
            axis: axis.map(|c| c / norm),
            angle_deg: row[6],
        });
    }
    if poses.len() < least {
        let why = if least == MIN_CONFIGURATIONS {
            " (one per unknown parameter of a leg)"
        } else {
            ""
        };
        return Err(error(
            file,
            None,
            None,
            format!("{} poses; at least {least} are needed{why}", poses.len()),
        ));
    }
    Ok(poses)
}
