//! The tests of `calib_arm::ArmError`: its messages, byte for byte (the typed errors replaced
//! strings formatted at the call sites, and the CLI and the Python package print them).

use calib_arm::ArmError;
use calib_pipeline::{DataError, OptionError};
use std::path::{Path, PathBuf};

#[test]
fn messages_are_the_ones_the_call_sites_formatted() {
    let cases: Vec<(ArmError, &str)> = vec![
        (
            DataError::new(Path::new("m.csv"), Some(3), Some("q1"), "bad").into(),
            "m.csv, line 3, field `q1`: bad",
        ),
        (
            OptionError::Tolerance(0.0).into(),
            "--tolerance: expected a positive number, found 0",
        ),
        (
            ArmError::Joints(8),
            "arms with 3 to 7 joints are supported, not 8",
        ),
        (ArmError::UnsupportedArm, "arms with 3 to 7 joints are supported"),
        (
            ArmError::JointReadings {
                readings: 5,
                joints: 6,
            },
            "a configuration has 5 joint readings; the arm has 6 joints",
        ),
        (
            ArmError::TooManyJointReadings,
            "a configuration has more joint readings than the model",
        ),
        (ArmError::NoFit, "no fit was made"),
        (
            ArmError::OrientScaleNeedsPose,
            "--scale-bounds orient_deg scales the orientations' bound: it needs 6-DoF data (--orientation-columns)",
        ),
        (
            ArmError::PoseNeedsToolRotation,
            "6-DoF measurements need the measured frame's rotation on the flange: [tool] rpy_deg and rotation_radius in the robot file (`arm register` with --orientation-columns finds them)",
        ),
        (
            ArmError::PoseNeedsOrientBound,
            "6-DoF measurements need the orientation's error bound: orient_deg (degrees, the half-width of each measured Euler angle) in the uncertainty file",
        ),
        (
            ArmError::RobotLacksToolRotation(PathBuf::from("robot.toml")),
            "robot.toml: [tool] has no rpy_deg and rotation_radius: 6-DoF measurements need the measured frame's rotation on the flange (`arm register --orientation-columns …` finds it)",
        ),
        (
            ArmError::UncertaintyLacksOrientBound(PathBuf::from("u.toml")),
            "u.toml: no orient_deg: 6-DoF measurements need the orientation's error bound (degrees, the half-width of each measured Euler angle)",
        ),
        (
            ArmError::Inconsistent,
            "the data were proved inconsistent with the model and the error bounds: there is no calibrated geometry to write (re-measure the conflicting configurations, or tolerate outliers)",
        ),
        (
            ArmError::Undecided,
            "no parameter vector was proved consistent with every measurement (the certification is undecided), so none can be handed out as calibrated: check the error bounds (`--error-scale auto`), allow more time (--hull), or tolerate outliers",
        ),
        (
            ArmError::CertifiedBoxSize {
                found: 44,
                expected: 39,
            },
            "the certified box has 44 parameters; the arm has 39",
        ),
        (
            ArmError::PoseCertifiedBoxSize {
                found: 39,
                expected: 42,
            },
            "the certified box has 39 parameters; the arm measured in 6-DoF has 42",
        ),
        (
            ArmError::CalibrationNeedsToolRotation,
            "a 6-DoF calibration needs the tool frame's rotation in the robot file ([tool] rpy_deg)",
        ),
        (
            ArmError::TooFewConfigurations(2),
            "registration needs at least 3 configurations, found 2",
        ),
        (
            ArmError::Prior {
                prior: "base position prior",
                value: -1.0,
            },
            "base position prior -1: expected a finite half-width >= 0",
        ),
        (
            ArmError::Prior {
                prior: "tool rotation prior",
                value: f64::NAN,
            },
            "tool rotation prior NaN: expected a finite half-width >= 0",
        ),
        (
            ArmError::Collinear,
            "the configurations' points are collinear: registration needs a spread",
        ),
        (
            ArmError::NoOrientation,
            "no orientation to register the tool frame from",
        ),
        (
            ArmError::Split(0.00125),
            "a link could not be split into Denavit-Hartenberg/Hayati parameters (off by 1.25e-3)",
        ),
        (
            ArmError::ChainJoints(2),
            "a chain of 2 joints; arms with 3 to 7 joints are supported",
        ),
        (
            ArmError::FlangeNotLastFrame,
            "the flange frame is not the last joint's frame",
        ),
        (
            ArmError::NonFiniteChain,
            "the chain holds a non-finite number (NaN or infinity)",
        ),
        (
            ArmError::FlangeOffset(6),
            "a6, alpha6, beta6 must be 0 to write a vendor chain (its flange is the last joint's frame)",
        ),
        (
            ArmError::UrJoints(7),
            "a UR kinematics file has 6 joints; this arm has 7",
        ),
        (
            ArmError::PointColumns(2),
            "expected three names x,y,z, found 2",
        ),
        (
            ArmError::Rows("x-3".into()),
            "`x-3`: expected rows as A-B, A- or A (1-based, e.g. 1-60 or 61-)",
        ),
        (
            ArmError::RowsReversed("3-1".into()),
            "`3-1`: the last row comes before the first",
        ),
        (ArmError::JointUnit("grad".into()), "`deg` or `rad`, not `grad`"),
        (ArmError::LengthUnit("ft".into()), "`mm` or `m`, not `ft`"),
        (
            ArmError::OrientationConvention("zyx".into()),
            "`euler-xyz-deg` or `euler-xyz-rad`, not `zyx`",
        ),
    ];
    for (e, want) in cases {
        assert_eq!(e.to_string(), want, "{e:?}");
    }
}

#[test]
fn the_parsers_report_their_variant() {
    use calib_arm::tracker_file::{JointUnit, LengthUnit, OrientationConvention, RowRange};
    assert_eq!("1-x".parse::<RowRange>(), Err(ArmError::Rows("1-x".into())));
    assert_eq!(
        "3-1".parse::<RowRange>(),
        Err(ArmError::RowsReversed("3-1".into()))
    );
    assert_eq!(
        "grad".parse::<JointUnit>(),
        Err(ArmError::JointUnit("grad".into()))
    );
    assert_eq!(
        "ft".parse::<LengthUnit>(),
        Err(ArmError::LengthUnit("ft".into()))
    );
    assert_eq!(
        "zyx".parse::<OrientationConvention>(),
        Err(ArmError::OrientationConvention("zyx".into()))
    );
}
