//! The tests of `calib_gough::files`.

use crate::scratch_dir::ScratchDir;
use calib_gough::files::*;
use calib_gough::measurement::Orientation;
use std::path::{Path, PathBuf};

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn robot_accepts_scalar_and_per_parameter_radii() {
    let dir = ScratchDir::new("gough-files-1");
    let p = write(
        &dir,
        "robot-ok.toml",
        "[[leg]]\na = [1, 2, 3]\nb = [4, 5, 6]\nl = 7.5\nradius = 0.1\n\n\
         [[leg]]\na = [1, 2, 3]\nb = [4, 5, 6]\nl = 7\nradius = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7]\n",
    );
    let legs = read_robot(&p).unwrap();
    assert_eq!(legs.len(), 2);
    assert_eq!(
        legs[0].nominal.params(),
        [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.5]
    );
    assert_eq!(legs[0].radius, [0.1; 7]);
    assert_eq!(legs[1].radius[6], 0.7);
    let bad = write(
        &dir,
        "robot-short.toml",
        "[[leg]]\na = [1, 2]\nb = [4, 5, 6]\nl = 7\nradius = 0.1\n",
    );
    let e = read_robot(&bad).unwrap_err();
    assert_eq!(e.line, Some(2), "{e}");
}

#[test]
fn measurements_in_both_orientation_formats_and_fewer_legs() {
    let dir = ScratchDir::new("gough-files-2");
    let rows: String = (0..7)
        .map(|k| format!("{k},0,60,0,0,1,5,10,11\n"))
        .collect();
    let p = write(
        &dir,
        "m-aa.csv",
        &format!("px,py,pz,ax,ay,az,angle_deg,L1,L2\n{rows}"),
    );
    let m = read_measurements(&p, 2).unwrap();
    assert!(!m.rodrigues && m.configs.len() == 7);
    assert_eq!(m.configs[3].lengths, vec![10.0, 11.0]);
    let rows: String = (0..8)
        .map(|k| format!("{k},0,60,0.01,0,0.02,10\n"))
        .collect();
    let p = write(&dir, "m-q.csv", &format!("px,py,pz,q1,q2,q3,L1\n{rows}"));
    let m = read_measurements(&p, 1).unwrap();
    assert!(m.rodrigues);
    assert_eq!(
        m.configs[0].orientation,
        Orientation::Rodrigues([0.01, 0.0, 0.02])
    );
    // Leg-count mismatch names both counts.
    let e = read_measurements(&p, 6).unwrap_err();
    assert!(e.message.contains("6 legs") && e.line == Some(1), "{e}");
    // A bad number names its line and column.
    let p = write(
        &dir,
        "m-bad.csv",
        &format!("px,py,pz,q1,q2,q3,L1\n{rows}1,2,3,0,0,x,5\n"),
    );
    let e = read_measurements(&p, 1).unwrap_err();
    assert_eq!((e.line, e.field.as_deref()), (Some(10), Some("q3")), "{e}");
}

#[test]
fn uncertainty_requires_what_the_measurements_need() {
    let dir = ScratchDir::new("gough-files-3");
    let p = write(&dir, "u.toml", "pos = 0.0005\nlen = 0.0005\nq = 1e-5\n");
    let u = read_uncertainty(&p).unwrap();
    assert!(check_uncertainty(&p, &u, true).is_ok());
    let e = check_uncertainty(&p, &u, false).unwrap_err();
    assert_eq!(e.field.as_deref(), Some("axis"));
    let p = write(&dir, "u-neg.toml", "pos = 0.0005\nlen = -1\n");
    assert_eq!(
        read_uncertainty(&p).unwrap_err().field.as_deref(),
        Some("len")
    );
}

#[test]
fn non_finite_numbers_are_refused_with_line_and_field() {
    let robot = Path::new("robot.toml");
    let good = "[[leg]]\na = [1, 2, 3]\nb = [4, 5, 6]\nl = 7.5\nradius = 0.1\n";
    // TOML's spellings of NaN and the infinities; `-1e999` reads as minus infinity.
    for bad in ["nan", "-nan", "inf", "+inf", "-inf", "-1e999"] {
        for (from, to, line, field) in [
            (
                "a = [1, 2, 3]",
                format!("a = [1, {bad}, 3]"),
                2,
                "leg[1].ay",
            ),
            (
                "b = [4, 5, 6]",
                format!("b = [4, 5, {bad}]"),
                3,
                "leg[1].bz",
            ),
            ("l = 7.5", format!("l = {bad}"), 4, "leg[1].l"),
            (
                "radius = 0.1",
                format!("radius = {bad}"),
                5,
                "leg[1].radius",
            ),
        ] {
            let e = parse_robot(robot, &good.replace(from, &to)).unwrap_err();
            assert_eq!(
                (e.line, e.field.as_deref()),
                (Some(line), Some(field)),
                "{bad}: {e}"
            );
            assert!(e.message.contains("expected a finite number"), "{bad}: {e}");
        }
        let u = Path::new("uncertainty.toml");
        let e = parse_uncertainty(u, &format!("pos = 0.1\nlen = 0.1\nq = {bad}\n")).unwrap_err();
        assert_eq!(
            (e.line, e.field.as_deref()),
            (Some(3), Some("q")),
            "{bad}: {e}"
        );
    }
    let f = Path::new("measurements.csv");
    let row = "0,0,60,0.01,0,0.02,10\n";
    for bad in ["nan", "NaN", "inf", "-inf", "infinity", "1e999", "-1e999"] {
        let text = format!(
            "px,py,pz,q1,q2,q3,L1\n{}0,0,60,0.01,{bad},0.02,10\n",
            row.repeat(7)
        );
        let e = parse_measurements(f, &text, 1).unwrap_err();
        assert_eq!(
            (e.line, e.field.as_deref()),
            (Some(9), Some("q2")),
            "{bad}: {e}"
        );
        let e = parse_poses(
            Path::new("poses.csv"),
            &format!("px,py,pz,ax,ay,az,angle_deg\n0,0,{bad},0,0,1,5\n"),
        )
        .unwrap_err();
        assert_eq!(
            (e.line, e.field.as_deref()),
            (Some(2), Some("pz")),
            "{bad}: {e}"
        );
    }
}

#[test]
fn stored_sets_keep_the_measurements_as_stated_and_their_kind() {
    use calib_gough::calibrated::{calibrated_robot, robot_toml};
    use calib_gough::certification::{certify_legs, CertifyOptions};
    use calib_gough::files::{leg_sets, parse_robot_file};
    use calib_gough::{
        builtin_hexapod, leg_boxes, simulate, Configuration, LegModel, Orientation, Uncertainty,
    };
    let sim = simulate(&builtin_hexapod(), 12, 4, Uncertainty::PAPER, 1.0, 0.1);
    let robot = crate::support::priors(&sim.nominal);
    let rodrigues: Vec<Configuration> = sim
        .measured
        .iter()
        .map(|c| {
            let Orientation::AxisAngle { axis, angle_deg } = c.orientation else {
                unreachable!()
            };
            let t = (angle_deg.to_radians() / 2.0).tan();
            Configuration {
                orientation: Orientation::Rodrigues(axis.map(|v| v * t)),
                ..c.clone()
            }
        })
        .collect();
    let u = Uncertainty {
        q: 2e-5,
        ..Uncertainty::PAPER
    };
    let options = CertifyOptions {
        legs: Some(vec![1]),
        fast: true,
        ..CertifyOptions::default()
    };
    let path = Path::new("calibrated.toml");
    for (configs, kind, columns) in [
        (&sim.measured, LegModel::AxisAngle, 8),
        (&rodrigues, LegModel::Rodrigues, 7),
    ] {
        let results = certify_legs(&robot, configs, &u, &options, &|| {}).unwrap();
        let cal = calibrated_robot(&robot, &results, configs, &u, None).unwrap();
        let text = robot_toml(&cal.legs, &cal.sets, "test");
        let file = parse_robot_file(path, &text).unwrap();
        let stored = file.sets[0].as_ref().unwrap();
        assert!(stored.measurements.iter().all(|m| m.len() == columns));
        let sets = leg_sets(path, &file).unwrap();
        let set = sets[0].as_ref().unwrap();
        assert_eq!(LegModel::of_set(set), kind);
        assert_eq!(set.measurements(), &leg_boxes(configs, &u, 0)[..]);
        if kind == LegModel::AxisAngle {
            // An angle column edited to the point 0 is refused, not read as Rodrigues data.
            let mut edited = file.clone();
            for m in &mut edited.sets[0].as_mut().unwrap().measurements {
                m[6] = [0.0, 0.0];
            }
            let e = leg_sets(path, &edited).unwrap_err().to_string();
            assert!(e.contains("certified_set.measurements"), "{e}");
        }
    }
}
