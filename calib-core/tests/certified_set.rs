//! The certified set: its pieces hold every consistent parameter vector (found by exhaustive
//! sampling and an independent corner test), its bounds of linear functions and maxima hold over
//! them, its lower bounds and calibrated points are proved consistent (rechecked independently),
//! and it is much narrower than its box where the data fix a combination of parameters.

use calib_core::{
    calibrated_point, hull, interval_model, is_consistent_by_corners, maximize_over_set,
    CertifiedSet, Interval, PointRule, Scalar, SetMaximumSettings, SetObjective, Settings,
};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// A line through measured points `(t, y)`: `y = x0 + x1 t`. With every `t` near 1 the data fix
/// `x0 + x1` far better than either: a thin set along `(1, -1)`.
#[interval_model]
pub fn line<S: Scalar>(x: &[S; 2], m: &[S; 2]) -> S {
    x[0] + x[1] * m[0] - m[1]
}

/// Points on `y = 1 + 2 t` at `t` in [0.9, 1.1], `y` known within ± 0.01 and `t` within ± 0.001.
fn data(rng: &mut StdRng, n: usize) -> Vec<[Interval; 2]> {
    (0..n)
        .map(|k| {
            let t = 0.9 + 0.2 * k as f64 / (n - 1) as f64;
            let y = 1.0 + 2.0 * t + rng.random_range(-0.01..0.01);
            [Interval::mid_rad(t, 0.001), Interval::mid_rad(y, 0.01)]
        })
        .collect()
}

fn x0() -> [Interval; 2] {
    [Interval::new(-2.0, 4.0), Interval::new(-1.0, 5.0)]
}

fn the_set(seed: u64) -> (CertifiedSet<2, 2>, Vec<[Interval; 2]>) {
    let mut rng = StdRng::seed_from_u64(seed);
    let m = data(&mut rng, 12);
    let h = hull(&Line, &x0(), &m, &Settings::default());
    let mut points = h.inner_points.clone();
    points.extend(h.witness);
    (CertifiedSet::new(&Line, &h.cover, &m, &points, 8), m)
}

/// Consistent vectors sampled in the set's outer box, checked by the exhaustive corner test
/// (independent of the kernel's linearisations).
fn consistent_samples(set: &CertifiedSet<2, 2>, m: &[[Interval; 2]], n: usize) -> Vec<[f64; 2]> {
    let outer = set.outer().expect("a consistent set");
    // Wider than the outer box, so that a set that lost a solution near its edge shows it.
    let wide: [Interval; 2] = outer.map(|v| Interval::mid_rad(v.mid(), 1.5 * v.rad()));
    let mut rng = StdRng::seed_from_u64(99);
    (0..n)
        .map(|_| wide.map(|v| rng.random_range(v.inf()..=v.sup())))
        .filter(|x| is_consistent_by_corners(&Line, x, m))
        .collect()
}

#[test]
fn every_consistent_vector_lies_in_a_piece_and_under_every_support_bound() {
    for seed in 0..4 {
        let (set, m) = the_set(seed);
        let samples = consistent_samples(&set, &m, 40_000);
        assert!(
            samples.len() > 100,
            "seed {seed}: {} samples",
            samples.len()
        );
        let mut q = set.query();
        let mut rng = StdRng::seed_from_u64(seed);
        let directions: Vec<[f64; 2]> = (0..64)
            .map(|_| [rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)])
            .collect();
        let support: Vec<f64> = directions.iter().map(|w| q.support(w)).collect();
        for x in &samples {
            assert!(set.admits(x, 1e-12), "seed {seed}: {x:?} fits no piece");
            for (w, s) in directions.iter().zip(&support) {
                assert!(
                    w[0] * x[0] + w[1] * x[1] <= *s,
                    "seed {seed}: {x:?} beyond {w:?}"
                );
            }
        }
    }
}

/// On a set refined into many pieces, the bound that visits pieces by their box bound and stops
/// early is the bound of every piece solved: the smaller of each piece's program and box bounds,
/// recomputed piece by piece (the box bound in plain interval arithmetic), largest over the
/// pieces — and it holds every consistent sample.
#[test]
fn the_early_stopping_bound_is_every_pieces_bound() {
    let (mut set, m) = the_set(3);
    let settings = Settings::default();
    while set.pieces().len() < 48 {
        let widest = (0..set.pieces().len())
            .max_by(|&a, &b| {
                let w = |i: usize| set.pieces()[i].bounds()[0].wid();
                w(a).total_cmp(&w(b))
            })
            .expect("pieces");
        assert!(set.refine(&Line, widest, &settings), "a piece splits");
    }
    let samples = consistent_samples(&set, &m, 20_000);
    assert!(samples.len() > 100, "{} samples", samples.len());
    let mut rng = StdRng::seed_from_u64(5);
    let (mut q, mut each) = (set.query(), set.query());
    for _ in 0..200 {
        let slopes: [Interval; 2] = core::array::from_fn(|_| {
            Interval::mid_rad(rng.random_range(-1.0..1.0), rng.random_range(0.0..0.01))
        });
        let about = [rng.random_range(-1.0..1.0), rng.random_range(0.0..3.0)];
        let got = q.max_linear(&slopes, &about).upper;
        let every = (0..set.pieces().len())
            .map(|i| {
                let b = set.pieces()[i].bounds();
                let by_box = (slopes[0] * (b[0] - Interval::point(about[0]))
                    + slopes[1] * (b[1] - Interval::point(about[1])))
                .sup();
                each.piece_max(i, &slopes, &about).0.min(by_box)
            })
            .fold(f64::NEG_INFINITY, f64::max);
        assert_eq!(got, every, "slopes {slopes:?} about {about:?}");
        for x in &samples {
            let lo = (0..2).fold(Interval::ZERO, |s, j| {
                s + slopes[j] * (Interval::point(x[j]) - Interval::point(about[j]))
            });
            assert!(lo.inf() <= got, "{x:?}: {lo:?} above {got}");
        }
    }
}

#[test]
fn the_set_is_thin_where_its_box_is_wide() {
    let (set, m) = the_set(7);
    let outer = set.outer().expect("consistent");
    let mut q = set.query();
    // x0 + x1 is fixed by the data to about the error bound; the box lets it spread over both
    // parameters' widths.
    let sum = q.range(&[1.0, 1.0]);
    let boxed = outer[0] + outer[1];
    assert!(sum.wid() < boxed.wid() / 10.0, "{sum:?} against {boxed:?}");
    // The range is attained (to a few percent) by certified points.
    let samples = consistent_samples(&set, &m, 20_000);
    let seen = samples
        .iter()
        .fold(Interval::EMPTY, |h, x| h.hull(Interval::point(x[0] + x[1])));
    assert!(
        sum.wid() < 1.3 * seen.wid(),
        "{sum:?} against sampled {seen:?}"
    );
}

#[test]
fn a_lying_lp_engine_cannot_cut_a_consistent_vector() {
    use calib_core::{LpBackend, LpStatus, Polyhedron};
    /// Answers at random: wrong multipliers (negative, huge, NaN), wrong points, false claims.
    struct Liar(u64);
    impl LpBackend for Liar {
        fn name(&self) -> &'static str {
            "liar"
        }
        fn minimize(
            &mut self,
            p: &Polyhedron,
            _: &[f64],
            dual: &mut [f64],
            primal: &mut [f64],
        ) -> LpStatus {
            let mut next = || {
                self.0 = self
                    .0
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (self.0 >> 11) as f64 / (1u64 << 53) as f64
            };
            for d in dual.iter_mut() {
                let r = next();
                *d = if r < 0.1 {
                    f64::NAN
                } else if r < 0.3 {
                    -1e3 * r
                } else {
                    r * 1e3
                };
            }
            for (j, x) in primal.iter_mut().enumerate() {
                *x = p.lo()[j] + (p.hi()[j] - p.lo()[j]) * 3.0 * next();
            }
            [LpStatus::Optimal, LpStatus::Infeasible, LpStatus::Failed][(next() * 3.0) as usize % 3]
        }
    }
    let (set, m) = the_set(3);
    let samples = consistent_samples(&set, &m, 20_000);
    let seed = std::cell::Cell::new(1u64);
    let liar = || -> Box<dyn LpBackend> {
        seed.set(seed.get() + 1);
        Box::new(Liar(seed.get()))
    };
    let mut q = set.query_with(&liar);
    let mut rng = StdRng::seed_from_u64(5);
    for _ in 0..200 {
        let w = [rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)];
        let s = q.support(&w);
        for x in &samples {
            assert!(
                w[0] * x[0] + w[1] * x[1] <= s,
                "the liar cut {x:?} along {w:?}"
            );
        }
    }
}

/// `x0 · x1`: a nonlinear function to maximise over the set.
struct Product;

impl SetObjective<2> for Product {
    fn value(&self, x: &[Interval; 2]) -> Interval {
        x[0] * x[1]
    }
    fn slopes(&self, x: &[Interval; 2]) -> [Interval; 2] {
        [x[1], x[0]]
    }
}

#[test]
fn the_maximum_over_the_set_is_bracketed_by_a_proved_point() {
    for seed in 0..3 {
        let (mut set, m) = the_set(seed);
        let max = maximize_over_set(&Line, &mut set, &Product, &SetMaximumSettings::default());
        let samples = consistent_samples(&set, &m, 20_000);
        let best = samples.iter().map(|x| x[0] * x[1]).fold(f64::MIN, f64::max);
        assert!(
            best <= max.upper,
            "seed {seed}: sampled {best} above {max:?}"
        );
        let arg = max.argmax.expect("a proved point");
        assert!(
            is_consistent_by_corners(&Line, &arg, &m),
            "seed {seed}: {arg:?}"
        );
        assert!(arg[0] * arg[1] >= max.lower - 1e-12, "seed {seed}: {max:?}");
        assert!(max.converged && max.ratio() <= 1.01, "seed {seed}: {max:?}");
        // The refined set still holds every sampled consistent vector.
        assert!(samples.iter().all(|x| set.admits(x, 1e-12)), "seed {seed}");
    }
}

#[test]
fn the_calibrated_point_fits_every_measurement_with_room_to_spare() {
    for seed in 0..4 {
        let (mut set, m) = the_set(seed);
        // Predictions: y at t = 0 and t = 2 (the intercept and an extrapolation).
        let predictions = [[1.0, 0.0], [1.0, 2.0]];
        for rule in [
            PointRule::PredictionCentre(&predictions),
            PointRule::LeastSquares,
        ] {
            let p = calibrated_point(&Line, &mut set, rule).expect("a consistent set");
            let narrowed = calib_core::narrowed(&m, p.margin);
            assert!(
                is_consistent_by_corners(&Line, &p.x, &narrowed),
                "seed {seed}: {p:?}"
            );
            assert!(p.margin > 0.0, "seed {seed}: room to spare on these data");
            // Far better than the box's midpoint, which the thin set need not contain.
            assert!(p.deepest_misfit < 1.0, "seed {seed}: {p:?}");
        }
        // The centre of the predictions: its worst distance to the set's extreme predictions is
        // no larger than the deepest point's (to first order, up to the margin's effect).
        let p = calibrated_point(&Line, &mut set, PointRule::PredictionCentre(&predictions))
            .expect("consistent");
        let mut q = set.query();
        let mut worst = |x: &[f64; 2]| {
            predictions
                .iter()
                .map(|g| {
                    let r = q.range(g);
                    let v = g[0] * x[0] + g[1] * x[1];
                    (r.sup() - v).max(v - r.inf())
                })
                .fold(0.0, f64::max)
        };
        assert!(
            worst(&p.x) <= worst(&p.deepest) * 1.001 + 1e-12,
            "seed {seed}: {p:?}"
        );
    }
}

/// The measurements with the half-widths of `y` multiplied by `s`.
fn widen_y(m: &[[Interval; 2]], s: f64) -> Vec<[Interval; 2]> {
    m.iter()
        .map(|b| [b[0], Interval::mid_rad(b[1].mid(), b[1].rad() * s)])
        .collect()
}

#[test]
fn the_chebyshev_scale_is_the_smallest_consistent_one() {
    for seed in 0..10 {
        let m = data(&mut StdRng::seed_from_u64(seed), 12);
        let e = calib_core::smallest_scale(&Line, &x0(), &m, &[false, true]);
        // The noise is within the bounds: the truth fits at × 1.
        assert!(e.scale <= 1.0 + 1e-9, "seed {seed}: {}", e.scale);
        // Its point fits just above the scale and not just below (the exhaustive corner test).
        assert!(is_consistent_by_corners(
            &Line,
            &e.point,
            &widen_y(&m, 1.001 * e.scale)
        ));
        assert!(!is_consistent_by_corners(
            &Line,
            &e.point,
            &widen_y(&m, 0.999 * e.scale)
        ));
        // No point fits 2% below it: the kernel proves it.
        let c = calib_core::certify(
            &Line,
            &x0(),
            &widen_y(&m, 0.98 * e.scale),
            &Settings::default(),
        );
        assert_eq!(c.status, calib_core::Status::Empty, "seed {seed}");
    }
}

#[test]
fn the_parallelotope_and_the_own_rows_bound_every_consistent_vector_at_the_sets_scale() {
    use calib_core::Parallelotope;
    for seed in 0..3 {
        let (set, m) = the_set(seed);
        let about = set.points().first().expect("a certified point").x;
        let p = Parallelotope::around(&set, &about).expect("a parallelotope");
        let samples = consistent_samples(&set, &m, 20_000);
        assert!(samples.len() > 100, "seed {seed}");
        let mut rng = StdRng::seed_from_u64(seed + 100);
        let mut own = set.query_own_rows();
        let mut full = set.query();
        for _ in 0..64 {
            // Interval slopes: any value within them.
            let w: [Interval; 2] = core::array::from_fn(|_| {
                let c = rng.random_range(-1.0..1.0);
                Interval::mid_rad(c, rng.random_range(0.0..0.01))
            });
            let bound = p.max_linear(&w);
            let abs = p.max_abs_linear(&w);
            let relaxed = own.max_linear(&w, &about).upper;
            // A relaxation is never tighter than the whole program (up to its rounding).
            let whole = full.max_linear(&w, &about).upper;
            assert!(relaxed >= whole - 1e-9 * (1.0 + whole.abs()), "seed {seed}");
            for x in &samples {
                for t in [0.0, 0.5, 1.0] {
                    let s = [0, 1].map(|j| w[j].inf() + t * w[j].wid());
                    let v = s[0] * (x[0] - about[0]) + s[1] * (x[1] - about[1]);
                    assert!(
                        v <= bound && v.abs() <= abs && v <= relaxed,
                        "seed {seed}: {x:?}"
                    );
                }
            }
        }
        // Thin where the data fix x0 + x1: far narrower than the box's sum.
        let outer = set.outer().expect("consistent");
        let sum = [Interval::point(1.0); 2];
        let width = p.max_linear(&sum) + p.max_linear(&sum.map(|v| -v));
        assert!(
            width < (outer[0] + outer[1]).wid() / 5.0,
            "seed {seed}: {width} against the box's {:?}",
            outer[0] + outer[1]
        );
    }
}
