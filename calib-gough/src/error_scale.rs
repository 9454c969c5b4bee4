//! `--error-scale auto` for the Gough platform: the smallest factor of the uncertainty file's
//! bounds (all of them, the positions', the leg readings' or the orientations') for which every
//! leg's data are consistent, as a proved bracket
//! ([`calib_pipeline::error_scale::search_from_estimate`]: each leg one sub-problem, started from
//! its Chebyshev fit, each trial the leg's witness or a verdict-only certification).

use crate::carry_over::StoredRows;
use crate::certification::leg_prior;
use crate::files::LegSpec;
use crate::measurement::{leg_boxes, Configuration, Uncertainty};
use crate::LegModel;
use calib_core::{hull, Interval, Settings, Status};
use calib_pipeline::error_scale::{search_from_estimate, ErrorScale, ScaledProblem};

/// Which error bounds the factor multiplies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ScaleBounds {
    /// Every bound.
    All,
    /// The platform positions' (`pos`).
    Pos,
    /// The leg readings' (`len`).
    Len,
    /// The platform orientations' (`axis` and `angle_deg`, or `q`).
    Orientation,
}

impl ScaleBounds {
    /// `u` with the chosen bounds multiplied by `s` (rounded up).
    pub fn scale(self, u: &Uncertainty, s: f64) -> Uncertainty {
        let times = |v: f64| {
            if v.is_nan() {
                v
            } else {
                (Interval::point(v) * Interval::point(s)).sup()
            }
        };
        let pick = |on: bool, v: f64| if on { times(v) } else { v };
        let all = self == ScaleBounds::All;
        let orientation = all || self == ScaleBounds::Orientation;
        Uncertainty {
            pos: pick(all || self == ScaleBounds::Pos, u.pos),
            len: pick(all || self == ScaleBounds::Len, u.len),
            axis: pick(orientation, u.axis),
            angle_deg: pick(orientation, u.angle_deg),
            q: pick(orientation, u.q),
        }
    }

    /// Which measured quantities of a leg (`P`, the axis and angle or the Rodrigues vector, the
    /// reading; [`crate::measurement::leg_boxes`]) the factor widens.
    pub fn mask(self) -> [bool; 8] {
        core::array::from_fn(|i| match self {
            ScaleBounds::All => true,
            ScaleBounds::Pos => i < 3,
            ScaleBounds::Orientation => (3..7).contains(&i),
            ScaleBounds::Len => i == 7,
        })
    }

    /// The name used in the JSON, the messages and the command line.
    pub fn name(self) -> &'static str {
        match self {
            ScaleBounds::All => "all",
            ScaleBounds::Pos => "pos",
            ScaleBounds::Len => "len",
            ScaleBounds::Orientation => "orientation",
        }
    }

    /// The bounds scaled by `s`, in words (the robot file's length unit): `len 0.00120`.
    pub fn describe(self, u: &Uncertainty, s: f64) -> String {
        let b = self.scale(u, s);
        let orientation = if b.q.is_nan() {
            format!("axis {:.3e} and angle {:.3e}°", b.axis, b.angle_deg)
        } else {
            format!("q {:.3e}", b.q)
        };
        match self {
            ScaleBounds::All => format!("pos {:.3e}, len {:.3e}, {orientation}", b.pos, b.len),
            ScaleBounds::Pos => format!("pos {:.3e}", b.pos),
            ScaleBounds::Len => format!("len {:.3e}", b.len),
            ScaleBounds::Orientation => orientation,
        }
    }
}

/// Boxes a leg's hull may contract per trial of the search.
pub const HULL_BOXES: usize = 2_000;

/// Searches the smallest consistent factor of `which` bounds of `u` for the `legs` (0-based) of
/// `robot` on `configs`; `on_trial` hears each factor before it is tried. Each trial is a hull
/// per leg, which cannot fail: the bracket itself is returned. A leg with rows carried over
/// (`stored[leg]`, [`crate::carry_over`]) is searched with them, as it is certified: from its
/// prior cut to the stored set's hull, the stored rows keeping the bounds they were certified
/// with (the factor scales the new rows only).
pub fn search(
    robot: &[LegSpec],
    stored: &[Option<StoredRows>],
    legs: &[usize],
    configs: &[Configuration],
    u: &Uncertainty,
    which: ScaleBounds,
    on_trial: impl FnMut(f64),
) -> ErrorScale {
    let carried = |leg: usize| stored.get(leg).and_then(Option::as_ref);
    let boxes: Vec<_> = legs
        .iter()
        .map(|&leg| {
            move |s: f64| {
                let mut b = leg_boxes(configs, &which.scale(u, s), leg);
                b.extend(carried(leg).map_or(&[][..], |c| &c.boxes[..]));
                b
            }
        })
        .collect();
    let model = LegModel::of(configs);
    let problems: Vec<ScaledProblem<'_, LegModel, 7, 8>> = legs
        .iter()
        .zip(&boxes)
        .map(|(&leg, b)| ScaledProblem {
            model: &model,
            x0: carried(leg).map_or_else(|| leg_prior(&robot[leg]), |c| c.prior(&robot[leg])),
            boxes: b,
            scaled: which.mask(),
        })
        .collect();
    // A leg has 7 parameters: the hull's subdivision decides where one contraction cannot, in
    // a fraction of a second.
    let settings = Settings::default()
        .with_conflict_sets(false)
        .with_hull_budget(HULL_BOXES, None);
    search_from_estimate(
        &problems,
        |i, s| {
            Ok::<Status, std::convert::Infallible>(
                hull(&model, &problems[i].x0, &(problems[i].boxes)(s), &settings).status,
            )
        },
        on_trial,
    )
    .unwrap_or_else(|never| match never {})
}
