//! [`hull`]: the tightest certified answer — an outer box that contains every solution and an inner
//! box spanned by certified solutions, refined until they meet within a tolerance.
//!
//! The paper's fixed point `x1` (Section IV) is only as tight as one linear relaxation over the whole
//! box, and its largest-box sweep (Section V) keeps little of what bisection proves. Here the
//! *hull of all surviving boxes* is kept and refined where it matters:
//!
//! **Outer bound.** A list of boxes covers every solution of `x0` (it starts as `[x1]`). The outer
//! box is their hull. Each round, for every face of the hull that is not yet close to the inner
//! bound (lower face of parameter `j`: `lo_j(outer) < lo_j(inner) - tol/2 · wid_j(inner)`), the box
//! whose bound attains that face is split at the midpoint of its widest dimension (relative to the
//! hull) and both halves are contracted with the Newton/LP step ([`crate::contract`]). For models
//! that provide second-order certificates ([`crate::VectorModel::curvature`]) the box is split
//! across the face's own parameter instead, halfway between the inner bound and the box's face, and
//! a half the contraction keeps but where no point is certified is tried with the certificate
//! ([`crate::proof::second_order`]): where the relaxation is too loose near the threshold, the
//! outer half is often provably empty. Halves proved empty are discarded — every discarded piece
//! carries a proof; the survivors replace the box. This is a best-first branch and bound on `min
//! x_j` and `max x_j` over the solution set, shared by the `2n` faces, so that a box proved empty
//! for one face is gone for all. Boxes that lie within the satisfied zone of every face are retired
//! into one box `D` that stays in the hull. The same loop handles large prior boxes: while the
//! Newton step does not bite, the face boxes are simply split until it does.
//!
//! **Inner bound.** Certified consistent points ([`crate::is_consistent_point`]) are pushed towards
//! each face by successive linear programs: at a point `p`, with `f_k = f(p, mid M_k)`,
//! `g_k = ∂f/∂x (p, mid M_k)` and `w_k = Σ_i |∂f/∂M_i| rad(M_{k,i})` (the first-order half-range of
//! `f(p, ·)` over `M_k`, paper eq. 6), minimise `±d_j` subject to `|f_k + g_k·d| <= θ w_k` and
//! `p + d` in the box, then certify `p + d`; the margin `θ < 1` absorbs the linearisation error and
//! is lowered when a step fails. The starting points are the LP extreme points the contraction
//! already computes. The inner box is the hull of certified points, so it lies inside the hull of
//! the solution set.
//!
//! Without inner bounds ([`Settings::inner_bounds`] `= false`) no face is ever satisfied: the outer
//! box alone is refined until a budget is spent (the witness still decides the status).
//!
//! **Stop rule.** Per parameter, stop refining when `wid(outer) <= (1 + tol) wid(inner)`
//! ([`Settings::hull_tolerance`]), or when [`Settings::hull_max_boxes`] boxes were contracted or
//! [`Settings::hull_max_seconds`] elapsed; the ratios reached are reported.
//!
//! **Parallel and deterministic.** The halves of one round are contracted in parallel (rayon) and
//! merged in a fixed order, so the result does not depend on the number of threads (it does depend
//! on the time budget, when one is set and reached).

use crate::kernel::bisection::split_widest;
use crate::kernel::certify::{certify, hull_box, MAX_SUBSETS};
use crate::kernel::contract::{
    contract, contract_from, is_fixed, Contraction, EmptinessProof, Workspace,
};
use crate::kernel::cover::Cover;
use crate::kernel::farthest_point::{push_towards, PushEngines};
use crate::kernel::inner_targets::wider_inner_points;
use crate::kernel::outliers::{certified_outliers, conflict_set, drop_sets, keep_all_but};
use crate::lp::{LpBackend, LpMemory};
use crate::proof::consistency::inner_points;
use crate::proof::second_order::second_order_emptiness;
use crate::proof::witness::find_witness;
use crate::{Interval, Settings, Status, VectorModel};
use rayon::prelude::*;
use std::marker::PhantomData;
use std::sync::Arc;
use std::time::Instant;

/// The result of [`hull`].
#[derive(Clone, Debug, PartialEq)]
pub struct Hull<const NX: usize> {
    /// The verdict: `Empty` (every piece of `x0` proved empty), `Consistent` (a certified solution
    /// exists) or `Undecided`.
    pub status: Status,
    /// Contains every solution in `x0` (all intervals empty when the status is `Empty`).
    pub outer: [Interval; NX],
    /// The hull of certified consistent points (`None` when none was found): the true hull of the
    /// solution set lies between `inner` and `outer`.
    pub inner: Option<[Interval; NX]>,
    /// The paper's fixed point `x1` (Section IV), for comparison (`None` when `x0` was proved empty
    /// at once).
    pub x1: Option<[Interval; NX]>,
    /// Newton/LP steps of the contraction to `x1`.
    pub iterations: usize,
    /// For `Empty`: the proof (the contraction's, or [`EmptinessProof::Subdivision`]).
    pub emptiness: Option<EmptinessProof>,
    /// A certified consistent point.
    pub witness: Option<[f64; NX]>,
    /// The certified consistent points that attain the faces of `inner`: for parameter `j`, entry
    /// `2j` attains `inf(inner_j)` and entry `2j + 1` attains `sup(inner_j)` (empty when `inner` is
    /// `None`). Each can be rechecked with [`crate::is_consistent_point`].
    pub inner_points: Vec<[f64; NX]>,
    /// Per parameter, `wid(outer) / wid(inner)` (`inf` where there is no inner width).
    pub ratio: [f64; NX],
    /// Whether every parameter met the tolerance (`false`: a budget ran out first).
    pub converged: bool,
    /// Boxes contracted with the Newton/LP step.
    pub boxes_contracted: usize,
    /// Refinement rounds.
    pub rounds: usize,
    /// Wall-clock seconds.
    pub seconds: f64,
    /// For `Empty` (with no outliers tolerated): a minimal set of measurements (0-based, sorted)
    /// that no parameter vector of `x0` fits together (a conflict set,
    /// [`Settings::conflict_sets`]); not searched when the misfit is [`spread`](Hull::spread).
    pub conflict: Option<Vec<usize>>,
    /// For `Empty` (with no outliers tolerated, and the conflict search on), when
    /// [`crate::certify`] proves it too: the measurements its certificate weighs
    /// ([`crate::Certification::support`]).
    pub support: Option<Vec<usize>>,
    /// For `Empty`: the support shows a misfit spread over the data
    /// ([`crate::Certification::spread`]); the conflict set is then not searched.
    pub spread: bool,
    /// With [`Settings::max_outliers`] `= q > 0`: the measurements that every parameter vector
    /// fitting at least `p - q` of them misfits (certified outliers).
    pub outliers: Vec<usize>,
    /// The boxes whose union contains every solution (empty when the status is `Empty`): what
    /// [`crate::CertifiedSet::new`] turns into the certified set.
    pub cover: Cover<NX>,
}

/// A box of the cover, with whether it is too small to split further, which measurement subset
/// it belongs to and the LP bases its contraction ended with.
#[derive(Clone)]
struct Piece<const NX: usize> {
    b: [Interval; NX],
    atomic: bool,
    /// The measurement subset whose solutions it covers (0 without outliers).
    set: usize,
    /// Where its halves' first Newton/LP step starts ([`contract_from`]): a half's polyhedron is
    /// its parent's over a smaller box, so the parent's optimal bases are a few pivots from the
    /// half's (measured on the built-in arm: see `benches/README.md`). Handed down the tree, not
    /// shared between workers, so that the result does not depend on the thread schedule.
    bases: Arc<LpMemory>,
}

/// A face of the outer box: parameter `j`, lower (`upper == false`) or upper side.
#[derive(Clone, Copy, PartialEq, Eq)]
struct Face {
    j: usize,
    upper: bool,
}

impl Face {
    fn all(nx: usize) -> impl Iterator<Item = Face> {
        (0..nx).flat_map(|j| [Face { j, upper: false }, Face { j, upper: true }])
    }

    /// How far `b` reaches beyond the face direction: `-inf(b_j)` for a lower face, `sup(b_j)` for
    /// an upper one (larger is more extreme).
    fn reach(self, b: &Interval) -> f64 {
        if self.upper {
            b.sup()
        } else {
            -b.inf()
        }
    }

    /// The unit vector pointing out of the face: `-e_j` for a lower face, `e_j` for an upper one.
    fn direction<const NX: usize>(self) -> [f64; NX] {
        let mut d = [0.0; NX];
        d[self.j] = if self.upper { 1.0 } else { -1.0 };
        d
    }

    /// The slot of this face in the workspace's LP extreme points.
    fn slot(self) -> usize {
        2 * self.j + usize::from(self.upper)
    }
}

/// The certified hull of the solution set in `x0` (see the module documentation).
///
/// ```
/// use calib_core::{hull, interval_model, Interval, Scalar, Settings, Status};
///
/// #[interval_model]
/// pub fn circle<S: Scalar>(x: &[S; 3], m: &[S; 2]) -> S {
///     let [cx, cy, r] = *x;
///     ((m[0] - cx).sqr() + (m[1] - cy).sqr()).sqrt() - r
/// }
///
/// let measurements: Vec<[Interval; 2]> = (0..12)
///     .map(|k| {
///         let t = k as f64 * 0.5;
///         [Interval::mid_rad(t.cos(), 1e-3), Interval::mid_rad(t.sin(), 1e-3)]
///     })
///     .collect();
/// let x0 = [Interval::new(-0.1, 0.1), Interval::new(-0.1, 0.1), Interval::new(0.9, 1.1)];
/// let h = hull(&Circle, &x0, &measurements, &Settings::default());
/// assert_eq!(h.status, Status::Consistent);
/// let inner = h.inner.unwrap();
/// for j in 0..3 {
///     assert!(inner[j].is_subset_of(h.outer[j]));           // inner ⊆ true hull ⊆ outer
///     assert!(h.outer[j].is_subset_of(h.x1.unwrap()[j]));   // never looser than the paper's x1
/// }
/// assert!(h.outer[2].contains(1.0));
/// ```
pub fn hull<
    M: VectorModel<NX, NM, NR> + Sync,
    const NX: usize,
    const NM: usize,
    const NR: usize,
>(
    model: &M,
    x0: &[Interval; NX],
    measurements: &[[Interval; NM]],
    settings: &Settings,
) -> Hull<NX> {
    hull_with(model, x0, measurements, settings, &|| settings.lp.backend())
}

/// [`hull`] with the LP engine of every contraction made by `engine` (one engine per worker
/// thread). Any engine is safe: its answers are hints that only decide how tight the rigorous
/// bounds are. (The inner-point search uses its own dense simplex: its points are certified by the
/// sign test, whatever produced them.)
pub fn hull_with<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x0: &[Interval; NX],
    measurements: &[[Interval; NM]],
    settings: &Settings,
    engine: &(dyn Fn() -> Box<dyn LpBackend> + Sync),
) -> Hull<NX>
where
    M: VectorModel<NX, NM, NR> + Sync,
{
    let start = Instant::now();
    let mut out = hull_core(model, x0, measurements, settings, engine);
    if out.status == Status::Empty && settings.max_outliers == 0 && settings.conflict_sets {
        // The conflict set, with the prover that gave the verdict: the contraction alone when it
        // proved x0 empty at once, else the hull (with a bounded budget per subset). `certify`
        // first, for the support of its certificate: when it shows a misfit spread over the data
        // there is no search (and `certify` alone is quick to prove x0 empty; `benches/README.md`).
        let x1_empty = out.x1.is_none();
        let plain = settings.clone().with_conflict_sets(x1_empty);
        let first = certify(model, x0, measurements, &plain);
        if first.status == Status::Empty {
            out.support = first.support;
            out.spread = first.spread;
        }
        out.conflict = if out.spread {
            None
        } else if x1_empty {
            first.conflict
        } else {
            conflict_within_budget(model, x0, measurements, settings, engine, start)
        };
    }
    out
}

/// The conflict set of measurements the hull proved inconsistent, by the deletion filter with a
/// hull per subset (a bounded budget each), within what is left of the run's time budget
/// ([`Settings::hull_max_seconds`], counted from `start`): `None` when the search could not finish
/// in it (a set it stopped in would not be minimal: mostly noise to the user).
fn conflict_within_budget<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x0: &[Interval; NX],
    measurements: &[[Interval; NM]],
    settings: &Settings,
    engine: &(dyn Fn() -> Box<dyn LpBackend> + Sync),
    start: Instant,
) -> Option<Vec<usize>>
where
    M: VectorModel<NX, NM, NR> + Sync,
{
    let left = || {
        settings
            .hull_max_seconds
            .map(|s| s - start.elapsed().as_secs_f64())
    };
    let mut stopped = false;
    let set = conflict_set(measurements.len(), &[], |kept| {
        let seconds = left();
        if stopped || seconds.is_some_and(|s| s <= 0.0) {
            stopped = true;
            return false;
        }
        let mut quick = settings
            .clone()
            .with_hull_budget(settings.hull_max_boxes.min(2000), seconds);
        quick.inner_bounds = false;
        let subset: Vec<[Interval; NM]> = kept.iter().map(|&k| measurements[k]).collect();
        let hull = hull_core(model, x0, &subset, &quick, engine);
        if hull.status != Status::Empty && left().is_some_and(|s| s <= 0.0) {
            // Undecided because the time ran out, not shown consistent: the search stops.
            stopped = true;
        }
        hull.status == Status::Empty
    });
    (!stopped).then_some(set)
}

/// [`hull_with`] without the conflict search, in its steps: the measurement subsets (one without
/// outliers), the paper's `x1` of each, certified points pushed to the faces of `x1`, the
/// refinement of the cover until the faces meet the inner bound, and the verdict.
fn hull_core<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x0: &[Interval; NX],
    measurements: &[[Interval; NM]],
    settings: &Settings,
    engine: &(dyn Fn() -> Box<dyn LpBackend> + Sync),
) -> Hull<NX>
where
    M: VectorModel<NX, NM, NR> + Sync,
{
    let start = Instant::now();
    let mut out = Hull::undecided(x0);
    let q = settings.max_outliers;
    let Some(drops) = dropped_subsets(measurements.len(), q) else {
        // Too many subsets (or q >= p): keep the initial box, undecided.
        out.x1 = Some(*x0);
        return out;
    };
    let sets: Vec<Vec<[Interval; NM]>> = drops
        .iter()
        .map(|d| keep_all_but(measurements, d))
        .collect();
    let firsts = first_steps(model, x0, &sets, settings, engine);
    out.boxes_contracted = sets.len();
    let (cover, x1) = first_cover(&mut out, &firsts);
    let Some(x1) = x1 else {
        out.status = Status::Empty;
        out.outer = [Interval::EMPTY; NX];
        out.cover = Cover::empty();
        if q > 0 {
            out.emptiness = Some(EmptinessProof::EverySubset);
        }
        out.seconds = start.elapsed().as_secs_f64();
        return out;
    };
    out.emptiness = None;
    out.x1 = Some(x1);
    out.cover = cover_of(cover.iter(), &drops);
    if !x1.iter().all(|v| v.is_bounded()) {
        // An unbounded box can be neither split at its midpoint nor linearised: keep it whole.
        out.outer = x1;
        out.seconds = start.elapsed().as_secs_f64();
        return out;
    }
    let mut refiner = Refiner::new(model, x0, &sets, settings, engine, cover);
    let pieces = refiner.cover.clone();
    for piece in &pieces {
        refiner.seed(piece, &firsts[piece.set].extremes);
    }
    let (converged, rounds) = refiner.run(start);
    out.rounds = rounds;
    out.converged = converged;
    refiner.conclude(&mut out, measurements.len(), &drops);
    out.seconds = start.elapsed().as_secs_f64();
    out
}

impl<const NX: usize> Hull<NX> {
    /// The answer before any work: undecided, `outer = x0`, nothing certified.
    fn undecided(x0: &[Interval; NX]) -> Self {
        Hull {
            status: Status::Undecided,
            outer: *x0,
            inner: None,
            x1: None,
            iterations: 0,
            emptiness: None,
            witness: None,
            inner_points: Vec::new(),
            ratio: [f64::INFINITY; NX],
            converged: false,
            boxes_contracted: 0,
            rounds: 0,
            seconds: 0.0,
            conflict: None,
            support: None,
            spread: false,
            outliers: Vec::new(),
            cover: Cover::single(*x0),
        }
    }
}

/// Per measurement subset, the measurements it drops: none without outliers (`q = 0`), else
/// every set of `q` of the `p` measurements; `None` when there are more than [`MAX_SUBSETS`].
fn dropped_subsets(p: usize, q: usize) -> Option<Vec<Vec<usize>>> {
    if q == 0 {
        Some(vec![Vec::new()])
    } else {
        drop_sets(p, q, MAX_SUBSETS)
    }
}

/// The contraction of `x0` to the paper's `x1` against one measurement subset, with where it
/// ended: the LP extreme points of its last step (the seeds of the inner bound) and its LP bases
/// (where its halves' contractions start).
struct FirstStep<const NX: usize> {
    contraction: Contraction<NX>,
    /// `extreme_points` of the contraction's last step (empty when it took no step).
    extremes: Vec<[f64; NX]>,
    bases: Arc<LpMemory>,
}

/// The [`FirstStep`] of every measurement subset, in parallel when there are several.
fn first_steps<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x0: &[Interval; NX],
    sets: &[Vec<[Interval; NM]>],
    settings: &Settings,
    engine: &(dyn Fn() -> Box<dyn LpBackend> + Sync),
) -> Vec<FirstStep<NX>>
where
    M: VectorModel<NX, NM, NR> + Sync,
{
    let first = |ws: &mut Workspace<NX>, set: &Vec<[Interval; NM]>| {
        let contraction = contract(model, x0, set, settings, ws);
        let extremes = if contraction.iterations > 0 {
            ws.extreme_points.clone()
        } else {
            Vec::new()
        };
        FirstStep {
            contraction,
            extremes,
            bases: Arc::new(ws.lp_memory()),
        }
    };
    if settings.parallel && sets.len() > 1 {
        sets.par_iter()
            .map_init(|| Workspace::with_backend(engine()), first)
            .collect()
    } else {
        let mut ws = Workspace::with_backend(engine());
        sets.iter().map(|set| first(&mut ws, set)).collect()
    }
}

/// The boxes the first steps kept, as the first cover, and their hull `x1` (`None` when every
/// subset was proved empty). Records the steps' iterations in `out`, and the first proof of
/// emptiness in `out.emptiness`.
fn first_cover<const NX: usize>(
    out: &mut Hull<NX>,
    firsts: &[FirstStep<NX>],
) -> (Vec<Piece<NX>>, Option<[Interval; NX]>) {
    let mut cover = Vec::new();
    let mut x1: Option<[Interval; NX]> = None;
    for (set, first) in firsts.iter().enumerate() {
        out.iterations += first.contraction.iterations;
        match first.contraction.result {
            Err(proof) => {
                out.emptiness.get_or_insert(proof);
            }
            Ok(b) => {
                x1 = Some(hull_box(x1, &b));
                cover.push(Piece {
                    b,
                    atomic: false,
                    set,
                    bases: Arc::clone(&first.bases),
                });
            }
        }
    }
    (cover, x1)
}

/// The [`Cover`] made of `pieces`, the subsets being those that drop `drops`.
fn cover_of<'p, const NX: usize>(
    pieces: impl Iterator<Item = &'p Piece<NX>> + Clone,
    drops: &[Vec<usize>],
) -> Cover<NX> {
    Cover {
        boxes: pieces.clone().map(|p| p.b).collect(),
        subsets: pieces.map(|p| p.set).collect(),
        dropped: drops.to_vec(),
    }
}

/// The state of the refinement: the cover of the solution set and the certified points.
struct Refiner<'a, M, const NX: usize, const NM: usize, const NR: usize> {
    model: &'a M,
    x0: &'a [Interval; NX],
    /// The measurement subsets (one, all measurements, without outliers).
    sets: &'a [Vec<[Interval; NM]>],
    settings: &'a Settings,
    engine: &'a (dyn Fn() -> Box<dyn LpBackend> + Sync),
    /// Boxes whose union contains every solution not in `retired`.
    cover: Vec<Piece<NX>>,
    /// The hull of retired boxes (boxes within the satisfied zone of every face).
    retired: Option<[Interval; NX]>,
    /// The retired boxes themselves (the cover of the solution set they hold).
    retired_pieces: Vec<Piece<NX>>,
    /// Per subset: whether one of its boxes was retired (so it may hold solutions).
    retired_sets: Vec<bool>,
    /// Per subset: whether a certified point of it was found (so it holds solutions).
    pointed_sets: Vec<bool>,
    /// The hull of certified consistent points.
    inner: Option<[Interval; NX]>,
    /// Per face (slot `2j`, `2j + 1`), the certified point that reaches furthest towards it.
    inner_points: Vec<[f64; NX]>,
    /// One certified consistent point.
    witness: Option<[f64; NX]>,
    /// Boxes contracted so far.
    contracted: usize,
    /// The number of residuals per configuration.
    rows: PhantomData<[(); NR]>,
}

impl<'a, M, const NX: usize, const NM: usize, const NR: usize> Refiner<'a, M, NX, NM, NR>
where
    M: VectorModel<NX, NM, NR> + Sync,
{
    /// The refinement of `cover`, the boxes of the first contraction of each measurement subset
    /// of `sets` (one contraction per subset so far), before any certified point is known.
    fn new(
        model: &'a M,
        x0: &'a [Interval; NX],
        sets: &'a [Vec<[Interval; NM]>],
        settings: &'a Settings,
        engine: &'a (dyn Fn() -> Box<dyn LpBackend> + Sync),
        cover: Vec<Piece<NX>>,
    ) -> Self {
        Refiner {
            model,
            x0,
            sets,
            settings,
            engine,
            cover,
            retired: None,
            retired_pieces: Vec::new(),
            retired_sets: vec![false; sets.len()],
            pointed_sets: vec![false; sets.len()],
            inner: None,
            inner_points: Vec::new(),
            witness: None,
            contracted: sets.len(),
            rows: PhantomData,
        }
    }

    /// The hull of the cover, the retired boxes and the inner box (`None` when all are empty).
    /// Sound: every solution lies in a cover box or a retired box, and the inner box is made of
    /// solutions, so adding it changes nothing but keeps the outer box around it.
    fn outer(&self) -> Option<[Interval; NX]> {
        let mut h: Option<[Interval; NX]> = self.retired;
        for b in self.cover.iter().map(|p| &p.b).chain(self.inner.iter()) {
            h = Some(match h {
                None => *b,
                Some(h) => core::array::from_fn(|j| h[j].hull(b[j])),
            });
        }
        h
    }

    /// How far beyond the inner bound a face may still reach when it counts as satisfied:
    /// `tol/2 · wid(inner_j)` (plus a few ulps, so that point-like parameters can stop too).
    fn slack(&self, j: usize) -> f64 {
        let Some(inner) = &self.inner else {
            return f64::NEG_INFINITY;
        };
        let w = inner[j].wid();
        let scale = inner[j].mag().max(f64::MIN_POSITIVE);
        0.5 * self.settings.hull_tolerance * w + 8.0 * f64::EPSILON * scale
    }

    /// The reach of the inner bound in the direction of `face` plus its slack: a box whose reach
    /// is at most this cannot make the face unsatisfied.
    fn threshold(&self, face: Face) -> f64 {
        match &self.inner {
            None => f64::NEG_INFINITY,
            Some(inner) => face.reach(&inner[face.j]) + self.slack(face.j),
        }
    }

    /// Per subset: whether it may hold solutions (a box of it is left, or a point was certified).
    fn alive(&self) -> Vec<bool> {
        let mut alive: Vec<bool> = (0..self.sets.len())
            .map(|s| self.retired_sets[s] || self.pointed_sets[s])
            .collect();
        for p in &self.cover {
            alive[p.set] = true;
        }
        alive
    }

    /// The first certified points in `piece`, a box of `x1`: a witness (from the contraction's
    /// LP `extremes`), for vector models the segment search of `certify`, then the LP extreme
    /// points and the witness pushed to their faces. Without inner bounds, the witness alone.
    fn seed(&mut self, piece: &Piece<NX>, extremes: &[[f64; NX]]) {
        let witness = if self.witness.is_none() {
            find_witness(self.model, &piece.b, &self.sets[piece.set], extremes)
        } else {
            None
        };
        if !self.settings.inner_bounds {
            if witness.is_some() {
                self.witness = witness;
                self.pointed_sets[piece.set] = true;
            }
            return;
        }
        self.add_points(witness.as_slice(), piece.set);
        if NR >= 2 {
            // Vector models: the segment search of `certify` (witness to each LP extreme point,
            // then to first-order extremes) seeds the inner box too. Their pushes below solve LPs
            // over every coupling direction of every configuration (thousands of nearly parallel
            // rows) and alone leave the inner bound of angles far inside, where the segments
            // reach much tighter ratios in a fraction of the time (`benches/README.md`).
            if let Some(w) = witness.or(self.witness) {
                let points = self.segment_points(piece, &w, extremes);
                self.add_points(&points, piece.set);
            }
        }
        // First inner points: push the LP extreme points of x1 (or the witness) to their faces.
        // (Not along parameters fixed at a point: nothing to gain there.)
        let seeds: Vec<(Face, [f64; NX])> = Face::all(NX)
            .filter(|f| !is_fixed(self.x0[f.j]))
            .flat_map(|f| {
                let lp = extremes.get(f.slot()).copied();
                lp.into_iter().chain(witness).map(move |p| (f, p))
            })
            .collect();
        let points = self.push_all(&piece.b, &seeds, piece.set);
        self.add_points(&points, piece.set);
    }

    /// Certified points of `piece` on segments from the certified point `w`: towards each LP
    /// extreme point, then towards first-order extremes ([`inner_points`],
    /// [`wider_inner_points`]).
    fn segment_points(
        &self,
        piece: &Piece<NX>,
        w: &[f64; NX],
        extremes: &[[f64; NX]],
    ) -> Vec<[f64; NX]> {
        let set = &self.sets[piece.set];
        let bisections = self.settings.inner_bisections;
        let mut points = inner_points(self.model, w, &piece.b, extremes, set, bisections);
        points.extend(wider_inner_points(
            self.model, w, &piece.b, set, &points, bisections,
        ));
        points
    }

    /// Writes the refinement's answer into `out`: the certified points, the final cover, and
    /// the verdict — `Empty` when no box is left (by subdivision, or in every subset with
    /// outliers), else the outer box, `Consistent` with a witness, the ratios and the certified
    /// outliers (`p` measurements, subsets dropping `drops`).
    fn conclude(&self, out: &mut Hull<NX>, p: usize, drops: &[Vec<usize>]) {
        let q = self.settings.max_outliers;
        out.boxes_contracted = self.contracted;
        out.witness = self.witness;
        out.inner = self.inner;
        out.inner_points = self.inner_points.clone();
        out.cover = cover_of(self.cover.iter().chain(&self.retired_pieces), drops);
        match self.outer() {
            None => {
                out.status = Status::Empty;
                out.outer = [Interval::EMPTY; NX];
                out.emptiness = Some(if q > 0 {
                    EmptinessProof::EverySubset
                } else {
                    EmptinessProof::Subdivision
                });
            }
            Some(outer) => {
                out.outer = outer;
                if out.witness.is_some() {
                    out.status = Status::Consistent;
                }
                if let Some(inner) = out.inner {
                    out.ratio = core::array::from_fn(|j| outer[j].wid() / inner[j].wid());
                }
                if q > 0 {
                    out.outliers = certified_outliers(p, drops, &self.alive());
                }
            }
        }
    }

    /// Adds points certified against subset `set`: each face keeps the point that reaches
    /// furthest, and the inner box is their hull.
    fn add_points(&mut self, points: &[[f64; NX]], set: usize) {
        if !points.is_empty() {
            self.pointed_sets[set] = true;
        }
        for p in points {
            self.witness.get_or_insert(*p);
            if self.inner_points.is_empty() {
                self.inner_points = vec![*p; 2 * NX];
            }
            for f in Face::all(NX) {
                let held = &mut self.inner_points[f.slot()];
                if f.reach(&Interval::point(p[f.j])) > f.reach(&Interval::point(held[f.j])) {
                    *held = *p;
                }
            }
        }
        if !self.inner_points.is_empty() {
            let pts = &self.inner_points;
            self.inner = Some(core::array::from_fn(|j| {
                Interval::new(pts[2 * j][j], pts[2 * j + 1][j])
            }));
        }
    }

    /// Pushes each seed towards its face inside `bounds` (clamped to `x0`); returns the certified
    /// points found.
    fn push_all(
        &self,
        bounds: &[Interval; NX],
        seeds: &[(Face, [f64; NX])],
        set: usize,
    ) -> Vec<[f64; NX]> {
        let region: [Interval; NX] = core::array::from_fn(|j| bounds[j].intersection(self.x0[j]));
        if region.iter().any(|v| v.is_empty()) {
            return Vec::new();
        }
        let push = |lp: &mut PushEngines, (face, seed): &(Face, [f64; NX])| {
            push_towards(
                self.model,
                lp,
                seed,
                &face.direction::<NX>(),
                &region,
                &self.sets[set],
            )
        };
        // Each push is independent of the others (it starts its LPs afresh), so the points do not
        // depend on how the pushes are spread over threads.
        let found: Vec<Option<[f64; NX]>> = if self.settings.parallel {
            seeds
                .par_iter()
                .map_init(PushEngines::default, push)
                .collect()
        } else {
            let mut lp = PushEngines::default();
            seeds.iter().map(|s| push(&mut lp, s)).collect()
        };
        found.into_iter().flatten().collect()
    }

    /// Runs refinement rounds until every face is satisfied or a budget is spent. Returns whether
    /// it converged and the number of rounds.
    fn run(&mut self, start: Instant) -> (bool, usize) {
        let mut rounds = 0;
        loop {
            self.retire();
            let faces: Vec<Face> = Face::all(NX).filter(|f| self.face_open(*f)).collect();
            // Per open face, the box that attains it.
            let mut picked: Vec<(usize, Vec<Face>)> = Vec::new();
            for face in &faces {
                let best = self
                    .cover
                    .iter()
                    .enumerate()
                    .filter(|(_, p)| !p.atomic)
                    .max_by(|a, b| {
                        face.reach(&a.1.b[face.j])
                            .total_cmp(&face.reach(&b.1.b[face.j]))
                    });
                let Some((i, p)) = best else { continue };
                if face.reach(&p.b[face.j]) <= self.threshold(*face) {
                    continue;
                }
                match picked.iter_mut().find(|(k, _)| *k == i) {
                    Some((_, fs)) => fs.push(*face),
                    None => picked.push((i, vec![*face])),
                }
            }
            if picked.is_empty() {
                // Either every face is satisfied, or the open ones are held by boxes too small
                // to split.
                return (faces.is_empty(), rounds);
            }
            let over_time = self
                .settings
                .hull_max_seconds
                .is_some_and(|s| start.elapsed().as_secs_f64() >= s);
            if self.contracted + 2 * picked.len() > self.settings.hull_max_boxes || over_time {
                return (false, rounds);
            }
            rounds += 1;
            self.refine(&picked);
        }
    }

    /// Whether a face is not yet within tolerance of the inner bound.
    fn face_open(&self, face: Face) -> bool {
        let Some(outer) = self.outer() else {
            return false;
        };
        face.reach(&outer[face.j]) > self.threshold(face)
    }

    /// Moves boxes that no open face can pick into the retired hull.
    fn retire(&mut self) {
        if self.inner.is_none() {
            return;
        }
        let thresholds: Vec<(Face, f64)> = Face::all(NX).map(|f| (f, self.threshold(f))).collect();
        let mut retired = self.retired;
        let retired_sets = &mut self.retired_sets;
        let retired_pieces = &mut self.retired_pieces;
        self.cover.retain(|p| {
            let reaches = thresholds.iter().any(|(f, t)| f.reach(&p.b[f.j]) > *t);
            if !reaches {
                retired_sets[p.set] = true;
                retired_pieces.push(p.clone());
                retired = Some(match retired {
                    None => p.b,
                    Some(h) => core::array::from_fn(|j| h[j].hull(p.b[j])),
                });
            }
            reaches
        });
        self.retired = retired;
    }

    /// Splits the picked boxes, contracts the halves in parallel, replaces the boxes by the
    /// surviving halves and pushes their LP extreme points towards the picking faces.
    fn refine(&mut self, picked: &[(usize, Vec<Face>)]) {
        let outer = self.outer().unwrap_or(*self.x0);
        let mut jobs: Vec<Job<'_, NX>> = Vec::with_capacity(2 * picked.len());
        let mut atomic = Vec::new();
        // Across a picked face where the second-order certificate can prove the outer half
        // empty; across the widest parameter otherwise (on the Gough leg, a scalar model without
        // it, face splits made `gough certify` on sample21 hundreds of times slower;
        // `benches/README.md`).
        let face_splits = self.model.curvature().is_some();
        for (i, faces) in picked {
            let Piece { b, set, bases, .. } = &self.cover[*i];
            let across_face = faces
                .iter()
                .filter(|_| face_splits)
                .filter_map(|f| split_at_face(b, *f, self.inner.as_ref(), &outer))
                .max_by(|a, c| a.0.total_cmp(&c.0))
                .map(|(_, halves)| halves);
            match across_face.or_else(|| split_widest(b, &outer)) {
                Some((l, r)) => {
                    jobs.push((l, faces, *set, Arc::clone(bases)));
                    jobs.push((r, faces, *set, Arc::clone(bases)));
                }
                None => atomic.push(*i),
            }
        }
        for i in atomic {
            self.cover[i].atomic = true;
        }
        let inner = self.inner;
        let work = |ws: &mut Workspace<NX>, (b, faces, set, bases): &Job<'_, NX>| {
            let c = contract_from(self.model, b, &self.sets[*set], self.settings, ws, bases);
            let Ok(child) = c.result else {
                return None;
            };
            // Seeds: the child's LP extreme points that reach beyond the inner bound.
            let seeds: Vec<(Face, [f64; NX])> = if c.iterations > 0 && self.settings.inner_bounds {
                faces
                    .iter()
                    .map(|f| (*f, ws.extreme_points[f.slot()]))
                    .filter(|(f, p)| match &inner {
                        None => true,
                        Some(h) => f.reach(&Interval::point(p[f.j])) > f.reach(&h[f.j]),
                    })
                    .collect()
            } else {
                Vec::new()
            };
            let bases = Arc::new(ws.lp_memory());
            let points = self.push_all(&child, &seeds, *set);
            // A half with no certified point may hold none: the second-order certificate decides
            // where the relaxation is too loose (it returns at once where the half's Chebyshev
            // fit already fits the data).
            if points.is_empty()
                && self
                    .model
                    .curvature()
                    .and_then(|k| second_order_emptiness(self.model, k, &child, &self.sets[*set]))
                    .is_some()
            {
                return None;
            }
            Some((child, points, *set, bases))
        };
        let results: Vec<Option<Refined<NX>>> = if self.settings.parallel {
            jobs.par_iter()
                .map_init(|| Workspace::with_backend((self.engine)()), work)
                .collect()
        } else {
            let mut ws = Workspace::with_backend((self.engine)());
            jobs.iter().map(|j| work(&mut ws, j)).collect()
        };
        self.contracted += jobs.len();
        let mut replaced: Vec<usize> = picked
            .iter()
            .map(|(i, _)| *i)
            .filter(|i| !self.cover[*i].atomic)
            .collect();
        replaced.sort_unstable();
        for i in replaced.into_iter().rev() {
            self.cover.swap_remove(i);
        }
        for (child, points, set, bases) in results.into_iter().flatten() {
            self.cover.push(Piece {
                b: child,
                atomic: false,
                set,
                bases,
            });
            self.add_points(&points, set);
        }
    }
}

/// Splits `b` across the parameter of `face`, halfway between the inner bound's face and `b`'s
/// own: the half beyond holds no certified point yet, and where the relaxation is too loose to
/// contract it the second-order certificate may prove it empty (on the real UR10 at 1.05 `s*`, a
/// slab of `tool_z` between the prior's face and the inner bound: `benches/README.md`). With the
/// gap's share of the outer width (the larger, the more the face can gain); `None` when `b` does
/// not reach beyond the inner bound there.
fn split_at_face<const NX: usize>(
    b: &[Interval; NX],
    face: Face,
    inner: Option<&[Interval; NX]>,
    outer: &[Interval; NX],
) -> Option<(f64, Halves<NX>)> {
    let j = face.j;
    let (lo, hi) = (b[j].inf(), b[j].sup());
    let (gap, cut) = if face.upper {
        let f = inner?[j].sup().max(lo);
        (hi - f, 0.5 * (f + hi))
    } else {
        let f = inner?[j].inf().min(hi);
        (f - lo, 0.5 * (lo + f))
    };
    if !(lo < cut && cut < hi) {
        return None;
    }
    let (mut l, mut r) = (*b, *b);
    l[j] = Interval::new(lo, cut);
    r[j] = Interval::new(cut, hi);
    Some((gap / outer[j].wid().max(f64::MIN_POSITIVE), (l, r)))
}

/// The two halves of a split box.
type Halves<const NX: usize> = ([Interval; NX], [Interval; NX]);

/// A contracted half, the certified points pushed from its LP extreme points, and its subset.
type Refined<const NX: usize> = ([Interval; NX], Vec<[f64; NX]>, usize, Arc<LpMemory>);

/// A half to contract: its box, the faces that picked its parent, its subset and the parent's
/// LP bases.
type Job<'a, const NX: usize> = ([Interval; NX], &'a [Face], usize, Arc<LpMemory>);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_models::{Hyperplane, HYPERPLANE_DIM as N};
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    /// Above the small engine's size (the scaled simplex, whose bases the halves inherit, and the
    /// interior-point pushes) the hull still does not depend on the thread schedule, contracts
    /// boxes with inherited bases, and keeps the truth.
    #[test]
    fn inherited_bases_keep_large_hulls_independent_of_threads() {
        let mut rng = StdRng::seed_from_u64(3);
        let truth: [f64; N] = core::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let x0: [Interval; N] = truth.map(|t| Interval::new(t - 0.3, t + 0.3));
        let measurements: Vec<[Interval; N + 1]> = (0..40)
            .map(|_| {
                let a: [f64; N] = core::array::from_fn(|_| rng.random_range(-1.0..1.0));
                let v: f64 = a.iter().zip(&truth).map(|(p, q)| p * q).sum::<f64>();
                // Coefficients known within ±0.002: the relaxation is not exact, boxes split.
                core::array::from_fn(|j| {
                    if j < N {
                        Interval::new(a[j] - 0.002, a[j] + 0.002)
                    } else {
                        Interval::new(v - 0.01, v + 0.01)
                    }
                })
            })
            .collect();
        let settings = Settings::default()
            .with_hull_tolerance(0.01)
            .with_hull_budget(24, None);
        let parallel = hull(&Hyperplane, &x0, &measurements, &settings);
        let serial = hull(
            &Hyperplane,
            &x0,
            &measurements,
            &settings.clone().with_parallel(false),
        );
        assert!(parallel.boxes_contracted > 1, "no box was split");
        assert_eq!(parallel.outer, serial.outer);
        assert_eq!(parallel.inner, serial.inner);
        assert_eq!(parallel.boxes_contracted, serial.boxes_contracted);
        assert!(parallel
            .outer
            .iter()
            .zip(&truth)
            .all(|(o, t)| o.contains(*t)));
    }
}
