//! The certified maximum (`calib_core::maximize`): over random smooth functions the upper bound
//! is never below any sampled value, the lower bound is attained at the reported point (rechecked
//! in plain floating point), the bracket meets its tolerance, monotone coordinates are moved to
//! their faces, and failed enclosures never drop a box.

use calib_core::{maximize, Interval, MaximumSettings, Objective, Scalar};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// `f(x) = Σ a_i sin(b_i x_i + c_i) + Σ_{i<j} d_ij x_i x_j`: wavy, non-separable, many local
/// maxima.
#[derive(Clone, Debug)]
struct Wavy<const N: usize> {
    /// Whether [`Objective::gradient`] is offered (the mean-value form and monotonicity).
    gradient: bool,
    /// Whether [`Objective::split_weights`] is offered (each coordinate's largest slope).
    weights: bool,
    a: [f64; N],
    b: [f64; N],
    c: [f64; N],
    d: [[f64; N]; N],
}

impl<const N: usize> Wavy<N> {
    fn random(rng: &mut StdRng) -> Self {
        Wavy {
            gradient: false,
            weights: false,
            a: core::array::from_fn(|_| rng.random_range(-2.0..2.0)),
            b: core::array::from_fn(|_| rng.random_range(-4.0..4.0)),
            c: core::array::from_fn(|_| rng.random_range(-3.0..3.0)),
            d: core::array::from_fn(|_| core::array::from_fn(|_| rng.random_range(-1.0..1.0))),
        }
    }

    fn eval<S: Scalar>(&self, x: &[S; N]) -> S {
        let mut f = S::cst(0.0);
        for i in 0..N {
            f = f + S::cst(self.a[i]) * (S::cst(self.b[i]) * x[i] + S::cst(self.c[i])).sin();
            for j in i + 1..N {
                f = f + S::cst(self.d[i][j]) * x[i] * x[j];
            }
        }
        f
    }
}

impl<const N: usize> Objective<N> for Wavy<N> {
    fn enclose(&self, x: &[Interval; N]) -> Interval {
        self.eval(x)
    }

    /// `|a_i b_i| + Σ_{j≠i} |d_ij| mag(x_j)`: a bound of `|∂f/∂x_i|` over the box.
    fn split_weights(&self, x: &[Interval; N]) -> Option<[f64; N]> {
        self.weights.then(|| {
            core::array::from_fn(|i| {
                let mut w = (self.a[i] * self.b[i]).abs();
                for (j, xj) in x.iter().enumerate().filter(|(j, _)| *j != i) {
                    let d = if i < j { self.d[i][j] } else { self.d[j][i] };
                    w += d.abs() * xj.mag();
                }
                w
            })
        })
    }

    /// `∂f/∂x_i = a_i b_i cos(b_i x_i + c_i) + Σ_{j≠i} d_ij x_j` (with `d_ij` for `i < j`).
    fn gradient(&self, x: &[Interval; N]) -> Option<[Interval; N]> {
        let c = Interval::point;
        self.gradient.then(|| {
            core::array::from_fn(|i| {
                let mut g = c(self.a[i] * self.b[i]) * (c(self.b[i]) * x[i] + c(self.c[i])).cos();
                for (j, xj) in x.iter().enumerate().filter(|(j, _)| *j != i) {
                    let d = if i < j { self.d[i][j] } else { self.d[j][i] };
                    g += c(d) * *xj;
                }
                g
            })
        })
    }
}

/// Maximises random [`Wavy`] functions over random boxes to `rel_tol` and checks the bracket.
fn check_random<const N: usize>(seeds: std::ops::Range<u64>, gradient: bool, rel_tol: f64) {
    check_random_split::<N>(seeds, gradient, false, rel_tol);
}

/// [`check_random`], with or without the split weights.
fn check_random_split<const N: usize>(
    seeds: std::ops::Range<u64>,
    gradient: bool,
    weights: bool,
    rel_tol: f64,
) {
    for seed in seeds {
        let mut rng = StdRng::seed_from_u64(seed);
        let f = Wavy::<N> {
            gradient,
            weights,
            ..Wavy::random(&mut rng)
        };
        let domain: [Interval; N] = core::array::from_fn(|_| {
            let lo = rng.random_range(-2.0..0.0);
            Interval::new(lo, lo + rng.random_range(0.5..2.5))
        });
        let settings = MaximumSettings {
            rel_tol,
            abs_tol: 1e-9,
            ..Default::default()
        };
        let m = maximize(&f, &domain, &settings);
        assert!(m.converged, "seed {seed}: {} boxes", m.boxes);
        assert!(m.lower <= m.upper, "seed {seed}");
        assert!(
            m.upper - m.lower <= rel_tol * m.lower.abs() + 1e-9,
            "seed {seed}"
        );
        // The lower bound is attained: recheck in plain floating point, at a point of the domain.
        assert!(
            (0..N).all(|j| domain[j].contains(m.argmax[j])),
            "seed {seed}"
        );
        assert!(f.eval(&m.argmax) >= m.lower - 1e-12, "seed {seed}");
        // No sampled value exceeds the upper bound (corners included).
        for k in 0..4000 {
            let p: [f64; N] = core::array::from_fn(|j| {
                if k < 1 << N {
                    if (k >> j) & 1 == 1 {
                        domain[j].sup()
                    } else {
                        domain[j].inf()
                    }
                } else {
                    rng.random_range(domain[j].inf()..=domain[j].sup())
                }
            });
            let v = f.eval(&p);
            assert!(
                v <= m.upper + 1e-12,
                "seed {seed}: f({p:?}) = {v} > {}",
                m.upper
            );
        }
        // The ratio is the bracket's: the bounds' quotient, +∞ without a positive lower bound.
        let r = m.ratio();
        if m.lower > 0.0 {
            assert_eq!(r, m.upper / m.lower);
            assert!(r >= 1.0, "seed {seed}: ratio {r}");
        } else {
            assert_eq!(r, f64::INFINITY);
        }
    }
}

#[test]
fn random_functions_are_bracketed_soundly() {
    // With the gradient (mean-value form): tight brackets.
    check_random::<1>(0..40, true, 1e-6);
    check_random::<2>(100..140, true, 1e-5);
    check_random::<3>(200..230, true, 1e-4);
    // The natural enclosure alone converges only linearly: looser brackets, same soundness.
    check_random::<2>(300..320, false, 1e-3);
    check_random::<3>(400..410, false, 1e-2);
}

/// Split weights change where boxes are split, never the bracket's soundness; where one
/// coordinate barely matters they save boxes.
#[test]
fn split_weights_keep_brackets_sound_and_spare_flat_coordinates() {
    check_random_split::<2>(500..520, true, true, 1e-5);
    check_random_split::<3>(600..610, false, true, 1e-2);
    let f = |weights| Wavy::<3> {
        gradient: false,
        weights,
        a: [2.0, 1e-9, 1e-9],
        b: [4.0, 4.0, 4.0],
        c: [0.3, 0.1, 0.2],
        d: [[0.0; 3]; 3],
    };
    let domain = [Interval::new(-1.0, 1.0); 3];
    let settings = MaximumSettings {
        rel_tol: 1e-6,
        ..Default::default()
    };
    let (plain, weighted) = (
        maximize(&f(false), &domain, &settings),
        maximize(&f(true), &domain, &settings),
    );
    assert!(plain.converged && weighted.converged);
    assert!(
        weighted.boxes * 2 < plain.boxes,
        "{} boxes with weights, {} without",
        weighted.boxes,
        plain.boxes
    );
}

/// `x0 + x1 - x2²` with its gradient: increasing in x0 and x1 everywhere.
struct Rising;

impl Objective<3> for Rising {
    fn enclose(&self, x: &[Interval; 3]) -> Interval {
        x[0] + x[1] - x[2].sqr()
    }

    fn gradient(&self, x: &[Interval; 3]) -> Option<[Interval; 3]> {
        Some([
            Interval::point(1.0),
            Interval::point(1.0),
            Interval::point(-2.0) * x[2],
        ])
    }
}

/// [`Rising`] without its gradient.
struct RisingBlind;

impl Objective<3> for RisingBlind {
    fn enclose(&self, x: &[Interval; 3]) -> Interval {
        Rising.enclose(x)
    }
}

#[test]
fn monotone_coordinates_go_to_their_faces() {
    let domain = [
        Interval::new(-1.0, 1.0),
        Interval::new(0.0, 2.0),
        Interval::new(-1.0, 0.5),
    ];
    let settings = MaximumSettings {
        rel_tol: 1e-6,
        ..Default::default()
    };
    let with = maximize(&Rising, &domain, &settings);
    let without = maximize(&RisingBlind, &domain, &settings);
    for m in [&with, &without] {
        assert!(m.converged);
        assert!(m.lower <= 3.0 && 3.0 <= m.upper, "{m:?}");
        assert!(m.upper - m.lower <= 3e-6);
    }
    assert_eq!(with.argmax[0], 1.0);
    assert_eq!(with.argmax[1], 2.0);
    assert!(
        with.boxes * 4 < without.boxes,
        "{} boxes with the gradient, {} without",
        with.boxes,
        without.boxes
    );
}

/// `sqrt(x)` whose enclosure fails (is empty) on every box reaching below 0: such boxes must stay.
struct Fragile;

impl Objective<1> for Fragile {
    fn enclose(&self, x: &[Interval; 1]) -> Interval {
        if x[0].inf() < 0.0 {
            Interval::EMPTY
        } else {
            x[0].sqrt()
        }
    }
}

#[test]
fn failed_enclosures_never_drop_a_box() {
    let domain = [Interval::new(-1.0, 4.0)];
    let budget = MaximumSettings {
        max_boxes: 2000,
        ..Default::default()
    };
    let m = maximize(&Fragile, &domain, &budget);
    assert!(m.lower <= 2.0 && m.lower > 0.0, "{m:?}");
    // Where the enclosure fails nothing is proved, and the bracket says so.
    assert!(!m.converged && m.upper == f64::INFINITY, "{m:?}");
    assert!(m.frontier[0].inf() < 0.0);
    // Where it works, the bracket closes.
    let m = maximize(
        &Fragile,
        &[Interval::new(0.0, 4.0)],
        &MaximumSettings::default(),
    );
    assert!(m.converged && m.lower <= 2.0 && 2.0 <= m.upper && m.upper <= 2.0 * 1.01);
    // A budget of one box: nothing proved beyond the trivial bracket.
    let tiny = MaximumSettings {
        max_boxes: 1,
        ..Default::default()
    };
    let m = maximize(&Fragile, &domain, &tiny);
    assert!(!m.converged && m.upper == f64::INFINITY);
    // An unbounded domain gives the trivial bracket.
    let m = maximize(&Fragile, &[Interval::new(0.0, f64::INFINITY)], &tiny);
    assert_eq!((m.lower, m.upper), (f64::NEG_INFINITY, f64::INFINITY));
}

/// `x (1 - x)` on `[0, 1]` with a local search that walks from any point to `x = 1/2`.
struct Ascending;

impl Objective<1> for Ascending {
    fn enclose(&self, x: &[Interval; 1]) -> Interval {
        x[0] * (Interval::ONE - x[0])
    }

    fn improve(&self, _x: &[f64; 1]) -> Option<([f64; 1], f64)> {
        // 1/4 is exact at x = 1/2 in floating point.
        Some(([0.5], 0.25))
    }
}

#[test]
fn a_local_search_raises_the_lower_bound_and_moves_the_argmax() {
    let m = maximize(
        &Ascending,
        &[Interval::new(0.0, 1.0)],
        &MaximumSettings::default(),
    );
    assert!(m.converged && m.lower == 0.25 && m.argmax == [0.5], "{m:?}");
    assert!(0.25 <= m.upper && m.upper <= 0.25 * 1.01, "{m:?}");
}

/// Over a finite list of thin boxes of random wavy functions: the upper bound is at least the
/// function at every listed point (sampled inside each box too), the lower bound is the value at
/// the reported point (rechecked in floating point) and at most the upper bound, the frontier is
/// one of the boxes, and the answer does not depend on the list's order.
#[test]
fn lists_are_bracketed_soundly() {
    let mut rng = StdRng::seed_from_u64(51);
    for _ in 0..40 {
        let f = Wavy::<3>::random(&mut rng);
        let points: Vec<[f64; 3]> = (0..rng.random_range(1..60))
            .map(|_| core::array::from_fn(|_| rng.random_range(-2.0..2.0)))
            .collect();
        let width = if rng.random_bool(0.5) { 0.0 } else { 1e-6 };
        let list: Vec<[Interval; 3]> = points
            .iter()
            .map(|p| p.map(|v| Interval::mid_rad(v, width)))
            .collect();
        let m = calib_core::maximize_over_list(|| f.clone(), &list, &MaximumSettings::default());
        assert_eq!(m.boxes, list.len());
        for b in &list {
            for _ in 0..4 {
                let x: [f64; 3] =
                    core::array::from_fn(|j| rng.random_range(b[j].inf()..=b[j].sup()));
                assert!(f.eval(&x) <= m.upper, "{:?} above {}", x, m.upper);
            }
        }
        assert!(list.contains(&m.frontier));
        let value = f.eval(&m.argmax);
        assert!(
            (value - m.lower).abs() <= 1e-9 * (1.0 + value.abs()),
            "{value} {m:?}"
        );
        assert!(m.lower <= m.upper);
        let best = points
            .iter()
            .map(|p| f.eval(p))
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(m.lower >= best - 1e-9 * (1.0 + best.abs()), "{best} {m:?}");
        let mut reversed = list.clone();
        reversed.reverse();
        let r =
            calib_core::maximize_over_list(|| f.clone(), &reversed, &MaximumSettings::default());
        assert_eq!((r.upper, r.lower), (m.upper, m.lower));
    }
}

/// A failed enclosure on one box of the list leaves the upper bound unproved (`+∞`), and an
/// empty list gives the trivial bracket.
#[test]
fn a_failed_box_of_a_list_proves_nothing() {
    let list = [
        [Interval::point(1.0)],
        [Interval::point(-1.0)],
        [Interval::point(4.0)],
    ];
    let m = calib_core::maximize_over_list(|| Fragile, &list, &MaximumSettings::default());
    assert_eq!(m.upper, f64::INFINITY);
    assert!(!m.converged && m.frontier == list[1], "{m:?}");
    assert!(
        m.lower <= 2.0 && m.lower > 1.999 && m.argmax == [4.0],
        "{m:?}"
    );
    let m = calib_core::maximize_over_list(|| Fragile, &list[..1], &MaximumSettings::default());
    assert!(
        m.converged && m.lower <= 1.0 && 1.0 <= m.upper && m.upper < 1.001,
        "{m:?}"
    );
    let m = calib_core::maximize_over_list(|| Fragile, &[], &MaximumSettings::default());
    assert_eq!((m.lower, m.upper), (f64::NEG_INFINITY, f64::INFINITY));
}
