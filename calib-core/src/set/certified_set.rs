//! The certified set: every parameter vector consistent with the measurements, as a finite union
//! of polyhedra, each valid on its box — not only the box around them.
//!
//! # What it is
//!
//! [`crate::certify`] and [`crate::hull`] keep a [`Cover`]: boxes `X_1 … X_r` whose union
//! contains every solution of the initial box (paper eq. 5: `x` with `f(x, M_k) = 0` for some
//! `M_k` in each measurement box). On each box the Newton step's relaxation (paper eqs. 6–7 and
//! the corner rows of [`crate::Relaxation`], or the affine forms of a vector model) gives linear
//! inequalities `G_i y <= g_i` in `y = x - c_i` (`c_i = mid(X_i)`) that every solution in `X_i`
//! satisfies. So
//!
//! `S ⊆ ∪_i { x ∈ X_i : G_i (x - c_i) <= g_i }`,
//!
//! which is what a [`CertifiedSet`] holds: its [`SetPiece`]s. Where the data fix a combination of
//! parameters that no single parameter shows (a Gough leg's `a_z + l - b_z`, an arm's base and
//! first joint together), the polyhedra keep it: a box cannot.
//!
//! # The maximum of a function over the set
//!
//! For `g` with slopes `s_j ⊇ ∂g/∂x_j` over a piece and any point `z`, the mean-value theorem gives
//! `g(x) ∈ g(z) + Σ_j s_j (x_j - z_j)`. With `x_j - z_j = y_j + (c_j - z_j)` and
//! `s_j = mid(s_j) + [-rad(s_j), rad(s_j)]`,
//!
//! `g(x) <= sup g(z) + max_{y ∈ P} mid(s)·y + Σ_j rad(s_j) mag(Y_j) + sup Σ_j s_j (c_j - z_j)`
//!
//! where `P` is the piece's polyhedron and `Y` its box. The linear program's answer is only a
//! hint: the bound uses the Neumaier–Shcherbina safe bound of its multipliers
//! ([`crate::lp::safe_lower_bound`]), valid whatever the engine returned. The largest bound over
//! the pieces bounds `max_S g` ([`SetQuery::max_linear`], [`maximize_over_set`]).
//!
//! The lower bound is attained: a parameter vector proved consistent with every measurement
//! ([`crate::is_consistent_point`]: a sign test, or the coupled existence test of
//! [`crate::proof::existence`]) at which `g` is evaluated rigorously. Such points are found by
//! pushing a certified point along the objective's gradient with successive linear programs, each
//! step kept only when its point is certified ([`CertifiedSet::extreme_point`]). The truth lies
//! between the two bounds.
//!
//! [`maximize_over_set`] refines the pieces where the upper bound is attained (split at the
//! widest side, both halves contracted by the Newton step, halves proved empty dropped) until the
//! bracket meets its tolerance or a budget is spent.

use super::curvature_rows::{with_curvature_rows, HessianOverBox, Hessians};
use crate::kernel::bisection::split_widest;
use crate::kernel::contract::{build_relaxation, contract, Workspace};
use crate::kernel::cover::hull_of;
use crate::kernel::farthest_point::{push_towards, PushEngines};
use crate::lp::{safe_lower_bound, DenseSimplex, LpBackend, LpStatus, Polyhedron};
use crate::{is_consistent_point, Cover, Interval, Relaxation, Settings, VectorModel};

/// One piece of a [`CertifiedSet`]: a box and a polyhedron that every solution in the box
/// satisfies (see the module documentation).
#[derive(Clone, Debug)]
pub struct SetPiece<const NX: usize> {
    bounds: [Interval; NX],
    centre: [f64; NX],
    /// In `y = x - centre`, over the box `bounds - centre` (rounded outward).
    poly: Polyhedron,
    subset: usize,
    /// Whether `poly` holds the second-order Taylor rows ([`CertifiedSet::add_curvature_rows`]).
    second_order: bool,
}

impl<const NX: usize> SetPiece<NX> {
    /// The piece's box.
    pub fn bounds(&self) -> &[Interval; NX] {
        &self.bounds
    }

    /// The centre `c` of the polyhedron's coordinates `y = x - c` (the box's midpoint).
    pub fn centre(&self) -> &[f64; NX] {
        &self.centre
    }

    /// The polyhedron in `y = x - centre`.
    pub fn polyhedron(&self) -> &Polyhedron {
        &self.poly
    }

    /// The measurement subset whose solutions it covers (see [`Cover`]).
    pub fn subset(&self) -> usize {
        self.subset
    }

    /// Whether `x` satisfies the piece's inequalities (in floating point, with a relative slack
    /// `tol`): a quick test for sampling, not a proof.
    pub fn admits(&self, x: &[f64; NX], tol: f64) -> bool {
        if !(0..NX).all(|j| self.bounds[j].contains(x[j])) {
            return false;
        }
        let y: [f64; NX] = core::array::from_fn(|j| x[j] - self.centre[j]);
        (0..self.poly.rows()).all(|i| {
            let row = self.poly.row(i);
            let v: f64 = row.iter().zip(&y).map(|(a, y)| a * y).sum();
            let scale: f64 = row.iter().zip(&y).map(|(a, y)| (a * y).abs()).sum();
            v <= self.poly.rhs(i) + tol * (scale + self.poly.rhs(i).abs() + 1.0)
        })
    }
}

/// A parameter vector proved consistent with every measurement of a subset.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CertifiedPoint<const NX: usize> {
    /// The parameter vector.
    pub x: [f64; NX],
    /// The measurement subset it fits (see [`Cover`]).
    pub subset: usize,
}

/// Every parameter vector consistent with the measurements, as a union of polyhedra each valid on
/// its box, with the measurement boxes and certified points of the set (see the module
/// documentation).
#[derive(Clone, Debug)]
pub struct CertifiedSet<const NX: usize, const NM: usize> {
    pieces: Vec<SetPiece<NX>>,
    measurements: Vec<[Interval; NM]>,
    dropped: Vec<Vec<usize>>,
    points: Vec<CertifiedPoint<NX>>,
}

/// At most this many pieces by default ([`CertifiedSet::new`]): each query solves one linear
/// program per piece.
pub const DEFAULT_MAX_PIECES: usize = 32;

impl<const NX: usize, const NM: usize> CertifiedSet<NX, NM> {
    /// The set of a certification's `cover` against `measurements` (the boxes it was certified
    /// against, all of them: each subset's drops are taken from the cover): the boxes are grouped
    /// into at most `max_pieces` pieces (each group's hull, per subset: a union of hulls still
    /// contains every solution), and each piece gets the Newton step's relaxation over its box.
    /// Pieces the relaxation proves empty are left out. `points` are kept when they are certified
    /// consistent with some subset.
    pub fn new<M, const NR: usize>(
        model: &M,
        cover: &Cover<NX>,
        measurements: &[[Interval; NM]],
        points: &[[f64; NX]],
        max_pieces: usize,
    ) -> Self
    where
        M: VectorModel<NX, NM, NR>,
    {
        let mut set = CertifiedSet {
            pieces: Vec::new(),
            measurements: measurements.to_vec(),
            dropped: cover.dropped.clone(),
            points: Vec::new(),
        };
        if set.dropped.is_empty() {
            set.dropped.push(Vec::new());
        }
        let subsets = set.dropped.len();
        let share = max_pieces.max(subsets) / subsets;
        for s in 0..subsets {
            let boxes: Vec<[Interval; NX]> = cover
                .boxes
                .iter()
                .zip(&cover.subsets)
                .filter(|(_, &k)| k == s)
                .map(|(b, _)| *b)
                .collect();
            let merged = boxes.len() > share.max(1);
            for b in coalesce(boxes, share.max(1)) {
                // A group's hull holds more than its boxes: one contraction takes it back
                // towards them (every solution in the hull is kept).
                let b = if merged {
                    let kept = set.subset_measurements(s);
                    let mut ws = Workspace::new(&Settings::default());
                    match contract(model, &b, &kept, &Settings::default(), &mut ws).result {
                        Ok(c) => c,
                        Err(_) => continue,
                    }
                } else {
                    b
                };
                set.push_piece(model, b, s);
            }
        }
        for p in points {
            set.add_point(model, p);
        }
        set
    }

    /// Adds the piece of box `b` for subset `s` (nothing when its relaxation proves it empty).
    fn push_piece<M, const NR: usize>(&mut self, model: &M, b: [Interval; NX], s: usize)
    where
        M: VectorModel<NX, NM, NR>,
    {
        if b.iter().any(|v| v.is_empty() || !v.is_bounded()) {
            return;
        }
        let kept = self.subset_measurements(s);
        let mut poly = Polyhedron::default();
        // Both families of rows (centred and corner forms): the tightest relaxation the kernel
        // has; vector models with affine forms use those rows instead.
        if let Ok(centre) = build_relaxation(model, &b, &kept, Relaxation::Both, 1, &mut poly) {
            if poly.rows() <= MAX_PRUNED_ROWS {
                poly = without_redundant_rows(&poly);
            }
            self.pieces.push(SetPiece {
                bounds: b,
                centre: centre.map(|v| v.mid()),
                poly,
                subset: s,
                second_order: false,
            });
        }
    }

    /// Adds to every piece's polyhedron that has none yet (pieces refined since the last call
    /// get theirs) the second-order Taylor rows of `model` about the piece's centre `c`: for each measurement box `M` (midpoint `M̂`) and residual row `r`,
    /// with `y = x - c` and `Δz = (y, M - M̂)`,
    ///
    /// `f_r(x, M) = f_r(c, M̂) + ∇_x f_r·y + ∇_M f_r·(M - M̂) + ½ Δzᵀ H_r(ξ) Δz`,
    ///
    /// the Hessian over the box enclosed as `H_r(c, M̂)` plus its third-order change
    /// ([`crate::Curvature`]), every constant part (the value, the measurement's terms, the
    /// gradient's enclosure radii, the quadratic form) gathered in an interval `C_r`: a
    /// consistent `x` satisfies `-sup C_r <= g·y <= -inf C_r`, `g` the gradient's midpoints.
    /// Valid on the piece's box, so every solution stays; tighter than the relaxation's rows
    /// where the box is wide and the model curved (a real arm's prior, whose affine forms add
    /// up every operation's remainder). Each measurement's rows open its group, so that they are
    /// its own rows for [`CertifiedSet::query_own_rows`]. Two Hessian enclosures per
    /// measurement and piece; nothing for a model without them ([`VectorModel::curvature`]) or
    /// a measurement with more than [`crate::MAX_CURVATURE_SYMBOLS`] symbols of nonzero width.
    pub fn add_curvature_rows<M, const NR: usize>(&mut self, model: &M)
    where
        M: VectorModel<NX, NM, NR> + Sync,
    {
        let Some(curvature) = model.curvature() else {
            return;
        };
        self.add_rows(model, Hessians::Curvature(curvature));
    }

    /// [`CertifiedSet::add_curvature_rows`] with the Hessians over each piece's box from the
    /// robot's own enclosure `hessian` (for a model without `#[interval_model(curvature)]`: a
    /// scalar residual evaluated over second-order jets, say).
    pub fn add_second_order_rows<M, const NR: usize>(
        &mut self,
        model: &M,
        hessian: &HessianOverBox<NX, NM>,
    ) where
        M: VectorModel<NX, NM, NR> + Sync,
    {
        self.add_rows(model, Hessians::OverBox(hessian));
    }

    /// The Taylor rows from `hessians` on every piece that has none yet.
    fn add_rows<M, const NR: usize>(&mut self, model: &M, hessians: Hessians<'_, NX, NM, NR>)
    where
        M: VectorModel<NX, NM, NR> + Sync,
    {
        for i in 0..self.pieces.len() {
            if self.pieces[i].second_order {
                continue;
            }
            let kept = self.subset_measurements(self.pieces[i].subset);
            let piece = &mut self.pieces[i];
            piece.second_order = true;
            piece.poly = with_curvature_rows(
                model,
                hessians,
                &piece.bounds,
                &piece.centre,
                &kept,
                &piece.poly,
            );
        }
    }

    /// The measurements of subset `s` (all but its dropped ones).
    pub fn subset_measurements(&self, s: usize) -> Vec<[Interval; NM]> {
        let drop = &self.dropped[s];
        self.measurements
            .iter()
            .enumerate()
            .filter(|(k, _)| drop.binary_search(k).is_err())
            .map(|(_, m)| *m)
            .collect()
    }

    /// Keeps `x` as a certified point when it is proved consistent with one of the subsets;
    /// returns whether it was.
    pub fn add_point<M, const NR: usize>(&mut self, model: &M, x: &[f64; NX]) -> bool
    where
        M: VectorModel<NX, NM, NR>,
    {
        if self.points.iter().any(|p| p.x == *x) {
            return true;
        }
        for s in 0..self.dropped.len() {
            if is_consistent_point(model, x, &self.subset_measurements(s)) {
                self.points.push(CertifiedPoint { x: *x, subset: s });
                return true;
            }
        }
        false
    }

    /// Whether no piece is left: every solution was proved absent (the data are inconsistent).
    pub fn is_empty(&self) -> bool {
        self.pieces.is_empty()
    }

    /// The pieces.
    pub fn pieces(&self) -> &[SetPiece<NX>] {
        &self.pieces
    }

    /// The measurement boxes the set was certified against.
    pub fn measurements(&self) -> &[[Interval; NM]] {
        &self.measurements
    }

    /// The certified points held (each proved consistent with its subset).
    pub fn points(&self) -> &[CertifiedPoint<NX>] {
        &self.points
    }

    /// The measurements subset `s` drops (0-based).
    pub fn dropped(&self, s: usize) -> &[usize] {
        &self.dropped[s]
    }

    /// The hull of the pieces' boxes: a box containing the set (`None` when it is empty).
    pub fn outer(&self) -> Option<[Interval; NX]> {
        hull_of(self.pieces.iter().map(|p| &p.bounds))
    }

    /// The pieces' boxes as a [`Cover`] (what a file stores to rebuild the set).
    pub fn cover(&self) -> Cover<NX> {
        Cover {
            boxes: self.pieces.iter().map(|p| p.bounds).collect(),
            subsets: self.pieces.iter().map(|p| p.subset).collect(),
            dropped: self.dropped.clone(),
        }
    }

    /// Whether `x` satisfies some piece's inequalities (floating point, relative slack `tol`): a
    /// necessary condition for consistency, for sampling the set in tests.
    pub fn admits(&self, x: &[f64; NX], tol: f64) -> bool {
        self.pieces.iter().any(|p| p.admits(x, tol))
    }

    /// A query context: one LP engine (the dense simplex) per piece, so that successive
    /// queries warm-start.
    pub fn query(&self) -> SetQuery<'_, NX, NM> {
        self.query_with(&|| Box::new(DenseSimplex::default()))
    }

    /// [`CertifiedSet::query`] with the LP engines of an earlier query ([`SetQuery::into_engines`]),
    /// one per piece (more are made when there are too few): no allocation, and an engine whose
    /// last program was on the same piece warm-starts from it (engines recognise their
    /// polyhedron, so an engine from another set only starts cold).
    pub fn query_reusing(&self, mut engines: Vec<Box<dyn LpBackend>>) -> SetQuery<'_, NX, NM> {
        while engines.len() < self.pieces.len() {
            engines.push(Box::new(DenseSimplex::default()));
        }
        SetQuery {
            set: self,
            engines,
            working: vec![None; self.pieces.len()],
            order: Vec::new(),
            dual: Vec::new(),
            primal: [0.0; NX],
            own_rows: false,
        }
    }

    /// [`CertifiedSet::query`] with the LP engines made by `engine`. Any engine is safe: its
    /// answers are hints that only decide how tight the rigorous bounds are.
    pub fn query_with(&self, engine: &dyn Fn() -> Box<dyn LpBackend>) -> SetQuery<'_, NX, NM> {
        SetQuery {
            set: self,
            engines: (0..self.pieces.len()).map(|_| engine()).collect(),
            working: vec![None; self.pieces.len()],
            order: Vec::new(),
            dual: Vec::new(),
            primal: [0.0; NX],
            own_rows: false,
        }
    }

    /// A query over a relaxation of the set: each piece's polyhedron with only the rows of each
    /// measurement's own residuals (not the combinations that couple them), solved once per query
    /// and warm-started from the previous query on the same piece. Fewer rows make a larger
    /// polyhedron, so every bound stays valid for the set; on the arms measured the first program
    /// over these rows is within 0.02% of the whole program's bound (see
    /// [`SetQuery::max_linear`]), at a fraction of its cost — for long runs of related queries
    /// (the accuracy certificates' branch and bound).
    pub fn query_own_rows(&self) -> SetQuery<'_, NX, NM> {
        let mut q = self.query();
        q.own_rows = true;
        q
    }

    /// A certified point that makes `direction·x` large: the held point with the largest value,
    /// pushed along `direction` by successive linear programs inside the set's outer box (each
    /// step certified); the point is also kept in the set. `None` when the set holds no point.
    pub fn extreme_point<M, const NR: usize>(
        &mut self,
        model: &M,
        direction: &[f64; NX],
    ) -> Option<[f64; NX]>
    where
        M: VectorModel<NX, NM, NR>,
    {
        let dot = |x: &[f64; NX]| -> f64 { direction.iter().zip(x).map(|(a, b)| a * b).sum() };
        let start = *self
            .points
            .iter()
            .max_by(|a, b| dot(&a.x).total_cmp(&dot(&b.x)))?;
        let region = self.outer()?;
        let kept = self.subset_measurements(start.subset);
        let mut lp = PushEngines::default();
        let pushed = push_towards(model, &mut lp, &start.x, direction, &region, &kept)?;
        if dot(&pushed) > dot(&start.x) {
            self.points.push(CertifiedPoint {
                x: pushed,
                subset: start.subset,
            });
            Some(pushed)
        } else {
            Some(start.x)
        }
    }

    /// Refines piece `i`: its box split at the widest side (relative to the set's outer box) and
    /// both halves contracted by the Newton step; the halves not proved empty replace it. Returns
    /// whether the piece could be split.
    pub fn refine<M, const NR: usize>(&mut self, model: &M, i: usize, settings: &Settings) -> bool
    where
        M: VectorModel<NX, NM, NR>,
    {
        let Some(reference) = self.outer() else {
            return false;
        };
        let piece = &self.pieces[i];
        let Some((l, r)) = split_widest(&piece.bounds, &reference) else {
            return false;
        };
        let s = piece.subset;
        let kept = self.subset_measurements(s);
        let mut ws = Workspace::new(settings);
        let halves: Vec<[Interval; NX]> = [l, r]
            .iter()
            .filter_map(|h| contract(model, h, &kept, settings, &mut ws).result.ok())
            .collect();
        self.pieces.swap_remove(i);
        for h in halves {
            self.push_piece(model, h, s);
        }
        true
    }
}

/// Pieces with at most this many rows have their redundant rows removed (one linear program
/// per row, once): every later query on the piece is faster.
const MAX_PRUNED_ROWS: usize = 400;

/// `p` without the rows the others and the box already imply: row `i` is dropped when the safe
/// bound of `max G_i·y` over the remaining rows is at most `g_i`, a proof that the row cuts
/// nothing off (dropping a row could never lose a solution anyway; the proof keeps the
/// polyhedron as tight as it was).
fn without_redundant_rows(p: &Polyhedron) -> Polyhedron {
    let n = p.dim();
    let frozen: Vec<Option<f64>> = (0..n)
        .map(|j| p.is_frozen(j).then(|| p.lo()[j].abs().max(p.hi()[j].abs())))
        .collect();
    let build = |keep: &[bool]| {
        let mut q = Polyhedron::default();
        q.reset(p.lo(), p.hi());
        for (j, f) in frozen.iter().enumerate() {
            if let Some(m) = f {
                q.freeze(j, *m);
            }
        }
        for i in (0..p.rows()).filter(|&i| keep[i]) {
            q.push_row(p.row(i), p.rhs(i));
        }
        q
    };
    let mut keep = vec![true; p.rows()];
    let mut lp = DenseSimplex::default();
    let mut primal = vec![0.0; n];
    for i in 0..p.rows() {
        keep[i] = false;
        let q = build(&keep);
        let objective: Vec<f64> = p.row(i).iter().map(|v| -v).collect();
        let mut dual = vec![0.0; q.rows()];
        lp.minimize(&q, &objective, &mut dual, &mut primal);
        let max = -safe_lower_bound(&q, &objective, &dual);
        // NaN (a failed bound) keeps the row.
        keep[i] = max.partial_cmp(&p.rhs(i)).is_none_or(|o| o.is_gt());
    }
    build(&keep)
}

/// Groups `boxes` into at most `k` hulls: a k-d split of the list at the median of the centres
/// along the hull's widest side, until each group is one of `k` (sound: every box lies in its
/// group's hull).
fn coalesce<const NX: usize>(boxes: Vec<[Interval; NX]>, k: usize) -> Vec<[Interval; NX]> {
    if boxes.len() <= k {
        return boxes;
    }
    if k <= 1 {
        return hull_of(boxes.iter()).into_iter().collect();
    }
    let hull = hull_of(boxes.iter()).expect("more than k >= 2 boxes");
    let j = (0..NX)
        .max_by(|&a, &b| hull[a].wid().total_cmp(&hull[b].wid()))
        .unwrap_or(0);
    let mut boxes = boxes;
    boxes.sort_by(|a, b| a[j].mid().total_cmp(&b[j].mid()));
    let right = boxes.split_off(boxes.len() / 2);
    let mut out = coalesce(boxes, k / 2);
    out.extend(coalesce(right, k - k / 2));
    out
}

/// Queries of a [`CertifiedSet`] over its own rows ([`CertifiedSet::query_own_rows`]), one per
/// *slot*: a caller that asks the same kind of question again and again (the same coordinate
/// and sign of a prediction at the next configuration, the same axis of an error at the next
/// box) gives it the same slot, and each program warm-starts from its slot's previous one. A
/// slot's query is made when first asked.
pub struct SlotQueries<'a, const NX: usize, const NM: usize> {
    set: &'a CertifiedSet<NX, NM>,
    slots: Vec<Option<SetQuery<'a, NX, NM>>>,
    /// Whether the programs take the measurements' own rows only.
    own_rows: bool,
}

impl<'a, const NX: usize, const NM: usize> SlotQueries<'a, NX, NM> {
    /// `slots` slots over `set`.
    pub fn new(set: &'a CertifiedSet<NX, NM>, slots: usize) -> Self {
        SlotQueries {
            set,
            slots: (0..slots).map(|_| None).collect(),
            own_rows: true,
        }
    }

    /// `slots` slots over `set`, each program over the pieces' whole polyhedra
    /// ([`CertifiedSet::query`]): tighter than the own rows where a scalar residual couples many
    /// measured quantities (a hexapod leg's), at the cost of more rows.
    pub fn with_all_rows(set: &'a CertifiedSet<NX, NM>, slots: usize) -> Self {
        SlotQueries {
            own_rows: false,
            ..SlotQueries::new(set, slots)
        }
    }

    /// An upper bound of `Σ_j s_j (x_j - about_j)` over the set ([`SetQuery::max_linear`]), by
    /// slot `slot`'s program.
    ///
    /// # Panics
    ///
    /// If `slot` is not below the number of slots.
    pub fn max_linear(&mut self, slot: usize, slopes: &[Interval; NX], about: &[f64; NX]) -> f64 {
        let (set, own_rows) = (self.set, self.own_rows);
        self.slots[slot]
            .get_or_insert_with(|| {
                if own_rows {
                    set.query_own_rows()
                } else {
                    set.query()
                }
            })
            .max_linear(slopes, about)
            .upper
    }
}

/// An upper bound of a linear function over the set, and where the linear program found it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinearMax<const NX: usize> {
    /// Proved: the function is at most this over every piece (`-∞` for an empty set).
    pub upper: f64,
    /// The piece whose bound is `upper`.
    pub piece: Option<usize>,
    /// That piece's LP optimum (in `x`), a hint for the lower bound (not a certified point).
    pub argmax: Option<[f64; NX]>,
}

/// Queries on a [`CertifiedSet`] with reusable LP engines (one per piece, warm-started from the
/// previous query on the same piece).
pub struct SetQuery<'a, const NX: usize, const NM: usize> {
    set: &'a CertifiedSet<NX, NM>,
    engines: Vec<Box<dyn LpBackend>>,
    /// Per piece solved by row generation, its working subset of rows and their polyhedron
    /// (rebuilt only when rows are added, so that the engine warm-starts between queries).
    working: Vec<Option<(Vec<usize>, Polyhedron)>>,
    /// The pieces' box bounds and indices, largest first ([`SetQuery::max_linear`]).
    order: Vec<(f64, usize)>,
    dual: Vec<f64>,
    primal: [f64; NX],
    /// Whether only the measurements' own rows are used ([`CertifiedSet::query_own_rows`]).
    own_rows: bool,
}

impl<const NX: usize, const NM: usize> SetQuery<'_, NX, NM> {
    /// The query's LP engines, for [`CertifiedSet::query_reusing`].
    pub fn into_engines(self) -> Vec<Box<dyn LpBackend>> {
        self.engines
    }

    /// An upper bound of `Σ_j s_j (x_j - z_j)` over the set, where `slopes` `s_j` are intervals
    /// (see the module documentation: the midpoints enter a linear program per piece, the radii
    /// are bounded over each piece's box).
    ///
    /// Each piece's bound is the smaller of its program's and its box's (interval arithmetic
    /// over the piece's box, which contains it). Pieces are visited by their box bound, largest
    /// first, and the visit stops at the first whose box bound is not above the best bound so
    /// far: it and every later piece are bounded by it. So a set refined into many small pieces
    /// solves programs only where the maximum may lie, and the bound is the same as if every
    /// piece were solved.
    pub fn max_linear(&mut self, slopes: &[Interval; NX], about: &[f64; NX]) -> LinearMax<NX> {
        let mut best = LinearMax {
            upper: f64::NEG_INFINITY,
            piece: None,
            argmax: None,
        };
        let mut order = core::mem::take(&mut self.order);
        order.clear();
        order.extend(self.set.pieces.iter().enumerate().map(|(i, piece)| {
            let bound = (0..NX)
                .fold(Interval::ZERO, |s, j| {
                    s + slopes[j] * (piece.bounds[j] - Interval::point(about[j]))
                })
                .sup();
            (if bound.is_nan() { f64::INFINITY } else { bound }, i)
        }));
        order.sort_unstable_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        for &(by_box, i) in &order {
            if best.piece.is_some() && by_box <= best.upper {
                break;
            }
            let (by_program, argmax) = self.piece_max(i, slopes, about);
            let upper = by_program.min(by_box);
            if upper > best.upper || best.piece.is_none() {
                best = LinearMax {
                    upper,
                    piece: Some(i),
                    argmax,
                };
            }
        }
        self.order = order;
        best
    }

    /// An upper bound of `w·x` over the set (its support function in direction `w`).
    pub fn support(&mut self, w: &[f64; NX]) -> f64 {
        self.max_linear(&w.map(Interval::point), &[0.0; NX]).upper
    }

    /// The range of `w·x` over the set: `[-support(-w), support(w)]`.
    pub fn range(&mut self, w: &[f64; NX]) -> Interval {
        let hi = self.support(w);
        let lo = -self.support(&w.map(|v| -v));
        if self.set.is_empty() {
            Interval::EMPTY
        } else {
            Interval::new(lo, hi)
        }
    }

    /// The bound of [`SetQuery::max_linear`] over piece `i`, and the LP's optimum.
    pub fn piece_max(
        &mut self,
        i: usize,
        slopes: &[Interval; NX],
        about: &[f64; NX],
    ) -> (f64, Option<[f64; NX]>) {
        let piece = &self.set.pieces[i];
        let p = &piece.poly;
        // Σ s_j (c_j - z_j) + Σ rad(s_j) mag(Y_j), rounded up.
        let mut fixed = Interval::ZERO;
        let mut objective = [0.0; NX];
        for j in 0..NX {
            let d = Interval::point(piece.centre[j]) - Interval::point(about[j]);
            fixed += slopes[j] * d;
            let y = Interval::new(p.lo()[j], p.hi()[j]);
            if p.is_frozen(j) {
                // A frozen variable is not an LP column: its whole term is bounded by the box.
                fixed += slopes[j] * y;
            } else {
                objective[j] = -slopes[j].mid();
                let spread = Interval::point(slopes[j].rad()) * Interval::point(y.mag());
                fixed += Interval::new(0.0, spread.sup());
            }
        }
        let (status, lower) = if self.own_rows {
            let (_, subset) = self.working[i].get_or_insert_with(|| own_rows_of(p));
            self.dual.resize(subset.rows(), 0.0);
            let status =
                self.engines[i].minimize(subset, &objective, &mut self.dual, &mut self.primal);
            (status, safe_lower_bound(subset, &objective, &self.dual))
        } else if p.rows() > ROW_GENERATION_ROWS {
            // A cold start: successive queries point in unrelated (often opposite) directions,
            // and a walk from the last optimum measured slower than the dual simplex from the
            // box.
            self.engines[i].forget();
            self.solve_by_row_generation(i, &objective)
        } else {
            self.engines[i].forget();
            self.dual.resize(p.rows(), 0.0);
            let status = self.engines[i].minimize(p, &objective, &mut self.dual, &mut self.primal);
            (status, safe_lower_bound(p, &objective, &self.dual))
        };
        if lower == f64::INFINITY {
            // The multipliers prove the polyhedron empty: no solution in this piece.
            return (f64::NEG_INFINITY, None);
        }
        if !lower.is_finite() {
            // No safe bound (a failed program): nothing is proved of this piece.
            return (f64::INFINITY, None);
        }
        let upper = (Interval::point(-lower) + fixed).sup();
        let argmax = (status == LpStatus::Optimal)
            .then(|| core::array::from_fn(|j| piece.centre[j] + self.primal[j]));
        (if upper.is_nan() { f64::INFINITY } else { upper }, argmax)
    }

    /// `min objective·y` over piece `i` by row generation: the program over a working subset of
    /// its rows (kept between queries), the rows its optimum violates added, until it violates
    /// none — then its optimum is the whole program's. The bound is the safe bound of the
    /// subset's multipliers, valid whatever the subset (fewer rows, a larger polyhedron).
    fn solve_by_row_generation(&mut self, i: usize, objective: &[f64; NX]) -> (LpStatus, f64) {
        let full = &self.set.pieces[i].poly;
        let (working, subset) = self.working[i].get_or_insert_with(|| own_rows_of(full));
        let mut status = LpStatus::Failed;
        let mut lower = f64::NEG_INFINITY;
        for _ in 0..ROW_GENERATION_ROUNDS {
            self.dual.resize(subset.rows(), 0.0);
            status = self.engines[i].minimize(subset, objective, &mut self.dual, &mut self.primal);
            lower = safe_lower_bound(subset, objective, &self.dual);
            if status != LpStatus::Optimal {
                break;
            }
            // The rows the optimum violates, most violated first.
            let y = &self.primal;
            let mut violated: Vec<(f64, usize)> = (0..full.rows())
                .filter_map(|r| {
                    let v: f64 =
                        full.row(r).iter().zip(y).map(|(a, b)| a * b).sum::<f64>() - full.rhs(r);
                    (v > VIOLATION_TOL * (1.0 + full.rhs(r).abs())).then_some((v, r))
                })
                .collect();
            if violated.is_empty() {
                break;
            }
            violated.sort_by(|a, b| b.0.total_cmp(&a.0));
            working.extend(violated.iter().take(ROWS_ADDED).map(|(_, r)| *r));
            working.sort_unstable();
            working.dedup();
            build_subset(full, working, subset);
        }
        (status, lower)
    }
}

/// Pieces with more rows than this are solved by row generation
/// ([`SetQuery::solve_by_row_generation`]): a long chain's thousands of coupling rows, most of
/// which never bind.
const ROW_GENERATION_ROWS: usize = 600;
/// The rows of each group a working subset starts with.
const FIRST_ROWS_PER_GROUP: u64 = 6;
/// At most this many programs per query of a piece solved by row generation (measured on the
/// built-in arm: the first program, over the configurations' own rows, is already within 0.02%
/// of the whole program's bound on the widths of predicted tool points, and three times faster
/// than solving to the end).
const ROW_GENERATION_ROUNDS: usize = 2;
/// At most this many violated rows added per round.
const ROWS_ADDED: usize = 64;
/// A row is violated beyond this (relative to its right-hand side; rows are scaled to
/// coefficients below 1).
const VIOLATION_TOL: f64 = 1e-10;

/// The first rows of each group of `full` (a configuration's own residuals, before its coupling
/// combinations), and their polyhedron.
fn own_rows_of(full: &Polyhedron) -> (Vec<usize>, Polyhedron) {
    let rows: Vec<usize> = (0..full.rows())
        .filter(|&r| full.tag(r) & 0xffff_ffff < FIRST_ROWS_PER_GROUP)
        .collect();
    let mut subset = Polyhedron::default();
    build_subset(full, &rows, &mut subset);
    (rows, subset)
}

/// The polyhedron of `full`'s rows `rows`, over its box, with its frozen columns.
fn build_subset(full: &Polyhedron, rows: &[usize], out: &mut Polyhedron) {
    out.reset(full.lo(), full.hi());
    for j in 0..full.dim() {
        if full.is_frozen(j) {
            out.freeze(j, full.lo()[j].abs().max(full.hi()[j].abs()));
        }
    }
    for &r in rows {
        out.begin_group((full.tag(r) >> 32) as u32);
        out.push_row(full.row(r), full.rhs(r));
    }
}

/// A function of the parameters to maximise over a [`CertifiedSet`].
pub trait SetObjective<const NX: usize> {
    /// An enclosure of `g` over the box `x` (at a point when the box is thin).
    fn value(&self, x: &[Interval; NX]) -> Interval;

    /// An enclosure of `∇g` over the box `x`.
    fn slopes(&self, x: &[Interval; NX]) -> [Interval; NX];
}

/// The linear function `g·x`, as a [`SetObjective`] (its value enclosed in interval arithmetic,
/// its slopes exact): to bracket a prediction's range over the set with refinement.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinearFunction<const NX: usize>(pub [f64; NX]);

impl<const NX: usize> SetObjective<NX> for LinearFunction<NX> {
    fn value(&self, x: &[Interval; NX]) -> Interval {
        (0..NX).fold(Interval::ZERO, |s, j| s + Interval::point(self.0[j]) * x[j])
    }

    fn slopes(&self, _: &[Interval; NX]) -> [Interval; NX] {
        self.0.map(Interval::point)
    }
}

/// When to stop [`maximize_over_set`].
#[derive(Clone, Debug, PartialEq)]
pub struct SetMaximumSettings {
    /// Stop once `upper - lower <= rel_tol · |lower|` (default 0.01).
    pub rel_tol: f64,
    /// … or `upper - lower <= abs_tol` (default 0).
    pub abs_tol: f64,
    /// Refine at most this many pieces (default 200).
    pub max_refinements: usize,
    /// The kernel's settings for the contractions of refined pieces.
    pub kernel: Settings,
}

impl Default for SetMaximumSettings {
    fn default() -> Self {
        SetMaximumSettings {
            rel_tol: 0.01,
            abs_tol: 0.0,
            max_refinements: 200,
            kernel: Settings::default(),
        }
    }
}

/// The certified bracket of a maximum over a set.
#[derive(Clone, Debug, PartialEq)]
pub struct SetMaximum<const NX: usize> {
    /// Proved: `g(x) <= upper` for every consistent `x` (`+∞` when an enclosure failed, `-∞`
    /// when the set is empty).
    pub upper: f64,
    /// Attained: `g(argmax) >= lower`, `argmax` proved consistent (`-∞` without a point).
    pub lower: f64,
    /// A parameter vector proved consistent with the measurements where `g >= lower`.
    pub argmax: Option<[f64; NX]>,
    /// Whether the tolerance was met.
    pub converged: bool,
    /// Pieces refined.
    pub refinements: usize,
}

impl<const NX: usize> SetMaximum<NX> {
    /// `upper / lower` (see [`crate::set::maximum::bracket_ratio`]).
    pub fn ratio(&self) -> f64 {
        crate::set::maximum::bracket_ratio(self.upper, self.lower)
    }
}

/// Brackets `max g` over the certified set (module documentation): per piece, the mean-value
/// form about the piece's centre with a linear program over its polyhedron; lower bounds at
/// certified points pushed along the gradient from the LP optima; the piece attaining the upper
/// bound refined until `upper <= (1 + rel_tol) lower` or the budget is spent. Refinement changes
/// `set` (its pieces get finer; it still contains every solution) and adds certified points.
pub fn maximize_over_set<M, O, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    set: &mut CertifiedSet<NX, NM>,
    objective: &O,
    settings: &SetMaximumSettings,
) -> SetMaximum<NX>
where
    M: VectorModel<NX, NM, NR>,
    O: SetObjective<NX>,
{
    let mut out = SetMaximum {
        upper: f64::NEG_INFINITY,
        lower: f64::NEG_INFINITY,
        argmax: None,
        converged: false,
        refinements: 0,
    };
    let value_at = |x: &[f64; NX]| objective.value(&x.map(Interval::point)).inf();
    for p in set.points() {
        let v = value_at(&p.x);
        if v > out.lower {
            out.lower = v;
            out.argmax = Some(p.x);
        }
    }
    loop {
        // Per piece: g(c) + slopes over the piece.
        let bounds: Vec<(f64, Option<[f64; NX]>, [Interval; NX])> = {
            let mut q = set.query();
            (0..set.pieces().len())
                .map(|i| {
                    let piece = &set.pieces()[i];
                    let c = *piece.centre();
                    let s = objective.slopes(piece.bounds());
                    let (lin, arg) = q.piece_max(i, &s, &c);
                    let g = objective.value(&c.map(Interval::point)).sup();
                    let total = if lin == f64::NEG_INFINITY {
                        // The piece is proved empty: it raises nothing.
                        f64::NEG_INFINITY
                    } else if !(g.is_finite() && lin.is_finite()) {
                        f64::INFINITY
                    } else {
                        (Interval::point(g) + Interval::point(lin)).sup()
                    };
                    (if total.is_nan() { f64::INFINITY } else { total }, arg, s)
                })
                .collect()
        };
        let worst = (0..bounds.len()).max_by(|&a, &b| bounds[a].0.total_cmp(&bounds[b].0));
        out.upper = worst.map_or(f64::NEG_INFINITY, |i| bounds[i].0);
        // The lower bound: a certified point pushed along the slopes' midpoints of the worst piece.
        if let Some(i) = worst {
            let direction = bounds[i].2.map(|s| s.mid());
            if let Some(p) = set.extreme_point(model, &direction) {
                let v = value_at(&p);
                if v > out.lower {
                    out.lower = v;
                    out.argmax = Some(p);
                }
            }
            if let Some(arg) = bounds[i].1 {
                // The LP optimum itself, when it happens to be consistent.
                if set.add_point(model, &arg) {
                    let v = value_at(&arg);
                    if v > out.lower {
                        out.lower = v;
                        out.argmax = Some(arg);
                    }
                }
            }
        }
        let gap = out.upper - out.lower;
        let met = gap <= settings.abs_tol || gap <= settings.rel_tol * out.lower.abs();
        if met || set.is_empty() {
            out.converged = true;
            return out;
        }
        if out.refinements >= settings.max_refinements {
            return out;
        }
        let Some(i) = worst else { return out };
        if !set.refine(model, i, &settings.kernel) {
            return out;
        }
        out.refinements += 1;
    }
}
