//! A leg's result in plain words: the verdict and its evidence, the tightness reached, the
//! outliers. The terminal output of `gough certify` and the HTML certificate say the same sentences.

use crate::certification::LegResult;
use crate::PARAMETER_NAMES;
use calib_core::{EmptinessProof, Interval, Status};

/// Names configurations by number and by their line in the measurement file.
#[derive(Clone, Copy, Debug)]
pub struct ConfigurationNames<'a> {
    /// The measurement file's name (as shown to the user).
    pub file: &'a str,
    /// The file line of each configuration (1-based lines, in configuration order).
    pub lines: &'a [usize],
}

impl ConfigurationNames<'_> {
    /// "configurations 4, 8 (measurements.csv lines 5, 9)" for 0-based configurations `[3, 7]`.
    pub fn name(&self, configs: &[usize]) -> String {
        let numbers: Vec<String> = configs.iter().map(|k| (k + 1).to_string()).collect();
        let at: Vec<String> = configs
            .iter()
            .map(|&k| self.lines.get(k).map_or("?".into(), |l| l.to_string()))
            .collect();
        let (noun, line) = if configs.len() == 1 {
            ("configuration", "line")
        } else {
            ("configurations", "lines")
        };
        format!(
            "{noun} {} ({} {line} {})",
            numbers.join(", "),
            self.file,
            at.join(", ")
        )
    }
}

/// What proved a leg empty, in words.
pub fn proof_in_words(proof: Option<EmptinessProof>) -> String {
    match proof {
        Some(EmptinessProof::CheapRejection { measurement }) => format!(
            "configuration {} fits no parameter vector left after contraction",
            measurement + 1
        ),
        Some(EmptinessProof::LpInfeasible) => {
            "the linear relaxation of the data has no solution (checked Farkas certificate)".into()
        }
        Some(EmptinessProof::EmptyIntersection { parameter }) => format!(
            "the certified lower and upper bounds of {} crossed",
            PARAMETER_NAMES.get(parameter).unwrap_or(&"a parameter")
        ),
        Some(EmptinessProof::Subdivision) => {
            "every piece of a subdivision of x0 was proved empty".into()
        }
        Some(EmptinessProof::EverySubset) => {
            "whichever configurations are dropped, the rest was proved inconsistent".into()
        }
        None => "no proof recorded".into(),
    }
}

/// A short verdict: "consistent", "proved empty" or "undecided".
pub fn short_verdict(status: Status) -> &'static str {
    match status {
        Status::Consistent => "consistent",
        Status::Empty => "proved empty",
        Status::Undecided => "undecided",
    }
}

/// The verdict and its evidence, one sentence per entry: for an empty leg the proof, the
/// conflicting configurations and what to do next.
pub fn verdict(r: &LegResult, names: &ConfigurationNames<'_>, max_outliers: usize) -> Vec<String> {
    match r.status {
        Status::Empty => {
            let tolerated = if max_outliers > 0 {
                format!(", even with {max_outliers} of them tolerated as outliers")
            } else {
                String::new()
            };
            let mut out = vec![format!(
                "verdict: no parameter vector in x0 fits the measurements within their error \
                 bounds{tolerated} — proved: {}",
                proof_in_words(r.emptiness)
            )];
            match &r.conflict {
                Some(conflict) => {
                    let named = names.name(conflict);
                    out.push(if conflict.len() == 1 {
                        format!("conflict: {named} alone fits no parameter vector of x0.")
                    } else {
                        format!(
                            "conflict: {named} cannot be fitted together; with any one of them \
                             removed the rest is not proved inconsistent."
                        )
                    });
                    out.push(format!(
                        "re-measure them, or run with --max-outliers {} to tolerate {} bad \
                         configuration{}",
                        max_outliers + 1,
                        max_outliers + 1,
                        if max_outliers == 0 { "" } else { "s" }
                    ));
                }
                None => out.push(
                    "run with a larger --max-outliers, or check the model and error bounds".into(),
                ),
            }
            out
        }
        Status::Consistent => {
            vec!["verdict: consistent (a certified witness satisfies every measurement box)".into()]
        }
        Status::Undecided => vec![
            "verdict: undecided (no certified witness found; the outer box \
                                   is still a certified enclosure)"
                .into(),
        ],
    }
}

/// The outer (or x1) width over the inner width, per parameter, when both exist.
pub fn width_ratios(r: &LegResult) -> Option<[f64; 7]> {
    let (outer, inner) = (r.outer?, r.inner?);
    Some(core::array::from_fn(|j| outer[j].wid() / inner[j].wid()))
}

/// What the outer/inner ratios mean for this run: converged, budget spent, or `--fast`.
pub fn tightness(r: &LegResult) -> Option<&'static str> {
    width_ratios(r)?;
    Some(match r.converged {
        Some(true) => {
            "the true range of each parameter lies between inner and outer: outer overstates it \
             by at most the ratio"
        }
        Some(false) => {
            "budget spent before every ratio reached the tolerance (--max-boxes, --max-seconds); \
             both boxes are still certified"
        }
        None => "(--fast: the paper's x1 only; drop --fast for the tight hull)",
    })
}

/// The parameters (index, which end) where the outer box reaches a face of the initial box x0.
pub fn x0_faces(r: &LegResult) -> Vec<(usize, &'static str)> {
    let Some(outer) = r.outer else {
        return Vec::new();
    };
    (0..7)
        .filter_map(|j| {
            let lo = outer[j].inf() <= r.x0[j].inf();
            let hi = outer[j].sup() >= r.x0[j].sup();
            match (lo, hi) {
                (true, true) => Some((j, "both ends")),
                (true, false) => Some((j, "lower end")),
                (false, true) => Some((j, "upper end")),
                (false, false) => None,
            }
        })
        .collect()
}

/// Where the outer box reaches a face of the initial box x0, in words: consistent parameter
/// vectors may then lie beyond x0, which the certificate does not cover.
pub fn touching_x0(r: &LegResult) -> Option<String> {
    let faces: Vec<String> = x0_faces(r)
        .iter()
        .map(|(j, end)| format!("{} ({end})", PARAMETER_NAMES[*j]))
        .collect();
    (!faces.is_empty()).then(|| {
        format!(
            "the outer box reaches x0 in {}: consistent parameter vectors may lie beyond x0 there, \
             and the certificate covers x0 only — enlarge the initial box (its radius) to look \
             further",
            faces.join(", ")
        )
    })
}

/// What a certificate proves about a parameter vector found by other means (a least-squares fit).
#[derive(Clone, Debug, PartialEq)]
pub enum Standing {
    /// Inside the certified box: not refuted (which alone does not prove it consistent).
    Inside,
    /// Inside x0 but outside the certified box (in these parameters), or anywhere in x0 when x0
    /// was proved empty: it does not fit the measurements within their error bounds.
    Refuted(Vec<usize>),
    /// Outside x0 (in these parameters): the certificate covers x0 only and proves nothing here.
    BeyondX0(Vec<usize>),
}

/// Where `x` stands against a certificate over `x0`: `certified` is the certified box, `None` when
/// x0 was proved to hold no consistent parameter vector.
pub fn standing(x0: &[Interval; 7], certified: Option<&[Interval; 7]>, x: &[f64; 7]) -> Standing {
    let outside =
        |b: &[Interval; 7]| -> Vec<usize> { (0..7).filter(|&j| !b[j].contains(x[j])).collect() };
    let beyond = outside(x0);
    if !beyond.is_empty() {
        return Standing::BeyondX0(beyond);
    }
    match certified {
        None => Standing::Refuted(Vec::new()),
        Some(b) => {
            let refuted = outside(b);
            if refuted.is_empty() {
                Standing::Inside
            } else {
                Standing::Refuted(refuted)
            }
        }
    }
}

/// [`standing`] against a leg's result: its outer box, or none when it was proved empty.
pub fn leg_standing(r: &LegResult, x: &[f64; 7]) -> Standing {
    let certified = match r.status {
        Status::Empty => None,
        _ => Some(r.outer.as_ref().unwrap_or(&r.x0)),
    };
    standing(&r.x0, certified, x)
}

/// With outliers tolerated (`max_outliers > 0`) on a leg that is not empty: which configurations
/// were proved to be outliers.
pub fn outliers(
    r: &LegResult,
    names: &ConfigurationNames<'_>,
    max_outliers: usize,
) -> Option<String> {
    if max_outliers == 0 || r.status == Status::Empty {
        return None;
    }
    Some(if r.outliers.is_empty() {
        format!("outliers (at most {max_outliers} tolerated): no configuration is proved to be one")
    } else {
        format!(
            "outliers (at most {max_outliers} tolerated): {} — every parameter vector that fits \
             the rest misfits {}",
            names.name(&r.outliers),
            if r.outliers.len() == 1 { "it" } else { "them" }
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn configurations_are_named_by_number_and_line() {
        let lines = [2, 3, 5, 6];
        let n = ConfigurationNames {
            file: "m.csv",
            lines: &lines,
        };
        assert_eq!(n.name(&[2]), "configuration 3 (m.csv line 5)");
        assert_eq!(n.name(&[0, 3]), "configurations 1, 4 (m.csv lines 2, 6)");
        assert_eq!(n.name(&[9]), "configuration 10 (m.csv line ?)");
    }

    #[test]
    fn faces_of_x0_reached_by_the_outer_box_are_named() {
        let x0 = [calib_core::Interval::new(-1.0, 1.0); 7];
        let mut outer = [calib_core::Interval::new(-0.5, 0.5); 7];
        outer[2] = calib_core::Interval::new(-1.0, 0.5);
        outer[6] = x0[6];
        let r = LegResult {
            leg: 0,
            x0,
            status: Status::Consistent,
            emptiness: None,
            x1: Some(outer),
            outer: Some(outer),
            inner: None,
            witness: None,
            conflict: None,
            outliers: vec![],
            iterations: 1,
            converged: Some(true),
            x2: None,
            paving: None,
            boxes: 1,
            seconds: 0.0,
        };
        let words = touching_x0(&r).expect("two faces reached");
        assert!(words.contains("az (lower end), l (both ends)"), "{words}");
        let inside = LegResult {
            outer: Some([calib_core::Interval::new(-0.5, 0.5); 7]),
            ..r
        };
        assert_eq!(touching_x0(&inside), None);
    }

    #[test]
    fn only_vectors_inside_x0_are_refuted() {
        let x0 = [Interval::new(-1.0, 1.0); 7];
        let outer = [Interval::new(-0.5, 0.5); 7];
        let mut x = [0.0; 7];
        assert_eq!(standing(&x0, Some(&outer), &x), Standing::Inside);
        assert_eq!(standing(&x0, None, &x), Standing::Refuted(vec![]));
        x[6] = 0.75;
        assert_eq!(standing(&x0, Some(&outer), &x), Standing::Refuted(vec![6]));
        x[2] = 3.0;
        assert_eq!(standing(&x0, Some(&outer), &x), Standing::BeyondX0(vec![2]));
        assert_eq!(standing(&x0, None, &x), Standing::BeyondX0(vec![2]));
    }

    #[test]
    fn every_proof_has_words() {
        for p in [
            Some(EmptinessProof::CheapRejection { measurement: 4 }),
            Some(EmptinessProof::LpInfeasible),
            Some(EmptinessProof::EmptyIntersection { parameter: 6 }),
            Some(EmptinessProof::Subdivision),
            Some(EmptinessProof::EverySubset),
            None,
        ] {
            let words = proof_in_words(p);
            assert!(
                !words.contains("Rejection") && !words.contains("Lp"),
                "{words}"
            );
        }
        assert!(
            proof_in_words(Some(EmptinessProof::CheapRejection { measurement: 4 }))
                .contains("configuration 5")
        );
    }
}
