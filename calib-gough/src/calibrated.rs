//! The calibrated robot (`gough certify --write-calibrated`): the robot file a controller loads
//! after calibration, and the certified set it comes from.
//!
//! Per certified leg the file holds
//! * the **calibrated geometry** `a, b, l`: a parameter vector proved consistent with every
//!   measurement (with 5% of every error bound to spare where the data allow), chosen towards
//!   the Chebyshev centre of the leg's predicted lengths over the workspace, so that the worst
//!   leg-length error a controller loading it can make is as small as the data allow
//!   ([`calib_core::calibrated_point()`], [`PointRule::PredictionCentre`]);
//! * `radius`: a box around that geometry containing the certified outer box (so that a reader
//!   that knows only boxes still holds every consistent geometry);
//! * `[leg.certified_set]`: the measurement boxes, the cover and certified points from which the
//!   certified set is rebuilt ([`calib_pipeline::stored_set`]), so that `gough accuracy` and
//!   `gough predict` bound errors over the set from the file alone.
//!
//! The box midpoint, written before, did not fit the data: on `sample21` it misfits 11 to 58
//! times the error bounds, because the set is thin along `a_z + l - b_z` and the box is not.

use crate::accuracy::LegReading;
use crate::certification::{carried_boxes, LegResult};
use crate::files::{leg_sets, LegSpec, RobotFile};
use crate::geometry::{Leg, Pose};
use crate::measurement::{Configuration, Orientation, Uncertainty};
use crate::workspace::Workspace;
use crate::GoughError;
use crate::LegModel;
use calib_core::{calibrated_point, CalibratedPoint, CertifiedSet, Model, PointRule};
use calib_pipeline::calibrated::radius_about;
use calib_pipeline::stored_set::StoredSet;
use rand::SeedableRng;
use std::fmt::Write as _;

/// At most this many pieces per leg's set: each leg-length bound over a box of poses solves two
/// linear programs per piece.
pub const MAX_PIECES: usize = 8;

/// Poses sampled in the workspace for the Chebyshev centre of the predictions.
const PREDICTION_POSES: usize = 300;

/// The calibrated robot: the geometry per leg and, for the legs certified, their sets.
#[derive(Clone, Debug)]
pub struct CalibratedRobot {
    /// The geometry a controller loads (the legs not certified in this run as they were).
    pub legs: Vec<LegSpec>,
    /// Per leg, its certified set (`None` for a leg not certified in this run).
    pub sets: Vec<Option<CertifiedSet<7, 8>>>,
    /// Per leg, how its geometry was chosen (`None` for a leg not certified in this run).
    pub points: Vec<Option<CalibratedPoint<7>>>,
}

impl CalibratedRobot {
    /// The legs not certified in this run (`--legs`) keep the certified sets their robot file
    /// `robot` (read from `file`) gives them (rebuilt and proved again, [`leg_sets`]), so that the
    /// file written still holds them.
    pub fn keep_stored_sets(
        &mut self,
        file: &std::path::Path,
        robot: &RobotFile,
    ) -> Result<(), calib_pipeline::DataError> {
        let kept: Vec<usize> = (0..self.sets.len())
            .filter(|&i| self.sets[i].is_none() && robot.sets.get(i).is_some_and(Option::is_some))
            .collect();
        if kept.is_empty() {
            return Ok(());
        }
        let mut sets = leg_sets(file, robot)?;
        for i in kept {
            self.sets[i] = sets[i].take();
        }
        Ok(())
    }
}

/// The workspace the predictions are taken over when none is given: the box of the measured
/// positions and the largest measured rotation.
pub fn measured_workspace(configs: &[Configuration]) -> Workspace {
    let range = |k: usize| {
        configs
            .iter()
            .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], c| {
                [lo.min(c.p[k]), hi.max(c.p[k])]
            })
    };
    let tilt = configs
        .iter()
        .map(|c| match c.orientation {
            Orientation::AxisAngle { angle_deg, .. } => angle_deg.abs(),
            Orientation::Rodrigues(q) => {
                2.0 * (q[0] * q[0] + q[1] * q[1] + q[2] * q[2])
                    .sqrt()
                    .atan()
                    .to_degrees()
            }
        })
        .fold(0.0, f64::max);
    Workspace {
        x: range(0),
        y: range(1),
        z: range(2),
        tilt_deg: tilt,
        stroke: None,
    }
}

/// Where the calibrated geometry should predict best: the Chebyshev centre of the leg lengths it
/// predicts there is the target of its choice ([`PointRule::PredictionCentre`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Task<'a> {
    /// 300 poses sampled in a workspace.
    Workspace(&'a Workspace),
    /// Exactly these poses (`gough certify --task poses.csv`).
    Poses(&'a [Pose]),
}

impl Task<'_> {
    /// The task's poses (sampled in a workspace with the legs of `robot`).
    fn poses(&self, robot: &[LegSpec]) -> Vec<Pose> {
        match self {
            Task::Poses(poses) => poses.to_vec(),
            Task::Workspace(workspace) => {
                let mut rng = rand::rngs::StdRng::seed_from_u64(0x5e7);
                let legs: Vec<Leg> = robot.iter().map(|s| s.nominal).collect();
                (0..PREDICTION_POSES)
                    .filter_map(|k| workspace.sample(&mut rng, &legs, k % 2 == 0))
                    .collect()
            }
        }
    }
}

/// A task file read (`gough certify --task FILE`): a workspace or a list of poses.
#[derive(Clone, Debug, PartialEq)]
pub enum TaskFile {
    /// `workspace.toml`.
    Workspace(Workspace),
    /// A poses CSV (`px,py,pz,ax,ay,az,angle_deg`, as `gough design` writes it).
    Poses(Vec<Pose>),
}

impl TaskFile {
    /// Reads a task: a `.toml` file is a workspace ([`crate::workspace::read_workspace`]), any
    /// other a poses CSV ([`crate::files::parse_poses_at_least`], at least one pose). Errors name
    /// the file, the line and the field.
    pub fn read(file: &std::path::Path) -> Result<TaskFile, calib_pipeline::DataError> {
        if file.extension().is_some_and(|e| e == "toml") {
            return crate::workspace::read_workspace(file).map(TaskFile::Workspace);
        }
        let text = calib_pipeline::read_text(file)?;
        crate::files::parse_poses_at_least(file, &text, 1).map(TaskFile::Poses)
    }

    /// The task it describes.
    pub fn task(&self) -> Task<'_> {
        match self {
            TaskFile::Workspace(w) => Task::Workspace(w),
            TaskFile::Poses(p) => Task::Poses(p),
        }
    }
}

/// The gradients `∂L_i/∂θ` of a leg's reading at `poses` (at the geometry `at`): the
/// predictions whose Chebyshev centre the calibrated geometry approaches.
fn predictions(poses: &[Pose], at: &[f64; 7]) -> Vec<[f64; 7]> {
    poses
        .iter()
        .map(|pose| {
            let q = pose.rodrigues();
            LegReading.jacobian_x(at, &[pose.p[0], pose.p[1], pose.p[2], q[0], q[1], q[2]])
        })
        .collect()
}

/// The calibrated robot from the certified legs (see the module documentation): predictions over
/// `task`, or over [`measured_workspace`] when none is given. An error naming a leg proved
/// inconsistent, or a leg with no geometry proved consistent (undecided): there is then no
/// calibrated geometry to hand out.
pub fn calibrated_robot(
    robot: &[LegSpec],
    results: &[LegResult],
    configs: &[Configuration],
    u: &Uncertainty,
    task: Option<Task<'_>>,
) -> Result<CalibratedRobot, GoughError> {
    let fallback = measured_workspace(configs);
    let poses = task.unwrap_or(Task::Workspace(&fallback)).poses(robot);
    let mut out = CalibratedRobot {
        legs: robot.to_vec(),
        sets: vec![None; robot.len()],
        points: vec![None; robot.len()],
    };
    for r in results {
        let leg = r.leg + 1;
        let outer = r.outer.ok_or(GoughError::LegInconsistent(leg))?;
        let undecided = || GoughError::LegUndecided(leg);
        let witness = r.points.first().ok_or_else(undecided)?;
        // The rows the leg was certified against: the new ones, then those carried over.
        let stored = r.carried.as_ref().map(|c| &c.stored);
        let boxes = carried_boxes(configs, u, r.leg, stored);
        let model = LegModel::of(configs);
        let mut set = CertifiedSet::new(&model, &r.cover, &boxes, &r.points, MAX_PIECES);
        let preds = predictions(&poses, witness);
        let point = calibrated_point(&model, &mut set, PointRule::PredictionCentre(&preds))
            .ok_or_else(undecided)?;
        let spec = &robot[r.leg];
        let nominal = spec.nominal.params();
        let mut value = [0.0; 7];
        let mut radius = [0.0; 7];
        for j in 0..7 {
            if spec.radius[j] == 0.0 {
                value[j] = nominal[j];
            } else {
                value[j] = point.x[j];
                radius[j] = radius_about(
                    value[j],
                    outer[j].hull(set.outer().map_or(outer[j], |o| o[j])),
                );
            }
        }
        out.legs[r.leg] = LegSpec {
            nominal: Leg::from_params(&value),
            radius,
        };
        out.sets[r.leg] = Some(set);
        out.points[r.leg] = Some(point);
    }
    Ok(out)
}

/// `robot.toml` text for `legs` (shortest round-trip decimals; read back bit-identical), with
/// each leg's certified set when given (`[leg.certified_set]`, in cm and degrees, the
/// measurements as stated: `px, py, pz, ax, ay, az, angle_deg, L` for axis–angle data,
/// `px, py, pz, q1, q2, q3, L` for Rodrigues data; [`LegModel::stored_quantities`]).
pub fn robot_toml(legs: &[LegSpec], sets: &[Option<CertifiedSet<7, 8>>], comment: &str) -> String {
    let mut text = String::new();
    for line in comment.lines() {
        let _ = writeln!(text, "# {line}");
    }
    let all: Vec<usize> = (0..7).collect();
    for (i, spec) in legs.iter().enumerate() {
        let l = &spec.nominal;
        let _ = writeln!(
            text,
            "\n[[leg]]\na = {:?}\nb = {:?}\nl = {:?}\nradius = {:?}",
            l.a, l.b, l.l, spec.radius
        );
        if let Some(Some(set)) = sets.get(i) {
            let quantities = LegModel::of_set(set).stored_quantities();
            text.push_str(&StoredSet::of(set, &all, quantities).to_toml("leg.certified_set"));
        }
    }
    text
}
