//! A chart that follows the commanded pose exactly: the platform's pose errors over a box of
//! poses in one step, wherever the legs' Jacobian is proved nonsingular across the box.
//!
//! **The chart.** At each pose `X` of the box, `δ = M(X) y` with `M(X) = J(X)⁻¹` exactly, where
//! `J(X) = ∇_δ G(X, 0, θ̂)` is the legs' Jacobian at the nominal geometry. `J(X)` is enclosed as
//! affine forms whose noise symbols are the pose's coordinates ([`calib_core::Affine`] through
//! [`calib_core::Jet`]); with `C ≈ J(X_c)⁻¹` (floating point), `S(X) = C J(X) - I` has entries
//! bounded in magnitude by `A`. When a scaled norm of `A` is below 1 ([`scaled_norm`]), `J(X)` is
//! nonsingular at every pose of the box, `|M(X)| <= B` entrywise (the Neumann series' bound, then
//! `B = |C| + A B`), and `M(X) = C - S C + S² M`: the affine form of `C - S C`, first order in the
//! pose, with the remainder `|S² M| <= A² B` (second order). The legs' Jacobian mixes centimetres
//! and the Rodrigues vector: across half of `sample21`'s default workspace the plain norm of `A`
//! is 34 where the scaled one is 0.93, so only the scaled one proves anything there.
//!
//! **The remainder.** Because `J(X) M(X) = I` at every pose, along the segment from `0` to
//! `δ = M(X) y`, `G_i - y_i = (∫₀¹ ∇_δ G_i(X, τ δ, θ*) dτ - ∇_δ G_i(X, 0, θ̂)) · δ`: the change of
//! the gradient with the move (second derivatives in `δ`, averaged over `τ` to half their reach)
//! and with the geometry (`∂²G/∂δ∂θ` times `θ* - θ̂`), both from one Hessian of `G` over the box
//! of poses, the widest region's moves and the leg's box ([`calib_core::Jet2`]). So `|G_i - y_i|
//! <= ρ_i = Σ_{c,d} |½ Mᵀ H_i M|_cd h_c h_d + Σ_r g_i,r z_r` over `|y| <= h`: the move's part as a
//! quadratic form in the legs' coordinates (the components of `δ = M y` keep their correlation,
//! which a bound per component, through `z` the region's reach, loses: the platform moves
//! sideways far more easily than it tilts a leg), the geometry's through `z`. First order in the
//! geometry's spread, second in the move, whatever the width of the box of poses (the chart is
//! exact; the box only widens the enclosures).
//!
//! **Closing and bounding.** Leg `i`'s change along the path lies in `[-U⁻_i, U⁺_i]` (see
//! [`super::pose_bound`]). The region `D(X) = {M(X) y : -R⁻ <= y <= R⁺}` closes when `U^±_i +
//! ρ_i < R^±_i` for every leg and side, `ρ` over the box `|y| <= max(R⁻, R⁺)`: every move on the
//! face `y_i = R⁺_i` then has `G_i >= R⁺_i - ρ_i > U⁺_i`, on `y_i = -R⁻_i` `G_i < -U⁻_i`, so no
//! move on the boundary lies in `F`, for every pose of the box and every geometry at once, and
//! the reached move lies in `D(X) ∩ F ⊆ {M(X) y : -U⁻ - ρ <= y <= U⁺ + ρ}`. The least such
//! region is sought by `R ← (U + ρ(R))(1 + g)` from `R = U (1 + g)`, each leg and side its own
//! width. The position and orientation errors are norms of `M(X) y`, bilinear in the pose's
//! noise symbols and `y`: convex in each, so their largest values are at one of the 64 × 64
//! vertex pairs, with the remainder of `M(X)` taken outward.

use super::enclosure::{AccuracyProblem, PoseBox};
use super::pose_bound::{
    errors_from_squares, leg_change_bounds, reached_change, squared_norms, ChangeBounds,
};
use calib_core::{Affine, Interval, Jet, Jet2};

/// Second-order jets in twelve symbols.
type Hessian = Jet2<Interval, 12, 78>;
/// Affine forms in the pose's noise symbols.
type Form = Affine<6>;
/// A 6 × 6 matrix of floating-point numbers.
type Matrix = [[f64; 6]; 6];

/// The widest region tried, in units of `U`: the remainder's Hessian is taken over its moves.
const WIDEST: f64 = 3.0;
/// The margin by which each round's region exceeds the previous one's `U + ρ`.
const GROWTH: f64 = 0.03;
/// Rounds of the search for the least region that closes.
const REGION_ROUNDS: usize = 16;
/// Rounds of the enclosure of `D(X) ∩ F` by `|y_i| <= U_i + ρ_i(h)`.
const SHRINK_ROUNDS: usize = 4;
/// Rounds of `B ← min(B, |C| + A B)` after the Neumann series' bound.
const INVERSE_ROUNDS: usize = 4;
/// The relative margin added to every vertex sum of products (floating point, far above the
/// `γ_n` bound of six products of six terms).
const ERROR_MARGIN: f64 = 1e-12;

/// The chart of one box of poses.
pub struct PoseChart {
    /// `M(X) ∈ centre + Σ_k slope_k ε_k ± slack` for the pose's noise symbols `ε_k ∈ [-1, 1]`
    /// (`X_k = mid(x_k) + rad(x_k) ε_k`).
    pub centre: Matrix,
    /// The change of `M(X)` along each pose coordinate over its half-width.
    pub slope: [Matrix; 6],
    /// The entries' remainder (second order in the box's width) and roundings.
    pub slack: Matrix,
    /// `[U⁻_i, U⁺_i]`: leg `i`'s change along the path lies in `[-U⁻_i, U⁺_i]`.
    pub bound: ChangeBounds,
    /// The box of poses.
    pose: PoseBox,
    /// Per leg, the box of the geometry `(a, b)` joined with the nominal values, and its spread
    /// `mag(Θ - θ̂)`.
    geometry: Vec<([Interval; 6], [f64; 6])>,
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

/// `a / b` rounded up, for `a >= 0`, `b > 0` (`+∞` when either is not finite).
fn div_up(a: f64, b: f64) -> f64 {
    if a.is_finite() && b.is_finite() && b > 0.0 {
        (Interval::point(a) / Interval::point(b)).sup()
    } else {
        f64::INFINITY
    }
}

/// An upper bound `σ` of the spectral radius of every matrix whose entries are bounded in
/// magnitude by the nonnegative `mag`, and the positive weights `v` that prove it:
/// `σ = max_r (Σ_c mag_rc v_c) / v_r`, rounded up (`‖D⁻¹ A D‖∞` with `D = diag(v)`: any positive
/// `v` proves it; shifted power iteration picks `v` near the Perron vector, where `σ` is nearly
/// `ρ(mag)`). `+∞` when not finite.
pub fn scaled_norm(mag: &Matrix) -> (f64, [f64; 6]) {
    let mut v = [1.0f64; 6];
    if !mag.iter().flatten().all(|x| x.is_finite() && *x >= 0.0) {
        return (f64::INFINITY, v);
    }
    // Power iteration on `mag + t I`, `t` half the last estimate of the radius: the shift keeps
    // it converging where `mag` alone cycles (a matrix that maps one scale onto another).
    let mut t = 0.0;
    for _ in 0..40 {
        let w: [f64; 6] =
            core::array::from_fn(|r| (0..6).map(|c| mag[r][c] * v[c]).sum::<f64>() + t * v[r]);
        let top = w.iter().fold(0.0f64, |a, b| a.max(*b));
        if !(top > 0.0 && top.is_finite()) {
            break;
        }
        let estimate = (0..6).map(|r| w[r] / v[r]).fold(0.0, f64::max) - t;
        // A floor keeps every weight positive (a zero row would otherwise zero its weight).
        v = w.map(|x| (x / top).max(1e-6));
        t = 0.5 * estimate.max(0.0);
    }
    let sigma = (0..6)
        .map(|r| {
            let s = (0..6).fold(0.0, |s, c| add_up(s, mul_up(mag[r][c], v[c])));
            div_up(s, v[r])
        })
        .fold(0.0, f64::max);
    (sigma, v)
}

/// The product of two nonnegative matrices, rounded up.
fn product_up(a: &Matrix, b: &Matrix) -> Matrix {
    core::array::from_fn(|r| {
        core::array::from_fn(|c| (0..6).fold(0.0, |s, k| add_up(s, mul_up(a[r][k], b[k][c]))))
    })
}

/// The pose, the move and the geometry of leg `i` as the inputs of [`reached_change`].
fn inputs<T: Copy>(pose: &[T; 6], geometry: &[T; 6]) -> [T; 12] {
    core::array::from_fn(|k| if k < 6 { pose[k] } else { geometry[k - 6] })
}

impl PoseChart {
    /// The chart of the box of poses `x` with actuator errors `± eps`; `None` when the legs'
    /// Jacobian is not proved nonsingular over the box or a leg's bound is not finite.
    pub fn new(problem: &AccuracyProblem, x: &PoseBox, eps: f64) -> Option<PoseChart> {
        let bound = leg_change_bounds(problem, x, eps)?;
        PoseChart::with_leg_bounds(problem, x, bound)
    }

    /// [`PoseChart::new`] with the legs' change bounds `U` given (any upper bounds of `U_i` over
    /// the box: a parent box's serve its halves).
    pub fn with_leg_bounds(
        problem: &AccuracyProblem,
        x: &PoseBox,
        bound: ChangeBounds,
    ) -> Option<PoseChart> {
        if problem.legs() != 6 || !bound.iter().flatten().all(|u| u.is_finite() && *u > 0.0) {
            return None;
        }
        // J(X) as affine forms in the pose's noise symbols, at the nominal geometry.
        let pose: [Form; 6] = core::array::from_fn(|k| Form::input(x[k], k));
        let constant = |v: f64| Form::from_interval(Interval::point(v));
        let jacobian: [[Form; 6]; 6] = core::array::from_fn(|i| {
            let n = problem.nominal(i);
            let delta: [Jet<Form, 6>; 6] =
                core::array::from_fn(|r| Jet::variable(constant(0.0), r));
            let geometry: [Jet<Form, 6>; 6] =
                core::array::from_fn(|k| Jet::constant(constant(n[k])));
            reached_change(&delta, &inputs(&pose.map(Jet::constant), &geometry)).grad
        });
        let c = nalgebra::Matrix6::from_fn(|r, k| jacobian[r][k].centre()).try_inverse()?;
        if !c.iter().all(|v| v.is_finite()) {
            return None;
        }
        let c: Matrix = core::array::from_fn(|r| core::array::from_fn(|k| c[(r, k)]));
        // S(X) = C J(X) - I and its magnitudes A.
        let s: [[Form; 6]; 6] = core::array::from_fn(|r| {
            core::array::from_fn(|col| {
                let start = constant(if r == col { -1.0 } else { 0.0 });
                (0..6).fold(start, |acc, k| acc + constant(c[r][k]) * jacobian[k][col])
            })
        });
        let a: Matrix = s.map(|row| row.map(|f| f.range().mag()));
        let (sigma, v) = scaled_norm(&a);
        // NaN fails too.
        if sigma.partial_cmp(&1.0) != Some(core::cmp::Ordering::Less) {
            return None;
        }
        let c_magnitude = c.map(|row| row.map(f64::abs));
        let magnitude = inverse_magnitude(&c_magnitude, &a, sigma, &v);
        // M(X) = C - S C + S² M, the last term within A² B.
        let second = product_up(&product_up(&a, &a), &magnitude);
        let mut centre = [[0.0; 6]; 6];
        let mut slope = [[[0.0; 6]; 6]; 6];
        let mut slack = [[0.0; 6]; 6];
        for r in 0..6 {
            for col in 0..6 {
                let m = (0..6).fold(constant(c[r][col]), |acc, k| {
                    acc - s[r][k] * constant(c[k][col])
                });
                centre[r][col] = m.centre();
                for (k, sk) in slope.iter_mut().enumerate() {
                    sk[r][col] = m.coefficients()[k];
                }
                slack[r][col] = add_up(m.error(), second[r][col]);
            }
        }
        let finite = |m: &Matrix| m.iter().flatten().all(|v| v.is_finite());
        if !(finite(&centre) && slope.iter().all(finite)) {
            return None;
        }
        let geometry = (0..6)
            .map(|i| {
                let t = problem.theta(i);
                let n = problem.nominal(i);
                let joined: [Interval; 6] =
                    core::array::from_fn(|k| t[k].hull(Interval::point(n[k])));
                let spread = core::array::from_fn(|k| (joined[k] - Interval::point(n[k])).mag());
                (joined, spread)
            })
            .collect();
        Some(PoseChart {
            centre,
            slope,
            slack,
            bound,
            pose: *x,
            geometry,
        })
    }

    /// Per leg, the remainder's parts from one Hessian of `G_i` over the box of poses, every move
    /// `|δ_j| <= z_j` and the leg's box joined with the nominal geometry; `None` when one is not
    /// finite.
    fn curvature(&self, z: &[f64; 6]) -> Option<Vec<Curvature>> {
        let pose = self.pose.map(Hessian::constant);
        // M(X) entrywise: centre ± (Σ_k |slope_k| + slack).
        let m: [[Interval; 6]; 6] = core::array::from_fn(|r| {
            core::array::from_fn(|c| {
                let w = (0..6).fold(self.slack[r][c], |s, k| {
                    add_up(s, self.slope[k][r][c].abs())
                });
                Interval::point(self.centre[r][c]) + Interval::new(-w, w)
            })
        });
        let out: Vec<Curvature> = self
            .geometry
            .iter()
            .map(|(joined, spread)| {
                let delta: [Hessian; 6] =
                    core::array::from_fn(|j| Hessian::variable(Interval::new(-z[j], z[j]), j));
                let theta: [Hessian; 6] =
                    core::array::from_fn(|k| Hessian::variable(joined[k], 6 + k));
                let h = reached_change(&delta, &inputs(&pose, &theta));
                // ½ Mᵀ H M, H = ∂²G_i/∂δ².
                let hm: [[Interval; 6]; 6] = core::array::from_fn(|r| {
                    core::array::from_fn(|c| {
                        (0..6).fold(Interval::ZERO, |s, j| s + h.second(r, j) * m[j][c])
                    })
                });
                let quadratic = core::array::from_fn(|c| {
                    core::array::from_fn(|d| {
                        let q = (0..6).fold(Interval::ZERO, |s, r| s + m[r][c] * hm[r][d]);
                        (Interval::point(0.5) * q).mag()
                    })
                });
                let geometry = core::array::from_fn(|c| {
                    (0..6).fold(0.0, |s, k| {
                        add_up(s, mul_up(h.second(c, 6 + k).mag(), spread[k]))
                    })
                });
                Curvature {
                    quadratic,
                    geometry,
                }
            })
            .collect();
        out.iter()
            .all(|c| {
                c.quadratic.iter().flatten().all(|v| v.is_finite())
                    && c.geometry.iter().all(|v| v.is_finite())
            })
            .then_some(out)
    }

    /// `ρ_i = Σ_{c,d} Q_i,cd h_c h_d + Σ_r g_i,r z_r` over `|y| <= h`, the moves' components
    /// within `z` (module documentation), from `curvature` taken over moves at least as large.
    fn remainder(curvature: &[Curvature], z: &[f64; 6], h: &[f64; 6]) -> [f64; 6] {
        core::array::from_fn(|i| {
            let q = &curvature[i].quadratic;
            let moves = (0..6).fold(0.0, |s, c| {
                (0..6).fold(s, |s, d| add_up(s, mul_up(mul_up(q[c][d], h[c]), h[d])))
            });
            let geometry = &curvature[i].geometry;
            (0..6).fold(moves, |s, r| add_up(s, mul_up(geometry[r], z[r])))
        })
    }

    /// `M(X)` at the 64 vertices of the pose's noise symbols, and per component the slack of
    /// every entry of its row (the remainder and a rounding margin) to be added outward.
    fn vertices(&self) -> (Vec<Matrix>, Matrix) {
        let slack: Matrix = core::array::from_fn(|r| {
            core::array::from_fn(|c| {
                let size = (0..6).fold(self.centre[r][c].abs(), |a, k| {
                    a + self.slope[k][r][c].abs()
                });
                add_up(self.slack[r][c], size * ERROR_MARGIN)
            })
        });
        let vertices = (0..64u32)
            .map(|noise| {
                let sign = |k: usize| if noise >> k & 1 == 1 { 1.0 } else { -1.0 };
                core::array::from_fn(|r| {
                    core::array::from_fn(|c| {
                        (0..6).fold(self.centre[r][c], |s, k| s + sign(k) * self.slope[k][r][c])
                    })
                })
            })
            .collect();
        (vertices, slack)
    }

    /// Upper bounds of `|δ_r|` over the moves `δ = M(X) y`, `|y_c| <= h_c`, for every pose of
    /// the box: `max_ε Σ_c |M(ε)_rc| h_c + Σ_c slack_rc h_c` (linear in the pose's noise
    /// symbols, so largest at a vertex).
    fn reach(vertices: &[Matrix], slack: &Matrix, h: &[f64; 6]) -> [f64; 6] {
        core::array::from_fn(|r| {
            let outward = (0..6).fold(0.0, |s, c| add_up(s, mul_up(slack[r][c], h[c])));
            let largest = vertices
                .iter()
                .map(|m| (0..6).fold(0.0, |s, c| add_up(s, mul_up(m[r][c].abs(), h[c]))))
                .fold(0.0, f64::max);
            add_up(largest, outward)
        })
    }

    /// `max(U⁻_i, U⁺_i)`, at least a quarter of the largest over the legs: the scale of each
    /// leg's region (so that a leg known almost exactly still has room for the others' moves).
    fn wider(&self) -> [f64; 6] {
        let sides = self.bound.map(|[below, above]| below.max(above));
        let largest = sides.iter().fold(0.0f64, |a, b| a.max(*b));
        sides.map(|v| v.max(0.25 * largest))
    }

    /// `ρ_i` over `|y_c| <= h_c` (module documentation), for `h` within 3 times each leg's
    /// scale (its change's larger side, or a quarter of the largest); `None` beyond, or when an
    /// enclosure failed.
    pub fn remainder_over(&self, h: &[f64; 6]) -> Option<[f64; 6]> {
        let wider = self.wider();
        if !(0..6).all(|i| h[i] <= WIDEST * wider[i]) {
            return None;
        }
        let (vertices, slack) = self.vertices();
        let curvature =
            self.curvature(&Self::reach(&vertices, &slack, &wider.map(|v| WIDEST * v)))?;
        Some(Self::remainder(
            &curvature,
            &Self::reach(&vertices, &slack, h),
            h,
        ))
    }

    /// Upper bounds of the position (cm) and orientation (degrees) errors over every pose of the
    /// box, every geometry and every actuator error, or `None` when no region closes.
    pub fn bound(&self) -> Option<[f64; 2]> {
        let u = self.bound;
        let wider = self.wider();
        let (vertices, slack) = self.vertices();
        let curvature =
            self.curvature(&Self::reach(&vertices, &slack, &wider.map(|v| WIDEST * v)))?;
        // ρ over a region [-r⁻, r⁺] (within the box of its larger sides).
        let rest = |r: &ChangeBounds| {
            let hull = r.map(|[below, above]| below.max(above));
            Self::remainder(&curvature, &Self::reach(&vertices, &slack, &hull), &hull)
        };
        // The least region that closes: R ← (U + ρ(R)) (1 + GROWTH) from R = U (1 + GROWTH), on
        // each side of each leg, rises towards the least fixed point, where U + ρ(R) < R; beyond
        // WIDEST the curvature does not hold.
        let grow = |r: &ChangeBounds| r.map(|sides| sides.map(|v| mul_up(v, 1.0 + GROWTH)));
        let mut r = grow(&u);
        let mut closed = None;
        for _ in 0..REGION_ROUNDS {
            if !(0..6).all(|i| r[i].iter().all(|v| *v <= WIDEST * wider[i])) {
                break;
            }
            let rest = rest(&r);
            let next: ChangeBounds =
                core::array::from_fn(|i| u[i].map(|side| add_up(side, rest[i])));
            if (0..6).all(|i| next[i][0] < r[i][0] && next[i][1] < r[i][1]) {
                closed = Some(r);
                break;
            }
            r = grow(&next);
        }
        let mut h = closed?;
        for _ in 0..SHRINK_ROUNDS {
            let rest = rest(&h);
            h = core::array::from_fn(|i| {
                core::array::from_fn(|k| add_up(u[i][k], rest[i]).min(h[i][k]))
            });
        }
        // An overflow bounds nothing.
        Some(Self::vertex_value(&vertices, &slack, &h)).filter(|b| b.iter().all(|v| v.is_finite()))
    }

    /// The largest `|d|` and orientation angle of `δ = M(X) y` over the pose's noise symbols and
    /// `-h⁻_c <= y_c <= h⁺_c`: bilinear, so at one of the 64 × 64 vertex pairs; each component's
    /// slack `Σ_c slack_rc max(h⁻_c, h⁺_c)` is added outward, and the norms rounded up.
    fn vertex_value(vertices: &[Matrix], slack: &Matrix, h: &ChangeBounds) -> [f64; 2] {
        let outward: [f64; 6] = core::array::from_fn(|r| {
            (0..6).fold(0.0, |s, c| {
                add_up(s, mul_up(slack[r][c], h[c][0].max(h[c][1])))
            })
        });
        let mut best = [0.0f64; 2];
        for m in vertices {
            for corner in 0..64u32 {
                let y: [f64; 6] = core::array::from_fn(|c| {
                    if corner >> c & 1 == 1 {
                        h[c][1]
                    } else {
                        -h[c][0]
                    }
                });
                let comp: [f64; 6] = core::array::from_fn(|r| {
                    let v: f64 = (0..6).map(|c| m[r][c] * y[c]).sum();
                    add_up(v.abs(), outward[r])
                });
                let sq = squared_norms(&comp);
                best = [best[0].max(sq[0]), best[1].max(sq[1])];
            }
        }
        errors_from_squares(best)
    }
}

/// One leg's part of the remainder (module documentation).
struct Curvature {
    /// `|½ Mᵀ H M|` entrywise, `H = ∂²G_i/∂δ²` over the moves: the move's curvature in the
    /// legs' coordinates `y`, where the components of `δ = M y` keep their correlation.
    quadratic: Matrix,
    /// `Σ_k |∂²G_i/∂δ_r∂θ_k| mag(θ_k - θ̂_k)` per move component: the gradient's change over the
    /// leg's box.
    geometry: [f64; 6],
}

/// `B >= |(I + S)⁻¹ C|` entrywise for every `|S| <= a` with `‖D⁻¹ a D‖∞ <= σ < 1` (`D =
/// diag(v)`): first the Neumann series' bound `B_rc = v_r max_s (|C|_sc / v_s) / (1 - σ)`, then
/// rounds of `B ← min(B, |C| + a B)`, each again a bound (`|M| <= |C| + |S| |M|`).
fn inverse_magnitude(c: &Matrix, a: &Matrix, sigma: f64, v: &[f64; 6]) -> Matrix {
    let gap = (Interval::point(1.0) - Interval::point(sigma)).inf();
    let column: [f64; 6] =
        core::array::from_fn(|col| (0..6).map(|s| div_up(c[s][col], v[s])).fold(0.0, f64::max));
    let mut b: Matrix = core::array::from_fn(|r| {
        core::array::from_fn(|col| div_up(mul_up(v[r], column[col]), gap))
    });
    for _ in 0..INVERSE_ROUNDS {
        let ab = product_up(a, &b);
        for r in 0..6 {
            for col in 0..6 {
                b[r][col] = b[r][col].min(add_up(c[r][col], ab[r][col]));
            }
        }
    }
    b
}
