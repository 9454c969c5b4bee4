//! The tests of `calib_gough::workspace`.

use calib_gough::files::DataError;
use calib_gough::simulate::builtin_hexapod;
use calib_gough::workspace::*;
use rand::rngs::StdRng;
use rand::SeedableRng;
use std::path::Path;

fn parse(text: &str) -> Result<Workspace, DataError> {
    parse_workspace(Path::new("workspace.toml"), text)
}

#[test]
fn the_shared_sample_file_is_the_simulator_workspace() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/workspace.toml");
    assert_eq!(read_workspace(&path).unwrap(), Workspace::SIMULATOR);
}

#[test]
fn bad_fields_are_named_with_their_line() {
    let ok = "x = [-5, 5]\ny = [-5, 5]\nz = [55, 65]\ntilt_deg = 15\n";
    assert_eq!(parse(ok).unwrap().stroke, None);
    let cases = [
        (
            "x = [5, -5]\ny = [-5, 5]\nz = [55, 65]\ntilt_deg = 15\n",
            1,
            Some("x"),
        ),
        (
            "x = [-5, 5]\ny = [-5, 5]\nz = [55, 65]\ntilt_deg = 200\n",
            4,
            Some("tilt_deg"),
        ),
        (&format!("{ok}stroke = [15, 0]\n"), 5, Some("stroke")),
        (
            "x = [-5, 5]\ny = [-5, 5]\nz = [55, nan]\ntilt_deg = 15\n",
            3,
            Some("z"),
        ),
        (
            "x = [-5, 5]\ny = [-inf, 5]\nz = [55, 65]\ntilt_deg = 15\n",
            2,
            Some("y"),
        ),
        (
            "x = [-5, 5]\ny = [-5, 5]\nz = [55, 65]\ntilt_deg = nan\n",
            4,
            Some("tilt_deg"),
        ),
        (
            "x = [-5, 5]\ny = [-5]\nz = [55, 65]\ntilt_deg = 15\n",
            2,
            None,
        ),
        (&format!("{ok}tilt = 3\n"), 5, None),
    ];
    for (text, line, field) in cases {
        let e = parse(text).unwrap_err();
        assert_eq!((e.line, e.field.as_deref()), (Some(line), field), "{e}");
    }
    let e = parse("x = [-5, 5]\n").unwrap_err();
    assert!(e.message.contains("missing field"), "{e}");
}

#[test]
fn sampled_poses_lie_in_the_workspace_and_an_impossible_stroke_is_an_error() {
    let legs = builtin_hexapod();
    let w = Workspace::SIMULATOR;
    let mut rng = StdRng::seed_from_u64(3);
    for extremes in [false, true] {
        let poses = w.poses(&mut rng, &legs, 300, extremes).unwrap();
        assert!(poses.iter().all(|p| w.contains(p, &legs)));
    }
    let tight = Workspace {
        stroke: Some([100.0, 101.0]),
        ..w
    };
    assert!(tight.poses(&mut rng, &legs, 1, false).is_err());
}
