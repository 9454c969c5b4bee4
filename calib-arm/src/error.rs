//! [`ArmError`]: what the arm library functions report, each message naming the option (as `arm`
//! spells it), the file or the parameter concerned.

use std::path::PathBuf;

use calib_pipeline::{DataError, OptionError};

use crate::certification::MAX_JOINTS;
use crate::files::JOINTS;

/// An error of calib-arm's library functions: a malformed input file, an
/// option value they do not accept, an arm or data set the model does not take, a joint space or
/// joint error the accuracy problem does not take, an empty certified set, inputs missing for
/// 6-DoF measurements, a certification with no calibrated geometry to hand out, a registration
/// or a vendor chain that cannot be made, an option's text that names none of its values, or a
/// file (a report, a certificate page) that cannot be written.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ArmError {
    /// A malformed input file (file, line, field).
    #[error(transparent)]
    Data(#[from] DataError),
    /// An option every robot shares (hull, outliers) with a value it does not accept.
    #[error(transparent)]
    Option(#[from] OptionError),
    /// An arm with a number of joints the padded model does not take.
    #[error("arms with 3 to {MAX_JOINTS} joints are supported, not {0}")]
    Joints(usize),
    /// An arm whose nominal tracked point cannot be computed (more joints than the model).
    #[error("arms with 3 to {MAX_JOINTS} joints are supported")]
    UnsupportedArm,
    /// A joint space with another number of ranges than the arm has joints.
    #[error("the joint space has {ranges} ranges; the arm has {joints} joints")]
    JointSpaceRanges {
        /// The joint space's ranges.
        ranges: usize,
        /// The arm's joints.
        joints: usize,
    },
    /// A joint error (degrees) that is not a finite value `>= 0`.
    #[error("joint error {0}: expected a finite value >= 0")]
    JointError(f64),
    /// A task's configuration with another number of joints than the arm, or a joint that is not
    /// a finite number of degrees.
    #[error("the task's configuration {index} has {found} finite joints; the arm has {joints}")]
    TaskConfiguration {
        /// The configuration (1-based).
        index: usize,
        /// Its finite joints.
        found: usize,
        /// The arm's joints.
        joints: usize,
    },
    /// A task without configurations.
    #[error("the task has no configurations")]
    EmptyTask,
    /// An accuracy problem over a certified set that is empty.
    #[error("the certified set is empty")]
    EmptySet,
    /// A robot file whose joint parameters' box and carried certified set (`[certified_set]` or
    /// `[carried_set]`) share no vector: the file was edited, or its box and set come from
    /// different calibrations.
    #[error(
        "the robot file's joint parameters lie outside its certified set's box: was the file \
         edited? Recalibrate, or re-register from the calibrated file (`arm register --robot`)"
    )]
    CarriedSetOutsidePrior,
    /// A certified set carried over to a 6-DoF certification (only point measurements take one).
    #[error(
        "carrying a certified set over to 6-DoF measurements is not supported: certify without \
         --orientation-columns, or from a robot file without a certified set"
    )]
    CarryWithPose,
    /// A file that cannot be written (why: the I/O error's message, as `ArmError` is `Clone`
    /// and `PartialEq` and `std::io::Error` is neither).
    #[error("{}: cannot write: {reason}", .path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        reason: String,
    },
    /// A certificate page that cannot be written (why, as for [`ArmError::Write`]).
    #[error("{}: cannot write the certificate: {reason}", .path.display())]
    WriteCertificate {
        /// The page's file.
        path: PathBuf,
        /// Why.
        reason: String,
    },
    /// A report whose JSON text cannot be read back to merge entries into (why).
    #[error("the JSON report: {0}")]
    JsonReport(String),
    /// A configuration with another number of joint readings than the arm has joints.
    #[error("a configuration has {readings} joint readings; the arm has {joints} joints")]
    JointReadings {
        /// The configuration's joint readings.
        readings: usize,
        /// The arm's joints.
        joints: usize,
    },
    /// A configuration with more joint readings than the padded model has joints.
    #[error("a configuration has more joint readings than the model")]
    TooManyJointReadings,
    /// A least-squares fit was asked for and none was made.
    #[error("no fit was made")]
    NoFit,
    /// `--scale-bounds orient_deg` on measurements without orientations.
    #[error("--scale-bounds orient_deg scales the orientations' bound: it needs 6-DoF data (--orientation-columns)")]
    OrientScaleNeedsPose,
    /// 6-DoF measurements on an arm without the tool frame's rotation.
    #[error("6-DoF measurements need the measured frame's rotation on the flange: [tool] rpy_deg and rotation_radius in the robot file (`arm register` with --orientation-columns finds them)")]
    PoseNeedsToolRotation,
    /// 6-DoF measurements with error bounds that do not bound the orientations.
    #[error("6-DoF measurements need the orientation's error bound: orient_deg (degrees, the half-width of each measured Euler angle) in the uncertainty file")]
    PoseNeedsOrientBound,
    /// 6-DoF measurements with a robot file without the tool frame's rotation.
    #[error("{}: [tool] has no rpy_deg and rotation_radius: 6-DoF measurements need the measured frame's rotation on the flange (`arm register --orientation-columns …` finds it)", .0.display())]
    RobotLacksToolRotation(
        /// The robot file.
        PathBuf,
    ),
    /// Measured orientations checked against a robot file without the tool frame's rotation
    /// (`arm predict --orientation-columns` on a positions-only calibration).
    #[error("{}: [tool] has no rpy_deg: checking measured orientations needs the tool frame's rotation (a 6-DoF calibration: `arm certify --orientation-columns … --write-calibrated`)", .0.display())]
    PredictionLacksToolRotation(
        /// The robot file.
        PathBuf,
    ),
    /// 6-DoF measurements with an uncertainty file without the orientations' bound.
    #[error("{}: no orient_deg: 6-DoF measurements need the orientation's error bound (degrees, the half-width of each measured Euler angle)", .0.display())]
    UncertaintyLacksOrientBound(
        /// The uncertainty file.
        PathBuf,
    ),
    /// A calibrated arm asked of data proved inconsistent: there is no certified box.
    #[error("the data were proved inconsistent with the model and the error bounds: there is no calibrated geometry to write (re-measure the conflicting configurations, or tolerate outliers)")]
    Inconsistent,
    /// A calibrated arm asked of an undecided certification: no parameter vector proved
    /// consistent.
    #[error("no parameter vector was proved consistent with every measurement (the certification is undecided), so none can be handed out as calibrated: check the error bounds (`--error-scale auto`), allow more time (--hull), or tolerate outliers")]
    Undecided,
    /// A certified box with another number of parameters than the arm has.
    #[error("the certified box has {found} parameters; the arm has {expected}")]
    CertifiedBoxSize {
        /// The certified box's parameters.
        found: usize,
        /// The arm's parameters.
        expected: usize,
    },
    /// A 6-DoF certified box with another number of parameters than the arm (tool rotation
    /// included) has.
    #[error("the certified box has {found} parameters; the arm measured in 6-DoF has {expected}")]
    PoseCertifiedBoxSize {
        /// The certified box's parameters.
        found: usize,
        /// The arm's parameters, the tool rotation's included.
        expected: usize,
    },
    /// A 6-DoF calibrated arm of a robot file without the tool frame's rotation.
    #[error(
        "a 6-DoF calibration needs the tool frame's rotation in the robot file ([tool] rpy_deg)"
    )]
    CalibrationNeedsToolRotation,
    /// Fewer than 3 configurations to register on.
    #[error("registration needs at least 3 configurations, found {0}")]
    TooFewConfigurations(usize),
    /// A registration prior half-width that is not a finite number `>= 0`.
    #[error("{prior} {value}: expected a finite half-width >= 0")]
    Prior {
        /// Which prior (`base position prior`, `base rotation prior`, `tool prior`, `tool
        /// rotation prior`).
        prior: &'static str,
        /// The value given.
        value: f64,
    },
    /// Configurations whose tracked points are collinear: no base frame to register.
    #[error("the configurations' points are collinear: registration needs a spread")]
    Collinear,
    /// No measured orientation to register the tool frame's rotation from.
    #[error("no orientation to register the tool frame from")]
    NoOrientation,
    /// A vendor link that is not a Denavit–Hartenberg or Hayati link (how far off, mm or
    /// radians).
    #[error("a link could not be split into Denavit-Hartenberg/Hayati parameters (off by {0:e})")]
    Split(f64),
    /// A vendor chain with a number of joints the model does not take.
    #[error("a chain of {0} joints; arms with {start} to {end} joints are supported", start = JOINTS.start(), end = JOINTS.end())]
    ChainJoints(usize),
    /// A vendor chain whose flange frame is not its last joint's frame.
    #[error("the flange frame is not the last joint's frame")]
    FlangeNotLastFrame,
    /// A vendor chain holding a NaN or an infinity.
    #[error("the chain holds a non-finite number (NaN or infinity)")]
    NonFiniteChain,
    /// An arm (its number of joints) whose last joint's `a, alpha, beta` are not all 0: no
    /// vendor chain has its flange elsewhere than the last joint's frame.
    #[error("a{0}, alpha{0}, beta{0} must be 0 to write a vendor chain (its flange is the last joint's frame)")]
    FlangeOffset(usize),
    /// A UR kinematics file asked of an arm (its number of joints) without 6 joints.
    #[error("a UR kinematics file has 6 joints; this arm has {0}")]
    UrJoints(usize),
    /// Point columns that are not three names (how many were given).
    #[error("expected three names x,y,z, found {0}")]
    PointColumns(usize),
    /// `--rows` text that is not `A-B`, `A-` or `A` (holds the text).
    #[error("`{0}`: expected rows as A-B, A- or A (1-based, e.g. 1-60 or 61-)")]
    Rows(String),
    /// `--rows` whose last row comes before its first (holds the text).
    #[error("`{0}`: the last row comes before the first")]
    RowsReversed(String),
    /// A joint unit other than `deg` or `rad` (holds the text).
    #[error("`deg` or `rad`, not `{0}`")]
    JointUnit(String),
    /// A length unit other than `mm` or `m` (holds the text).
    #[error("`mm` or `m`, not `{0}`")]
    LengthUnit(String),
    /// An orientation convention other than `euler-xyz-deg` or `euler-xyz-rad` (holds the
    /// text).
    #[error("`euler-xyz-deg` or `euler-xyz-rad`, not `{0}`")]
    OrientationConvention(String),
}
