//! The tests of `calib_gough::accuracy::pose_error`.

use calib_gough::accuracy::enclosure::{AccuracyProblem, PoseVector};
use calib_gough::accuracy::pose_error::*;
use calib_gough::workspace::Workspace;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// The floating-point move that scores the search's second climb is the reached pose the
/// instance's proof encloses (the same solution, followed from the commanded pose), at random
/// poses and sign patterns of a robot whose moves are centimetres.
#[test]
fn the_search_score_is_the_proved_reached_move() {
    let spec = crate::pose_error::centimetre_robot();
    let workspace = Workspace {
        x: [-2.0, 2.0],
        y: [-2.0, 2.0],
        z: [58.0, 62.0],
        tilt_deg: 5.0,
        stroke: None,
    };
    let problem = AccuracyProblem::new(&spec, &workspace);
    let domain = problem.domain();
    let eps = 0.0005;
    let mut rng = StdRng::seed_from_u64(4);
    let mut checked = 0;
    while checked < 20 {
        let x: PoseVector =
            core::array::from_fn(|k| rng.random_range(domain[k].inf()..=domain[k].sup()));
        if !problem.proved_feasible(&x) {
            continue;
        }
        let pattern = rng.random_range(0..64u32);
        let (theta, actuator) = pattern_instance(&problem, &x, pattern, eps);
        let Some(proved) = prove_instance(&problem, &x, theta, actuator) else {
            continue;
        };
        checked += 1;
        for (kind, value) in [
            (PoseErrorKind::Position, proved.position),
            (PoseErrorKind::Orientation, proved.orientation_deg),
        ] {
            let mut score = exact_size(&problem, &x, pattern, eps, kind);
            if kind == PoseErrorKind::Orientation {
                score = score.to_degrees();
            }
            assert!(
                (score - value).abs() <= 1e-6 * (1.0 + value),
                "{kind:?}: score {score}, proved {value}"
            );
        }
    }
}
