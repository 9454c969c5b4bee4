//! [`certify`]: contraction to a fixed point plus the evidence for the verdict.

use crate::kernel::contract::{contract, is_fixed, EmptinessProof, Workspace};
use crate::kernel::cover::Cover;
use crate::kernel::inner_targets::wider_inner_points;
use crate::kernel::outliers::{
    certified_outliers, conflict_set, conflict_subset, drop_sets, is_spread, keep_all_but,
};
use crate::proof::consistency::{inner_points, point_hull};
use crate::proof::second_order::second_order_emptiness;
use crate::proof::witness::find_witness;
use crate::{Interval, Settings, VectorModel};

/// The verdict on a box of parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Status {
    /// Proved: no parameter vector in the initial box is consistent with the measurements
    /// (the proof is in [`Certification::emptiness`]).
    Empty,
    /// Proved: at least one parameter vector in the box is consistent with the measurements (the
    /// witness is in [`Certification::witness`]).
    Consistent,
    /// Neither proof was found; the outer box is still a valid enclosure of all solutions.
    Undecided,
}

/// The result of [`certify`].
#[derive(Clone, Debug, PartialEq)]
pub struct Certification<const NX: usize> {
    /// The verdict.
    pub status: Status,
    /// A box containing every parameter vector of `x0` consistent with the measurements (all
    /// intervals empty when the status is `Empty`).
    pub outer: [Interval; NX],
    /// Newton/LP steps performed.
    pub iterations: usize,
    /// For `Empty`: which test proved it.
    pub emptiness: Option<EmptinessProof>,
    /// For `Consistent`: a point of `outer` proved consistent with every measurement box.
    pub witness: Option<[f64; NX]>,
    /// Inner bounds: the hull of certified consistent points, contained in the hull of the solution
    /// set (so the true hull lies between `inner` and `outer`).
    pub inner: Option<[Interval; NX]>,
    /// LP solves and failures (failures never shrink the box).
    pub lp_solves: usize,
    /// LP solves that failed or whose infeasibility claim did not check.
    pub lp_failures: usize,
    /// For `Empty` (with no outliers tolerated): a minimal set of measurements (0-based, sorted)
    /// that no parameter vector of `x0` fits together — removing any one of them, the rest is not
    /// proved empty (a conflict set, [`Settings::conflict_sets`]). Not searched when the misfit is
    /// [`spread`](Certification::spread).
    pub conflict: Option<Vec<usize>>,
    /// For `Empty` (with no outliers tolerated): the measurements (0-based, sorted) the final
    /// certificate of emptiness weighs, when it names them — the configurations of the rows of a
    /// Farkas ray ([`EmptinessProof::LpInfeasible`]), of the second-order certificate's
    /// combination ([`EmptinessProof::SecondOrder`]), or the one measurement of a
    /// [`EmptinessProof::CheapRejection`]. The certificate applies to the box the contraction
    /// reached with every measurement, so the support alone need not be inconsistent; how many
    /// measurements it weighs tells a misfit spread over the data from a few bad measurements.
    pub support: Option<Vec<usize>>,
    /// For `Empty`: the [`support`](Certification::support) weighs more than half of the
    /// measurements a certificate can weigh ([`crate::kernel::outliers::is_spread`]) — a misfit
    /// spread over the data (the error bounds too tight for the model) rather than a few bad
    /// measurements; the conflict set is then not searched.
    pub spread: bool,
    /// With [`Settings::max_outliers`] `= q > 0`: the measurements (0-based, sorted) that every
    /// parameter vector fitting at least `p - q` of them misfits — certified outliers under the
    /// assumption that at most `q` are bad. Empty otherwise.
    pub outliers: Vec<usize>,
    /// Boxes whose union contains every solution: `outer` itself, or with outliers tolerated one
    /// box per subset not proved empty (empty when the status is `Empty`). What
    /// [`crate::CertifiedSet::new`] turns into the certified set.
    pub cover: Cover<NX>,
}

impl<const NX: usize> Certification<NX> {
    /// Per parameter, `wid(outer) / wid(inner)`: the worst-case overestimation of the outer bound
    /// over the true hull of the solution set (`None` without inner bounds; `inf` where the inner
    /// interval is a point).
    pub fn overestimation(&self) -> Option<[f64; NX]> {
        let inner = self.inner?;
        Some(core::array::from_fn(|j| {
            self.outer[j].wid() / (inner[j].sup() - inner[j].inf())
        }))
    }
}

/// At most this many weighed readings, each alone the cause of a first-order proof of emptiness
/// (the rest consistent without it), make the misfit a few bad readings rather than a spread one.
const MAX_EXPLAINING_READINGS: usize = 2;

/// Certifies a box: contracts `x0` with the Newton/Krawczyk–LP step to a fixed point (paper Section
/// IV), then looks for a certified witness and inner bounds.
///
/// `measurements[k]` is the box `M_k` of measurement `k`. The returned `outer` box contains every
/// `x ∈ x0` with `f(x, M_k) = 0` for some `M_k ∈ measurements[k]`, for all `k` — or, with
/// [`Settings::max_outliers`] `= q`, for all but at most `q` of the `k` (the union over every choice
/// of `q` dropped measurements; see the `outliers` section of the crate documentation). An `Empty`
/// verdict comes with the measurements its certificate weighs ([`Certification::support`]) and,
/// unless they show a misfit spread over the data ([`Certification::spread`]), a minimal conflict
/// set ([`Certification::conflict`]).
pub fn certify<M: VectorModel<NX, NM, NR>, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x0: &[Interval; NX],
    measurements: &[[Interval; NM]],
    settings: &Settings,
) -> Certification<NX> {
    let mut ws = Workspace::new(settings);
    certify_with(model, x0, measurements, settings, &mut ws)
}

/// [`certify`] with a caller-provided workspace (no allocation in the contraction after warm-up).
pub fn certify_with<
    M: VectorModel<NX, NM, NR>,
    const NX: usize,
    const NM: usize,
    const NR: usize,
>(
    model: &M,
    x0: &[Interval; NX],
    measurements: &[[Interval; NM]],
    settings: &Settings,
    ws: &mut Workspace<NX>,
) -> Certification<NX> {
    if settings.max_outliers > 0 {
        return certify_relaxed(model, x0, measurements, settings, ws);
    }
    let mut out = certify_plain(model, x0, measurements, settings, ws);
    if out.status != Status::Empty {
        return out;
    }
    let free = x0.iter().filter(|v| !is_fixed(**v)).count();
    out.spread = out
        .support
        .as_ref()
        .is_some_and(|s| is_spread(s.len(), measurements.len(), free));
    if out.spread && out.emptiness == Some(EmptinessProof::LpInfeasible) {
        // A first-order certificate may weigh many measurements around one gross error (one
        // configuration of a simulated arm moved 50 times its bound: 19 of 50 weighed). If the
        // data without one weighed measurement are proved consistent (a witness in the box the
        // contraction leaves) for one or two of them only, those readings explain the misfit:
        // search the conflict set as before. Where no single reading does, or many do (each one
        // of a dozen would do: no reading stands out), the misfit stays spread.
        let support = out.support.clone().unwrap_or_default();
        let mut explaining = 0;
        for &k in &support {
            let rest: Vec<[Interval; NM]> = (0..measurements.len())
                .filter(|&j| j != k)
                .map(|j| measurements[j])
                .collect();
            let consistent = contract(model, x0, &rest, settings, ws)
                .result
                .is_ok_and(|b| find_witness(model, &b, &rest, &[]).is_some());
            explaining += usize::from(consistent);
            if explaining > MAX_EXPLAINING_READINGS {
                break;
            }
        }
        out.spread = !(1..=MAX_EXPLAINING_READINGS).contains(&explaining);
    }
    if out.spread || !settings.conflict_sets {
        // Spread: a minimal conflict set would name many measurements, at many times the
        // verdict's cost, where the support already tells (`benches/README.md`).
        return out;
    }
    if out.emptiness == Some(EmptinessProof::SecondOrder) {
        // The second-order proof's subsets are tested by the contraction and, where it leaves a
        // box, by the second-order proof on it; from the configurations the proof weighed when
        // they alone are proved inconsistent.
        let mut proves_empty = |kept: &[usize]| {
            let subset: Vec<[Interval; NM]> = kept.iter().map(|&k| measurements[k]).collect();
            match contract(model, x0, &subset, settings, ws).result {
                Err(_) => true,
                Ok(b) => model
                    .curvature()
                    .and_then(|c| second_order_emptiness(model, c, &b, &subset))
                    .is_some(),
            }
        };
        let support = out.support.clone().unwrap_or_default();
        let start = if !support.is_empty() && proves_empty(&support) {
            support
        } else {
            (0..measurements.len()).collect()
        };
        out.conflict = Some(conflict_subset(start, &[], proves_empty));
        return out;
    }
    let used = match out.emptiness {
        Some(EmptinessProof::CheapRejection { measurement }) => vec![measurement],
        _ => Vec::new(),
    };
    // The prover of the verdict, the contraction, alone: the witness and inner-bound
    // searches `certify_plain` runs on the subsets that are not proved empty (most of the
    // tests once the set is near minimal) decide nothing here. On the real UR10 the gain is
    // within the machine's variance: the time is the contractions themselves, one per tested
    // subset (`benches/README.md`).
    out.conflict = Some(conflict_set(measurements.len(), &used, |kept| {
        let subset: Vec<[Interval; NM]> = kept.iter().map(|&k| measurements[k]).collect();
        contract(model, x0, &subset, settings, ws).result.is_err()
    }));
    out
}

/// At most this many subsets are certified for the q-relaxation (`C(p, q)` of them); beyond, the
/// result is `Undecided` with the initial box.
pub(crate) const MAX_SUBSETS: usize = 20_000;

/// The q-relaxed certification: every subset of `p - q` measurements certified on its own, the
/// hulls of the results (see [`crate::outliers`]).
fn certify_relaxed<
    M: VectorModel<NX, NM, NR>,
    const NX: usize,
    const NM: usize,
    const NR: usize,
>(
    model: &M,
    x0: &[Interval; NX],
    measurements: &[[Interval; NM]],
    settings: &Settings,
    ws: &mut Workspace<NX>,
) -> Certification<NX> {
    let p = measurements.len();
    let mut out = Certification {
        status: Status::Undecided,
        outer: *x0,
        iterations: 0,
        emptiness: None,
        witness: None,
        inner: None,
        lp_solves: 0,
        lp_failures: 0,
        conflict: None,
        support: None,
        spread: false,
        outliers: Vec::new(),
        cover: Cover::single(*x0),
    };
    let Some(drops) = drop_sets(p, settings.max_outliers, MAX_SUBSETS) else {
        // Too many subsets (or q >= p): keep the initial box, undecided.
        return out;
    };
    let mut cover = Cover {
        boxes: Vec::new(),
        subsets: Vec::new(),
        dropped: drops.clone(),
    };
    let mut outer: Option<[Interval; NX]> = None;
    let mut alive = Vec::with_capacity(drops.len());
    for d in &drops {
        let subset = keep_all_but(measurements, d);
        let c = certify_plain(model, x0, &subset, settings, ws);
        out.iterations += c.iterations;
        out.lp_solves += c.lp_solves;
        out.lp_failures += c.lp_failures;
        alive.push(c.status != Status::Empty);
        if c.status == Status::Empty {
            continue;
        }
        cover.boxes.push(c.outer);
        cover.subsets.push(alive.len() - 1);
        outer = Some(hull_box(outer, &c.outer));
        if let Some(inner) = c.inner {
            out.inner = Some(hull_box(out.inner, &inner));
        }
        if out.witness.is_none() {
            out.witness = c.witness;
        }
    }
    match outer {
        None => {
            out.status = Status::Empty;
            out.outer = [Interval::EMPTY; NX];
            out.emptiness = Some(EmptinessProof::EverySubset);
            out.cover = Cover::empty();
        }
        Some(o) => {
            out.outer = o;
            out.cover = cover;
            out.status = if out.witness.is_some() {
                Status::Consistent
            } else {
                Status::Undecided
            };
            out.outliers = certified_outliers(p, &drops, &alive);
        }
    }
    out
}

/// The hull of `b` and an optional box.
pub(crate) fn hull_box<const NX: usize>(
    h: Option<[Interval; NX]>,
    b: &[Interval; NX],
) -> [Interval; NX] {
    match h {
        None => *b,
        Some(h) => core::array::from_fn(|j| h[j].hull(b[j])),
    }
}

/// [`certify_with`] without outliers and without the conflict search (with the proof's support).
fn certify_plain<M: VectorModel<NX, NM, NR>, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x0: &[Interval; NX],
    measurements: &[[Interval; NM]],
    settings: &Settings,
    ws: &mut Workspace<NX>,
) -> Certification<NX> {
    let (solves, failures) = (ws.lp_solves, ws.lp_failures);
    let c = contract(model, x0, measurements, settings, ws);
    let mut out = Certification {
        status: Status::Undecided,
        outer: [Interval::EMPTY; NX],
        iterations: c.iterations,
        emptiness: None,
        witness: None,
        inner: None,
        lp_solves: 0,
        lp_failures: 0,
        conflict: None,
        support: None,
        spread: false,
        outliers: Vec::new(),
        cover: Cover::empty(),
    };
    match c.result {
        Err(proof) => {
            out.status = Status::Empty;
            out.emptiness = Some(proof);
            out.support = match proof {
                EmptinessProof::CheapRejection { measurement } => Some(vec![measurement]),
                EmptinessProof::LpInfeasible => Some(ws.farkas_support()),
                _ => None,
            };
        }
        Ok(outer) => {
            out.outer = outer;
            out.cover = Cover::single(outer);
            let extremes = if c.iterations > 0 {
                ws.extreme_points.clone()
            } else {
                Vec::new()
            };
            if let Some(w) = find_witness(model, &outer, measurements, &extremes) {
                out.status = Status::Consistent;
                out.witness = Some(w);
                if settings.inner_bounds {
                    let mut points = inner_points(
                        model,
                        &w,
                        &outer,
                        &extremes,
                        measurements,
                        settings.inner_bisections,
                    );
                    points.extend(wider_inner_points(
                        model,
                        &w,
                        &outer,
                        measurements,
                        &points,
                        settings.inner_bisections,
                    ));
                    out.inner = Some(point_hull(core::iter::once(&w).chain(&points)));
                }
            } else if let Some(proof) = model
                .curvature()
                .and_then(|c| second_order_emptiness(model, c, &outer, measurements))
            {
                out.status = Status::Empty;
                out.emptiness = Some(EmptinessProof::SecondOrder);
                out.outer = [Interval::EMPTY; NX];
                out.cover = Cover::empty();
                out.support = Some(proof.support);
            }
        }
    }
    out.lp_solves = ws.lp_solves - solves;
    out.lp_failures = ws.lp_failures - failures;
    out
}
