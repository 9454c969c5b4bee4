//! [`GoughError`]: what the Gough library functions report, each message naming the option (as
//! `gough` spells it), the leg or the file concerned.

use std::path::PathBuf;

use calib_core::Status;
use calib_pipeline::{DataError, OptionError};

use crate::workspace::SAMPLE_TRIES;

/// An error of calib-gough's library functions (outside `accuracy`): an option value they do not
/// accept, a leg with no calibrated geometry, a workspace that excludes the poses, a data set
/// that cannot be written, or a malformed input file.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GoughError {
    /// A malformed input file (file, line, field).
    #[error(transparent)]
    Data(#[from] DataError),
    /// An option every robot shares (hull, outliers, error scale) with a value it does not accept.
    #[error(transparent)]
    Option(#[from] OptionError),
    /// `--legs` names a leg the robot does not have (`leg` 1-based).
    #[error("--legs: leg {leg} does not exist (robot.toml has {legs} legs)")]
    NoSuchLeg {
        /// The leg asked for, 1-based.
        leg: usize,
        /// The robot's number of legs.
        legs: usize,
    },
    /// `--pose-seconds` is not a finite number of seconds above 0.
    #[error("--pose-seconds: expected a number of seconds > 0, found {0}")]
    PoseSeconds(f64),
    /// `--pave` is not a relative width in (0, 1).
    #[error("--pave: expected a relative width in (0, 1), found {0}")]
    Pave(f64),
    /// A leg (1-based) proved inconsistent with the data: no calibrated geometry to hand out.
    #[error("leg {0} was proved inconsistent with the data: there is no calibrated geometry to write (re-measure its conflicting configurations, or tolerate outliers)")]
    LegInconsistent(usize),
    /// A leg (1-based) whose certification is undecided: no geometry proved consistent.
    #[error("leg {0}: no geometry was proved consistent with every measurement (the certification is undecided), so none can be handed out as calibrated: allow more boxes or seconds, tolerate outliers, or check the error bounds")]
    LegUndecided(usize),
    /// `--extend` with Rodrigues data and no uncertainty file giving their half-width `q`.
    #[error("--extend: the measurements give Rodrigues vectors (q1,q2,q3); give --uncertainty with their half-width q")]
    ExtendNeedsQ,
    /// `--extend`: a leg (1-based) of the measured data with no certified consistent parameter
    /// vector to simulate the new readings at.
    #[error("--extend: leg {leg} of the measured data has no certified consistent parameter vector ({status:?}); certify the data (gough certify) and resolve that leg first")]
    ExtendLegUnresolved {
        /// The leg, 1-based.
        leg: usize,
        /// Its verdict.
        status: Status,
    },
    /// `gough design --configs 0`.
    #[error("--configs: expected at least 1 configuration")]
    NoConfigurations,
    /// `--candidates` fewer than `--configs`.
    #[error("--candidates {candidates}: expected at least as many candidates as configurations ({configs})")]
    TooFewCandidates {
        /// The candidates asked for.
        candidates: usize,
        /// The configurations asked for.
        configs: usize,
    },
    /// No random pose of the workspace has every leg reading within the stroke.
    #[error("no pose of {SAMPLE_TRIES} random tries in the workspace has every leg reading within the stroke {0:?} (nominal geometry): check `stroke`")]
    StrokeExcludesPoses([f64; 2]),
    /// `gough simulate --configs` below 7.
    #[error("--configs {0}: at least 7 configurations are needed")]
    TooFewConfigurations(usize),
    /// Fewer than 7 poses to simulate at.
    #[error("{0} poses: at least 7 configurations are needed (one per unknown of a leg)")]
    TooFewPoses(usize),
    /// `--noise-scale` is not a finite number >= 0.
    #[error("--noise-scale: expected a finite number >= 0")]
    NoiseScale,
    /// An `--outlier` outside the data set (configuration and leg 0-based here, 1-based in the
    /// message).
    #[error("--outlier {}:{}:{delta}: configuration must be 1..={configs}, leg 1..=6, delta finite", .configuration + 1, .leg + 1)]
    Outlier {
        /// The configuration, 0-based.
        configuration: usize,
        /// The leg, 0-based.
        leg: usize,
        /// The change of the reading (cm).
        delta: f64,
        /// The number of configurations.
        configs: usize,
    },
    /// A directory that cannot be created.
    #[error("{}: cannot create: {source}", .path.display())]
    CreateDir {
        /// The directory.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A file that cannot be written.
    #[error("{}: cannot write: {source}", .path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
}
