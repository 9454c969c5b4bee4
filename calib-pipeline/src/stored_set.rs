//! The certified set in a calibrated robot file: what `accuracy` and `predict` need to work over
//! the set from the file alone.
//!
//! A [`calib_core::CertifiedSet`] is rebuilt from three things, all stored exactly (shortest
//! round-trip decimals read back bit-identical): the measurement boxes it was certified against,
//! the boxes of its cover (with the measurement subset of each, when outliers were tolerated) and
//! its certified points. The polyhedra themselves are not stored: the Newton step's relaxation
//! recomputes them from the model, the boxes and the measurements, and holds for any box, so a
//! file cannot carry a polyhedron that excludes a solution of its own boxes. Points read back are
//! proved consistent again before they are used.
//!
//! Values are in the model's units (a robot crate says which: centimetres for a Gough leg,
//! millimetres and radians for an arm). In TOML:
//!
//! ```toml
//! [certified_set]           # or [leg.certified_set] after a [[leg]] table
//! measurements = [[[lo, hi], ...], ...]   # one row per configuration, one interval per measured quantity
//! boxes = [[[lo, hi], ...], ...]          # the cover: every consistent parameter vector lies in one
//! subsets = [0, ...]                      # per box, the index in `dropped`
//! dropped = [[]]                          # per subset, the configurations it leaves out (0-based)
//! points = [[...], ...]                   # certified consistent parameter vectors
//! ```

use calib_core::{CertifiedSet, Cover, Interval};
use serde::Deserialize;
use std::fmt::Write as _;

/// A certified set as a file stores it (see the module documentation).
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StoredSet {
    /// Per configuration, the measured quantities' intervals `[lo, hi]`.
    pub measurements: Vec<Vec<[f64; 2]>>,
    /// The cover's boxes, one interval `[lo, hi]` per parameter.
    pub boxes: Vec<Vec<[f64; 2]>>,
    /// Per box, its measurement subset (an index into `dropped`).
    pub subsets: Vec<usize>,
    /// Per subset, the configurations it leaves out (0-based, sorted).
    pub dropped: Vec<Vec<usize>>,
    /// Certified consistent parameter vectors.
    pub points: Vec<Vec<f64>>,
}

/// `[lo, hi]` of an interval.
fn pair(v: Interval) -> [f64; 2] {
    [v.inf(), v.sup()]
}

impl StoredSet {
    /// What a file stores of `set` (the parameters and measured quantities listed by `params` and
    /// `quantities`, in that order: a robot certified through a larger model keeps its own).
    pub fn of<const NX: usize, const NM: usize>(
        set: &CertifiedSet<NX, NM>,
        params: &[usize],
        quantities: &[usize],
    ) -> StoredSet {
        let cover = set.cover();
        StoredSet {
            measurements: set
                .measurements()
                .iter()
                .map(|m| quantities.iter().map(|&i| pair(m[i])).collect())
                .collect(),
            boxes: cover
                .boxes
                .iter()
                .map(|b| params.iter().map(|&j| pair(b[j])).collect())
                .collect(),
            subsets: cover.subsets,
            dropped: cover.dropped,
            points: set
                .points()
                .iter()
                .map(|p| params.iter().map(|&j| p.x[j]).collect())
                .collect(),
        }
    }

    /// The TOML table `[name]` holding the set, after a comment that says what it is.
    pub fn to_toml(&self, name: &str) -> String {
        let mut t = String::new();
        let _ = writeln!(
            t,
            "\n# The certified set: every parameter vector consistent with the measurements below \
             lies in one of\n# `boxes` (and satisfies the linear inequalities the Newton step \
             derives on it); `points` are\n# proved consistent.{}\n[{name}]",
            if name.ends_with("certified_set") {
                " Read by `accuracy` and `predict` to bound errors over the set, not its box."
            } else {
                ""
            }
        );
        let intervals = |rows: &[Vec<[f64; 2]>]| -> String {
            let lines: Vec<String> = rows
                .iter()
                .map(|r| {
                    let cells: Vec<String> = r
                        .iter()
                        .map(|[lo, hi]| format!("[{lo:?}, {hi:?}]"))
                        .collect();
                    format!("  [{}],", cells.join(", "))
                })
                .collect();
            format!("[\n{}\n]", lines.join("\n"))
        };
        let _ = writeln!(t, "measurements = {}", intervals(&self.measurements));
        let _ = writeln!(t, "boxes = {}", intervals(&self.boxes));
        let _ = writeln!(t, "subsets = {:?}", self.subsets);
        let _ = writeln!(t, "dropped = {:?}", self.dropped);
        let points: Vec<String> = self
            .points
            .iter()
            .map(|p| {
                let v: Vec<String> = p.iter().map(|x| format!("{x:?}")).collect();
                format!("  [{}],", v.join(", "))
            })
            .collect();
        let _ = writeln!(t, "points = [\n{}\n]", points.join("\n"));
        t
    }

    /// The cover, the measurement boxes and the points, checked: `nx` parameters and `nm`
    /// quantities per row, bounded intervals with `lo <= hi`, subsets and dropped configurations
    /// in range. Parameters and quantities go to the positions `params` and `quantities` of the
    /// model's `NX` and `NM` (the others take `fill_x` and `fill_m`); errors name the field.
    pub fn restore<const NX: usize, const NM: usize>(
        &self,
        params: &[usize],
        quantities: &[usize],
        fill_x: &[Interval; NX],
        fill_m: &[Interval; NM],
    ) -> Result<Restored<NX, NM>, (String, String)> {
        let measurements = placed("measurements", &self.measurements, quantities, fill_m)?;
        self.check_dropped(measurements.len())?;
        if self.subsets.len() != self.boxes.len() {
            return Err((
                "subsets".into(),
                format!(
                    "expected one entry per box ({}), found {}",
                    self.boxes.len(),
                    self.subsets.len()
                ),
            ));
        }
        let boxes = placed("boxes", &self.boxes, params, fill_x)?;
        if let Some(bad) = self.subsets.iter().position(|&s| s >= self.dropped.len()) {
            return Err((
                format!("subsets[{}]", bad + 1),
                "not an index of `dropped`".into(),
            ));
        }
        let mut points = Vec::with_capacity(self.points.len());
        for (k, p) in self.points.iter().enumerate() {
            if p.len() != params.len() || p.iter().any(|v| !v.is_finite()) {
                return Err((
                    format!("points[{}]", k + 1),
                    format!("expected {} finite numbers", params.len()),
                ));
            }
            let mut x = fill_x.map(|v| v.mid());
            for (&j, &v) in params.iter().zip(p) {
                x[j] = v;
            }
            points.push(x);
        }
        Ok(Restored {
            cover: Cover {
                boxes,
                subsets: self.subsets.clone(),
                dropped: self.dropped.clone(),
            },
            measurements,
            points,
        })
    }

    /// At least one subset, each a sorted list of configuration indices below `configurations`.
    fn check_dropped(&self, configurations: usize) -> Result<(), (String, String)> {
        if self.dropped.is_empty() {
            return Err((
                "dropped".into(),
                "expected at least one subset (`[[]]`)".into(),
            ));
        }
        for (s, d) in self.dropped.iter().enumerate() {
            if d.windows(2).any(|w| w[0] >= w[1]) || d.iter().any(|&k| k >= configurations) {
                return Err((
                    format!("dropped[{}]", s + 1),
                    format!("expected sorted configuration indices below {configurations}"),
                ));
            }
        }
        Ok(())
    }
}

/// The rows of `field`, each of `positions.len()` intervals placed at those positions of `fill`;
/// errors name the row.
fn placed<const N: usize>(
    field: &str,
    rows: &[Vec<[f64; 2]>],
    positions: &[usize],
    fill: &[Interval; N],
) -> Result<Vec<[Interval; N]>, (String, String)> {
    let mut out = Vec::with_capacity(rows.len());
    for (k, r) in rows.iter().enumerate() {
        let name = format!("{field}[{}]", k + 1);
        if r.len() != positions.len() {
            return Err((
                name,
                format!("expected {} intervals, found {}", positions.len(), r.len()),
            ));
        }
        let mut b = *fill;
        for (&i, &[lo, hi]) in positions.iter().zip(r) {
            if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
                return Err((
                    name,
                    format!("expected [lo, hi] with finite lo <= hi, found [{lo}, {hi}]"),
                ));
            }
            b[i] = Interval::new(lo, hi);
        }
        out.push(b);
    }
    Ok(out)
}

/// A [`StoredSet`] read back in the model's dimensions, ready for [`CertifiedSet::new`].
#[derive(Clone, Debug, PartialEq)]
pub struct Restored<const NX: usize, const NM: usize> {
    /// The cover.
    pub cover: Cover<NX>,
    /// The measurement boxes.
    pub measurements: Vec<[Interval; NM]>,
    /// The certified points (to be proved again).
    pub points: Vec<[f64; NX]>,
}
