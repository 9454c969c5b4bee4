//! The `arm` command line end to end, on a small 3-joint arm (seconds, where the built-in 6-axis
//! arm takes a minute): simulate, certify with the truth inside, an outlier proved and named,
//! least squares, and bad input refused with the file, line and field named and nothing written.

use crate::scratch_dir::ScratchDir;
use serde_json::Value;
use std::path::Path;
use std::process::{Command, Output};

/// A 3-joint arm with small priors (one Newton step bites) and a tilted base.
const ROBOT: &str = include_str!("data/small_arm.toml");

fn arm(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_arm"))
        .args(args)
        .output()
        .expect("the arm binary runs")
}

fn text(o: &Output) -> String {
    format!(
        "{}\n{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

fn tempdir(name: &str) -> ScratchDir {
    ScratchDir::new(&format!("arm-cli-{name}"))
}

/// Simulates `configs` configurations of [`ROBOT`] into `dir`, with `extra` options.
fn simulated(dir: &Path, configs: usize, extra: &[&str]) {
    let robot = dir.join("design.toml");
    std::fs::write(&robot, ROBOT).expect("write robot");
    let configs = configs.to_string();
    let mut args = vec![
        "simulate",
        "--robot",
        robot.to_str().expect("utf-8"),
        "--configs",
        &configs,
        "--seed",
        "5",
        "--out",
        dir.to_str().expect("utf-8"),
    ];
    args.extend_from_slice(extra);
    let o = arm(&args);
    assert!(o.status.success(), "{}", text(&o));
}

fn certify(dir: &Path, extra: &[&str]) -> Output {
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    let (robot, data, u) = (
        p("robot.toml"),
        p("measurements.csv"),
        p("uncertainty.toml"),
    );
    let mut args = vec![
        "certify",
        "--robot",
        &robot,
        "--measurements",
        &data,
        "--uncertainty",
        &u,
    ];
    args.extend_from_slice(extra);
    arm(&args)
}

#[test]
fn certify_keeps_the_truth_and_reports_in_json() {
    let dir = tempdir("truth");
    simulated(&dir, 12, &[]);
    let json = dir.join("report.json");
    let o = certify(&dir, &["--lsq", "--json", json.to_str().expect("utf-8")]);
    assert!(o.status.success(), "{}", text(&o));
    let out = text(&o);
    assert!(out.contains("verdict: consistent"), "{out}");
    assert!(out.contains("identifiability:"), "{out}");
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(&json).expect("report")).expect("json");
    let truth: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("truth.json")).expect("truth"))
            .expect("json");
    assert_eq!(report["status"], "consistent");
    let params = report["parameters"].as_array().expect("parameters");
    assert_eq!(params.len(), 24);
    for p in params {
        let name = p["name"].as_str().expect("name");
        let t = truth[name].as_f64().expect("truth value");
        let outer = &p["outer"];
        let (lo, hi) = (
            outer[0].as_f64().expect("lo"),
            outer[1].as_f64().expect("hi"),
        );
        assert!(lo <= t && t <= hi, "{name}: {t} outside [{lo}, {hi}]");
        if p["fixed"] == false {
            let inner = &p["inner"];
            assert!(
                lo <= inner[0].as_f64().expect("inner") && inner[1].as_f64().expect("inner") <= hi
            );
        }
        assert!(p["lsq"].is_f64(), "{name}: least squares value");
    }
}

#[test]
fn the_certificate_is_one_page_stating_the_certified_boxes_and_the_inputs() {
    let dir = tempdir("report");
    simulated(&dir, 12, &[]);
    let page_path = dir.join("certificate.html");
    let o = certify(&dir, &["--report", page_path.to_str().expect("utf-8")]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("certificate written to"), "{}", text(&o));
    let page = std::fs::read_to_string(&page_path).expect("the certificate");
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    let doc = roxmltree::Document::parse_with_options(&page, options).expect("well-formed XML");
    let cells = |row: roxmltree::Node| -> Vec<String> {
        row.children()
            .filter(|c| c.has_tag_name("td"))
            .map(|c| c.text().unwrap_or_default().to_string())
            .collect()
    };
    // The measurements' SHA-256 is what sha256sum prints for the file.
    let data = std::fs::read(dir.join("measurements.csv")).expect("data");
    let sha = calib_pipeline::html::sha256_hex(&data);
    assert!(doc.descendants().any(|n| n.text() == Some(sha.as_str())));
    // Every free parameter's printed outer box contains the truth, and its inner bounds.
    let truth: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("truth.json")).expect("truth"))
            .expect("json");
    let parse = |s: &str| -> (f64, f64) {
        let (a, b) = s
            .trim_matches(|c| c == '[' || c == ']')
            .split_once(", ")
            .expect("an interval");
        (a.parse().expect("lo"), b.parse().expect("hi"))
    };
    let mut rows = 0;
    for row in doc.descendants().filter(|n| n.has_tag_name("tr")) {
        let c = cells(row);
        let Some(t) = c.first().and_then(|name| truth[name].as_f64()) else {
            continue;
        };
        let (lo, hi) = parse(&c[3]);
        assert!(lo <= t && t <= hi, "{}: {t} outside {}", c[0], c[3]);
        let (a, b) = parse(&c[4]);
        assert!(
            lo <= a && b <= hi,
            "{}: inner {} outside outer {}",
            c[0],
            c[4],
            c[3]
        );
        rows += 1;
    }
    assert!(rows >= 10, "{rows} parameter rows");
    assert!(
        page.contains("least-squares solution"),
        "--report implies --lsq"
    );
    assert_eq!(
        doc.descendants().filter(|n| n.has_tag_name("svg")).count(),
        1
    );
    // An unwritable destination is an error naming it, and nothing is left behind.
    let bad = dir.join("missing").join("c.html");
    let o = certify(&dir, &["--report", bad.to_str().expect("utf-8")]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("cannot write the certificate"),
        "{}",
        text(&o)
    );
    assert!(!dir.join("missing").exists());
}

/// The simulator's own example: one configuration of the built-in arm moved 0.5 mm (50 times
/// the tracker's bound). Its first-order certificate weighs 19 of the 50 configurations, which
/// alone would read as a spread misfit; leaving out configuration 12 shows it is one bad reading,
/// and the conflict set names it.
#[test]
fn one_gross_outlier_among_many_weighed_is_still_named() {
    let dir = tempdir("gross_outlier");
    let d = dir.to_str().expect("utf-8");
    let o = arm(&[
        "simulate",
        "--configs",
        "50",
        "--seed",
        "7",
        "--outlier",
        "12:0.5",
        "--out",
        d,
    ]);
    assert!(o.status.success(), "{}", text(&o));
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    let o = arm(&[
        "certify",
        "--robot",
        &p("robot.toml"),
        "--measurements",
        &p("measurements.csv"),
        "--uncertainty",
        &p("uncertainty.toml"),
        "--json",
        &p("report.json"),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(p("report.json")).expect("report"))
            .expect("json");
    assert_eq!(report["spread"], false, "{}", text(&o));
    assert!(
        report["conflict"]
            .as_array()
            .is_some_and(|c| c.contains(&12.into())),
        "{report}"
    );
}

#[test]
fn a_shifted_configuration_is_proved_and_named_then_tolerated() {
    let dir = tempdir("outlier");
    simulated(&dir, 12, &["--outlier", "4:0.5"]);
    let strict_json = dir.join("strict.json");
    let o = certify(&dir, &["--json", strict_json.to_str().expect("utf-8")]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    let out = text(&o);
    assert!(
        out.contains("configuration 4 (measurements.csv line 5)"),
        "{out}"
    );
    // A few bad readings: the certificate weighs the bad one; the conflict set is searched.
    let strict: Value =
        serde_json::from_str(&std::fs::read_to_string(&strict_json).expect("report"))
            .expect("json");
    assert_eq!(strict["spread"], false);
    assert!(strict["conflict"]
        .as_array()
        .is_some_and(|c| c.contains(&4.into())));
    let json = dir.join("tolerated.json");
    let o = certify(
        &dir,
        &[
            "--max-outliers",
            "1",
            "--json",
            json.to_str().expect("utf-8"),
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(&json).expect("report")).expect("json");
    assert_eq!(report["outliers"], serde_json::json!([4]));

    // `auto` finds that one outlier is needed, and then certifies exactly as `--max-outliers 1`.
    let auto_json = dir.join("auto.json");
    let o = certify(
        &dir,
        &[
            "--max-outliers",
            "auto",
            "--json",
            auto_json.to_str().expect("utf-8"),
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        text(&o).contains("1 outlier tolerated (proved: with every configuration kept"),
        "{}",
        text(&o)
    );
    let auto: Value =
        serde_json::from_str(&std::fs::read_to_string(&auto_json).expect("report")).expect("json");
    assert_eq!(auto["outliers"], report["outliers"]);
    assert_eq!(auto["parameters"], report["parameters"]);
}

/// Every configuration off by about three times the position bounds (the simulated noise is 0.01
/// mm, the bounds 0.003 mm): no few readings are to blame. The verdict says so at once, with the
/// configurations the proof weighs and `--error-scale auto`, and no conflict set; the JSON keeps
/// its keys (`conflict: null`) and adds `support` and `spread`.
#[test]
fn a_misfit_spread_over_the_data_is_said_at_once_without_a_conflict_set() {
    let dir = tempdir("spread");
    simulated(&dir, 12, &[]);
    std::fs::write(
        dir.join("uncertainty.toml"),
        "joint_deg = 0.001\npos = 0.003\n",
    )
    .expect("write");
    let json = dir.join("report.json");
    let o = certify(&dir, &["--json", json.to_str().expect("utf-8")]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    let out = text(&o);
    assert!(
        out.contains("spread: the proof of emptiness weighs"),
        "{out}"
    );
    assert!(out.contains("of the 12 configurations"), "{out}");
    assert!(
        out.contains("--error-scale auto") && !out.contains("conflict:"),
        "{out}"
    );
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(&json).expect("report")).expect("json");
    assert_eq!(report["status"], "empty");
    assert!(report["conflict"].is_null(), "{report}");
    assert_eq!(report["spread"], true);
    let support = report["support"].as_array().expect("the support");
    assert!(support.len() > 6 && support.len() <= 12, "{support:?}");
    let verdict = report["verdict"].as_array().expect("sentences");
    assert!(verdict
        .iter()
        .any(|s| s.as_str().is_some_and(|s| s.starts_with("spread:"))));
}

#[test]
fn least_squares_runs_on_the_files() {
    let dir = tempdir("lsq");
    simulated(&dir, 12, &[]);
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    let (robot, measurements) = (p("robot.toml"), p("measurements.csv"));
    let lsq = |extra: &[&str]| {
        let mut args = vec!["lsq", "--robot", &robot, "--measurements", &measurements];
        args.extend_from_slice(extra);
        arm(&args)
    };
    let o = lsq(&[]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("residuals: rms"), "{}", text(&o));
    // Checked against error bounds: proved consistent with generous bounds, not with bounds far
    // below the noise; the verdict is printed, in the JSON and in the written file's header.
    for (pos, proved) in [(5.0, true), (1e-4, false)] {
        std::fs::write(p("u.toml"), format!("joint_deg = 0.001\npos = {pos}\n")).expect("write");
        let (u, json, out) = (p("u.toml"), p("lsq.json"), p("lsq.toml"));
        let o = lsq(&["--uncertainty", &u, "--json", &json, "--out", &out]);
        assert!(o.status.success(), "{}", text(&o));
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).expect("json")).expect("json");
        assert_eq!(json["consistent"], proved, "pos {pos}: {}", text(&o));
        let header = std::fs::read_to_string(&out).expect("toml");
        let says = if proved {
            "# proved consistent"
        } else {
            "# NOT proved consistent"
        };
        assert!(header.contains(says), "{header}");
        // The written file is the fit: checked again from the file, the same verdict.
        let fitted = calib_arm::files::read_robot(Path::new(&out)).expect("robot");
        let data =
            calib_arm::files::read_measurements(Path::new(&measurements), 3).expect("measurements");
        let u = calib_arm::simulate::Uncertainty {
            joint_deg: 0.001,
            pos,
        };
        assert_eq!(
            calib_arm::certification::is_consistent_arm(&fitted, &data.readings, &u),
            proved
        );
        // Only a proved fit is handed on to a controller: the other is refused, naming the file,
        // its line and the field, and nothing is written. (This 3-joint arm has no vendor chain
        // either: the library call tells the two refusals apart.)
        assert_eq!(
            calib_arm::files::read_exportable_robot(Path::new(&out)).is_ok(),
            proved
        );
        let urdf = p("lsq.urdf");
        let o = arm(&["export", "--robot", &out, "--urdf", &urdf]);
        assert!(!Path::new(&urdf).exists());
        assert_eq!(
            text(&o).contains("least_squares.proved_consistent"),
            !proved,
            "{}",
            text(&o)
        );
        if !proved {
            let line = header
                .lines()
                .position(|l| l.starts_with("proved_consistent = false"))
                .expect("the mark")
                + 1;
            let err = text(&o);
            assert!(
                err.contains(&format!("lsq.toml, line {line}"))
                    && err.contains("least_squares.proved_consistent")
                    && err.contains("arm certify --write-calibrated"),
                "{err}"
            );
        }
    }
}

/// A stream whose reading end is closed: every write to it fails (EPIPE), as under
/// `… | head -0`.
#[cfg(unix)]
fn closed_pipe() -> std::process::Stdio {
    let (writer, reader) = std::os::unix::net::UnixStream::pair().expect("a socket pair");
    drop(reader);
    std::os::fd::OwnedFd::from(writer).into()
}

#[cfg(unix)]
#[test]
fn a_closed_output_ends_the_program_quietly() {
    let dir = tempdir("pipe");
    simulated(&dir, 6, &[]);
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    // `arm lsq … | head -0`: the reader is gone before the program starts (a
    // pipe whose read end is already closed: no race with the first line).
    let child = Command::new(env!("CARGO_BIN_EXE_arm"))
        .args(["lsq", "--robot", &p("robot.toml")])
        .args(["--measurements", &p("measurements.csv")])
        .stdout(closed_pipe())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the arm binary runs");
    let o = child.wait_with_output().expect("the arm binary ends");
    assert!(!text(&o).contains("panicked"), "{}", text(&o));
    assert_eq!(
        o.status.code(),
        Some(calib_pipeline::CLOSED_OUTPUT_STATUS),
        "{}",
        text(&o)
    );
}

#[test]
fn bad_files_name_file_line_and_field_and_write_nothing() {
    let dir = tempdir("bad");
    simulated(&dir, 6, &[]);
    let json = dir.join("never.json");
    let robot = dir.join("robot.toml");
    let good = std::fs::read_to_string(&robot).expect("robot");
    // A non-numeric link length on the second joint.
    let bad = good.replacen("a = -400.0", "a = \"long\"", 1);
    std::fs::write(&robot, &bad).expect("write");
    let o = certify(&dir, &["--json", json.to_str().expect("utf-8")]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    let line = bad
        .lines()
        .position(|l| l.contains("\"long\""))
        .expect("edited line")
        + 1;
    assert!(
        err.contains("robot.toml") && err.contains(&format!("line {line}")),
        "{err}"
    );
    assert!(!json.exists());
    // A measurement row with a missing coordinate.
    std::fs::write(&robot, &good).expect("write");
    let data = dir.join("measurements.csv");
    let rows = std::fs::read_to_string(&data).expect("data");
    let cut: Vec<&str> = rows.lines().collect();
    let short = format!(
        "{}\n{}\n",
        cut[0],
        cut[1].rsplit_once(',').expect("comma").0
    );
    std::fs::write(&data, short).expect("write");
    let o = certify(&dir, &["--json", json.to_str().expect("utf-8")]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        err.contains("measurements.csv") && err.contains("line 2"),
        "{err}"
    );
    assert!(!json.exists());
}

/// The calibrated file `cal` (in `dir`, beside the simulated data) carries its certified set and
/// fits every configuration: with the joint errors of a weighted least-squares fit of each
/// configuration's reading (an independent computation: plain Gauss–Newton in floating point),
/// every joint error and every coordinate's residual is within its bound. Returns the file's arm,
/// the data and their error bounds.
fn assert_fits_every_configuration(
    dir: &Path,
    cal: &str,
) -> (
    calib_arm::Arm,
    calib_arm::files::Measurements,
    calib_arm::simulate::Uncertainty,
) {
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    let (calibrated, set) =
        calib_arm::files::read_calibrated(Path::new(&p(cal))).expect("a calibrated file");
    assert!(
        set.is_some(),
        "the calibrated file carries its certified set"
    );
    let data = calib_arm::files::read_measurements(
        Path::new(&p("measurements.csv")),
        calibrated.joints.len(),
    )
    .expect("data");
    let u = calib_arm::files::read_uncertainty(Path::new(&p("uncertainty.toml"))).expect("u");
    for (k, r) in data.readings.iter().enumerate() {
        let (joint_errors, residual) = fit_joint_errors(&calibrated, &r.joints_deg, &r.point, &u);
        assert!(
            joint_errors.iter().all(|e| e.abs() <= u.joint_deg)
                && residual.iter().all(|e| e.abs() <= u.pos),
            "configuration {}: joint errors {joint_errors:?} (bound {}), residual {residual:?} \
             (bound {})",
            k + 1,
            u.joint_deg,
            u.pos
        );
    }
    (calibrated, data, u)
}

#[test]
fn a_calibration_chosen_for_a_task_fits_every_measurement() {
    let dir = tempdir("task");
    simulated(&dir, 12, &[]);
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    let task = |file: &str, out: &str| {
        certify(
            &dir,
            &[
                "--json",
                &p("report.json"),
                "--write-calibrated",
                &p(out),
                "--task",
                &p(file),
            ],
        )
    };
    // A joint box and a list of configurations.
    std::fs::write(
        p("task.toml"),
        "q1 = [-10.0, 10.0]\nq2 = [-100.0, -80.0]\nq3 = [80.0, 100.0]\n",
    )
    .expect("write");
    std::fs::write(p("task.csv"), "q1,q2,q3\n0,-90,90\n5,-85,95\n-5,-95,85\n").expect("write");
    for (file, out) in [("task.toml", "box.toml"), ("task.csv", "rows.toml")] {
        let o = task(file, out);
        assert!(o.status.success(), "{}", text(&o));
        assert!(text(&o).contains("at the task's"), "{}", text(&o));
        let report: Value =
            serde_json::from_str(&std::fs::read_to_string(p("report.json")).expect("report"))
                .expect("json");
        assert_eq!(report["calibrated"]["rule"], "task", "{report}");
        assert_fits_every_configuration(&dir, out);
    }
    // A task file with the wrong columns: named with its line, exit 1, nothing written.
    std::fs::write(p("bad.csv"), "q1,q2\n0,-90\n").expect("write");
    let o = task("bad.csv", "never.toml");
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("bad.csv") && text(&o).contains("line 1"),
        "{}",
        text(&o)
    );
    assert!(!dir.join("never.toml").exists());
    // --task without --write-calibrated: a usage error.
    let o = certify(&dir, &["--task", &p("task.toml")]);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
}

#[test]
fn the_calibrated_arm_contains_the_certified_box_and_its_accuracy_is_bracketed() {
    let dir = tempdir("accuracy");
    simulated(&dir, 12, &[]);
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    let o = certify(
        &dir,
        &[
            "--json",
            &p("report.json"),
            "--write-calibrated",
            &p("cal.toml"),
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(p("report.json")).expect("report"))
            .expect("json");
    let cal = calib_arm::files::read_robot(Path::new(&p("cal.toml"))).expect("calibrated file");
    let prior = calib_arm::files::read_robot(Path::new(&p("robot.toml"))).expect("robot");
    for (((param, v), r), r0) in report["parameters"]
        .as_array()
        .expect("parameters")
        .iter()
        .zip(cal.nominal())
        .zip(cal.radius())
        .zip(prior.radius())
    {
        let (lo, hi) = (
            param["outer"][0].as_f64().expect("lo"),
            param["outer"][1].as_f64().expect("hi"),
        );
        // The calibrated value is a consistent vector, not the box's midpoint: its radius
        // reaches the farther end of the outer box (at most the prior's width).
        if r0 > 0.0 {
            assert!(
                v - r <= lo && hi <= v + r && r <= 2.0 * r0 * (1.0 + 1e-9),
                "{param}: {v} ± {r}"
            );
        } else {
            assert_eq!(r, 0.0);
        }
    }
    let (calibrated, data, u) = assert_fits_every_configuration(&dir, "cal.toml");
    std::fs::write(
        p("joints.toml"),
        "q1 = [-10.0, 10.0]\nq2 = [-100.0, -80.0]\nq3 = [80.0, 100.0]\n",
    )
    .expect("write");
    let accuracy = |joints: &str, json: &str| {
        arm(&[
            "accuracy",
            "--robot",
            &p("cal.toml"),
            "--before",
            &p("robot.toml"),
            "--joints",
            &p(joints),
            "--uncertainty",
            &p("uncertainty.toml"),
            "--max-boxes",
            "3000",
            "--json",
            &p(json),
            "--report",
            &p("accuracy.html"),
        ])
    };
    let o = accuracy("joints.toml", "accuracy.json");
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("calibration reduced the worst tool-point error"));
    let a: Value =
        serde_json::from_str(&std::fs::read_to_string(p("accuracy.json")).expect("accuracy"))
            .expect("json");
    for key in ["position", "before"] {
        let (upper, lower) = (
            a[key]["upper"].as_f64().expect("upper"),
            a[key]["lower"].as_f64().expect("lower"),
        );
        assert!(upper >= lower && lower > 0.0, "{key}: {upper} {lower}");
        assert_eq!(
            a[key]["worst"]["joints_deg"].as_array().map(Vec::len),
            Some(3)
        );
    }
    // After calibration the bounds hold over the certified set; before, over the prior box.
    assert_eq!(a["position"]["over"], "certified set", "{a}");
    assert_eq!(a["before"]["over"], "box", "{a}");
    // The improvement is the proved factor: before's lower bound over after's upper bound.
    let factor = a["before"]["lower"].as_f64().expect("lower")
        / a["position"]["upper"].as_f64().expect("upper");
    assert_eq!(a["improvement"].as_f64(), Some(factor), "{a}");
    accuracy_page_states(&p("accuracy.html"), &a, &p("joints.toml"));
    // At the measured configurations, each as given: a bracket per robot over exactly them, the
    // worst instances at one of them.
    let at_rows = |source: &str, file: &str| {
        arm(&[
            "accuracy",
            "--robot",
            &p("cal.toml"),
            "--before",
            &p("robot.toml"),
            source,
            &p(file),
            "--uncertainty",
            &p("uncertainty.toml"),
            "--json",
            &p("task.json"),
        ])
    };
    let o = at_rows("--measurements", "measurements.csv");
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        text(&o).contains("at the 12 configurations"),
        "{}",
        text(&o)
    );
    let t: Value = serde_json::from_str(&std::fs::read_to_string(p("task.json")).expect("task"))
        .expect("json");
    let rows: Vec<Vec<f64>> = data.readings.iter().map(|r| r.joints_deg.clone()).collect();
    for key in ["position", "before"] {
        assert_eq!(t[key]["boxes"].as_u64(), Some(12), "{t}");
        let q: Vec<f64> = t[key]["worst"]["joints_deg"]
            .as_array()
            .expect("joints")
            .iter()
            .map(|v| v.as_f64().expect("a joint"))
            .collect();
        assert!(
            rows.iter()
                .any(|r| r.iter().zip(&q).all(|(a, b)| (a - b).abs() <= 1e-9)),
            "{key}: {q:?} is not a measured configuration"
        );
    }
    let factor = t["before"]["lower"].as_f64().expect("lower")
        / t["position"]["upper"].as_f64().expect("upper");
    assert_eq!(t["improvement"].as_f64(), Some(factor), "{t}");
    // The report says the bounds hold at these configurations, not over their hull.
    assert_eq!(t["configurations"].as_u64(), Some(12), "{t}");
    // A joint box given as a task is refused: its bounds would hold at sample points only.
    let o = at_rows("--task", "joints.toml");
    assert!(
        !o.status.success() && text(&o).contains("--joints"),
        "{}",
        text(&o)
    );
    // A task file with a joint missing is named, with its line, and nothing is written.
    std::fs::write(p("task.csv"), "q1,q2,q3\n1,2,3\n4,5\n").expect("write");
    std::fs::remove_file(p("task.json")).expect("remove");
    let o = at_rows("--task", "task.csv");
    assert!(!o.status.success());
    assert!(
        text(&o).contains("task.csv") && text(&o).contains("line 3"),
        "{}",
        text(&o)
    );
    assert!(!Path::new(&p("task.json")).exists());
    // The measurement file's column options with a task would be ignored: refused, named.
    std::fs::write(p("task.csv"), "q1,q2,q3\n1,2,3\n4,5,6\n").expect("write");
    for (flag, value) in [("--rows", "1"), ("--joint-unit", "rad")] {
        let o = arm(&[
            "accuracy",
            "--robot",
            &p("cal.toml"),
            "--task",
            &p("task.csv"),
            flag,
            value,
            "--json",
            &p("task.json"),
        ]);
        assert!(
            !o.status.success() && text(&o).contains(flag) && text(&o).contains("--measurements"),
            "{}",
            text(&o)
        );
        assert!(!Path::new(&p("task.json")).exists());
    }
    // Likewise over the default joint box.
    let o = arm(&["accuracy", "--robot", &p("cal.toml"), "--rows", "1"]);
    assert!(
        !o.status.success() && text(&o).contains("--rows") && text(&o).contains("--joints"),
        "{}",
        text(&o)
    );
    // Predictions over the set: the true tracked point (truth.json, the simulator's geometry)
    // lies in every certified range, every measured point in its range with the error bounds.
    let predict = |measurements: &str| {
        arm(&[
            "predict",
            "--robot",
            &p("cal.toml"),
            "--measurements",
            &p(measurements),
            "--uncertainty",
            &p("uncertainty.toml"),
            "--json",
            &p("predictions.json"),
        ])
    };
    let o = predict("measurements.csv");
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let predicted: Value =
        serde_json::from_str(&std::fs::read_to_string(p("predictions.json")).expect("json"))
            .expect("json");
    assert_eq!(predicted["over"], "certified set");
    let truth: Value =
        serde_json::from_str(&std::fs::read_to_string(p("truth.json")).expect("truth"))
            .expect("json");
    let names = calib_arm::params::names(calibrated.joints.len());
    let x: Vec<f64> = names
        .iter()
        .map(|(name, unit)| {
            let v = truth[name].as_f64().expect("a true value");
            match unit {
                calib_arm::params::Unit::Deg => v.to_radians(),
                calib_arm::params::Unit::Mm => v,
            }
        })
        .collect();
    let rows = predicted["rows"].as_array().expect("rows");
    assert_eq!(rows.len(), data.readings.len());
    for (row, r) in rows.iter().zip(&data.readings) {
        let q: Vec<f64> = r.joints_deg.iter().map(|v| v.to_radians()).collect();
        let t = calib_arm::model::tracked_point(&x, &q).expect("a point");
        for (c, t) in t.iter().enumerate() {
            let range = &row["range"][c];
            let (lo, hi) = (
                range[0].as_f64().expect("lo"),
                range[1].as_f64().expect("hi"),
            );
            // The true point, computed in floating point: within a rounding of the range.
            assert!(
                lo - 1e-9 <= *t && *t <= hi + 1e-9,
                "row {}: {t} not in [{lo}, {hi}]",
                row["row"]
            );
        }
    }
    // A measured point moved by ten error bounds is named by row and file line; exit code 2.
    let measured = std::fs::read_to_string(p("measurements.csv")).expect("data");
    let mut lines: Vec<String> = measured.lines().map(String::from).collect();
    let mut cells: Vec<f64> = lines[3]
        .split(',')
        .map(|c| c.trim().parse().expect("a number"))
        .collect();
    let last = cells.len() - 1;
    cells[last] += 10.0 * u.pos;
    lines[3] = cells
        .iter()
        .map(|v| format!("{v:?}"))
        .collect::<Vec<_>>()
        .join(",");
    std::fs::write(p("moved.csv"), lines.join("\n") + "\n").expect("write");
    let o = predict("moved.csv");
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("row 3 ("), "{}", text(&o));
    let predicted: Value =
        serde_json::from_str(&std::fs::read_to_string(p("predictions.json")).expect("json"))
            .expect("json");
    assert_eq!(predicted["refuting"][0]["row"], 3, "{predicted}");
    assert_eq!(predicted["refuting"][0]["line"], 4, "{predicted}");
    // A bad joint space: file, line and field named, nothing written.
    std::fs::write(
        p("bad.toml"),
        "q1 = [-10.0, 10.0]\nq2 = [-80.0, -100.0]\nq3 = [80.0, 100.0]\n",
    )
    .expect("write");
    let o = accuracy("bad.toml", "never.json");
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        err.contains("bad.toml") && err.contains("line 2") && err.contains("q2"),
        "{err}"
    );
    assert!(!dir.join("never.json").exists());
}

/// The joint errors `e` (degrees) and the residual `r = p(q + e) - point` (mm) that minimise
/// `max(max_i |e_i| / joint_deg, max_c |r_c| / pos)` (successive linearisation, a numerical
/// Jacobian and a small linear program each step, in floating point): an independent check that
/// a parameter vector fits one configuration — one reading within the bounds making all three
/// coordinates agree.
fn fit_joint_errors(
    arm: &calib_arm::Arm,
    joints_deg: &[f64],
    point: &[f64; 3],
    u: &calib_arm::simulate::Uncertainty,
) -> (Vec<f64>, [f64; 3]) {
    use calib_core::{DenseSimplex, LpBackend, Polyhedron};
    let x = arm_model_parameters(arm);
    let residual = |e: &[f64]| -> [f64; 3] {
        let q: Vec<f64> = joints_deg
            .iter()
            .zip(e)
            .map(|(q, e)| (q + e).to_radians())
            .collect();
        let p = calib_arm::model::tracked_point(&x, &q).expect("3 to 7 joints");
        [p[0] - point[0], p[1] - point[1], p[2] - point[2]]
    };
    let n = joints_deg.len();
    let mut e = vec![0.0; n];
    let (mut lp, mut poly) = (DenseSimplex::default(), Polyhedron::default());
    for _ in 0..6 {
        let r = residual(&e);
        let jac: Vec<[f64; 3]> = (0..n)
            .map(|c| {
                let mut de = e.clone();
                de[c] += 1e-7;
                let rp = residual(&de);
                core::array::from_fn(|k| (rp[k] - r[k]) / 1e-7)
            })
            .collect();
        // Variables: the step d (degrees), then t; minimise t.
        let mut lo: Vec<f64> = vec![-10.0 * u.joint_deg; n];
        let mut hi: Vec<f64> = vec![10.0 * u.joint_deg; n];
        lo.push(0.0);
        hi.push(100.0);
        poly.reset(&lo, &hi);
        let mut row = vec![0.0; n + 1];
        for i in 0..n {
            for s in [1.0, -1.0] {
                // ±(e_i + d_i) <= t joint_deg
                row.iter_mut().for_each(|v| *v = 0.0);
                row[i] = s;
                row[n] = -u.joint_deg;
                poly.push_row(&row, -s * e[i]);
            }
        }
        for k in 0..3 {
            for s in [1.0, -1.0] {
                // ±(r_k + J_k d) <= t pos
                for c in 0..n {
                    row[c] = s * jac[c][k];
                }
                row[n] = -u.pos;
                poly.push_row(&row, -s * r[k]);
            }
        }
        let mut objective = vec![0.0; n + 1];
        objective[n] = 1.0;
        let (mut dual, mut primal) = (vec![0.0; poly.rows()], vec![0.0; n + 1]);
        lp.minimize(&poly, &objective, &mut dual, &mut primal);
        for c in 0..n {
            e[c] += primal[c];
        }
    }
    let r = residual(&e);
    (e, r)
}

/// The arm's parameters in the model's order and units (radians for angles).
fn arm_model_parameters(arm: &calib_arm::Arm) -> Vec<f64> {
    let units = calib_arm::params::names(arm.joints.len());
    arm.nominal()
        .iter()
        .zip(units)
        .map(|(v, (_, unit))| match unit {
            calib_arm::params::Unit::Deg => v.to_radians(),
            calib_arm::params::Unit::Mm => *v,
        })
        .collect()
}

#[test]
fn a_vendor_file_with_a_non_finite_number_is_refused_and_nothing_is_written() {
    let dir = tempdir("non-finite");
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    let urdf = r#"<robot name="r">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/>
  <joint name="shoulder_pan_joint" type="revolute"><parent link="base"/><child link="l1"/>
<origin xyz="0 0 0.2" rpy="0 0 0"/><axis xyz="0 0 1"/>
<limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="shoulder_lift_joint" type="continuous"><parent link="l1"/><child link="l2"/>
<origin xyz="0.3 0 0" rpy="0 0 0"/><axis xyz="0 1 0"/></joint>
  <joint name="elbow_joint" type="continuous"><parent link="l2"/><child link="l3"/>
<origin xyz="0.25 0.02 0" rpy="0 0 0"/><axis xyz="0 0 1"/></joint>
</robot>"#;
    // The good file imports (so that what follows tests the number, not the file).
    std::fs::write(p("good.urdf"), urdf).expect("write");
    let o = arm(&[
        "import",
        "--urdf",
        &p("good.urdf"),
        "--out",
        &p("good.toml"),
    ]);
    assert!(o.status.success(), "{}", text(&o));
    std::fs::write(
        p("nan.urdf"),
        urdf.replacen(r#"xyz="0.3 0 0""#, r#"xyz="0.3 nan 0""#, 1),
    )
    .expect("write");
    let o = arm(&[
        "import",
        "--urdf",
        &p("nan.urdf"),
        "--out",
        &p("never.toml"),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        err.contains("nan.urdf")
            && err.contains("joint 'shoulder_lift_joint' origin xyz")
            && err.contains("NaN"),
        "{err}"
    );
    assert!(!String::from_utf8_lossy(&o.stdout).contains("imported"));
    // UR's YAML spells an infinity `.inf`.
    let yaml = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/ur10_default_kinematics.yaml"),
    )
    .expect("yaml")
    .replacen("z: 0.1273", "z: .inf", 1);
    std::fs::write(p("inf.yaml"), yaml).expect("write");
    let o = arm(&[
        "import",
        "--ur-yaml",
        &p("inf.yaml"),
        "--out",
        &p("never.toml"),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        err.contains("inf.yaml") && err.contains("line 5") && err.contains("shoulder.z"),
        "{err}"
    );
    // Nothing written, not even a temporary file.
    let mut files: Vec<String> = std::fs::read_dir(&*dir)
        .expect("the directory")
        .map(|e| {
            e.expect("an entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    files.sort();
    assert_eq!(files, ["good.toml", "good.urdf", "inf.yaml", "nan.urdf"]);
}

/// The accuracy certificate (`arm accuracy --report`) is one well-formed page that states the
/// JSON's brackets (to the printed digits), the worst configurations, the proved improvement, a
/// figure, and the joint space file's SHA-256.
fn accuracy_page_states(page: &str, a: &Value, joints: &str) {
    let page = std::fs::read_to_string(page).expect("the accuracy certificate");
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    let doc = roxmltree::Document::parse_with_options(&page, options).expect("well-formed XML");
    let row = |first: &str| -> Vec<String> {
        doc.descendants()
            .filter(|n| n.has_tag_name("tr"))
            .map(|r| {
                r.children()
                    .filter(|c| c.has_tag_name("td"))
                    .map(|c| c.text().unwrap_or_default().to_string())
                    .collect::<Vec<_>>()
            })
            .find(|cells| cells.first().map(String::as_str) == Some(first))
            .unwrap_or_else(|| panic!("no row {first}"))
    };
    for (name, key) in [
        ("after calibration", "position"),
        ("before calibration", "before"),
    ] {
        let cells = row(name);
        let printed = |i: usize| cells[i].parse::<f64>().expect("a number");
        let (upper, lower) = (
            a[key]["upper"].as_f64().expect("upper"),
            a[key]["lower"].as_f64().expect("lower"),
        );
        // Printed to 1e-5, the upper bound rounded up and the lower one down: still bounds.
        assert!(
            upper <= printed(1) && printed(1) <= upper + 1e-5,
            "{name}: {cells:?} against {upper}"
        );
        assert!(
            lower - 1e-5 <= printed(2) && printed(2) <= lower,
            "{name}: {cells:?} against {lower}"
        );
    }
    let sha = calib_pipeline::html::sha256_hex(&std::fs::read(joints).expect("joints"));
    assert!(page.contains(&format!("SHA-256 {sha}")));
    assert!(page.contains("Calibration reduced the worst tool-point error at least"));
    // The proved factor is printed rounded down.
    let factor = a["improvement"].as_f64().expect("improvement");
    let printed = page
        .split("worst tool-point error at least ")
        .nth(1)
        .and_then(|t| t.split("-fold").next())
        .and_then(|t| t.parse::<f64>().ok())
        .expect("a printed factor");
    assert!(
        printed <= factor && factor - printed < 0.01 + 1e-12,
        "{printed} for {factor}"
    );
    assert_eq!(
        doc.descendants().filter(|n| n.has_tag_name("svg")).count(),
        1
    );
}

#[test]
fn a_calibration_registered_in_a_new_cell_carries_its_set_into_certify() {
    let dir = tempdir("carry");
    simulated(&dir, 12, &[]);
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    let calibrated = p("calibrated.toml");
    let o = certify(&dir, &["--rows", "1-6", "--write-calibrated", &calibrated]);
    assert!(o.status.success(), "{}", text(&o));
    let (data, here) = (p("measurements.csv"), p("here.toml"));
    let o = arm(&[
        "register",
        "--robot",
        &calibrated,
        "--measurements",
        &data,
        "--rows",
        "7-12",
        "--out",
        &here,
    ]);
    assert!(o.status.success(), "{}", text(&o));
    let written = std::fs::read_to_string(&here).expect("here.toml");
    assert!(written.contains("\n[carried_set]\n") && !written.contains("[certified_set]"));
    let json = p("carried.json");
    let (u, robot) = (p("uncertainty.toml"), here.clone());
    let o = arm(&[
        "certify",
        "--robot",
        &robot,
        "--measurements",
        &data,
        "--uncertainty",
        &u,
        "--rows",
        "7-12",
        "--json",
        &json,
        "--write-calibrated",
        &p("calibrated-here.toml"),
    ]);
    assert!(o.status.success(), "{}", text(&o));
    // The written file: the vector chosen over both series, the set in this frame (predict reads
    // it back, its points proved again).
    let o2 = arm(&[
        "predict",
        "--robot",
        &p("calibrated-here.toml"),
        "--measurements",
        &data,
        "--uncertainty",
        &u,
        "--rows",
        "7-12",
    ]);
    assert!(o2.status.success(), "{}", text(&o2));
    assert!(
        text(&o).contains("carried over: 6 configurations"),
        "{}",
        text(&o)
    );
    let report: Value =
        serde_json::from_str(&std::fs::read_to_string(&json).expect("json")).expect("valid");
    assert_eq!(report["carried_over"]["configurations"], 6);
    assert_eq!(report["status"], "consistent");
    // `predict` reads no carried set (its base is another frame's): the file predicts as any
    // registered file does.
    let o = arm(&[
        "predict",
        "--robot",
        &here,
        "--measurements",
        &data,
        "--uncertainty",
        &u,
        "--rows",
        "1-3",
    ]);
    assert!(o.status.success(), "{}", text(&o));
}

#[test]
fn rows_the_earlier_certification_tolerated_as_outliers_are_not_carried_over() {
    let dir = tempdir("carry-outlier");
    simulated(&dir, 14, &["--outlier", "3:0.5"]);
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    let (calibrated, data, here, u) = (
        p("calibrated.toml"),
        p("measurements.csv"),
        p("here.toml"),
        p("uncertainty.toml"),
    );
    let o = certify(
        &dir,
        &[
            "--rows",
            "1-10",
            "--max-outliers",
            "1",
            "--write-calibrated",
            &calibrated,
        ],
    );
    assert!(o.status.success(), "{}", text(&o));
    let register = [
        "register",
        "--robot",
        &calibrated,
        "--measurements",
        &data,
        "--rows",
        "11-14",
        "--out",
        &here,
    ];
    let o = arm(&register);
    assert!(o.status.success(), "{}", text(&o));
    let o = arm(&[
        "certify",
        "--robot",
        &here,
        "--measurements",
        &data,
        "--uncertainty",
        &u,
        "--rows",
        "11-14",
    ]);
    // The outlier (row 3) stays out: the two series are consistent, not proved empty by it.
    assert!(o.status.success(), "{}", text(&o));
    let out = text(&o);
    assert!(
        out.contains("carried over: 9 configurations")
            && out.contains("1 stored row the earlier certification tolerated as outliers"),
        "{out}"
    );
}
