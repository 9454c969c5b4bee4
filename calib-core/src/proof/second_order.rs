//! Second-order Farkas certificates: proofs that no parameter vector fits the data, where the
//! linear relaxation of the contraction is too loose to show it.
//!
//! Near the smallest consistent error bound `s*` the data miss consistency by a margin far smaller
//! than the slack of any linear relaxation over a realistic prior (on the real UR10, 0.008 mm per
//! row at `0.98 s*` against 0.19 mm; `benches/README.md`), so the contraction's LP stays feasible
//! and the box undecided. The certificate here uses the curvature the relaxation throws away.
//!
//! **The combination.** The Chebyshev fit of the box ([`crate::smallest_scale`]) has, at its point
//! `x*`, LP multipliers that weigh the residuals of the configurations into one function
//! ([`crate::proof::chebyshev::chebyshev_weights`]):
//!
//! `φ(x, M) = Σ_k Σ_r c_{k,r} f_r(x, M_k)`.
//!
//! If the data are consistent, some `x` in the box and readings `M_k` in their boxes make every
//! `f_r(x, M_k) = 0`, hence `φ = 0`. So **a proof that `φ > 0` over the whole box (times the
//! measurement boxes) proves the box empty**. At a Chebyshev point the gradient of `φ` in `x` is
//! what keeps `x*` in the box (zero in the interior), and `φ(x*, mid M)` exceeds the measurement
//! half-ranges by `(s_box − 1)` per unit: when the box's misfit `s_box > 1`, `φ`'s linear part
//! certifies emptiness to first order, and everything rests on the nonlinear remainder.
//!
//! **The remainder.** Taylor's theorem at `z0 = (x*, mid M)`, with `δ = z − z0` over the box `Z`:
//!
//! `φ(z) = φ(z0) + ∇φ(z0)·δ + ½ δᵀ H(z0) δ + ⅙ Σ_abc T_abc(ξ) δ_a δ_b δ_c`,  `ξ ∈ Z`,
//!
//! with `H` and `T` the second and third derivatives of `φ`. The combination is taken **before**
//! the bounds: the weights of the configurations cancel most of their curvature in `H(z0)` (on the
//! real UR10, 22× less than the sum of the rows' own curvatures), which a per-row relaxation
//! cannot. The model provides, through [`Curvature`], enclosures of every row's `H` at `z0` and of
//! `Σ_c T_abc(ξ) δ_c` over the box (forward-mode second-order [`Jet2`]s of [`Jet`]s over
//! intervals); this module bounds, rigorously:
//!
//! * `φ(z0)` and `∇φ(z0)·δ` by interval arithmetic at the point and over the box;
//! * `½ δᵀ H(z0) δ` over the parameters by a diagonal-shift (Shor) bound: with `δ = c + R ε`,
//!   `ε ∈ [-1, 1]ⁿ`, the form is `vᵀ Q v` for `v = (1, ε)`, and `Q + diag(d) ⪰ 0` (proved by an
//!   interval Cholesky factorisation) gives `vᵀ Q v >= −d_0 − Σ_{i>0} max(d_i, 0)`; the shift is
//!   found by subgradient steps on `Σ d − n λ_min(Q + diag(d))` (a hint: only the Cholesky proof
//!   counts). The terms between parameters and readings, and between readings, by magnitudes;
//! * the third-order term by `⅙ Σ_ab |T_ab| |δ_a| |δ_b|`.
//!
//! If the sum of the lower bounds is positive the box is empty. Nothing else is assumed: the
//! weights, the point and the shift are numerical hints, and a poor hint only makes the bound
//! fail. On the real UR10 (60 configurations, 27 parameters, prior ±0.1° / ±1–2 mm) the
//! certificate over the box contracted at `0.98 s*` proves it empty, where the contraction alone
//! stops at `0.76 s*`.

use crate::model::curvature::{on_large_stacks, Curvature};
use crate::proof::chebyshev::chebyshev_weights;
use crate::{smallest_scale, Interval, VectorModel};

/// A proof that a box holds no parameter vector consistent with the measurements (see the module
/// documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct SecondOrderCertificate {
    /// The measurements (0-based, sorted) whose residuals the combination weighs: the proof uses
    /// no other.
    pub support: Vec<usize>,
    /// The proved lower bound of the combination over the box (positive), in units of the
    /// combination's measurement half-ranges.
    pub margin: f64,
}

/// Tries to prove that no `x` in the box `x` fits every measurement box (see the module
/// documentation). `None` when the proof fails — which proves nothing.
pub fn second_order_emptiness<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    curvature: &dyn Curvature<NX, NM, NR>,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
) -> Option<SecondOrderCertificate>
where
    M: VectorModel<NX, NM, NR>,
{
    if measurements.is_empty() || x.iter().any(|v| !v.is_bounded()) {
        return None;
    }
    let all = [true; NM];
    let fit = smallest_scale(model, x, measurements, &all);
    if fit.scale.is_nan() || fit.scale <= 1.0 {
        return None;
    }
    let xs = fit.point;
    let mut weights = chebyshev_weights(model, x, measurements, &all, &xs)?;
    // φ(z0) > 0 is the side to prove.
    let phi0: f64 = measurements
        .iter()
        .zip(&weights)
        .map(|(m, c)| {
            let f = model.residuals(&xs, &m.map(|v| v.mid()));
            (0..NR).map(|r| c[r] * f[r]).sum::<f64>()
        })
        .sum();
    if phi0 < 0.0 {
        weights.iter_mut().flatten().for_each(|c| *c = -*c);
    }
    let bound =
        |w: &[[f64; NR]]| combination_lower_bound(model, curvature, x, measurements, &xs, w);
    // First without the configurations whose weight is at the LP solver's noise (see
    // [`NEGLIGIBLE_WEIGHT`]): the certificate then weighs only the configurations the fit rests
    // on, and their derivatives alone are computed. Any weights give a valid bound; if these fail,
    // the full ones are tried.
    let trimmed = trim_negligible(&weights);
    let (weights, margin) = match (trimmed != weights).then(|| bound(&trimmed)).flatten() {
        Some(m) if m > 0.0 => (trimmed, m),
        _ => {
            let m = bound(&weights)?;
            (weights, m)
        }
    };
    let support: Vec<usize> = (0..measurements.len())
        .filter(|&k| weights[k].iter().any(|&v| v != 0.0))
        .collect();
    (margin > 0.0).then_some(SecondOrderCertificate { support, margin })
}

/// A configuration whose weights add up to at most this fraction of all the weights is left out
/// of the first try of a second-order certificate. The weights are an interior-point LP's
/// multipliers, which leave every configuration some weight: on the real UR10 at 0.98 `s*`, 17 of
/// 60 configurations carry the combination (the least 3.6e-5 of it) and the other 43 at most
/// 2.3e-8 each (5e-7 on subsets), the solver's tolerance. Counting those would make every
/// certificate weigh every configuration.
pub(crate) const NEGLIGIBLE_WEIGHT: f64 = 1e-6;

/// `weights` with the configurations of negligible weight ([`NEGLIGIBLE_WEIGHT`]) set to zero.
fn trim_negligible<const NR: usize>(weights: &[[f64; NR]]) -> Vec<[f64; NR]> {
    let size = |w: &[f64; NR]| w.iter().map(|c| c.abs()).sum::<f64>();
    let total: f64 = weights.iter().map(size).sum();
    weights
        .iter()
        .map(|w| {
            if size(w) <= NEGLIGIBLE_WEIGHT * total {
                [0.0; NR]
            } else {
                *w
            }
        })
        .collect()
}

/// A rigorous lower bound of `φ(x, M) = Σ_k Σ_r weights[k][r] f_r(x, M_k)` over the box `x` and
/// the measurement boxes, by the second-order Taylor bound at `(point, mid M)` of the module
/// documentation. Any weights and any `point` of the box give a valid bound (the Chebyshev fit's
/// make it tight); `None` when the model's derivatives are not available (more than
/// [`crate::MAX_CURVATURE_SYMBOLS`] symbols), `point` is outside the box or the lengths differ. A
/// positive bound proves that no parameter vector of the box fits the measurements.
pub fn combination_lower_bound<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    curvature: &dyn Curvature<NX, NM, NR>,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
    point: &[f64; NX],
    weights: &[[f64; NR]],
) -> Option<f64>
where
    M: VectorModel<NX, NM, NR>,
{
    if weights.len() != measurements.len() || (0..NX).any(|j| !x[j].contains(point[j])) {
        return None;
    }
    let xs = *point;
    let support: Vec<usize> = (0..measurements.len())
        .filter(|&k| weights[k].iter().any(|&v| v != 0.0))
        .collect();
    let live_x: Vec<usize> = (0..NX).filter(|&j| x[j].rad() > 0.0).collect();
    // The symbols of the second-order terms: the live quantities some first derivative depends
    // on (for the others every second and third derivative is 0).
    let curved_x: Vec<usize> = live_x
        .iter()
        .copied()
        .filter(|&j| curvature.curved(j))
        .collect();
    let symbols_of = |m: &[Interval; NM]| -> Vec<usize> {
        curved_x
            .iter()
            .copied()
            .chain(
                (0..NM)
                    .filter(|&i| m[i].rad() > 0.0 && curvature.curved(NX + i))
                    .map(|i| NX + i),
            )
            .collect()
    };
    // Every configuration's derivatives, on threads with large stacks.
    let derivatives = on_large_stacks(&support, |&k| {
        let m = &measurements[k];
        let m0 = m.map(|v| v.mid());
        let symbols = symbols_of(m);
        let h = curvature.second_derivatives(&xs, &m0, &symbols)?;
        let t = curvature.third_derivatives_along(x, m, &xs, &m0, &symbols)?;
        Some((symbols, h, t))
    })?;
    let xp: [Interval; NX] = xs.map(Interval::point);
    let mut sums = TaylorSums {
        // δ over the box, per parameter.
        dx: core::array::from_fn(|j| x[j] - xp[j]),
        xp,
        nx: curved_x.len(),
        bound: Interval::ZERO,
        gx: [Interval::ZERO; NX],
        hxx: vec![Interval::ZERO; curved_x.len() * curved_x.len()],
    };
    for (&k, d) in support.iter().zip(derivatives) {
        let (symbols, h, t) = d?;
        sums.add(model, &measurements[k], &weights[k], &symbols, (&h, &t))?;
    }
    let TaylorSums {
        mut bound,
        gx,
        hxx,
        dx,
        ..
    } = sums;
    for &j in &live_x {
        bound += Interval::point((gx[j] * dx[j]).inf());
    }
    let deltas: Vec<Interval> = curved_x.iter().map(|&j| dx[j]).collect();
    bound += Interval::point(half_quadratic_lower_bound(&hxx, &deltas));
    Some(bound.inf())
}

/// The terms of [`combination_lower_bound`] summed over the configurations, at the point `xp`
/// with `δ = x - xp` over the box: what is bounded per configuration goes into `bound`; the
/// parameters' gradient and curvature are summed first and bounded once over the box.
struct TaylorSums<const NX: usize> {
    /// The point, as intervals.
    xp: [Interval; NX],
    /// `δ = x - xp` over the box, per parameter.
    dx: [Interval; NX],
    /// How many curved parameters lead the symbols (the rows and columns of `hxx`).
    nx: usize,
    /// The weighted values, the readings' first-order terms and the lower bounds of the
    /// higher-order terms not kept in `hxx`.
    bound: Interval,
    /// `Σ_k Σ_r c_kr ∂f_r/∂x` at the point.
    gx: [Interval; NX],
    /// `Σ_k Σ_r c_kr ∂²f_r/∂x²` over the curved parameters at the point (`nx × nx`, row-major).
    hxx: Vec<Interval>,
}

impl<const NX: usize> TaylorSums<NX> {
    /// Adds configuration `m` with weights `c`: its value and first-order terms at
    /// `(xp, mid m)`, then its second- and third-order terms over `symbols` from the derivative
    /// blocks `(h, t)` (`NR` blocks of `n × n`, `n = symbols.len()`; `None` if their sizes
    /// differ).
    fn add<M, const NM: usize, const NR: usize>(
        &mut self,
        model: &M,
        m: &[Interval; NM],
        c: &[f64; NR],
        symbols: &[usize],
        (h, t): (&[Interval], &[Interval]),
    ) -> Option<()>
    where
        M: VectorModel<NX, NM, NR>,
    {
        let m0 = m.map(|v| v.mid());
        let dm: [Interval; NM] = core::array::from_fn(|i| m[i] - Interval::point(m0[i]));
        let ev = model.evaluate_rows_interval(&self.xp, &m0.map(Interval::point));
        let cw: [Interval; NR] = c.map(Interval::point);
        for r in 0..NR {
            self.bound += cw[r] * ev[r].value;
            for j in 0..NX {
                self.gx[j] += cw[r] * ev[r].dx[j];
            }
        }
        // The readings' first-order term, exact per configuration (its own readings only).
        for i in 0..NM {
            let g = (0..NR).fold(Interval::ZERO, |acc, r| acc + cw[r] * ev[r].dm[i]);
            self.bound += Interval::point((g * dm[i]).inf());
        }
        let n = symbols.len();
        if h.len() != NR * n * n || t.len() != NR * n * n {
            return None;
        }
        self.add_curvature(&cw, symbols, (h, t), &dm);
        Some(())
    }

    /// The second- and third-order terms of one configuration with weights `cw`: `½ δᵀ H δ`
    /// between parameters goes into `hxx`; the rest of `½ δᵀ H δ` and `⅙ δᵀ T δ` are bounded by
    /// magnitudes (`dm`: the readings' `δ`) and subtracted from `bound`.
    fn add_curvature<const NM: usize, const NR: usize>(
        &mut self,
        cw: &[Interval; NR],
        symbols: &[usize],
        (h, t): (&[Interval], &[Interval]),
        dm: &[Interval; NM],
    ) {
        let (n, nx) = (symbols.len(), self.nx);
        let combined = |blocks: &[Interval], a: usize, b: usize| -> Interval {
            (0..NR).fold(Interval::ZERO, |acc, r| {
                acc + cw[r] * blocks[r * n * n + a * n + b]
            })
        };
        // |δ| per symbol, rounded up.
        let reach = |a: usize| -> f64 {
            let s = symbols[a];
            if s < NX {
                self.dx[s].mag()
            } else {
                dm[s - NX].mag()
            }
        };
        let mut lost = Interval::ZERO;
        for a in 0..n {
            for b in 0..n {
                let ra = Interval::point(reach(a)) * Interval::point(reach(b));
                // ⅙ δᵀ T δ, bounded by magnitudes.
                lost += Interval::point(combined(t, a, b).mag()) * ra / Interval::point(6.0);
                if a < nx && b < nx {
                    self.hxx[a * nx + b] += combined(h, a, b);
                } else {
                    // ½ δᵀ H δ between parameters and readings and between readings.
                    lost += Interval::point(combined(h, a, b).mag()) * ra * Interval::point(0.5);
                }
            }
        }
        self.bound -= Interval::point(lost.sup());
    }
}

/// A lower bound of `½ δᵀ H δ` over every symmetric `H` in the interval matrix `h` (`n × n`,
/// row-major) and every `δ` in the box `delta`, by the diagonal-shift bound of the module
/// documentation; `−∞` when no bound is found.
pub(crate) fn half_quadratic_lower_bound(h: &[Interval], delta: &[Interval]) -> f64 {
    let n = delta.len();
    if n == 0 {
        return 0.0;
    }
    if h.len() != n * n || h.iter().chain(delta).any(|v| !v.is_bounded()) {
        return f64::NEG_INFINITY;
    }
    // δ = c + R ε covers the box (rad is rounded up so that mid ± rad contains it).
    let c: Vec<Interval> = delta.iter().map(|d| Interval::point(d.mid())).collect();
    let rad: Vec<Interval> = delta.iter().map(|d| Interval::point(d.rad())).collect();
    let hm: Vec<Interval> = h.iter().map(|v| Interval::point(v.mid())).collect();
    // The width of h: ½ Σ rad(h_ab) |δ_a| |δ_b|.
    let mut lost = Interval::ZERO;
    for a in 0..n {
        for b in 0..n {
            lost += Interval::point(h[a * n + b].rad())
                * Interval::point(delta[a].mag())
                * Interval::point(delta[b].mag());
        }
    }
    // Q over v = (1, ε): Q00 = cᵀ Hm c, Q0a = R_a (Hm c)_a, Qab = R_a Hm_ab R_b.
    let hc: Vec<Interval> = (0..n)
        .map(|a| (0..n).fold(Interval::ZERO, |acc, b| acc + hm[a * n + b] * c[b]))
        .collect();
    let dim = n + 1;
    let mut q = vec![Interval::ZERO; dim * dim];
    q[0] = (0..n).fold(Interval::ZERO, |acc, a| acc + c[a] * hc[a]);
    for a in 0..n {
        q[a + 1] = rad[a] * hc[a];
        q[(a + 1) * dim] = q[a + 1];
        for b in 0..n {
            q[(a + 1) * dim + b + 1] = rad[a] * hm[a * n + b] * rad[b];
        }
    }
    // vᵀ (Q − mid Q) v >= −Σ rad(Q_ab), since |v_a v_b| <= 1.
    let q_rad = q
        .iter()
        .fold(Interval::ZERO, |acc, v| acc + Interval::point(v.rad()));
    let qm: Vec<f64> = q.iter().map(|v| v.mid()).collect();
    let Some(shifted) = psd_shift(&qm, dim) else {
        return f64::NEG_INFINITY;
    };
    // vᵀ Qm v = vᵀ S v − Σ d_i v_i² with S = Qm + diag(d) ⪰ 0 and d_i = S_ii − Qm_ii exactly.
    let mut form = Interval::ZERO - q_rad;
    for i in 0..dim {
        let d = Interval::point(shifted[i * dim + i]) - Interval::point(qm[i * dim + i]);
        let d = if i == 0 { d.sup() } else { d.sup().max(0.0) };
        form -= Interval::point(d);
    }
    (Interval::point(0.5) * (form - lost)).inf()
}

/// A matrix `S = Qm + diag(d)` (row-major) proved positive semidefinite by an interval Cholesky
/// factorisation, with `d` from subgradient steps minimising `d_0 + Σ_{i>0} max(d_i, 0)` (see the
/// module documentation). `None` if the proof fails.
fn psd_shift(qm: &[f64], dim: usize) -> Option<Vec<f64>> {
    use nalgebra::DMatrix;
    const STEPS: usize = 600;
    let base = DMatrix::from_row_slice(dim, dim, qm);
    let scale = qm.iter().map(|v| v.abs()).sum::<f64>() / dim as f64;
    if scale == 0.0 || !scale.is_finite() {
        return Some(qm.to_vec());
    }
    // A margin on the smallest eigenvalue, so that the rounding of the Cholesky proof has room.
    let margin = 1e-9 * scale;
    let cost = |d: &[f64]| d[0] + d[1..].iter().map(|v| v.max(0.0)).sum::<f64>();
    let mut d = vec![0.0; dim];
    let mut best: Option<(f64, Vec<f64>)> = None;
    for step in 0..STEPS {
        let mut s = base.clone();
        for i in 0..dim {
            s[(i, i)] += d[i];
        }
        let e = s.symmetric_eigen();
        let (lowest, lambda) =
            e.eigenvalues
                .iter()
                .enumerate()
                .fold(
                    (0, f64::INFINITY),
                    |acc, (i, &v)| if v < acc.1 { (i, v) } else { acc },
                );
        // Shifted up to the margin: a feasible candidate.
        let candidate: Vec<f64> = d.iter().map(|v| v - lambda + margin).collect();
        let value = cost(&candidate);
        if best.as_ref().is_none_or(|(b, _)| value < *b) {
            best = Some((value, candidate));
        }
        let v = e.eigenvectors.column(lowest);
        let rate = 0.02 * scale / (1.0 + step as f64).sqrt();
        for i in 0..dim {
            d[i] -= rate * (1.0 - dim as f64 * v[i] * v[i]);
        }
    }
    let (_, d) = best?;
    let mut s = qm.to_vec();
    for i in 0..dim {
        s[i * dim + i] += d[i];
    }
    is_positive_definite(&s, dim).then_some(s)
}

/// Whether the symmetric matrix `s` (row-major) is positive definite, proved by a Cholesky
/// factorisation in interval arithmetic: every pivot's enclosure positive means the exact
/// factorisation exists. `false` proves nothing.
pub(crate) fn is_positive_definite(s: &[f64], dim: usize) -> bool {
    let mut l = vec![Interval::ZERO; dim * dim];
    for j in 0..dim {
        let mut pivot = Interval::point(s[j * dim + j]);
        for k in 0..j {
            pivot -= l[j * dim + k].sqr();
        }
        // A NaN pivot fails too.
        if pivot.inf().partial_cmp(&0.0) != Some(core::cmp::Ordering::Greater) {
            return false;
        }
        let root = pivot.sqrt();
        l[j * dim + j] = root;
        for i in j + 1..dim {
            let mut v = Interval::point(s[i * dim + j]);
            for k in 0..j {
                v -= l[i * dim + k] * l[j * dim + k];
            }
            l[i * dim + j] = v / root;
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    /// `½ δᵀ H δ` at sampled `δ` (corners among them) and `H` in the intervals never falls below
    /// the bound, and the bound of a positive semidefinite form over a box around 0 is near 0.
    #[test]
    fn quadratic_bounds_hold_at_sampled_points() {
        let mut rng = StdRng::seed_from_u64(7);
        for trial in 0..200 {
            let n = rng.random_range(1..7);
            let mut mid = vec![0.0; n * n];
            let mut rad = vec![0.0; n * n];
            for a in 0..n {
                for b in a..n {
                    mid[a * n + b] = rng.random_range(-1.0..1.0);
                    mid[b * n + a] = mid[a * n + b];
                    rad[a * n + b] = rng.random_range(0.0..0.05);
                    rad[b * n + a] = rad[a * n + b];
                }
            }
            let h: Vec<Interval> = (0..n * n)
                .map(|k| Interval::mid_rad(mid[k], rad[k]))
                .collect();
            let delta: Vec<Interval> = (0..n)
                .map(|_| {
                    let a = rng.random_range(-2.0..0.5);
                    Interval::new(a, a + rng.random_range(0.0..2.0))
                })
                .collect();
            let bound = half_quadratic_lower_bound(&h, &delta);
            assert!(bound.is_finite(), "trial {trial}: no bound");
            for sample in 0..400 {
                let d: Vec<f64> = delta
                    .iter()
                    .map(|v| {
                        if sample % 2 == 0 {
                            if rng.random_bool(0.5) {
                                v.inf()
                            } else {
                                v.sup()
                            }
                        } else {
                            rng.random_range(v.inf()..=v.sup())
                        }
                    })
                    .collect();
                let mut value = 0.0;
                for a in 0..n {
                    for b in a..n {
                        let e = mid[a * n + b] + rng.random_range(-1.0..=1.0) * rad[a * n + b];
                        value += if a == b { e } else { 2.0 * e } * d[a] * d[b];
                    }
                }
                assert!(
                    0.5 * value >= bound - 1e-12,
                    "trial {trial}: ½ δᵀHδ = {} below the bound {bound}",
                    0.5 * value
                );
            }
        }
    }

    #[test]
    fn a_positive_definite_form_over_a_centred_box_loses_nothing() {
        // H = [[2, 1], [1, 2]] (eigenvalues 1 and 3) over [-1, 1]²: the minimum 0 at δ = 0.
        let h: Vec<Interval> = [2.0, 1.0, 1.0, 2.0].map(Interval::point).to_vec();
        let delta = vec![Interval::new(-1.0, 1.0); 2];
        let bound = half_quadratic_lower_bound(&h, &delta);
        assert!((-1e-6..=0.0).contains(&bound), "{bound}");
        // The indefinite [[1, 2], [2, 1]]: minimum ½ (1 + 1 − 4) = −1 at (1, −1).
        let h: Vec<Interval> = [1.0, 2.0, 2.0, 1.0].map(Interval::point).to_vec();
        let bound = half_quadratic_lower_bound(&h, &delta);
        assert!((-1.01..=-1.0).contains(&bound), "{bound}");
    }

    #[test]
    fn cholesky_proofs_accept_definite_and_refuse_indefinite_matrices() {
        assert!(is_positive_definite(&[4.0, 1.0, 1.0, 3.0], 2));
        assert!(!is_positive_definite(&[1.0, 2.0, 2.0, 1.0], 2));
        // Singular: not provably definite.
        assert!(!is_positive_definite(&[1.0, 1.0, 1.0, 1.0], 2));
    }
}
