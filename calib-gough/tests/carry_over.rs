//! End-to-end tests of a calibration that carries over (`gough certify --robot calibrated.toml`
//! with new measurements): the stored rows join the new ones, the set narrows and keeps the
//! truth, a second round carries both series, a contradiction is proved and its stored rows
//! named, and a stored set that cannot carry over is a clear error.

use crate::support::{gough, simulate_configs, tempdir, truth_values};
use std::path::{Path, PathBuf};
use std::process::Output;

/// Twelve configurations of the built-in hexapod ([`simulate_configs`]).
fn simulate12(dir: &Path, seed: u64, extra: &[&str]) {
    simulate_configs(dir, 12, seed, extra);
}

/// `gough certify --robot ROBOT` on the measurements and error bounds of `data`, with the JSON
/// report at `json` and `extra`.
fn certify_with(robot: &Path, data: &Path, json: &Path, extra: &[&str]) -> Output {
    let f = |n: &str| data.join(n).to_str().unwrap().to_string();
    let (m, u) = (f("measurements.csv"), f("uncertainty.toml"));
    let mut args = vec!["certify", "--robot", robot.to_str().unwrap()];
    args.extend(["--measurements", &m, "--uncertainty", &u]);
    args.extend(["--json", json.to_str().unwrap()]);
    args.extend_from_slice(extra);
    gough(&args)
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The outer box of leg `i` (0-based) in a JSON report.
fn outer(rep: &serde_json::Value, i: usize) -> Vec<(f64, f64)> {
    rep["legs"][i]["outer"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| (b[0].as_f64().unwrap(), b[1].as_f64().unwrap()))
        .collect()
}

/// The number of stored rows per leg of a calibrated robot file.
fn stored_rows(file: &Path) -> Vec<usize> {
    let robot = calib_gough::files::read_robot_file(file).unwrap();
    robot
        .sets
        .iter()
        .map(|s| s.as_ref().map_or(0, |s| s.measurements.len()))
        .collect()
}

fn ok(out: &Output) -> String {
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    stdout
}

/// Three series of the same hexapod, A, B, C, 12 configurations each.
struct Series {
    dir: crate::scratch_dir::ScratchDir,
    a: PathBuf,
    b: PathBuf,
    c: PathBuf,
}

fn three_series(name: &str) -> Series {
    let dir = tempdir(name);
    let [a, b, c] = ["a", "b", "c"].map(|s| dir.join(s));
    simulate12(&a, 21, &[]);
    simulate12(&b, 22, &[]);
    simulate12(&c, 23, &[]);
    Series { dir, a, b, c }
}

#[test]
fn a_calibration_carries_over_to_new_measurements_and_again() {
    let s = three_series("carry");
    let d = |n: &str| s.dir.join(n);
    // Round 0: series A alone, written as a calibrated file; B alone for comparison, from the
    // same boxes (the calibrated file without its certified sets: B's own prior box would cut
    // B's set where the combined certification does not).
    ok(&certify_with(
        &s.a.join("robot.toml"),
        &s.a,
        &d("a.json"),
        &["--write-calibrated", d("cal_a.toml").to_str().unwrap()],
    ));
    let legs = calib_gough::files::read_robot(&d("cal_a.toml")).unwrap();
    let boxes_only = calib_gough::calibrated::robot_toml(&legs, &[], "cal_a.toml's boxes");
    std::fs::write(d("boxes_a.toml"), boxes_only).unwrap();
    ok(&certify_with(&d("boxes_a.toml"), &s.b, &d("b.json"), &[]));
    // Round 1: the calibrated file with series B.
    let stdout = ok(&certify_with(
        &d("cal_a.toml"),
        &s.b,
        &d("ab.json"),
        &["--write-calibrated", d("cal_ab.toml").to_str().unwrap()],
    ));
    assert!(
        stdout.contains("carried over: 12 stored configurations of")
            && stdout.contains("cal_a.toml join the 12 new ones"),
        "{stdout}"
    );
    assert_eq!(stdout.matches("carried over").count(), 1, "{stdout}");
    assert_eq!(stored_rows(&d("cal_a.toml")), vec![12; 6]);
    assert_eq!(stored_rows(&d("cal_ab.toml")), vec![24; 6]);
    let truth = json(&s.a.join("truth.json"));
    let (a, b, ab) = (json(&d("a.json")), json(&d("b.json")), json(&d("ab.json")));
    for i in 0..6 {
        let leg = &ab["legs"][i];
        assert_eq!(leg["status"], "consistent", "leg {}", i + 1);
        assert_eq!(leg["carried_over"]["first"], 13);
        assert_eq!(leg["carried_over"]["rows"].as_array().unwrap().len(), 12);
        let t = truth_values(&truth, i);
        let (oa, ob, oab) = (outer(&a, i), outer(&b, i), outer(&ab, i));
        for j in 0..7 {
            let (lo, hi) = oab[j];
            assert!(
                lo <= t[j] && t[j] <= hi,
                "leg {} param {j}: truth outside",
                i + 1
            );
            // The combined set lies in each set alone; each outer box is within the hull's
            // tolerance (5%) of its set's range.
            let w = hi - lo;
            for (name, o) in [("A", oa[j]), ("B", ob[j])] {
                assert!(
                    w <= 1.05 * (o.1 - o.0) * (1.0 + 1e-12),
                    "leg {} param {j}: {w} wider than {name} alone, {}",
                    i + 1,
                    o.1 - o.0
                );
            }
        }
    }
    // The calibrated geometry of the combined file fits every row of both series (checked by
    // the exhaustive corner test, independently of the kernel).
    let file = calib_gough::files::read_robot_file(&d("cal_ab.toml")).unwrap();
    let read = |dir: &Path| {
        let m = calib_gough::files::read_measurements(&dir.join("measurements.csv"), 6);
        let u = calib_gough::files::read_uncertainty(&dir.join("uncertainty.toml"));
        (m.unwrap(), u.unwrap())
    };
    let ((ma, ua), (mb, ub)) = (read(&s.a), read(&s.b));
    for (i, spec) in file.legs.iter().enumerate() {
        let mut boxes = calib_gough::leg_boxes(&mb.configs, &ub, i);
        boxes.extend(calib_gough::leg_boxes(&ma.configs, &ua, i));
        let p = spec.nominal.params();
        assert!(
            calib_core::is_consistent_by_corners(&calib_gough::GoughLeg, &p, &boxes),
            "leg {}: the calibrated geometry misfits a row",
            i + 1
        );
    }
    // Round 2: the combined file with series C carries both earlier series.
    let stdout = ok(&certify_with(
        &d("cal_ab.toml"),
        &s.c,
        &d("abc.json"),
        &["--write-calibrated", d("cal_abc.toml").to_str().unwrap()],
    ));
    assert!(stdout.contains("carried over: 24 stored"), "{stdout}");
    assert_eq!(stored_rows(&d("cal_abc.toml")), vec![36; 6]);
    let abc = json(&d("abc.json"));
    for i in 0..6 {
        let t = truth_values(&truth, i);
        for (j, (lo, hi)) in outer(&abc, i).into_iter().enumerate() {
            assert!(lo <= t[j] && t[j] <= hi, "round 2, leg {} param {j}", i + 1);
        }
    }
}

#[test]
fn new_rows_of_another_geometry_prove_the_carried_set_empty() {
    let s = three_series("carry-contradicted");
    let d = |n: &str| s.dir.join(n);
    ok(&certify_with(
        &s.a.join("robot.toml"),
        &s.a,
        &d("a.json"),
        &["--write-calibrated", d("cal_a.toml").to_str().unwrap()],
    ));
    // Series B measured on another hexapod: its base 3 mm further along x (every position
    // reading 0.3 cm smaller is the same robot with every `a_x` 0.3 cm larger). Alone it is
    // consistent; with the stored rows of A, no geometry fits.
    let csv = s.b.join("measurements.csv");
    let text = std::fs::read_to_string(&csv).unwrap();
    let moved: Vec<String> = text
        .lines()
        .enumerate()
        .map(|(k, line)| match line.split_once(',') {
            Some((px, rest)) if k > 0 => {
                format!("{:?},{rest}", px.parse::<f64>().unwrap() - 0.3)
            }
            _ => line.to_string(),
        })
        .collect();
    std::fs::write(&csv, moved.join("\n") + "\n").unwrap();
    let wide = std::fs::read_to_string(s.b.join("robot.toml"))
        .unwrap()
        .replace("radius = 0.1\n", "radius = 0.5\n");
    std::fs::write(d("wide.toml"), wide).unwrap();
    let alone = certify_with(&d("wide.toml"), &s.b, &d("b.json"), &["--fast"]);
    let stdout = String::from_utf8_lossy(&alone.stdout);
    assert_eq!(alone.status.code(), Some(0), "{stdout}");
    let out = certify_with(&d("cal_a.toml"), &s.b, &d("ab.json"), &["--fast"]);
    assert_eq!(
        out.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let ab = json(&d("ab.json"));
    for leg in ab["legs"].as_array().unwrap() {
        assert_eq!(leg["status"], "empty", "{leg}");
    }
}

#[test]
fn a_conflict_names_stored_rows_as_rows_of_the_calibrated_file() {
    let dir = tempdir("carry-conflict");
    let d = |n: &str| dir.join(n);
    let a = dir.join("a");
    simulate12(&a, 11, &[]);
    ok(&certify_with(
        &a.join("robot.toml"),
        &a,
        &d("a.json"),
        &["--write-calibrated", d("cal_a.toml").to_str().unwrap()],
    ));
    // Leg 1's reading in configuration 3 of a new series is 40 µm off (8 times its bound).
    let bad = dir.join("bad");
    simulate12(&bad, 13, &["--outlier", "3:1:0.004"]);
    let out = certify_with(&d("cal_a.toml"), &bad, &d("bad.json"), &["--legs", "1"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(2), "{stdout}");
    let leg = &json(&d("bad.json"))["legs"][0];
    assert_eq!(leg["status"], "empty");
    let first = leg["carried_over"]["first"].as_u64().unwrap();
    assert_eq!(first, 13);
    let conflict: Vec<u64> = leg["conflict"]
        .as_array()
        .expect("a conflict set")
        .iter()
        .map(|c| c.as_u64().unwrap())
        .collect();
    assert!(conflict.contains(&3), "{conflict:?}");
    // The bad reading conflicts with rows of the earlier series, and the terminal names each
    // by its row in the calibrated file (configuration 12 + k is stored row k here).
    let stored: Vec<String> = conflict
        .iter()
        .filter(|&&c| c >= first)
        .map(|&c| leg["carried_over"]["rows"][(c - first) as usize].to_string())
        .collect();
    assert!(!stored.is_empty(), "{conflict:?}");
    let rows = format!(
        "stored row{} {} of cal_a.toml",
        if stored.len() == 1 { "" } else { "s" },
        stored.join(", ")
    );
    let conflict_line = stdout.lines().find(|l| l.starts_with("conflict:")).unwrap();
    assert!(conflict_line.contains(&rows), "{conflict_line}");
    assert!(
        conflict_line.contains("measurements.csv line 4"),
        "{conflict_line}"
    );
}

/// Certifies series B against the calibrated file of series A after `edit` changed it: a clear
/// error (exit 1, no panic) naming the file and each of `expect`.
fn refuses(name: &str, edit: impl Fn(String) -> String, expect: &[&str]) {
    let dir = tempdir(name);
    let (a, b) = (dir.join("a"), dir.join("b"));
    simulate12(&a, 21, &[]);
    simulate12(&b, 22, &[]);
    let cal = dir.join("cal_a.toml");
    let out = certify_with(
        &a.join("robot.toml"),
        &a,
        &dir.join("a.json"),
        &["--fast", "--write-calibrated", cal.to_str().unwrap()],
    );
    ok(&out);
    let text = std::fs::read_to_string(&cal).unwrap();
    std::fs::write(&cal, edit(text)).unwrap();
    let json = dir.join("ab.json");
    let out = certify_with(&cal, &b, &json, &[]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{name}: {err}");
    assert!(!err.contains("panicked"), "{name}: {err}");
    assert!(err.contains("cal_a.toml"), "{name}: {err}");
    for e in expect {
        assert!(err.contains(e), "{name}: `{e}` not in: {err}");
    }
    assert!(!json.exists(), "{name}: a report was written");
}

/// `text` with the rows of the first stored `measurements` table changed by `row`.
fn first_measurements(text: String, row: impl Fn(Vec<&str>) -> Vec<String>) -> String {
    let mut inside = false;
    let mut done = false;
    let mut out = String::new();
    for line in text.lines() {
        if !done && line.starts_with("measurements = [") {
            inside = true;
        } else if inside && line == "]" {
            (inside, done) = (false, true);
        } else if inside {
            let cells = line
                .trim()
                .strip_prefix("[[")
                .unwrap()
                .strip_suffix("]],")
                .unwrap();
            let changed = row(cells.split("], [").collect());
            out.push_str(&format!("  [[{}]],\n", changed.join("], [")));
            continue;
        }
        out.push_str(line);
        out.push('\n');
    }
    out
}

#[test]
fn a_stored_set_that_cannot_carry_over_is_a_clear_error() {
    // Seven quantities per row (a Rodrigues series) against axis–angle measurements.
    refuses(
        "carry-quantities",
        |t| {
            first_measurements(t, |mut cells| {
                cells.remove(6);
                cells.into_iter().map(String::from).collect()
            })
        },
        &[
            "leg[1].certified_set.measurements",
            "7 measured quantities",
            "Rodrigues",
        ],
    );
    // A bound that is not a number.
    refuses(
        "carry-nan",
        |t| {
            first_measurements(t, |cells| {
                let mut cells: Vec<String> = cells.into_iter().map(String::from).collect();
                cells[0] = "nan, 1.0".into();
                cells
            })
        },
        &["leg[1].certified_set.measurements[1]", "finite"],
    );
    // A leg box moved off its stored set: the file contradicts itself.
    refuses(
        "carry-moved",
        |t| {
            let (head, tail) = t.split_once("\na = [").unwrap();
            let (x, rest) = tail.split_once(',').unwrap();
            let moved = x.parse::<f64>().unwrap() + 1.0;
            format!("{head}\na = [{moved:?},{rest}")
        },
        &["leg[1].certified_set.boxes", "contradicts itself"],
    );
}

#[test]
fn the_error_scale_with_stored_rows_scales_the_new_rows_only() {
    // A's calibrated file carried to B: the bracket of B's bounds with A's rows as stored is
    // proved (consistent at its top, with the stored rows), and no lower than B's alone, which
    // has fewer rows to fit (a consistent factor with both is consistent without A's rows).
    let dir = tempdir("carry-scale");
    let (a, b) = (dir.join("a"), dir.join("b"));
    simulate12(&a, 31, &[]);
    // B's noise four times its declared bounds: the bracket is well above 0.
    simulate12(&b, 32, &["--noise-scale", "4"]);
    let d = |n: &str| dir.join(n);
    ok(&certify_with(
        &a.join("robot.toml"),
        &a,
        &d("a.json"),
        &[
            "--legs",
            "2",
            "--write-calibrated",
            d("cal_a.toml").to_str().unwrap(),
        ],
    ));
    let scale = [
        "--legs",
        "2",
        "--fast",
        "--error-scale",
        "auto",
        "--scale-bounds",
        "all",
    ];
    ok(&certify_with(&d("cal_a.toml"), &b, &d("ab.json"), &scale));
    ok(&certify_with(
        &b.join("robot.toml"),
        &b,
        &d("b.json"),
        &scale,
    ));
    let (ab, alone) = (json(&d("ab.json")), json(&d("b.json")));
    let (with, without) = (&ab["error_scale"], &alone["error_scale"]);
    let s = |j: &serde_json::Value, k: &str| j[k].as_f64().unwrap();
    assert!(s(with, "s_hi") >= s(without, "s_lo"), "{with}\n{without}");
    // The report lists the certified legs only: leg 2 first.
    assert_eq!(ab["legs"][0]["status"], "consistent");
    assert_eq!(
        ab["legs"][0]["carried_over"]["rows"]
            .as_array()
            .unwrap()
            .len(),
        12
    );
}
