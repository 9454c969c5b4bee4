//! A leg's length error over its certified set: the hexapod's prediction for
//! [`calib_pipeline::accuracy`], the engine that bounds it at the set's scale.
//!
//! The controller commands `L(X; θ̂)` at the pose `X = (p, q)`; the real leg needs `L(X; θ*)`
//! for some `θ*` in its certified set: the engine brackets `max |L(X; θ*) - L(X; θ̂)|` over the
//! workspace and the set.

use super::enclosure::{refined_maximum, AccuracyProblem, Instance, PoseBox, PoseVector};
use super::model::{leg_reading, LegCurvature, LegReading};
use crate::LegModel;
use calib_core::{CertifiedSet, Interval, Jet, Model, Quadratic, SetMaximum};
use calib_pipeline::accuracy::{bracket_over_set, BracketSettings, Prediction, SetAccuracy};

/// One leg's length at a pose as a prediction, the pose `(p, q)` in the measurement slot; the
/// workspace (its tilt and stroke) from the accuracy problem.
pub struct LegLength<'a> {
    problem: &'a AccuracyProblem,
    leg: usize,
}

/// Refinements of a leg's set per prediction and side (the refined pieces are kept for the next
/// predictions: a leg's set gets finer where its predictions reach) …
const REFINEMENTS: usize = 16;
/// … until it has this many pieces.
const MAX_PIECES: usize = 96;

/// A second-order model in the pose's noise symbols, with derivatives in the leg's geometry.
type PoseJet = Jet<Quadratic<6>, 7>;

impl Prediction<7, 8, 6, 6, 1> for LegLength<'_> {
    const OWN_ROWS: bool = false;

    const TERMS_BY_PROGRAMS: bool = true;

    type Model = LegReading;

    fn model(&self) -> &LegReading {
        &LegReading
    }

    fn second_order(&self, x: &[PoseJet; 7], m: &[PoseJet; 6]) -> [PoseJet; 1] {
        [leg_reading(x, m)]
    }

    fn push(&self, set: &mut CertifiedSet<7, 8>, direction: &[f64; 7]) -> bool {
        let model = LegModel::of_set(set);
        set.extreme_point(&model, direction).is_some()
    }

    /// `0 <= L(X; θ) - L(X; θ̂) - ∇_θ L(X; θ̂)·δ <=` [`super::model::leg_curvature`].
    fn curvature(&self, spread: &[Interval; 7], x: &PoseBox) -> Option<[Interval; 1]> {
        // The bound's premise (`|d| < |v|`, a positive denominator) holds where its enclosure
        // is bounded and non-negative with a positive upper end (a negative denominator over a
        // zero numerator would give `[-0, -0]`).
        let c = LegCurvature.residual_interval(spread, &self.problem.inputs(self.leg, x));
        let premise = c.is_bounded() && !c.is_empty() && c.inf() >= 0.0 && c.sup() > 0.0;
        premise.then(|| [Interval::new(0.0, c.sup())])
    }

    /// Refined where the bound is attained, until within 0.5% of the set's range of `g·θ` or
    /// 16 refinements (none once the set has 96 pieces: each solves a program per piece).
    fn max_over_set(&self, set: &mut CertifiedSet<7, 8>, g: &[f64; 7]) -> Option<SetMaximum<7>> {
        let refinements = if set.pieces().len() < MAX_PIECES {
            REFINEMENTS
        } else {
            0
        };
        refined_maximum(set, g, refinements)
    }

    fn narrow(&self, x: &PoseBox) -> Option<PoseBox> {
        if !self.problem.may_be_feasible(x) {
            return None;
        }
        self.problem.within_tilt(x)
    }

    fn admits(&self, x: &PoseVector) -> bool {
        self.problem.proved_feasible(x)
    }
}

/// The engine's problem for leg `leg`'s length over its certified set on the poses of `domain`
/// (within the problem's workspace): `None` if the leg has no set.
pub(crate) fn leg_engine<'a>(
    problem: &'a AccuracyProblem,
    leg: usize,
    domain: &PoseBox,
    prediction: &'a LegLength<'a>,
) -> Option<SetAccuracy<'a, LegLength<'a>, 7, 8, 6, 6, 1>> {
    let set = problem.leg_set(leg)?.set().clone();
    SetAccuracy::new(prediction, set, *problem.nominal(leg), *domain, [0.0; 6])
}

impl<'a> LegLength<'a> {
    /// Leg `leg`'s length, in `problem`'s workspace.
    pub(crate) fn new(problem: &'a AccuracyProblem, leg: usize) -> Self {
        LegLength { problem, leg }
    }
}

/// Brackets leg `leg`'s length error over its certified set on the poses of `domain` (within
/// the problem's workspace): `None` if the leg has no set.
pub(crate) fn bracket_leg_over_set(
    problem: &AccuracyProblem,
    leg: usize,
    domain: &PoseBox,
    settings: &BracketSettings,
) -> Option<super::Bracket> {
    let prediction = LegLength::new(problem, leg);
    let engine = leg_engine(problem, leg, domain, &prediction)?;
    let b = bracket_over_set(&engine, settings);
    let worst = b.worst.map(|w| Instance {
        pose: w.inputs,
        theta: w.theta.map(Interval::point),
        value: w.value,
    });
    Some(super::Bracket {
        upper: b.upper,
        lower: b.lower,
        worst,
        frontier: b.frontier,
        converged: b.converged,
        boxes: b.boxes,
    })
}
