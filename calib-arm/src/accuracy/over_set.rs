//! The tool-point error over the certified set (a calibrated file that carries one): the arm's
//! prediction for [`calib_pipeline::accuracy`], the engine that bounds it at the set's scale.
//!
//! The controller computes `p(q; θ̂)`; the real arm has some `θ*` in the certified set `S` and
//! its joints reach `q + e`, `|e_i| <= joint_deg`: the engine brackets
//! `max ‖p(q + e; θ*) - p(q; θ̂)‖` over the joint box, `S` and the encoders' errors.

use super::{ToolBracket, ToolInstance};
use crate::certification::{padded_index, ArmSet, MAX_JOINTS, NM, NX};
use crate::joint_space::JointSpace;
use crate::model::arm7_point;
use crate::robot::Arm;
use crate::units::{deg_to_rad, to_deg};
use crate::{Arm7Point, ArmError};
use calib_core::{CertifiedSet, Interval, Jet, Quadratic};
use calib_pipeline::accuracy::{
    bracket_over_inputs, bracket_over_set, Bracket, BracketSettings, Instance, Prediction,
    SetAccuracy,
};

/// The arm's tool point as a prediction: `p(q; θ)` from the padded model, the joints in the
/// measurement slot (the tracked point's part 0, so that the residual is the point itself).
pub struct ToolPoint;

impl Prediction<NX, NM, NM, MAX_JOINTS, 3> for ToolPoint {
    /// Sines and cosines of a joint deviating by at most 1 rad from its centre keep their
    /// second-order models ([`Quadratic`]).
    const SECOND_ORDER_WIDTH: f64 = 1.0;

    /// Every joint turns one rotation `Rz(theta_i + q_i)` of the chain (padded joints too).
    const ANGULAR_INPUTS: bool = true;

    type Model = Arm7Point;

    fn model(&self) -> &Arm7Point {
        &Arm7Point
    }

    fn second_order(
        &self,
        x: &[Jet<Quadratic<MAX_JOINTS>, NX>; NX],
        m: &[Jet<Quadratic<MAX_JOINTS>, NX>; NM],
    ) -> [Jet<Quadratic<MAX_JOINTS>, NX>; 3] {
        arm7_point(x, m)
    }

    fn push(&self, set: &mut CertifiedSet<NX, NM>, direction: &[f64; NX]) -> bool {
        set.extreme_point(&Arm7Point, direction).is_some()
    }
}

/// The engine's problem for the tool point of the calibrated `arm` (its values, in the model's
/// units: what the controller computes with) over its certified `set`, on the padded joint box
/// `domain` (radians), every joint within `joint_deg` of its command.
pub(crate) fn tool_point_engine(
    arm: &Arm,
    set: ArmSet,
    domain: [Interval; MAX_JOINTS],
    joint_deg: f64,
) -> Result<ToolPointEngine, ArmError> {
    if !(joint_deg.is_finite() && joint_deg >= 0.0) {
        return Err(ArmError::JointError(joint_deg));
    }
    let joints = arm.joints.len();
    let mut nominal = [0.0; NX];
    let units = crate::params::names(joints);
    for ((&p, v), (_, unit)) in padded_index(joints).iter().zip(arm.nominal()).zip(&units) {
        nominal[p] = match unit {
            crate::params::Unit::Deg => crate::units::to_rad(v),
            crate::params::Unit::Mm => v,
        };
    }
    let joint_rad = deg_to_rad(Interval::point(joint_deg)).sup();
    let input_error = core::array::from_fn(|i| if i < joints { joint_rad } else { 0.0 });
    SetAccuracy::new(&ToolPoint, set, nominal, domain, input_error).ok_or(ArmError::EmptySet)
}

/// The joints `[lo, hi]` (degrees) in radians, enclosed.
pub(crate) fn joint_box(lo: f64, hi: f64) -> Interval {
    let (l, h) = (
        deg_to_rad(Interval::point(lo)),
        deg_to_rad(Interval::point(hi)),
    );
    Interval::new(l.inf(), h.sup())
}

/// The engine's problem for the arm's tool point.
pub(crate) type ToolPointEngine = SetAccuracy<'static, ToolPoint, NX, NM, NM, MAX_JOINTS, 3>;

/// The tool-point accuracy problem over a certified set.
pub struct SetToolAccuracy {
    joints: usize,
    engine: ToolPointEngine,
}

impl SetToolAccuracy {
    /// The problem for the calibrated `arm` (its values: what the controller computes with) over
    /// its certified `set`, on `space`, every joint within `joint_deg` of its command.
    pub fn new(
        arm: &Arm,
        set: ArmSet,
        space: &JointSpace,
        joint_deg: f64,
    ) -> Result<Self, ArmError> {
        let joints = arm.joints.len();
        if space.ranges_deg.len() != joints {
            return Err(ArmError::JointSpaceRanges {
                ranges: space.ranges_deg.len(),
                joints,
            });
        }
        let mut domain = [Interval::ZERO; MAX_JOINTS];
        for (i, &[lo, hi]) in space.ranges_deg.iter().enumerate() {
            domain[i] = joint_box(lo, hi);
        }
        let engine = tool_point_engine(arm, set, domain, joint_deg)?;
        Ok(SetToolAccuracy { joints, engine })
    }

    /// The joint box searched (radians, padded joints at 0).
    pub fn domain(&self) -> [Interval; MAX_JOINTS] {
        self.engine.domain()
    }

    /// An instance in the arm's terms (degrees, unpadded parameters; the joint error reached,
    /// `e_i`, moved into `theta_i` as the model's `Rz(theta_i + q_i)` allows).
    fn tool_instance(&self, i: &Instance<NX, MAX_JOINTS, 3>) -> ToolInstance {
        let index = padded_index(self.joints);
        let mut theta: Vec<Interval> = index.iter().map(|&p| Interval::point(i.theta[p])).collect();
        for k in 0..self.joints {
            let e = Interval::point(i.reached[k]) - Interval::point(i.inputs[k]);
            theta[5 * k] += e;
        }
        ToolInstance {
            joints_deg: i.inputs[..self.joints].iter().map(|v| to_deg(*v)).collect(),
            joints_rad: i.inputs[..self.joints].to_vec(),
            theta,
            error: i.error,
            value: i.value,
        }
    }
}

/// Brackets the tool-point error over the certified set ([`calib_pipeline::accuracy`]).
pub fn certify_set_accuracy(
    problem: &SetToolAccuracy,
    settings: &super::ToolAccuracySettings,
) -> ToolBracket {
    let b = bracket_over_set(
        &problem.engine,
        &BracketSettings {
            rel_tol: settings.rel_tol,
            max_boxes: settings.max_set_boxes,
        },
    );
    problem.tool_bracket(&b)
}

/// [`certify_set_accuracy`] over the configurations `list` (thin joint boxes, radians, padded)
/// instead of the problem's joint box ([`bracket_over_inputs`]).
pub fn certify_set_accuracy_at(
    problem: &SetToolAccuracy,
    list: &[[Interval; MAX_JOINTS]],
    settings: &super::ToolAccuracySettings,
) -> ToolBracket {
    let b = bracket_over_inputs(
        &problem.engine,
        list,
        &BracketSettings {
            rel_tol: settings.rel_tol,
            max_boxes: list.len(),
        },
    );
    problem.tool_bracket(&b)
}

impl SetToolAccuracy {
    /// The engine's bracket in the arm's terms.
    fn tool_bracket(&self, b: &Bracket<NX, MAX_JOINTS, 3>) -> ToolBracket {
        ToolBracket {
            upper: b.upper,
            lower: b.lower,
            worst: b.worst.as_ref().map(|w| self.tool_instance(w)),
            frontier_deg: super::frontier_deg(&b.frontier, self.joints),
            converged: b.converged,
            boxes: b.boxes,
            seconds: b.seconds,
        }
    }
}
