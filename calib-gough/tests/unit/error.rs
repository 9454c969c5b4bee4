//! The tests of `calib_gough::GoughError`: its messages, byte for byte (the typed errors replaced
//! strings formatted at the call sites, and the CLI prints them).

use calib_core::Status;
use calib_gough::GoughError;
use calib_pipeline::OptionError;
use std::path::PathBuf;

#[test]
fn messages_are_the_ones_the_command_line_printed() {
    let io = || std::io::Error::new(std::io::ErrorKind::PermissionDenied, "denied");
    let cases: Vec<(GoughError, &str)> = vec![
        (
            GoughError::NoSuchLeg { leg: 9, legs: 6 },
            "--legs: leg 9 does not exist (robot.toml has 6 legs)",
        ),
        (
            GoughError::Pave(1.5),
            "--pave: expected a relative width in (0, 1), found 1.5",
        ),
        (
            OptionError::Tolerance(0.0).into(),
            "--tolerance: expected a positive number, found 0",
        ),
        (
            GoughError::LegInconsistent(2),
            "leg 2 was proved inconsistent with the data: there is no calibrated geometry to write (re-measure its conflicting configurations, or tolerate outliers)",
        ),
        (
            GoughError::LegUndecided(3),
            "leg 3: no geometry was proved consistent with every measurement (the certification is undecided), so none can be handed out as calibrated: allow more boxes or seconds, tolerate outliers, or check the error bounds",
        ),
        (
            GoughError::ExtendNeedsQ,
            "--extend: the measurements give Rodrigues vectors (q1,q2,q3); give --uncertainty with their half-width q",
        ),
        (
            GoughError::ExtendLegUnresolved {
                leg: 4,
                status: Status::Empty,
            },
            "--extend: leg 4 of the measured data has no certified consistent parameter vector (Empty); certify the data (gough certify) and resolve that leg first",
        ),
        (
            GoughError::NoConfigurations,
            "--configs: expected at least 1 configuration",
        ),
        (
            GoughError::TooFewCandidates {
                candidates: 5,
                configs: 10,
            },
            "--candidates 5: expected at least as many candidates as configurations (10)",
        ),
        (
            GoughError::StrokeExcludesPoses([0.0, 15.0]),
            "no pose of 100000 random tries in the workspace has every leg reading within the stroke [0.0, 15.0] (nominal geometry): check `stroke`",
        ),
        (
            GoughError::TooFewConfigurations(6),
            "--configs 6: at least 7 configurations are needed",
        ),
        (
            GoughError::TooFewPoses(3),
            "3 poses: at least 7 configurations are needed (one per unknown of a leg)",
        ),
        (
            GoughError::NoiseScale,
            "--noise-scale: expected a finite number >= 0",
        ),
        (
            GoughError::Outlier {
                configuration: 20,
                leg: 6,
                delta: 0.5,
                configs: 21,
            },
            "--outlier 21:7:0.5: configuration must be 1..=21, leg 1..=6, delta finite",
        ),
        (
            GoughError::CreateDir {
                path: PathBuf::from("out"),
                source: io(),
            },
            "out: cannot create: denied",
        ),
        (
            GoughError::Write {
                path: PathBuf::from("out/robot.toml"),
                source: io(),
            },
            "out/robot.toml: cannot write: denied",
        ),
    ];
    for (e, text) in cases {
        assert_eq!(e.to_string(), text);
    }
}
