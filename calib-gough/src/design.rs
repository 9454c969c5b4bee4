//! Experiment design for the hexapod (`gough design`): which poses of a workspace to measure so
//! that every leg parameter is determined, and the certified widths a design is predicted to give.
//!
//! Candidates are random poses of the [`Workspace`] (half of each coordinate and of the angle at
//! an end of its range: informative poses lie on the boundary). Each candidate adds one row per
//! leg to the leg's scaled identification Jacobian at the nominal geometry
//! ([`calib_pipeline::identify::identification_jacobian`]); [`calib_pipeline::design`] chooses
//! among them. The prediction of a design is a certification: simulated data measured at its
//! poses (the nominal geometry as the truth, noise within the error bounds) certified with the
//! robot file's prior — the tight hull `gough certify` reports.

use crate::certification::{certify_legs, CertifyOptions, LegResult};
use crate::files::LegSpec;
use crate::geometry::{leg_reading, Leg, Pose};
use crate::measurement::{leg_boxes, measured, Configuration, Orientation, Uncertainty};
use crate::simulate::simulate_at;
use crate::workspace::Workspace;
use crate::GoughError;
use crate::LegModel;
use calib_core::Interval;
use calib_pipeline::design::{
    certified_design, greedy_design, linearized_widths, Criterion, Group,
};
use calib_pipeline::identify::identification_jacobian;
use rand::rngs::StdRng;
use rand::SeedableRng;

/// What `gough design` is asked.
#[derive(Clone, Debug, PartialEq)]
pub struct DesignRequest {
    /// The configurations to choose.
    pub configs: usize,
    /// How many candidate poses to draw from the workspace.
    pub candidates: usize,
    /// The criterion.
    pub criterion: Criterion,
    /// Seeds the candidates, the random design and the simulated noise.
    pub seed: u64,
}

impl Default for DesignRequest {
    fn default() -> Self {
        DesignRequest {
            configs: 21,
            candidates: 2000,
            criterion: Criterion::Certified,
            seed: 1,
        }
    }
}

/// Exchange sweeps over a design (see [`calib_pipeline::design::exchange`]).
pub const EXCHANGE_PASSES: usize = 3;

/// A design and what it is predicted to give.
#[derive(Clone, Debug, PartialEq)]
pub struct Design {
    /// The chosen poses (greedy order, then improved by exchanges).
    pub poses: Vec<Pose>,
    /// Per leg and parameter, the first-order certified width of the design, of a random design
    /// of the same size, and of measuring every candidate (the best this workspace allows from
    /// these candidates), in cm.
    pub first_order: Vec<[[f64; 7]; 3]>,
    /// The number of greedily chosen poses whose first-order geometric mean width already
    /// matches the random design's.
    pub matching_prefix: Option<usize>,
    /// The random design of the same size the design is compared with.
    pub random: Vec<Pose>,
}

/// The robot `gough design` plans for without a robot file: the built-in hexapod, ± 0.1 cm.
pub fn builtin_robot() -> Vec<LegSpec> {
    crate::simulate::builtin_hexapod()
        .into_iter()
        .map(|nominal| LegSpec {
            nominal,
            radius: [0.1; 7],
        })
        .collect()
}

/// The configurations of a measurements file to extend (`--extend`), checked against the error
/// bounds they need: Rodrigues data need `q` from an uncertainty file (`uncertainty_file`; the
/// built-in bounds have none).
pub fn extension(
    data: crate::files::Measurements,
    u: &Uncertainty,
    uncertainty_file: Option<&std::path::Path>,
) -> Result<Vec<Configuration>, GoughError> {
    match (data.rodrigues, uncertainty_file) {
        (false, _) => Ok(data.configs),
        (true, Some(file)) => {
            crate::files::check_uncertainty(file, u, true)?;
            Ok(data.configs)
        }
        (true, None) => Err(GoughError::ExtendNeedsQ),
    }
}

/// The geometry the poses are planned at.
fn nominal_legs(robot: &[LegSpec]) -> Vec<Leg> {
    robot.iter().map(|s| s.nominal).collect()
}

/// The configuration a pose gives at the nominal geometry (exact readings).
fn configuration(legs: &[Leg], pose: &Pose) -> Configuration {
    Configuration {
        p: pose.p,
        orientation: Orientation::AxisAngle {
            axis: pose.axis,
            angle_deg: pose.angle_deg,
        },
        lengths: legs.iter().map(|l| leg_reading(l, pose)).collect(),
    }
}

/// One [`Group`] per leg: the scaled identification rows each configuration adds (one per leg),
/// at the nominal geometry, over the leg's free parameters (radius > 0). Also the free
/// parameters of each leg.
pub fn groups(
    robot: &[LegSpec],
    configs: &[Configuration],
    u: &Uncertainty,
) -> (Vec<Group>, Vec<Vec<usize>>) {
    robot
        .iter()
        .enumerate()
        .map(|(leg, spec)| {
            let nominal = spec.nominal.params();
            let x0: [Interval; 7] = core::array::from_fn(|j| measured(nominal[j], spec.radius[j]));
            let boxes = leg_boxes(configs, u, leg);
            let (free, j) = identification_jacobian(&LegModel::of(configs), &nominal, &x0, &boxes);
            let rows = (0..configs.len())
                .map(|k| vec![j.row(k).iter().copied().collect()])
                .collect();
            (
                Group {
                    dim: free.len(),
                    rows,
                },
                free,
            )
        })
        .unzip()
}

/// First-order widths in cm (fixed parameters: 0) of the chosen configurations.
fn widths_cm(
    robot: &[LegSpec],
    groups: &[Group],
    free: &[Vec<usize>],
    chosen: &[usize],
) -> Vec<[f64; 7]> {
    robot
        .iter()
        .zip(groups.iter().zip(free))
        .map(|(spec, (g, free))| {
            let w = linearized_widths(g, chosen);
            let mut out = [0.0; 7];
            for (c, &p) in free.iter().enumerate() {
                out[p] = w[c] * spec.radius[p];
            }
            out
        })
        .collect()
}

/// The geometric mean of the positive entries.
pub fn geometric_mean(widths: impl IntoIterator<Item = f64>) -> f64 {
    let (s, n) = widths
        .into_iter()
        .filter(|w| *w > 0.0)
        .fold((0.0, 0usize), |(s, n), w| (s + w.ln(), n + 1));
    if n == 0 {
        0.0
    } else {
        (s / n as f64).exp()
    }
}

/// Designs `request.configs` poses of `workspace` for `robot` (see the module documentation).
/// With `measured_already`, those configurations are kept and the design extends them (the
/// sequential design of `--extend`). `progress` is called after each chosen pose. Errors: a
/// workspace whose stroke excludes the poses, or too few candidates.
pub fn design(
    robot: &[LegSpec],
    u: &Uncertainty,
    workspace: &Workspace,
    request: &DesignRequest,
    measured_already: &[Configuration],
    progress: &(dyn Fn() + Sync),
) -> Result<Design, GoughError> {
    if request.configs == 0 {
        return Err(GoughError::NoConfigurations);
    }
    if request.candidates < request.configs {
        return Err(GoughError::TooFewCandidates {
            candidates: request.candidates,
            configs: request.configs,
        });
    }
    let legs = nominal_legs(robot);
    let mut rng = StdRng::seed_from_u64(request.seed);
    let candidates = workspace.poses(&mut rng, &legs, request.candidates, true)?;
    let random = workspace.poses(&mut rng, &legs, request.configs, false)?;
    let configs: Vec<Configuration> = measured_already
        .iter()
        .cloned()
        .chain(
            candidates
                .iter()
                .chain(&random)
                .map(|p| configuration(&legs, p)),
        )
        .collect();
    let (groups, free) = groups(robot, &configs, u);
    let start: Vec<usize> = (0..measured_already.len()).collect();
    let first_candidate = measured_already.len();
    let first_random = first_candidate + candidates.len();
    // The random poses are rows too (to compare designs), but never candidates.
    let mut candidate_groups = groups.clone();
    for g in &mut candidate_groups {
        g.rows.truncate(first_random);
    }
    // The greedy order: every prefix is a greedy design of its own (for `matching_prefix`).
    let (picked, sequence) = match request.criterion {
        Criterion::DOptimal => {
            let p = greedy_design(
                &candidate_groups,
                &start,
                request.configs,
                Criterion::DOptimal,
                progress,
            );
            (p.clone(), p)
        }
        Criterion::Certified => certified_design(
            &candidate_groups,
            &start,
            request.configs,
            EXCHANGE_PASSES,
            progress,
        ),
    };
    let with = |extra: &[usize]| -> Vec<usize> { start.iter().chain(extra).copied().collect() };
    let random_rows: Vec<usize> = (first_random..configs.len()).collect();
    let all_rows: Vec<usize> = (0..first_random).collect();
    let designed = widths_cm(robot, &groups, &free, &with(&picked));
    let random_w = widths_cm(robot, &groups, &free, &with(&random_rows));
    let best = widths_cm(robot, &groups, &free, &all_rows);
    let gm = |w: &[[f64; 7]]| geometric_mean(w.iter().flatten().copied());
    let target = gm(&random_w);
    let matching_prefix = (1..=sequence.len())
        .find(|&m| gm(&widths_cm(robot, &groups, &free, &with(&sequence[..m]))) <= target);
    Ok(Design {
        poses: picked
            .iter()
            .map(|&c| candidates[c - first_candidate])
            .collect(),
        first_order: (0..robot.len())
            .map(|leg| [designed[leg], random_w[leg], best[leg]])
            .collect(),
        matching_prefix,
        random,
    })
}

/// The certified prediction of measuring `poses` (after `measured_already`): simulated
/// readings at `truth` (per leg; the nominal geometry when planning from scratch) with noise
/// within the error bounds (seed `seed`), certified with the robot file's prior by the tight hull.
pub fn predict(
    robot: &[LegSpec],
    u: &Uncertainty,
    truth: &[Leg],
    poses: &[Pose],
    measured_already: &[Configuration],
    seed: u64,
) -> Result<Vec<LegResult>, GoughError> {
    let sim = simulate_at(truth, poses, seed, *u, 1.0, 0.0);
    let configs: Vec<Configuration> = measured_already
        .iter()
        .cloned()
        .chain(sim.measured)
        .collect();
    certify_legs(robot, &configs, u, &CertifyOptions::default(), &|| {})
}

/// A design with its predictions: what `gough design` prints and `--json` writes.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// The design.
    pub design: Design,
    /// The criterion it was chosen by.
    pub criterion: Criterion,
    /// The other criterion, whose design it is compared with.
    pub other: Criterion,
    /// The other criterion's design.
    pub other_poses: Vec<Pose>,
    /// Certified predictions of the design, the random design and the other criterion's.
    pub predicted: [Vec<LegResult>; 3],
    /// How many configurations were measured already (`--extend`).
    pub extended: usize,
    /// Seconds spent choosing the design.
    pub design_seconds: f64,
}

/// The command-line name of a criterion.
pub fn criterion_name(c: Criterion) -> &'static str {
    match c {
        Criterion::Certified => "certified",
        Criterion::DOptimal => "d-optimal",
    }
}

/// Designs (see [`design`]) and predicts the certified widths of the design, of a random design of
/// the same size and of the other criterion's design (see [`predict`]). Extending measured data,
/// the new readings are simulated at a certified consistent parameter vector of those data (so
/// that old and new agree); an error if a leg of them has none.
pub fn plan(
    robot: &[LegSpec],
    u: &Uncertainty,
    workspace: &Workspace,
    request: &DesignRequest,
    measured_already: &[Configuration],
    progress: &(dyn Fn() + Sync),
) -> Result<Plan, GoughError> {
    let start = std::time::Instant::now();
    let d = design(robot, u, workspace, request, measured_already, progress)?;
    let design_seconds = start.elapsed().as_secs_f64();
    let truth: Vec<Leg> = if measured_already.is_empty() {
        nominal_legs(robot)
    } else {
        certify_legs(
            robot,
            measured_already,
            u,
            &CertifyOptions::default(),
            &|| {},
        )?
        .iter()
        .map(|r| {
            r.witness
                .map(|w| Leg::from_params(&w))
                .ok_or(GoughError::ExtendLegUnresolved {
                    leg: r.leg + 1,
                    status: r.status,
                })
        })
        .collect::<Result<_, _>>()?
    };
    let other = match request.criterion {
        Criterion::DOptimal => Criterion::Certified,
        Criterion::Certified => Criterion::DOptimal,
    };
    let other_request = DesignRequest {
        criterion: other,
        ..request.clone()
    };
    let other_poses = design(
        robot,
        u,
        workspace,
        &other_request,
        measured_already,
        &|| {},
    )?
    .poses;
    let at = |poses: &[Pose]| predict(robot, u, &truth, poses, measured_already, request.seed);
    let predicted = [at(&d.poses)?, at(&d.random)?, at(&other_poses)?];
    Ok(Plan {
        design: d,
        criterion: request.criterion,
        other,
        other_poses,
        predicted,
        extended: measured_already.len(),
        design_seconds,
    })
}

/// The certified outer width of each parameter (0 for a leg proved empty).
pub fn certified_widths(r: &LegResult) -> [f64; 7] {
    r.outer.map_or([0.0; 7], |o| o.map(|v| v.wid()))
}

impl Plan {
    /// The geometric means of the certified widths: design, random, other criterion.
    pub fn geometric_means(&self) -> [f64; 3] {
        self.predicted
            .each_ref()
            .map(|r| geometric_mean(r.iter().flat_map(certified_widths)))
    }

    /// The JSON of `gough design --json`: the poses (rows of [`crate::files::POSE_COLUMNS`]),
    /// per design (`designed`, `random` and the other criterion's name) the certified widths per
    /// leg and their geometric mean, the first-order widths, and the matching prefix.
    pub fn json(&self) -> serde_json::Value {
        let rows = |poses: &[Pose]| -> Vec<[f64; 7]> {
            poses
                .iter()
                .map(|p| {
                    [
                        p.p[0],
                        p.p[1],
                        p.p[2],
                        p.axis[0],
                        p.axis[1],
                        p.axis[2],
                        p.angle_deg,
                    ]
                })
                .collect()
        };
        let gm = self.geometric_means();
        let names = ["designed", "random", criterion_name(self.other)];
        let first_order =
            |i: usize| -> Vec<[f64; 7]> { self.design.first_order.iter().map(|w| w[i]).collect() };
        let predicted: serde_json::Map<String, serde_json::Value> = names
            .iter()
            .zip(&self.predicted)
            .zip(gm)
            .map(|((name, r), g)| {
                let widths: Vec<[f64; 7]> = r.iter().map(certified_widths).collect();
                (
                    name.to_string(),
                    serde_json::json!({ "widths": widths, "geometric_mean": g }),
                )
            })
            .collect();
        serde_json::json!({
            "version": 1,
            "criterion": criterion_name(self.criterion),
            "columns": crate::files::POSE_COLUMNS,
            "param_order": crate::PARAMETER_NAMES,
            "poses": rows(&self.design.poses),
            "random_poses": rows(&self.design.random),
            "other_poses": rows(&self.other_poses),
            "extended": self.extended,
            "predicted": predicted,
            "first_order": {
                "designed": first_order(0),
                "random": first_order(1),
                "every_candidate": first_order(2),
            },
            "matching_prefix": self.design.matching_prefix,
            "design_seconds": self.design_seconds,
        })
    }
}

/// The poses as a poses file (header [`crate::files::POSE_COLUMNS`]), shortest round-trip
/// decimals.
pub fn poses_csv(poses: &[Pose]) -> String {
    let mut out = crate::files::POSE_COLUMNS.join(",") + "\n";
    for p in poses {
        let row: Vec<String> =
            p.p.iter()
                .chain(&p.axis)
                .chain([&p.angle_deg])
                .map(|v| format!("{v:?}"))
                .collect();
        out += &row.join(",");
        out.push('\n');
    }
    out
}
