//! The workspace file `workspace.toml` (cm, degrees): the poses a measurement campaign (or a
//! controller) may use, and sampling poses from it.
//!
//! ```toml
//! x = [-5.0, 5.0]          # platform centre in the base frame
//! y = [-5.0, 5.0]
//! z = [55.0, 65.0]
//! tilt_deg = 15.0          # rotation angle (axis-angle, any axis) at most this
//! stroke = [0.0, 15.0]     # optional: every leg reading L_i must lie here
//! ```
//!
//! The workspace is every pose meeting all of these; the stroke is checked with the leg readings
//! of a given geometry (the nominal one when planning).

use crate::files::{read_text, DataError};
use crate::geometry::{leg_reading, Leg, Pose};
use crate::GoughError;
use calib_pipeline::{finite_number, line_at, toml_error};
use rand::rngs::StdRng;
use rand::Rng;
use serde::Deserialize;
use std::path::Path;
use toml::Spanned;

/// A workspace (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Workspace {
    /// Platform centre x range (cm).
    pub x: [f64; 2],
    /// Platform centre y range (cm).
    pub y: [f64; 2],
    /// Platform centre z range (cm).
    pub z: [f64; 2],
    /// The largest rotation angle, about any axis (degrees, in `[0, 180)`).
    pub tilt_deg: f64,
    /// Every leg reading must lie in this range (cm), when given.
    pub stroke: Option<[f64; 2]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct WorkspaceFile {
    x: Spanned<[f64; 2]>,
    y: Spanned<[f64; 2]>,
    z: Spanned<[f64; 2]>,
    tilt_deg: Spanned<f64>,
    stroke: Option<Spanned<[f64; 2]>>,
}

const FORMAT: &str = "expected x, y, z = [lo, hi] (cm, the platform centre in the base frame), \
tilt_deg = the largest rotation angle (degrees) and optionally stroke = [lo, hi] (cm, every leg \
reading)";

/// How many random tries [`Workspace::sample`] makes before concluding that the stroke excludes
/// (nearly) every pose.
pub const SAMPLE_TRIES: usize = 100_000;

/// Reads `workspace.toml` (see [`parse_workspace`]).
pub fn read_workspace(file: &Path) -> Result<Workspace, DataError> {
    parse_workspace(file, &read_text(file)?)
}

/// Parses `workspace.toml`: `x`, `y`, `z` as `[lo, hi]` with `lo <= hi`, `tilt_deg` in
/// `[0, 180)`, optional `stroke = [lo, hi]`; all finite. Errors name the file, the line and the
/// field; `file` names the text.
pub fn parse_workspace(file: &Path, text: &str) -> Result<Workspace, DataError> {
    let w: WorkspaceFile = toml::from_str(text).map_err(|e| toml_error(file, text, &e, FORMAT))?;
    let err = |span: std::ops::Range<usize>, field: &str, message: String| {
        let line = Some(line_at(text, span.start));
        DataError::new(file, line, Some(field), message)
    };
    let range = |v: &Spanned<[f64; 2]>, field: &str| -> Result<[f64; 2], DataError> {
        let [lo, hi] = *v.get_ref();
        for t in [lo, hi] {
            finite_number(file, Some(line_at(text, v.span().start)), field, t)?;
        }
        if lo > hi {
            return Err(err(
                v.span(),
                field,
                format!("[{lo}, {hi}]: expected [lo, hi] with lo <= hi"),
            ));
        }
        Ok([lo, hi])
    };
    let tilt = finite_number(
        file,
        Some(line_at(text, w.tilt_deg.span().start)),
        "tilt_deg",
        *w.tilt_deg.get_ref(),
    )?;
    if !(0.0..180.0).contains(&tilt) {
        return Err(err(
            w.tilt_deg.span(),
            "tilt_deg",
            format!("{tilt}: expected a rotation angle in [0, 180) degrees"),
        ));
    }
    Ok(Workspace {
        x: range(&w.x, "x")?,
        y: range(&w.y, "y")?,
        z: range(&w.z, "z")?,
        tilt_deg: tilt,
        stroke: w.stroke.as_ref().map(|s| range(s, "stroke")).transpose()?,
    })
}

impl Workspace {
    /// The workspace of the built-in simulator (`gough simulate`): centre within ± 5 cm
    /// horizontally, 55–65 cm high, rotation up to 15°, leg readings within [0, 15] cm.
    pub const SIMULATOR: Workspace = Workspace {
        x: [-5.0, 5.0],
        y: [-5.0, 5.0],
        z: [55.0, 65.0],
        tilt_deg: 15.0,
        stroke: Some([0.0, 15.0]),
    };

    /// Whether `pose` lies in the workspace, its leg readings computed with `legs`.
    pub fn contains(&self, pose: &Pose, legs: &[Leg]) -> bool {
        let within = |v: f64, [lo, hi]: [f64; 2]| lo <= v && v <= hi;
        within(pose.p[0], self.x)
            && within(pose.p[1], self.y)
            && within(pose.p[2], self.z)
            && pose.angle_deg.abs() <= self.tilt_deg
            && self
                .stroke
                .is_none_or(|s| legs.iter().all(|leg| within(leg_reading(leg, pose), s)))
    }

    /// A random pose of the workspace (readings of `legs` within the stroke), uniform in
    /// position, axis and angle — a "random design" pose. With `extremes`, each coordinate
    /// lies at an end of its range and the angle at `tilt_deg` with probability ½ each (design
    /// candidates: informative poses lie on the workspace's boundary). `None` when
    /// [`SAMPLE_TRIES`] tries all miss the stroke.
    pub fn sample(&self, rng: &mut StdRng, legs: &[Leg], extremes: bool) -> Option<Pose> {
        let draw = |[lo, hi]: [f64; 2], rng: &mut StdRng| {
            if extremes && rng.random_bool(0.5) {
                if rng.random_bool(0.5) {
                    lo
                } else {
                    hi
                }
            } else {
                lo + (hi - lo) * rng.random::<f64>()
            }
        };
        for _ in 0..SAMPLE_TRIES {
            let axis = random_axis(rng);
            let p = [draw(self.x, rng), draw(self.y, rng), draw(self.z, rng)];
            let angle_deg = draw([0.0, self.tilt_deg], rng);
            let pose = Pose { p, axis, angle_deg };
            if self.contains(&pose, legs) {
                return Some(pose);
            }
        }
        None
    }

    /// `count` poses by [`Workspace::sample`], or an error saying the stroke excludes the poses.
    pub fn poses(
        &self,
        rng: &mut StdRng,
        legs: &[Leg],
        count: usize,
        extremes: bool,
    ) -> Result<Vec<Pose>, GoughError> {
        (0..count)
            .map(|_| {
                self.sample(rng, legs, extremes)
                    .ok_or(GoughError::StrokeExcludesPoses(
                        self.stroke.unwrap_or_default(),
                    ))
            })
            .collect()
    }
}

/// A uniformly random unit vector.
fn random_axis(rng: &mut StdRng) -> [f64; 3] {
    loop {
        let v: [f64; 3] = core::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if n > 0.2 && n <= 1.0 {
            return v.map(|c| c / n);
        }
    }
}
