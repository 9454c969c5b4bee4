//! The real UR10 (docs/data/ur10_ipa, laser-tracker data as exported) through the commands a
//! newcomer runs: import UR's YAML, register the tracker, certify, predict held-out rows, export
//! the calibrated YAML; and the files' mistakes named without anything written.

use crate::scratch_dir::ScratchDir;
use std::path::Path;
use std::process::{Command, Output};

fn arm(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_arm"))
        .args(args)
        .output()
        .expect("the arm binary runs")
}

/// The JSON file at `path`.
fn json_file(path: &str) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("a JSON file")).expect("JSON")
}

fn text(o: &Output) -> String {
    format!(
        "{}\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

fn data(file: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../docs/data/ur10_ipa")
        .join(file)
        .to_string_lossy()
        .into_owned()
}

fn tempdir(name: &str) -> ScratchDir {
    ScratchDir::new(&format!("arm-ur10-{name}"))
}

const JOINTS: &str = "shoulder_pan_joint,shoulder_lift_joint,elbow_joint,wrist_1_joint,\
                      wrist_2_joint,wrist_3_joint";
const POINT: &str = "measurement_x,measurement_y,measurement_z";

/// The arguments that read the tracker's file as it comes, rows `rows`.
fn tracker(rows: &str) -> Vec<String> {
    [
        "--measurements",
        &data("series_b_joint_configurations.csv"),
        "--joint-columns",
        JOINTS,
        "--joint-unit",
        "rad",
        "--point-columns",
        POINT,
        "--rows",
        rows,
    ]
    .map(String::from)
    .to_vec()
}

/// `arm import` of UR's YAML into `out`.
fn import_nominal(out: &str) {
    let o = arm(&[
        "import",
        "--ur-yaml",
        &data("ur10_default_kinematics.yaml"),
        "--out",
        out,
    ]);
    assert!(o.status.success(), "{}", text(&o));
}

/// UR's nominal kinematics imported into `dir/nominal.toml`, then registered on series B's rows
/// 1-60 into `dir/robot.toml` (tutorial steps 1 and 2): `register`'s output, checked a success.
fn registered(dir: &Path) -> Output {
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    import_nominal(&p("nominal.toml"));
    let o = run(
        &[
            "register",
            "--robot",
            &p("nominal.toml"),
            "--out",
            &p("robot.toml"),
        ],
        &tracker("1-60"),
    );
    assert!(o.status.success(), "{}", text(&o));
    o
}

fn run(args: &[&str], extra: &[String]) -> Output {
    let mut all: Vec<&str> = args.to_vec();
    all.extend(extra.iter().map(String::as_str));
    arm(&all)
}

#[test]
fn from_the_tracker_file_and_ur_yaml_to_a_certified_ur_yaml() {
    let dir = tempdir("pipeline");
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    let o = registered(&dir);
    // Five flange orientations and the home pose: base and tool told apart, nothing to warn.
    assert!(!text(&o).contains("warning"), "{}", text(&o));
    // The T-Mac sits about 93 mm out along the flange axis (the dataset's README).
    let robot = calib_arm::files::read_robot(Path::new(&p("robot.toml"))).expect("robot");
    assert!((robot.tool[2] - 93.0).abs() < 2.0, "{:?}", robot.tool);
    assert!(robot.tool[0].hypot(robot.tool[1]) < 2.0, "{:?}", robot.tool);
    std::fs::write(p("u.toml"), "joint_deg = 0.001\npos = 0.6\n").expect("write");
    let o = run(
        &[
            "certify",
            "--robot",
            &p("robot.toml"),
            "--uncertainty",
            &p("u.toml"),
            "--write-calibrated",
            &p("calibrated.toml"),
            "--json",
            &p("certified.json"),
        ],
        &tracker("1-60"),
    );
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(text(&o).contains("verdict: consistent"), "{}", text(&o));
    // The inner bounds reach where the consistent set does: certified points found towards the
    // first-order extremes (towards the contraction's extremes alone they stopped at half the
    // outer width, outer/inner 2.0-2.5 on every parameter at x1).
    let certified = json_file(&p("certified.json"));
    // The JSON says which vector the calibrated file holds and how it was chosen.
    let chosen = &certified["calibrated"];
    assert_eq!(chosen["rule"], "lsq", "{chosen}");
    let weight = chosen["prior_weight"].as_f64().expect("a prior weight");
    assert!(calib_core::PRIOR_WEIGHTS.contains(&weight), "{chosen}");
    assert!(
        chosen["margin"].as_f64().is_some_and(|m| m > 0.0),
        "{chosen}"
    );
    let params = certified["parameters"].as_array().expect("parameters");
    for q in params.iter().filter(|q| q["fixed"] == false) {
        let ratio = q["ratio"].as_f64().expect("a ratio");
        assert!(ratio < 1.6, "{}: outer/inner {ratio}", q["name"]);
    }
    // Held-out rows: every measurement inside its certified prediction with the error bounds,
    // and the written model's residuals reported.
    let o = run(
        &[
            "predict",
            "--robot",
            &p("calibrated.toml"),
            "--uncertainty",
            &p("u.toml"),
            "--json",
            &p("check.json"),
        ],
        &tracker("61-160"),
    );
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let check = json_file(&p("check.json"));
    assert_eq!(check["rows"].as_array().map(Vec::len), Some(100));
    assert_eq!(check["over"], "certified set");
    let rms = check["residuals"]["rms_mm"].as_f64().expect("rms");
    assert!(rms > 0.0 && rms < 0.3, "held-out rms {rms} mm");
    // The written vector, regularised least squares within the set, predicts the held-out rows
    // better than plain least squares on the same configurations (which sends 12 parameters out
    // of their priors).
    let o = run(
        &["lsq", "--robot", &p("robot.toml"), "--out", &p("lsq.toml")],
        &tracker("1-60"),
    );
    assert!(o.status.success(), "{}", text(&o));
    let o = run(
        &[
            "predict",
            "--robot",
            &p("lsq.toml"),
            "--uncertainty",
            &p("u.toml"),
            "--json",
            &p("lsq_check.json"),
        ],
        &tracker("61-160"),
    );
    let lsq = json_file(&p("lsq_check.json"));
    let lsq_rms = lsq["residuals"]["rms_mm"].as_f64().expect("rms");
    assert!(
        rms < lsq_rms,
        "certified {rms} mm, least squares {lsq_rms} mm: {}",
        text(&o)
    );
    // The UR YAML out, and its forward kinematics are the calibrated file's.
    let o = arm(&[
        "export",
        "--robot",
        &p("calibrated.toml"),
        "--ur-yaml",
        &p("calibrated.yaml"),
    ]);
    assert!(o.status.success(), "{}", text(&o));
    let yaml = std::fs::read_to_string(p("calibrated.yaml")).expect("yaml");
    let k = calib_arm::vendor::ur_yaml::parse(Path::new("calibrated.yaml"), &yaml).expect("UR");
    let (cal, _) =
        calib_arm::files::read_calibrated(Path::new(&p("calibrated.toml"))).expect("calibrated");
    let base = calib_arm::vendor::base_frame(&cal.base);
    for q in [
        [0.3, -1.2, 1.9, -0.4, 1.1, 2.5],
        [-2.0, -0.3, -1.0, 2.2, -1.7, 0.2],
    ] {
        let a = calib_arm::vendor::arm_flange(&cal, &q);
        let b = base * calib_arm::vendor::chain_flange(&k.origins, &q);
        assert!((a.translation.vector - b.translation.vector).norm() < 1e-6);
    }
}

/// The series at 0.98 times its smallest consistent position bound (0.3846 mm, tutorial step 3):
/// proved inconsistent by the second-order certificate, which weighs 17 of the 60 configurations -
/// a misfit spread over the series, said at once, where the conflict search took a minute to name
/// 22 configurations. The JSON keeps `conflict` (null) and adds `support` and `spread`.
#[test]
fn just_below_the_smallest_consistent_bound_the_misfit_is_spread_over_the_series() {
    let dir = tempdir("spread");
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    registered(&dir);
    std::fs::write(p("u.toml"), "joint_deg = 0.001\npos = 0.3769\n").expect("write");
    let o = run(
        &[
            "certify",
            "--robot",
            &p("robot.toml"),
            "--uncertainty",
            &p("u.toml"),
            "--json",
            &p("report.json"),
        ],
        &tracker("1-60"),
    );
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    let out = text(&o);
    assert!(out.contains("second-order Farkas certificate"), "{out}");
    assert!(out.contains("too tight for the model") && out.contains("--error-scale auto"));
    let report = json_file(&p("report.json"));
    assert_eq!(report["status"], "empty");
    assert!(report["conflict"].is_null(), "{}", report["conflict"]);
    assert_eq!(report["spread"], true);
    let support = report["support"].as_array().expect("the support");
    // 27 free parameters: a certificate weighs at most 28 configurations; spread above 14.
    assert!((15..=28).contains(&support.len()), "{support:?}");
    // The hull proves it by subdivision; `certify` gives it the same support.
    let o = run(
        &[
            "certify",
            "--robot",
            &p("robot.toml"),
            "--uncertainty",
            &p("u.toml"),
            "--hull",
            "--json",
            &p("hull.json"),
        ],
        &tracker("1-60"),
    );
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    let hull = json_file(&p("hull.json"));
    assert_eq!(
        (&hull["spread"], &hull["support"], &hull["conflict"]),
        (
            &report["spread"],
            &report["support"],
            &serde_json::Value::Null
        )
    );
}

#[test]
fn wrong_units_and_columns_are_named_and_nothing_is_written() {
    let dir = tempdir("mistakes");
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    import_nominal(&p("nominal.toml"));
    // Millimetres read as metres: the row, its line and the column, and the fix.
    let mut args = tracker("1-60");
    args.extend(["--length-unit".into(), "m".into()]);
    let o = run(
        &[
            "register",
            "--robot",
            &p("nominal.toml"),
            "--out",
            &p("never.toml"),
        ],
        &args,
    );
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        err.contains("series_b_joint_configurations.csv")
            && err.contains("line 2")
            && err.contains("measurement_x")
            && err.contains("--length-unit mm"),
        "{err}"
    );
    // A misspelt column: named, with the columns there are.
    let mut args = tracker("1-60");
    args[3] = JOINTS.replace("elbow_joint", "elbow");
    let o = run(
        &[
            "register",
            "--robot",
            &p("nominal.toml"),
            "--out",
            &p("never.toml"),
        ],
        &args,
    );
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        err.contains("no column `elbow`") && err.contains("elbow_joint"),
        "{err}"
    );
    // Radians read as degrees: a note that names the fix.
    let mut args = tracker("1-60");
    args.retain(|a| a != "rad" && a != "--joint-unit");
    let o = run(
        &[
            "register",
            "--robot",
            &p("nominal.toml"),
            "--out",
            &p("deg.toml"),
        ],
        &args,
    );
    assert!(text(&o).contains("--joint-unit rad"), "{}", text(&o));
    assert!(!dir.join("never.toml").exists());
    // A bad UR YAML: file, line and field; nothing written.
    std::fs::write(
        p("bad.yaml"),
        std::fs::read_to_string(data("ur10_default_kinematics.yaml"))
            .expect("yaml")
            .replace("z: 0.1273", "z: lots"),
    )
    .expect("write");
    let o = arm(&[
        "import",
        "--ur-yaml",
        &p("bad.yaml"),
        "--out",
        &p("never.toml"),
    ]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(err.contains("bad.yaml") && err.contains("line 5"), "{err}");
    assert!(!dir.join("never.toml").exists());
}

const ORIENTATION: &str = "measurement_rx,measurement_ry,measurement_rz";

#[test]
fn the_tmac_orientations_register_the_tool_frame_and_go_where_they_are_used() {
    let dir = tempdir("six-dof");
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    import_nominal(&p("nominal.toml"));
    let mut six = tracker("1-40");
    six.extend(["--orientation-columns".into(), ORIENTATION.into()]);
    let o = run(
        &[
            "register",
            "--robot",
            &p("nominal.toml"),
            "--out",
            &p("robot.toml"),
        ],
        &six,
    );
    assert!(o.status.success(), "{}", text(&o));
    // The T-Mac's frame is turned a quarter turn about the flange axis (as registered from
    // every configuration's orientation; the fit leaves about a tenth of a degree).
    let robot = calib_arm::files::read_robot(Path::new(&p("robot.toml"))).expect("robot");
    let t = robot.tool_rotation.expect("the tool frame's rotation");
    assert!((t.rpy_deg[2] + 90.0).abs() < 1.0, "{t:?}");
    assert!(
        t.rpy_deg[0].abs() < 1.0 && t.rpy_deg[1].abs() < 1.0,
        "{t:?}"
    );
    assert_eq!(t.radius, [0.5; 3]);
    let out = text(&o);
    let rms: f64 = out
        .split("orientation residuals rms ")
        .nth(1)
        .and_then(|s| s.split('°').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("{out}"));
    assert!(rms > 0.0 && rms < 0.2, "{out}");
    // Commands that use positions only say so; nothing is written.
    std::fs::write(
        p("u.toml"),
        "joint_deg = 0.001\npos = 0.6\norient_deg = 0.2\n",
    )
    .expect("write");
    let o = run(
        &[
            "lsq",
            "--robot",
            &p("robot.toml"),
            "--out",
            &p("never.json"),
        ],
        &six,
    );
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(text(&o).contains("positions only"), "{}", text(&o));
    // Certification with the orientations: six equations per configuration.
    let o = run(
        &[
            "certify",
            "--robot",
            &p("robot.toml"),
            "--uncertainty",
            &p("u.toml"),
            "--json",
            &p("six.json"),
            "--write-calibrated",
            &p("six_calibrated.toml"),
        ],
        &six,
    );
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(text(&o).contains("6-DoF"), "{}", text(&o));
    // Decided at x1: a parameter vector proved to fit all six equations of every configuration
    // (undecided while a failed LP of an existence proof's hint ended the proof).
    assert!(text(&o).contains("verdict: consistent"), "{}", text(&o));
    assert!(dir.join("six.json").exists());
    // The calibrated file carries the tool frame's rotation (calibrated, not the registered one)
    // and the positions' certified set, which `predict` reads.
    let (calibrated, set) =
        calib_arm::files::read_calibrated(&dir.join("six_calibrated.toml")).expect("read back");
    let registered = calib_arm::files::read_robot(&dir.join("robot.toml")).expect("robot");
    let (rot, reg) = (
        calibrated.tool_rotation.unwrap(),
        registered.tool_rotation.unwrap(),
    );
    assert_ne!(
        rot.rpy_deg, reg.rpy_deg,
        "the tool rotation was not calibrated"
    );
    assert!(set.is_some_and(|s| !s.is_empty()));
    std::fs::write(p("u_predict.toml"), "joint_deg = 0.001\npos = 0.6\n").expect("write");
    let o = run(
        &[
            "predict",
            "--robot",
            &p("six_calibrated.toml"),
            "--uncertainty",
            &p("u_predict.toml"),
        ],
        &tracker("61-80"),
    );
    assert!(matches!(o.status.code(), Some(0 | 2)), "{}", text(&o));
    assert!(text(&o).contains("20 configurations"), "{}", text(&o));
    // With the orientations: their held-out residuals against the calibrated tool frame, in
    // the JSON too, and smaller than against the registered (uncalibrated) robot file's frame.
    let mut held_out = tracker("61-80");
    held_out.extend(["--orientation-columns".into(), ORIENTATION.into()]);
    let orientation_rms = |robot: &str, json: &str| -> f64 {
        let o = run(
            &[
                "predict",
                "--robot",
                &p(robot),
                "--uncertainty",
                &p("u_predict.toml"),
                "--json",
                &p(json),
            ],
            &held_out,
        );
        assert!(matches!(o.status.code(), Some(0 | 2)), "{}", text(&o));
        assert!(text(&o).contains("measured orientations"), "{}", text(&o));
        let v = json_file(&p(json));
        let r = &v["orientation_residuals"];
        assert_eq!(r["per_row_deg"].as_array().map(Vec::len), Some(20), "{r}");
        r["rms_deg"].as_f64().expect("rms")
    };
    let (calibrated_rms, registered_rms) = (
        orientation_rms("six_calibrated.toml", "six_check.json"),
        orientation_rms("robot.toml", "registered_check.json"),
    );
    assert!(
        0.0 < calibrated_rms && calibrated_rms < registered_rms,
        "calibrated {calibrated_rms}°, registered {registered_rms}°"
    );
    // A file without the tool frame's rotation cannot check orientations: named, exit 1.
    let o = run(
        &[
            "predict",
            "--robot",
            &p("nominal.toml"),
            "--uncertainty",
            &p("u_predict.toml"),
        ],
        &held_out,
    );
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        err.contains("nominal.toml") && err.contains("rpy_deg"),
        "{err}"
    );
    assert!(!dir.join("never.json").exists());
    // Orientations need the tool frame's rotation and a bound for them: each file named.
    std::fs::write(p("u_pos.toml"), "joint_deg = 0.001\npos = 0.6\n").expect("write");
    for (robot, bounds, named, what) in [
        ("nominal.toml", "u.toml", "nominal.toml", "rpy_deg"),
        ("robot.toml", "u_pos.toml", "u_pos.toml", "orient_deg"),
    ] {
        let o = run(
            &[
                "certify",
                "--robot",
                &p(robot),
                "--uncertainty",
                &p(bounds),
                "--json",
                &p("never.json"),
            ],
            &six,
        );
        assert_eq!(o.status.code(), Some(1), "{}", text(&o));
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        assert!(err.contains(named) && err.contains(what), "{err}");
    }
    assert!(!dir.join("never.json").exists());
    // A rotation without its prior in the robot file: file, line and field.
    let text_robot = std::fs::read_to_string(p("robot.toml")).expect("robot");
    let cut: String = text_robot
        .lines()
        .filter(|l| !l.starts_with("rotation_radius"))
        .map(|l| format!("{l}\n"))
        .collect();
    let e = calib_arm::files::parse_robot(Path::new("cut.toml"), &cut).unwrap_err();
    let e = e.to_string();
    assert!(
        e.contains("cut.toml") && e.contains("tool.rpy_deg") && e.contains("rotation_radius"),
        "{e}"
    );
}

#[test]
fn one_flange_orientation_is_registered_with_the_files_tool_and_a_warning() {
    let dir = tempdir("one-orientation");
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    import_nominal(&p("nominal.toml"));
    // Series B's first 60 rows commanded to one orientation (Goal roll, pitch, yaw = 180°,
    // 100°, 90°), the tracker's file as it comes otherwise.
    let series = std::fs::read_to_string(data("series_b_joint_configurations.csv")).expect("csv");
    let mut lines = series.lines();
    let mut block = vec![lines.next().expect("a header")];
    block.extend(
        lines
            .filter(|l| {
                let goal: Vec<f64> = l
                    .split(';')
                    .skip(4)
                    .take(3)
                    .map(|v| v.replace(',', ".").parse::<f64>().expect("a goal angle"))
                    .collect();
                [180.0, 100.0, 90.0]
                    .iter()
                    .zip(&goal)
                    .all(|(want, rad)| (rad.to_degrees() - want).abs() < 0.05)
            })
            .take(60),
    );
    assert_eq!(block.len(), 61);
    std::fs::write(p("one.csv"), block.join("\n") + "\n").expect("write");
    let mut args = tracker("1-");
    args[1] = p("one.csv");
    let register = |out: &str, extra: &[&str]| {
        let mut all = args.clone();
        all.extend(extra.iter().map(|s| s.to_string()));
        run(
            &["register", "--robot", &p("nominal.toml"), "--out", &p(out)],
            &all,
        )
    };
    let o = register("robot.toml", &[]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let said = text(&o);
    assert!(
        said.contains("warning: the 60 configurations hold one flange orientation (all within")
            && said.contains("base and tool cannot be told apart there")
            && said.contains("kept from")
            && said.contains("nominal.toml and fixed (--tool-radius 0)")
            && said.contains("--tool fit fits it anyway"),
        "{said}"
    );
    // The nominal file's tool point (the flange's centre), fixed; the base found, and the rows
    // fitted as well as by the nine parameters (0.75 mm with the nominal joints).
    let robot = calib_arm::files::read_robot(Path::new(&p("robot.toml"))).expect("robot");
    assert_eq!(robot.tool, [0.0; 3]);
    assert_eq!(robot.tool_radius, [0.0; 3]);
    assert_eq!(robot.base_radius, [2.0, 2.0, 2.0, 0.1, 0.1, 0.1]);
    let header = std::fs::read_to_string(p("robot.toml")).expect("robot");
    assert!(
        header
            .lines()
            .next()
            .is_some_and(|l| l.contains("tool point kept")),
        "{header}"
    );
    // Fitting all nine anyway, as before: the tool point goes far from the T-Mac's 93 mm on the
    // flange axis, for the same residuals, and the warning stays.
    let o = register("fit.toml", &["--tool", "fit"]);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(
        text(&o).contains("warning: the 60 configurations hold one flange orientation")
            && text(&o).contains("fitted as asked (--tool fit)"),
        "{}",
        text(&o)
    );
    let fit = calib_arm::files::read_robot(Path::new(&p("fit.toml"))).expect("robot");
    let off = (fit.tool[0].powi(2) + fit.tool[1].powi(2) + (fit.tool[2] - 93.0).powi(2)).sqrt();
    assert!(off > 100.0, "{:?}", fit.tool);
    // A prior asked for is written as asked, around the kept tool point.
    let o = register("asked.toml", &["--tool-radius", "2"]);
    assert!(text(&o).contains("the prior ± 2 mm asked"), "{}", text(&o));
    let asked = calib_arm::files::read_robot(Path::new(&p("asked.toml"))).expect("robot");
    assert!(asked.tool == [0.0; 3] && asked.tool_radius == [2.0; 3]);
}
