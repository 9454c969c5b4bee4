//! The tests of `calib_arm::vendor::urdf`.

use calib_arm::vendor::from_xyz_rpy;
use calib_arm::vendor::urdf::*;
use calib_arm::vendor::{chain_flange, ur_yaml};
use std::path::Path;

const UR10: &str = include_str!("../../tests/data/ur10_default_kinematics.yaml");

#[test]
fn a_urdf_of_the_ur10_reads_back_as_the_yaml_chain() {
    let yaml = ur_yaml::parse(Path::new("ur10.yaml"), UR10).expect("UR10");
    let text = write("ur10", &yaml.origins, [0.0, 0.0, 93.0]);
    let f = Path::new("ur10.urdf");
    // Up to the last moving joint's link (the default tip) and with the tool link as tip
    // refused (it is offset).
    let chain = parse(f, &text, None, Some("link6")).expect("a chain");
    let e = parse(f, &text, None, None).unwrap_err();
    assert!(e.message.contains("offset"), "{e}");
    for q in [[0.1, -1.2, 0.7, 2.0, -0.4, 3.0], [0.0; 6]] {
        let a = chain_flange(&yaml.origins, &q);
        let b = chain_flange(&chain, &q);
        assert!((a.translation.vector - b.translation.vector).norm() < 1e-9);
        assert!(a.rotation.angle_to(&b.rotation) < 1e-12);
    }
}

#[test]
fn axes_other_than_z_and_fixed_links_fold_into_the_chain() {
    let text = r#"<robot name="r">
  <link name="b"/><link name="m"/><link name="l1"/><link name="l2"/><link name="l3"/>
  <link name="l4"/>
  <joint name="fix" type="fixed"><parent link="b"/><child link="m"/>
<origin xyz="0 0 0.1" rpy="0 0 0.3"/></joint>
  <joint name="j1" type="revolute"><parent link="m"/><child link="l1"/>
<origin xyz="0.01 0 0.2" rpy="0.1 0 0"/><axis xyz="0 0 1"/>
<limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j2" type="continuous"><parent link="l1"/><child link="l2"/>
<origin xyz="0.3 0 0" rpy="0 0 0"/><axis xyz="0 1 0"/></joint>
  <joint name="j3" type="continuous"><parent link="l2"/><child link="l3"/>
<origin xyz="0.25 0.02 0" rpy="0 0 0"/><axis xyz="-1 0 0"/></joint>
  <joint name="j4" type="continuous"><parent link="l3"/><child link="l4"/>
<origin xyz="0 0 0.05" rpy="0 0 0"/><axis xyz="0 0 1"/></joint>
</robot>"#;
    let chain = parse(Path::new("r.urdf"), text, None, None).expect("a chain");
    assert_eq!(chain.len(), 4);
    // The same frames by hand: about y then about -x.
    let q = [0.4, -0.8, 1.1, 0.6];
    let by_hand = from_xyz_rpy([0.0, 0.0, 100.0], [0.0, 0.0, 0.3])
        * from_xyz_rpy([10.0, 0.0, 200.0], [0.1, 0.0, 0.0])
        * from_xyz_rpy([0.0; 3], [0.0, 0.0, q[0]])
        * from_xyz_rpy([300.0, 0.0, 0.0], [0.0; 3])
        * from_xyz_rpy([0.0; 3], [0.0, q[1], 0.0])
        * from_xyz_rpy([250.0, 20.0, 0.0], [0.0; 3])
        * from_xyz_rpy([0.0; 3], [-q[2], 0.0, 0.0])
        * from_xyz_rpy([0.0, 0.0, 50.0], [0.0, 0.0, q[3]]);
    let got = chain_flange(&chain, &q);
    let p = nalgebra::Point3::new(5.0, -7.0, 11.0);
    assert!((by_hand * p - got * p).norm() < 1e-9);
    let e = parse(
        Path::new("r.urdf"),
        &text.replace("continuous", "prismatic"),
        None,
        None,
    )
    .unwrap_err();
    assert!(
        e.message.contains("Prismatic") && e.field.as_deref() == Some("j2"),
        "{e}"
    );
}

/// A three-joint URDF whose second joint's origin is `xyz`, `rpy` and axis `axis`.
fn three_joints(xyz: &str, rpy: &str, axis: &str) -> String {
    format!(
        r#"<robot name="r">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/>
  <joint name="shoulder_pan_joint" type="revolute"><parent link="base"/><child link="l1"/>
<origin xyz="0 0 0.2" rpy="0 0 0"/><axis xyz="0 0 1"/>
<limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="shoulder_lift_joint" type="continuous"><parent link="l1"/><child link="l2"/>
<origin xyz="{xyz}" rpy="{rpy}"/><axis xyz="{axis}"/></joint>
  <joint name="elbow_joint" type="continuous"><parent link="l2"/><child link="l3"/>
<origin xyz="0.25 0.02 0" rpy="0 0 0"/><axis xyz="0 0 1"/></joint>
</robot>"#
    )
}

#[test]
fn non_finite_numbers_are_refused_naming_the_joint_and_the_attribute() {
    let f = Path::new("arm.urdf");
    let good = ("0.3 0 0", "0 0 0", "0 1 0");
    assert_eq!(
        parse(f, &three_joints(good.0, good.1, good.2), None, None)
            .expect("a chain")
            .len(),
        3
    );
    // Rust's float parser (which urdf-rs uses) reads all of these as NaN or an infinity.
    for bad in ["nan", "NaN", "inf", "-inf", "infinity", "1e999"] {
        for (text, attribute) in [
            (
                three_joints(&format!("0.3 {bad} 0"), good.1, good.2),
                "origin xyz",
            ),
            (
                three_joints(good.0, &format!("0 0 {bad}"), good.2),
                "origin rpy",
            ),
            (
                three_joints(good.0, good.1, &format!("0 {bad} 0")),
                "axis xyz",
            ),
        ] {
            let e = parse(f, &text, None, None).unwrap_err();
            let field = format!("joint 'shoulder_lift_joint' {attribute}");
            assert_eq!(e.field.as_deref(), Some(field.as_str()), "{bad}: {e}");
            assert_eq!(e.file, f);
            assert!(e.message.contains("expected a finite number"), "{bad}: {e}");
        }
    }
    // A fixed joint folded into the chain is read too.
    let fixed = three_joints(good.0, good.1, good.2).replace(
        r#"<joint name="shoulder_pan_joint" type="revolute"><parent link="base"/>"#,
        r#"<link name="m"/><joint name="mount" type="fixed"><parent link="base"/>
<child link="m"/><origin xyz="0 0 inf"/></joint>
<joint name="shoulder_pan_joint" type="revolute"><parent link="m"/>"#,
    );
    let e = parse(f, &fixed, None, None).unwrap_err();
    assert_eq!(e.field.as_deref(), Some("joint 'mount' origin xyz"), "{e}");
}
