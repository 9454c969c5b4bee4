//! Operation-level tests of `Interval` against exact rational references: for random intervals and
//! random members (end points included), the exact real result of the operation lies inside the
//! interval result. Plus hand-picked edge cases: signed zeros, infinities, intervals containing zero,
//! the empty set, division by intervals containing zero.

use calib_core::Interval;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn rat(x: f64) -> BigRational {
    BigRational::from_float(x).expect("finite")
}

/// Whether the exact rational `v` lies in `iv` (infinite bounds are unbounded).
fn encloses(iv: Interval, v: &BigRational) -> bool {
    if iv.is_empty() {
        return false;
    }
    let lo_ok = iv.inf() == f64::NEG_INFINITY || rat(iv.inf()) <= *v;
    let hi_ok = iv.sup() == f64::INFINITY || *v <= rat(iv.sup());
    lo_ok && hi_ok
}

/// A random double from a wide range of magnitudes, with special values mixed in.
fn number(rng: &mut StdRng) -> f64 {
    match rng.random_range(0..10) {
        0 => [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.1,
            1.0 / 3.0,
            5e-324,
            -5e-324,
            1e308,
            -1e308,
        ][rng.random_range(0..10)],
        1..=3 => rng.random_range(-10.0..10.0),
        4..=6 => rng.random_range(-1.0..1.0) * 10f64.powi(rng.random_range(-30..30)),
        _ => rng.random_range(-1000.0..1000.0),
    }
}

fn interval(rng: &mut StdRng) -> Interval {
    let (a, b) = (number(rng), number(rng));
    if rng.random_range(0..6) == 0 {
        Interval::point(a)
    } else {
        Interval::new(a.min(b), a.max(b))
    }
}

/// End points and random members of `iv`.
fn members(rng: &mut StdRng, iv: Interval) -> Vec<f64> {
    let mut v = vec![iv.inf(), iv.sup(), iv.mid()];
    for _ in 0..3 {
        let t: f64 = rng.random();
        v.push((iv.inf() + t * (iv.sup() - iv.inf())).clamp(iv.inf(), iv.sup()));
    }
    if iv.contains(0.0) {
        v.push(0.0);
    }
    v
}

const CASES: usize = 1000;

#[test]
fn arithmetic_encloses_exact_results() {
    let mut rng = StdRng::seed_from_u64(1);
    for _ in 0..CASES {
        let (x, y) = (interval(&mut rng), interval(&mut rng));
        let (sum, diff, prod, quot) = (x + y, x - y, x * y, x / y);
        for a in members(&mut rng, x) {
            for b in members(&mut rng, y) {
                let (ra, rb) = (rat(a), rat(b));
                assert!(
                    encloses(sum, &(&ra + &rb)),
                    "{x} + {y} = {sum} misses {a} + {b}"
                );
                assert!(
                    encloses(diff, &(&ra - &rb)),
                    "{x} - {y} = {diff} misses {a} - {b}"
                );
                assert!(
                    encloses(prod, &(&ra * &rb)),
                    "{x} * {y} = {prod} misses {a} * {b}"
                );
                if b != 0.0 {
                    assert!(
                        encloses(quot, &(&ra / &rb)),
                        "{x} / {y} = {quot} misses {a} / {b}"
                    );
                }
            }
        }
    }
}

#[test]
fn negation_abs_min_max_are_exact_enclosures() {
    let mut rng = StdRng::seed_from_u64(2);
    for _ in 0..CASES {
        let (x, y) = (interval(&mut rng), interval(&mut rng));
        for a in members(&mut rng, x) {
            assert!((-x).contains(-a));
            assert!(x.abs().contains(a.abs()));
            for b in members(&mut rng, y) {
                assert!(x.min(y).contains(a.min(b)));
                assert!(x.max(y).contains(a.max(b)));
            }
        }
    }
}

#[test]
fn powers_enclose_exact_results() {
    let mut rng = StdRng::seed_from_u64(3);
    for _ in 0..CASES {
        let x = interval(&mut rng);
        let n = rng.random_range(-7..=9);
        let (sq, p) = (x.sqr(), x.powi(n));
        for a in members(&mut rng, x) {
            let ra = rat(a);
            assert!(encloses(sq, &(&ra * &ra)), "{x}.sqr() = {sq} misses {a}^2");
            if a != 0.0 || n >= 0 {
                let exact = if n >= 0 {
                    num_traits::pow(ra.clone(), n as usize)
                } else {
                    num_traits::pow(ra.clone(), (-n) as usize).recip()
                };
                assert!(encloses(p, &exact), "{x}.powi({n}) = {p} misses {a}^{n}");
            }
        }
    }
}

#[test]
fn sqrt_encloses_exact_results() {
    let mut rng = StdRng::seed_from_u64(4);
    for _ in 0..CASES {
        let x = interval(&mut rng);
        let s = x.sqrt();
        for a in members(&mut rng, x).into_iter().filter(|&a| a >= 0.0) {
            // lo^2 <= a <= hi^2 with lo >= 0 means lo <= sqrt(a) <= hi.
            assert!(s.inf() >= 0.0);
            let ra = rat(a);
            assert!(
                rat(s.inf()) * rat(s.inf()) <= ra,
                "{x}.sqrt() = {s} misses sqrt({a})"
            );
            assert!(s.sup() == f64::INFINITY || ra <= rat(s.sup()) * rat(s.sup()));
        }
    }
}

/// sin(a) and cos(a) as rationals with a rigorous truncation bound `r`: the true values lie in
/// `[s - r, s + r]` and `[c - r, c + r]` (Taylor series, |a| <= 8, 70 terms).
///
/// `a = p / d` exactly (a float is a dyadic rational), so every term `a^k / k!` is
/// `t_k / (d^K K!)` with the integer `t_k = p^k d^(K-k) K!/k!`: the sums are sums of integers over
/// one denominator, reduced once (a rational sum per term spends its time in gcds: 30× slower).
fn sin_cos_reference(a: f64) -> (BigRational, BigRational, BigRational) {
    const K: u32 = 70;
    assert!(a.abs() <= 8.0);
    let x = rat(a);
    let (p, d) = (x.numer(), x.denom());
    let mut denominator = BigInt::one();
    for k in 1..=K {
        denominator *= d * BigInt::from(k);
    }
    let (mut s, mut c) = (BigInt::zero(), BigInt::zero());
    // t_0 = d^K K!, and t_(k+1) = t_k p / (d (k + 1)), an exact division (t_k holds d^(K-k) and
    // K!/k!, of which d (k + 1) divides for k < K).
    let mut term = denominator.clone();
    for k in 0..K {
        match k % 4 {
            0 => c += &term,
            1 => s += &term,
            2 => c -= &term,
            _ => s -= &term,
        }
        let divisor = d * BigInt::from(k + 1);
        term *= p;
        debug_assert!((&term % &divisor).is_zero());
        term /= divisor;
    }
    // |remainder| <= 2 |x|^70 / 70! for |x| <= 8 (the tail is dominated by a geometric series).
    let r = BigRational::new(term.abs() * BigInt::from(2), denominator.clone());
    (
        BigRational::new(s, denominator.clone()),
        BigRational::new(c, denominator),
        r,
    )
}

fn encloses_range(iv: Interval, v: &BigRational, r: &BigRational) -> bool {
    encloses(iv, &(v - r)) && encloses(iv, &(v + r))
}

#[test]
fn trigonometric_functions_enclose_exact_results() {
    let mut rng = StdRng::seed_from_u64(5);
    for case in 0..120 {
        let c: f64 = rng.random_range(-7.0..7.0);
        let w: f64 = if case % 3 == 0 {
            0.0
        } else {
            rng.random_range(0.0..1.0) * 10f64.powi(rng.random_range(-12..1))
        };
        let x = Interval::new(c, (c + w).min(8.0));
        let (si, co) = (x.sin(), x.cos());
        for a in [x.inf(), x.sup(), x.mid()] {
            let (s, cv, r) = sin_cos_reference(a);
            assert!(
                encloses_range(si, &s, &r),
                "{x}.sin() = {si} misses sin({a})"
            );
            assert!(
                encloses_range(co, &cv, &r),
                "{x}.cos() = {co} misses cos({a})"
            );
        }
        let t = Interval::new(c / 5.0, c / 5.0 + w.min(0.1));
        let ti = t.tan();
        for a in [t.inf(), t.sup()] {
            let (s, cv, r) = sin_cos_reference(a);
            // cos > 0 on |a| < 1.5: tan(a) lies between (s -+ r) / (c +- r).
            let cands = [
                (&s - &r) / (&cv + &r),
                (&s - &r) / (&cv - &r),
                (&s + &r) / (&cv + &r),
                (&s + &r) / (&cv - &r),
            ];
            let lo = cands.iter().min().unwrap();
            let hi = cands.iter().max().unwrap();
            assert!(
                encloses(ti, lo) && encloses(ti, hi),
                "{t}.tan() = {ti} misses tan({a})"
            );
        }
    }
    // Extrema and poles inside the argument.
    assert_eq!(Interval::new(1.0, 2.0).sin().sup(), 1.0);
    assert_eq!(Interval::new(4.0, 5.0).sin().inf(), -1.0);
    assert_eq!(Interval::new(-0.5, 0.5).cos().sup(), 1.0);
    assert_eq!(Interval::new(3.0, 3.5).cos().inf(), -1.0);
    assert_eq!(Interval::new(1.5, 1.7).tan(), Interval::ENTIRE);
    assert_eq!(Interval::new(0.0, 100.0).sin(), Interval::new(-1.0, 1.0));
    assert_eq!(Interval::ENTIRE.cos(), Interval::new(-1.0, 1.0));
}

#[test]
fn division_by_intervals_containing_zero() {
    let i = Interval::new;
    let inf = f64::INFINITY;
    assert_eq!(i(1.0, 2.0) / i(0.0, 1.0), i(1.0f64.next_down(), inf));
    assert_eq!(i(1.0, 2.0) / i(-1.0, 0.0), i(-inf, (-1.0f64).next_up()));
    assert_eq!(i(-2.0, -1.0) / i(0.0, 1.0), i(-inf, (-1.0f64).next_up()));
    assert_eq!(i(-2.0, -1.0) / i(-1.0, 0.0), i(1.0f64.next_down(), inf));
    assert_eq!(i(1.0, 2.0) / i(-1.0, 1.0), Interval::ENTIRE);
    assert_eq!(i(-1.0, 2.0) / i(0.0, 1.0), Interval::ENTIRE);
    assert_eq!(i(0.0, 0.0) / i(-1.0, 1.0), Interval::ZERO);
    assert!((i(1.0, 2.0) / i(0.0, 0.0)).is_empty());
    assert!((i(0.0, 0.0) / i(0.0, 0.0)).is_empty());
    assert_eq!(
        (i(1.0, 2.0) / i(-0.0, 1.0)).sup(),
        inf,
        "negative zero is zero"
    );
    let r = Interval::ONE / i(2.0, inf);
    assert!(r.inf() <= 0.0 && r.inf() > -1e-300 && r.sup() >= 0.5 && r.sup() < 0.5000001);
    let r = i(1.0, inf) / i(1.0, inf);
    assert!(r.inf() <= 0.0 && r.sup() == inf, "{r}");
}

#[test]
fn signed_zeros_infinities_and_empty() {
    let i = Interval::new;
    let inf = f64::INFINITY;
    let e = Interval::EMPTY;
    // Signed zeros are the same real number.
    assert!(i(-0.0, 0.0).contains(0.0) && i(0.0, 0.0).contains(-0.0));
    assert_eq!((i(-0.0, 1.0) * i(2.0, 3.0)).inf(), 0.0);
    // 0 times an unbounded interval is 0: the infinities are not members.
    assert_eq!(Interval::ZERO * Interval::ENTIRE, Interval::ZERO);
    assert_eq!((i(0.0, 1.0) * i(1.0, inf)).inf(), 0.0);
    assert_eq!((i(0.0, 1.0) * i(1.0, inf)).sup(), inf);
    assert_eq!((i(-inf, 1.0) + i(1.0, 2.0)).inf(), -inf);
    assert!(!Interval::ENTIRE.contains(inf) && !Interval::ENTIRE.contains(f64::NAN));
    // Overflow: the lower bound stays finite and below the exact sum, the upper bound is infinite.
    let big = i(f64::MAX, f64::MAX) + i(f64::MAX, f64::MAX);
    assert!(big.inf() >= f64::MAX.next_down() && big.sup() == inf);
    // The empty set propagates and is neutral for the hull.
    for r in [
        e + Interval::ONE,
        e * Interval::ONE,
        Interval::ONE / e,
        e.sqrt(),
        e.sin(),
        e.sqr(),
        e.powi(3),
    ] {
        assert!(r.is_empty());
    }
    assert_eq!(e.hull(Interval::ONE), Interval::ONE);
    assert!(i(0.0, 1.0).intersection(i(2.0, 3.0)).is_empty());
    assert_eq!(i(0.0, 2.0).intersection(i(1.0, 3.0)), i(1.0, 2.0));
    assert!(e.is_interior_of(Interval::ONE) && e.is_subset_of(Interval::ONE));
    // sqrt restricts to its domain.
    assert_eq!(i(-4.0, 4.0).sqrt().inf(), 0.0);
    assert!(i(-2.0, -1.0).sqrt().is_empty());
    assert_eq!(i(0.0, inf).sqrt().sup(), inf);
    // sqr is tighter than the product when zero is inside.
    assert_eq!(i(-1.0, 2.0).sqr().inf(), 0.0);
    assert!((i(-1.0, 2.0) * i(-1.0, 2.0)).inf() < 0.0);
    assert!(Interval::try_new(2.0, 1.0).is_none() && Interval::try_new(f64::NAN, 1.0).is_none());
    assert!(Interval::try_new(inf, inf).is_none());
}

#[test]
fn accessors() {
    let x = Interval::new(1.0, 4.0);
    assert_eq!((x.inf(), x.sup(), x.mid()), (1.0, 4.0, 2.5));
    assert!(x.rad() >= 1.5 && x.wid() >= 3.0);
    assert_eq!(Interval::new(-3.0, 2.0).mag(), 3.0);
    assert_eq!(Interval::new(-3.0, 2.0).mig(), 0.0);
    assert_eq!(Interval::new(2.0, 3.0).mig(), 2.0);
    assert!(Interval::new(1.5, 2.0).is_interior_of(x));
    assert!(!Interval::new(1.0, 2.0).is_interior_of(x));
    assert!(x.is_interior_of(Interval::ENTIRE));
    assert_eq!(Interval::ENTIRE.mid(), 0.0);
    assert_eq!(Interval::new(1.0, f64::INFINITY).mid(), f64::MAX);
    // mid and rad describe an enclosing ball even for awkward bounds.
    let mut rng = StdRng::seed_from_u64(6);
    for _ in 0..CASES {
        let x = interval(&mut rng);
        if !x.is_bounded() || x.rad() == f64::INFINITY {
            continue;
        }
        let (m, r) = (rat(x.mid()), rat(x.rad()));
        assert!(x.contains(x.mid()));
        assert!(
            &m - &r <= rat(x.inf()) && rat(x.sup()) <= &m + &r,
            "{x}: mid {} rad {}",
            x.mid(),
            x.rad()
        );
        assert!(x.wid() == f64::INFINITY || rat(x.wid()) >= rat(x.sup()) - rat(x.inf()));
    }
}

#[test]
fn hull_and_intersection_are_set_operations() {
    let mut rng = StdRng::seed_from_u64(7);
    for _ in 0..CASES {
        let (x, y) = (interval(&mut rng), interval(&mut rng));
        let (h, s) = (x.hull(y), x.intersection(y));
        for a in members(&mut rng, x).into_iter().chain(members(&mut rng, y)) {
            assert!(h.contains(a));
            assert_eq!(
                s.contains(a),
                x.contains(a) && y.contains(a),
                "{x} ∩ {y} = {s} at {a}"
            );
        }
    }
}

/// The quotient's ends by the definition: the least and greatest of the four corner quotients,
/// each rounded outward (a zero numerator gives an exact zero), NaN corners dropped.
fn division_by_corners(x: Interval, y: Interval) -> (f64, f64) {
    let down = |a: f64, b: f64| if a == 0.0 { 0.0 } else { (a / b).next_down() };
    let up = |a: f64, b: f64| if a == 0.0 { 0.0 } else { (a / b).next_up() };
    let corners = [
        (x.inf(), y.inf()),
        (x.inf(), y.sup()),
        (x.sup(), y.inf()),
        (x.sup(), y.sup()),
    ];
    (
        corners
            .iter()
            .map(|&(a, b)| down(a, b))
            .fold(f64::NAN, f64::min),
        corners
            .iter()
            .map(|&(a, b)| up(a, b))
            .fold(f64::NAN, f64::max),
    )
}

#[test]
fn division_by_a_divisor_of_one_sign_gives_the_corner_bounds() {
    let mut rng = StdRng::seed_from_u64(41);
    let infinite = |rng: &mut StdRng, v: f64| {
        if rng.random_range(0..8) == 0 {
            v.signum() * f64::INFINITY
        } else {
            v
        }
    };
    for _ in 0..50_000 {
        let x = interval(&mut rng);
        let x = Interval::new(
            infinite(&mut rng, x.inf()).min(x.sup()),
            infinite(&mut rng, x.sup()).max(x.inf()),
        );
        let y = interval(&mut rng);
        if y.inf() <= 0.0 && y.sup() >= 0.0 {
            continue;
        }
        let y = if rng.random_range(0..8) == 0 && y.inf() > 0.0 {
            Interval::new(y.inf(), f64::INFINITY)
        } else if rng.random_range(0..8) == 0 && y.sup() < 0.0 {
            Interval::new(f64::NEG_INFINITY, y.sup())
        } else {
            y
        };
        let q = x / y;
        let (lo, hi) = division_by_corners(x, y);
        // The same ends, but where a corner quotient is zero only by underflow or by `x / ∞`:
        // the corners round that zero outward by one ulp, where the numerator's sign already
        // proves the quotient's (e.g. `[0, 5e-324] / 535` has lower end 0, not -5e-324).
        let near_zero = |v: f64| v.abs() <= 5e-324;
        let same = |a: f64, b: f64| a == b || (near_zero(a) && near_zero(b));
        assert!(
            lo <= q.inf() && q.sup() <= hi && same(q.inf(), lo) && same(q.sup(), hi),
            "{x:?} / {y:?} = {q:?}, corners give [{lo}, {hi}]"
        );
        // Sound: ends and random members divide into the quotient.
        for u in members(&mut rng, x).into_iter().filter(|v| v.is_finite()) {
            for v in members(&mut rng, y).into_iter().filter(|v| v.is_finite()) {
                assert!(encloses(q, &(rat(u) / rat(v))), "{u} / {v} outside {q:?}");
            }
        }
    }
}
