//! The tests of `calib_pipeline::design`.

use calib_pipeline::design::*;

/// Two parameters; candidates are directions `(cos t, sin t)` scaled by `s`.
fn planar(angles: &[f64], s: f64) -> Group {
    Group {
        dim: 2,
        rows: angles
            .iter()
            .map(|t| vec![vec![s * t.cos(), s * t.sin()]])
            .collect(),
    }
}

#[test]
fn widths_of_a_polytope_known_in_closed_form() {
    // |10 δ0| <= 1 and |10 δ1| <= 1: widths 0.2 each; with nothing measured, the prior (2).
    let g = planar(&[0.0, std::f64::consts::FRAC_PI_2], 10.0);
    let w = linearized_widths(&g, &[0, 1]);
    assert!(
        (w[0] - 0.2).abs() < 1e-12 && (w[1] - 0.2).abs() < 1e-12,
        "{w:?}"
    );
    assert_eq!(linearized_widths(&g, &[]), vec![2.0, 2.0]);
    // One diagonal row |10(δ0 + δ1)/√2| <= 1 leaves the box's corners (1, -1) in: no gain.
    let d = planar(&[std::f64::consts::FRAC_PI_4], 10.0);
    assert_eq!(linearized_widths(&d, &[0]), vec![2.0, 2.0]);
}

#[test]
fn the_certified_criterion_picks_complementary_directions() {
    // Candidates: three nearly parallel directions and one orthogonal; the second pick must
    // be the orthogonal one (a D-optimal pick would agree here; the LP sees it too).
    let g = planar(&[0.0, 0.01, 0.02, 1.5], 10.0);
    let picked = greedy_design(
        std::slice::from_ref(&g),
        &[],
        2,
        Criterion::Certified,
        &|| {},
    );
    assert!(picked.contains(&3), "{picked:?}");
    let d = greedy_design(
        std::slice::from_ref(&g),
        &[],
        2,
        Criterion::DOptimal,
        &|| {},
    );
    assert!(d.contains(&3), "{d:?}");
    // Starting from candidate 3 already measured, the next pick is one of the others.
    let more = greedy_design(&[g], &[3], 1, Criterion::Certified, &|| {});
    assert!(more.len() == 1 && more[0] != 3);
}

#[test]
fn greedy_gains_match_recomputed_widths() {
    // The skipped LPs are exactly those whose optimum the candidate does not cut: the gain
    // the greedy step computes equals the drop of Σ ln(width) recomputed from scratch.
    let angles: Vec<f64> = (0..12).map(|k| 0.37 * k as f64).collect();
    let g = planar(&angles, 3.0);
    let groups = [g.clone(), planar(&angles, 5.0)];
    let chosen = [0, 5];
    let current = optima(&groups, &chosen);
    let mut s = Solver::default();
    let total = |ch: &[usize]| -> f64 {
        groups
            .iter()
            .map(|g| linearized_widths(g, ch).iter().map(|w| w.ln()).sum::<f64>())
            .sum()
    };
    for c in 1..12 {
        if chosen.contains(&c) {
            continue;
        }
        let gain = certified_gain(&groups, &chosen, &current, c, &mut s);
        let recomputed = total(&chosen) - total(&[0, 5, c]);
        assert!(
            (gain - recomputed).abs() < 1e-9,
            "{c}: {gain} vs {recomputed}"
        );
    }
}

#[test]
fn exchanges_never_worsen_a_design_and_fix_a_bad_one() {
    // A design of two nearly parallel directions is improved by swapping one for the
    // orthogonal candidate.
    let g = planar(&[0.0, 0.01, 0.02, 1.5], 10.0);
    let groups = [g];
    let before = log_widths(&groups, &[0, 1]);
    let after = exchange(&groups, &[], &[0, 1], 3);
    assert!(after.contains(&3), "{after:?}");
    assert!(log_widths(&groups, &after) < before);
    // A design that is already best stays.
    assert_eq!(exchange(&groups, &[], &after, 3), after);
}

#[test]
fn criteria_parse_from_their_command_line_names() {
    assert_eq!("certified".parse(), Ok(Criterion::Certified));
    assert_eq!("d-optimal".parse(), Ok(Criterion::DOptimal));
    assert!("a-optimal".parse::<Criterion>().is_err());
}
