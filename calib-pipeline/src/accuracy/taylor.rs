//! A prediction's curvature in `θ` from its second and third derivatives: the Taylor remainder the
//! engine takes when the prediction's model has them (`#[interval_model(curvature)]`) and the
//! robot supplies no enclosure of its own ([`Prediction::curvature`](super::Prediction::curvature)).
//!
//! For `δ = θ - θ̂` in `spread` and inputs `u` in a box, Taylor's theorem in `θ` gives
//!
//! `g_r(u; θ) - g_r(u; θ̂) - ∇_θ g_r(u; θ̂)·δ = ½ δᵀ H_r(θ̂ + tδ, u) δ`, `t ∈ [0, 1]`,
//!
//! with `H_r` the Hessian in `θ`. Over the box `(θ̂ + spread) × u` it is enclosed as `H_r(θ̂, û) +
//! T_r`, `T_r ⊇ Σ_c ∂³g_r/∂θ_a∂θ_b∂z_c (η) (z_c - z0_c)` ([`Curvature::third_derivatives_along`]),
//! and the quadratic form in interval arithmetic (`δ_a²` on the diagonal): about half the term
//! the interval slopes over the set's box imply (the mean-value form counts `∇g`'s whole
//! variation against the whole spread), and exact in its cross terms' signs.

use calib_core::{Curvature, Interval};

/// The Taylor remainder's enclosure per coordinate (module documentation) of `model` about
/// `nominal` over `spread` (intervals holding `θ - θ̂` over the set, widened to hold 0) and the
/// measurement slot's box `m` (the inputs, then zeros). `None` with more symbols of nonzero width than
/// [`calib_core::MAX_CURVATURE_SYMBOLS`], or when an enclosure failed.
pub fn taylor_remainder<const NX: usize, const NP: usize, const R: usize>(
    model: &dyn Curvature<NX, NP, R>,
    nominal: &[f64; NX],
    spread: &[Interval; NX],
    m: &[Interval; NP],
) -> Option<[Interval; R]> {
    // Taylor's segment from θ̂ must lie in the box the derivatives are enclosed over.
    let spread = spread.map(|v| v.hull(Interval::ZERO));
    let params: Vec<usize> = (0..NX)
        .filter(|&j| spread[j].mag() > 0.0 && model.curved(j))
        .collect();
    if params.is_empty() {
        return Some([Interval::ZERO; R]);
    }
    let inputs = (0..NP).filter(|&i| m[i].wid() > 0.0).map(|i| NX + i);
    let symbols: Vec<usize> = params.iter().copied().chain(inputs).collect();
    let m_mid = m.map(|v| v.mid());
    let hull: [Interval; NX] = core::array::from_fn(|j| Interval::point(nominal[j]) + spread[j]);
    let h0 = model.second_derivatives(nominal, &m_mid, &symbols)?;
    let t = model.third_derivatives_along(&hull, m, nominal, &m_mid, &symbols)?;
    let (n, p) = (symbols.len(), params.len());
    let half = Interval::point(0.5);
    let out: [Interval; R] = core::array::from_fn(|r| {
        let mut q = Interval::ZERO;
        for a in 0..p {
            for b in 0..p {
                let k = r * n * n + a * n + b;
                let h = h0[k] + t[k];
                let (da, db) = (spread[params[a]], spread[params[b]]);
                q += if a == b { h * da.sqr() } else { h * da * db };
            }
        }
        q * half
    });
    out.iter()
        .all(|v| v.is_bounded() && !v.is_empty())
        .then_some(out)
}
