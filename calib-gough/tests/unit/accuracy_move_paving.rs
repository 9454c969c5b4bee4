//! The tests of `calib_gough::accuracy::move_paving`.

use calib_core::{Interval, Model};
use calib_gough::accuracy::enclosure::AccuracyProblem;
use calib_gough::accuracy::enclosure::PoseVector;
use calib_gough::accuracy::move_paving::*;
use calib_gough::accuracy::pose_bound::ReachedChange;
use calib_gough::accuracy::{prove_instance, worst_instance, PoseErrorInstance, PoseErrorKind};
use calib_gough::workspace::Workspace;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// The centimetre-error problem of these tests: the built-in hexapod with calibrated-like
/// radii (`a_z` and `l` at ± 0.1 cm), `x, y` in `[-0.5, hi]` cm, `z` within ± 0.5 cm of 60
/// and 1° of tilt.
fn centimetre_problem(hi: f64) -> AccuracyProblem {
    let spec = crate::pose_error::centimetre_robot();
    let workspace = Workspace {
        x: [-0.5, hi],
        y: [-0.5, hi],
        z: [59.5, 60.5],
        tilt_deg: 1.0,
        stroke: None,
    };
    AccuracyProblem::new(&spec, &workspace)
}

/// A sub-box of poses that starts from its parent's pieces, and then continues from its own,
/// keeps the reached move of every instance in one of its pieces, and bounds its errors: the
/// worst instances found in the sub-box, and proved instances at random poses, geometries at
/// the vertices that make each leg's change extreme and actuator errors at `± ε`. The
/// parent's paving examines `parent_budget` boxes of moves; returns whether it closed.
fn sub_box_holds_its_instances(parent_budget: usize) -> bool {
    let mut rng = StdRng::seed_from_u64(5);
    let eps = 0.0005;
    let problem = centimetre_problem(0.5);
    let x = problem.domain();
    // A quarter of the box in position, the whole tilt.
    let quarter = centimetre_problem(0.0);
    let sub = quarter.domain();
    assert!((0..6).all(|k| sub[k].is_subset_of(x[k])));
    let mut found: Vec<PoseErrorInstance> = [PoseErrorKind::Position, PoseErrorKind::Orientation]
        .into_iter()
        .map(|kind| worst_instance(&quarter, kind, eps, 1).expect("a worst instance"))
        .collect();
    let target = [found[0].position, found[1].orientation_deg];
    let parent = MovePaving::new(&problem, &x, eps, None).expect("paved");
    let (closed, _, paved) = parent.bound(target, parent_budget, None);
    let paved = paved.expect("pieces of the parent's paving");
    let child = MovePaving::new(&quarter, &sub, eps, Some(&paved)).expect("paved");
    let (bound, _, kept) = child.bound(target, 2000, Some(&paved));
    let (bound, kept) = bound.zip(kept).expect("the sub-box's paving closes");
    while found.len() < 14 {
        let pose: PoseVector =
            core::array::from_fn(|k| rng.random_range(sub[k].inf()..=sub[k].sup()));
        if !quarter.proved_feasible(&pose) {
            continue;
        }
        let pattern: u32 = rng.random_range(0..64);
        let (theta, actuator) = (0..6)
            .map(|i| {
                let high = pattern >> i & 1 == 1;
                let e = if high { eps } else { -eps };
                (quarter.vertex(i, &pose, !high), e)
            })
            .unzip();
        found.extend(prove_instance(&quarter, &pose, theta, actuator));
    }
    // The sub-box's paving continued from its own pieces (a refinement) holds them too.
    let (again, _, more) = child.bound(target, 1000, Some(&kept));
    let (again, more) = again.zip(more).expect("the sub-box's own proof holds");
    for (bound, kept) in [(bound, kept), (again, more)] {
        for i in &found {
            let held = kept
                .pieces
                .iter()
                .any(|q| (0..6).all(|k| q.moves[k].contains(i.reached[k].mid())));
            assert!(held, "reached move {:?} in no piece", i.reached);
            assert!(
                i.position <= bound[0] && i.orientation_deg <= bound[1],
                "instance {} cm {}° above the sub-box's bounds {bound:?}",
                i.position,
                i.orientation_deg
            );
        }
    }
    closed.is_some()
}

/// A sub-box continues from a closed parent's pieces without closing `∂B` again.
#[test]
fn a_sub_box_bounds_its_instances_from_its_parents_pieces() {
    assert!(
        sub_box_holds_its_instances(2000),
        "the parent's paving closes"
    );
}

/// A sub-box continues the closing of a parent whose paving ran out of boxes (its pieces
/// still reaching `∂B` come first).
#[test]
fn a_sub_box_continues_its_parents_open_closing() {
    assert!(
        !sub_box_holds_its_instances(40),
        "the parent's paving stays open"
    );
}

/// The geometry's share `Γ_i` encloses `G_i(X, δ, θ*) - G_i(X, δ, θ̂)` at random poses of the
/// box, moves of `y` and geometries of the box (mostly at their ends).
#[test]
fn the_geometry_share_encloses_point_differences() {
    let mut rng = StdRng::seed_from_u64(3);
    let problem = centimetre_problem(0.5);
    let x = problem.domain();
    let paving = MovePaving::new(&problem, &x, 0.0005, None).expect("centimetre moves are paved");
    let pick = |v: Interval, rng: &mut StdRng| {
        if rng.random_bool(0.5) {
            if rng.random_bool(0.5) {
                v.inf()
            } else {
                v.sup()
            }
        } else {
            rng.random_range(v.inf()..=v.sup())
        }
    };
    for _ in 0..200 {
        let y: [Interval; 6] = core::array::from_fn(|k| {
            let o = paving.outer[k];
            let (a, b) = (pick(o, &mut rng), pick(o, &mut rng));
            Interval::new(a.min(b), a.max(b))
        });
        for i in 0..6 {
            let spread = paving.geometry_spread(i, &y);
            let m = &paving.boxes[i];
            let delta: [f64; 6] = core::array::from_fn(|k| pick(y[k], &mut rng));
            let pose: [f64; 6] = core::array::from_fn(|k| pick(m[k], &mut rng));
            let at = |theta: [f64; 6]| -> Interval {
                let input: [Interval; 12] = core::array::from_fn(|k| {
                    Interval::point(if k < 6 { pose[k] } else { theta[k - 6] })
                });
                ReachedChange.residual_interval(&delta.map(Interval::point), &input)
            };
            let theta: [f64; 6] = core::array::from_fn(|j| pick(m[6 + j], &mut rng));
            let diff = at(theta) - at(paving.nominal[i]);
            assert!(
                !diff.intersection(spread).is_empty(),
                "leg {i}: {diff} outside {spread}"
            );
        }
    }
}
