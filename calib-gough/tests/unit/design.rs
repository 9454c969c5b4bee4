//! The tests of `calib_gough::design`.

use calib_gough::design::*;
use calib_gough::files::parse_poses;
use calib_gough::measurement::Uncertainty;
use calib_gough::simulate::builtin_hexapod;
use calib_gough::workspace::Workspace;
use std::path::Path;

#[test]
fn designed_poses_lie_in_the_workspace_and_round_trip_through_the_poses_file() {
    let w = Workspace::SIMULATOR;
    let request = DesignRequest {
        configs: 9,
        candidates: 200,
        ..DesignRequest::default()
    };
    let d = design(
        &builtin_robot(),
        &Uncertainty::PAPER,
        &w,
        &request,
        &[],
        &|| {},
    )
    .unwrap();
    assert_eq!(d.poses.len(), 9);
    let legs = builtin_hexapod();
    assert!(d
        .poses
        .iter()
        .chain(&d.random)
        .all(|p| w.contains(p, &legs)));
    let back = parse_poses(Path::new("poses.csv"), &poses_csv(&d.poses)).unwrap();
    for (a, b) in back.iter().zip(&d.poses) {
        assert_eq!(a.p, b.p);
        assert_eq!(a.angle_deg, b.angle_deg);
        assert!(a
            .axis
            .iter()
            .zip(&b.axis)
            .all(|(x, y)| (x - y).abs() < 1e-15));
    }
}
