//! The enclosures behind the accuracy certificate: per box of poses, the legs' length errors
//! over every geometry of the certified set (or of the robot file's box); per pose, an explicit
//! worst instance.
//!
//! Leg `i` has the nominal geometry `θ̂_i` the controller loads and a true geometry `θ*_i`
//! somewhere in its certified set `S_i` (a calibrated file carries it: [`crate::calibrated`]) or,
//! for a robot file without one, in the box `Θ_i` of the file.
//!
//! **Over the set.** `ΔL_i(X, θ̂) = 0`, so by the mean-value theorem in `θ`,
//! `ΔL_i(X, θ) ∈ Σ_j G_j (θ_j - θ̂_j)` with `G ⊇ ∂ΔL_i/∂θ` over the box of poses and the hull of
//! the set and `θ̂`; its largest and smallest values over `S_i` are bounded by one linear program
//! per piece of the set ([`calib_core::SetQuery::max_linear`], safe bounds). Instances take the
//! certified geometries of a catalogue — the set's points pushed along `±∂ΔL_i/∂θ` at poses
//! spread over the workspace, each proved consistent with every measurement — so every lower
//! bound is attained by a geometry the data allow.
//!
//! **Over the box.** At a pose `X = (p, q)` (`q` the Rodrigues vector)
//! the controller commands `L_i(X; θ̂_i)`; the real leg would need `L_i(X; θ*_i)`. The leg-length
//! error `ΔL_i(X, θ*) = L_i(X; θ*) - L_i(X; θ̂)` is enclosed over a box of poses and all of `Θ_i` by
//! the natural enclosure of [`super::leg_length_error`] (written without cancellation)
//! intersected with its mean-value form about the box's centre. Since `L_i` is convex in `(a, b)`
//! and affine in `l`, its largest value over `Θ_i` is at a vertex: instances take the vertex the
//! gradient's signs point to.

use super::model::{leg_reading, LegCurvature, LegLengthError, LegReading};
use crate::files::LegSpec;
use crate::measurement::measured;
use crate::workspace::Workspace;
use crate::LegModel;
use calib_core::LpBackend;
use calib_core::SetQuery;
use calib_core::{
    maximize_over_set, CertifiedSet, Interval, Jet, LinearFunction, Model, Quadratic, SetMaximum,
    SetMaximumSettings,
};
use rand::{Rng, SeedableRng};
use std::cell::RefCell;
use std::sync::Arc;

/// The most rounds of [`AccuracyProblem::climb`].
const MAX_CLIMB_ROUNDS: usize = 500;

/// A pose as `(p_x, p_y, p_z, q_1, q_2, q_3)`: centre (cm) and Rodrigues vector.
pub type PoseVector = [f64; 6];

/// A box of poses.
pub type PoseBox = [Interval; 6];

/// One leg's geometry: what the controller loads and where the real leg lies.
#[derive(Clone, Debug)]
struct LegBounds {
    /// `θ̂`: the robot file's values, as the controller loads them.
    nominal: [f64; 7],
    /// `Θ`: an enclosure of nominal ± radius (decimal values enclosed); over a set, the hull of
    /// the set's pieces and `θ̂`.
    theta: [Interval; 7],
    /// Per parameter, the box's lower and upper ends moved inward past rounding (the vertices
    /// of instances), or, for a fixed parameter, the enclosure of its value.
    vertex: [[Interval; 7]; 2],
    /// The certified set and its catalogue of certified geometries, when the file has one.
    set: Option<Arc<LegSet>>,
}

/// A leg's certified set with a catalogue of certified geometries (see the module
/// documentation): the instances' true geometries.
#[derive(Clone, Debug)]
pub struct LegSet {
    set: CertifiedSet<7, 8>,
    /// The same set as one piece (its hull, contracted, with the relaxation over it): for the
    /// many small terms of [`AccuracyProblem::set_error`], where one linear program per term is
    /// enough.
    coarse: CertifiedSet<7, 8>,
    catalogue: Vec<[f64; 7]>,
    /// `±∂ΔL/∂θ` at the catalogue's poses: where the accuracy's bounds look.
    directions: Vec<[f64; 7]>,
}

/// A second-order Taylor model over a box of poses: a noise symbol per pose coordinate.
type SlopeForm = Quadratic<6>;

/// At most this many pose coordinates get the vertices of [`AccuracyProblem::set_error`]
/// (`2^n` linear programs per piece and sign).
const MAX_VERTEX_COORDINATES: usize = 3;

thread_local! {
    /// Per thread, the LP engines of the last leg bound over a set (fine pieces, coarse piece).
    static ENGINES: RefCell<EnginePool> = RefCell::new((Vec::new(), Vec::new()));
}

/// LP engines for the fine pieces and for the coarse piece of a leg's set.
type EnginePool = (Vec<Box<dyn LpBackend>>, Vec<Box<dyn LpBackend>>);

/// Pieces of a leg's set for the accuracy's linear programs (fewer than a file may store: each
/// bound solves `2^n` programs per piece).
const FINE_PIECES: usize = 4;

/// Poses per leg whose `±∂ΔL/∂θ` directions the catalogue's geometries are pushed along (and a
/// refined set is refined along: [`AccuracyProblem::refine_sets`]).
const CATALOGUE_POSES: usize = 40;
/// Pieces refined at most per direction by [`AccuracyProblem::refine_sets`].
const REFINEMENTS_PER_DIRECTION: usize = 16;

/// The pieces `gough accuracy --refine-set` refines each leg's set to
/// ([`AccuracyProblem::refine_sets`]; the bounds use 4 as stored).
pub const REFINED_SET_PIECES: usize = 36;

impl LegSet {
    /// The catalogue for `set` on the poses of `domain` (see the module documentation).
    fn new(set: CertifiedSet<7, 8>, nominal: &[f64; 7], domain: &PoseBox) -> LegSet {
        let points: Vec<[f64; 7]> = set.points().iter().map(|p| p.x).collect();
        let model = LegModel::of_set(&set);
        let mut set = CertifiedSet::new(
            &model,
            &set.cover(),
            set.measurements(),
            &points,
            FINE_PIECES,
        );
        set.add_second_order_rows(&model, &move |x, m, s| model.hessian_over(x, m, s));
        let mut rng = rand::rngs::StdRng::seed_from_u64(0xca7a);
        let t = domain[3].sup();
        let mut directions = Vec::with_capacity(2 * CATALOGUE_POSES);
        for k in 0..CATALOGUE_POSES {
            // Corners of the positions and the largest rotations first, then random poses.
            let x: PoseVector = core::array::from_fn(|c| {
                let (lo, hi) = (domain[c].inf(), domain[c].sup());
                let u: f64 = if k < 16 {
                    f64::from((k >> (c % 4)) as u8 & 1)
                } else {
                    rng.random()
                };
                let v = lo + u * (hi - lo);
                if c >= 3 {
                    v / 3f64.sqrt().max(1.0)
                } else {
                    v
                }
            });
            let q = (x[3] * x[3] + x[4] * x[4] + x[5] * x[5]).sqrt();
            let x = if q > t && q > 0.0 {
                core::array::from_fn(|c| if c >= 3 { x[c] * t / q } else { x[c] })
            } else {
                x
            };
            let m: [f64; 13] = core::array::from_fn(|c| if c < 6 { x[c] } else { nominal[c - 6] });
            let g = LegLengthError.jacobian_x(nominal, &m);
            for sign in [1.0, -1.0] {
                set.extreme_point(&model, &g.map(|v| sign * v));
                directions.push(g.map(|v| sign * v));
            }
        }
        let catalogue: Vec<[f64; 7]> = set.points().iter().map(|p| p.x).collect();
        let coarse = CertifiedSet::new(
            &model,
            &set.cover(),
            set.measurements(),
            &catalogue[..catalogue.len().min(1)],
            1,
        );
        LegSet {
            set,
            coarse,
            catalogue,
            directions,
        }
    }

    /// The same leg's set refined where the maxima of `w·θ` lie, for each of its directions `w`
    /// in turn (corners of the workspace first; at most [`REFINEMENTS_PER_DIRECTION`] pieces
    /// each, until the maximum is bracketed within 0.5% of the set's range of `w·θ`), until it
    /// has `pieces` pieces, with the certified points found on the way in its catalogue. Every
    /// refined piece still holds every solution in its box ([`CertifiedSet::refine`]).
    fn refined(&self, pieces: usize) -> LegSet {
        let mut set = self.set.clone();
        for w in &self.directions {
            if set.pieces().len() >= pieces {
                break;
            }
            let budget = REFINEMENTS_PER_DIRECTION.min(pieces - set.pieces().len());
            refined_maximum(&mut set, w, budget);
        }
        // The refined pieces' own Taylor rows (the others keep theirs).
        let model = LegModel::of_set(&set);
        set.add_second_order_rows(&model, &move |x, m, s| model.hessian_over(x, m, s));
        LegSet {
            catalogue: set.points().iter().map(|p| p.x).collect(),
            set,
            coarse: self.coarse.clone(),
            directions: self.directions.clone(),
        }
    }

    /// The certified set.
    pub fn set(&self) -> &CertifiedSet<7, 8> {
        &self.set
    }

    /// The catalogue of certified geometries.
    pub fn catalogue(&self) -> &[[f64; 7]] {
        &self.catalogue
    }
}

/// `max w·θ` over a leg's set, bracketed within 0.5% of the set's range of `w·θ` by refining the
/// piece attaining it, at most `refinements` times ([`maximize_over_set`]: the refined pieces and
/// the certified points found stay in `set`). `None` when the set's range is not finite.
pub(crate) fn refined_maximum(
    set: &mut CertifiedSet<7, 8>,
    w: &[f64; 7],
    refinements: usize,
) -> Option<SetMaximum<7>> {
    let width = set.query().range(w).wid();
    if !width.is_finite() {
        return None;
    }
    let settings = SetMaximumSettings {
        rel_tol: 0.0,
        abs_tol: 0.005 * width,
        max_refinements: refinements,
        ..SetMaximumSettings::default()
    };
    let model = LegModel::of_set(set);
    Some(maximize_over_set(
        &model,
        set,
        &LinearFunction(*w),
        &settings,
    ))
}

impl LegBounds {
    /// Over the certified set: `Θ` the hull of the set and `θ̂`.
    fn over_set(spec: &LegSpec, set: CertifiedSet<7, 8>, domain: &PoseBox) -> LegBounds {
        let nominal = spec.nominal.params();
        let theta: [Interval; 7] = match set.outer() {
            Some(o) => core::array::from_fn(|j| o[j].hull(Interval::point(nominal[j]))),
            None => nominal.map(Interval::point),
        };
        LegBounds {
            nominal,
            theta,
            vertex: [theta; 2],
            set: Some(Arc::new(LegSet::new(set, &nominal, domain))),
        }
    }

    fn new(spec: &LegSpec) -> LegBounds {
        let nominal = spec.nominal.params();
        let theta: [Interval; 7] = core::array::from_fn(|j| measured(nominal[j], spec.radius[j]));
        let inward = |j: usize, up: bool| {
            let (v, r) = (Interval::point(nominal[j]), Interval::point(spec.radius[j]));
            if spec.radius[j] == 0.0 {
                return theta[j];
            }
            // The value and the radius are within half an ulp of their decimals: two ulps of the
            // sum inward stay inside the decimal box (and never pass the nominal value).
            let end = if up {
                (v + r).inf().next_down().next_down().max(nominal[j])
            } else {
                (v - r).sup().next_up().next_up().min(nominal[j])
            };
            Interval::point(end)
        };
        LegBounds {
            nominal,
            theta,
            vertex: [false, true].map(|up| core::array::from_fn(|j| inward(j, up))),
            set: None,
        }
    }
}

/// The accuracy problem of a robot file on a workspace (see the module documentation).
#[derive(Clone, Debug)]
pub struct AccuracyProblem {
    legs: Vec<LegBounds>,
    /// The pose box searched: the workspace's position ranges and the cube `|q_j| <= tan(tilt/2)`.
    domain: PoseBox,
    /// `tan(tilt/2)²`, enclosed.
    tilt_sq: Interval,
    /// The stroke, when given.
    stroke: Option<[f64; 2]>,
    /// The position ranges as read (for the feasibility of instance poses).
    ranges: [[f64; 2]; 3],
    /// The workspace.
    workspace: Workspace,
}

fn thin<const N: usize>(x: &[f64; N]) -> [Interval; N] {
    x.map(Interval::point)
}

impl AccuracyProblem {
    /// The problem for `robot` on `workspace` over its certified sets: leg `i` over `sets[i]`
    /// when given, else over its box (a robot file without a set).
    pub fn over_sets(
        robot: &[LegSpec],
        sets: &[Option<CertifiedSet<7, 8>>],
        workspace: &Workspace,
    ) -> AccuracyProblem {
        let mut problem = AccuracyProblem::new(robot, workspace);
        let domain = problem.domain;
        for (i, spec) in robot.iter().enumerate() {
            if let Some(Some(set)) = sets.get(i) {
                problem.legs[i] = LegBounds::over_set(spec, set.clone(), &domain);
            }
        }
        problem
    }

    /// Refines each leg's certified set where the workspace's leg-length errors are largest,
    /// to `pieces` pieces: a set as stored is a few polyhedra, each the linearisation of the
    /// measurements over a wide box, which overstate `max ±∂ΔL/∂θ · θ` by up to 25% at a pose;
    /// refined along the directions the bounds ask (the gradients at the workspace's corners
    /// first), they come within 0.5% there. Every bound stays proved over the whole set; each
    /// costs more (a linear program per piece where a maximum may lie), which pays where the
    /// gradients barely turn across the workspace (a small one).
    pub fn refine_sets(&mut self, pieces: usize) {
        for leg in &mut self.legs {
            if let Some(set) = &leg.set {
                leg.set = Some(Arc::new(set.refined(pieces)));
            }
        }
    }

    /// Whether leg `i`'s errors are taken over its certified set (else over its box).
    pub fn over_set(&self, i: usize) -> bool {
        self.legs[i].set.is_some()
    }

    /// Leg `i`'s certified set and catalogue, when it has one.
    pub fn leg_set(&self, i: usize) -> Option<&LegSet> {
        self.legs[i].set.as_deref()
    }

    /// The problem for `robot` on `workspace`, every leg over its box.
    pub fn new(robot: &[LegSpec], workspace: &Workspace) -> AccuracyProblem {
        let half_tilt = measured(workspace.tilt_deg, 0.0) * Interval::PI / Interval::point(360.0);
        let t = half_tilt.tan();
        let widen = |[lo, hi]: [f64; 2]| Interval::new(lo.next_down(), hi.next_up());
        let cube = Interval::new(-t.sup(), t.sup());
        AccuracyProblem {
            legs: robot.iter().map(LegBounds::new).collect(),
            domain: [
                widen(workspace.x),
                widen(workspace.y),
                widen(workspace.z),
                cube,
                cube,
                cube,
            ],
            tilt_sq: t.sqr(),
            stroke: workspace.stroke,
            ranges: [workspace.x, workspace.y, workspace.z],
            workspace: *workspace,
        }
    }

    /// The workspace.
    pub fn workspace(&self) -> &Workspace {
        &self.workspace
    }

    /// The values `θ̂_i` the controller loads for leg `i`.
    pub(crate) fn nominal(&self, i: usize) -> &[f64; 7] {
        &self.legs[i].nominal
    }

    /// The box `Θ_i` the real leg `i` lies in (decimal bounds enclosed).
    #[doc(hidden)]
    pub fn theta(&self, i: usize) -> &[Interval; 7] {
        &self.legs[i].theta
    }

    /// The number of legs.
    pub fn legs(&self) -> usize {
        self.legs.len()
    }

    /// The box of poses searched.
    pub fn domain(&self) -> PoseBox {
        self.domain
    }

    /// The commanded reading of leg `i` over the box (nominal geometry).
    fn commanded(&self, i: usize, x: &PoseBox) -> Interval {
        LegReading.residual_interval(&thin(&self.legs[i].nominal), x)
    }

    /// Whether the box may hold a pose of the workspace (`false` is a proof that it holds none).
    pub fn may_be_feasible(&self, x: &PoseBox) -> bool {
        let q_sq = x[3].sqr() + x[4].sqr() + x[5].sqr();
        q_sq.inf() <= self.tilt_sq.sup() && self.stroke_may_hold(x)
    }

    /// Whether the stroke may hold the commanded readings over `x` (`false` is a proof that no
    /// pose of `x` has every reading within it).
    fn stroke_may_hold(&self, x: &PoseBox) -> bool {
        match self.stroke {
            None => true,
            Some([lo, hi]) => (0..self.legs.len()).all(|i| {
                let r = self.commanded(i, x);
                !(r.sup() < lo.next_down() || r.inf() > hi.next_up())
            }),
        }
    }

    /// Whether the pose is proved to lie in the workspace.
    pub fn proved_feasible(&self, x: &PoseVector) -> bool {
        let inside = |v: f64, [lo, hi]: [f64; 2]| lo.next_up() <= v && v <= hi.next_down();
        if !(0..3).all(|k| inside(x[k], self.ranges[k])) {
            return false;
        }
        let q = thin(&[x[3], x[4], x[5]]);
        if (q[0].sqr() + q[1].sqr() + q[2].sqr()).sup() > self.tilt_sq.inf() {
            return false;
        }
        match self.stroke {
            None => true,
            Some(s) => (0..self.legs.len()).all(|i| {
                let r = self.commanded(i, &thin(x));
                inside(r.inf(), s) && inside(r.sup(), s)
            }),
        }
    }

    /// The pose-and-nominal inputs `m = (X, θ̂_i)` of [`LegLengthError`] over the box `x`.
    pub(crate) fn inputs(&self, i: usize, x: &PoseBox) -> [Interval; 13] {
        let nominal = &self.legs[i].nominal;
        core::array::from_fn(|k| {
            if k < 6 {
                x[k]
            } else {
                Interval::point(nominal[k - 6])
            }
        })
    }

    /// An enclosure of `ΔL_i(X, θ)` over the poses of `x` and the geometries `theta`: the
    /// natural enclosure intersected with the mean-value form about the centre of both.
    fn mean_value(&self, i: usize, x: &PoseBox, theta: &[Interval; 7]) -> Interval {
        let e = LegLengthError.evaluate_interval(theta, &self.inputs(i, x));
        let xc = x.map(|v| v.mid());
        let tc = theta.map(|v| v.mid());
        let mut mv = LegLengthError.residual_interval(&thin(&tc), &self.inputs(i, &thin(&xc)));
        for j in 0..7 {
            mv += e.dx[j] * (theta[j] - Interval::point(tc[j]));
        }
        for k in 0..6 {
            mv += e.dm[k] * (x[k] - Interval::point(xc[k]));
        }
        let both = e.value.intersection(mv);
        if both.is_empty() || both.inf().is_nan() || both.sup().is_nan() {
            e.value
        } else {
            both
        }
    }

    /// An enclosure of leg `i`'s length error `ΔL_i(X, θ*)` over the poses of `x` and every
    /// `θ*` in its box (see the module documentation).
    pub fn leg_error(&self, i: usize, x: &PoseBox) -> Interval {
        match &self.legs[i].set {
            Some(set) => self.set_error(i, x, set, 0.0),
            None => self.mean_value(i, x, &self.legs[i].theta),
        }
    }

    /// An enclosure of `ΔL_i(X, θ)` over the poses of `x` and every `θ` of the set (see the
    /// module documentation), tight where its magnitude exceeds `enough` (below, a cheaper
    /// bound may be returned: it cannot raise a maximum beyond `enough`).
    ///
    /// Exactly `ΔL_i = G(X)·δ + r` with `δ = θ - θ̂`, `G = ∇_θ L_i(X; θ̂)` (the reading
    /// `L = |p + R b - a| - l` at the controller's geometry) and `0 <= r <=` the curvature bound
    /// of [`super::leg_curvature`] (`|û × d|² / 2(|v| - |d|)`, `d` the attachment points'
    /// displacement): micrometres, where the legs' directions barely turn across the set.
    /// The slopes `G` are second-order Taylor models ([`calib_core::Quadratic`], carried by
    /// [`calib_core::Jet`]) in the pose's noise symbols `ε_k`:
    /// `G_j = c_j + Σ_k a_jk ε_k + Σ_{k<=l} q_jkl ε_k ε_l ± e_j`. So
    ///
    /// `ΔL_i <= max_σ max_{δ ∈ S} (c + Σ_k σ_k a_k)·δ + Σ_{k<=l} max_{δ ∈ S} |q_kl·δ| + Σ_j e_j |δ_j| + max r`
    ///
    /// (`σ` over the vertices of the noise box of the pose coordinates whose linear term
    /// matters most), and the same below without `r`. The pose's first- and second-order
    /// effects are taken over the set, where the data make them small; only third-order
    /// remainders meet the set's box. First a cheap bound (the set as one piece, each pose
    /// coordinate's term bounded on its own); the vertices and every piece only where it
    /// exceeds `enough`.
    fn set_error(&self, i: usize, x: &PoseBox, set: &LegSet, enough: f64) -> Interval {
        let leg = &self.legs[i];
        let nominal = &leg.nominal;
        let theta: [Jet<SlopeForm, 7>; 7] = core::array::from_fn(|j| {
            Jet::variable(SlopeForm::from_interval(Interval::point(nominal[j])), j)
        });
        let m: [Jet<SlopeForm, 7>; 6] =
            core::array::from_fn(|k| Jet::constant(SlopeForm::input(x[k], k)));
        let g = leg_reading(&theta, &m).grad;
        let finite = |f: &SlopeForm| {
            f.centre().is_finite()
                && f.error().is_finite()
                && f.linear().iter().all(|v| v.is_finite())
                && (0..6).all(|k| (k..6).all(|l| f.quadratic(k, l).is_finite()))
        };
        if !g.iter().all(finite) {
            // A model that blew up (a box too wide for second order): no bound here; the
            // branch and bound splits the box.
            return Interval::ENTIRE;
        }
        let spread: [Interval; 7] =
            core::array::from_fn(|j| leg.theta[j] - Interval::point(nominal[j]));
        let delta = spread.map(|v| v.mag());
        // Σ_j e_j mag(δ_j): the Taylor models' remainders.
        let rest = (0..7).fold(Interval::ZERO, |s, j| {
            s + Interval::point(g[j].error()) * Interval::point(delta[j])
        });
        let curvature = LegCurvature
            .residual_interval(&spread, &self.inputs(i, x))
            .sup();
        let curvature = if curvature.is_finite() && curvature >= 0.0 {
            curvature
        } else {
            return Interval::ENTIRE;
        };
        // The engines of this thread's last bound, so that nothing is allocated.
        let (fine_engines, coarse_engines) =
            ENGINES.with(|e| core::mem::take(&mut *e.borrow_mut()));
        let mut q = set.set.query_reusing(fine_engines);
        let mut coarse = set.coarse.query_reusing(coarse_engines);
        let bounds = set_error_bounds(&g, &delta, rest, &mut q, &mut coarse, nominal, enough);
        ENGINES.with(|e| *e.borrow_mut() = (q.into_engines(), coarse.into_engines()));
        if bounds.is_empty() || !bounds.sup().is_finite() {
            return Interval::ENTIRE;
        }
        Interval::new(
            bounds.inf(),
            (Interval::point(bounds.sup()) + Interval::point(curvature)).sup(),
        )
    }

    /// The box `x` with its rotation coordinates narrowed to what the tilt allows: each
    /// `|q_k| <= sqrt(t² - Σ_{j≠k} mig(q_j)²)`, twice (every pose of the workspace in `x` stays;
    /// `None` when none can be in it).
    pub fn within_tilt(&self, x: &PoseBox) -> Option<PoseBox> {
        let mut out = *x;
        for _ in 0..2 {
            for k in 3..6 {
                let others = (3..6)
                    .filter(|&j| j != k)
                    .fold(Interval::ZERO, |s, j| s + out[j].sqr());
                let room = self.tilt_sq - others;
                if room.sup() < 0.0 {
                    return None;
                }
                let r = Interval::new(0.0, room.sup()).sqrt().sup();
                out[k] = out[k].intersection(Interval::new(-r, r));
                if out[k].is_empty() {
                    return None;
                }
            }
        }
        Some(out)
    }

    /// An enclosure of `f_i(X) = max_{θ* ∈ Θ_i} |ΔL_i(X, θ*)|` over the poses of `x`.
    ///
    /// Where `∂ΔL_i/∂θ_j` keeps its sign over the box (and all of `Θ_i`), `ΔL_i` is monotone in
    /// `θ_j`, so its largest and smallest values over `Θ_i` have `θ_j` at an end. With `θ↑`
    /// (`θ↓`) those ends — as boxes only as wide as rounding, from the inward vertex to the
    /// outward enclosure's end — and the whole range of the other parameters,
    /// `f_i ∈ [max(ΔL_i(X, θ↑), -ΔL_i(X, θ↓))]`, each enclosed by its mean-value form: without
    /// the overestimation of an interval over every parameter.
    pub fn leg_bounds(&self, i: usize, x: &PoseBox) -> Interval {
        self.leg_bounds_up_to(i, x, 0.0)
    }

    /// [`AccuracyProblem::leg_bounds`], tight only where it exceeds `enough` (a leg over its set
    /// then skips the costlier part of its bound).
    pub fn leg_bounds_up_to(&self, i: usize, x: &PoseBox, enough: f64) -> Interval {
        let leg = &self.legs[i];
        if let Some(set) = &leg.set {
            let e = self.set_error(i, x, set, enough);
            return Interval::new(0.0, e.mag());
        }
        let (u, d) = self.box_ends(i, x);
        Interval::new(u.inf().max(d.inf()).max(0.0), u.sup().max(d.sup()).max(0.0))
    }

    /// Upper bounds of how far leg `i`'s length error reaches below and above zero over the
    /// poses of `x` and every geometry of its set (or box): `[max(-ΔL_i), max(ΔL_i)]`, each at
    /// least 0; `None` when an enclosure failed.
    pub fn leg_error_reach(&self, i: usize, x: &PoseBox) -> Option<[f64; 2]> {
        let leg = &self.legs[i];
        let (below, above) = match &leg.set {
            Some(set) => {
                let e = self.set_error(i, x, set, 0.0);
                (-e.inf(), e.sup())
            }
            None => {
                let (u, d) = self.box_ends(i, x);
                (d.sup(), u.sup())
            }
        };
        // NaN fails (f64::max would turn it into 0).
        (below.is_finite() && above.is_finite()).then(|| [below.max(0.0), above.max(0.0)])
    }

    /// Enclosures of `max ΔL_i` and `max -ΔL_i` over the poses of `x` and leg `i`'s box, from the
    /// ends of its box where the gradient's signs are known (see [`AccuracyProblem::leg_bounds`]).
    fn box_ends(&self, i: usize, x: &PoseBox) -> (Interval, Interval) {
        let leg = &self.legs[i];
        let e = LegLengthError.evaluate_interval(&leg.theta, &self.inputs(i, x));
        let end = |up: bool| -> [Interval; 7] {
            core::array::from_fn(|j| {
                let g = e.dx[j];
                if !(g.inf() > 0.0 || g.sup() < 0.0) {
                    // The sign is not known on this box: the whole range of the parameter.
                    return leg.theta[j];
                }
                let rising = (g.inf() > 0.0) == up;
                let outer = Interval::point(if rising {
                    leg.theta[j].sup()
                } else {
                    leg.theta[j].inf()
                });
                outer.hull(leg.vertex[usize::from(rising)][j])
            })
        };
        (
            self.mean_value(i, x, &end(true)),
            -self.mean_value(i, x, &end(false)),
        )
    }

    /// The vertex of leg `i`'s box where `ΔL_i` at `x` is largest (`up`) or smallest, by the
    /// signs of its gradient at the nominal geometry.
    #[doc(hidden)]
    pub fn vertex(&self, i: usize, x: &PoseVector, up: bool) -> [Interval; 7] {
        let leg = &self.legs[i];
        let m: [f64; 13] = core::array::from_fn(|k| if k < 6 { x[k] } else { leg.nominal[k - 6] });
        if let Some(set) = &leg.set {
            // The certified geometry of the catalogue with the largest (or smallest) error, to
            // first order (`ΔL ≈ ∂ΔL/∂θ (θ - θ̂)`: the choice only, the error of the geometry
            // chosen is evaluated rigorously by its user).
            let g = LegLengthError.jacobian_x(&leg.nominal, &m);
            let sign = if up { 1.0 } else { -1.0 };
            let e = |t: &[f64; 7]| -> f64 {
                sign * (0..7).map(|j| g[j] * (t[j] - leg.nominal[j])).sum::<f64>()
            };
            let best = set
                .catalogue
                .iter()
                .max_by(|a, b| e(a).total_cmp(&e(b)))
                .copied()
                .unwrap_or(leg.nominal);
            return best.map(Interval::point);
        }
        let g = LegLengthError.jacobian_x(&leg.nominal, &m);
        core::array::from_fn(|j| leg.vertex[usize::from((g[j] > 0.0) == up)][j])
    }

    /// `|ΔL_i|` at the pose `x` with the geometry `theta`, rounded down.
    fn error_at(&self, i: usize, x: &PoseVector, theta: &[Interval; 7]) -> f64 {
        LegLengthError
            .residual_interval(theta, &self.inputs(i, &thin(x)))
            .mig()
    }

    /// The largest `|ΔL_i|` at `x` over the geometries instances may take (a proved lower bound
    /// of `max |ΔL_i|` over the set at the pose, 0 for a leg over its box).
    pub(crate) fn attained(&self, i: usize, x: &PoseVector) -> f64 {
        if self.legs[i].set.is_none() {
            return 0.0;
        }
        [true, false]
            .map(|up| self.error_at(i, x, &self.vertex(i, x, up)))
            .into_iter()
            .fold(0.0, f64::max)
    }

    /// The largest `|ΔL_i|` of the two extreme vertices at `x` (a floating-point estimate, for
    /// the search).
    fn estimate(&self, i: usize, x: &PoseVector, geometries: &[[f64; 7]; 2]) -> f64 {
        let leg = &self.legs[i];
        let m: [f64; 13] = core::array::from_fn(|k| if k < 6 { x[k] } else { leg.nominal[k - 6] });
        geometries
            .iter()
            .map(|t| LegLengthError.residual(t, &m).abs())
            .fold(0.0, f64::max)
    }

    /// A local search for the largest `score` from the pose `x` (proved inside the workspace)
    /// over poses proved inside it: steps along each coordinate, rotations projected back onto
    /// the largest tilt, halving down to 1e-7 of the workspace; jumps to the position bounds and
    /// out to the largest tilt; at most 500 rounds.
    pub(crate) fn climb(&self, x: &PoseVector, score: impl Fn(&PoseVector) -> f64) -> PoseVector {
        let mut best = (*x, score(x));
        let widths = self.domain.map(|v| v.wid());
        let t_max = self.tilt_sq.inf().sqrt() * (1.0 - 1e-9);
        // Onto the ball |q| <= t_max: rotations larger than the tilt are not poses.
        let project = |mut y: PoseVector| {
            let n = (y[3].powi(2) + y[4].powi(2) + y[5].powi(2)).sqrt();
            if n > t_max {
                for k in 3..6 {
                    y[k] *= t_max / n;
                }
            }
            y
        };
        let mut step = 0.25;
        // A ridge may be climbed in ever smaller gains: the rounds are capped.
        let mut rounds = 0;
        while step >= 1e-7 && rounds < MAX_CLIMB_ROUNDS {
            rounds += 1;
            let mut tries: Vec<PoseVector> = Vec::with_capacity(20);
            for k in 0..6 {
                for sign in [-1.0, 1.0] {
                    let mut y = best.0;
                    y[k] += sign * step * widths[k];
                    tries.push(project(y));
                }
            }
            // Straight to the position bounds, and out to the largest tilt along the axis.
            for k in 0..3 {
                for end in [self.ranges[k][0].next_up(), self.ranges[k][1].next_down()] {
                    let mut y = best.0;
                    y[k] = end;
                    tries.push(y);
                }
            }
            let n = (best.0[3].powi(2) + best.0[4].powi(2) + best.0[5].powi(2)).sqrt();
            if n > 0.0 {
                let mut y = best.0;
                for k in 3..6 {
                    y[k] *= t_max / n;
                }
                tries.push(y);
            }
            let mut moved = false;
            for y in tries {
                let v = score(&y);
                if v > best.1 && self.proved_feasible(&y) {
                    best = (y, v);
                    moved = true;
                }
            }
            if !moved {
                step /= 2.0;
            }
        }
        best.0
    }

    /// The worst instance of leg `i` found from the pose `x`: a local search (steps along each
    /// coordinate, jumps to the workspace's bounds) on the larger `|ΔL_i|` of the two extreme
    /// vertices (over a set: the catalogue's two extreme geometries at `x`), then the vertex
    /// (geometry) with the larger `|ΔL_i|` at the pose reached. `None` when `x` is not proved to
    /// lie in the workspace.
    pub fn instance(&self, i: usize, x: &PoseVector) -> Option<Instance> {
        if !self.proved_feasible(x) {
            return None;
        }
        let search = if self.legs[i].set.is_some() {
            Some([true, false].map(|up| self.vertex(i, x, up).map(|v| v.mid())))
        } else {
            None
        };
        let x = self.climb(x, |y| {
            let geometries = search
                .unwrap_or_else(|| [true, false].map(|up| self.vertex(i, y, up).map(|v| v.mid())));
            self.estimate(i, y, &geometries)
        });
        let (value, theta) = [true, false]
            .map(|up| {
                let theta = self.vertex(i, &x, up);
                (self.error_at(i, &x, &theta), theta)
            })
            .into_iter()
            .max_by(|a, b| a.0.total_cmp(&b.0))?;
        Some(Instance {
            pose: x,
            theta,
            value,
        })
    }
}

/// The bounds of [`AccuracyProblem::set_error`] from the slopes' Taylor models `g`, the
/// geometry's reach `delta` and its terms `rest`, with the set's fine (`q`) and one-piece
/// (`coarse`) queries.
fn set_error_bounds(
    g: &[SlopeForm; 7],
    delta: &[f64; 7],
    rest: Interval,
    q: &mut SetQuery<'_, 7, 8>,
    coarse: &mut SetQuery<'_, 7, 8>,
    nominal: &[f64; 7],
    enough: f64,
) -> Interval {
    let second = second_order_bound(g, delta, coarse, nominal);
    let centre = g.map(|f| f.centre());
    let linear: [[f64; 7]; 6] = core::array::from_fn(|k| g.map(|f| f.linear()[k]));
    let reach: [f64; 6] = core::array::from_fn(|k| reach_over_set(coarse, linear[k], nominal));
    let cheap = one_piece_bounds(&centre, &reach, rest + second, coarse, nominal);
    if cheap.mag() <= enough {
        return cheap;
    }
    let fine = vertex_bounds(&centre, &linear, &reach, rest + second, q, nominal);
    let tight = fine.intersection(cheap);
    if tight.is_empty() {
        fine
    } else {
        tight
    }
}

/// `v + w`, rounded up.
fn sum_up(v: f64, w: f64) -> f64 {
    (Interval::point(v) + Interval::point(w)).sup()
}

/// `[lo, hi]` (in either order), or every number when either is NaN or infinite.
fn ordered_bounds(hi: f64, lo: f64) -> Interval {
    if hi.is_nan() || lo.is_nan() || !hi.is_finite() || !lo.is_finite() {
        Interval::ENTIRE
    } else {
        Interval::new(lo.min(hi), hi.max(lo))
    }
}

/// `max |v·δ|` over the set, with its one-piece query `coarse` (0 for `v = 0`).
fn reach_over_set(coarse: &mut SetQuery<'_, 7, 8>, v: [f64; 7], nominal: &[f64; 7]) -> f64 {
    if v.iter().all(|x| *x == 0.0) {
        return 0.0;
    }
    let plus = coarse.max_linear(&thin(&v), nominal).upper;
    let minus = coarse.max_linear(&thin(&v.map(|x| -x)), nominal).upper;
    plus.max(minus).max(0.0)
}

/// A bound of the pose's second-order terms of `g`, one by one: by their coefficients'
/// magnitudes over the set's box (reach `delta`) where that is small, else by the set.
fn second_order_bound(
    g: &[SlopeForm; 7],
    delta: &[f64; 7],
    coarse: &mut SetQuery<'_, 7, 8>,
    nominal: &[f64; 7],
) -> Interval {
    let quadratic: Vec<[f64; 7]> = (0..6)
        .flat_map(|k| (k..6).map(move |l| (k, l)))
        .map(|(k, l)| g.map(|f| f.quadratic(k, l)))
        .collect();
    let crude: Vec<f64> = quadratic
        .iter()
        .map(|v| {
            (0..7).fold(0.0, |s, j| {
                sum_up(
                    s,
                    (Interval::point(v[j].abs()) * Interval::point(delta[j])).sup(),
                )
            })
        })
        .collect();
    let crude_total: f64 = crude.iter().sum();
    let mut second = Interval::ZERO;
    for (v, c) in quadratic.iter().zip(&crude) {
        let term = if *c > crude_total / 32.0 {
            reach_over_set(coarse, *v, nominal).min(*c)
        } else {
            *c
        };
        second += Interval::point(term);
    }
    second
}

/// The cheap bounds: the centre's slopes `centre` over the set in one piece, every pose
/// coordinate on its own (its `reach`), plus the terms `fixed` (the geometry's and the second
/// order's).
fn one_piece_bounds(
    centre: &[f64; 7],
    reach: &[f64; 6],
    fixed: Interval,
    coarse: &mut SetQuery<'_, 7, 8>,
    nominal: &[f64; 7],
) -> Interval {
    let all = reach
        .iter()
        .fold(fixed, |s, r| s + Interval::point(*r))
        .sup();
    ordered_bounds(
        sum_up(coarse.max_linear(&thin(centre), nominal).upper, all),
        -sum_up(
            coarse.max_linear(&thin(&centre.map(|v| -v)), nominal).upper,
            all,
        ),
    )
}

/// The fine bounds: the coordinates with the largest linear terms (`reach`, at most
/// [`MAX_VERTEX_COORDINATES`]) at each vertex of the pose box, the slopes `centre ± linear`
/// over the set with its fine query `q`; the other coordinates on their own, plus the terms
/// `fixed`.
fn vertex_bounds(
    centre: &[f64; 7],
    linear: &[[f64; 7]; 6],
    reach: &[f64; 6],
    fixed: Interval,
    q: &mut SetQuery<'_, 7, 8>,
    nominal: &[f64; 7],
) -> Interval {
    let (c, a) = (centre, linear);
    let total: f64 = reach.iter().sum();
    let mut vertex: Vec<usize> = (0..6).filter(|&k| reach[k] > total / 64.0).collect();
    vertex.sort_by(|&p, &r| reach[r].total_cmp(&reach[p]));
    vertex.truncate(MAX_VERTEX_COORDINATES);
    let others = (0..6)
        .filter(|k| !vertex.contains(k))
        .fold(Interval::ZERO, |s, k| s + Interval::point(reach[k]));
    let slack = (fixed + others).sup();
    let mut bound = |sign: f64| -> f64 {
        let mut best = f64::NEG_INFINITY;
        for pattern in 0..1u32 << vertex.len() {
            let mut w = *c;
            for (bit, &k) in vertex.iter().enumerate() {
                let s = if pattern >> bit & 1 == 1 { 1.0 } else { -1.0 };
                for j in 0..7 {
                    w[j] += s * a[k][j];
                }
            }
            // The sums above are rounded: their error is bounded into the slopes' radii.
            let slopes: [Interval; 7] = core::array::from_fn(|j| {
                let err = vertex.iter().fold(c[j].abs(), |e, &k| e + a[k][j].abs())
                    * (vertex.len() as f64 + 1.0)
                    * f64::EPSILON;
                Interval::mid_rad(sign * w[j], err)
            });
            best = best.max(q.max_linear(&slopes, nominal).upper);
        }
        sum_up(best, slack)
    };
    ordered_bounds(bound(1.0), -bound(-1.0))
}

/// An explicit worst-case instance of a leg: a pose of the workspace and a true geometry (proved
/// consistent with the measurements, over a set; in the leg's box otherwise) whose length error
/// is at least `value`.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// The commanded pose `(p, q)`, proved to lie in the workspace.
    pub pose: PoseVector,
    /// The true geometry `θ*` (over a set: a certified geometry, as point intervals; over a box:
    /// points inside it, a fixed parameter as the enclosure of its decimal value).
    pub theta: [Interval; 7],
    /// `|L(X; θ*) - L(X; θ̂)|`, rounded down (cm).
    pub value: f64,
}
