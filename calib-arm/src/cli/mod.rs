//! The `arm` subcommands.

mod accuracy;
mod certify;
mod demo;
mod lsq;
mod output;
mod predict;
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
}

/// The data files every command reads.
#[derive(clap::Args, Debug)]
pub struct DataFiles {
    /// The arm: [[joint]] tables (theta_deg, d, a, alpha_deg, beta_deg, radius), [base], [tool].
    // The brackets are TOML table names shown verbatim by --help, not rustdoc links.
    #[allow(rustdoc::broken_intra_doc_links)]
    #[arg(long, value_name = "FILE")]
    robot: PathBuf,
    /// One row per configuration: q1,…,qN (degrees), px,py,pz (mm, tracker frame).
    #[arg(long, value_name = "FILE")]
    measurements: PathBuf,
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
    }
}
