//! The tests of `calib_arm::tracker_file`.

use calib_arm::simulate::Uncertainty;
use calib_arm::tracker_file::*;
use std::path::Path;

fn columns(unit: JointUnit, length: LengthUnit) -> MeasurementColumns {
    MeasurementColumns {
        joints: vec!["j1".into(), "j2".into(), "j3".into()],
        point: ["X".into(), "Y".into(), "Z".into()],
        joint_unit: unit,
        length_unit: length,
        rows: None,
        orientation: None,
    }
}

const SIX_DOF: &str = "j1;j2;j3;X;Y;Z;A;B;C\n\
    0,1;0,2;0,3;383,7;-3240,8;201,9;179,5;-0,25;-90,125\n\
    0,4;0,5;0,6;380,1;-3241,2;205,3;-179,75;0,5;89,5\n";

#[test]
fn orientation_columns_read_euler_angles_in_degrees_or_radians() {
    let f = Path::new("six.csv");
    let mut c = columns(JointUnit::Rad, LengthUnit::Mm);
    let names = ["A".to_string(), "B".into(), "C".into()];
    c.orientation = Some((names.clone(), OrientationConvention::EulerXyzDeg));
    let m = parse_tracker_measurements(f, SIX_DOF, 3, &c).unwrap();
    let o = m.orientations.unwrap();
    assert_eq!(o, vec![[179.5, -0.25, -90.125], [-179.75, 0.5, 89.5]]);
    assert_eq!(m.slack.orient_deg, 0.0);
    // Without orientation columns the file reads as before.
    let plain = parse_tracker_measurements(f, SIX_DOF, 3, &columns(JointUnit::Rad, LengthUnit::Mm));
    assert_eq!(plain.unwrap().orientations, None);
    // Radians are converted, their rounding kept for the bound; degrees read as radians refused.
    let text = SIX_DOF
        .replace("179,5;-0,25;-90,125", "3,1;-0,25;-1,5")
        .replace("-179,75;0,5;89,5", "-3;0,5;1,5");
    c.orientation = Some((names.clone(), OrientationConvention::EulerXyzRad));
    let m = parse_tracker_measurements(f, &text, 3, &c).unwrap();
    let o = m.orientations.unwrap();
    assert!((o[0][0] - 3.1_f64.to_degrees()).abs() < 1e-12);
    assert!(m.slack.orient_deg > 0.0 && m.slack.orient_deg < 1e-12);
    assert!(m.slack.widen_orientation(0.01) >= 0.01);
    let e = parse_tracker_measurements(f, SIX_DOF, 3, &c)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("six.csv") && e.contains("line 2") && e.contains('A'),
        "{e}"
    );
    assert!(e.contains("euler-xyz-deg"), "{e}");
}

#[test]
fn a_bad_orientation_field_is_named_with_its_line() {
    let f = Path::new("six.csv");
    let mut c = columns(JointUnit::Rad, LengthUnit::Mm);
    c.orientation = Some((
        ["A".to_string(), "B".into(), "C".into()],
        OrientationConvention::EulerXyzDeg,
    ));
    let text = SIX_DOF.replace("0,5;89,5", "zero;89,5");
    let e = parse_tracker_measurements(f, &text, 3, &c)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("six.csv") && e.contains("line 3") && e.contains('B'),
        "{e}"
    );
    let text = SIX_DOF.replace("-90,125", "-450");
    let e = parse_tracker_measurements(f, &text, 3, &c)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("line 2") && e.contains("-450") && e.contains("360"),
        "{e}"
    );
    let missing = SIX_DOF.replace(";C\n", ";D\n");
    let e = parse_tracker_measurements(f, &missing, 3, &c)
        .unwrap_err()
        .to_string();
    assert!(e.contains("six.csv") && e.contains('C'), "{e}");
}

const EXPORT: &str = "Stamp;j1;j2;j3;T;X;Y;Z\n\
    2,02011E+13;-2,78E-05;-3,14159;-1,5708;21,9;383,76294;-3240,8734;201,93157\n\
    2,02011E+13;0,5;-0,05;-1,9;21,9;-0,507;-3343,15;-426,95\n";

#[test]
fn a_european_export_in_radians_reads_in_degrees_with_its_rounding_kept() {
    let f = Path::new("series.csv");
    let c = columns(JointUnit::Rad, LengthUnit::Mm);
    let m = parse_tracker_measurements(f, EXPORT, 3, &c).unwrap();
    assert_eq!(m.lines, vec![2, 3]);
    let r = &m.readings[0];
    let reading: f64 = "-3.14159".parse().unwrap();
    assert!((r.joints_deg[1] - reading.to_degrees()).abs() < 1e-12);
    assert_eq!(r.point, [383.76294, -3240.8734, 201.93157]);
    // The conversion's rounding: positive, tiny, and the bounds grow by it.
    assert!(m.slack.joint_deg > 0.0 && m.slack.joint_deg < 1e-12);
    assert_eq!(m.slack.pos, 0.0);
    let u = m.slack.widen(&Uncertainty {
        joint_deg: 0.001,
        pos: 0.5,
    });
    assert!(u.joint_deg > 0.001 && u.pos == 0.5);
    // Rows pick a part of the file.
    let mut one = c.clone();
    one.rows = Some("2-".parse().unwrap());
    let m = parse_tracker_measurements(f, EXPORT, 3, &one).unwrap();
    assert_eq!(m.lines, vec![3]);
}

#[test]
fn values_in_the_wrong_unit_are_named() {
    let f = Path::new("series.csv");
    // Radians read as degrees: a note, not an error (a small cell looks the same).
    let many = format!(
        "{EXPORT}{}",
        EXPORT.lines().skip(1).collect::<Vec<_>>().join("\n")
    );
    let m =
        parse_tracker_measurements(f, &many, 3, &columns(JointUnit::Deg, LengthUnit::Mm)).unwrap();
    assert!(m.notes[0].contains("--joint-unit rad"), "{:?}", m.notes);
    // Millimetres read as metres: the coordinate, its line and the fix.
    let e = parse_tracker_measurements(f, EXPORT, 3, &columns(JointUnit::Rad, LengthUnit::M))
        .unwrap_err();
    assert_eq!((e.line, e.field.as_deref()), (Some(2), Some("X")));
    assert!(e.message.contains("--length-unit mm"), "{e}");
    // Degrees read as radians.
    let deg = "j1,j2,j3,X,Y,Z\n10,90,-120,1000,2000,3000\n";
    let e = parse_tracker_measurements(f, deg, 3, &columns(JointUnit::Rad, LengthUnit::Mm))
        .unwrap_err();
    assert_eq!((e.line, e.field.as_deref()), (Some(2), Some("j1")));
    assert!(e.message.contains("--joint-unit deg"), "{e}");
    // Metres read as millimetres: a note.
    let m_file = format!("j1,j2,j3,X,Y,Z\n{}", "10,90,-120,1.1,2.2,-0.3\n".repeat(4));
    let m = parse_tracker_measurements(f, &m_file, 3, &columns(JointUnit::Deg, LengthUnit::Mm))
        .unwrap();
    assert!(m.notes[0].contains("--length-unit m"), "{:?}", m.notes);
    // A missing column, the wrong number of joints, an empty row range.
    let e = parse_tracker_measurements(f, deg, 4, &columns(JointUnit::Deg, LengthUnit::Mm))
        .unwrap_err();
    assert!(e.message.contains("4 joints"), "{e}");
    let mut c = columns(JointUnit::Deg, LengthUnit::Mm);
    c.rows = Some("5-".parse().unwrap());
    let e = parse_tracker_measurements(f, deg, 3, &c).unwrap_err();
    assert!(e.message.contains("1 data rows"), "{e}");
    assert!("3-1".parse::<RowRange>().is_err() && "0-".parse::<RowRange>().is_err());
}

#[test]
fn layouts_and_units_from_names() {
    let c = MeasurementColumns::with_names(2, Some(vec!["a".into(), "b".into()]), None)
        .expect("layout");
    assert_eq!(c.joints, ["a", "b"]);
    assert_eq!(c.point, ["px", "py", "pz"]);
    let e = MeasurementColumns::with_names(2, None, Some(vec!["x".into()]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("three names") && e.contains("found 1"), "{e}");
    assert_eq!("rad".parse::<JointUnit>(), Ok(JointUnit::Rad));
    assert_eq!("m".parse::<LengthUnit>(), Ok(LengthUnit::M));
    let e = "grad".parse::<JointUnit>().unwrap_err().to_string();
    assert!(e.contains("`grad`"), "{e}");
    let e = "ft".parse::<LengthUnit>().unwrap_err().to_string();
    assert!(e.contains("`ft`"), "{e}");
}
