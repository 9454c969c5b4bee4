//! The leg residual's Hessian over boxes (`LegModel::hessian_over`, for the certified sets'
//! Taylor rows): at a point it agrees with finite differences of the generated Jacobians, and over
//! a box it holds every sampled point's, for both orientation kinds.

use calib_core::{Interval, Model};
use calib_gough::LegModel;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// A leg about a typical geometry and configuration of `sample21`, as `(x, m)` boxes of the given
/// half-widths (cm; the orientation's entries a hundredth of them).
fn boxes(kind: LegModel, rng: &mut StdRng, r: f64) -> ([Interval; 7], [Interval; 8]) {
    let x0 = [30.0, 5.0, 0.0, 15.0, 3.0, 0.0, 50.0];
    let orientation = match kind {
        LegModel::AxisAngle => [0.3, 0.5, 0.8, 6.0],
        LegModel::Rodrigues => [0.02, -0.03, 0.05, 0.0],
    };
    let m0 = [
        1.0,
        -2.0,
        60.0,
        orientation[0],
        orientation[1],
        orientation[2],
        orientation[3],
        8.0,
    ];
    let x = x0.map(|v| Interval::mid_rad(v + rng.random_range(-r..r), r));
    let m: [Interval; 8] = core::array::from_fn(|i| {
        let w = if (3..7).contains(&i) { r / 100.0 } else { r };
        if kind == LegModel::Rodrigues && i == 6 {
            Interval::ZERO
        } else {
            Interval::mid_rad(m0[i] + rng.random_range(-w..w), w)
        }
    });
    (x, m)
}

/// Every symbol of nonzero width.
fn symbols(x: &[Interval; 7], m: &[Interval; 8]) -> Vec<usize> {
    (0..7)
        .filter(|&j| x[j].wid() > 0.0)
        .chain((0..8).filter(|&i| m[i].wid() > 0.0).map(|i| 7 + i))
        .collect()
}

/// The gradient in every symbol at a point.
fn gradient(kind: LegModel, x: &[f64; 7], m: &[f64; 8], symbols: &[usize]) -> Vec<f64> {
    let e = kind.evaluate(x, m);
    symbols
        .iter()
        .map(|&s| if s < 7 { e.dx[s] } else { e.dm[s - 7] })
        .collect()
}

#[test]
fn the_legs_hessian_matches_finite_differences_and_holds_over_boxes() {
    let mut rng = StdRng::seed_from_u64(3);
    for kind in [LegModel::AxisAngle, LegModel::Rodrigues] {
        for trial in 0..4 {
            let (x, m) = boxes(kind, &mut rng, 0.3);
            let s = symbols(&x, &m);
            let n = s.len();
            let over = kind.hessian_over(&x, &m, &s).expect("a Hessian");
            for _ in 0..20 {
                let xp: [f64; 7] = x.map(|b| rng.random_range(b.inf()..=b.sup()));
                let mp: [f64; 8] = m.map(|b| rng.random_range(b.inf()..=b.sup()));
                let at = kind
                    .hessian_over(&xp.map(Interval::point), &mp.map(Interval::point), &s)
                    .expect("a Hessian");
                for b in 0..n {
                    let h = 1e-6;
                    let (mut x1, mut x2, mut m1, mut m2) = (xp, xp, mp, mp);
                    if s[b] < 7 {
                        x1[s[b]] += h;
                        x2[s[b]] -= h;
                    } else {
                        m1[s[b] - 7] += h;
                        m2[s[b] - 7] -= h;
                    }
                    let (g1, g2) = (gradient(kind, &x1, &m1, &s), gradient(kind, &x2, &m2, &s));
                    for a in 0..n {
                        let fd = (g1[a] - g2[a]) / (2.0 * h);
                        let exact = at[a * n + b];
                        let tol = 1e-4 * (1.0 + fd.abs());
                        assert!(
                            (exact.mid() - fd).abs() <= tol,
                            "{kind:?} {trial}: ∂²f/∂{a}∂{b} {exact:?} against {fd}"
                        );
                        assert!(
                            exact.is_subset_of(over[a * n + b]),
                            "{kind:?} {trial}: the point's {exact:?} outside the box's {:?}",
                            over[a * n + b]
                        );
                    }
                }
            }
        }
    }
}
