//! The tests of `calib_pipeline::stored_set`.

use calib_core::Interval;
use calib_pipeline::stored_set::*;
use serde::Deserialize;

#[test]
fn a_stored_set_reads_back_bit_identical_and_refuses_bad_rows() {
    let stored = StoredSet {
        measurements: vec![vec![[0.1, 0.30000000000000004], [-1e-7, 2.5]]],
        boxes: vec![vec![[1.0 / 3.0, 0.5]], vec![[-2.0, -1.0]]],
        subsets: vec![0, 0],
        dropped: vec![vec![]],
        points: vec![vec![0.4]],
    };
    let text = stored.to_toml("certified_set");
    #[derive(Deserialize)]
    struct File {
        certified_set: StoredSet,
    }
    let back: File = toml::from_str(&text).expect("valid TOML");
    assert_eq!(back.certified_set, stored);
    let r = back
        .certified_set
        .restore::<2, 3>(
            &[1],
            &[0, 2],
            &[Interval::point(9.0); 2],
            &[Interval::point(7.0); 3],
        )
        .expect("consistent dimensions");
    assert_eq!(r.cover.boxes[0][1], Interval::new(1.0 / 3.0, 0.5));
    assert_eq!(r.cover.boxes[0][0], Interval::point(9.0));
    assert_eq!(r.measurements[0][2], Interval::new(-1e-7, 2.5));
    assert_eq!(r.measurements[0][1], Interval::point(7.0));
    assert_eq!(r.points[0], [9.0, 0.4]);
    let mut bad = stored.clone();
    bad.boxes[1][0] = [1.0, 0.0];
    let e = bad.restore::<1, 2>(&[0], &[0, 1], &[Interval::ZERO], &[Interval::ZERO; 2]);
    assert_eq!(e.unwrap_err().0, "boxes[2]");
    let mut bad = stored;
    bad.dropped = vec![vec![3]];
    let e = bad.restore::<1, 2>(&[0], &[0, 1], &[Interval::ZERO], &[Interval::ZERO; 2]);
    assert_eq!(e.unwrap_err().0, "dropped[1]");
}
