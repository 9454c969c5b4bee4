//! Experiment design (`gough design`): designed poses lie in the workspace, the predicted widths
//! are the certified widths of the simulated data written to disk (truth inside), a design beats
//! random poses on a fixed seed, `--extend` keeps the measured data, and bad files are errors
//! naming file, line and field with nothing written.

use crate::support;

use calib_gough::certification::{certify_legs, CertifyOptions};
use calib_gough::design::{design, geometric_mean, predict, DesignRequest};
use calib_gough::files::{parse_measurements, read_poses, LegSpec};
use calib_gough::measurement::Uncertainty;
use calib_gough::simulate::{builtin_hexapod, data_set_files, simulate_at};
use calib_gough::workspace::Workspace;
use calib_pipeline::design::Criterion;
use std::path::Path;
use support::{gough, simulate, tempdir};

fn robot() -> Vec<LegSpec> {
    calib_gough::design::builtin_robot()
}

fn widths(r: &[calib_gough::certification::LegResult]) -> Vec<f64> {
    r.iter()
        .flat_map(|l| l.outer.expect("consistent").map(|v| v.wid()))
        .collect()
}

#[test]
fn a_design_beats_random_poses_and_its_prediction_is_a_certification_of_the_data_on_disk() {
    let (robot, u, w) = (robot(), Uncertainty::PAPER, Workspace::SIMULATOR);
    let request = DesignRequest {
        configs: 12,
        candidates: 400,
        criterion: Criterion::Certified,
        seed: 5,
    };
    let d = design(&robot, &u, &w, &request, &[], &|| {}).unwrap();
    let legs = builtin_hexapod();
    assert_eq!(d.poses.len(), 12);
    assert!(d.poses.iter().all(|p| w.contains(p, &legs)));
    let designed = predict(&robot, &u, &legs, &d.poses, &[], 5).unwrap();
    let random = predict(&robot, &u, &legs, &d.random, &[], 5).unwrap();
    let (gd, gr) = (
        geometric_mean(widths(&designed)),
        geometric_mean(widths(&random)),
    );
    assert!(gd * 1.3 < gr, "designed {gd} random {gr}");
    // The first-order widths with every candidate measured bound the design's first-order ones.
    for leg in &d.first_order {
        for j in 0..7 {
            assert!(leg[2][j] <= leg[0][j] * (1.0 + 1e-9), "{leg:?}");
        }
    }
    // The prediction is what certifying the simulated data written to disk gives, and it holds
    // the truth (the nominal geometry).
    let sim = simulate_at(&legs, &d.poses, 5, u, 1.0, 0.0);
    let [(_, csv), ..] = data_set_files(&sim, 5, 1.0, &[]);
    let data = parse_measurements(Path::new("measurements.csv"), &csv, 6).unwrap();
    let certified = certify_legs(
        &robot,
        &data.configs,
        &u,
        &CertifyOptions::default(),
        &|| {},
    )
    .unwrap();
    for (p, c) in designed.iter().zip(&certified) {
        assert_eq!(p.outer, c.outer);
        let outer = p.outer.unwrap();
        let truth = legs[p.leg].params();
        assert!(
            (0..7).all(|j| outer[j].contains(truth[j])),
            "leg {}",
            p.leg + 1
        );
    }
}

#[test]
fn the_command_writes_poses_in_the_workspace_and_extends_measured_data() {
    let dir = tempdir("design");
    let ws = dir.join("workspace.toml");
    std::fs::write(
        &ws,
        "x = [-3, 3]\ny = [-4, 2]\nz = [56, 62]\ntilt_deg = 10\nstroke = [0, 15]\n",
    )
    .unwrap();
    let out = dir.join("poses.csv");
    let o = gough(&[
        "design",
        "--workspace",
        ws.to_str().unwrap(),
        "--configs",
        "8",
        // What this test checks is the command's output, not the design's quality (the
        // library's test above): few candidates.
        "--candidates",
        "40",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        stdout.contains("geometric mean") && stdout.contains("a_z and l"),
        "{stdout}"
    );
    let poses = read_poses(&out).unwrap();
    let w = calib_gough::workspace::read_workspace(&ws).unwrap();
    assert_eq!(poses.len(), 8);
    assert!(poses.iter().all(|p| w.contains(p, &builtin_hexapod())));
    // Extending a measured data set: its robot file, and new poses only.
    let data = dir.join("data");
    simulate(&data, 2, &[]);
    let next = dir.join("next.csv");
    let f = |n: &str| data.join(n).to_str().unwrap().to_string();
    let o = gough(&[
        "design",
        "--robot",
        &f("robot.toml"),
        "--uncertainty",
        &f("uncertainty.toml"),
        "--extend",
        &f("measurements.csv"),
        "--configs",
        "7",
        "--candidates",
        "30",
        "--out",
        next.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(stdout.contains("after the 21 measured"), "{stdout}");
    assert_eq!(read_poses(&next).unwrap().len(), 7);
    // Rodrigues data need their q half-width: without --uncertainty, a clear error, no output.
    let text = std::fs::read_to_string(data.join("measurements.csv")).unwrap();
    let mut rodrigues = String::from("px,py,pz,q1,q2,q3,L1,L2,L3,L4,L5,L6\n");
    for line in text.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|c| c.parse().unwrap()).collect();
        let t = (v[6].to_radians() / 2.0).tan();
        let row: Vec<String> = v[..3]
            .iter()
            .copied()
            .chain(v[3..6].iter().map(|a| a * t))
            .chain(v[7..].iter().copied())
            .map(|x| format!("{x:?}"))
            .collect();
        rodrigues += &(row.join(",") + "\n");
    }
    let q_file = dir.join("rodrigues.csv");
    std::fs::write(&q_file, rodrigues).unwrap();
    let none = dir.join("none.csv");
    let o = gough(&[
        "design",
        "--robot",
        &f("robot.toml"),
        "--extend",
        q_file.to_str().unwrap(),
        "--configs",
        "3",
        "--candidates",
        "50",
        "--out",
        none.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("Rodrigues") && stderr.contains("--uncertainty"),
        "{stderr}"
    );
    assert!(!none.exists());
}

#[test]
fn bad_workspace_files_name_file_line_and_field_and_write_nothing() {
    let dir = tempdir("design-bad");
    let out = dir.join("poses.csv");
    for (text, expect) in [
        (
            "x = [-5, 5]\ny = [5, -5]\nz = [55, 65]\ntilt_deg = 15\n",
            "line 2, field `y`",
        ),
        (
            "x = [-5, 5]\ny = [-5, 5]\nz = [55, 65]\ntilt_deg = -1\n",
            "line 4, field `tilt_deg`",
        ),
        (
            "x = [-5, 5]\ny = [-5, 5]\nz = [55, 65]\n",
            "missing field `tilt_deg`",
        ),
        (
            "x = [-5, 5]\ny = [-5, 5]\nz = [55, 65]\ntilt_deg = 15\nstroke = [40, 41]\n",
            "stroke",
        ),
    ] {
        let ws = dir.join("workspace.toml");
        std::fs::write(&ws, text).unwrap();
        let o = gough(&[
            "design",
            "--workspace",
            ws.to_str().unwrap(),
            "--candidates",
            "50",
            "--configs",
            "7",
            "--out",
            out.to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{stderr}");
        assert!(
            stderr.contains("workspace.toml") || stderr.contains("stroke"),
            "{stderr}"
        );
        assert!(stderr.contains(expect), "{expect}: {stderr}");
        assert!(!out.exists(), "{stderr}");
    }
}
