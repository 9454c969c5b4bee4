//! Reading the arm's files (mm and degrees): `robot.toml`, `measurements.csv`,
//! `uncertainty.toml`. Every malformed input is a [`DataError`] naming the file, the line and the
//! field.

use crate::certification::{padded_box, padded_index, padded_quantities, ArmSet, NM, NX};
use crate::pose::{PoseReading, PoseUncertainty};
use crate::robot::{Arm, Joint, ToolRotation};
use crate::simulate::{Reading, Uncertainty};
pub use crate::tracker_file::{parse_tracker_measurements, MeasurementColumns, Slack};
use crate::Arm7Point;
use calib_core::Interval;
use calib_pipeline::stored_set::StoredSet;
use calib_pipeline::{finite_number, line_at, read_text, toml_error, DataError};
use serde::Deserialize;
use std::path::Path;
use toml::Spanned;

/// Fewest and most joints an arm may have.
pub const JOINTS: std::ops::RangeInclusive<usize> = 3..=7;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RobotFile {
    joint: Vec<JointEntry>,
    base: BaseEntry,
    tool: ToolEntry,
    certified_set: Option<StoredSet>,
    carried_set: Option<StoredSet>,
    least_squares: Option<LeastSquaresEntry>,
}

/// `arm lsq --out`'s mark: whether the fit was proved consistent with the measurements.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LeastSquaresEntry {
    proved_consistent: Spanned<bool>,
}

/// The `[least_squares]` table `arm lsq --out` ends its robot file with: `proved_consistent`
/// says whether its parameter vector was proved to fit every measurement within the error bounds
/// (`--uncertainty`). A file marked `false` is a comparison, which [`read_exportable_robot`]
/// refuses to hand on as a calibration.
pub fn least_squares_mark(proved_consistent: bool) -> String {
    format!(
        "\n# a least-squares fit: {} consistent with the measurements within their error bounds\n\
         [least_squares]\nproved_consistent = {proved_consistent}\n",
        if proved_consistent {
            "proved"
        } else {
            "NOT proved"
        }
    )
}

/// Reads a robot file to hand on to a controller (`arm export`): as [`read_robot`], but refuses
/// `arm lsq --out`'s fits that are not proved consistent with their measurements
/// (`[least_squares] proved_consistent = false`, see [`least_squares_mark`]): every parameter
/// vector certicalib hands out is either a proved one or the user's own (nominal, imported,
/// registered).
pub fn read_exportable_robot(file: &Path) -> Result<Arm, DataError> {
    let text = read_text(file)?;
    let (arm, parsed) = parse_robot_file(file, &text)?;
    if let Some(mark) = parsed.least_squares {
        if !*mark.proved_consistent.get_ref() {
            return Err(DataError::new(
                file,
                Some(line_at(&text, mark.proved_consistent.span().start)),
                Some("least_squares.proved_consistent"),
                "this least-squares fit is not proved consistent with the measurements: a \
                 comparison, not a calibration to load into a controller; export what `arm \
                 certify --write-calibrated` writes (proved to fit every measurement)",
            ));
        }
    }
    Ok(arm)
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct JointEntry {
    theta_deg: Spanned<f64>,
    d: Spanned<f64>,
    a: Spanned<f64>,
    alpha_deg: Spanned<f64>,
    #[serde(default)]
    beta_deg: Option<Spanned<f64>>,
    radius: Spanned<Radius<5>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BaseEntry {
    xyz: Spanned<[f64; 3]>,
    rpy_deg: Spanned<[f64; 3]>,
    radius: Spanned<Radius<6>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ToolEntry {
    xyz: Spanned<[f64; 3]>,
    radius: Spanned<Radius<3>>,
    #[serde(default)]
    rpy_deg: Option<Spanned<[f64; 3]>>,
    #[serde(default)]
    rotation_radius: Option<Spanned<Radius<3>>>,
}

/// One half-width for all, or one per parameter.
#[derive(Deserialize)]
#[serde(untagged)]
enum Radius<const N: usize> {
    One(f64),
    #[serde(with = "serde_arrays")]
    Each([f64; N]),
}

/// Serde for const-generic arrays (serde implements arrays only up to 32 by macro, not for a
/// generic `N`).
mod serde_arrays {
    use serde::{Deserialize, Deserializer};

    pub fn deserialize<'de, D: Deserializer<'de>, const N: usize>(
        d: D,
    ) -> Result<[f64; N], D::Error> {
        let v = Vec::<f64>::deserialize(d)?;
        let len = v.len();
        v.try_into()
            .map_err(|_| serde::de::Error::invalid_length(len, &format!("{N} numbers").as_str()))
    }
}

impl<const N: usize> Radius<N> {
    fn each(&self) -> [f64; N] {
        match self {
            Radius::One(r) => [*r; N],
            Radius::Each(r) => *r,
        }
    }
}

const ROBOT_FORMAT: &str = "expected [[joint]] tables (base to flange) with theta_deg, d, a, \
alpha_deg, optional beta_deg and radius (one half-width or five: theta°, d mm, a mm, alpha°, \
beta°), then [base] with xyz, rpy_deg = [rx, ry, rz] and radius (one or six), and [tool] with xyz \
and radius (one or three), and for 6-DoF measurements rpy_deg = [rx, ry, rz] with rotation_radius (one or \
three, degrees)";

/// Reads `robot.toml` (see [`parse_robot`]).
pub fn read_robot(file: &Path) -> Result<Arm, DataError> {
    parse_robot(file, &read_text(file)?)
}

/// Reads a robot file with the certified set a calibrated file carries (`arm certify
/// --write-calibrated`): the arm, and its set rebuilt (`None` in a file without one). The
/// stored measurement boxes, cover and points are checked (errors name the field), the
/// polyhedra recomputed by the Newton step's relaxation and the points proved consistent again.
/// A `[carried_set]` (another tracker frame's, see [`parse_carried`]) is not read.
pub fn read_calibrated(file: &Path) -> Result<(Arm, Option<ArmSet>), DataError> {
    let text = read_text(file)?;
    let (arm, parsed) = parse_robot_file(file, &text)?;
    let set = parsed
        .certified_set
        .map(|stored| restore_set(file, &arm, &stored, "certified_set"))
        .transpose()?;
    Ok((arm, set))
}

/// Parses a robot file for `arm certify`: the arm, and the certified set it carries over to the
/// new measurements ([`crate::carry`]): its `[carried_set]` (what `arm register` copies from a
/// calibrated file, in that calibration's tracker frame) or its `[certified_set]`; `None` when
/// it has neither. Checked as [`read_calibrated`] checks a set.
pub fn parse_carried(file: &Path, text: &str) -> Result<(Arm, Option<ArmSet>), DataError> {
    let (arm, parsed) = parse_robot_file(file, text)?;
    let (stored, table) =
        match (parsed.carried_set, parsed.certified_set) {
            (Some(_), Some(_)) => return Err(DataError::new(
                file,
                None,
                Some("carried_set"),
                "a robot file holds a [certified_set] (its own) or a [carried_set] (an earlier \
                 frame's, written by `arm register`), not both",
            )),
            (Some(s), None) => (s, "carried_set"),
            (None, Some(s)) => (s, "certified_set"),
            (None, None) => return Ok((arm, None)),
        };
    let set = restore_set(file, &arm, &stored, table)?;
    Ok((arm, Some(set)))
}

/// Sets of at most this many pieces get the second-order Taylor rows
/// ([`calib_core::CertifiedSet::add_curvature_rows`]: two Hessian enclosures per configuration
/// and piece). A set of more pieces comes from `--hull`, whose smaller boxes leave the
/// relaxation's rows less slack to take back, at a cost that grows with the pieces.
const CURVATURE_ROW_PIECES: usize = 4;

/// The stored set of the robot file's table `table` as a certified set in the padded model
/// (module [`calib_pipeline::stored_set`]), checked; errors name `table.field`.
fn restore_set(
    file: &Path,
    arm: &Arm,
    stored: &StoredSet,
    table: &str,
) -> Result<ArmSet, DataError> {
    let joints = arm.joints.len();
    let x0 = padded_box(arm);
    let restored = stored
        .restore::<NX, NM>(
            &padded_index(joints),
            &padded_quantities(joints),
            &x0,
            &[Interval::ZERO; NM],
        )
        .map_err(|(f, m)| DataError::new(file, None, Some(&format!("{table}.{f}")), m))?;
    let mut set = ArmSet::new(
        &Arm7Point,
        &restored.cover,
        &restored.measurements,
        &restored.points,
        usize::MAX,
    );
    if set.pieces().len() <= CURVATURE_ROW_PIECES {
        set.add_curvature_rows(&Arm7Point);
    }
    if set.is_empty() || set.points().is_empty() {
        return Err(DataError::new(
            file,
            None,
            Some(&format!("{table}.points")),
            "the stored set holds no parameter vector proved consistent with its measurements \
             (was the file edited?): recalibrate with `arm certify --write-calibrated`",
        ));
    }
    Ok(set)
}

/// Parses a robot file with the set it carries as its text stores it (its `[certified_set]`,
/// else its `[carried_set]`; `None` when it has neither): what `arm register` copies on as the
/// registered file's `[carried_set]`, for `arm certify` ([`parse_carried`]).
pub fn parse_robot_and_set(file: &Path, text: &str) -> Result<(Arm, Option<StoredSet>), DataError> {
    let (arm, parsed) = parse_robot_file(file, text)?;
    Ok((arm, parsed.certified_set.or(parsed.carried_set)))
}

/// Parses `robot.toml`: one `[[joint]]` table per joint, base to flange, with `theta_deg, d, a,
/// alpha_deg`, optional `beta_deg` (default 0) and `radius` (one half-width for all, or five:
/// theta°, d mm, a mm, alpha°, beta°; 0 fixes a parameter); `[base]` with `xyz`, `rpy_deg =
/// [rx, ry, rz]`, `radius` (one, or six: x, y, z in mm, then rx, ry, rz in degrees); `[tool]`
/// with `xyz`, `radius` (one, or three). `file` names the text in errors.
pub fn parse_robot(file: &Path, text: &str) -> Result<Arm, DataError> {
    parse_robot_file(file, text).map(|(arm, _)| arm)
}

/// The half-widths of `r` (one for all, or one each), checked: finite and >= 0.
fn radii<const N: usize>(
    file: &Path,
    text: &str,
    r: &Spanned<Radius<N>>,
    field: &str,
) -> Result<[f64; N], DataError> {
    let line = Some(line_at(text, r.span().start));
    let each = r.get_ref().each();
    for v in each {
        if finite_number(file, line, field, v)? < 0.0 {
            return Err(DataError::new(
                file,
                line,
                Some(field),
                format!("{v}: expected half-widths >= 0 (0 fixes a parameter)"),
            ));
        }
    }
    Ok(each)
}

/// [`parse_robot`], also returning the parsed tables (for the optional ones: the certified set,
/// the least-squares mark).
fn parse_robot_file(file: &Path, text: &str) -> Result<(Arm, RobotFile), DataError> {
    let parsed: RobotFile =
        toml::from_str(text).map_err(|e| toml_error(file, text, &e, ROBOT_FORMAT))?;
    let line = |span: std::ops::Range<usize>| Some(line_at(text, span.start));
    let err = |span: std::ops::Range<usize>, field: &str, what: String| {
        DataError::new(file, line(span), Some(field), what)
    };
    let value = |v: &Spanned<f64>, field: String| -> Result<f64, DataError> {
        finite_number(file, line(v.span()), &field, *v.get_ref())
    };
    let values = |v: &Spanned<[f64; 3]>, field: &str| -> Result<[f64; 3], DataError> {
        let x = *v.get_ref();
        for c in x {
            finite_number(file, line(v.span()), field, c)?;
        }
        Ok(x)
    };
    let n = parsed.joint.len();
    if !JOINTS.contains(&n) {
        return Err(DataError::new(
            file,
            None,
            Some("joint"),
            format!(
                "{n} [[joint]] tables; arms with {} to {} joints are supported",
                JOINTS.start(),
                JOINTS.end()
            ),
        ));
    }
    let mut joints = Vec::with_capacity(n);
    for (i, j) in parsed.joint.iter().enumerate() {
        let f = |name: &str| format!("joint[{}].{name}", i + 1);
        let beta = match &j.beta_deg {
            Some(b) => value(b, f("beta_deg"))?,
            None => 0.0,
        };
        joints.push(Joint {
            nominal: [
                value(&j.theta_deg, f("theta_deg"))?,
                value(&j.d, f("d"))?,
                value(&j.a, f("a"))?,
                value(&j.alpha_deg, f("alpha_deg"))?,
                beta,
            ],
            radius: radii(file, text, &j.radius, &f("radius"))?,
        });
    }
    let xyz = values(&parsed.base.xyz, "base.xyz")?;
    let rpy = values(&parsed.base.rpy_deg, "base.rpy_deg")?;
    let tool_rotation =
        match (&parsed.tool.rpy_deg, &parsed.tool.rotation_radius) {
            (None, None) => None,
            (Some(rpy), Some(radius)) => Some(ToolRotation {
                rpy_deg: values(rpy, "tool.rpy_deg")?,
                radius: radii(file, text, radius, "tool.rotation_radius")?,
            }),
            (Some(rpy), None) => return Err(err(
                rpy.span(),
                "tool.rpy_deg",
                "the tool frame's rotation needs its prior too: rotation_radius = one half-width \
                 or three (degrees)"
                    .into(),
            )),
            (None, Some(radius)) => return Err(err(
                radius.span(),
                "tool.rotation_radius",
                "a prior for the tool frame's rotation needs the rotation: rpy_deg = [rx, ry, rz] \
                 (degrees)"
                    .into(),
            )),
        };
    let arm = Arm {
        joints,
        base: [xyz[0], xyz[1], xyz[2], rpy[0], rpy[1], rpy[2]],
        base_radius: radii(file, text, &parsed.base.radius, "base.radius")?,
        tool: values(&parsed.tool.xyz, "tool.xyz")?,
        tool_radius: radii(file, text, &parsed.tool.radius, "tool.radius")?,
        tool_rotation,
    };
    Ok((arm, parsed))
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct UncertaintyFile {
    joint_deg: Spanned<f64>,
    pos: Spanned<f64>,
    #[serde(default)]
    orient_deg: Option<Spanned<f64>>,
}

/// Reads `uncertainty.toml` (see [`parse_uncertainty`]).
pub fn read_uncertainty(file: &Path) -> Result<Uncertainty, DataError> {
    parse_uncertainty(file, &read_text(file)?)
}

/// Parses `uncertainty.toml`: `joint_deg` (half-width of every joint reading, degrees) and `pos`
/// (half-width of every tracked coordinate, mm).
pub fn parse_uncertainty(file: &Path, text: &str) -> Result<Uncertainty, DataError> {
    parse_pose_uncertainty(file, text).map(|u| u.position)
}

/// Parses `uncertainty.toml` with the bound of 6-DoF measurements' orientations: as
/// [`parse_uncertainty`], and `orient_deg` (optional: the half-width of every measured Euler
/// angle, degrees).
pub fn parse_pose_uncertainty(file: &Path, text: &str) -> Result<PoseUncertainty, DataError> {
    let u: UncertaintyFile = toml::from_str(text).map_err(|e| {
        toml_error(
            file,
            text,
            &e,
            "expected joint_deg = half-width in degrees, pos = half-width in mm, and for \
             6-DoF measurements orient_deg = half-width of each Euler angle in degrees",
        )
    })?;
    let check = |v: &Spanned<f64>, field: &str| {
        let line = Some(line_at(text, v.span().start));
        let x = finite_number(file, line, field, *v.get_ref())?;
        if x >= 0.0 {
            Ok(x)
        } else {
            Err(DataError::new(
                file,
                line,
                Some(field),
                format!("expected a finite half-width >= 0, found {x}"),
            ))
        }
    };
    Ok(PoseUncertainty {
        position: Uncertainty {
            joint_deg: check(&u.joint_deg, "joint_deg")?,
            pos: check(&u.pos, "pos")?,
        },
        orient_deg: u.orient_deg.map(|o| check(&o, "orient_deg")).transpose()?,
    })
}

/// The readings of a measurement file and the file line of each.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurements {
    /// One reading per configuration, in file order.
    pub readings: Vec<Reading>,
    /// The 1-based file line of each configuration.
    pub lines: Vec<usize>,
    /// The largest rounding error of converting the file's units to degrees and mm (0 for a file
    /// in those units): [`Slack::widen`] adds it to the error bounds.
    pub slack: Slack,
    /// Remarks on the file (values that may be in another unit than the one read).
    pub notes: Vec<String>,
    /// The measured orientation of each configuration (6-DoF probes), intrinsic Euler angles
    /// `XYZ` in degrees; `None` when the file was read for positions only.
    pub orientations: Option<Vec<[f64; 3]>>,
}

impl Measurements {
    /// The 6-DoF readings (each reading with its orientation) and the bounds `u` widened by the
    /// file's conversion slack ([`Slack::widen`], [`Slack::widen_orientation`]); `None` when the
    /// file was read for positions only.
    pub fn pose_readings(
        &self,
        u: &PoseUncertainty,
    ) -> Option<(Vec<PoseReading>, PoseUncertainty)> {
        let orientations = self.orientations.as_ref()?;
        let readings = self
            .readings
            .iter()
            .zip(orientations)
            .map(|(r, o)| PoseReading {
                reading: r.clone(),
                euler_xyz_deg: *o,
            })
            .collect();
        let bounds = PoseUncertainty {
            position: self.slack.widen(&u.position),
            orient_deg: u.orient_deg.map(|o| self.slack.widen_orientation(o)),
        };
        Some((readings, bounds))
    }
}

/// Reads `measurements.csv` (see [`parse_measurements`]).
pub fn read_measurements(file: &Path, joints: usize) -> Result<Measurements, DataError> {
    parse_measurements(file, &read_text(file)?, joints)
}

/// Parses `measurements.csv`: columns `q1,…,qN,px,py,pz` (`N = joints`; joint readings in
/// degrees, the tracked point in mm in the tracker frame; other columns are ignored), one row per
/// configuration, at least one row. Other layouts and units: [`parse_tracker_measurements`].
pub fn parse_measurements(
    file: &Path,
    text: &str,
    joints: usize,
) -> Result<Measurements, DataError> {
    parse_tracker_measurements(file, text, joints, &MeasurementColumns::standard(joints))
}

/// Reads a measurement file laid out as `columns` says (see [`parse_tracker_measurements`]).
pub fn read_tracker_measurements(
    file: &Path,
    joints: usize,
    columns: &MeasurementColumns,
) -> Result<Measurements, DataError> {
    parse_tracker_measurements(file, &read_text(file)?, joints, columns)
}
