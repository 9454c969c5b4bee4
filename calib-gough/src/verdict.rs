//! A leg's result in plain words: the robot-agnostic sentences of [`calib_pipeline::verdict`]
//! applied to a leg (with the leg's parameter names). The terminal output of `gough certify` and
//! the HTML certificate say the same sentences.

use crate::certification::LegResult;
use crate::PARAMETER_NAMES;
use calib_core::{EmptinessProof, Interval, Status};
use calib_pipeline::verdict as words;
pub use calib_pipeline::verdict::{
    auto_outliers, short_verdict, CarriedRows, ConfigurationNames, Standing,
};

/// What proved a leg empty, in words.
pub fn proof_in_words(proof: Option<EmptinessProof>) -> String {
    let names: Vec<String> = PARAMETER_NAMES.iter().map(|s| s.to_string()).collect();
    words::proof_in_words(proof, &names)
}

/// Names configurations of a leg's result: a new row by its number and its line in the
/// measurement file, a row carried over from a calibrated robot file ([`crate::carry_over`]) by
/// its number and its row in that file — "configurations 4, 23 (measurements.csv line 5; stored
/// row 2 of calibrated.toml)" ([`ConfigurationNames::name`]).
pub fn name_configurations(
    r: &LegResult,
    names: &ConfigurationNames<'_>,
    configs: &[usize],
) -> String {
    with_stored_rows(r, names, |every| every.name(configs))
}

/// `f` of `names` with the rows `r` carried over named by their rows in the stored set.
fn with_stored_rows<T>(
    r: &LegResult,
    names: &ConfigurationNames<'_>,
    f: impl FnOnce(&ConfigurationNames<'_>) -> T,
) -> T {
    let rows: Vec<usize> = r
        .carried
        .as_ref()
        .map_or_else(Vec::new, |c| c.stored.rows.iter().map(|i| i + 1).collect());
    let carried = r.carried.as_ref().map(|c| CarriedRows {
        file: &c.stored.file,
        rows: &rows,
    });
    f(&ConfigurationNames {
        file: names.file,
        lines: names.lines,
        carried,
    })
}

/// The verdict and its evidence, one sentence per entry: for an empty leg the proof, the
/// conflicting configurations and what to do next (with the outliers the result tolerates).
/// Rows carried over from a calibrated robot file are named as its rows
/// ([`name_configurations`]).
pub fn verdict(r: &LegResult, names: &ConfigurationNames<'_>) -> Vec<String> {
    with_stored_rows(r, names, |every| {
        words::verdict(&r.outcome(), every, r.tolerated)
    })
}

/// The outer (or x1) width over the inner width, per parameter, when both exist.
pub fn width_ratios(r: &LegResult) -> Option<[f64; 7]> {
    let (outer, inner) = (r.outer?, r.inner?);
    Some(core::array::from_fn(|j| outer[j].wid() / inner[j].wid()))
}

/// What the outer/inner ratios mean for this run: converged, budget spent, or `--fast`.
pub fn tightness(r: &LegResult) -> Option<&'static str> {
    words::tightness(&r.outcome())
}

/// The parameters (index, which end) where the outer box reaches a face of the initial box x0.
pub fn x0_faces(r: &LegResult) -> Vec<(usize, &'static str)> {
    r.outcome().x0_faces()
}

/// Where the outer box reaches a face of the initial box x0, in words: consistent parameter
/// vectors may then lie beyond x0, which the certificate does not cover. (For a leg that carried
/// rows over, x0 is the file's box cut to the stored set's hull; where that face is the file's
/// own box, geometries beyond it are not covered either, so the warning is the same.)
pub fn touching_x0(r: &LegResult) -> Option<String> {
    words::touching_x0(&r.outcome())
}

/// Where `x` stands against a certificate over `x0`: `certified` is the certified box, `None` when
/// x0 was proved to hold no consistent parameter vector.
pub fn standing(x0: &[Interval; 7], certified: Option<&[Interval; 7]>, x: &[f64; 7]) -> Standing {
    words::standing(x0, certified.map(|b| &b[..]), x)
}

/// [`standing`] against a leg's result: its outer box, or none when it was proved empty.
pub fn leg_standing(r: &LegResult, x: &[f64; 7]) -> Standing {
    let certified = match r.status {
        Status::Empty => None,
        _ => Some(r.outer.as_ref().unwrap_or(&r.x0)),
    };
    standing(&r.x0, certified, x)
}

/// With outliers tolerated (`r.tolerated > 0`) on a leg that is not empty: which configurations
/// were proved to be outliers.
pub fn outliers(r: &LegResult, names: &ConfigurationNames<'_>) -> Option<String> {
    with_stored_rows(r, names, |every| {
        words::outliers(&r.outcome(), every, r.tolerated)
    })
}
