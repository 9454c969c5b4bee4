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
