//! The arm's files: the built-in arm written as `robot.toml` reads back as itself, and every
//! malformed input names the file, the line and the field.

use calib_arm::files::{parse_measurements, parse_robot, parse_uncertainty};
use calib_arm::{builtin_arm, Arm};
use std::path::Path;

/// `arm` as `robot.toml` text.
fn robot_toml(arm: &Arm) -> String {
    let list = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:?}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut s = String::from("# test arm\n");
    for j in &arm.joints {
        let n = j.nominal;
        s += &format!(
            "\n[[joint]]\ntheta_deg = {:?}\nd = {:?}\na = {:?}\nalpha_deg = {:?}\nbeta_deg = {:?}\nradius = [{}]\n",
            n[0], n[1], n[2], n[3], n[4], list(&j.radius)
        );
    }
    s += &format!(
        "\n[base]\nxyz = [{}]\nrpy_deg = [{}]\nradius = [{}]\n",
        list(&arm.base[..3]),
        list(&arm.base[3..]),
        list(&arm.base_radius)
    );
    s += &format!(
        "\n[tool]\nxyz = [{}]\nradius = [{}]\n",
        list(&arm.tool),
        list(&arm.tool_radius)
    );
    s
}

#[test]
fn the_builtin_arm_reads_back_exactly() {
    let arm = builtin_arm();
    let text = robot_toml(&arm);
    assert_eq!(parse_robot(Path::new("robot.toml"), &text).unwrap(), arm);
    // One radius for all, beta_deg left out.
    let short = text.replacen(
        "beta_deg = 0.0\nradius = [0.0, 0.0, 0.5, 0.05, 0.0]",
        "radius = 0.25",
        1,
    );
    let parsed = parse_robot(Path::new("robot.toml"), &short).unwrap();
    assert_eq!(parsed.joints[0].radius, [0.25; 5]);
    assert_eq!(parsed.joints[0].nominal[4], 0.0);
}

/// The error of `text` names `robot.toml`, the line of `needle` and the field.
fn assert_robot_error(text: &str, needle: &str, field: Option<&str>) {
    let e = parse_robot(Path::new("robot.toml"), text).unwrap_err();
    assert_eq!(e.file, Path::new("robot.toml"));
    assert_eq!(e.field.as_deref(), field, "{e}");
    let line = text.lines().position(|l| l.contains(needle)).map(|i| i + 1);
    assert_eq!(e.line, line, "{e}");
    assert!(!e.message.is_empty());
}

#[test]
fn malformed_robot_files_name_line_and_field() {
    let good = robot_toml(&builtin_arm());
    assert_robot_error(
        &good.replacen(
            "radius = [0.05, 0.0, 0.5, 0.05, 0.05]",
            "radius = [0.05, -1.0, 0.5, 0.05, 0.05]",
            1,
        ),
        "radius = [0.05, -1.0",
        Some("joint[2].radius"),
    );
    // Four half-widths where five are needed: the TOML reader points at the value.
    let e = parse_robot(
        Path::new("robot.toml"),
        &good.replacen(
            "radius = [0.0, 0.0, 0.5, 0.05, 0.0]",
            "radius = [0.0, 0.5, 0.05, 0.0]",
            1,
        ),
    )
    .unwrap_err();
    assert!(e.line.is_some(), "{e}");
    assert_robot_error(
        &good.replacen("d = 89.159", "d = 1e300", 1),
        "d = 1e300",
        Some("joint[1].d"),
    );
    assert_robot_error(
        &good
            .replacen("rpy_deg = [", "rpy_deg = [1e200, ", 1)
            .replacen(", 25.0]", "]", 1),
        "rpy_deg",
        Some("base.rpy_deg"),
    );
    // A typo in a key.
    let e = parse_robot(
        Path::new("robot.toml"),
        &good.replacen("alpha_deg", "alpha", 1),
    )
    .unwrap_err();
    assert!(e.message.contains("alpha") && e.line.is_some(), "{e}");
    // Too few joints.
    let two: String = {
        let mut arm = builtin_arm();
        arm.joints.truncate(2);
        robot_toml(&arm)
    };
    let e = parse_robot(Path::new("robot.toml"), &two).unwrap_err();
    assert_eq!(e.field.as_deref(), Some("joint"));
    assert!(e.message.contains("3 to 7"), "{e}");
    // No [tool] table.
    let cut = &good[..good.find("[tool]").unwrap()];
    let e = parse_robot(Path::new("robot.toml"), cut).unwrap_err();
    assert!(e.message.contains("tool"), "{e}");
}

#[test]
fn measurements_and_uncertainty_are_checked() {
    let f = Path::new("measurements.csv");
    let m = parse_measurements(f, "q1,q2,q3,px,py,pz\n1,2,3,4,5,6\n7,8,9,10,11,12\n", 3).unwrap();
    assert_eq!(m.readings[1].joints_deg, vec![7.0, 8.0, 9.0]);
    assert_eq!(m.readings[1].point, [10.0, 11.0, 12.0]);
    assert_eq!(m.lines, vec![2, 3]);
    let e = parse_measurements(f, "q1,q2,q3,px,py,pz\n1,2,3,4,5,6\n", 6).unwrap_err();
    assert_eq!(e.line, Some(1));
    assert_eq!(e.field.as_deref(), Some("q4"));
    assert!(
        e.message.contains("no column `q4`") && e.message.contains("q1, q2, q3, px, py, pz"),
        "{e}"
    );
    let e = parse_measurements(f, "q1,q2,q3,px,py,pz\n1,2,3,4,5,6\n1,2,x,4,5,6\n", 3).unwrap_err();
    assert_eq!((e.line, e.field.as_deref()), (Some(3), Some("q3")));
    let e = parse_measurements(f, "q1,q2,q3,px,py,pz\n", 3).unwrap_err();
    assert!(e.message.contains("no configurations"), "{e}");
    let u = Path::new("uncertainty.toml");
    let ok = parse_uncertainty(u, "joint_deg = 0.001\npos = 0.01\n").unwrap();
    assert_eq!((ok.joint_deg, ok.pos), (0.001, 0.01));
    let e = parse_uncertainty(u, "joint_deg = 0.001\npos = -0.01\n").unwrap_err();
    assert_eq!((e.line, e.field.as_deref()), (Some(2), Some("pos")));
    let e = parse_uncertainty(u, "joint_deg = 0.001\n").unwrap_err();
    assert!(e.message.contains("pos"), "{e}");
}

/// TOML's spellings of NaN and the infinities, and a decimal that overflows to one (the TOML
/// reader refuses `1e999` itself, but reads `-1e999` as minus infinity).
const NON_FINITE_TOML: [&str; 6] = ["nan", "-nan", "inf", "+inf", "-inf", "-1e999"];

/// `text` with its first line starting with `start` replaced by `line`, and that line's number.
fn with_line(text: &str, start: &str, line: &str) -> (String, usize) {
    let at = text
        .lines()
        .position(|l| l.starts_with(start))
        .expect("the line");
    let lines: Vec<&str> = text
        .lines()
        .enumerate()
        .map(|(i, l)| if i == at { line } else { l })
        .collect();
    (lines.join("\n") + "\n", at + 1)
}

#[test]
fn non_finite_numbers_are_refused_with_line_and_field() {
    let good = robot_toml(&builtin_arm());
    for bad in NON_FINITE_TOML {
        for (start, line, field) in [
            ("d = ", format!("d = {bad}"), "joint[1].d"),
            (
                "theta_deg = ",
                format!("theta_deg = {bad}"),
                "joint[1].theta_deg",
            ),
            ("xyz = ", format!("xyz = [0.0, {bad}, 0.0]"), "base.xyz"),
            (
                "radius = ",
                format!("radius = [0.0, 0.0, {bad}, 0.05, 0.0]"),
                "joint[1].radius",
            ),
        ] {
            let (text, at) = with_line(&good, start, &line);
            let e = parse_robot(Path::new("robot.toml"), &text).unwrap_err();
            assert_eq!(
                (e.line, e.field.as_deref()),
                (Some(at), Some(field)),
                "{bad}: {e}"
            );
            assert!(e.message.contains("expected a finite number"), "{bad}: {e}");
        }
        let u = Path::new("uncertainty.toml");
        let e = parse_uncertainty(u, &format!("joint_deg = 0.001\npos = {bad}\n")).unwrap_err();
        assert_eq!(
            (e.line, e.field.as_deref()),
            (Some(2), Some("pos")),
            "{bad}: {e}"
        );
    }
    // `1e999` is not a TOML number: refused by the reader at its line.
    let (text, at) = with_line(&good, "d = ", "d = 1e999");
    let e = parse_robot(Path::new("robot.toml"), &text).unwrap_err();
    assert_eq!(e.line, Some(at), "{e}");
}

#[test]
fn non_finite_measurements_are_refused_with_line_and_column() {
    let f = Path::new("measurements.csv");
    for bad in ["nan", "NaN", "inf", "-inf", "infinity", "1e999", "-1e999"] {
        let text = format!("q1,q2,q3,px,py,pz\n1,2,3,4,5,6\n1,2,3,4,{bad},6\n");
        let e = parse_measurements(f, &text, 3).unwrap_err();
        assert_eq!(
            (e.line, e.field.as_deref()),
            (Some(3), Some("py")),
            "{bad}: {e}"
        );
        assert!(e.to_string().starts_with("measurements.csv, line 3"), "{e}");
    }
}
