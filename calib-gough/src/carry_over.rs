//! A calibration that carries over: `gough certify --robot calibrated.toml` with new measurements
//! certifies each leg against the new rows **and** the rows its stored set was certified against.
//!
//! A calibrated robot file (`gough certify --write-calibrated`) stores per leg the measurement
//! boxes its certified set was certified against and the cover of that set
//! ([`calib_pipeline::stored_set`]). When the robot is measured again in the same frames, the
//! geometries consistent with both series are the old set cut by what the new rows allow: an
//! ordinary certification over more rows, the new rows followed by the stored ones, from a prior
//! box that holds the old set — the leg's box in the file (`a, b, l ± radius`, which contains the
//! certified outer box) cut to the hull of the stored cover (which contains every geometry of the
//! set). Nothing new is asked of the kernel.
//!
//! The stored rows are carried over as they are (model units, the error bounds of their own
//! series). Two exceptions, both on the safe side:
//! * rows that a piece of the stored cover leaves out (the earlier run tolerated them as outliers)
//!   are not carried over: the set was not certified to fit them (the rows carried over are a
//!   subset of those every piece fits, so the set certified is never smaller than the exact
//!   intersection);
//! * stored rows and new rows must be measured the same way (axis–angle data store eight
//!   quantities per configuration, Rodrigues data seven: [`LegModel::stored_quantities`]); one
//!   residual serves every row of a leg, so a mismatch is an error naming the field.

use crate::certification::leg_prior;
use crate::files::{LegSpec, RobotFile};
use crate::{LegModel, PARAMETER_NAMES};
use calib_core::Interval;
use calib_pipeline::DataError;
use std::path::Path;

/// The rows one leg carries over from a calibrated robot file.
#[derive(Clone, Debug, PartialEq)]
pub struct StoredRows {
    /// The calibrated file's name, as messages show it (`calibrated.toml`).
    pub file: String,
    /// Per carried configuration, its 0-based row in `leg[i].certified_set.measurements`.
    pub rows: Vec<usize>,
    /// The file's rows not carried over (0-based): left out by a piece of the stored cover, the
    /// earlier run having tolerated them as outliers.
    pub left_out: Vec<usize>,
    /// The carried rows' measurement boxes, in the order of [`LegModel`]'s `M`.
    pub boxes: Vec<[Interval; 8]>,
    /// The hull of the stored cover: it contains every geometry of the stored set.
    pub hull: [Interval; 7],
}

impl StoredRows {
    /// The prior box of a leg that carries these rows: the leg's box `spec` (nominal ± radius)
    /// cut to the hull of the stored cover. Both contain the stored set.
    pub fn prior(&self, spec: &LegSpec) -> [Interval; 7] {
        let own = leg_prior(spec);
        core::array::from_fn(|j| own[j].intersection(self.hull[j]))
    }
}

/// Per leg of `robot` (read from `file`), the rows it carries over to new measurements of the
/// kind `rodrigues` says (`None` for a leg without a stored set). Errors name the file and the
/// leg's field: stored rows measured another way than the new ones (another number of
/// quantities per configuration), a malformed stored set (non-finite bounds, indices out of
/// range), a stored cover without a box, or a cover whose hull misses the leg's own box (the
/// file contradicts itself).
pub fn stored_rows(
    file: &Path,
    robot: &RobotFile,
    rodrigues: bool,
) -> Result<Vec<Option<StoredRows>>, DataError> {
    let model = if rodrigues {
        LegModel::Rodrigues
    } else {
        LegModel::AxisAngle
    };
    let quantities = model.stored_quantities();
    let all: Vec<usize> = (0..7).collect();
    let name = file.file_name().map_or_else(
        || file.display().to_string(),
        |n| n.to_string_lossy().into(),
    );
    robot
        .sets
        .iter()
        .zip(&robot.legs)
        .enumerate()
        .map(|(i, (stored, spec))| {
            let Some(stored) = stored else {
                return Ok(None);
            };
            let field = |f: &str| format!("leg[{}].certified_set.{f}", i + 1);
            let fail = |f: &str, m: String| DataError::new(file, None, Some(&field(f)), m);
            let Some(first) = stored.measurements.first() else {
                return Err(fail(
                    "measurements",
                    "no stored configuration: a certified set is certified against at least one"
                        .into(),
                ));
            };
            if first.len() != quantities.len() {
                return Err(fail("measurements", kind_mismatch(first.len(), rodrigues)));
            }
            let restored = stored
                .restore::<7, 8>(&all, quantities, &[Interval::ZERO; 7], &[Interval::ZERO; 8])
                .map_err(|(f, m)| fail(&f, m))?;
            if LegModel::of_measurements(&restored.measurements) != model {
                return Err(fail(
                    "measurements",
                    "every angle is the point [0.0, 0.0]: a measured angle has a box of positive \
                     width (was the file edited?)"
                        .into(),
                ));
            }
            let hull = restored.cover.hull().ok_or_else(|| {
                fail(
                    "boxes",
                    "no box: the stored set holds no geometry (was the file edited?)".into(),
                )
            })?;
            let carried = StoredRows {
                file: name.clone(),
                rows: Vec::new(),
                left_out: Vec::new(),
                boxes: Vec::new(),
                hull,
            };
            let prior = carried.prior(spec);
            if let Some(j) = prior.iter().position(|v| v.is_empty()) {
                return Err(fail(
                    "boxes",
                    format!(
                        "the stored cover's hull misses the leg's box (a, b, l ± radius) in {}: \
                         the set and the box both claim to hold every consistent geometry, so \
                         the file contradicts itself (was it edited?); recalibrate with `gough \
                         certify --write-calibrated`",
                        PARAMETER_NAMES[j]
                    ),
                ));
            }
            // The rows some piece of the cover leaves out (subsets no box uses leave none out).
            let cover = &restored.cover;
            let mut left_out: Vec<usize> = cover
                .subsets
                .iter()
                .flat_map(|&s| cover.dropped[s].iter().copied())
                .collect();
            left_out.sort_unstable();
            left_out.dedup();
            let rows: Vec<usize> = (0..restored.measurements.len())
                .filter(|k| left_out.binary_search(k).is_err())
                .collect();
            Ok(Some(StoredRows {
                boxes: rows.iter().map(|&k| restored.measurements[k]).collect(),
                rows,
                left_out,
                ..carried
            }))
        })
        .collect()
}

/// Why stored rows of `found` quantities do not carry over to new data of the kind `rodrigues`.
fn kind_mismatch(found: usize, rodrigues: bool) -> String {
    let kind = |n: usize| match n {
        7 => "Rodrigues data: px, py, pz, q1, q2, q3, L".to_string(),
        8 => "axis–angle data: px, py, pz, ax, ay, az, angle_deg, L".to_string(),
        _ => "neither axis–angle (8) nor Rodrigues (7) data".to_string(),
    };
    let expected = if rodrigues { 7 } else { 8 };
    format!(
        "the stored rows have {found} measured quantities per configuration ({}), the new \
         measurements {expected} ({}): one leg model serves every row, so a stored set carries \
         over only to data measured the same way (certify the new data against the nominal robot \
         file instead)",
        kind(found),
        kind(expected)
    )
}

/// The stored rows a leg's result was certified with: configurations `first..` of the result
/// (0-based; the new rows come first) are the stored rows `stored.rows`.
#[derive(Clone, Debug, PartialEq)]
pub struct Carried {
    /// The result's first stored configuration (0-based): the number of new rows.
    pub first: usize,
    /// The rows carried over.
    pub stored: StoredRows,
}

impl Carried {
    /// The 0-based stored row of the result's configuration `k` (0-based), when it is one.
    pub fn stored_row(&self, k: usize) -> Option<usize> {
        k.checked_sub(self.first)
            .and_then(|i| self.stored.rows.get(i).copied())
    }
}
