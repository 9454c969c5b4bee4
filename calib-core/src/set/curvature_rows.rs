//! Second-order Taylor rows for a certified set's pieces: a tighter outer description where the
//! piece's box is wide and the model curved.
//!
//! # Why
//!
//! A piece's polyhedron comes from the Newton step's relaxation over its box (affine forms, or
//! the interval Jacobian): each row's slack holds the model's nonlinearity over the whole box, of
//! first order in the box's width times its width, with the remainders of every operation added
//! up. For a long chain whose prior leaves most parameters undetermined (a real arm's 25 of 27),
//! that slack is a large share of each row's width, and every linear program over the set —
//! each accuracy and prediction bound — inherits it.
//!
//! # The rows
//!
//! With `z = (x, M)`, the piece's centre `c`, the measurement box's midpoint `M̂`, `y = x - c`,
//! `ΔM = M - M̂`, Taylor's theorem with the Lagrange remainder gives, for every `x` in the box `X`
//! and `M` in the measurement box,
//!
//! `f_r(x, M) = f_r(c, M̂) + ∇_x f_r·y + ∇_M f_r·ΔM + ½ Δzᵀ H_r(ξ) Δz`, `ξ ∈ X × M`,
//!
//! the derivatives at `(c, M̂)`. The Hessian over the box is enclosed as `H(c, M̂) + T` with `T ⊇
//! Σ_c ∂³f/∂z_a∂z_b∂z_c (η) (z_c - z0_c)` ([`Curvature::third_derivatives_along`]), and the
//! quadratic form in interval arithmetic (`Δz_a²` for the diagonal). Writing `∇_x f_r =
//! g + [-ρ, ρ]` with `g` the midpoints, every constant part is collected in an interval `C_r`:
//!
//! `C_r = f_r(c, M̂) + Σ_i ∂f_r/∂M_i ΔM_i + Σ_j (∇_x f_r - g)_j y_j + ½ Δzᵀ (H + T) Δz`,
//!
//! so a consistent `x` (some `M` in the box with `f(x, M) = 0`) satisfies `0 ∈ g·y + C_r`:
//! `g·y <= -inf C_r` and `-g·y <= sup C_r`. Every number is enclosed with outward rounding; the
//! rows hold on the whole box, so adding them to the polyhedron keeps every solution. What they
//! take back on a real arm's calibration is in `benches/README.md`.

use crate::lp::Polyhedron;
use crate::model::curvature::{Curvature, MAX_CURVATURE_SYMBOLS};
use crate::{Interval, VectorModel};

/// A robot's own enclosure of its residual rows' Hessians over boxes of parameters and
/// measured quantities: per row, the `n × n` enclosures (row-major) of `∂²f_r/∂z_a∂z_b` over the
/// boxes for the `n` symbols given (`j < NX` parameter `j`, `NX + i` measured quantity `i`), or
/// `None`.
pub type HessianOverBox<const NX: usize, const NM: usize> =
    dyn Fn(&[Interval; NX], &[Interval; NM], &[usize]) -> Option<Vec<Interval>> + Sync;

/// Where a row's Hessian over the box comes from.
#[derive(Clone, Copy)]
pub(crate) enum Hessians<'a, const NX: usize, const NM: usize, const NR: usize> {
    /// The model's derivatives (`#[interval_model(curvature)]`): at the centre, plus the
    /// third-order change over the box.
    Curvature(&'a dyn Curvature<NX, NM, NR>),
    /// The robot's own enclosure over the box.
    OverBox(&'a HessianOverBox<NX, NM>),
}

impl<const NX: usize, const NM: usize, const NR: usize> Hessians<'_, NX, NM, NR> {
    /// Whether symbol `s` can curve a row (only the model's derivatives know it is not).
    fn curved(&self, s: usize) -> bool {
        match self {
            Hessians::Curvature(c) => c.curved(s),
            Hessians::OverBox(_) => true,
        }
    }

    /// Per row, the `n × n` enclosures of the Hessian over the boxes `x`, `m` (about `centre`,
    /// `m_mid` for the model's derivatives).
    fn over(
        &self,
        x: &[Interval; NX],
        m: &[Interval; NM],
        centre: &[f64; NX],
        m_mid: &[f64; NM],
        symbols: &[usize],
    ) -> Option<Vec<Interval>> {
        match self {
            Hessians::Curvature(c) => {
                let h0 = c.second_derivatives(centre, m_mid, symbols)?;
                let t = c.third_derivatives_along(x, m, centre, m_mid, symbols)?;
                (h0.len() == t.len()).then(|| h0.iter().zip(&t).map(|(a, b)| *a + *b).collect())
            }
            Hessians::OverBox(h) => h(x, m, symbols),
        }
    }
}

/// `poly` (the relaxation's rows over the box `x`, in `y = x - centre`) with the second-order
/// Taylor rows (module documentation) of `model` against `measurements` added: each
/// measurement's rows open its group (group `k` for measurement `k`), so that they are the
/// configuration's own rows ([`crate::CertifiedSet::query_own_rows`]), before the group's earlier
/// rows, which all stay. A measurement with more than [`MAX_CURVATURE_SYMBOLS`] symbols of
/// nonzero width, or whose enclosures fail, adds no rows.
pub(crate) fn with_curvature_rows<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    hessians: Hessians<'_, NX, NM, NR>,
    x: &[Interval; NX],
    centre: &[f64; NX],
    measurements: &[[Interval; NM]],
    poly: &Polyhedron,
) -> Polyhedron
where
    M: VectorModel<NX, NM, NR> + Sync,
{
    use rayon::prelude::*;
    let taylor: Vec<Vec<([f64; NX], f64, f64)>> = measurements
        .par_iter()
        .map(|m| taylor_rows(model, hessians, x, centre, m).unwrap_or_default())
        .collect();
    let mut out = Polyhedron::default();
    out.reset(poly.lo(), poly.hi());
    for j in 0..poly.dim() {
        if poly.is_frozen(j) {
            out.freeze(j, poly.lo()[j].abs().max(poly.hi()[j].abs()));
        }
    }
    // Groups in increasing order: measurement k's Taylor rows open group k, then the old rows
    // of that group; groups beyond the old rows' last get their Taylor rows alone.
    let mut next = 0usize;
    let open = |out: &mut Polyhedron, upto: usize, next: &mut usize| {
        while *next <= upto && *next < taylor.len() {
            out.begin_group(group(*next));
            for (g, lo, hi) in &taylor[*next] {
                // g·y <= -inf C and -g·y <= sup C.
                out.push_row(g, -lo);
                out.push_row(&g.map(|v| -v), *hi);
            }
            *next += 1;
        }
    };
    let mut current = None;
    for i in 0..poly.rows() {
        let g = (poly.tag(i) >> 32) as usize;
        if current != Some(g) {
            open(&mut out, g, &mut next);
            if next <= g {
                out.begin_group(group(g));
            }
            current = Some(g);
        }
        out.push_row(poly.row(i), poly.rhs(i));
    }
    open(&mut out, usize::MAX, &mut next);
    out
}

/// The group tag of measurement `k`.
fn group(k: usize) -> u32 {
    u32::try_from(k).unwrap_or(u32::MAX)
}

/// Per residual row, `(g, inf C, sup C)` (module documentation) for the measurement box `m`,
/// `None` where an enclosure failed or there are too many symbols.
#[allow(clippy::type_complexity)]
fn taylor_rows<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    hessians: Hessians<'_, NX, NM, NR>,
    x: &[Interval; NX],
    centre: &[f64; NX],
    m: &[Interval; NM],
) -> Option<Vec<([f64; NX], f64, f64)>>
where
    M: VectorModel<NX, NM, NR>,
{
    let m_mid = m.map(|v| v.mid());
    // The symbols: parameters and measured quantities of nonzero width that curve a row.
    let symbols: Vec<usize> = (0..NX)
        .filter(|&j| x[j].wid() > 0.0)
        .chain((0..NM).filter(|&i| m[i].wid() > 0.0).map(|i| NX + i))
        .filter(|&s| hessians.curved(s))
        .collect();
    if symbols.len() > MAX_CURVATURE_SYMBOLS {
        return None;
    }
    let at_centre =
        model.evaluate_rows_interval(&centre.map(Interval::point), &m_mid.map(Interval::point));
    let n = symbols.len();
    let h = if n == 0 {
        Vec::new()
    } else {
        hessians.over(x, m, centre, &m_mid, &symbols)?
    };
    if h.len() != NR * n * n {
        return None;
    }
    let dz: Vec<Interval> = symbols
        .iter()
        .map(|&s| {
            if s < NX {
                x[s] - Interval::point(centre[s])
            } else {
                m[s - NX] - Interval::point(m_mid[s - NX])
            }
        })
        .collect();
    let half = Interval::point(0.5);
    let mut out = Vec::with_capacity(NR);
    for (r, e) in at_centre.iter().enumerate() {
        // ½ Δzᵀ H Δz.
        let mut q = Interval::ZERO;
        for a in 0..n {
            for b in 0..n {
                let hab = h[r * n * n + a * n + b];
                q += if a == b {
                    hab * dz[a].sqr()
                } else {
                    hab * dz[a] * dz[b]
                };
            }
        }
        let mut c = e.value + q * half;
        for i in 0..NM {
            if m[i].wid() > 0.0 {
                c += e.dm[i] * (m[i] - Interval::point(m_mid[i]));
            }
        }
        let mut g = [0.0; NX];
        for j in 0..NX {
            g[j] = e.dx[j].mid();
            let y = x[j] - Interval::point(centre[j]);
            c += (e.dx[j] - Interval::point(g[j])) * y;
        }
        if !(c.is_bounded() && !c.is_empty() && g.iter().all(|v| v.is_finite())) {
            return None;
        }
        out.push((g, c.inf(), c.sup()));
    }
    Some(out)
}
