//! A chart that follows the commanded pose: the platform's pose errors over a box of poses in one
//! step, when the legs' Jacobian changes little across the box and the move.
//!
//! A chart `δ = M y` fixed for the whole box of poses (`M ≈ J⁻¹` at its centre) would not do:
//! over a box of width `w` the legs' Jacobian `J(X)` changes by `O(w)`, and in a fixed chart so
//! does every leg's change, `G_i(X, M y) - y_i ≈ ((J(X) - J_c) M y)_i`, which the condition
//! number of `J` amplifies. Regions then close only on small boxes of poses.
//!
//! Here the chart moves with the pose: `M(X) = M_c - M_c (J(X) - J_c) M_c`, the first-order
//! inverse of `J(X)`, enclosed as affine forms whose noise symbols are the pose's coordinates
//! ([`calib_core::Affine`]; `J(X)` from `∇_δ G` at `δ = 0` with the nominal geometry, through
//! [`calib_core::Jet`]). `M(X)` is nonsingular for every pose of the box when
//! `‖M_c (J(X) - J_c)‖∞ < 1`, so `D(X) = M(X) · [-R, R]` is a parallelepiped around `δ = 0`
//! whose boundary is the image of the box's faces.
//!
//! **The remainder.** `G_i(X, 0, θ*) = 0`, so along the segment from `0` to `δ = M(X) y`,
//! `G_i - y_i = (∫₀¹ ∇_δ G_i(X, M(X) τ y, θ*) dτ · M(X) - e_i) · y`. The integrand is evaluated
//! with the same noise symbols for the pose in `∇_δ G_i` and in `M(X)`, and with noise symbols
//! for `τ y` (so that `ξ = M(X) τ y` keeps the parallelepiped's shape: its box would triple the
//! remainder). The first-order parts in the pose cancel (`J(X) M(X) = I + O(w²)`); the terms in
//! `τ y`, the move's curvature, average to half their reach over `τ` (for a fixed `y`, `τ y`
//! runs from 0 to `y`). So `|G_i - y_i| <= Σ_c |S_ic| h_c =: ρ_i` over `|y_c| <= h_c` is second
//! order in the box's width and the move.
//!
//! **Closing and bounding.** With `R_i = f U_i` and `ρ_i(R) < R_i - U_i` for every leg, every
//! move on face `i` of `D(X)` has `|G_i| >= R_i - ρ_i > U_i`: no move on the boundary lies in
//! `F` (see [`super::pose_bound`]), for every pose of the box and every geometry at once, so the
//! reached move lies in `D(X) ∩ F ⊆ {M(X) y : |y_i| <= U_i + ρ_i}`. The position and
//! orientation errors are norms of `M(X) y`, bilinear in the pose's noise symbols and `y`:
//! convex in each, so their largest values are at one of the 64 × 64 vertex pairs, with the
//! forms' error terms taken outward.

use super::enclosure::{AccuracyProblem, PoseBox};
use super::pose_bound::{
    centre_jacobian, errors_from_squares, leg_change_bounds, leg_inputs, proved_inverse,
    reached_change, squared_norms,
};
use calib_core::{Affine, Interval, Jet};

/// Affine forms over the box of poses (noise symbols `0..6`) and, in the remainder, the box of
/// moves (`6..12`).
type Form = Affine<12>;

/// The region half-widths tried, in units of `U` (the narrowest that closes is kept).
const FACTORS: [f64; 5] = [1.05, 1.1, 1.25, 1.5, 2.0];
/// Rounds of the enclosure of `D(X) ∩ F` by `|y_i| <= U_i + ρ_i(h)`.
const SHRINK_ROUNDS: usize = 3;
/// The relative margin added to every vertex sum of products (floating point, far above the
/// `γ_n` bound of six products of six terms).
const ERROR_MARGIN: f64 = 1e-12;

/// The chart of one box of poses.
pub struct PoseChart {
    /// `M(X)`.
    pub m: [[Form; 6]; 6],
    /// `U_i`, rounded up.
    pub bound: [f64; 6],
    /// Per leg, the box of poses as forms and the geometry's box (without correlation).
    inputs: Vec<[Form; 12]>,
}

/// `a + b` rounded up (`+∞` when either is not finite).
pub fn add_up(a: f64, b: f64) -> f64 {
    if a.is_finite() && b.is_finite() {
        (Interval::point(a) + Interval::point(b)).sup()
    } else {
        f64::INFINITY
    }
}

/// `a · b` rounded up, for `a, b >= 0` (`+∞` when either is not finite).
pub fn mul_up(a: f64, b: f64) -> f64 {
    if a.is_finite() && b.is_finite() {
        (Interval::point(a) * Interval::point(b)).sup()
    } else {
        f64::INFINITY
    }
}

/// `max |S|` over the pose's noise symbols of the slope `S = ∫₀¹ s(X, τ y) dτ`, where the form
/// `s` encloses `s(X, τ y)` with noise symbols `0..6` for the pose and `6..12` for `τ y` over
/// `[-h, h]`: for a fixed `y`, `τ y` runs along the segment from 0 to `y`, so its symbols'
/// average over `τ` is `y / 2h` and their terms count half, `|c + Σ_k a_k ε_k| + ½ Σ_c |a_c| +
/// e`, rounded up (`+∞` when not finite).
fn averaged_mag(s: &Form) -> f64 {
    let a = s.coefficients();
    let pose = a[..6]
        .iter()
        .fold(s.centre().abs(), |t, v| add_up(t, v.abs()));
    let moves = a[6..].iter().fold(0.0, |t, v| add_up(t, v.abs()));
    add_up(add_up(pose, mul_up(0.5, moves)), s.error())
}

impl PoseChart {
    /// The chart of the box of poses `x` with actuator errors `± eps`; `None` when `J_c` is
    /// singular, `M(X)` is not proved nonsingular over the box, or a leg's bound is not finite.
    pub fn new(problem: &AccuracyProblem, x: &PoseBox, eps: f64) -> Option<PoseChart> {
        if problem.legs() != 6 {
            return None;
        }
        let bound = leg_change_bounds(problem, x, eps)?;
        let jc = centre_jacobian(problem, x);
        let mc = proved_inverse(&jc)?;
        let pose: [Form; 6] = core::array::from_fn(|k| Form::input(x[k], k));
        let cst = |v: f64| Form::from_interval(Interval::point(v));
        // J(X): ∇_δ G at δ = 0 with the nominal geometry, the pose as forms.
        let jx: [[Form; 6]; 6] = core::array::from_fn(|i| {
            let n = problem.nominal(i);
            let delta: [Jet<Form, 6>; 6] = core::array::from_fn(|r| Jet::variable(cst(0.0), r));
            let inputs: [Jet<Form, 6>; 12] = core::array::from_fn(|k| {
                Jet::constant(if k < 6 { pose[k] } else { cst(n[k - 6]) })
            });
            reached_change(&delta, &inputs).grad
        });
        // E(X) = J(X) - J_c and M_c E(X).
        let e: [[Form; 6]; 6] =
            core::array::from_fn(|i| core::array::from_fn(|k| jx[i][k] - cst(jc[(i, k)])));
        let me: [[Form; 6]; 6] = core::array::from_fn(|r| {
            core::array::from_fn(|c| (0..6).fold(cst(0.0), |s, k| s + cst(mc[(r, k)]) * e[k][c]))
        });
        let norm = (0..6)
            .map(|r| (0..6).fold(0.0, |s, c| add_up(s, me[r][c].range().mag())))
            .fold(0.0, f64::max);
        // M(X) = (I - M_c E(X)) M_c is nonsingular when ‖M_c E(X)‖∞ < 1 (NaN fails too).
        if norm.partial_cmp(&1.0) != Some(core::cmp::Ordering::Less) {
            return None;
        }
        let m: [[Form; 6]; 6] = core::array::from_fn(|r| {
            core::array::from_fn(|c| {
                (0..6).fold(cst(mc[(r, c)]), |s, k| s - me[r][k] * cst(mc[(k, c)]))
            })
        });
        let inputs = leg_inputs(problem, &pose, Form::from_interval);
        Some(PoseChart { m, bound, inputs })
    }

    /// `ρ_i` over `|y_c| <= h_c` (module documentation); `+∞` where an enclosure failed.
    pub fn remainder(&self, h: &[f64; 6]) -> [f64; 6] {
        // The segment's points ξ = M(X) (τ y), τ y in the box [-h, h]: noise symbols 6..12
        // for τ y, so that ξ keeps the parallelepiped's shape (its box would not).
        let ty: [Form; 6] =
            core::array::from_fn(|c| Form::input(Interval::new(-h[c], h[c]), 6 + c));
        let zero = Form::from_interval(Interval::ZERO);
        let delta: [Jet<Form, 6>; 6] = core::array::from_fn(|r| {
            Jet::variable((0..6).fold(zero, |s, c| s + self.m[r][c] * ty[c]), r)
        });
        core::array::from_fn(|i| {
            let inputs = self.inputs[i].map(Jet::constant);
            let grad = reached_change(&delta, &inputs).grad;
            (0..6).fold(0.0, |s, c| {
                let id = Form::from_interval(Interval::point(if c == i { 1.0 } else { 0.0 }));
                let slope = (0..6).fold(-id, |s, k| s + grad[k] * self.m[k][c]);
                add_up(s, mul_up(averaged_mag(&slope), h[c]))
            })
        })
    }

    /// Upper bounds of the position (cm) and orientation (degrees) errors over every pose of the
    /// box, every geometry and every actuator error, or `None` when no region closes.
    pub fn bound(&self) -> Option<[f64; 2]> {
        let u = self.bound;
        let (mut h, mut rest) = FACTORS.iter().find_map(|f| {
            let r = u.map(|v| f * v);
            let rest = self.remainder(&r);
            (0..6)
                .all(|i| add_up(u[i], rest[i]) < r[i])
                .then_some((r, rest))
        })?;
        // The closing region's remainder starts the shrinking (each round's box holds D(X) ∩ F).
        for round in 0..SHRINK_ROUNDS {
            if round > 0 {
                rest = self.remainder(&h);
            }
            h = core::array::from_fn(|i| add_up(u[i], rest[i]).min(h[i]));
        }
        Some(self.vertex_value(&h))
    }

    /// The largest `|d|` and orientation angle of `δ = M(X) y` over the pose's noise symbols and
    /// `|y_c| <= h_c`: bilinear, so at one of the 64 × 64 vertex pairs; each component's error
    /// terms `Σ_c e_rc h_c` and a rounding margin are added outward, and the norms rounded up.
    fn vertex_value(&self, h: &[f64; 6]) -> [f64; 2] {
        let slack: [f64; 6] = core::array::from_fn(|r| {
            (0..6).fold(0.0, |s, c| {
                let f = &self.m[r][c];
                let a = f.coefficients();
                let size = a.iter().fold(f.centre().abs(), |a, v| a + v.abs());
                // Symbols other than the pose's (none in M(X), but kept outward if any).
                let other = a[6..].iter().fold(f.error(), |s, v| add_up(s, v.abs()));
                add_up(s, mul_up(add_up(other, size * ERROR_MARGIN), h[c]))
            })
        });
        let mut best = [0.0f64; 2];
        for noise in 0..64u32 {
            let sign = |k: usize| if noise >> k & 1 == 1 { 1.0 } else { -1.0 };
            let m: [[f64; 6]; 6] = core::array::from_fn(|r| {
                core::array::from_fn(|c| {
                    let f = &self.m[r][c];
                    (0..6).fold(f.centre(), |s, k| s + sign(k) * f.coefficients()[k])
                })
            });
            for corner in 0..64u32 {
                let y: [f64; 6] =
                    core::array::from_fn(|c| if corner >> c & 1 == 1 { h[c] } else { -h[c] });
                let comp: [f64; 6] = core::array::from_fn(|r| {
                    let v: f64 = (0..6).map(|c| m[r][c] * y[c]).sum();
                    add_up(v.abs(), slack[r])
                });
                let sq = squared_norms(&comp);
                best = [best[0].max(sq[0]), best[1].max(sq[1])];
            }
        }
        errors_from_squares(best)
    }
}
