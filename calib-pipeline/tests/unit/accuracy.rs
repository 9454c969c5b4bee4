//! The accuracy engine on a planar two-link arm: its bracket holds for every consistent
//! geometry and joint error sampled, and its worst instance is rechecked by independent code.

use calib_core::{
    certify, interval_model, is_consistent_point, CertifiedSet, Cover, Interval, Jet, Quadratic,
    Scalar, Settings, Status,
};
use calib_pipeline::accuracy::{bracket_over_set, BracketSettings, Prediction, SetAccuracy};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// The tip of a planar two-link arm minus a measured point: `x = (l1, l2, o1, o2)` link lengths
/// and joint offsets, `m = (q1, q2, px, py)`.
#[interval_model]
fn planar_tip<S: Scalar>(x: &[S; 4], m: &[S; 4]) -> [S; 2] {
    let [l1, l2, o1, o2] = *x;
    let [q1, q2, px, py] = *m;
    let a = q1 + o1;
    let b = a + q2 + o2;
    [
        l1 * a.cos() + l2 * b.cos() - px,
        l1 * a.sin() + l2 * b.sin() - py,
    ]
}

/// The tip as a prediction: the joints in the measurement slot, the point 0.
struct Tip;

impl Prediction<4, 4, 4, 2, 2> for Tip {
    type Model = PlanarTip;

    fn model(&self) -> &PlanarTip {
        &PlanarTip
    }

    fn second_order(
        &self,
        x: &[Jet<Quadratic<2>, 4>; 4],
        m: &[Jet<Quadratic<2>, 4>; 4],
    ) -> [Jet<Quadratic<2>, 4>; 2] {
        planar_tip(x, m)
    }

    fn push(&self, set: &mut CertifiedSet<4, 4>, direction: &[f64; 4]) -> bool {
        set.extreme_point(&PlanarTip, direction).is_some()
    }
}

/// The tip by plain trigonometry (independent of the generated evaluators).
fn tip(x: &[f64; 4], q: &[f64; 2]) -> [f64; 2] {
    let a = q[0] + x[2];
    let b = a + q[1] + x[3];
    [
        x[0] * a.cos() + x[1] * b.cos(),
        x[0] * a.sin() + x[1] * b.sin(),
    ]
}

#[test]
fn the_bracket_holds_for_every_consistent_geometry_sampled_and_its_worst_case_is_real() {
    let mut rng = StdRng::seed_from_u64(11);
    let truth = [1.0, 0.8, 0.01, -0.02];
    let (joint_err, point_err) = (1e-4, 1e-3);
    let boxes: Vec<[Interval; 4]> = (0..14)
        .map(|_| {
            let q = [rng.random_range(-1.5..1.5), rng.random_range(-2.0..2.0)];
            let p = tip(&truth, &q);
            let read = [q[0], q[1], p[0], p[1]];
            core::array::from_fn(|k| {
                let r = if k < 2 { joint_err } else { point_err };
                Interval::mid_rad(read[k] + rng.random_range(-r..r), r)
            })
        })
        .collect();
    let prior = [
        Interval::new(0.9, 1.1),
        Interval::new(0.7, 0.9),
        Interval::new(-0.1, 0.1),
        Interval::new(-0.1, 0.1),
    ];
    let r = certify(&PlanarTip, &prior, &boxes, &Settings::default());
    assert_eq!(r.status, Status::Consistent);
    let witness = r.witness.expect("a certified point");
    let set = CertifiedSet::new(&PlanarTip, &Cover::single(r.outer), &boxes, &[witness], 4);
    // The controller computes with the nominal geometry; the joints' box and errors.
    let nominal = [1.0, 0.8, 0.0, 0.0];
    let domain = [Interval::new(-0.4, 0.4), Interval::new(0.3, 1.1)];
    let engine = SetAccuracy::new(&Tip, set, nominal, domain, [joint_err; 2]).expect("a set");
    let b = bracket_over_set(
        &engine,
        &BracketSettings {
            rel_tol: 0.02,
            max_boxes: 200,
        },
    );
    assert!(
        b.upper.is_finite() && b.lower > 0.0 && b.upper >= b.lower,
        "{b:?}"
    );
    // At the set's scale: within 1.5 of what is attained (1.14 measured).
    assert!(b.ratio() < 1.5, "{b:?}");
    // Consistent geometries: the truth and every catalogued point, each rechecked against the
    // measurements; joints and joint errors at random.
    let mut geometries = vec![truth];
    geometries.extend(engine.catalogue());
    for g in &geometries {
        assert!(is_consistent_point(&PlanarTip, g, &boxes), "{g:?}");
    }
    let mut largest: f64 = 0.0;
    for k in 0..4000 {
        let g = &geometries[k % geometries.len()];
        let q = [
            rng.random_range(domain[0].inf()..=domain[0].sup()),
            rng.random_range(domain[1].inf()..=domain[1].sup()),
        ];
        let real = [
            q[0] + rng.random_range(-joint_err..=joint_err),
            q[1] + rng.random_range(-joint_err..=joint_err),
        ];
        let (p, p0) = (tip(g, &real), tip(&nominal, &q));
        let e = ((p[0] - p0[0]).powi(2) + (p[1] - p0[1]).powi(2)).sqrt();
        largest = largest.max(e);
        assert!(e <= b.upper * (1.0 + 1e-9), "error {e} above {}", b.upper);
    }
    // The worst instance: a consistent geometry, inputs in the box reached within their
    // errors, its value recomputed.
    let w = b.worst.as_ref().expect("an instance");
    assert!(is_consistent_point(&PlanarTip, &w.theta, &boxes));
    assert!((0..2).all(|i| domain[i].contains(w.inputs[i])));
    assert!((0..2).all(|i| (w.reached[i] - w.inputs[i]).abs() <= joint_err));
    let (p, p0) = (tip(&w.theta, &w.reached), tip(&nominal, &w.inputs));
    let value = ((p[0] - p0[0]).powi(2) + (p[1] - p0[1]).powi(2)).sqrt();
    assert!(value >= b.lower * (1.0 - 1e-9), "{value} below {}", b.lower);
    assert!(
        b.lower >= 0.9 * largest,
        "lower {} below a sample {largest}",
        b.lower
    );
}

#[test]
fn the_inputs_own_errors_never_cancel_in_the_bound() {
    // Large joint errors, the controller's geometry the truth itself: the whole error is the
    // joints', largest at the vertices of their error box (where the partials' signs differ,
    // a bound that let them cancel falls below it).
    let truth = [1.0, 0.8, 0.01, -0.02];
    let boxes: Vec<[Interval; 4]> = [[0.3, 0.9], [-0.4, 1.6], [1.1, -0.7], [-1.2, 0.2]]
        .iter()
        .map(|q| {
            let p = tip(&truth, q);
            [
                Interval::mid_rad(q[0], 1e-4),
                Interval::mid_rad(q[1], 1e-4),
                Interval::mid_rad(p[0], 1e-3),
                Interval::mid_rad(p[1], 1e-3),
            ]
        })
        .collect();
    let prior = truth.map(|v| Interval::mid_rad(v, 0.05));
    let r = certify(&PlanarTip, &prior, &boxes, &Settings::default());
    assert_eq!(r.status, Status::Consistent);
    let set = CertifiedSet::new(
        &PlanarTip,
        &Cover::single(r.outer),
        &boxes,
        &[r.witness.expect("a point")],
        2,
    );
    let eps = 0.05;
    let domain = [Interval::new(0.2, 0.3), Interval::new(0.5, 0.6)];
    let engine = SetAccuracy::new(&Tip, set, truth, domain, [eps; 2]).expect("a set");
    let b = bracket_over_set(
        &engine,
        &BracketSettings {
            rel_tol: 0.02,
            max_boxes: 100,
        },
    );
    let mut largest: f64 = 0.0;
    for i in 0..=10 {
        for k in 0..=10 {
            let q = [0.2 + 0.01 * i as f64, 0.5 + 0.01 * k as f64];
            for s in [[1.0, 1.0], [1.0, -1.0], [-1.0, 1.0], [-1.0, -1.0]] {
                let p = tip(&truth, &[q[0] + s[0] * eps, q[1] + s[1] * eps]);
                let p0 = tip(&truth, &q);
                largest = largest.max(((p[0] - p0[0]).powi(2) + (p[1] - p0[1]).powi(2)).sqrt());
            }
        }
    }
    assert!(largest <= b.upper, "{largest} above the proved {}", b.upper);
    // The lower bound reaches the joints' errors too (without them it would stay near 0).
    assert!(b.lower >= 0.9 * largest, "lower {} for {largest}", b.lower);
}
