//! The interval Newton / Krawczyk–LP contraction and its fixed-point iteration (paper Section IV).
//!
//! One step, for a box `x` and measurement boxes `M_1..M_p`, with `y = x - xm`, `xm = mid(x)`:
//!
//! 1. Cheap rejection: if `0 ∉ f(x, M_k)` (natural interval evaluation) for some `k`, no parameter
//!    vector in `x` fits measurement `k`: the box is empty.
//! 2. Rows of a polyhedron containing every solution in `x` ([`Relaxation`]):
//!    * Krawczyk (paper eqs. 6–7 and Section IV-B): with `A_k = ∂f/∂x (x, M_k)`,
//!      `b_k ⊇ -f(xm, M)` over `M_k` (the centred form `f(xm, mid M_k) + B_k (M_k - mid M_k)`,
//!      with `B_k = ∂f/∂M (x, M_k)` from the same evaluation as `A_k`; the paper takes it at
//!      `(xm, M_k)`, a subset, which costs one more evaluation per row) and `Am = mid(A_k)`:
//!      `inf(c_k) <= Am·y <= sup(c_k)` with `c_k = b_k - (A_k - Am)·(x - xm)`.
//!    * Corners: for the corner `v = inf(x)` and every solution `x`,
//!      `0 = f(v, M) + A'(x - v)` with `A' ∈ A_k` and `x - v >= 0`, hence
//!      `Σ inf(A_kj)(x_j - v_j) <= -inf f(v, M_k)` and `-Σ sup(A_kj)(x_j - v_j) <= sup f(v, M_k)`;
//!      symmetrically at `v = sup(x)`.
//!
//!    * Affine forms, for models that provide them ([`VectorModel::linear_enclosures`]): each
//!      residual (and each coupling combination) satisfies `|c + Σ gx_j ε_j| <= Σ |gm_i| + e` at
//!      every solution, with `ε_j = y_j / rad(x_j)`. These rows then replace the two above: over a
//!      long kinematic chain the interval Jacobian overestimates 14-41x where the affine form
//!      overestimates ~2x, and the LPs get 3-4x fewer rows.
//!
//!    Right-hand sides are rounded outward, so every row holds exactly for every solution.
//! 3. 2n linear programs: min and max of each `y_j` over the polyhedron; each LP answer is turned
//!    into a rigorous bound by [`crate::lp::safe_lower_bound`], and the box is intersected with it
//!    at once (eq. 8). An empty intersection, or a checked Farkas certificate, proves emptiness.
//!
//! The step is repeated until `‖rad(x_j)‖₁ - ‖rad(x_{j+1})‖₁ < Δ` or the iteration cap. Nothing is
//! lost: every step keeps all solutions of the box it started from (paper Section IV-A).

use crate::lp::{proves_infeasible, safe_lower_bound, LpBackend, LpMemory, LpStatus, Polyhedron};
use crate::model::coupling::{coupling_directions, Directions};
use crate::num::affine::rounding;
use crate::num::interval::round::{add_up, mul_up};
use crate::{Interval, LinearEnclosure, Relaxation, Settings, VectorModel};

/// Which test proved a box empty.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EmptinessProof {
    /// `0 ∉ f(x, M_k)`: measurement `k` (0-based) fits no parameter vector of the box.
    CheapRejection {
        /// The measurement.
        measurement: usize,
    },
    /// A Farkas certificate of the LP polyhedron, checked in interval arithmetic.
    LpInfeasible,
    /// The rigorous LP bounds of a parameter crossed (its new interval is empty).
    EmptyIntersection {
        /// The parameter (0-based).
        parameter: usize,
    },
    /// A weighted sum of the residuals (the Chebyshev fit's LP multipliers) proved positive over
    /// the contracted box by a second-order Taylor bound ([`crate::second_order_emptiness`]), where
    /// the linear relaxation was too loose to decide.
    SecondOrder,
    /// Every piece of a subdivision of the box was proved empty by one of the tests above
    /// ([`crate::hull`]).
    Subdivision,
    /// With `q` outliers tolerated: every choice of `q` dropped measurements leaves a set that was
    /// proved empty by one of the tests above.
    EverySubset,
}

/// Reusable buffers for contractions: after the first contraction of a given problem size, a
/// contraction performs no heap allocation.
pub struct Workspace<const NX: usize> {
    pub(crate) poly: Polyhedron,
    lp: Box<dyn LpBackend>,
    dual: Vec<f64>,
    objective: [f64; NX],
    zeros: [f64; NX],
    primal: [f64; NX],
    /// Primal LP points (in `x` coordinates) at the minimum and maximum of each parameter from the
    /// last step: `extreme_points[2j]` for the minimum of `x_j`, `[2j + 1]` for the maximum.
    pub(crate) extreme_points: Vec<[f64; NX]>,
    /// The optimal LP points of the current step (shifted coordinates), to skip the LPs whose
    /// bound one of them already attains.
    optima: Vec<[f64; NX]>,
    /// LP solves and LP failures since creation (for reports).
    pub lp_solves: usize,
    /// LPs skipped since creation because a point of the same step already attained their bound.
    pub lp_skipped: usize,
    /// LP solves that failed or whose Farkas ray did not check (the bound stayed where it was or
    /// came from the partial multipliers).
    pub lp_failures: usize,
}

impl<const NX: usize> Workspace<NX> {
    /// A workspace using the LP engine of `settings`.
    pub fn new(settings: &Settings) -> Self {
        Workspace::with_backend(settings.lp.backend())
    }

    /// A workspace using a caller-provided LP engine (any engine is safe: its answers only decide
    /// how tight the rigorous bounds are).
    pub fn with_backend(lp: Box<dyn LpBackend>) -> Self {
        Workspace {
            poly: Polyhedron::default(),
            lp,
            dual: Vec::new(),
            objective: [0.0; NX],
            zeros: [0.0; NX],
            primal: [0.0; NX],
            extreme_points: vec![[0.0; NX]; 2 * NX],
            optima: Vec::with_capacity(2 * NX),
            lp_solves: 0,
            lp_skipped: 0,
            lp_failures: 0,
        }
    }

    /// Right after a contraction proved its box empty by [`EmptinessProof::LpInfeasible`]: the
    /// measurements (0-based, sorted) whose rows the checked Farkas ray weighs (the positive
    /// multipliers, the only rows the certificate uses; over the box the earlier steps contracted
    /// with every measurement). The ray and the rows are still the workspace's then; computed
    /// here, not in the contraction, which allocates nothing once warmed up.
    pub(crate) fn farkas_support(&self) -> Vec<usize> {
        let mut support: Vec<usize> = (0..self.poly.rows().min(self.dual.len()))
            .filter(|&i| self.dual[i] > 0.0 && self.dual[i].is_finite())
            // Rows are tagged by configuration, in increasing order (`build_relaxation`).
            .map(|i| (self.poly.tag(i) >> 32) as usize)
            .collect();
        support.dedup();
        support
    }

    /// The LP bases the last contraction ended with, to start another box's contraction from
    /// ([`contract_from`]).
    pub fn lp_memory(&self) -> LpMemory {
        self.lp.memory()
    }
}

/// The result of contracting one box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contraction<const NX: usize> {
    /// The contracted box, or the proof that it holds no solution.
    pub result: Result<[Interval; NX], EmptinessProof>,
    /// Newton/LP steps performed.
    pub iterations: usize,
}

/// `‖rad(x)‖₁`.
pub(crate) fn radius_sum<const NX: usize>(x: &[Interval; NX]) -> f64 {
    x.iter().map(|v| v.rad()).sum()
}

/// Contracts `x` to a fixed point (see the module documentation). The result contains every
/// solution in `x`; an `Err` is a proof that there is none.
pub fn contract<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
    settings: &Settings,
    ws: &mut Workspace<NX>,
) -> Contraction<NX>
where
    M: VectorModel<NX, NM, NR>,
{
    contract_from(model, x, measurements, settings, ws, &LpMemory::default())
}

/// [`contract`], with the LPs of the first step starting from `start` (the bases an earlier
/// contraction left, [`Workspace::lp_memory`]) instead of from scratch: the hull hands a box's
/// bases to its halves. The box is the same whatever `start` is, up to where the engine's
/// walks end (every bound is rigorous either way); it depends only on `start`, not on which
/// boxes the workspace contracted before.
pub fn contract_from<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
    settings: &Settings,
    ws: &mut Workspace<NX>,
    start: &LpMemory,
) -> Contraction<NX>
where
    M: VectorModel<NX, NM, NR>,
{
    let mut current = *x;
    let mut iterations = 0;
    // Each box's LPs warm-start only from `start` and this box's earlier steps: the result must
    // not depend on which boxes a worker thread contracted before.
    ws.lp.restore(start);
    if current.iter().any(|v| v.is_empty()) {
        return Contraction {
            result: Err(EmptinessProof::EmptyIntersection {
                parameter: current.iter().position(|v| v.is_empty()).unwrap_or(0),
            }),
            iterations,
        };
    }
    if !current.iter().all(|v| v.is_bounded()) {
        // The centred forms need a bounded box; an unbounded one is returned unchanged.
        return Contraction {
            result: Ok(current),
            iterations,
        };
    }
    while iterations < settings.max_iterations {
        iterations += 1;
        let before = radius_sum(&current);
        match newton_step(
            model,
            &current,
            measurements,
            settings.relaxation,
            iterations,
            ws,
        ) {
            Err(proof) => {
                return Contraction {
                    result: Err(proof),
                    iterations,
                }
            }
            Ok(next) => current = next,
        }
        if before - radius_sum(&current) < settings.delta {
            break;
        }
    }
    Contraction {
        result: Ok(current),
        iterations,
    }
}

/// `f(v, mid m) + B (m - mid m)`: the centred form of a residual over the measurement box `m`
/// (paper eq. 6), from its value at `(v, mid m)` and `B = ∂f/∂M (x, m)` computed over the whole box
/// (valid for any `v ∈ x` by the mean-value theorem in `M`).
fn centred_over_measurement<const NM: usize>(
    at_mid: Interval,
    m: &[Interval; NM],
    m_mid: &[Interval; NM],
    b: &[Interval; NM],
) -> Interval {
    let mut centred = at_mid;
    for i in 0..NM {
        centred += b[i] * (m[i] - m_mid[i]);
    }
    centred
}

/// The corner pair of iteration `i`: first the lowest/highest corners, then a fixed pseudo-random
/// sequence of opposite pairs, so that directions along which the parameters trade off against
/// each other are linearised too.
fn corner_mask(i: usize) -> u64 {
    if i <= 1 {
        return 0;
    }
    let mut z = (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z ^ (z >> 27)
}

/// One scalar equation `φ(x, M) = 0` of a configuration, as the relaxation needs it: `a ⊇ ∂φ/∂x`
/// over the box, and enclosures of `φ` over the measurement box at the box centre and at the two
/// corners (each only where the relaxation uses it).
struct ScalarRow<const NX: usize> {
    a: [Interval; NX],
    at_centre: Interval,
    at_corners: [Interval; 2],
}

/// The geometry of one Newton step: the centre, the box relative to it and the two corners.
struct StepFrame<const NX: usize> {
    relaxation: Relaxation,
    xm_iv: [Interval; NX],
    y_box: [Interval; NX],
    sides: [[bool; NX]; 2],
    corner_iv: [[Interval; NX]; 2],
    delta: [[Interval; NX]; 2],
}

impl<const NX: usize> StepFrame<NX> {
    fn new(x: &[Interval; NX], relaxation: Relaxation, iteration: usize) -> Self {
        let xm_iv: [Interval; NX] = core::array::from_fn(|j| Interval::point(x[j].mid()));
        // y = x - xm, enclosed by a float box.
        let y_box: [Interval; NX] = core::array::from_fn(|j| x[j] - xm_iv[j]);
        // Two opposite corners: bit j of `mask` puts the first corner at sup(x_j).
        let mask = corner_mask(iteration);
        let first: [bool; NX] = core::array::from_fn(|j| (mask >> (j % 64)) & 1 == 1);
        let sides = [first, first.map(|b| !b)];
        let corner_iv: [[Interval; NX]; 2] = core::array::from_fn(|c| {
            core::array::from_fn(|j| {
                Interval::point(if sides[c][j] { x[j].sup() } else { x[j].inf() })
            })
        });
        // delta_j = v_j - xm_j for each corner, enclosed.
        let delta = core::array::from_fn(|c| core::array::from_fn(|j| corner_iv[c][j] - xm_iv[j]));
        StepFrame {
            relaxation,
            xm_iv,
            y_box,
            sides,
            corner_iv,
            delta,
        }
    }

    fn krawczyk(&self) -> bool {
        matches!(self.relaxation, Relaxation::Krawczyk | Relaxation::Both)
    }

    fn corners(&self) -> bool {
        matches!(self.relaxation, Relaxation::Corners | Relaxation::Both)
    }

    /// Adds the rows of the relaxation of one scalar equation to the polyhedron.
    fn push_rows(&self, poly: &mut Polyhedron, row: &mut [f64; NX], eq: &ScalarRow<NX>) {
        let a = &eq.a;
        if self.krawczyk() {
            let mut c = -eq.at_centre;
            for j in 0..NX {
                row[j] = a[j].mid();
                c -= (a[j] - Interval::point(row[j])) * self.y_box[j];
            }
            poly.push_row(row, c.sup());
            row.iter_mut().for_each(|v| *v = -*v);
            poly.push_row(row, -c.inf());
        }
        if self.corners() {
            for corner in 0..2 {
                let fv = eq.at_corners[corner];
                // d_j = x_j - v_j is >= 0 where the corner is at inf(x_j), <= 0 where at sup(x_j).
                // The coefficient bounding A'_j d_j from below is then inf(A_j), resp. sup(A_j).
                let up = &self.sides[corner];
                let low = |j: usize| if up[j] { a[j].sup() } else { a[j].inf() };
                let high = |j: usize| if up[j] { a[j].inf() } else { a[j].sup() };
                // 0 >= inf f(v, M) + Σ low_j d_j
                push_shifted_row(poly, row, low, -fv.inf(), &self.delta[corner]);
                // 0 <= sup f(v, M) + Σ high_j d_j
                push_shifted_row(poly, row, |j| -high(j), fv.sup(), &self.delta[corner]);
            }
        }
    }
}

/// Whether a parameter is fixed: a point, or a sliver of a few ulps (a parameter fixed at a value
/// converted to other units, enclosed). The LPs freeze such parameters, the hull pushes no point
/// along them, and reports list them apart.
pub fn is_fixed(x: Interval) -> bool {
    x.wid() <= 1e-12 * x.mag().max(1.0)
}

/// One Newton/LP step. `Ok` holds a sub-box of `x` containing every solution in `x`.
///
/// Each configuration contributes the relaxation rows of each of its `NR` residuals and, for
/// `NR >= 2`, of the combinations `λ·f` along its coupling directions ([`crate::coupling`]), so
/// that the polyhedron encloses the coupled solution set, not only the decoupled one.
pub(crate) fn newton_step<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
    relaxation: Relaxation,
    iteration: usize,
    ws: &mut Workspace<NX>,
) -> Result<[Interval; NX], EmptinessProof>
where
    M: VectorModel<NX, NM, NR>,
{
    let xm_iv = build_relaxation(model, x, measurements, relaxation, iteration, &mut ws.poly)?;
    bound_by_linear_programs(x, &xm_iv, ws)
}

/// The polyhedron of one Newton step (steps 1 and 2 of the module documentation): every solution
/// `x` in the box `x` has `y = x - mid(x)` in `poly` (over the box `x - mid(x)`, rounded
/// outward). Returns `mid(x)` as point intervals, or the cheap rejection's proof of emptiness.
pub(crate) fn build_relaxation<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
    relaxation: Relaxation,
    iteration: usize,
    poly: &mut Polyhedron,
) -> Result<[Interval; NX], EmptinessProof>
where
    M: VectorModel<NX, NM, NR>,
{
    let frame = StepFrame::new(x, relaxation, iteration);
    let ylo = frame.y_box.map(|v| v.inf());
    let yhi = frame.y_box.map(|v| v.sup());
    poly.reset(&ylo, &yhi);
    for j in 0..NX {
        if is_fixed(x[j]) {
            poly.freeze(j, frame.y_box[j].mag());
        }
    }
    let mut row = [0.0; NX];
    // The affine forms' noise symbols: x_j = mid(x_j) + rad(x_j) ε_j, i.e. y_j = rad(x_j) ε_j.
    let rad_x = x.map(|v| v.rad());
    for (k, m) in measurements.iter().enumerate() {
        poly.begin_group(k as u32);
        let e = model.evaluate_rows_interval(x, m);
        let forms = model.linear_enclosures(x, m);
        let excluded = |r: usize| {
            !e[r].value.contains(0.0) || forms.as_ref().is_some_and(|f| !f[r].range().contains(0.0))
        };
        if (0..NR).any(excluded) {
            return Err(EmptinessProof::CheapRejection { measurement: k });
        }
        // The coupling directions of this configuration (none for one row).
        let directions = if NR >= 2 {
            let b_mid: [[f64; NM]; NR] = core::array::from_fn(|r| e[r].dm.map(|v| v.mid()));
            coupling_directions(&b_mid, &m.map(|v| v.rad()))
        } else {
            Directions::new()
        };
        // With affine forms (measured 6-20x tighter than the interval Jacobian over a long chain's
        // prior, and no looser near the fixed point) their rows replace the interval relaxation.
        if let Some(forms) = forms {
            for form in &forms {
                push_enclosure_rows(poly, &mut row, form, &rad_x);
            }
            for lambda in directions.as_slice() {
                push_enclosure_rows(poly, &mut row, &combine(lambda, &forms), &rad_x);
            }
        } else {
            push_relaxation_rows(model, &frame, m, &e, &directions, poly, &mut row);
        }
    }
    Ok(frame.xm_iv)
}

/// The interval relaxation rows ([`Relaxation`]) of one configuration: each of its rows and each
/// combination `λ·f` along its coupling directions.
fn push_relaxation_rows<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    frame: &StepFrame<NX>,
    m: &[Interval; NM],
    e: &[crate::Evaluation<Interval, NX, NM>; NR],
    directions: &Directions<NR>,
    poly: &mut Polyhedron,
    row: &mut [f64; NX],
) where
    M: VectorModel<NX, NM, NR>,
{
    let unused = [Interval::ZERO; NR];
    let m_mid: [Interval; NM] = core::array::from_fn(|i| Interval::point(m[i].mid()));
    // Values at (centre, mid M) and (corner, mid M), every row at once.
    let at_centre = if frame.krawczyk() {
        model.residuals_interval(&frame.xm_iv, &m_mid)
    } else {
        unused
    };
    let at_corners: [[Interval; NR]; 2] = if frame.corners() {
        core::array::from_fn(|c| model.residuals_interval(&frame.corner_iv[c], &m_mid))
    } else {
        [unused; 2]
    };
    // The centred forms only where the relaxation uses them (the others stay zero, unread).
    let (centre, corners) = (frame.krawczyk(), frame.corners());
    for r in 0..NR {
        let over = |used: bool, v: Interval| {
            if used {
                centred_over_measurement(v, m, &m_mid, &e[r].dm)
            } else {
                Interval::ZERO
            }
        };
        let eq = ScalarRow {
            a: e[r].dx,
            at_centre: over(centre, at_centre[r]),
            at_corners: [
                over(corners, at_corners[0][r]),
                over(corners, at_corners[1][r]),
            ],
        };
        frame.push_rows(poly, row, &eq);
    }
    for lambda in directions.as_slice() {
        let l = lambda.map(Interval::point);
        let combine = |v: &[Interval; NR]| (0..NR).fold(Interval::ZERO, |s, r| s + l[r] * v[r]);
        let b: [Interval; NM] =
            core::array::from_fn(|i| (0..NR).fold(Interval::ZERO, |s, r| s + l[r] * e[r].dm[i]));
        let over = |used: bool, v: &[Interval; NR]| {
            if used {
                centred_over_measurement(combine(v), m, &m_mid, &b)
            } else {
                Interval::ZERO
            }
        };
        let eq = ScalarRow {
            a: core::array::from_fn(|j| (0..NR).fold(Interval::ZERO, |s, r| s + l[r] * e[r].dx[j])),
            at_centre: over(centre, &at_centre),
            at_corners: [over(corners, &at_corners[0]), over(corners, &at_corners[1])],
        };
        frame.push_rows(poly, row, &eq);
    }
}

/// `Σ_r λ_r F_r` for linear enclosures `F_r` of the rows of one configuration, with every
/// rounding bounded into the error radius (so the result encloses `λ·f`).
fn combine<const NX: usize, const NM: usize, const NR: usize>(
    lambda: &[f64; NR],
    forms: &[LinearEnclosure<NX, NM>; NR],
) -> LinearEnclosure<NX, NM> {
    let mut e = 0.0;
    let mut dot = |values: &dyn Fn(usize) -> f64| {
        let mut acc = 0.0;
        for r in 0..NR {
            let t = lambda[r] * values(r);
            acc += t;
            e = add_up(e, add_up(rounding(t), rounding(acc)));
        }
        acc
    };
    let c = dot(&|r| forms[r].c);
    let gx = core::array::from_fn(|j| dot(&|r| forms[r].gx[j]));
    let gm = core::array::from_fn(|i| dot(&|r| forms[r].gm[i]));
    for r in 0..NR {
        e = add_up(e, mul_up(lambda[r].abs(), forms[r].e));
    }
    LinearEnclosure { c, gx, gm, e }
}

/// The two rows of a linear enclosure in `y = x - mid(x)`: a solution has `f = 0` for some
/// reading, so `Σ_j (gx_j / rad_j) y_j ∈ -c ± (Σ_i |gm_i| + e)`; the rounded coefficients'
/// errors (at most `rounding(g_j) rad_j` each) widen the slack.
fn push_enclosure_rows<const NX: usize, const NM: usize>(
    poly: &mut Polyhedron,
    row: &mut [f64; NX],
    form: &LinearEnclosure<NX, NM>,
    rad: &[f64; NX],
) {
    let mut slack = form.gm.iter().fold(form.e, |s, g| add_up(s, g.abs()));
    for j in 0..NX {
        row[j] = if rad[j] > 0.0 {
            form.gx[j] / rad[j]
        } else {
            0.0
        };
        if row[j] != 0.0 {
            slack = add_up(slack, mul_up(rounding(row[j]), rad[j]));
        } else if form.gx[j] != 0.0 {
            // A coefficient on a point parameter: it cannot move; its term is at most |gx_j|.
            slack = add_up(slack, form.gx[j].abs());
        }
    }
    if !slack.is_finite() || !form.c.is_finite() {
        return;
    }
    poly.push_row(row, add_up(-form.c, slack));
    row.iter_mut().for_each(|v| *v = -*v);
    poly.push_row(row, add_up(form.c, slack));
}

/// Adds `Σ a_j (y_j - delta_j) <= r`, i.e. `Σ a_j y_j <= r + Σ a_j delta_j` rounded up.
fn push_shifted_row<const NX: usize>(
    poly: &mut Polyhedron,
    row: &mut [f64; NX],
    coef: impl Fn(usize) -> f64,
    r: f64,
    delta: &[Interval; NX],
) {
    if !r.is_finite() {
        return;
    }
    // The upper bound of `r + Σ a_j delta_j` in interval arithmetic, bound by bound: the sup of
    // a sum is the rounded-up sum of the sups, and the sup of `[a, a] · delta` is `a sup(delta)`
    // for `a >= 0`, `a inf(delta)` below, rounded up (the same roundings as `Interval`'s, so the
    // same number, without the lower bounds nobody reads).
    let mut rhs = r;
    for j in 0..NX {
        row[j] = coef(j);
        if !row[j].is_finite() {
            return;
        }
        let a = row[j];
        let term = if a >= 0.0 {
            mul_up(a, delta[j].sup())
        } else {
            mul_up(a, delta[j].inf())
        };
        rhs = add_up(rhs, term);
    }
    poly.push_row(row, rhs);
}

/// Min and max of every `y_j` over the polyhedron, made rigorous; returns the new box in `x`.
fn bound_by_linear_programs<const NX: usize>(
    x: &[Interval; NX],
    xm: &[Interval; NX],
    ws: &mut Workspace<NX>,
) -> Result<[Interval; NX], EmptinessProof> {
    let rows = ws.poly.rows();
    ws.dual.resize(rows, 0.0);
    let mut out = *x;
    ws.optima.clear();
    let skip = ws.lp.skips_attained_bounds(NX);
    for j in 0..NX {
        if ws.poly.is_frozen(j) {
            continue;
        }
        for sense in [1.0, -1.0] {
            let slot = 2 * j + usize::from(sense < 0.0);
            // An optimal point of an earlier LP of this step that lies in the current bounds and
            // on this face: the LP's bound cannot move the face (the minimum of `±y_j` is at
            // most that point's value, and the face bounds it from below), so the LP is skipped.
            // The box is the one the LP would give; only the LP engine's warm start differs.
            let (lo, hi) = (ws.poly.lo(), ws.poly.hi());
            let on_face = ws.optima.iter().filter(|_| skip).find(|p| {
                (if sense > 0.0 {
                    p[j] <= lo[j]
                } else {
                    p[j] >= hi[j]
                }) && (0..NX).all(|i| lo[i] <= p[i] && p[i] <= hi[i])
            });
            if let Some(p) = on_face {
                ws.lp_skipped += 1;
                for (i, v) in p.iter().enumerate() {
                    ws.extreme_points[slot][i] = xm[i].mid() + v;
                }
                continue;
            }
            ws.objective = [0.0; NX];
            ws.objective[j] = sense;
            ws.lp_solves += 1;
            let status = ws
                .lp
                .minimize(&ws.poly, &ws.objective, &mut ws.dual, &mut ws.primal);
            if status == LpStatus::Infeasible {
                if proves_infeasible(&ws.poly, &ws.dual, &ws.zeros) {
                    // (`Workspace::farkas_support` reads the ray left in `dual`.)
                    return Err(EmptinessProof::LpInfeasible);
                }
                ws.lp_failures += 1;
                continue;
            }
            if status == LpStatus::Failed {
                ws.lp_failures += 1;
            }
            let bound = safe_lower_bound(&ws.poly, &ws.objective, &ws.dual);
            let (lo, hi) = (ws.poly.lo()[j], ws.poly.hi()[j]);
            let (new_lo, new_hi) = if sense > 0.0 {
                (lo.max(bound), hi)
            } else {
                (lo, hi.min(-bound))
            };
            if new_lo > new_hi {
                return Err(EmptinessProof::EmptyIntersection { parameter: j });
            }
            ws.poly.set_bounds(j, new_lo, new_hi);
            if status == LpStatus::Optimal {
                for (i, p) in ws.primal.iter().enumerate() {
                    ws.extreme_points[slot][i] = xm[i].mid() + p;
                }
                if skip {
                    ws.optima.push(ws.primal);
                }
            }
        }
    }
    for j in 0..NX {
        let y = Interval::new(ws.poly.lo()[j], ws.poly.hi()[j]);
        let shifted = xm[j] + y;
        out[j] = x[j].intersection(shifted);
        if out[j].is_empty() {
            return Err(EmptinessProof::EmptyIntersection { parameter: j });
        }
    }
    Ok(out)
}
