//! The `arm` subcommands.

mod accuracy;
mod certify;
mod demo;
mod export;
mod import;
mod lsq;
mod output;
mod predict;
mod register;
mod simulate;

use clap::{Parser, Subcommand};
use std::path::PathBuf;

/// Certified calibration of serial arms tracked by a laser tracker: for joint readings and
/// tracked points known within error bounds, boxes of kinematic parameters that provably contain
/// every parameter vector consistent with the data, or a proof that the data are inconsistent.
///
/// Model: p = T_base · A_1(q_1) ⋯ A_N(q_N) · t, with A_i(q) = Rz(theta_i + q) Tz(d_i) Tx(a_i)
/// Rx(alpha_i) Ry(beta_i) (Denavit–Hartenberg plus Hayati's beta). Units: mm and degrees.
#[derive(Parser, Debug)]
#[command(name = "arm", version, propagate_version = true)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// The main job on the embedded default (no files needed): simulate the built-in 6-axis arm
    /// (50 configurations), check identifiability, certify its 27 free parameters, compare with
    /// least squares and with the simulated truth.
    ///
    /// Example:
    ///   arm demo --out results/
    ///
    /// --out writes the simulated data set and report.json there.
    #[command(verbatim_doc_comment)]
    Demo(demo::Args),
    /// Certify an arm: the outer box, inner bounds, verdict, identifiability, outliers.
    ///
    /// Example:
    ///   arm certify --robot robot.toml --measurements measurements.csv \
    ///               --uncertainty uncertainty.toml --json report.json \
    ///               --report certificate.html
    ///
    /// --report writes the calibration certificate: one self-contained HTML page (verdict and
    /// evidence, identifiability, every free parameter's boxes in a table and a figure, inputs
    /// with SHA-256, settings) to archive or print. --max-outliers auto finds the smallest number
    /// of bad configurations that explains the data.
    ///
    /// Carrying a calibration over (the tracker moved, a new cell, a month later): when --robot
    /// carries a certified set (a calibrated file's `[certified_set]`, or the `[carried_set]` that
    /// `arm register --robot calibrated.toml` copies into the new cell's file), its rows join the
    /// new ones in one certification, each series with its own base and tool point, the joints'
    /// parameters shared: the new rows narrow the earlier set, or prove the two inconsistent and
    /// name the rows (earlier ones numbered after the new).
    ///
    /// What the boxes mean, per parameter:
    ///   outer  every parameter vector that fits all configurations (one reading of each within
    ///          its error bounds making all three coordinates agree) lies in this box: a proof.
    ///   inner  spanned by parameter vectors each proved to fit every configuration: the true
    ///          range of each parameter covers at least this box.
    ///   ratio  outer width / inner width: the true range lies between the two.
    ///
    /// Exit code: 0 when certified (consistent or undecided), 2 when the data are proved
    /// inconsistent with the model and the error bounds, 1 on errors.
    #[command(verbatim_doc_comment)]
    Certify(certify::Args),
    /// Levenberg–Marquardt least squares from the nominal geometry (the classical calibration),
    /// with residual statistics.
    ///
    /// Example:
    ///   arm lsq --robot robot.toml --measurements measurements.csv
    #[command(verbatim_doc_comment)]
    Lsq(lsq::Args),
    /// Write a simulated data set (robot.toml, measurements.csv, uncertainty.toml, truth.json)
    /// for the built-in arm or a given robot.toml.
    ///
    /// Example:
    ///   arm simulate --configs 50 --seed 7 --out data/ --outlier 12:0.5
    #[command(verbatim_doc_comment)]
    Simulate(simulate::Args),
    /// The accuracy certificate: how far the tool point can be from where the controller
    /// computes it, anywhere in a joint-space box, for every geometry the robot file's box allows
    /// and every joint error within the bound. A bracket: an upper bound proved over the whole
    /// box and a lower bound attained by an explicit configuration and geometry.
    ///
    /// Example:
    ///   arm certify --robot robot.toml --measurements measurements.csv \
    ///               --uncertainty uncertainty.toml --write-calibrated calibrated.toml
    ///   arm accuracy --robot calibrated.toml --before robot.toml \
    ///                --joints joints.toml --uncertainty uncertainty.toml --json accuracy.json
    ///
    /// joints.toml: q1 = [lo, hi], q2 = [lo, hi], … (degrees). The bracket tightens as the joint
    /// box shrinks: over a whole ±170° space the upper bound may stay several times the lower;
    /// over the cell a task uses (±10° of every joint) it converges within 1.05 in about half a
    /// minute (see --max-boxes).
    ///
    /// At the configurations the robot works at, each bounded as given:
    ///   arm accuracy --robot calibrated.toml --before robot.toml \
    ///                --measurements held_out.csv --uncertainty uncertainty.toml
    /// (--rows and the column options as for certify; or --task task.csv, columns q1..qN in
    /// degrees). On the real UR10's 1,435 held-out rows: at most 5.3 mm after calibration, at
    /// least 21.2 mm before.
    #[command(verbatim_doc_comment)]
    Accuracy(accuracy::Args),
    /// Predict the tracked point at joint readings, over every parameter vector the calibration
    /// allows: per configuration, the certified range of each coordinate and the range a
    /// measurement may show (with the error bounds). With --measurements, every measured point
    /// outside its prediction is named: the model or the error bounds are wrong there. This is
    /// how a calibration is checked on held-out data.
    ///
    /// Examples:
    ///   arm predict --robot calibrated.toml --joints joints.csv \
    ///               --uncertainty uncertainty.toml --out predictions.csv
    ///   arm predict --robot calibrated.toml --measurements held_out.csv \
    ///               --uncertainty uncertainty.toml --json check.json
    ///
    /// Exit code: 0, or 2 when a measured point lies outside its prediction; 1 on errors.
    #[command(verbatim_doc_comment)]
    Predict(predict::Args),
    /// Import a vendor's kinematics (UR's YAML or a URDF) into robot.toml: the exact
    /// Denavit-Hartenberg/Hayati parameters (the forward kinematics agree to rounding), which
    /// are free (the identifiable set for a tracked point), and priors around them.
    ///
    /// Examples:
    ///   arm import --ur-yaml default_kinematics.yaml --out nominal.toml
    ///   arm import --urdf ur10.urdf --base-link base_link --tip-link wrist_3_link \
    ///              --angle-radius 0.1 --length-radius 2 --out nominal.toml
    ///
    /// Conventions: each joint turns about its frame's z axis from the vendor's zero; axes
    /// within 45° of parallel get Hayati's beta (d fixed at 0), others standard DH (beta fixed);
    /// theta1, d1 and the last joint stay fixed (the base and the tool point absorb them).
    #[command(verbatim_doc_comment)]
    Import(import::Args),
    /// Export a robot file (e.g. the calibrated one) as UR's kinematics YAML, for the UR
    /// driver, or as a URDF.
    ///
    /// Examples:
    ///   arm export --robot calibrated.toml --ur-yaml calibrated_kinematics.yaml
    ///   arm export --robot calibrated.toml --urdf calibrated.urdf
    ///
    /// The joints' frames are placed at the feet of their Denavit-Hartenberg normals (for UR's
    /// nominal geometry, exactly UR's frames); the tracker-to-base transform is not exported.
    #[command(verbatim_doc_comment)]
    Export(export::Args),
    /// Find where the robot stands in the tracker's frame (any rotation, any distance) and the
    /// tracked point on the flange, from scratch: a closed-form start (alternating best rigid
    /// fits and linear least squares), then least squares of the nine base and tool parameters
    /// with the nominal joints. Writes the robot file with them and their priors.
    ///
    /// Base and tool can be told apart only when the flange's orientation changes over the
    /// rows: at one orientation the base's position takes up the tool point, which the fit
    /// would then send anywhere (a metre away) for the same residuals. When the orientations
    /// spread less than 0.1° across some direction of the tool (one orientation, turns about a
    /// single axis, or too few rows), register says so, keeps the --robot file's tool point,
    /// fixed (--tool-radius 0 unless given), and fits the base alone; --tool fit fits it anyway,
    /// --tool keep always keeps it.
    ///
    /// From a calibrated file (--robot with a `[certified_set]`) the written file carries that set
    /// on as `[carried_set]`, in its own tracker frame: `arm certify` joins its rows to the new
    /// cell's; `predict` and `accuracy` do not read it.
    ///
    /// Example (the real UR10 data of the tutorial, radians and metres as exported):
    ///   arm register --robot nominal.toml --measurements series_b.csv \
    ///                --joint-columns shoulder_pan_joint,shoulder_lift_joint,elbow_joint,\
    ///                                wrist_1_joint,wrist_2_joint,wrist_3_joint \
    ///                --joint-unit rad --point-columns measurement_x,measurement_y,measurement_z \
    ///                --rows 1-60 --out robot.toml
    #[command(verbatim_doc_comment)]
    Register(register::Args),
}

/// The data files every command reads.
#[derive(clap::Args, Debug)]
pub struct DataFiles {
    /// The arm: [[joint]] tables (theta_deg, d, a, alpha_deg, beta_deg, radius), [base], [tool].
    // The brackets are TOML table names shown verbatim by --help, not rustdoc links.
    #[allow(rustdoc::broken_intra_doc_links)]
    #[arg(long, value_name = "FILE")]
    robot: PathBuf,
    /// One row per configuration: by default columns q1,…,qN (degrees), px,py,pz (mm, tracker
    /// frame); a tracker's own export with --joint-columns, --point-columns and the units.
    #[arg(long, value_name = "FILE")]
    measurements: PathBuf,
    #[command(flatten)]
    columns: ColumnArgs,
}

/// Where the measurements are in the file and in which units (a tracker's export as it comes:
/// `,`, `;` or tab separated, decimal points or commas, detected).
#[derive(clap::Args, Debug, Clone)]
pub struct ColumnArgs {
    /// The joint readings' columns, base to flange, comma-separated [default: q1,…,qN]
    #[arg(long, value_name = "NAMES", value_delimiter = ',')]
    joint_columns: Option<Vec<String>>,
    /// The tracked point's x,y,z columns [default: px,py,pz]
    #[arg(long, value_name = "X,Y,Z", value_delimiter = ',', num_args = 1)]
    point_columns: Option<Vec<String>>,
    /// The joint readings' unit.
    #[arg(long, value_enum, value_name = "UNIT", default_value_t = ColumnArgs::JOINT_UNIT)]
    joint_unit: calib_arm::tracker_file::JointUnit,
    /// The tracked point's unit.
    #[arg(long, value_enum, value_name = "UNIT", default_value_t = ColumnArgs::LENGTH_UNIT)]
    length_unit: calib_arm::tracker_file::LengthUnit,
    /// Use only these data rows (1-based, the header is not a row): A-B, A- or A. E.g. 1-60 to
    /// calibrate on the first 60 configurations, 61- to check the rest with `predict`.
    #[arg(long, value_name = "A-B")]
    rows: Option<calib_arm::tracker_file::RowRange>,
    /// The measured frame's orientation, three columns (a 6-DoF probe such as Leica's T-Mac):
    /// six equations per configuration instead of three, with the tool frame's rotation
    /// (tool_rx, tool_ry, tool_rz: [tool] rpy_deg and rotation_radius in the robot file) among
    /// the parameters and orient_deg in the uncertainty file. Used by `certify` and `register`.
    // The brackets are a TOML table name shown verbatim by --help, not a rustdoc link.
    #[allow(rustdoc::broken_intra_doc_links)]
    #[arg(long, value_name = "A,B,C", value_delimiter = ',', num_args = 1)]
    orientation_columns: Option<Vec<String>>,
    /// How the orientation columns write it: intrinsic Euler angles XYZ, R = Rx(a) Ry(b) Rz(c),
    /// in degrees (the T-Mac's export) or radians.
    #[arg(
        long,
        value_enum,
        value_name = "CONVENTION",
        default_value_t = ColumnArgs::ORIENTATION_CONVENTION
    )]
    orientation_convention: calib_arm::tracker_file::OrientationConvention,
}

impl ColumnArgs {
    /// `--joint-unit`'s default.
    const JOINT_UNIT: calib_arm::tracker_file::JointUnit = calib_arm::tracker_file::JointUnit::Deg;
    /// `--length-unit`'s default.
    const LENGTH_UNIT: calib_arm::tracker_file::LengthUnit =
        calib_arm::tracker_file::LengthUnit::Mm;
    /// `--orientation-convention`'s default.
    const ORIENTATION_CONVENTION: calib_arm::tracker_file::OrientationConvention =
        calib_arm::tracker_file::OrientationConvention::EulerXyzDeg;

    /// The layout for an arm with `joints` joints.
    fn columns(
        &self,
        joints: usize,
    ) -> Result<calib_arm::tracker_file::MeasurementColumns, String> {
        let mut c = calib_arm::tracker_file::MeasurementColumns::with_names(
            joints,
            self.joint_columns.clone(),
            self.point_columns.clone(),
        )
        .map_err(|e| format!("--point-columns: {e}"))?;
        c.joint_unit = self.joint_unit;
        c.length_unit = self.length_unit;
        c.rows = self.rows;
        if let Some(o) = &self.orientation_columns {
            let names = <[String; 3]>::try_from(o.clone()).map_err(|o| {
                format!(
                    "--orientation-columns: expected three names a,b,c, found {}",
                    o.len()
                )
            })?;
            c.orientation = Some((names, self.orientation_convention));
        }
        Ok(c)
    }

    /// The first column option given a value other than its default (`--rows`, say), for a
    /// command that reads no measurement file this time and must not ignore it silently.
    fn first_given(&self) -> Option<&'static str> {
        [
            (self.joint_columns.is_some(), "--joint-columns"),
            (self.point_columns.is_some(), "--point-columns"),
            (self.joint_unit != Self::JOINT_UNIT, "--joint-unit"),
            (self.length_unit != Self::LENGTH_UNIT, "--length-unit"),
            (self.rows.is_some(), "--rows"),
            (self.orientation_columns.is_some(), "--orientation-columns"),
            (
                self.orientation_convention != Self::ORIENTATION_CONVENTION,
                "--orientation-convention",
            ),
        ]
        .into_iter()
        .find_map(|(given, flag)| given.then_some(flag))
    }

    /// An error for a command (`arm COMMAND`) that uses positions only when orientation columns
    /// are given.
    fn positions_only(&self, command: &str) -> Result<(), String> {
        match &self.orientation_columns {
            Some(_) => Err(format!(
                "--orientation-columns: `arm {command}` uses the tracked positions only; \
                 orientations are used by `arm certify`, `arm register` and `arm predict \
                 --measurements`"
            )),
            None => Ok(()),
        }
    }

    /// Reads `file` (whose text is `text`) for an arm with `joints` joints, printing the file's
    /// notes on standard error.
    fn parse(
        &self,
        file: &std::path::Path,
        text: &str,
        joints: usize,
    ) -> Result<calib_arm::files::Measurements, Box<dyn std::error::Error>> {
        let m = calib_arm::files::parse_tracker_measurements(
            file,
            text,
            joints,
            &self.columns(joints)?,
        )?;
        for note in &m.notes {
            eprintln!("note: {note}");
        }
        Ok(m)
    }

    /// [`ColumnArgs::parse`] reading the file.
    fn read(
        &self,
        file: &std::path::Path,
        joints: usize,
    ) -> Result<calib_arm::files::Measurements, Box<dyn std::error::Error>> {
        self.parse(file, &calib_pipeline::read_text(file)?, joints)
    }
}

/// Runs a subcommand; the exit code on success.
pub fn run(cli: Cli) -> Result<i32, Box<dyn std::error::Error>> {
    match cli.command {
        Command::Demo(a) => demo::run(a),
        Command::Certify(a) => certify::run(a),
        Command::Lsq(a) => lsq::run(a),
        Command::Simulate(a) => simulate::run(a),
        Command::Accuracy(a) => accuracy::run(a),
        Command::Predict(a) => predict::run(a),
        Command::Import(a) => import::run(a),
        Command::Export(a) => export::run(a),
        Command::Register(a) => register::run(a),
    }
}
