//! Rigorous bounds from LP multipliers (Neumaier & Shcherbina, "Safe bounds in linear and
//! mixed-integer programming", Math. Programming 2004).
//!
//! For `y` in the box `Y = [lo, hi]` with `G y <= g` and any `λ >= 0`:
//! `c·y >= c·y + λ·(G y - g) = (c + Gᵀλ)·y - λ·g >= inf((c + Gᵀλ)·Y) - sup(λ·g)`.
//! Both terms are evaluated in interval arithmetic, so the bound holds whatever `λ` is: the LP
//! solver's multipliers only decide how good it is. With `c = 0`, a bound `> 0` contradicts
//! `0 >= ...`: the polyhedron is empty (a checked Farkas certificate).

use super::Polyhedron;
use crate::Interval;

/// A lower bound of `c·y` over the polyhedron, valid for any multipliers (negative or NaN entries
/// of `dual` are treated as zero). `+inf` means the polyhedron is proved empty.
pub fn safe_lower_bound(p: &Polyhedron, c: &[f64], dual: &[f64]) -> f64 {
    let n = p.dim();
    let usable = |l: f64| l > 0.0 && l.is_finite();
    // r = c + Gᵀλ, enclosed, accumulated row by row over the non-zero multipliers.
    const STACK: usize = 64;
    let mut stack = [Interval::ZERO; STACK];
    let mut lg = Interval::ZERO;
    let total = if n <= STACK {
        let r = &mut stack[..n];
        for (rj, &cj) in r.iter_mut().zip(c) {
            *rj = Interval::point(cj);
        }
        for (i, &l) in dual.iter().enumerate() {
            if usable(l) {
                let li = Interval::point(l);
                for (rj, &g) in r.iter_mut().zip(p.row(i)) {
                    *rj += li * Interval::point(g);
                }
                lg += li * Interval::point(p.rhs(i));
            }
        }
        (0..n).fold(Interval::ZERO, |t, j| {
            t + r[j] * Interval::new(p.lo()[j], p.hi()[j])
        })
    } else {
        let mut total = Interval::ZERO;
        for j in 0..n {
            let mut r = Interval::point(c[j]);
            for (i, &l) in dual.iter().enumerate() {
                if usable(l) {
                    r += Interval::point(l) * Interval::point(p.row(i)[j]);
                }
            }
            total += r * Interval::new(p.lo()[j], p.hi()[j]);
        }
        for (i, &l) in dual.iter().enumerate() {
            if usable(l) {
                lg += Interval::point(l) * Interval::point(p.rhs(i));
            }
        }
        total
    };
    let bound = (total - lg).inf();
    if bound.is_nan() {
        f64::NEG_INFINITY
    } else {
        bound
    }
}

/// Whether the multipliers `ray` prove that the polyhedron is empty: the safe lower bound of the
/// zero objective is positive.
pub fn proves_infeasible(p: &Polyhedron, ray: &[f64], zeros: &[f64]) -> bool {
    safe_lower_bound(p, zeros, ray) > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Polyhedron {
        super::super::small_test_polyhedron()
    }

    #[test]
    fn exact_multipliers_give_the_optimum() {
        // max y1 = -min(-y1): optimum y1 = 0.75 at y0 = 0.25 with λ = (1, 1) for the rows as
        // stored (scaled by 1/2).
        let p = square();
        let b = safe_lower_bound(&p, &[0.0, -1.0], &[1.0, 1.0]);
        assert!(b <= -0.75 && b > -0.75 - 1e-12, "{b}");
    }

    #[test]
    fn wrong_multipliers_never_cut_a_feasible_point() {
        let p = square();
        let feasible = [
            [0.25, 0.75],
            [-1.0, -1.0],
            [1.0, -1.0],
            [0.0, 0.5],
            [-1.0, -0.5],
        ];
        let mut seed = 1u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 4.0 - 1.0
        };
        for _ in 0..2000 {
            let c = [rnd(), rnd()];
            let dual = [rnd() * 10.0, rnd() * 10.0];
            let b = safe_lower_bound(&p, &c, &dual);
            for y in feasible {
                assert!(
                    c[0] * y[0] + c[1] * y[1] >= b,
                    "bound {b} cuts {y:?} for c {c:?} λ {dual:?}"
                );
            }
        }
        // NaN and infinite multipliers are ignored rather than poisoning the bound.
        assert!(safe_lower_bound(&p, &[1.0, 0.0], &[f64::NAN, f64::INFINITY]) <= -1.0);
    }

    /// Both evaluation orders (row by row on the stack up to 64 variables, column by column
    /// beyond): with sparse multipliers, as an LP optimum has, the bound never cuts a feasible
    /// point.
    #[test]
    fn wide_problems_get_sound_bounds_on_both_paths() {
        use rand::{rngs::StdRng, Rng, SeedableRng};
        let mut rng = StdRng::seed_from_u64(7);
        let mut rnd = || rng.random_range(-1.0..1.0);
        for n in [40usize, 70] {
            // Rows through a known feasible point y0 (slack 0.1), over the box [-1, 1]^n.
            let y0: Vec<f64> = (0..n).map(|_| 0.5 * rnd()).collect();
            let mut p = Polyhedron::default();
            p.reset(&vec![-1.0; n], &vec![1.0; n]);
            for _ in 0..3 * n {
                let a: Vec<f64> = (0..n).map(|_| rnd()).collect();
                let b = a.iter().zip(&y0).map(|(x, y)| x * y).sum::<f64>() + 0.1;
                p.push_row(&a, b);
            }
            for _ in 0..200 {
                let c: Vec<f64> = (0..n).map(|_| rnd()).collect();
                let dual: Vec<f64> = (0..p.rows())
                    .map(|_| {
                        let v = rnd();
                        if v > 0.8 {
                            5.0 * v
                        } else {
                            0.0
                        }
                    })
                    .collect();
                let b = safe_lower_bound(&p, &c, &dual);
                let at_y0: f64 = c.iter().zip(&y0).map(|(x, y)| x * y).sum();
                assert!(at_y0 >= b, "n {n}: bound {b} cuts y0 ({at_y0})");
                assert!(b.is_finite(), "n {n}");
            }
        }
    }

    #[test]
    fn farkas_certificates_are_checked() {
        // y0 <= -0.5 and -y0 <= -0.5 (y0 >= 0.5): empty, ray (1, 1).
        let mut p = Polyhedron::default();
        p.reset(&[-1.0], &[1.0]);
        p.push_row(&[1.0], -0.5);
        p.push_row(&[-1.0], -0.5);
        assert!(proves_infeasible(&p, &[1.0, 1.0], &[0.0]));
        // A wrong ray proves nothing, and neither does a feasible polyhedron.
        assert!(!proves_infeasible(&p, &[1.0, 0.0], &[0.0]));
        assert!(!proves_infeasible(&square(), &[1.0, 1.0], &[0.0, 0.0]));
    }
}
