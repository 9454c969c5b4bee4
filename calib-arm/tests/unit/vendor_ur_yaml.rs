//! The tests of `calib_arm::vendor::ur_yaml`.

use calib_arm::vendor::ur_yaml::*;
use std::path::Path;

const UR10: &str = include_str!("../../tests/data/ur10_default_kinematics.yaml");

#[test]
fn ur10_reads_writes_and_reads_back_the_same_frames() {
    let f = Path::new("ur10.yaml");
    let k = parse(f, UR10).expect("UR10");
    assert_eq!(k.hash.as_deref(), Some("calib_17227329492635474227"));
    assert!((k.origins[0].translation.vector.z - 127.3).abs() < 1e-12);
    let text = write(&k.origins, k.hash.as_deref(), "test").expect("six joints");
    assert!(text.starts_with("# test\nkinematics:\n  shoulder:\n"));
    let again = parse(f, &text).expect("reads back");
    assert_eq!(again.hash, k.hash);
    for (a, b) in again.origins.iter().zip(&k.origins) {
        assert!((a.translation.vector - b.translation.vector).norm() < 1e-12);
        assert!(a.rotation.angle_to(&b.rotation) < 1e-12);
    }
    let own = write(&k.origins, None, "").expect("six joints");
    assert!(own.contains("hash: certicalib_"), "{own}");
}

#[test]
fn bad_files_are_named_with_line_and_field() {
    let f = Path::new("bad.yaml");
    let e = parse(f, &UR10.replace("forearm", "fore_arm")).unwrap_err();
    assert!(e.line.is_some() && e.message.contains("fore_arm"), "{e}");
    let e = parse(f, &UR10.replace("x: -0.612", "x: -612e9")).unwrap_err();
    assert_eq!((e.line, e.field.as_deref()), (Some(17), Some("forearm.x")));
    let e = parse(f, "kinematics: [1, 2]").unwrap_err();
    assert_eq!(e.line, Some(1));
}

#[test]
fn non_finite_numbers_are_refused_naming_the_line_and_the_field() {
    let f = Path::new("bad.yaml");
    // YAML's own spellings of NaN and the infinities.
    for bad in [".nan", ".NaN", ".inf", "-.inf", "+.INF"] {
        let e = parse(
            f,
            &UR10.replace("roll: 1.570796327", &format!("roll: {bad}")),
        )
        .unwrap_err();
        assert_eq!(
            (e.line, e.field.as_deref()),
            (Some(13), Some("upper_arm.roll")),
            "{e}"
        );
        assert!(e.message.contains("expected a finite number"), "{bad}: {e}");
        assert_eq!(e.file, f);
    }
    // Rust's spellings and an overflowing decimal are not YAML numbers: a type error at the line.
    for bad in ["nan", "inf", "1e999"] {
        let e = parse(f, &UR10.replace("x: -0.612", &format!("x: {bad}"))).unwrap_err();
        assert_eq!(e.line, Some(17), "{bad}: {e}");
    }
}
