//! How far a robot's predictions can be off, proved over its certified set: the one engine
//! every robot's `accuracy` runs on.
//!
//! A robot supplies its prediction `g(u; θ)` ([`Prediction`]): the arm's tool point in the
//! tracker frame as a function of its joints, one hexapod leg's length as a function of the
//! platform's pose. The controller computes `g(u; θ̂)` with the values `θ̂` it loads; the real
//! robot has some geometry `θ*` in the certified set `S` and its inputs reach `u + e`, each
//! `|e_i| <=` the input's own error (encoders). The engine brackets
//!
//! `max_{u ∈ U, θ* ∈ S, |e| <= ε} ‖g(u + e; θ*) - g(u; θ̂)‖`
//!
//! over a box `U` of inputs: an upper bound proved over all of it ([`SetAccuracy`], the method
//! in its documentation) and a lower bound attained by an explicit input and a geometry proved
//! consistent with every measurement ([`Instance`]).
//!
//! The same terms, along each coordinate's axis at one input, give what the robot predicts there
//! over the set ([`SetAccuracy::predict`], [`Predicted`]): the ranges new measurements are checked
//! against.

mod arcs;
mod over_set;
mod sphere;
mod taylor;

pub use over_set::{bracket_over_inputs, bracket_over_set, SetAccuracy};
pub use taylor::taylor_remainder;

#[doc(hidden)]
pub use arcs::arc_vertices;
#[doc(hidden)]
pub use sphere::cover_bound;

use calib_core::{CertifiedSet, Interval, Jet, Quadratic, SetMaximum, VectorModel};

/// What a robot supplies to the accuracy engine: its prediction `g(u; θ)` of `R` coordinates
/// from `NX` parameters and `NU` inputs.
///
/// The prediction is a vector model ([`VectorModel`], written once under `#[interval_model]`)
/// whose measurement slot holds the inputs: `u` in its first `NU` entries, the others `0`. The
/// certified set it is asked over was certified with another model (the calibration's
/// residual, `NMS` measured quantities per configuration), which [`Prediction::push`] uses.
pub trait Prediction<
    const NX: usize,
    const NMS: usize,
    const NP: usize,
    const NU: usize,
    const R: usize,
>: Sync
{
    /// Input boxes at most this wide (every input) get the second-order columns; wider ones the
    /// interval slopes. By default every box (a prediction polynomial or rational in its inputs
    /// keeps its second-order models tight however wide the box); a prediction through sines and
    /// cosines of its inputs may want `1` ([`Quadratic`]'s second-order reach).
    const SECOND_ORDER_WIDTH: f64 = f64::INFINITY;

    /// Whether every input is an angle that enters `g` only through its cosine and sine, one
    /// rotation each: for fixed `θ`, `g` and its derivatives are affine in `(cos u_i, sin u_i)`
    /// for each input, the others fixed (a chain of revolute joints, each `Rz(θ_i + q_i)`). Then
    /// input boxes wider than [`Prediction::SECOND_ORDER_WIDTH`] are bounded at the vertices of
    /// triangles around their arcs, with no interval slopes over the box (tight on boxes of tens
    /// of degrees). A soundness claim about the prediction: by default `false`.
    const ANGULAR_INPUTS: bool = false;

    /// Whether the inputs' terms that are bounded apart take two linear programs each over the
    /// set (tighter than the parallelotope around it; worth it where the programs are small,
    /// e.g. a hexapod leg's seven parameters). By default the parallelotope alone.
    const TERMS_BY_PROGRAMS: bool = false;

    /// Whether the main terms' programs take only each measurement's own rows of the set's
    /// polyhedra ([`calib_core::CertifiedSet::query_own_rows`]: within 0.02% on the arms
    /// measured, much cheaper) rather than all of them. A scalar residual that couples many
    /// measured quantities (a hexapod leg's) needs all of them.
    const OWN_ROWS: bool = true;

    /// The prediction's evaluators.
    type Model: VectorModel<NX, NP, R> + Sync;

    /// The prediction's model.
    fn model(&self) -> &Self::Model;

    /// `g`, evaluated over second-order models in the inputs carried with their derivatives in
    /// `θ` (the generic function under `#[interval_model]`, called with these numbers).
    fn second_order(
        &self,
        x: &[Jet<Quadratic<NU>, NX>; NX],
        m: &[Jet<Quadratic<NU>, NX>; NP],
    ) -> [Jet<Quadratic<NU>, NX>; R];

    /// Moves a certified point of `set` along `direction` ([`CertifiedSet::extreme_point`] with
    /// the calibration's model): whether a point was found.
    fn push(&self, set: &mut CertifiedSet<NX, NMS>, direction: &[f64; NX]) -> bool;

    /// An enclosure of `g`'s curvature in `θ`, when the robot has one: per coordinate, an
    /// interval holding `g_r(u; θ) - g_r(u; θ̂) - ∇_θ g_r(u; θ̂)·(θ - θ̂)` for every `θ - θ̂` in
    /// `spread` and `u` in `u`. With it the columns `∂g/∂θ` are taken at `θ̂` and this enclosure
    /// is added (a one-sided one helps one side). Without it (the default) the engine takes,
    /// on boxes of inputs wider than a configuration's reading, the Taylor remainder from the
    /// model's second and third derivatives when it has them ([`taylor_remainder`]); otherwise
    /// the columns are taken over the set's outer box, whose spread times the set's reach is
    /// then the curvature term — about twice the second-order Taylor term.
    fn curvature(&self, spread: &[Interval; NX], u: &[Interval; NU]) -> Option<[Interval; R]> {
        let _ = (spread, u);
        None
    }

    /// Brackets `max g·θ` over `set` (the robot's calibration model refining the pieces where it
    /// is attained: [`calib_core::maximize_over_set`]; the refined pieces stay for the next
    /// predictions), for predictions tighter than one linear program per piece
    /// ([`SetAccuracy::predict`]; worth it where the set is small, e.g. a hexapod leg's seven
    /// parameters). `None` (the default): the programs alone.
    fn max_over_set(
        &self,
        set: &mut CertifiedSet<NX, NMS>,
        g: &[f64; NX],
    ) -> Option<SetMaximum<NX>> {
        let _ = (set, g);
        None
    }

    /// The part of the input box `u` where the task's inputs may lie (`None`: none do), for a
    /// task that is not a box (a hexapod's workspace bounds the platform's tilt). By default the
    /// box itself.
    fn narrow(&self, u: &[Interval; NU]) -> Option<[Interval; NU]> {
        Some(*u)
    }

    /// Whether the input `u` is proved to be one of the task's (instances are taken only there).
    /// By default every point of the box is.
    fn admits(&self, u: &[f64; NU]) -> bool {
        let _ = u;
        true
    }
}

/// The measurement slot of a prediction at the inputs `u`: `u`, then zeros.
pub(crate) fn slot<T: Copy, const NU: usize, const NP: usize>(u: &[T; NU], zero: T) -> [T; NP] {
    core::array::from_fn(|k| if k < NU { u[k] } else { zero })
}

/// An explicit instance of the prediction error: inputs, a geometry proved consistent with
/// every measurement, and the error they make.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance<const NX: usize, const NU: usize, const R: usize> {
    /// The commanded inputs (inside the box).
    pub inputs: [f64; NU],
    /// The inputs the robot reached: each within its own error of its command.
    pub reached: [f64; NU],
    /// The true geometry `θ*`: a certified point of the set (consistent with every measurement
    /// the set keeps: all of them, or all but the outliers its cover drops).
    pub theta: [f64; NX],
    /// `g(u + e; θ*) - g(u; θ̂)` in floating point (`u + e` the reached inputs).
    pub error: [f64; R],
    /// `‖g(u + e; θ*) - g(u; θ̂)‖`, enclosed and rounded down.
    pub value: f64,
}

/// What a robot predicts at one input over its certified set ([`SetAccuracy::predict`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Predicted<const NX: usize, const R: usize> {
    /// Per coordinate, proved to hold the prediction of every geometry of the set.
    pub outer: [Interval; R],
    /// Per coordinate, what geometries proved consistent reach (`None` when they overlap too
    /// little to say): how tight `outer` is.
    pub attained: [Option<Attained<NX>>; R],
}

/// Values of one coordinate of a prediction that certified geometries reach.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Attained<const NX: usize> {
    /// `lowest` gives at most its lower end, `highest` at least its upper end.
    pub range: Interval,
    /// A certified point of the set (consistent with every measurement the set keeps).
    pub lowest: [f64; NX],
    /// Another.
    pub highest: [f64; NX],
}

/// The median over `ranges` (each a certified range and what certified geometries attain in it)
/// of the attained share of the range's width, in percent: how tight predictions are, in one
/// number for a summary line. `None` when no range has an attained part.
pub fn median_attained_percent(
    ranges: impl Iterator<Item = (Interval, Option<Interval>)>,
) -> Option<f64> {
    let mut shares: Vec<f64> = ranges
        .filter_map(|(range, attained)| {
            let a = attained?;
            (range.wid() > 0.0).then(|| 100.0 * (a.wid() / range.wid()).min(1.0))
        })
        .filter(|v| v.is_finite())
        .collect();
    shares.sort_by(f64::total_cmp);
    shares.get(shares.len() / 2).copied()
}

/// A certified bracket of the largest prediction error.
#[derive(Clone, Debug, PartialEq)]
pub struct Bracket<const NX: usize, const NU: usize, const R: usize> {
    /// Proved over the whole input box and set (`+∞` when an enclosure failed).
    pub upper: f64,
    /// Attained by `worst`.
    pub lower: f64,
    /// The worst instance found.
    pub worst: Option<Instance<NX, NU, R>>,
    /// Where a larger error could still hide: the input box that gives `upper`.
    pub frontier: [Interval; NU],
    /// Whether `upper <= (1 + rel_tol) lower` was reached (else the box budget ran out).
    pub converged: bool,
    /// Input boxes examined.
    pub boxes: usize,
    /// Wall-clock seconds.
    pub seconds: f64,
}

impl<const NX: usize, const NU: usize, const R: usize> Bracket<NX, NU, R> {
    /// `upper / lower` (`+∞` without a positive lower bound).
    pub fn ratio(&self) -> f64 {
        calib_core::bracket_ratio(self.upper, self.lower)
    }
}

/// When to stop the branch and bound over the inputs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BracketSettings {
    /// Stop at `upper <= (1 + rel_tol) lower`.
    pub rel_tol: f64,
    /// Examine at most this many input boxes.
    pub max_boxes: usize,
}
