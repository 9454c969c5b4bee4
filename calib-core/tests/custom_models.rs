//! Models written in a crate that depends only on `calib-core`: their generated evaluators enclose
//! the point values, and their Jacobians agree with finite differences and dual numbers.

use crate::support;

use calib_core::{interval_model, Dual, Interval, Model, Scalar};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use support::*;

/// Signed distance from a measured point to a circle: uses `sqrt`.
#[interval_model]
pub fn circle_distance<S: Scalar>(x: &[S; 3], m: &[S; 2]) -> S {
    let [cx, cy, r] = *x;
    ((m[0] - cx).sqr() + (m[1] - cy).sqr()).sqrt() - r
}

/// A rational residual with powers, a trigonometric factor, tuples and blocks.
#[interval_model]
pub fn rational_trig<S: Scalar>(x: &[S; 3], m: &[S; 3]) -> S {
    let (num, den) = (x[0] * m[0] - 0.3, 1.5 + (x[1] * m[1]).sqr());
    let wave = {
        let t = x[2] * m[2];
        t.sin() * 2 - (t * 0.5).cos() + (0.1 * t).tan()
    };
    num / den + x[2].powi(3) / m[0].powi(-2) - wave * S::cst(-0.25) + (x[0] * x[0]).sqrt()
}

/// A constant model for literal-enclosure tests: the parameter cancels exactly.
#[allow(clippy::eq_op)]
#[interval_model]
pub fn tenth<S: Scalar>(x: &[S; 1], _m: &[S; 1]) -> S {
    S::cst(0.1) + (x[0] - x[0])
}

/// Only a literal.
#[interval_model]
fn only_tenth<S: Scalar>(_x: &[S; 1], _m: &[S; 1]) -> S {
    S::cst(0.1)
}

#[interval_model]
fn literals<S: Scalar>(_x: &[S; 1], m: &[S; 4]) -> S {
    m[0] * 1e-300 + m[1] * 52.2496 + m[2] * 3 + m[3] / 3.0
}

#[test]
fn circle_distance_encloses_point_values() {
    let mut rng = StdRng::seed_from_u64(11);
    assert_encloses(
        &CircleDistance,
        &mut rng,
        &[0.0, 0.0, 1.0],
        &[0.5, 0.5, 0.5],
        &[1.0, 0.5],
        &[0.5, 0.5],
        400,
    );
}

#[test]
fn rational_trig_encloses_point_values() {
    let mut rng = StdRng::seed_from_u64(12);
    assert_encloses(
        &RationalTrig,
        &mut rng,
        &[1.0, -0.5, 0.7],
        &[0.5, 0.5, 0.5],
        &[1.2, 0.8, -1.1],
        &[0.3, 0.5, 0.5],
        400,
    );
}

#[test]
fn jacobians_match_finite_differences_and_dual_numbers() {
    let mut rng = StdRng::seed_from_u64(13);
    for _ in 0..200 {
        let x = [
            rng.random_range(-2.0..2.0),
            rng.random_range(-2.0..2.0),
            rng.random_range(0.1..2.0),
        ];
        let m = [rng.random_range(-3.0..3.0), rng.random_range(-3.0..3.0)];
        assert_jacobians_match_finite_differences(&CircleDistance, &x, &m);
        assert_jacobians_match_dual(&CircleDistance, circle_distance::<Dual<5>>, &x, &m);
        let m3 = [
            rng.random_range(0.5..2.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        ];
        assert_jacobians_match_finite_differences(&RationalTrig, &x, &m3);
        assert_jacobians_match_dual(&RationalTrig, rational_trig::<Dual<6>>, &x, &m3);
    }
}

#[test]
fn literals_are_enclosed_as_decimals() {
    // 0.1 is not a double: the interval evaluator encloses the real tenth, the point one uses the
    // nearest double.
    let t = Tenth.residual_interval(&[Interval::new(-1.0, 1.0)], &[Interval::ZERO]);
    assert_eq!((t.inf(), t.sup()), (0.1f64.next_down(), 0.1));
    assert_eq!(Tenth.residual(&[0.3], &[0.0]), 0.1);
    // The kept generic function encloses too.
    let k = only_tenth::<Interval>(&[Interval::ONE], &[Interval::ZERO]);
    assert_eq!((k.inf(), k.sup()), (0.1f64.next_down(), 0.1));
    assert_eq!(
        OnlyTenth.residual_interval(&[Interval::ONE], &[Interval::ONE]),
        k
    );
    // 1e-300, 52.2496 and 1/3 are not doubles; 3 is.
    let pick = |i: usize| {
        let mut m = [Interval::ZERO; 4];
        m[i] = Interval::ONE;
        literals::<Interval>(&[Interval::ZERO], &m)
    };
    for (i, exact) in [(0, "1e-300"), (1, "52.2496")] {
        let v = pick(i);
        let nearest: f64 = exact.parse().unwrap();
        assert!(v.inf() < v.sup() && v.contains(nearest), "{exact}: {v}");
        assert!(
            v.wid() <= 4.0 * (nearest.next_up() - nearest),
            "{exact} enclosed too loosely: {v}"
        );
    }
    assert!(pick(2).contains(3.0) && pick(2).wid() <= 1e-15);
    let third = pick(3);
    assert!(third.inf() < 1.0 / 3.0 + 1e-16 && third.contains(1.0 / 3.0));
    let g = Literals.residual_interval(&[Interval::ZERO], &[Interval::ONE; 4]);
    assert!(g.contains(1e-300 + 52.2496 + 3.0 + 1.0 / 3.0));
}

#[test]
fn generated_struct_is_a_unit_value_with_the_functions_visibility() {
    let models: (CircleDistance, RationalTrig, Tenth) = Default::default();
    assert_eq!(format!("{:?}", models.0), "CircleDistance");
    // `x * x` of the same variable is a square: never negative, unlike the product of intervals.
    let x = [Interval::new(-1.0, 1.0), Interval::ONE, Interval::ONE];
    let m = [Interval::ONE; 3];
    let f = RationalTrig.residual_interval(&x, &m);
    assert!(f.is_bounded());
}
