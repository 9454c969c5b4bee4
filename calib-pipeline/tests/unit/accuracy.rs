//! The accuracy engine on a planar two-link arm: its bracket holds for every consistent
//! geometry and joint error sampled, and its worst instance is rechecked by independent code.

use calib_core::{
    certify, interval_model, is_consistent_point, maximize_over_set, CertifiedSet, Cover, Interval,
    Jet, LinearFunction, Quadratic, Scalar, SetMaximum, SetMaximumSettings, Settings, Status,
};
use calib_pipeline::accuracy::{
    arc_vertices, bracket_over_set, cover_bound, BracketSettings, Prediction, SetAccuracy,
};
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

    fn max_over_set(&self, set: &mut CertifiedSet<4, 4>, g: &[f64; 4]) -> Option<SetMaximum<4>> {
        // Within 0.5% of the set's range of `g·θ` (relative to `g·θ` itself, far larger, it
        // would stop at once).
        let settings = SetMaximumSettings {
            rel_tol: 0.0,
            abs_tol: 0.005 * set.query().range(g).wid(),
            max_refinements: 16,
            ..SetMaximumSettings::default()
        };
        Some(maximize_over_set(
            &PlanarTip,
            set,
            &LinearFunction(*g),
            &settings,
        ))
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

/// The true geometry of the simulated arm.
const TRUTH: [f64; 4] = [1.0, 0.8, 0.01, -0.02];
/// The joints' error bound (rad); the point's is ten times it.
const JOINT_ERROR: f64 = 1e-4;

/// The simulated arms' prior box.
fn prior() -> [Interval; 4] {
    [
        Interval::new(0.9, 1.1),
        Interval::new(0.7, 0.9),
        Interval::new(-0.1, 0.1),
        Interval::new(-0.1, 0.1),
    ]
}

/// A reading of two joints and a point as measured: each value moved at random within its
/// error bound (the joints' `JOINT_ERROR`, the point's ten times it) and boxed by it.
fn measured<const NM: usize>(rng: &mut StdRng, read: [f64; NM]) -> [Interval; NM] {
    core::array::from_fn(|k| {
        let r = if k < 2 {
            JOINT_ERROR
        } else {
            10.0 * JOINT_ERROR
        };
        Interval::mid_rad(read[k] + rng.random_range(-r..r), r)
    })
}

/// Fourteen simulated measurements of the arm and the set certified from them.
fn calibrated(rng: &mut StdRng) -> (Vec<[Interval; 4]>, CertifiedSet<4, 4>) {
    let boxes: Vec<[Interval; 4]> = (0..14)
        .map(|_| {
            let q = [rng.random_range(-1.5..1.5), rng.random_range(-2.0..2.0)];
            let p = tip(&TRUTH, &q);
            measured(rng, [q[0], q[1], p[0], p[1]])
        })
        .collect();
    let r = certify(&PlanarTip, &prior(), &boxes, &Settings::default());
    assert_eq!(r.status, Status::Consistent);
    let witness = r.witness.expect("a certified point");
    let set = CertifiedSet::new(&PlanarTip, &Cover::single(r.outer), &boxes, &[witness], 4);
    (boxes, set)
}

#[test]
fn the_bracket_holds_for_every_consistent_geometry_sampled_and_its_worst_case_is_real() {
    let mut rng = StdRng::seed_from_u64(11);
    let (truth, joint_err) = (TRUTH, JOINT_ERROR);
    let (boxes, set) = calibrated(&mut rng);
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

#[test]
fn predictions_hold_every_consistent_geometry_and_their_attained_ends_are_real() {
    let mut rng = StdRng::seed_from_u64(5);
    let (truth, joint_err) = (TRUTH, JOINT_ERROR);
    let (boxes, set) = calibrated(&mut rng);
    let nominal = [1.0, 0.8, 0.0, 0.0];
    let domain = [Interval::new(-1.5, 1.5), Interval::new(-2.0, 2.0)];
    let engine = SetAccuracy::new(&Tip, set, nominal, domain, [joint_err; 2]).expect("a set");
    let mut lps = engine.programs();
    let mut ratios = Vec::new();
    let mut geometries = vec![truth];
    geometries.extend(engine.catalogue());
    for g in &geometries {
        assert!(is_consistent_point(&PlanarTip, g, &boxes), "{g:?}");
    }
    for _ in 0..60 {
        let q = [rng.random_range(-1.5..1.5), rng.random_range(-2.0..2.0)];
        let exact = engine
            .predict(&q.map(Interval::point), false, &mut lps)
            .expect("a prediction");
        let with_errors = engine
            .predict(&q.map(Interval::point), true, &mut lps)
            .expect("a prediction");
        for g in &geometries {
            let p = tip(g, &q);
            let e = [
                q[0] + rng.random_range(-joint_err..=joint_err),
                q[1] + rng.random_range(-joint_err..=joint_err),
            ];
            let moved = tip(g, &e);
            for c in 0..2 {
                // Computed in floating point: within a rounding of the bounds.
                let (o, w) = (exact.outer[c], with_errors.outer[c]);
                assert!(
                    o.inf() - 1e-12 <= p[c] && p[c] <= o.sup() + 1e-12,
                    "{p:?} {o:?}"
                );
                assert!(w.inf() - 1e-12 <= moved[c] && moved[c] <= w.sup() + 1e-12);
                assert!(
                    w.inf() <= o.inf() && o.sup() <= w.sup(),
                    "errors widen: {w:?} {o:?}"
                );
            }
        }
        // The attained range: inside the outer one, its ends reached by geometries rechecked
        // against the measurements (values by plain trigonometry).
        for c in 0..2 {
            let a = exact.attained[c].expect("certified geometries");
            assert!(exact.outer[c].inf() <= a.range.inf() && a.range.sup() <= exact.outer[c].sup());
            for (g, end, below) in [
                (a.lowest, a.range.inf(), true),
                (a.highest, a.range.sup(), false),
            ] {
                assert!(is_consistent_point(&PlanarTip, &g, &boxes), "{g:?}");
                let v = tip(&g, &q)[c];
                assert!(
                    if below {
                        v <= end + 1e-12
                    } else {
                        v >= end - 1e-12
                    },
                    "{v} {a:?}"
                );
            }
            ratios.push(exact.outer[c].wid() / a.range.wid());
        }
    }
    // How tight: the outer ranges against what the rechecked geometries reach (measured: median
    // 1.41, the largest 1.62 — the affine form's remainder over the set's outer box, at this
    // set's scale, not the maxima, which are refined to 0.5%).
    ratios.sort_by(f64::total_cmp);
    let (median, largest) = (ratios[ratios.len() / 2], ratios[ratios.len() - 1]);
    println!("outer / attained: median {median:.3}, largest {largest:.3}");
    assert!(
        median < 1.5 && largest < 2.0,
        "outer / attained: median {median}, largest {largest}"
    );
}

/// A prediction whose enclosures fail where an input box holds 0: `x_k / u_k`.
#[interval_model]
fn ratio<S: Scalar>(x: &[S; 4], m: &[S; 4]) -> [S; 2] {
    [x[0] / m[0], x[1] / m[1]]
}

/// The ratio as a prediction over the planar arm's set.
struct Over;

impl Prediction<4, 4, 4, 2, 2> for Over {
    type Model = Ratio;

    fn model(&self) -> &Ratio {
        &Ratio
    }

    fn second_order(
        &self,
        x: &[Jet<Quadratic<2>, 4>; 4],
        m: &[Jet<Quadratic<2>, 4>; 4],
    ) -> [Jet<Quadratic<2>, 4>; 2] {
        ratio(x, m)
    }

    fn push(&self, set: &mut CertifiedSet<4, 4>, direction: &[f64; 4]) -> bool {
        set.extreme_point(&PlanarTip, direction).is_some()
    }
}

#[test]
fn a_prediction_whose_enclosure_fails_is_not_made_and_nothing_panics() {
    let mut rng = StdRng::seed_from_u64(7);
    let (_, set) = calibrated(&mut rng);
    let domain = [Interval::new(-1.0, 2.0), Interval::new(-1.0, 2.0)];
    let engine =
        SetAccuracy::new(&Over, set, [1.0, 0.8, 0.0, 0.0], domain, [0.0; 2]).expect("a set");
    let mut lps = engine.programs();
    // Over inputs holding 0 the ratio has no enclosure: no prediction, no panic.
    let through_zero = [Interval::new(-1.0, 1.0), Interval::new(-1.0, 1.0)];
    assert_eq!(engine.predict(&through_zero, false, &mut lps), None);
    // Away from 0 it holds every catalogued geometry's ratio.
    let u = [Interval::new(1.5, 1.5), Interval::new(2.0, 2.0)];
    let p = engine.predict(&u, false, &mut lps).expect("a prediction");
    for g in engine.catalogue() {
        for (k, q) in [1.5, 2.0].iter().enumerate() {
            let v = g[k] / q;
            assert!(p.outer[k].inf() - 1e-12 <= v && v <= p.outer[k].sup() + 1e-12);
        }
    }
}

/// A spatial two-joint arm (a base turning about `z`, a link raised by the second joint):
/// `x = (l1, l2, o1, o2)`, `m = (q1, q2, px, py, pz)`. Each joint enters through one rotation,
/// so the tip is affine in each joint's cosine and sine.
#[interval_model]
fn spatial_tip<S: Scalar>(x: &[S; 4], m: &[S; 5]) -> [S; 3] {
    let [l1, l2, o1, o2] = *x;
    let [q1, q2, px, py, pz] = *m;
    let (a, b) = (q1 + o1, q2 + o2);
    let reach = l1 + l2 * b.cos();
    [
        reach * a.cos() - px,
        reach * a.sin() - py,
        l2 * b.sin() + l1 * 0.25 - pz,
    ]
}

/// The spatial tip as a prediction with angular inputs: boxes wider than 0.2 rad take the arcs'
/// vertices, and the error's norm the sphere's cover.
struct SpatialTipPoint;

impl Prediction<4, 5, 5, 2, 3> for SpatialTipPoint {
    const SECOND_ORDER_WIDTH: f64 = 0.2;
    const ANGULAR_INPUTS: bool = true;
    type Model = SpatialTip;

    fn model(&self) -> &SpatialTip {
        &SpatialTip
    }

    fn second_order(
        &self,
        x: &[Jet<Quadratic<2>, 4>; 4],
        m: &[Jet<Quadratic<2>, 4>; 5],
    ) -> [Jet<Quadratic<2>, 4>; 3] {
        spatial_tip(x, m)
    }

    fn push(&self, set: &mut CertifiedSet<4, 5>, direction: &[f64; 4]) -> bool {
        set.extreme_point(&SpatialTip, direction).is_some()
    }
}

/// The spatial tip by plain trigonometry.
fn spatial(x: &[f64; 4], q: &[f64; 2]) -> [f64; 3] {
    let (a, b) = (q[0] + x[2], q[1] + x[3]);
    let reach = x[0] + x[1] * b.cos();
    [
        reach * a.cos(),
        reach * a.sin(),
        x[1] * b.sin() + 0.25 * x[0],
    ]
}

#[test]
fn wide_boxes_of_angular_inputs_keep_the_bracket_sound() {
    let mut rng = StdRng::seed_from_u64(5);
    let boxes: Vec<[Interval; 5]> = (0..16)
        .map(|_| {
            let q = [rng.random_range(-0.6..0.6), rng.random_range(-0.8..0.8)];
            let p = spatial(&TRUTH, &q);
            measured(&mut rng, [q[0], q[1], p[0], p[1], p[2]])
        })
        .collect();
    let r = certify(&SpatialTip, &prior(), &boxes, &Settings::default());
    assert_eq!(r.status, Status::Consistent);
    let (r_outer, witness) = (r.outer, r.witness.expect("a certified point"));
    let set = engine_set(&boxes, &r_outer, &witness);
    // Far outside the measured joints (the error grows there), boxes of up to two radians.
    let nominal = [1.0, 0.8, 0.0, 0.0];
    let domain = [Interval::new(-2.0, 2.0), Interval::new(-1.2, 2.0)];
    let engine =
        SetAccuracy::new(&SpatialTipPoint, set, nominal, domain, [JOINT_ERROR; 2]).expect("a set");
    let b = bracket_over_set(
        &engine,
        &BracketSettings {
            rel_tol: 0.05,
            max_boxes: 150,
        },
    );
    assert!(
        b.upper.is_finite() && b.lower > 0.0 && b.upper >= b.lower,
        "{b:?}"
    );
    let mut geometries = vec![TRUTH];
    geometries.extend(engine.catalogue());
    for g in &geometries {
        assert!(is_consistent_point(&SpatialTip, g, &boxes), "{g:?}");
    }
    for k in 0..4000 {
        let g = &geometries[k % geometries.len()];
        let q = [
            rng.random_range(domain[0].inf()..=domain[0].sup()),
            rng.random_range(domain[1].inf()..=domain[1].sup()),
        ];
        let real = q.map(|v| v + rng.random_range(-JOINT_ERROR..=JOINT_ERROR));
        let (p, p0) = (spatial(g, &real), spatial(&nominal, &q));
        let e = (0..3).map(|c| (p[c] - p0[c]).powi(2)).sum::<f64>().sqrt();
        assert!(e <= b.upper * (1.0 + 1e-9), "error {e} above {}", b.upper);
    }
    // Single boxes of 0.8 rad per joint, the controller's geometry off the set: each bound is
    // the arcs' alone (no split to hide behind), tight enough that a vertex missed shows.
    let far = [1.03, 0.78, 0.02, -0.01];
    for (a, c) in [(-1.5, -1.0), (-0.4, 0.2), (0.6, 1.2), (1.2, -0.6)] {
        let wide = [Interval::new(a, a + 0.8), Interval::new(c, c + 0.8)];
        let root = bracket_over_set(
            &SetAccuracy::new(
                &SpatialTipPoint,
                engine_set(&boxes, &r_outer, &witness),
                far,
                wide,
                [JOINT_ERROR; 2],
            )
            .expect("a set"),
            &BracketSettings {
                rel_tol: 0.0,
                max_boxes: 1,
            },
        );
        for k in 0..2000 {
            let g = &geometries[k % geometries.len()];
            let q = wide.map(|d| rng.random_range(d.inf()..=d.sup()));
            let real = q.map(|v| v + rng.random_range(-JOINT_ERROR..=JOINT_ERROR));
            let (p, p0) = (spatial(g, &real), spatial(&far, &q));
            let e = (0..3).map(|c| (p[c] - p0[c]).powi(2)).sum::<f64>().sqrt();
            assert!(e <= root.upper, "error {e} above the box's {}", root.upper);
        }
    }
    let w = b.worst.as_ref().expect("an instance");
    assert!(is_consistent_point(&SpatialTip, &w.theta, &boxes));
    let (p, p0) = (spatial(&w.theta, &w.reached), spatial(&nominal, &w.inputs));
    let value = (0..3).map(|c| (p[c] - p0[c]).powi(2)).sum::<f64>().sqrt();
    assert!(value >= b.lower * (1.0 - 1e-9), "{value} below {}", b.lower);
}

/// The spatial arm's certified set from its measurements, outer box and witness.
fn engine_set(
    boxes: &[[Interval; 5]],
    outer: &[Interval; 4],
    witness: &[f64; 4],
) -> CertifiedSet<4, 5> {
    CertifiedSet::new(&SpatialTip, &Cover::single(*outer), boxes, &[*witness], 4)
}

#[test]
fn an_arc_lies_in_its_triangle_for_every_function_affine_in_its_cosine_and_sine() {
    // max over the arc of A cos φ + B sin φ + C is at most the largest value at the triangle's
    // vertices (the lemma the wide boxes rest on), and the triangle is not much larger.
    let mut rng = StdRng::seed_from_u64(3);
    for _ in 0..2000 {
        let lo = rng.random_range(-4.0..4.0);
        let arc = Interval::new(lo, lo + rng.random_range(1e-3..2.4));
        let vertices = arc_vertices(arc).expect("an arc narrower than the widest");
        let (a, b, c) = (
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        );
        let f = |phi: Interval| {
            Interval::point(a) * phi.cos() + Interval::point(b) * phi.sin() + Interval::point(c)
        };
        let at_vertices = vertices
            .iter()
            .map(|evaluations| {
                evaluations
                    .iter()
                    .fold(Interval::ZERO, |s, (phi, w)| s + *w * f(*phi))
                    .sup()
            })
            .fold(f64::NEG_INFINITY, f64::max);
        for k in 0..=64 {
            let phi = arc.inf() + arc.wid() * k as f64 / 64.0;
            let v = a * phi.cos() + b * phi.sin() + c;
            assert!(
                v <= at_vertices + 1e-12,
                "{v} above {at_vertices} on {arc:?}"
            );
        }
    }
    // An arc too wide for a triangle gets none; a point, itself.
    assert!(arc_vertices(Interval::new(0.0, 3.0)).is_none());
    assert_eq!(arc_vertices(Interval::point(0.5)).map(|v| v.len()), Some(1));
}

#[test]
fn the_sphere_cover_bounds_the_norm_of_every_point_and_comes_within_two_percent() {
    // Point clouds with one long spike in a random direction: the cover's bound from the exact
    // support function is at least every point's norm, and close to the largest.
    let mut rng = StdRng::seed_from_u64(9);
    for _ in 0..200 {
        let mut points: Vec<[f64; 3]> = (0..20)
            .map(|_| core::array::from_fn(|_| rng.random_range(-0.3..0.3)))
            .collect();
        let d: [f64; 3] = core::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        points.push(d.map(|v| v / n));
        let support = |u: &[f64; 3]| {
            points
                .iter()
                .map(|p| {
                    (0..3)
                        .fold(Interval::ZERO, |s, c| {
                            s + Interval::point(u[c]) * Interval::point(p[c])
                        })
                        .sup()
                })
                .fold(f64::NEG_INFINITY, f64::max)
        };
        // Asked to reach the spike itself: refined to the tolerance.
        let bound = cover_bound(f64::INFINITY, 1.0, |_, u| support(u));
        assert!(bound >= 1.0, "{bound} below the spike's norm 1");
        assert!(bound <= 1.02, "{bound}: the refinement stopped early");
    }
    // A failed bound (infinite along every direction) gives no bound, not a panic.
    assert_eq!(
        cover_bound(f64::INFINITY, 1.0, |_, _| f64::INFINITY),
        f64::INFINITY
    );
}
