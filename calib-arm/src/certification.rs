//! Certifying an arm: the arm's data turned into the robot-agnostic pipeline's inputs (the model
//! for its joint count, the prior box and one measurement box per configuration, in the model's
//! radians), and its outputs turned back into the files' millimetres and degrees.
//!
//! An arm is one sub-problem: all its configurations constrain one parameter vector.
//!
//! Every arm goes through the 7-joint model ([`Arm7Point`]): an arm of `N < 7` joints is padded
//! with `7 - N` identity joints (every parameter fixed at 0, joint readings exactly 0, so each
//! padded `A_i` is the identity matrix, exactly, in interval arithmetic too). The certified set is
//! the arm's own, and the kernel is compiled once instead of once per joint count (minutes of
//! build time each).

use crate::params::{self, Unit};
use crate::robot::Arm;
use crate::simulate::{measurement_box, Reading, Uncertainty};
use crate::units::{rad_to_deg, to_deg, to_rad};
use crate::{Arm7Point, ArmError};
use calib_core::{CertifiedSet, Interval, Settings};
use calib_pipeline::design::CandidateRows;
use calib_pipeline::identify::{analyse, identification_jacobian, Identifiability};
use calib_pipeline::lsq::{least_squares, Fit};
use calib_pipeline::report::OutcomeReport;
use calib_pipeline::verdict::{self, ConfigurationNames};
use calib_pipeline::{
    certify_model, check_hull_options, smallest_consistent, Depth, OptionError, Outcome,
    OutlierBudget,
};

/// What one run on an arm's data found (every value in the files' units: mm and degrees).
#[derive(Clone, Debug)]
pub struct ArmRun {
    /// The certified outcome.
    pub outcome: Outcome,
    /// The identifiability of the free parameters on these configurations, at the nominal.
    pub identifiability: Identifiability,
    /// The least-squares fit from the nominal (`None` when not asked for).
    pub fit: Option<Fit>,
    /// The certified set, in the padded model's parameters and units (radians, mm; see
    /// [`ArmSet`]): `None` when nothing was certified or the data were proved inconsistent. For a
    /// 6-DoF run, the set the position equations leave within the projection of the 6-DoF cover
    /// (it holds every parameter vector of [`ArmRun::pose_set`], without the tool rotation).
    pub set: Option<ArmSet>,
    /// A 6-DoF run's certified set in the padded pose model (the tool frame's rotation appended,
    /// [`crate::pose::certification::PoseSet`]); `None` for positions.
    pub pose_set: Option<crate::pose::certification::PoseSet>,
    /// A run with a certified set carried over: the set over both series in the two-frame model
    /// ([`crate::carry::TwoFrameSet`]), where the written vector is chosen and proved; `None`
    /// otherwise.
    pub two_frame_set: Option<crate::carry::TwoFrameSet>,
}

/// An arm's certified set in the padded model (every arm goes through the 7-joint model): its
/// parameters are [`padded_index`] of the arm's, in radians and mm; its measured quantities the
/// joint readings (radians, padded joints at 0) and the tracked point (mm).
pub type ArmSet = CertifiedSet<NX, NM>;

/// At most this many pieces in an arm's certified set: each query solves one linear program of
/// up to 44 variables per piece.
pub const ARM_PIECES: usize = 1;

/// What to compute.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunOptions {
    /// x1 only, or the tight hull.
    pub depth: Depth,
    /// Also the least-squares fit.
    pub lsq: bool,
}

/// The parameter names of an arm with `joints` joints.
pub fn names(joints: usize) -> Vec<String> {
    params::names(joints).into_iter().map(|(n, _)| n).collect()
}

/// The unit symbols of the parameters `names` (an arm's, with the tool rotation's in a 6-DoF
/// run; see [`params::unit_of`]).
pub fn units_of(names: &[String]) -> Vec<String> {
    names
        .iter()
        .map(|n| params::unit_of(n).map_or("", Unit::symbol).to_string())
        .collect()
}

/// The unit symbols of an arm with `joints` joints.
pub fn units(joints: usize) -> Vec<String> {
    params::names(joints)
        .into_iter()
        .map(|(_, u)| u.symbol().to_string())
        .collect()
}

/// `v` (model units: radians for angles) in the files' units, enclosed outward.
fn to_file_units(unit: Unit, v: Interval) -> Interval {
    match unit {
        Unit::Deg => rad_to_deg(v),
        Unit::Mm => v,
    }
}

/// What a run computes besides identifiability.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Job {
    Identify,
    Fit,
    Certify(RunOptions),
}

/// The identifiability of `arm`'s free parameters on the configurations of `readings`, at the
/// nominal geometry (no certification).
pub fn identifiability(
    arm: &Arm,
    readings: &[Reading],
    u: &Uncertainty,
) -> Result<Identifiability, ArmError> {
    Ok(dispatch(arm, readings, u, Job::Identify, &Settings::default())?.identifiability)
}

/// The least-squares fit of `arm`'s free parameters to `readings` (taken as exact), from the
/// nominal, in the files' units.
pub fn fit_arm(arm: &Arm, readings: &[Reading]) -> Result<Fit, ArmError> {
    let exact = Uncertainty {
        joint_deg: 0.0,
        pos: 0.0,
    };
    dispatch(arm, readings, &exact, Job::Fit, &Settings::default())?
        .fit
        .ok_or(ArmError::NoFit)
}

/// Whether the arm's nominal values — one parameter vector — are proved consistent with every
/// reading within the error bounds `u` ([`calib_core::is_consistent_point`] on the padded model:
/// for each configuration, one joint reading and tracked point within their bounds that fit all
/// three coordinates). `false` means *not proved*; the prior box plays no part.
pub fn is_consistent_arm(arm: &Arm, readings: &[Reading], u: &Uncertainty) -> bool {
    let joints = arm.joints.len();
    if !(3..=MAX_JOINTS).contains(&joints) || readings.iter().any(|r| r.joints_deg.len() != joints)
    {
        return false;
    }
    let boxes: Vec<[Interval; NM]> = readings
        .iter()
        .filter_map(|r| measurement_box(r, u))
        .collect();
    calib_core::is_consistent_point(&Arm7Point, &padded_nominal(arm), &boxes)
}

/// What `arm certify` computes, as options (the command line's, and the Python package's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CertifyRequest {
    /// x1 only, or the tight hull.
    pub depth: Depth,
    /// The hull's tolerance: stop at `wid(outer) <= (1 + tol) wid(inner)`.
    pub tolerance: f64,
    /// The hull's box budget.
    pub max_boxes: usize,
    /// The hull's time budget.
    pub max_seconds: Option<f64>,
    /// Tolerated outliers: a number, or the smallest number not proved empty.
    pub max_outliers: OutlierBudget,
    /// Also the least-squares fit.
    pub lsq: bool,
}

impl Default for CertifyRequest {
    fn default() -> Self {
        CertifyRequest {
            depth: Depth::Fast,
            tolerance: 0.10,
            max_boxes: 10_000,
            max_seconds: None,
            max_outliers: OutlierBudget::Fixed(0),
            lsq: false,
        }
    }
}

impl CertifyRequest {
    /// The kernel settings for `configs` configurations (outliers are set per try); errors name
    /// the option as the command line spells it.
    pub fn settings(&self, configs: usize) -> Result<Settings, OptionError> {
        check_hull_options(self.tolerance, self.max_seconds)?;
        self.max_outliers.check(configs)?;
        Ok(arm_settings()
            .with_hull_tolerance(self.tolerance)
            .with_hull_budget(self.max_boxes, self.max_seconds))
    }

    /// The settings (outliers set per try) and options of each certification this request makes
    /// on `configs` configurations.
    pub(crate) fn prepared(&self, configs: usize) -> Result<(Settings, RunOptions), OptionError> {
        let mut settings = self.settings(configs)?;
        if self.max_outliers == OutlierBudget::Auto {
            // Every result `auto` keeps is consistent, or tolerates outliers: a conflict set
            // (sought only for an empty verdict with none tolerated) would be thrown away.
            settings = settings.with_conflict_sets(false);
        }
        let options = RunOptions {
            depth: self.depth,
            lsq: self.lsq,
        };
        Ok((settings, options))
    }
}

/// Certifies `arm` as `arm certify` does: with [`OutlierBudget::Auto`], with the smallest number
/// of tolerated outliers not proved empty. Returns that number and the run.
pub fn certify_request(
    arm: &Arm,
    readings: &[Reading],
    u: &Uncertainty,
    request: &CertifyRequest,
) -> Result<(usize, ArmRun), ArmError> {
    let (settings, options) = request.prepared(readings.len())?;
    smallest_consistent(
        request.max_outliers,
        readings.len(),
        |q| {
            certify_arm(
                arm,
                readings,
                u,
                options,
                &settings.clone().with_max_outliers(q),
            )
        },
        |run| run.outcome.status == calib_core::Status::Empty,
    )
}

/// The JSON report of a run (the layout of [`calib_pipeline::report`]) with `tolerated` outliers.
pub fn json_report(run: &ArmRun, names: &ConfigurationNames<'_>, tolerated: usize) -> String {
    let o = &run.outcome;
    let mut sentences = verdict::verdict(o, names, tolerated);
    sentences.extend(verdict::not_determined(o));
    sentences.extend(verdict::outliers(o, names, tolerated));
    let mut report = OutcomeReport::new(
        o,
        &units_of(&o.names),
        sentences,
        run.identifiability.sentences(&o.names),
        run.fit.as_ref().map(|f| &f.x[..]),
    );
    report.outliers_tolerated = tolerated;
    report.to_json()
}

/// The kernel settings the `arm` commands start from: the defaults, with
/// [`Settings::inner_bisections`] at [`INNER_BISECTIONS`].
pub fn arm_settings() -> Settings {
    Settings {
        inner_bisections: INNER_BISECTIONS,
        ..Settings::default()
    }
}

/// Bisection steps of the inner-bound search for an arm. Each step certifies a point against every
/// configuration (a Krawczyk proof per configuration), and 12 steps already place each inner face
/// within `2⁻¹²` of its search segment (a few hundredths of a per cent of the outer width), far
/// below any tolerance a user asks of the hull; the kernel's default 24 made the search two thirds
/// of the built-in arm's run.
pub const INNER_BISECTIONS: usize = 12;

/// Certifies `arm` against `readings` with the error bounds `u`.
pub fn certify_arm(
    arm: &Arm,
    readings: &[Reading],
    u: &Uncertainty,
    options: RunOptions,
    settings: &Settings,
) -> Result<ArmRun, ArmError> {
    dispatch(arm, readings, u, Job::Certify(options), settings)
}

/// Only the verdict of certifying `arm` against `readings` with the error bounds `u` (the paper's
/// x1, no inner bounds, no search of conflicting configurations): what the smallest consistent
/// error bound is searched with.
pub fn verdict_only(
    arm: &Arm,
    readings: &[Reading],
    u: &Uncertainty,
) -> Result<calib_core::Status, ArmError> {
    let (settings, options) = verdict_settings(readings.len())?;
    Ok(certify_arm(arm, readings, u, options, &settings)?
        .outcome
        .status)
}

/// The settings and options of a verdict-only certification on `configs` configurations: x1,
/// no inner bounds, no search of conflicting configurations.
pub(crate) fn verdict_settings(configs: usize) -> Result<(Settings, RunOptions), OptionError> {
    let mut settings = CertifyRequest::default()
        .settings(configs)?
        .with_conflict_sets(false);
    settings.inner_bounds = false;
    let options = RunOptions {
        depth: Depth::Fast,
        lsq: false,
    };
    Ok((settings, options))
}

fn dispatch(
    arm: &Arm,
    readings: &[Reading],
    u: &Uncertainty,
    job: Job,
    settings: &Settings,
) -> Result<ArmRun, ArmError> {
    check_shape(arm, readings)?;
    Ok(run(arm, readings, u, job, settings))
}

/// Whether the padded model takes `arm` (3 to [`MAX_JOINTS`] joints) and `readings` (one reading
/// per joint each); the error says what is wrong.
pub(crate) fn check_shape(arm: &Arm, readings: &[Reading]) -> Result<(), ArmError> {
    let joints = arm.joints.len();
    if !(3..=MAX_JOINTS).contains(&joints) {
        return Err(ArmError::Joints(joints));
    }
    if let Some(r) = readings.iter().find(|r| r.joints_deg.len() != joints) {
        return Err(ArmError::JointReadings {
            readings: r.joints_deg.len(),
            joints,
        });
    }
    Ok(())
}

/// The most joints an arm may have (the model every arm is padded to).
pub const MAX_JOINTS: usize = 7;
/// Parameters of the padded model.
pub const NX: usize = 5 * MAX_JOINTS + 9;
/// Measured quantities of the padded model.
pub const NM: usize = MAX_JOINTS + 3;

/// The padded model's index of each of the arm's measured quantities (joint readings, then the
/// tracked point).
pub fn padded_quantities(joints: usize) -> Vec<usize> {
    (0..joints).chain(MAX_JOINTS..NM).collect()
}

/// The padded model's index of each of the arm's parameters (model order).
pub fn padded_index(joints: usize) -> Vec<usize> {
    let shift = 5 * (MAX_JOINTS - joints);
    (0..params::count(joints))
        .map(|j| if j < 5 * joints { j } else { j + shift })
        .collect()
}

/// The padded model's problem: the prior box, the nominal (model units), one measurement box per
/// reading, and the padded index and unit of each of the arm's parameters.
pub(crate) struct Padded<const X: usize, const Q: usize> {
    pub(crate) x0: [Interval; X],
    pub(crate) nominal: [f64; X],
    pub(crate) boxes: Vec<[Interval; Q]>,
    pub(crate) index: Vec<usize>,
    pub(crate) units: Vec<Unit>,
}

/// The arm's prior box in the padded model (radians; padded parameters are points at 0, an
/// identity joint).
pub fn padded_box(arm: &Arm) -> [Interval; NX] {
    let mut x0 = [Interval::ZERO; NX];
    for (&p, v) in padded_index(arm.joints.len()).iter().zip(arm.initial_box()) {
        x0[p] = v;
    }
    x0
}

/// The arm's nominal values in the padded model (radians; padded parameters at 0).
pub fn padded_nominal(arm: &Arm) -> [f64; NX] {
    let joints = arm.joints.len();
    let units: Vec<Unit> = params::names(joints).into_iter().map(|(_, u)| u).collect();
    let nominal_files = arm.nominal();
    let mut nominal = [0.0; NX];
    for (j, &p) in padded_index(joints).iter().enumerate() {
        nominal[p] = match units[j] {
            Unit::Deg => to_rad(nominal_files[j]),
            Unit::Mm => nominal_files[j],
        };
    }
    nominal
}

fn padded(arm: &Arm, readings: &[Reading], u: &Uncertainty) -> Padded<NX, NM> {
    let joints = arm.joints.len();
    let index = padded_index(joints);
    let units: Vec<Unit> = params::names(joints).into_iter().map(|(_, u)| u).collect();
    let x0 = padded_box(arm);
    let nominal = padded_nominal(arm);
    // At most MAX_JOINTS joint readings (checked by `dispatch`): every reading has a box.
    let boxes: Vec<[Interval; NM]> = readings
        .iter()
        .filter_map(|r| measurement_box(r, u))
        .collect();
    Padded {
        x0,
        nominal,
        boxes,
        index,
        units,
    }
}

/// The scaled identification Jacobian of `arm` on the configurations of `readings` at the
/// nominal geometry (see [`calib_pipeline::identify::identification_jacobian`]), per
/// configuration its three rows (one column per free parameter), for experiment design
/// ([`calib_pipeline::design`]); and each column's parameter (arm order).
pub fn identification_rows(
    arm: &Arm,
    readings: &[Reading],
    u: &Uncertainty,
) -> Result<(Vec<usize>, Vec<CandidateRows>), ArmError> {
    dispatch(arm, readings, u, Job::Identify, &Settings::default())?;
    let p = padded(arm, readings, u);
    let (free, j) = identification_jacobian(&Arm7Point, &p.nominal, &p.x0, &p.boxes);
    let to_arm = |q: usize| p.index.iter().position(|&r| r == q).unwrap_or(q);
    let rows = (0..readings.len())
        .map(|k| {
            (0..3)
                .map(|r| j.row(3 * k + r).iter().copied().collect())
                .collect()
        })
        .collect();
    Ok((free.into_iter().map(to_arm).collect(), rows))
}

fn run(arm: &Arm, readings: &[Reading], u: &Uncertainty, job: Job, settings: &Settings) -> ArmRun {
    let p = padded(arm, readings, u);
    let (mut run, cover) = run_model(
        &Arm7Point,
        &p,
        names(arm.joints.len()),
        &arm.initial_box(),
        job,
        settings,
    );
    run.set = cover
        .map(|(cover, points)| CertifiedSet::new(&Arm7Point, &cover, &p.boxes, &points, ARM_PIECES))
        .filter(|s| !s.is_empty());
    run
}

/// The certified cover and points of a run (model units), for its certified set.
pub(crate) type Cover<const X: usize> = (calib_core::Cover<X>, Vec<[f64; X]>);

/// A cover and its points in a model that extends the point model (its first [`NX`]
/// parameters are the point model's), without the parameters after those: the boxes' and points'
/// first `NX` coordinates, each box keeping its subset.
pub(crate) fn point_model_cover<const X: usize>((cover, points): &Cover<X>) -> Cover<NX> {
    let head = |b: &[Interval; X]| -> [Interval; NX] { core::array::from_fn(|i| b[i]) };
    let cover = calib_core::Cover {
        boxes: cover.boxes.iter().map(head).collect(),
        subsets: cover.subsets.clone(),
        dropped: cover.dropped.clone(),
    };
    let points = points
        .iter()
        .map(|x| core::array::from_fn(|i| x[i]))
        .collect();
    (cover, points)
}

/// A run of `model` on the padded problem `p` (the arm's parameters `names`, its prior `prior` in
/// model units): the outcome, identifiability and fit in the files' units (the [`ArmRun`] without
/// its set), and what a certified set is built from (`None` when nothing was certified).
pub(crate) fn run_model<M, const X: usize, const Q: usize, const R: usize>(
    model: &M,
    p: &Padded<X, Q>,
    names: Vec<String>,
    prior: &[Interval],
    job: Job,
    settings: &Settings,
) -> (ArmRun, Option<Cover<X>>)
where
    M: calib_core::VectorModel<X, Q, R> + Sync,
{
    let Padded {
        x0,
        nominal,
        boxes,
        index,
        units,
    } = p;
    let (free, jacobian) = identification_jacobian(model, nominal, x0, boxes);
    let to_arm = |p: usize| index.iter().position(|&q| q == p).unwrap_or(p);
    let mut identifiability = analyse(&free, jacobian);
    for c in identifiability
        .undetermined
        .iter_mut()
        .chain(identifiability.weak.iter_mut())
    {
        c.members.iter_mut().for_each(|m| m.0 = to_arm(m.0));
    }
    let mid = || -> Vec<[f64; Q]> { boxes.iter().map(|b| b.map(|v| v.mid())).collect() };
    let (outcome, fit, cover) = match job {
        Job::Certify(o) => {
            let all_names: Vec<String> = (0..X).map(|p| format!("#{p}")).collect();
            let c = certify_model(model, &all_names, x0, boxes, o.depth, settings);
            let fit = o.lsq.then(|| least_squares(model, nominal, &free, &mid()));
            let cover =
                (c.outcome.status != calib_core::Status::Empty).then_some((c.cover, c.points));
            (c.outcome.select(index, names), fit, cover)
        }
        Job::Fit => (
            uncertified(names, prior),
            Some(least_squares(model, nominal, &free, &mid())),
            None,
        ),
        Job::Identify => (uncertified(names, prior), None, None),
    };
    let outcome = outcome.map_units(
        |j, v| to_file_units(units[j], v),
        |j, v| match units[j] {
            Unit::Deg => to_deg(v),
            Unit::Mm => v,
        },
    );
    let fit = fit.map(|f| Fit {
        x: index
            .iter()
            .enumerate()
            .map(|(j, &p)| match units[j] {
                Unit::Deg => to_deg(f.x[p]),
                Unit::Mm => f.x[p],
            })
            .collect(),
        ..f
    });
    let run = ArmRun {
        outcome,
        identifiability,
        fit,
        set: None,
        pose_set: None,
        two_frame_set: None,
    };
    (run, cover)
}

/// An outcome with nothing certified yet (the prior box only).
fn uncertified(names: Vec<String>, x0: &[Interval]) -> Outcome {
    Outcome {
        names,
        x0: x0.to_vec(),
        status: calib_core::Status::Undecided,
        emptiness: None,
        x1: None,
        outer: None,
        inner: None,
        witness: None,
        conflict: None,
        support: None,
        spread: false,
        outliers: Vec::new(),
        iterations: 0,
        converged: None,
        boxes: 0,
        seconds: 0.0,
    }
}
