//! The native half of the `certicalib` Python package: thin PyO3 wrappers around
//! `calib_gough::certification`, `calib_gough::simulate` and `calib_gough::lsq`, and
//! `calib_gough::design`, `calib_gough::accuracy`, `calib_arm::certification` and `calib_arm::simulate`, so that Python gets
//! exactly what `gough certify`, `gough simulate`, `gough lsq`, `gough design`, `gough accuracy`,
//! `arm certify`, `arm simulate`, `arm import`, `arm export`, `arm register` and
//! `arm certify --error-scale auto` compute.
//! Results cross the boundary as JSON text (the CLI's report schema); the Python side turns them
//! into objects with numpy arrays. Every data error becomes a `ValueError` naming the file, line and field; the long
//! work runs with the interpreter detached (other Python threads keep running).
//!
//! (No `#![deny(unsafe_code)]` here: PyO3's macros expand to the FFI glue, which is unsafe code.)

use calib_arm::certification::{certify_request, json_report, CertifyRequest};
use calib_gough::carry_over::{stored_rows, StoredRows};
use calib_gough::certification::{certify_legs_carrying, report, CertifyOptions};
use calib_gough::files::{
    check_uncertainty, parse_measurements, parse_robot_file, parse_uncertainty, read_measurements,
    read_robot, read_robot_file, read_uncertainty, LegSpec, Measurements, RobotFile,
};
use calib_gough::lsq::fit_legs;
use calib_gough::Uncertainty;
use calib_pipeline::verdict::ConfigurationNames;
use calib_pipeline::Depth;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::path::PathBuf;
use std::time::Instant;

fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// The parsed inputs of a certification, with the name the uncertainty goes by in errors.
struct Inputs {
    robot: Vec<LegSpec>,
    /// Per leg, the rows a calibrated robot file carries over (`gough certify --robot
    /// calibrated.toml`: the stored rows join the new ones).
    stored: Vec<Option<StoredRows>>,
    /// The robot file as read, and the name it goes by (the legs not certified keep its sets).
    file: (PathBuf, RobotFile),
    data: Measurements,
    uncertainty: Uncertainty,
    uncertainty_name: PathBuf,
}

/// Certifies and returns the JSON report.
fn run(
    py: Python<'_>,
    inputs: Inputs,
    options: CertifyOptions,
    write_calibrated: Option<PathBuf>,
    task: Option<PathBuf>,
) -> PyResult<String> {
    check_uncertainty(
        &inputs.uncertainty_name,
        &inputs.uncertainty,
        inputs.data.rodrigues,
    )
    .map_err(value_error)?;
    // The task is read before any work: a bad file is named at once.
    let task = task
        .as_deref()
        .map(calib_gough::calibrated::TaskFile::read)
        .transpose()
        .map_err(value_error)?;
    let start = Instant::now();
    let results = py
        .detach(|| {
            certify_legs_carrying(
                &inputs.robot,
                &inputs.stored,
                &inputs.data.configs,
                &inputs.uncertainty,
                &options,
                &|| {},
            )
        })
        .map_err(value_error)?;
    let seconds = start.elapsed().as_secs_f64();
    if let Some(path) = write_calibrated {
        // What `gough certify --write-calibrated` writes: per leg a geometry proved consistent
        // with every measurement, and the certified set.
        let cal = py.detach(|| {
            let mut cal = calib_gough::calibrated::calibrated_robot(
                &inputs.robot,
                &results,
                &inputs.data.configs,
                &inputs.uncertainty,
                task.as_ref().map(calib_gough::calibrated::TaskFile::task),
            )
            .map_err(value_error)?;
            cal.keep_stored_sets(&inputs.file.0, &inputs.file.1)
                .map_err(value_error)?;
            Ok::<_, PyErr>(cal)
        })?;
        let comment = format!(
            "calibrated by certicalib {} (Python): per leg a geometry proved consistent with \
             every measurement, and [leg.certified_set], the certified set",
            env!("CARGO_PKG_VERSION")
        );
        let text = calib_gough::calibrated::robot_toml(&cal.legs, &cal.sets, &comment);
        calib_pipeline::write_atomically(&path, &text)
            .map_err(|e| value_error(format!("{}: cannot write: {e}", path.display())))?;
    }
    serde_json::to_string(&report(&results, seconds)).map_err(value_error)
}

/// The options of `certify`, passed from Python as one dict (the keyword arguments of
/// `certicalib.certify`).
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
struct Options {
    legs: Option<Vec<usize>>,
    sweep: bool,
    /// A number or `auto` (what `--max-outliers` accepts).
    max_outliers: String,
    fast: bool,
    tolerance: f64,
    max_boxes: usize,
    max_seconds: Option<f64>,
    /// Where to write the calibrated robot file (`--write-calibrated`), if anywhere.
    write_calibrated: Option<PathBuf>,
    /// The task its geometry is chosen for (`--task`: a workspace.toml or a poses CSV).
    task: Option<PathBuf>,
}

impl TryFrom<Options> for CertifyOptions {
    type Error = PyErr;

    fn try_from(o: Options) -> PyResult<Self> {
        let max_outliers = o
            .max_outliers
            .parse()
            .map_err(|e| value_error(format!("max_outliers: {e}")))?;
        Ok(CertifyOptions {
            legs: o.legs,
            fast: o.fast,
            sweep: o.sweep,
            pave: None,
            tolerance: o.tolerance,
            max_boxes: o.max_boxes,
            max_seconds: o.max_seconds,
            max_outliers,
        })
    }
}

/// Certifies from the three files `gough certify` reads; returns the JSON report.
#[pyfunction]
fn certify_files(
    py: Python<'_>,
    robot: PathBuf,
    measurements: PathBuf,
    uncertainty: PathBuf,
    options: Options,
) -> PyResult<String> {
    let file = read_robot_file(&robot).map_err(value_error)?;
    let data = read_measurements(&measurements, file.legs.len()).map_err(value_error)?;
    let u = read_uncertainty(&uncertainty).map_err(value_error)?;
    let stored = stored_rows(&robot, &file, data.rodrigues).map_err(value_error)?;
    let inputs = Inputs {
        robot: file.legs.clone(),
        stored,
        file: (robot, file),
        data,
        uncertainty: u,
        uncertainty_name: uncertainty,
    };
    let (write, task) = (options.write_calibrated.clone(), options.task.clone());
    run(py, inputs, options.try_into()?, write, task)
}

/// Certifies from the three inputs as text in the files' formats (TOML, CSV, TOML), each with
/// the name it goes by in error messages; returns the JSON report.
#[pyfunction]
fn certify_text(
    py: Python<'_>,
    robot: &str,
    measurements: &str,
    uncertainty: &str,
    names: (String, String, String),
    options: Options,
) -> PyResult<String> {
    let (rn, mn, un) = (
        PathBuf::from(names.0),
        PathBuf::from(names.1),
        PathBuf::from(names.2),
    );
    let file: RobotFile = parse_robot_file(&rn, robot).map_err(value_error)?;
    let data = parse_measurements(&mn, measurements, file.legs.len()).map_err(value_error)?;
    let u = parse_uncertainty(&un, uncertainty).map_err(value_error)?;
    let stored = stored_rows(&rn, &file, data.rodrigues).map_err(value_error)?;
    let inputs = Inputs {
        robot: file.legs.clone(),
        stored,
        file: (rn, file),
        data,
        uncertainty: u,
        uncertainty_name: un,
    };
    let (write, task) = (options.write_calibrated.clone(), options.task.clone());
    run(py, inputs, options.try_into()?, write, task)
}

/// Writes the simulated data set of `gough simulate` into `out`, at random poses or (with
/// `poses`, a poses CSV) at the poses of `gough simulate --poses`; `outliers` are 1-based
/// `(configuration, leg, delta)`. Returns the contents of `truth.json`.
#[pyfunction]
#[pyo3(signature = (out, configs=21, seed=7, noise_scale=1.0, outliers=Vec::new(), poses=None))]
fn simulate(
    py: Python<'_>,
    out: PathBuf,
    configs: usize,
    seed: u64,
    noise_scale: f64,
    outliers: Vec<(usize, usize, f64)>,
    poses: Option<PathBuf>,
) -> PyResult<String> {
    let poses = poses
        .map(|p| calib_gough::files::read_poses(&p))
        .transpose()
        .map_err(value_error)?;
    let zero_based = outliers
        .iter()
        .map(|&(c, l, d)| {
            if c == 0 || l == 0 {
                Err(value_error(format!(
                    "outlier ({c}, {l}, {d}): configuration and leg are 1-based"
                )))
            } else {
                Ok((c - 1, l - 1, d))
            }
        })
        .collect::<PyResult<Vec<_>>>()?;
    py.detach(|| match &poses {
        Some(poses) => {
            calib_gough::simulate::write_data_set_at(&out, poses, seed, noise_scale, &zero_based)
        }
        None => {
            calib_gough::simulate::write_data_set(&out, configs, seed, noise_scale, &zero_based)
        }
    })
    .map_err(value_error)?;
    std::fs::read_to_string(out.join("truth.json")).map_err(value_error)
}

/// Least squares per leg (what `gough lsq` prints), as JSON: one object per leg with `leg`,
/// `converged`, `x`, `rms` and `max_length_error`.
#[pyfunction]
fn lsq(py: Python<'_>, robot: PathBuf, measurements: PathBuf) -> PyResult<String> {
    let spec = read_robot(&robot).map_err(value_error)?;
    let data = read_measurements(&measurements, spec.len()).map_err(value_error)?;
    let fits = py.detach(|| fit_legs(&spec, &data.configs));
    let legs: Vec<serde_json::Value> = fits
        .iter()
        .enumerate()
        .map(|(i, f)| {
            serde_json::json!({
                "leg": i + 1, "converged": f.converged, "x": f.x.to_vec(),
                "rms": f.rms, "max_length_error": f.max_length_error,
            })
        })
        .collect();
    serde_json::to_string(&legs).map_err(value_error)
}

/// The options of `arm_certify_files`, passed from Python as one dict (the keyword arguments of
/// `certicalib.certify_arm`).
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
struct ArmOptions {
    hull: bool,
    tolerance: f64,
    max_boxes: usize,
    max_seconds: Option<f64>,
    /// A number or `auto`.
    max_outliers: String,
    lsq: bool,
    /// Where to write the calibrated robot file (`--write-calibrated`), if anywhere.
    write_calibrated: Option<PathBuf>,
    /// The task its parameters are chosen for (`--task`: a joints.toml box or a CSV of
    /// configurations).
    task: Option<PathBuf>,
    /// 6-DoF data: the three orientation columns (`--orientation-columns`), if any.
    orientation_columns: Option<Vec<String>>,
    /// Their convention (`--orientation-convention`).
    orientation_convention: String,
}

impl TryFrom<ArmOptions> for CertifyRequest {
    type Error = PyErr;

    fn try_from(o: ArmOptions) -> PyResult<Self> {
        Ok(CertifyRequest {
            depth: if o.hull { Depth::Hull } else { Depth::Fast },
            tolerance: o.tolerance,
            max_boxes: o.max_boxes,
            max_seconds: o.max_seconds,
            max_outliers: o
                .max_outliers
                .parse()
                .map_err(|e| value_error(format!("max_outliers: {e}")))?,
            lsq: o.lsq,
        })
    }
}

/// Certifies a serial arm from the three files `arm certify` reads (the measurements with
/// `columns` and, for 6-DoF data, the options' orientation columns); returns the JSON report of
/// `arm certify --json`.
#[pyfunction]
fn arm_certify_files(
    py: Python<'_>,
    robot: PathBuf,
    measurements: PathBuf,
    uncertainty: PathBuf,
    options: ArmOptions,
    columns: Columns,
) -> PyResult<String> {
    let (write, options_task) = (options.write_calibrated.clone(), options.task.clone());
    let orientation = orientation_layout(
        options.orientation_columns.clone(),
        &options.orientation_convention,
    )?;
    let request: CertifyRequest = options.try_into()?;
    let (arm, data, bounds) =
        arm_pose_inputs(&robot, &measurements, &uncertainty, columns, orientation)?;
    // The task is read before any work: a bad file is named at once.
    let task = options_task
        .as_deref()
        .map(|t| calib_arm::joint_space::read_task(t, arm.joints.len()))
        .transpose()
        .map_err(value_error)?;
    let pose = data.pose_readings(&bounds);
    if pose.is_some() {
        calib_arm::pose::require_pose_inputs(&arm, &robot, &bounds, &uncertainty)
            .map_err(value_error)?;
    }
    let earlier = carried_set(&robot)?;
    if pose.is_some() && earlier.is_some() {
        return Err(value_error(calib_arm::ArmError::CarryWithPose));
    }
    let (q, run) = py
        .detach(|| match (&pose, &earlier) {
            (Some((readings, b)), _) => calib_arm::pose::certify_pose(&arm, readings, b, &request),
            (None, earlier) => {
                let u = data.slack.widen(&bounds.position);
                match earlier {
                    Some(set) => {
                        calib_arm::carry::certify_carried(&arm, set, &data.readings, &u, &request)
                    }
                    None => certify_request(&arm, &data.readings, &u, &request),
                }
            }
        })
        .map_err(value_error)?;
    let base_name = |p: &std::path::Path| {
        p.file_name()
            .map_or_else(String::new, |f| f.to_string_lossy().into_owned())
    };
    let (file, robot_file) = (base_name(&measurements), base_name(&robot));
    let stored_rows: Vec<usize> = earlier.as_ref().map_or_else(Vec::new, |s| {
        calib_arm::carry::carried_rows(s)
            .iter()
            .map(|k| k + 1)
            .collect()
    });
    let names = ConfigurationNames {
        file: &file,
        lines: &data.lines,
        carried: earlier
            .as_ref()
            .map(|_| calib_pipeline::verdict::CarriedRows {
                file: &robot_file,
                rows: &stored_rows,
            }),
    };
    if let Some(path) = write {
        use calib_arm::calibrated::PointChoice;
        let (choice, joints, rule) = match (task, &options_task) {
            (Some(joints), Some(t)) => (
                PointChoice::Task,
                joints,
                format!(
                    "towards the centre of the tool points it predicts over the task {}",
                    t.display()
                ),
            ),
            _ => (
                PointChoice::LeastSquares,
                data.readings.iter().map(|r| r.joints_deg.clone()).collect(),
                "towards the least-squares fit within the set (regularised, weight by \
                 cross-validation)"
                    .to_string(),
            ),
        };
        let cal = py
            .detach(|| calib_arm::calibrated::calibrated_arm(&arm, &run, &joints, choice))
            .map_err(value_error)?;
        let comment = format!(
            "# calibrated by certicalib {} (Python): a parameter vector proved consistent with \
             every measurement, {rule}; [certified_set]: the certified set\n",
            env!("CARGO_PKG_VERSION")
        );
        calib_pipeline::write_atomically(
            &path,
            &calib_arm::calibrated::calibrated_toml(&cal, &comment),
        )
        .map_err(|e| value_error(format!("{}: cannot write: {e}", path.display())))?;
    }
    let report = json_report(&run, &names, q);
    if earlier.is_none() {
        return Ok(report);
    }
    // As `arm certify --json`: where the carried rows came from (numbered after the new ones).
    let mut json: serde_json::Value = serde_json::from_str(&report).map_err(value_error)?;
    json["carried_over"] = serde_json::json!({
        "file": robot_file,
        "configurations": stored_rows.len(),
    });
    Ok(json.to_string())
}

/// Writes the simulated data set of `arm simulate` into `out` (the built-in arm, or `robot`);
/// `outliers` are 1-based `(configuration, delta_mm)`. Returns the contents of `truth.json`.
#[pyfunction]
#[pyo3(signature = (out, configs=50, seed=1, robot=None, outliers=Vec::new()))]
fn arm_simulate(
    py: Python<'_>,
    out: PathBuf,
    configs: usize,
    seed: u64,
    robot: Option<PathBuf>,
    outliers: Vec<(usize, f64)>,
) -> PyResult<String> {
    if configs == 0 {
        return Err(value_error("configs: at least one configuration"));
    }
    let arm = match robot {
        Some(path) => calib_arm::files::read_robot(&path).map_err(value_error)?,
        None => calib_arm::builtin_arm(),
    };
    let zero_based = outliers
        .iter()
        .map(|&(c, d)| {
            if c == 0 || c > configs || !d.is_finite() {
                Err(value_error(format!(
                    "outlier ({c}, {d}): configuration must be 1..={configs}, delta finite"
                )))
            } else {
                Ok((c - 1, d))
            }
        })
        .collect::<PyResult<Vec<_>>>()?;
    py.detach(|| {
        let u = calib_arm::simulate::Uncertainty::TRACKER;
        let sim = calib_arm::simulate::simulate(&arm, configs, seed, u, 1.0, &zero_based);
        calib_arm::write::write_data_set(&out, &arm, &sim)
    })
    .map_err(|e| value_error(format!("{}: cannot write the data set: {e}", out.display())))?;
    std::fs::read_to_string(out.join("truth.json")).map_err(value_error)
}

/// Where the measurements are in a tracker's file and in which units (the keyword arguments of
/// the arm functions: `joint_columns`, `point_columns`, `joint_unit`, `length_unit`, `rows`).
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
struct Columns {
    joint_columns: Option<Vec<String>>,
    point_columns: Option<Vec<String>>,
    joint_unit: String,
    length_unit: String,
    rows: Option<String>,
}

/// The orientation columns (three names) and their convention (`euler-xyz-deg` or
/// `euler-xyz-rad`), when given (what `--orientation-columns` and `--orientation-convention` do).
fn orientation_layout(
    columns: Option<Vec<String>>,
    convention: &str,
) -> PyResult<Option<([String; 3], calib_arm::tracker_file::OrientationConvention)>> {
    let Some(o) = columns else {
        return Ok(None);
    };
    let names = <[String; 3]>::try_from(o).map_err(|o| {
        value_error(format!(
            "orientation_columns: expected three names, found {}",
            o.len()
        ))
    })?;
    let convention = convention
        .parse()
        .map_err(|e: calib_arm::ArmError| value_error(format!("orientation_convention: {e}")))?;
    Ok(Some((names, convention)))
}

/// The arm of `robot`, its measurements read with `columns` and `orientation`, and the bounds of
/// `uncertainty` (orientations' included): what the 6-DoF-aware arm functions read.
fn arm_pose_inputs(
    robot: &std::path::Path,
    measurements: &std::path::Path,
    uncertainty: &std::path::Path,
    columns: Columns,
    orientation: Option<([String; 3], calib_arm::tracker_file::OrientationConvention)>,
) -> PyResult<(
    calib_arm::robot::Arm,
    calib_arm::files::Measurements,
    calib_arm::pose::PoseUncertainty,
)> {
    let arm = calib_arm::files::read_robot(robot).map_err(value_error)?;
    let mut layout = arm_columns(arm.joints.len(), columns)?;
    layout.orientation = orientation;
    let data = calib_arm::files::read_tracker_measurements(measurements, arm.joints.len(), &layout)
        .map_err(value_error)?;
    let text = std::fs::read_to_string(uncertainty)
        .map_err(|e| value_error(format!("{}: cannot read: {e}", uncertainty.display())))?;
    let bounds =
        calib_arm::files::parse_pose_uncertainty(uncertainty, &text).map_err(value_error)?;
    Ok((arm, data, bounds))
}

/// The certified set the robot file carries over to a certification (its `[carried_set]` or
/// `[certified_set]`, see `calib_arm::carry`), if any.
fn carried_set(robot: &std::path::Path) -> PyResult<Option<calib_arm::certification::ArmSet>> {
    let text = calib_pipeline::read_text(robot).map_err(value_error)?;
    let (_, set) = calib_arm::files::parse_carried(robot, &text).map_err(value_error)?;
    Ok(set)
}

/// The layout `columns` gives an arm of `joints` joints.
fn arm_columns(joints: usize, c: Columns) -> PyResult<calib_arm::tracker_file::MeasurementColumns> {
    use calib_arm::tracker_file::MeasurementColumns;
    let mut m = MeasurementColumns::with_names(joints, c.joint_columns, c.point_columns)
        .map_err(|e| value_error(format!("point_columns: {e}")))?;
    m.joint_unit = (c.joint_unit.parse())
        .map_err(|e: calib_arm::ArmError| value_error(format!("joint_unit: {e}")))?;
    m.length_unit = (c.length_unit.parse())
        .map_err(|e: calib_arm::ArmError| value_error(format!("length_unit: {e}")))?;
    m.rows = c
        .rows
        .map(|r| r.parse())
        .transpose()
        .map_err(|e| value_error(format!("rows: {e}")))?;
    Ok(m)
}

/// Imports a vendor's kinematics (`kind`: `ur_yaml` or `urdf`) into the robot file `out`, as
/// `arm import` does; returns the file's text.
#[pyfunction]
#[pyo3(signature = (source, kind, out, base_link=None, tip_link=None, angle_radius=0.1, length_radius=1.0))]
fn arm_import(
    source: PathBuf,
    kind: &str,
    out: PathBuf,
    base_link: Option<String>,
    tip_link: Option<String>,
    angle_radius: f64,
    length_radius: f64,
) -> PyResult<String> {
    use calib_arm::vendor::{chain_to_arm, ur_yaml, urdf, ImportRadii};
    for (v, name) in [
        (angle_radius, "angle_radius"),
        (length_radius, "length_radius"),
    ] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(value_error(format!("{name} {v}: a finite half-width >= 0")));
        }
    }
    let text = calib_pipeline::read_text(&source).map_err(value_error)?;
    let origins = match kind {
        "ur_yaml" => ur_yaml::parse(&source, &text).map_err(value_error)?.origins,
        "urdf" => urdf::parse(&source, &text, base_link.as_deref(), tip_link.as_deref())
            .map_err(value_error)?,
        other => {
            return Err(value_error(format!(
                "kind: `ur_yaml` or `urdf`, not `{other}`"
            )))
        }
    };
    let radii = ImportRadii {
        angle_deg: angle_radius,
        length_mm: length_radius,
    };
    let arm = chain_to_arm(&origins, radii)
        .map_err(|e| value_error(format!("{}: {e}", source.display())))?;
    let robot = format!(
        "# imported by certicalib {} from {}\n{}",
        env!("CARGO_PKG_VERSION"),
        source.display(),
        calib_arm::write::robot_toml(&arm)
    );
    calib_pipeline::write_atomically(&out, &robot)
        .map_err(|e| value_error(format!("{}: cannot write: {e}", out.display())))?;
    Ok(robot)
}

/// Exports a robot file as UR's kinematics YAML and/or a URDF, as `arm export` does.
#[pyfunction]
#[pyo3(signature = (robot, ur_yaml=None, urdf=None, hash=None))]
fn arm_export(
    robot: PathBuf,
    ur_yaml: Option<PathBuf>,
    urdf: Option<PathBuf>,
    hash: Option<String>,
) -> PyResult<()> {
    let arm = calib_arm::files::read_exportable_robot(&robot).map_err(value_error)?;
    let chain = calib_arm::vendor::arm_to_chain(&arm)
        .map_err(|e| value_error(format!("{}: {e}", robot.display())))?;
    let source = format!("exported by certicalib from {}", robot.display());
    let yaml = ur_yaml
        .as_ref()
        .map(|_| calib_arm::vendor::ur_yaml::write(&chain, hash.as_deref(), &source))
        .transpose()
        .map_err(value_error)?;
    let write = |path: &PathBuf, text: &str| {
        calib_pipeline::write_atomically(path, text)
            .map_err(|e| value_error(format!("{}: cannot write: {e}", path.display())))
    };
    if let (Some(path), Some(text)) = (&ur_yaml, yaml) {
        write(path, &text)?;
    }
    if let Some(path) = &urdf {
        write(
            path,
            &calib_arm::vendor::urdf::write("robot", &chain, arm.tool),
        )?;
    }
    Ok(())
}

/// Registers the tracker and the tool point, as `arm register` does — and with
/// `orientation_columns` (three names, `orientation_convention` `euler-xyz-deg` or
/// `euler-xyz-rad`) the tool frame's rotation with the prior `tool_rotation_radius` (degrees):
/// writes `out` and returns JSON (`base`, `tool`, `tool_kept`, `warning`, `rms_mm`, `max_mm`,
/// `start_rms_mm`, `converged`, and `tool_rotation` with `rpy_deg`, `rms_deg`, `max_deg` or
/// null). Where the rows cannot tell the tool point from the base (one flange orientation), the
/// robot file's is kept, fixed, and `warning` says why (else null).
#[pyfunction]
#[pyo3(signature = (robot, measurements, out, columns, priors, orientation_columns=None, orientation_convention="euler-xyz-deg", tool_rotation_radius=0.5))]
#[allow(clippy::too_many_arguments)] // the command line's options, one argument each
fn arm_register(
    py: Python<'_>,
    robot: PathBuf,
    measurements: PathBuf,
    out: PathBuf,
    columns: Columns,
    priors: (f64, f64, f64),
    orientation_columns: Option<Vec<String>>,
    orientation_convention: &str,
    tool_rotation_radius: f64,
) -> PyResult<String> {
    let text = calib_pipeline::read_text(&robot).map_err(value_error)?;
    let (arm, set) = calib_arm::files::parse_robot_and_set(&robot, &text).map_err(value_error)?;
    let mut layout = arm_columns(arm.joints.len(), columns)?;
    layout.orientation = orientation_layout(orientation_columns, orientation_convention)?;
    let data =
        calib_arm::files::read_tracker_measurements(&measurements, arm.joints.len(), &layout)
            .map_err(value_error)?;
    let priors = calib_arm::register::RegistrationPriors {
        base_mm: priors.0,
        base_deg: priors.1,
        tool_mm: priors.2,
    };
    let mut r = py
        .detach(|| calib_arm::register::register(&arm, &data.readings, priors))
        .map_err(|e| value_error(format!("{}: {e}", measurements.display())))?;
    let rotation = match &data.orientations {
        Some(o) => {
            let (t, rms, max) = calib_arm::register::register_tool_rotation(
                &r.arm,
                &data.readings,
                o,
                tool_rotation_radius,
            )
            .map_err(|e| value_error(format!("{}: {e}", measurements.display())))?;
            r.arm.tool_rotation = Some(t);
            serde_json::json!({"rpy_deg": t.rpy_deg, "rms_deg": rms, "max_deg": max})
        }
        None => serde_json::Value::Null,
    };
    let carried = set.map_or_else(String::new, |s| {
        calib_arm::carry::carried_set_toml(&robot, &s)
    });
    let text = format!(
        "# registered by certicalib {}\n{}{carried}",
        env!("CARGO_PKG_VERSION"),
        calib_arm::write::robot_toml(&r.arm)
    );
    calib_pipeline::write_atomically(&out, &text)
        .map_err(|e| value_error(format!("{}: cannot write: {e}", out.display())))?;
    // Rows that cannot tell the tool point from the base: the library kept the file's, fixed.
    let warning = r.separability.reason().map(|why| {
        format!(
            "{why}. The tool point is kept from {} and fixed (prior half-width 0); the base is \
             fitted alone",
            robot.display()
        )
    });
    Ok(serde_json::json!({
        "base": r.arm.base,
        "tool": r.arm.tool,
        "tool_kept": r.tool_kept,
        "warning": warning,
        "rms_mm": r.rms,
        "max_mm": r.max_abs,
        "start_rms_mm": r.start_rms,
        "converged": r.converged,
        "tool_rotation": rotation,
    })
    .to_string())
}

/// The smallest consistent factor of the error bounds, as `arm certify --error-scale auto`
/// finds it (with `orientation_columns`, on positions and orientations): JSON (`bounds`, `s_lo`,
/// `s_hi`, `ratio`, `trials`, …).
#[pyfunction]
#[pyo3(signature = (robot, measurements, uncertainty, columns, scale_bounds, orientation_columns=None, orientation_convention="euler-xyz-deg"))]
#[allow(clippy::too_many_arguments)] // the command line's options, one argument each
fn arm_error_scale(
    py: Python<'_>,
    robot: PathBuf,
    measurements: PathBuf,
    uncertainty: PathBuf,
    columns: Columns,
    scale_bounds: &str,
    orientation_columns: Option<Vec<String>>,
    orientation_convention: &str,
) -> PyResult<String> {
    use calib_arm::error_scale::{search, search_pose, ScaleBounds};
    use calib_pipeline::error_scale::to_json;
    let which = match scale_bounds {
        "all" => ScaleBounds::All,
        "pos" => ScaleBounds::Pos,
        "joint_deg" => ScaleBounds::JointDeg,
        "orient_deg" => ScaleBounds::OrientDeg,
        other => {
            return Err(value_error(format!(
                "scale_bounds: `all`, `pos`, `joint_deg` or `orient_deg`, not `{other}`"
            )))
        }
    };
    let orientation = orientation_layout(orientation_columns, orientation_convention)?;
    let (arm, data, bounds) =
        arm_pose_inputs(&robot, &measurements, &uncertainty, columns, orientation)?;
    let started = Instant::now();
    let found = match data.pose_readings(&bounds) {
        Some(_) if carried_set(&robot)?.is_some() => {
            return Err(value_error(calib_arm::ArmError::CarryWithPose));
        }
        Some((readings, bounds)) => {
            py.detach(|| search_pose(&arm, &readings, &bounds, which, |_| {}))
        }
        None => {
            let u = data.slack.widen(&bounds.position);
            let earlier = carried_set(&robot)?;
            py.detach(|| match &earlier {
                Some(set) => {
                    calib_arm::carry::search_carried(&arm, set, &data.readings, &u, which, |_| {})
                }
                None => search(&arm, &data.readings, &u, which, |_| {}),
            })
        }
    }
    .map_err(value_error)?;
    Ok(to_json(&found, which.name(), None, started.elapsed().as_secs_f64()).to_string())
}

/// The smallest consistent factor of a Gough platform's error bounds, as `gough certify
/// --error-scale auto` finds it: JSON (`bounds`, `s_lo`, `s_hi`, `ratio`, `trials`, …).
#[pyfunction]
#[pyo3(signature = (robot, measurements, uncertainty, scale_bounds, legs=None))]
fn error_scale_files(
    py: Python<'_>,
    robot: PathBuf,
    measurements: PathBuf,
    uncertainty: PathBuf,
    scale_bounds: &str,
    legs: Option<Vec<usize>>,
) -> PyResult<String> {
    use calib_gough::error_scale::{search, ScaleBounds};
    use calib_pipeline::error_scale::to_json;
    let which = match scale_bounds {
        "all" => ScaleBounds::All,
        "pos" => ScaleBounds::Pos,
        "len" => ScaleBounds::Len,
        "orientation" => ScaleBounds::Orientation,
        other => {
            return Err(value_error(format!(
                "scale_bounds: `all`, `pos`, `len` or `orientation`, not `{other}`"
            )))
        }
    };
    let file = calib_gough::files::read_robot_file(&robot).map_err(value_error)?;
    let spec = file.legs.clone();
    let data = read_measurements(&measurements, spec.len()).map_err(value_error)?;
    let u = read_uncertainty(&uncertainty).map_err(value_error)?;
    check_uncertainty(&uncertainty, &u, data.rodrigues).map_err(value_error)?;
    // As `gough certify --error-scale auto`: rows a calibrated file carries over join the new.
    let stored = stored_rows(&robot, &file, data.rodrigues).map_err(value_error)?;
    let (legs, _) = CertifyOptions {
        legs,
        ..CertifyOptions::default()
    }
    .validate(spec.len(), data.configs.len())
    .map_err(value_error)?;
    let started = Instant::now();
    let found = py.detach(|| search(&spec, &stored, &legs, &data.configs, &u, which, |_| {}));
    Ok(to_json(&found, which.name(), None, started.elapsed().as_secs_f64()).to_string())
}

/// Predicts the leg readings at `poses` (a poses CSV) or at the poses of `measurements` (whose
/// readings are then checked) over the robot file's certified set, as `gough predict` does;
/// returns the JSON of `gough predict --json`.
#[pyfunction]
#[pyo3(signature = (robot, uncertainty, poses=None, measurements=None))]
fn predict(
    py: Python<'_>,
    robot: PathBuf,
    uncertainty: PathBuf,
    poses: Option<PathBuf>,
    measurements: Option<PathBuf>,
) -> PyResult<String> {
    use calib_gough::files::{leg_sets, prediction_configurations, read_robot_file, PredictAt};
    let file = read_robot_file(&robot).map_err(value_error)?;
    let sets = leg_sets(&robot, &file).map_err(value_error)?;
    let u = read_uncertainty(&uncertainty).map_err(value_error)?;
    let at = match (&measurements, &poses) {
        (Some(path), None) => PredictAt::Measurements(path),
        (None, Some(path)) => PredictAt::Poses(path),
        _ => return Err(value_error("give poses or measurements (one of them)")),
    };
    let measured = measurements.is_some();
    let (configs, lines) = prediction_configurations(at, file.legs.len()).map_err(value_error)?;
    let predictions =
        py.detach(|| calib_gough::predict::predict(&file.legs, &sets, &configs, &u, measured));
    let over_set: Vec<bool> = sets.iter().map(Option::is_some).collect();
    Ok(
        calib_gough::predict::predictions_json(&predictions, &over_set, lines.as_deref())
            .to_string(),
    )
}

/// Predicts the tracked point at the joint readings of `measurements` (read with `columns`, the
/// points then checked) over the robot file's certified set, as `arm predict --measurements`
/// does; with `orientation_columns` (in `orientation_convention`) the measured orientations'
/// residuals against the file's values too. Returns the JSON of `arm predict --json`.
#[pyfunction]
#[pyo3(signature = (robot, uncertainty, measurements, columns, orientation_columns=None, orientation_convention="euler-xyz-deg"))]
fn arm_predict(
    py: Python<'_>,
    robot: PathBuf,
    uncertainty: PathBuf,
    measurements: PathBuf,
    columns: Columns,
    orientation_columns: Option<Vec<String>>,
    orientation_convention: &str,
) -> PyResult<String> {
    let (arm, set) = calib_arm::files::read_calibrated(&robot).map_err(value_error)?;
    let mut layout = arm_columns(arm.joints.len(), columns)?;
    layout.orientation = orientation_layout(orientation_columns, orientation_convention)?;
    let data =
        calib_arm::files::read_tracker_measurements(&measurements, arm.joints.len(), &layout)
            .map_err(value_error)?;
    let orientations = data
        .orientations
        .as_ref()
        .map(|o| {
            calib_arm::predict::OrientationResiduals::of(&arm, &robot, &data.readings, o)
                .map_err(value_error)
        })
        .transpose()?;
    let u = data
        .slack
        .widen(&calib_arm::files::read_uncertainty(&uncertainty).map_err(value_error)?);
    let joints: Vec<Vec<f64>> = data.readings.iter().map(|r| r.joints_deg.clone()).collect();
    let points: Vec<[f64; 3]> = data.readings.iter().map(|r| r.point).collect();
    let predictions =
        py.detach(|| calib_arm::predict::predict(&arm, set.as_ref(), &joints, &u, Some(&points)));
    let mut json =
        calib_arm::predict::predictions_json(&predictions, set.is_some(), Some(&data.lines));
    if let Some(o) = orientations {
        json["orientation_residuals"] = o.json();
    }
    Ok(json.to_string())
}

/// Designs the poses to measure, as `gough design` does: writes the poses CSV to `out` and
/// returns the JSON of `gough design --json`. Without `robot`, the built-in hexapod (± 0.1 cm);
/// without `uncertainty`, the paper's bounds; without `workspace`, the simulator's.
#[pyfunction]
#[pyo3(signature = (out, robot=None, uncertainty=None, workspace=None, configs=21, candidates=2000, criterion="certified".to_string(), seed=1, extend=None))]
#[allow(clippy::too_many_arguments)]
fn design(
    py: Python<'_>,
    out: PathBuf,
    robot: Option<PathBuf>,
    uncertainty: Option<PathBuf>,
    workspace: Option<PathBuf>,
    configs: usize,
    candidates: usize,
    criterion: String,
    seed: u64,
    extend: Option<PathBuf>,
) -> PyResult<String> {
    use calib_gough::design::{builtin_robot, plan, poses_csv, DesignRequest};
    let robot = match robot {
        Some(p) => read_robot(&p).map_err(value_error)?,
        None => builtin_robot(),
    };
    let u = match &uncertainty {
        Some(p) => {
            let u = read_uncertainty(p).map_err(value_error)?;
            check_uncertainty(p, &u, false).map_err(value_error)?;
            u
        }
        None => Uncertainty::PAPER,
    };
    let workspace = match workspace {
        Some(p) => calib_gough::workspace::read_workspace(&p).map_err(value_error)?,
        None => calib_gough::workspace::Workspace::SIMULATOR,
    };
    let already = match extend {
        Some(p) => {
            let data = read_measurements(&p, robot.len()).map_err(value_error)?;
            calib_gough::design::extension(data, &u, uncertainty.as_deref()).map_err(value_error)?
        }
        None => Vec::new(),
    };
    let request = DesignRequest {
        configs,
        candidates,
        criterion: criterion
            .parse()
            .map_err(|e| value_error(format!("criterion: {e}")))?,
        seed,
    };
    let plan = py
        .detach(|| plan(&robot, &u, &workspace, &request, &already, &|| {}))
        .map_err(value_error)?;
    calib_pipeline::write_atomically(&out, &poses_csv(&plan.design.poses))
        .map_err(|e| value_error(format!("{}: cannot write: {e}", out.display())))?;
    Ok(plan.json().to_string())
}

/// Brackets the leg-length errors of a robot file over a workspace, as `gough accuracy` does;
/// returns the JSON of `gough accuracy --json`.
#[pyfunction]
#[pyo3(signature = (robot, workspace, before=None, uncertainty=None, tolerance=0.04, max_boxes=300_000, pose_seconds=30.0, max_set_boxes=1000, report=None, refine_set=false))]
#[allow(clippy::too_many_arguments)]
fn accuracy(
    py: Python<'_>,
    robot: PathBuf,
    workspace: PathBuf,
    before: Option<PathBuf>,
    uncertainty: Option<PathBuf>,
    tolerance: f64,
    max_boxes: usize,
    pose_seconds: f64,
    max_set_boxes: usize,
    report: Option<PathBuf>,
    refine_set: bool,
) -> PyResult<String> {
    use calib_gough::accuracy::{
        accuracy_report, AccuracyProblem, AccuracySettings, REFINED_SET_PIECES,
    };
    let file = calib_gough::files::read_robot_file(&robot).map_err(value_error)?;
    let sets = calib_gough::files::leg_sets(&robot, &file).map_err(value_error)?;
    let inputs = accuracy_inputs(&[
        ("robot file", Some(&robot)),
        ("workspace", Some(&workspace)),
        ("robot before calibration", before.as_ref()),
        ("error bounds", uncertainty.as_ref()),
    ]);
    let workspace = calib_gough::workspace::read_workspace(&workspace).map_err(value_error)?;
    let before = before
        .map(|p| read_robot(&p))
        .transpose()
        .map_err(value_error)?;
    let actuator = uncertainty
        .map(|p| read_uncertainty(&p))
        .transpose()
        .map_err(value_error)?
        .map(|u| u.len);
    if !(tolerance > 0.0 && tolerance.is_finite()) {
        return Err(value_error(format!(
            "tolerance: expected a number > 0, found {tolerance}"
        )));
    }
    if !(pose_seconds > 0.0 && pose_seconds.is_finite()) {
        return Err(value_error(format!(
            "pose_seconds: expected a number of seconds > 0, found {pose_seconds}"
        )));
    }
    let settings = AccuracySettings {
        rel_tol: tolerance,
        max_boxes,
        max_set_boxes,
        pose_seconds,
        ..AccuracySettings::default()
    };
    let page = report;
    let report = py.detach(|| {
        let mut problem = AccuracyProblem::over_sets(&file.legs, &sets, &workspace);
        if refine_set {
            problem.refine_sets(REFINED_SET_PIECES);
        }
        accuracy_report(
            &problem,
            before
                .as_deref()
                .map(|b| AccuracyProblem::new(b, &workspace))
                .as_ref(),
            actuator,
            &settings,
            page.is_some(),
        )
    });
    if let Some(path) = &page {
        write_accuracy_page(
            path,
            "accuracy of a calibrated 6-leg parallel robot",
            &report.section(),
            &inputs,
        )?;
    }
    Ok(report.json().to_string())
}

/// The accuracy certificate's inputs that were given: `(role, path)`.
fn accuracy_inputs(files: &[(&'static str, Option<&PathBuf>)]) -> Vec<(&'static str, PathBuf)> {
    files
        .iter()
        .filter_map(|(role, path)| path.map(|p| (*role, p.clone())))
        .collect()
}

/// Writes an accuracy certificate page (`--report` of the `accuracy` commands) to `path`,
/// through a temporary file.
fn write_accuracy_page(
    path: &std::path::Path,
    title: &str,
    section: &calib_pipeline::html::Section,
    inputs: &[(&'static str, PathBuf)],
) -> PyResult<()> {
    let files: Vec<(&str, &std::path::Path)> =
        inputs.iter().map(|(r, p)| (*r, p.as_path())).collect();
    let page = calib_pipeline::html::section_page(title, section, &files).map_err(value_error)?;
    calib_pipeline::write_atomically(path, &page)
        .map_err(|e| value_error(format!("{}: cannot write: {e}", path.display())))
}

/// Brackets the tool-point error of an arm's robot file over a joint box, as `arm accuracy`
/// does (over the file's certified set when it carries one, else over its boxes; with
/// `before`, the uncalibrated robot over its boxes and the improvement as a proved factor);
/// returns the JSON of `arm accuracy --json`. With `task` (a CSV of configurations `q1..qN`,
/// degrees), at those configurations instead, each as given (`arm accuracy --task`).
#[pyfunction]
#[pyo3(signature = (robot, joints=None, before=None, uncertainty=None, tolerance=0.04, max_boxes=20_000, max_set_boxes=300, report=None, task=None))]
#[allow(clippy::too_many_arguments)]
fn arm_accuracy(
    py: Python<'_>,
    robot: PathBuf,
    joints: Option<PathBuf>,
    before: Option<PathBuf>,
    uncertainty: Option<PathBuf>,
    tolerance: f64,
    max_boxes: usize,
    max_set_boxes: usize,
    report: Option<PathBuf>,
    task: Option<PathBuf>,
) -> PyResult<String> {
    use calib_arm::accuracy::{tool_accuracy, tool_accuracy_at, ToolAccuracySettings};
    use calib_arm::joint_space::{read_joint_space, read_task, JointSpace};
    if !(tolerance > 0.0 && tolerance.is_finite()) {
        return Err(value_error(format!(
            "tolerance: expected a number > 0, found {tolerance}"
        )));
    }
    let (arm, set) = calib_arm::files::read_calibrated(&robot).map_err(value_error)?;
    let inputs = accuracy_inputs(&[
        ("robot file", Some(&robot)),
        ("joint space", joints.as_ref()),
        ("task", task.as_ref()),
        ("robot before calibration", before.as_ref()),
        ("error bounds", uncertainty.as_ref()),
    ]);
    if task.is_some() && joints.is_some() {
        return Err(value_error(
            "joints and task: give a joint box or a task's configurations, not both",
        ));
    }
    let n = arm.joints.len();
    let task = task
        .map(|p| read_task(&p, n))
        .transpose()
        .map_err(value_error)?;
    let before = before
        .map(|p| calib_arm::files::read_robot(&p))
        .transpose()
        .map_err(value_error)?;
    let space = match joints {
        Some(p) => read_joint_space(&p, n).map_err(value_error)?,
        None => JointSpace::simulator(n),
    };
    let joint_deg = uncertainty
        .map(|p| calib_arm::files::read_uncertainty(&p))
        .transpose()
        .map_err(value_error)?
        .map_or(0.0, |u| u.joint_deg);
    let settings = ToolAccuracySettings {
        rel_tol: tolerance,
        max_boxes,
        max_set_boxes,
    };
    let page = report;
    let report = py
        .detach(|| match &task {
            Some(list) => tool_accuracy_at(&arm, set, before.as_ref(), list, joint_deg, &settings),
            None => tool_accuracy(&arm, set, before.as_ref(), space, joint_deg, &settings),
        })
        .map_err(value_error)?;
    if let Some(path) = &page {
        write_accuracy_page(
            path,
            "accuracy of a calibrated serial arm",
            &report.section(),
            &inputs,
        )?;
    }
    let units: Vec<calib_arm::params::Unit> = calib_arm::params::names(n)
        .into_iter()
        .map(|(_, u)| u)
        .collect();
    Ok(report.to_json(&calib_arm::certification::names(n), &units))
}

/// The parameter names, in order.
#[pyfunction]
fn parameter_names() -> Vec<&'static str> {
    calib_gough::PARAMETER_NAMES.to_vec()
}

/// The certicalib version.
#[pyfunction]
fn version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(certify_files, m)?)?;
    m.add_function(wrap_pyfunction!(certify_text, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(lsq, m)?)?;
    m.add_function(wrap_pyfunction!(arm_certify_files, m)?)?;
    m.add_function(wrap_pyfunction!(arm_simulate, m)?)?;
    m.add_function(wrap_pyfunction!(arm_import, m)?)?;
    m.add_function(wrap_pyfunction!(arm_export, m)?)?;
    m.add_function(wrap_pyfunction!(arm_register, m)?)?;
    m.add_function(wrap_pyfunction!(arm_error_scale, m)?)?;
    m.add_function(wrap_pyfunction!(error_scale_files, m)?)?;
    m.add_function(wrap_pyfunction!(predict, m)?)?;
    m.add_function(wrap_pyfunction!(arm_predict, m)?)?;
    m.add_function(wrap_pyfunction!(design, m)?)?;
    m.add_function(wrap_pyfunction!(accuracy, m)?)?;
    m.add_function(wrap_pyfunction!(arm_accuracy, m)?)?;
    m.add_function(wrap_pyfunction!(parameter_names, m)?)?;
    m.add_function(wrap_pyfunction!(version, m)?)?;
    Ok(())
}
