//! The `gough` subcommands.

mod accuracy;
mod certify;
mod design;
mod lsq;
mod predict;
mod reproduce;
mod simulate;

use clap::{Parser, Subcommand};
use std::path::PathBuf;

/// Certified calibration of Gough (Stewart) platforms: for measurements known within error bounds,
/// boxes of leg parameters that provably contain every parameter vector consistent with the data,
/// or a proof that the data are inconsistent (Daney, Papegay & Neumaier, ICRA 2004).
///
/// Units: cm and degrees. Parameters per leg: a (base point), b (platform point), l (offset).
#[derive(Parser, Debug)]
#[command(name = "gough", version, propagate_version = true)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Certify every leg: the tight outer box, inner bounds, verdict, evidence, timing.
    ///
    /// Example:
    ///   gough certify --robot robot.toml --measurements measurements.csv \
    ///                 --uncertainty uncertainty.toml --json report.json \
    ///                 --report certificate.html
    ///
    /// --report writes the calibration certificate: one self-contained HTML page (summary in
    /// words, inputs with SHA-256, settings, per-leg tables and figures) to archive or print.
    ///
    /// --robot may be a calibrated robot file (--write-calibrated): each leg is then certified
    /// against the new measurements and the rows its stored set was certified against, from
    /// its box cut to that set (the robot measured again, same frames); the output says how many
    /// rows were carried over, names a stored row by its row in the file, and --write-calibrated
    /// stores both series.
    ///
    /// What the boxes mean, per leg parameter (a = base point, b = platform point, l = offset):
    ///   outer  every parameter vector that fits all measurements within their error bounds lies
    ///          in this box: a proof, with rigorous rounding.
    ///   inner  spanned by parameter vectors each proved to fit all measurements: the true range
    ///          of every parameter covers at least this box.
    ///   ratio  outer width / inner width: the true range lies between the two, so 1.05 means
    ///          the outer box overstates it by at most 5%. By default the refinement stops at 1.05
    ///          (--tolerance 0.05) or when its budget runs out.
    ///   x1     the paper's fixed point (one Newton/LP contraction), kept for comparison;
    ///          --fast reports only x1 (milliseconds per leg) as the outer box.
    ///   x2     the paper's 128-box bisection sweep (with --sweep), for comparison.
    ///
    /// Exit code: 0 when every leg is certified (consistent or undecided), 2 when a leg is proved
    /// empty (the data are inconsistent with the model and the error bounds), 1 on errors.
    #[command(verbatim_doc_comment)]
    Certify(certify::Args),
    /// Levenberg–Marquardt least squares per leg from the nominal geometry, with residual
    /// statistics (the classical calibration the paper compares against).
    ///
    /// Example:
    ///   gough lsq --robot robot.toml --measurements measurements.csv
    #[command(verbatim_doc_comment)]
    Lsq(lsq::Args),
    /// Write a simulated data set (robot.toml, measurements.csv, uncertainty.toml, truth.json) for
    /// the built-in hexapod, whose leg 1 is the paper's Table I.
    ///
    /// Examples:
    ///   gough simulate --configs 21 --seed 7 --out data/ --outlier 5:2:0.1
    ///   gough simulate --poses poses.csv --seed 7 --out data/
    ///
    /// --poses measures at the poses of a CSV (header px,py,pz,ax,ay,az,angle_deg) instead of
    /// random ones, with the same noise model: a measurement plan can be tried before the robot
    /// is measured.
    #[command(verbatim_doc_comment)]
    Simulate(simulate::Args),
    /// How far the leg lengths the controller commands can be from those the real robot needs,
    /// anywhere in the workspace, for every geometry the (calibrated) robot file's box allows:
    /// per leg, a bracket [lower, upper] — upper proved over the whole workspace, lower attained
    /// by an explicit pose and geometry — and, with --before, the improvement calibration
    /// brought as a proved factor.
    ///
    /// Example:
    ///   gough certify ... --write-calibrated calibrated.toml
    ///   gough accuracy --robot calibrated.toml --workspace workspace.toml \
    ///                  --before robot.toml --uncertainty uncertainty.toml --json accuracy.json
    ///
    /// The controller uses the robot file's values; the real robot has some geometry in its box
    /// (value ± radius). The platform's position and orientation errors are bracketed too: a
    /// lower bound attained by an instance whose reached pose is proved (interval Newton along
    /// the path from the commanded pose), and an upper bound proved over the whole workspace
    /// where the reached pose can be enclosed — where it cannot (a singular pose, or errors so
    /// large that the legs' directions change across them), or when --pose-seconds ends first,
    /// no upper bound is printed: the output names the poses, says which of the two happened
    /// and how much of the workspace was settled.
    #[command(verbatim_doc_comment)]
    Accuracy(accuracy::Args),
    /// Predict the leg readings at poses, over every geometry the calibration allows: per pose
    /// and leg, the certified range of the reading and the range a measurement may show (with
    /// the error bounds). With --measurements, every reading outside its prediction is named:
    /// the model or the error bounds are wrong there. This is how a calibration is checked on
    /// held-out data.
    ///
    /// Examples:
    ///   gough predict --robot calibrated.toml --poses poses.csv \
    ///                 --uncertainty uncertainty.toml --out predictions.csv
    ///   gough predict --robot calibrated.toml --measurements held_out.csv \
    ///                 --uncertainty uncertainty.toml --json check.json
    ///
    /// Exit code: 0, or 2 when a measured reading lies outside its prediction; 1 on errors.
    #[command(verbatim_doc_comment)]
    Predict(predict::Args),
    /// Choose the configurations to measure: K poses of the workspace that determine every leg
    /// parameter best, with the certified widths they are predicted to give next to a random
    /// design of the same size and the classical D-optimal one.
    ///
    /// Examples:
    ///   gough design --configs 21 --out poses.csv
    ///   gough design --robot robot.toml --uncertainty uncertainty.toml \
    ///                --workspace workspace.toml --configs 21 --out poses.csv
    ///   gough design --robot robot.toml --extend measurements.csv --configs 5 --out next.csv
    ///
    /// How: 2000 candidate poses are drawn from the workspace (half of them on its boundary);
    /// each adds one row per leg to the identification Jacobian at the nominal geometry. The
    /// `certified` criterion picks, one pose at a time, the pose that most shrinks the
    /// first-order certified box (the paper's LP step on the linearised problem: the geometric
    /// mean of the widths); `d-optimal` maximises the product of the singular values instead.
    /// The prediction printed is not first order: it is the tight certified hull of simulated
    /// data measured at each design (the nominal geometry as the truth, noise within the error
    /// bounds). Try a design end to end with `gough simulate --poses poses.csv`.
    ///
    /// --extend: the configurations of measurements.csv are kept, and the next ones are chosen
    /// to shrink the certified box of all of them (new readings are predicted at a certified
    /// consistent parameter vector of the measured data).
    #[command(verbatim_doc_comment)]
    Design(design::Args),
    /// The paper's Section V experiment on an embedded default (no files): exact-data check, then
    /// x0, x1, x2 (sweep) and xs (hull of Monte-Carlo least-squares solutions) next to the paper's
    /// Tables II–IV, and the tight certified hull (outer, inner) of this run.
    ///
    /// Example:
    ///   gough reproduce --samples 1000 --out results/
    ///
    /// --out writes results/report.html (the certificate of the run, with the paper's tables and
    /// Figs. 3-5) and the figures as SVG files.
    #[command(verbatim_doc_comment)]
    Reproduce(reproduce::Args),
}

/// Runs a subcommand; the exit code on success.
pub fn run(cli: Cli) -> Result<i32, Box<dyn std::error::Error>> {
    match cli.command {
        Command::Certify(a) => certify::run(a),
        Command::Lsq(a) => lsq::run(a),
        Command::Simulate(a) => simulate::run(a),
        Command::Design(a) => design::run(a),
        Command::Accuracy(a) => accuracy::run(a),
        Command::Predict(a) => predict::run(a),
        Command::Reproduce(a) => reproduce::run(a),
    }
}

/// The data files every command that reads data takes.
#[derive(clap::Args, Debug)]
pub struct DataFiles {
    /// Nominal geometry: one `[[leg]]` table per leg with a, b, l and radius.
    #[arg(long, value_name = "FILE")]
    pub robot: PathBuf,
    /// Measured configurations: px,py,pz,ax,ay,az,angle_deg,L1..L6 (or px,py,pz,q1,q2,q3,L1..L6).
    #[arg(long, value_name = "FILE")]
    pub measurements: PathBuf,
}
