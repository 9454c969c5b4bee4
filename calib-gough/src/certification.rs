//! Certifying every leg of a robot: the work behind `gough certify` (and the Python package),
//! from parsed data to one [`LegResult`] per leg and the JSON [`Report`].

use crate::carry_over::{Carried, StoredRows};
use crate::files::LegSpec;
use crate::measurement::{leg_boxes, measured, Configuration, Uncertainty};
use crate::report::{bounds, CarriedReport, LegReport, Report};
use crate::GoughError;
use crate::{LegModel, PARAMETER_NAMES};
use calib_core::{
    certify, hull, pave, sweep, Cover, EmptinessProof, Hull, Interval, Settings, Status,
};
use calib_pipeline::identify::{analyse, identification_jacobian};
use calib_pipeline::{check_hull_options, smallest_consistent, Outcome, OutlierBudget};
use rayon::prelude::*;
use std::time::Instant;

/// What to compute per leg (the options of `gough certify`).
#[derive(Clone, Debug, PartialEq)]
pub struct CertifyOptions {
    /// Only these legs (1-based); all when `None`.
    pub legs: Option<Vec<usize>>,
    /// Only the paper's fixed point x1 instead of the tight hull.
    pub fast: bool,
    /// Also the paper's 128-box sweep (x2).
    pub sweep: bool,
    /// Also a paving down to this relative width.
    pub pave: Option<f64>,
    /// The hull's tolerance: stop at `wid(outer) <= (1 + tol) wid(inner)`.
    pub tolerance: f64,
    /// The hull's box budget per leg.
    pub max_boxes: usize,
    /// The hull's time budget per leg.
    pub max_seconds: Option<f64>,
    /// Tolerated outliers per leg: a number, or the smallest number that makes each leg
    /// consistent ([`OutlierBudget::Auto`]).
    pub max_outliers: OutlierBudget,
}

impl Default for CertifyOptions {
    fn default() -> Self {
        CertifyOptions {
            legs: None,
            fast: false,
            sweep: false,
            pave: None,
            tolerance: Settings::default().hull_tolerance,
            max_boxes: Settings::default().hull_max_boxes,
            max_seconds: None,
            max_outliers: OutlierBudget::Fixed(0),
        }
    }
}

impl CertifyOptions {
    /// Checks the options against the data; returns the 0-based legs and the kernel settings.
    /// Errors name the option, as the command line spells it.
    pub fn validate(
        &self,
        legs: usize,
        configs: usize,
    ) -> Result<(Vec<usize>, Settings), GoughError> {
        let chosen: Vec<usize> = match &self.legs {
            Some(list) => {
                if let Some(l) = list.iter().find(|&&l| l == 0 || l > legs) {
                    return Err(GoughError::NoSuchLeg { leg: *l, legs });
                }
                list.iter().map(|l| l - 1).collect()
            }
            None => (0..legs).collect(),
        };
        if let Some(tol) = self.pave {
            if !(tol > 0.0 && tol < 1.0) {
                return Err(GoughError::Pave(tol));
            }
        }
        check_hull_options(self.tolerance, self.max_seconds)?;
        self.max_outliers.check(configs)?;
        let tolerated = match self.max_outliers {
            OutlierBudget::Fixed(q) => q,
            OutlierBudget::Auto => 0,
        };
        let settings = Settings::default()
            .with_hull_tolerance(self.tolerance)
            .with_hull_budget(self.max_boxes, self.max_seconds)
            .with_max_outliers(tolerated);
        Ok((chosen, settings))
    }
}

/// One leg's certified result, from the tight hull or (with `fast`) from x1 alone.
#[derive(Clone, Debug, PartialEq)]
pub struct LegResult {
    /// 0-based leg.
    pub leg: usize,
    /// The initial box: nominal ± radius, decimal values enclosed.
    pub x0: [Interval; 7],
    /// The verdict.
    pub status: Status,
    /// For `Empty`: what proved it.
    pub emptiness: Option<EmptinessProof>,
    /// The paper's fixed point (`None` when x0 was proved empty at once).
    pub x1: Option<[Interval; 7]>,
    /// The tightest certified outer box (`None` when empty).
    pub outer: Option<[Interval; 7]>,
    /// Certified inner bounds.
    pub inner: Option<[Interval; 7]>,
    /// A certified consistent parameter vector.
    pub witness: Option<[f64; 7]>,
    /// For an empty leg: a minimal set of configurations (0-based) that cannot be fitted together
    /// (not searched when the misfit is [`spread`](LegResult::spread)).
    pub conflict: Option<Vec<usize>>,
    /// For an empty leg: the configurations (0-based) the certificate of emptiness weighs, when it
    /// names them ([`calib_core::Certification::support`]).
    pub support: Option<Vec<usize>>,
    /// For an empty leg: the support shows a misfit spread over the data — the error bounds too
    /// tight for the leg's model rather than a few bad readings; no conflict set was searched.
    pub spread: bool,
    /// With outliers tolerated: the configurations (0-based) proved to be outliers.
    pub outliers: Vec<usize>,
    /// How many outliers this result tolerates (the kernel's [`Settings::max_outliers`]).
    pub tolerated: usize,
    /// Newton/LP steps to x1.
    pub iterations: usize,
    /// Whether the hull met the tolerance (`None` with `fast`).
    pub converged: Option<bool>,
    /// The sweep hull x2 (outer `None` without sweep; inner `None` when empty).
    pub x2: Option<Option<[Interval; 7]>>,
    /// With paving: boxes, inner volume, outer volume.
    pub paving: Option<(usize, f64, f64)>,
    /// Boxes contracted in total.
    pub boxes: usize,
    /// Wall-clock seconds.
    pub seconds: f64,
    /// Boxes whose union contains every consistent geometry (what the certified set is built
    /// on, [`calib_core::CertifiedSet`]).
    pub cover: Cover<7>,
    /// Certified consistent geometries: the witness and the points that attain the inner bounds.
    pub points: Vec<[f64; 7]>,
    /// The rows carried over from a calibrated robot file, numbered after the new ones (`None`
    /// when the leg was certified against the new rows alone; [`crate::carry_over`]).
    pub carried: Option<Carried>,
}

impl LegResult {
    /// The result of the tight hull (`seconds` left at 0 for the caller to set).
    pub fn from_hull(leg: usize, x0: [Interval; 7], h: Hull<7>) -> LegResult {
        LegResult {
            leg,
            x0,
            status: h.status,
            emptiness: h.emptiness,
            x1: h.x1,
            outer: (h.status != Status::Empty).then_some(h.outer),
            inner: h.inner,
            witness: h.witness,
            conflict: h.conflict,
            support: h.support,
            spread: h.spread,
            outliers: h.outliers,
            tolerated: 0,
            iterations: h.iterations,
            converged: Some(h.converged),
            x2: None,
            paving: None,
            boxes: h.boxes_contracted,
            seconds: 0.0,
            points: h.witness.into_iter().chain(h.inner_points).collect(),
            cover: h.cover,
            carried: None,
        }
    }

    /// The leg as a robot-agnostic [`Outcome`] (for the shared sentences of
    /// [`calib_pipeline::verdict`]).
    pub fn outcome(&self) -> Outcome {
        let vec = |b: [Interval; 7]| b.to_vec();
        Outcome {
            names: PARAMETER_NAMES.iter().map(|s| s.to_string()).collect(),
            x0: vec(self.x0),
            status: self.status,
            emptiness: self.emptiness,
            x1: self.x1.map(vec),
            outer: self.outer.map(vec),
            inner: self.inner.map(vec),
            witness: self.witness.map(|w| w.to_vec()),
            conflict: self.conflict.clone(),
            support: self.support.clone(),
            spread: self.spread,
            outliers: self.outliers.clone(),
            iterations: self.iterations,
            converged: self.converged,
            boxes: self.boxes,
            seconds: self.seconds,
        }
    }

    /// The leg's entry in the JSON report (1-based leg and configuration numbers).
    pub fn report(&self) -> LegReport {
        let one_based = |c: &[usize]| c.iter().map(|k| k + 1).collect::<Vec<_>>();
        LegReport {
            leg: self.leg + 1,
            status: format!("{:?}", self.status).to_lowercase(),
            names: PARAMETER_NAMES.iter().map(|s| s.to_string()).collect(),
            x0: bounds(&self.x0),
            x1: self.x1.map(|b| bounds(&b)),
            x2: self.x2.flatten().map(|b| bounds(&b)),
            outer: self.outer.map(|b| bounds(&b)),
            inner: self.inner.map(|b| bounds(&b)),
            converged: self.converged,
            conflict: self.conflict.as_deref().map(one_based),
            support: self.support.as_deref().map(one_based),
            spread: self.spread,
            outliers: one_based(&self.outliers),
            outliers_tolerated: self.tolerated,
            witness: self.witness.map(|w| w.to_vec()),
            carried_over: self.carried.as_ref().map(|c| CarriedReport {
                file: c.stored.file.clone(),
                first: c.first + 1,
                rows: one_based(&c.stored.rows),
            }),
            iterations: self.iterations,
            boxes: self.boxes,
            seconds: self.seconds,
        }
    }
}

/// The JSON report (schema version 1) of a run.
pub fn report(results: &[LegResult], seconds: f64) -> Report {
    Report {
        version: 1,
        legs: results.iter().map(LegResult::report).collect(),
        seconds,
    }
}

/// The identifiability of one leg's parameters on the configurations, in words (see
/// [`calib_pipeline::identify`]): the identification Jacobian at the nominal geometry, columns
/// scaled by the prior half-widths, rows by the error bounds. Empty when every free parameter is
/// determined (to first order). With rows carried over from a calibrated robot file (`stored`),
/// over the new rows and the stored ones, from the leg's box cut to the stored set's hull.
pub fn identifiability(
    spec: &LegSpec,
    leg: usize,
    configs: &[Configuration],
    u: &Uncertainty,
    stored: Option<&StoredRows>,
) -> Vec<String> {
    let nominal = spec.nominal.params();
    let x0 = stored.map_or_else(|| leg_prior(spec), |s| s.prior(spec));
    let boxes = carried_boxes(configs, u, leg, stored);
    let (free, jacobian) = identification_jacobian(&LegModel::of(configs), &nominal, &x0, &boxes);
    let names: Vec<String> = PARAMETER_NAMES.iter().map(|s| s.to_string()).collect();
    analyse(&free, jacobian).sentences(&names)
}

/// The prior box of a leg: its nominal ± its radii, outward rounded.
pub fn leg_prior(spec: &LegSpec) -> [Interval; 7] {
    let nominal = spec.nominal.params();
    core::array::from_fn(|j| measured(nominal[j], spec.radius[j]))
}

/// The measurement boxes of leg `leg` (0-based): the configurations' ([`leg_boxes`]), followed
/// by the rows carried over, when any.
pub fn carried_boxes(
    configs: &[Configuration],
    u: &Uncertainty,
    leg: usize,
    stored: Option<&StoredRows>,
) -> Vec<[Interval; 8]> {
    let mut boxes = leg_boxes(configs, u, leg);
    boxes.extend(stored.iter().flat_map(|s| s.boxes.iter().copied()));
    boxes
}

/// Certifies one leg (0-based) of `spec` against the configurations, and against the rows
/// `stored` carries over from a calibrated robot file when given (from the leg's box cut to the
/// stored cover's hull, [`StoredRows::prior`]).
pub fn certify_leg(
    spec: &LegSpec,
    leg: usize,
    configs: &[Configuration],
    u: &Uncertainty,
    stored: Option<&StoredRows>,
    options: &CertifyOptions,
    settings: &Settings,
) -> LegResult {
    let t = Instant::now();
    let x0 = stored.map_or_else(|| leg_prior(spec), |s| s.prior(spec));
    let boxes = carried_boxes(configs, u, leg, stored);
    let model = LegModel::of(configs);
    let mut r = if options.fast {
        let c = certify(&model, &x0, &boxes, settings);
        let x1 = (c.status != Status::Empty).then_some(c.outer);
        LegResult {
            leg,
            x0,
            status: c.status,
            emptiness: c.emptiness,
            x1,
            outer: x1,
            inner: c.inner,
            witness: c.witness,
            conflict: c.conflict,
            support: c.support,
            spread: c.spread,
            outliers: c.outliers,
            tolerated: 0,
            iterations: c.iterations,
            converged: None,
            x2: None,
            paving: None,
            boxes: 1,
            seconds: 0.0,
            points: c.witness.into_iter().collect(),
            cover: c.cover,
            carried: None,
        }
    } else {
        LegResult::from_hull(leg, x0, hull(&model, &x0, &boxes, settings))
    };
    if options.sweep {
        let s = sweep(&model, &x0, &boxes, settings);
        r.boxes += s.boxes_contracted;
        r.x2 = Some(s.hull);
    }
    if let Some(tol) = options.pave {
        let p = pave(&model, &x0, &boxes, settings, tol, 20_000);
        r.boxes += p.boxes_contracted;
        r.paving = Some((p.boxes.len(), p.inner_volume, p.outer_volume));
    }
    r.tolerated = settings.max_outliers;
    r.carried = stored.map(|s| Carried {
        first: configs.len(),
        stored: s.clone(),
    });
    r.seconds = t.elapsed().as_secs_f64();
    r
}

/// Certifies the chosen legs in parallel (in leg order); `done` is called after each leg (for
/// progress). With [`OutlierBudget::Auto`], each leg is certified with the smallest number of
/// tolerated outliers that does not prove it empty (see [`smallest_consistent`]; the leg's
/// [`LegResult::tolerated`] says which). Errors are option errors (see
/// [`CertifyOptions::validate`]).
pub fn certify_legs(
    robot: &[LegSpec],
    configs: &[Configuration],
    u: &Uncertainty,
    options: &CertifyOptions,
    done: &(dyn Fn() + Sync),
) -> Result<Vec<LegResult>, GoughError> {
    certify_legs_carrying(robot, &[], configs, u, options, done)
}

/// [`certify_legs`] for a calibrated robot file measured again: each leg with rows in `stored`
/// (per leg, [`crate::carry_over::stored_rows`]; a shorter list carries nothing for the legs
/// after it) is certified against the new configurations followed by its stored rows, from its
/// box cut to the stored cover's hull ([`certify_leg`]).
pub fn certify_legs_carrying(
    robot: &[LegSpec],
    stored: &[Option<StoredRows>],
    configs: &[Configuration],
    u: &Uncertainty,
    options: &CertifyOptions,
    done: &(dyn Fn() + Sync),
) -> Result<Vec<LegResult>, GoughError> {
    let most = stored.iter().flatten().map(|s| s.rows.len()).max();
    let (legs, mut settings) = options.validate(robot.len(), configs.len() + most.unwrap_or(0))?;
    if options.max_outliers == OutlierBudget::Auto {
        // Every result `auto` keeps is consistent, or tolerates outliers: a conflict set (sought
        // only for an empty verdict with none tolerated) would be thrown away.
        settings = settings.with_conflict_sets(false);
    }
    Ok(legs
        .par_iter()
        .map(|&leg| {
            let t = Instant::now();
            let carried = stored.get(leg).and_then(Option::as_ref);
            let (_, mut r) = smallest_consistent(
                options.max_outliers,
                configs.len() + carried.map_or(0, |s| s.rows.len()),
                |q| {
                    let settings = settings.clone().with_max_outliers(q);
                    Ok::<_, std::convert::Infallible>(certify_leg(
                        &robot[leg],
                        leg,
                        configs,
                        u,
                        carried,
                        options,
                        &settings,
                    ))
                },
                |r| r.status == Status::Empty,
            )
            .unwrap_or_else(|never| match never {});
            // With `auto`, the leg's time includes the tries that proved fewer outliers too few.
            r.seconds = t.elapsed().as_secs_f64();
            done();
            r
        })
        .collect())
}
