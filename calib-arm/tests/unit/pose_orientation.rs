//! Euler angles of orientations (`calib_arm::pose::orientation`).

use calib_arm::pose::orientation::{from_euler_xyz, to_euler_xyz};

#[test]
fn euler_angles_round_trip() {
    for a in [-3.0, -1.0, 0.0, 0.4, 2.9] {
        for b in [-1.5, -0.3, 0.0, 0.7, 1.5] {
            for c in [-3.1, -0.2, 0.0, 1.1, 3.0] {
                let r = from_euler_xyz([a, b, c]);
                let back = from_euler_xyz(to_euler_xyz(&r));
                assert!((r.matrix() - back.matrix()).norm() < 1e-12, "{a} {b} {c}");
                let e = to_euler_xyz(&r);
                assert!((e[0] - a).abs() < 1e-9 && (e[2] - c).abs() < 1e-9, "{e:?}");
            }
        }
    }
    // Gimbal lock: the rotation is still recovered.
    let r = from_euler_xyz([0.3, std::f64::consts::FRAC_PI_2, 0.5]);
    assert!((r.matrix() - from_euler_xyz(to_euler_xyz(&r)).matrix()).norm() < 1e-9);
}
