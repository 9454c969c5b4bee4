//! The tests of `calib_arm::joint_space`.

use calib_arm::joint_space::*;
use std::path::Path;

fn parse(text: &str) -> Result<JointSpace, String> {
    parse_joint_space(Path::new("joints.toml"), text, 3).map_err(|e| e.to_string())
}

#[test]
fn reads_one_range_per_joint() {
    let s = parse("q1 = [-10.0, 10.0]\nq3 = [0, 5.5]\nq2 = [-1.0, 2.0]\n").unwrap();
    assert_eq!(s.ranges_deg, vec![[-10.0, 10.0], [-1.0, 2.0], [0.0, 5.5]]);
}

#[test]
fn bad_files_name_the_line_and_the_field() {
    for (text, line, field) in [
        (
            "q1 = [-1.0, 1.0]\nq2 = [2.0, 1.0]\nq3 = [0.0, 1.0]\n",
            "line 2",
            "q2",
        ),
        (
            "q1 = [-1.0, 1.0]\nq2 = [0.0, 1.0]\nq4 = [0.0, 1.0]\n",
            "line 3",
            "q4",
        ),
        (
            "q1 = [-1.0, 1.0]\nq2 = [0.0, nan]\nq3 = [0.0, 1.0]\n",
            "line 2",
            "q2",
        ),
        (
            "q1 = [-1.0, 1.0]\nq2 = [0.0, 1.0]\nq3 = 4\n",
            "line 3",
            "q3",
        ),
        ("q1 = [-1.0, 1.0]\nq2 = [0.0, 1.0]\n", "joints.toml", "q3"),
        (
            "q1 = [-1.0, 1.0]\nq02 = [0.0, 1.0]\nq3 = [0.0, 1.0]\n",
            "line 2",
            "q02",
        ),
    ] {
        let e = parse(text).unwrap_err();
        assert!(e.contains(line) && e.contains(field), "{text}: {e}");
    }
}
