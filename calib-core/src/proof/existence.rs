//! Proving that one configuration of a vector model is fitted: for every `x` in a box (a point when
//! the box is degenerate) there is **one** reading `M ∈ M_k` with `f(x, M) = 0` in all `NR` rows.
//!
//! For `NR = 1` the sign test of [`crate::proof::consistency`] suffices. For `NR >= 2` the proof is
//! a parametric Krawczyk test on a square sub-system in the measurement variables:
//!
//! 1. A *hint*: the reading `M̂` of `M_k` closest to the centre of `M_k` (in the norm scaled by the
//!    half-widths) that fits the rows at `x̂ = mid(x)`, by successive linear programs
//!    `min t  s.t.  f(x̂, M) + ∂f/∂M·δ = 0,  |M + δ - mid M_k| <= t · rad(M_k)`. Floating point,
//!    a hint only.
//! 2. A square sub-system: `NR` of the `NM` measured quantities, `S`, chosen by column pivoting on
//!    `∂f/∂M_S` scaled by the room each quantity has left inside its interval; the others are
//!    fixed at their hint values (points of `M_k`, so the reading stays in the box).
//! 3. Krawczyk: with `g(y) = f(x, y, M̂_rest)`, `ŷ = M̂_S`, `C ≈ (∂g/∂y (x̂, ŷ))⁻¹` and a box
//!    `Y ∋ ŷ`, `Y ⊆ M_S`,
//!    `K = ŷ - C g(x, ŷ) + (I - C ∂g/∂y (x, Y)) (Y - ŷ)`
//!    is evaluated in interval arithmetic over the whole box `x`. If `K ⊂ int Y`, then for every
//!    `x` in the box `g(x, ·)` has exactly one zero in `Y` (Krawczyk's theorem; the strict
//!    inclusion also proves `C` and every matrix of `∂g/∂y (x, Y)` regular). That zero together
//!    with `M̂_rest` is a reading of `M_k` at which all `NR` rows vanish: the configuration is
//!    fitted with one reading, not one per row. `Y` starts as `ŷ ± 2|C g|` and is inflated a few
//!    times (ε-inflation), always inside `M_S`.
//!
//! A failed test proves nothing and certifies nothing: the point is simply not used as a witness
//! or an inner point.

use crate::lp::{DenseSimplex, LpBackend, LpStatus, Polyhedron};
use crate::num::linalg::gauss_jordan_inverse;
use crate::{Interval, VectorModel};

/// Whether every `x` in the bounded box `x` fits the bounded measurement box `m` with one reading
/// (see the module documentation).
pub(crate) fn configuration_fits<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    m: &[Interval; NM],
) -> bool
where
    M: VectorModel<NX, NM, NR>,
{
    let xm = x.map(|v| v.mid());
    let Some(mut hint) = closest_reading(model, &xm, m) else {
        return false;
    };
    let room: [f64; NM] =
        core::array::from_fn(|i| (hint[i] - m[i].inf()).min(m[i].sup() - hint[i]).max(0.0));
    let jm = model.jacobians_m(&xm, &hint);
    let Some(s) = square_subsystem(&jm, &room) else {
        return false;
    };
    let mut c = vec![0.0; NR * NR];
    if !polish(model, &xm, m, &s, &mut hint, &mut c) {
        return false;
    }
    krawczyk(model, x, m, &s, &hint, &c)
}

/// The hint of step 1: a reading of `m` that fits every row at the point `x`, as close to the
/// centre of `m` as successive LPs find (where an LP fails, the reading reached before it: the
/// centre at worst); `None` when `m` is unbounded.
fn closest_reading<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[f64; NX],
    m: &[Interval; NM],
) -> Option<[f64; NM]>
where
    M: VectorModel<NX, NM, NR>,
{
    let centre = m.map(|v| v.mid());
    // The LP's unknowns are the steps in units of each quantity's half-width (`δ_i = r_i z_i`):
    // joint readings in radians and points in mm differ by four orders of magnitude, on which the
    // unscaled dense simplex reported feasible LPs infeasible.
    let unit: [f64; NM] = core::array::from_fn(|i| {
        let r = m[i].rad();
        if r > 0.0 {
            r
        } else {
            1.0
        }
    });
    let mut reading = centre;
    let mut poly = Polyhedron::default();
    let mut lp = DenseSimplex::default();
    let n = NM + 1;
    let mut objective = vec![0.0; n];
    objective[NM] = 1.0;
    let mut dual = vec![0.0; 2 * (NR + NM)];
    let mut primal = vec![0.0; n];
    let mut row = vec![0.0; n];
    let mut lo = vec![0.0; n];
    let mut hi = vec![0.0; n];
    for _ in 0..8 {
        let (values, jm) = model.residuals_and_jacobians_m(x, &reading);
        let scale = values.iter().map(|v| v.abs()).fold(0.0, f64::max);
        for i in 0..NM {
            lo[i] = (m[i].inf() - reading[i]) / unit[i];
            hi[i] = (m[i].sup() - reading[i]) / unit[i];
        }
        // t: the scaled distance from the centre, at most 2 (beyond, the reading is lost anyway).
        lo[NM] = 0.0;
        hi[NM] = 2.0;
        if lo
            .iter()
            .zip(&hi)
            .any(|(l, h)| l > h || !l.is_finite() || !h.is_finite())
        {
            return None;
        }
        poly.reset(&lo, &hi);
        for (value, dm) in values.iter().zip(&jm) {
            // f + J δ = 0, as two inequalities, in the scaled unknowns and divided by the row's
            // largest coefficient.
            for i in 0..NM {
                row[i] = dm[i] * unit[i];
            }
            row[NM] = 0.0;
            let norm = row.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            if !(norm > 0.0 && norm.is_finite()) {
                return Some(reading);
            }
            row.iter_mut().for_each(|v| *v /= norm);
            poly.push_row(&row, -value / norm);
            row.iter_mut().for_each(|v| *v = -*v);
            poly.push_row(&row, *value / norm);
        }
        for i in 0..NM {
            if m[i].rad() > 0.0 {
                // |reading + δ - centre| <= t rad, i.e. |z + (reading - centre) / rad| <= t
                let offset = (reading[i] - centre[i]) / unit[i];
                row.iter_mut().for_each(|v| *v = 0.0);
                row[i] = 1.0;
                row[NM] = -1.0;
                poly.push_row(&row, -offset);
                row[i] = -1.0;
                poly.push_row(&row, offset);
            }
        }
        dual.resize(poly.rows(), 0.0);
        if lp.minimize(&poly, &objective, &mut dual, &mut primal) != LpStatus::Optimal {
            // A hint only: the reading reached so far (a point of `m`) is still the best start
            // for the Newton steps and the proof.
            break;
        }
        let mut step = 0.0f64;
        for i in 0..NM {
            let next = (reading[i] + unit[i] * primal[i]).clamp(m[i].inf(), m[i].sup());
            step = step.max((next - reading[i]).abs() / (m[i].rad() + f64::MIN_POSITIVE));
            reading[i] = next;
        }
        if scale == 0.0 || step < 1e-6 {
            break;
        }
    }
    Some(reading)
}

/// Step 2: `NR` measured quantities whose columns of `∂f/∂M`, scaled by the room left inside
/// their intervals, are the best conditioned (greedy column pivoting); `None` when the scaled
/// columns do not span `NR` dimensions.
fn square_subsystem<const NM: usize, const NR: usize>(
    jm: &[[f64; NM]; NR],
    room: &[f64; NM],
) -> Option<[usize; NR]> {
    let mut cols: [[f64; NR]; NM] =
        core::array::from_fn(|i| core::array::from_fn(|r| jm[r][i] * room[i]));
    let mut chosen = [usize::MAX; NR];
    let norm2 = |c: &[f64; NR]| c.iter().map(|v| v * v).sum::<f64>();
    let first = cols.iter().map(norm2).fold(0.0, f64::max);
    if first <= 0.0 || !first.is_finite() {
        return None;
    }
    for k in 0..NR {
        let (best, n2) = (0..NM)
            .filter(|i| !chosen.contains(i))
            .map(|i| (i, norm2(&cols[i])))
            .max_by(|a, b| a.1.total_cmp(&b.1))?;
        if n2.is_nan() || n2 <= 1e-20 * first {
            return None;
        }
        chosen[k] = best;
        let pivot = cols[best];
        for c in cols.iter_mut() {
            let d: f64 = c.iter().zip(&pivot).map(|(a, b)| a * b).sum::<f64>() / n2;
            for r in 0..NR {
                c[r] -= d * pivot[r];
            }
        }
    }
    chosen.sort_unstable();
    Some(chosen)
}

/// Newton steps on the square sub-system at the point `x` (the hint moves only in `S`, within
/// `m`), then `c = (∂f/∂M_S)⁻¹` at the polished hint (row-major). False when it is singular.
fn polish<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[f64; NX],
    m: &[Interval; NM],
    s: &[usize; NR],
    hint: &mut [f64; NM],
    c: &mut [f64],
) -> bool
where
    M: VectorModel<NX, NM, NR>,
{
    let mut a = vec![0.0; NR * NR];
    for step in 0..4 {
        let (values, jm) = model.residuals_and_jacobians_m(x, hint);
        for r in 0..NR {
            for (k, &i) in s.iter().enumerate() {
                a[r * NR + k] = jm[r][i];
            }
        }
        if !gauss_jordan_inverse(NR, &mut a, c) {
            return false;
        }
        if step == 3 {
            break;
        }
        for (k, &i) in s.iter().enumerate() {
            let d: f64 = (0..NR).map(|r| c[k * NR + r] * values[r]).sum();
            hint[i] = (hint[i] - d).clamp(m[i].inf(), m[i].sup());
        }
    }
    true
}

/// Step 3: the Krawczyk test with ε-inflation.
fn krawczyk<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    m: &[Interval; NM],
    s: &[usize; NR],
    hint: &[f64; NM],
    c: &[f64],
) -> bool
where
    M: VectorModel<NX, NM, NR>,
{
    let at_hint = hint.map(Interval::point);
    let g = model.residuals_interval(x, &at_hint);
    let ci = |k: usize, r: usize| Interval::point(c[k * NR + r]);
    // z = -C g(x, ŷ)
    let z: [Interval; NR] =
        core::array::from_fn(|k| -(0..NR).fold(Interval::ZERO, |acc, r| acc + ci(k, r) * g[r]));
    let centre: [f64; NR] = core::array::from_fn(|k| hint[s[k]]);
    let within = |k: usize, lo: f64, hi: f64| {
        let b = m[s[k]];
        Interval::new(lo.max(b.inf()), hi.min(b.sup()))
    };
    let mut y: [Interval; NR] = core::array::from_fn(|k| {
        let r = 2.0 * z[k].mag() + 1e-12 * (centre[k].abs() + m[s[k]].rad());
        within(k, centre[k] - r, centre[k] + r)
    });
    for _ in 0..8 {
        let mut reading = at_hint;
        for k in 0..NR {
            reading[s[k]] = y[k];
        }
        let jac = model.jacobians_m_interval(x, &reading);
        let mut kbox = [Interval::ZERO; NR];
        for k in 0..NR {
            let mut acc = Interval::point(centre[k]) + z[k];
            for l in 0..NR {
                // (I - C J)_{kl}
                let cj = (0..NR).fold(Interval::ZERO, |a, r| a + ci(k, r) * jac[r][s[l]]);
                let identity = if k == l {
                    Interval::ONE
                } else {
                    Interval::ZERO
                };
                acc += (identity - cj) * (y[l] - Interval::point(centre[l]));
            }
            kbox[k] = acc;
        }
        if (0..NR).all(|k| kbox[k].inf() > y[k].inf() && kbox[k].sup() < y[k].sup()) {
            return true;
        }
        if kbox.iter().any(|v| !v.is_bounded()) {
            return false;
        }
        let next: [Interval; NR] = core::array::from_fn(|k| {
            let reach = (kbox[k].inf() - centre[k])
                .abs()
                .max((kbox[k].sup() - centre[k]).abs());
            let r = 1.5 * reach + 1e-12 * (centre[k].abs() + m[s[k]].rad());
            within(k, centre[k] - r, centre[k] + r)
        });
        if next == y {
            return false;
        }
        y = next;
    }
    false
}
