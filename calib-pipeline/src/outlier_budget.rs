//! `--max-outliers`: how many bad configurations a sub-problem may have — a number, or `auto`, the
//! smallest number that makes it consistent.
//!
//! With `q` outliers tolerated, the certified set is every parameter vector that fits all but at
//! most `q` configurations. It grows with `q`, so "proved empty at `q`" implies "proved empty at
//! every smaller `q`": the smallest `q` whose certification is not empty is found by trying
//! `q = 0, 1, 2, …` in turn ([`smallest_consistent`]). An `Empty` verdict at `q - 1` is a proof
//! that fewer than `q` outliers cannot explain the data; the result at `q` is an ordinary
//! certification with `q` tolerated.

use std::fmt;
use std::str::FromStr;

/// The number of outliers to tolerate per sub-problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutlierBudget {
    /// Exactly this many (0: every configuration must fit).
    Fixed(usize),
    /// The smallest number that leaves the sub-problem not proved empty.
    Auto,
}

impl Default for OutlierBudget {
    fn default() -> Self {
        OutlierBudget::Fixed(0)
    }
}

impl From<usize> for OutlierBudget {
    fn from(q: usize) -> Self {
        OutlierBudget::Fixed(q)
    }
}

impl FromStr for OutlierBudget {
    type Err = String;

    /// `auto` or a non-negative integer (what `--max-outliers` accepts).
    fn from_str(s: &str) -> Result<Self, String> {
        let s = s.trim();
        if s.eq_ignore_ascii_case("auto") {
            return Ok(OutlierBudget::Auto);
        }
        s.parse().map(OutlierBudget::Fixed).map_err(|_| {
            format!("expected a number of configurations (0, 1, 2, …) or `auto`, found `{s}`")
        })
    }
}

impl fmt::Display for OutlierBudget {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            OutlierBudget::Fixed(q) => write!(f, "{q}"),
            OutlierBudget::Auto => write!(f, "auto"),
        }
    }
}

impl OutlierBudget {
    /// Checks a fixed budget against the number of configurations (at least one must remain);
    /// the error names the option.
    pub fn check(&self, configs: usize) -> Result<(), String> {
        match *self {
            OutlierBudget::Fixed(q) if q >= configs => Err(format!(
                "--max-outliers {q}: must be smaller than the number of configurations ({configs})"
            )),
            _ => Ok(()),
        }
    }
}

/// Certifies with the budget: for [`OutlierBudget::Fixed`]`(q)`, `certify(q)` once; for
/// [`OutlierBudget::Auto`], `certify(q)` for `q = 0, 1, …, configs - 1` until a result is not
/// `is_empty` (the last result when every one is). Returns the `q` of the result and the result.
pub fn smallest_consistent<R, E>(
    budget: OutlierBudget,
    configs: usize,
    mut certify: impl FnMut(usize) -> Result<R, E>,
    is_empty: impl Fn(&R) -> bool,
) -> Result<(usize, R), E> {
    let mut q = match budget {
        OutlierBudget::Fixed(q) => return Ok((q, certify(q)?)),
        OutlierBudget::Auto => 0,
    };
    loop {
        let r = certify(q)?;
        if !is_empty(&r) || q + 1 >= configs {
            return Ok((q, r));
        }
        q += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_numbers_and_auto() {
        assert_eq!("2".parse(), Ok(OutlierBudget::Fixed(2)));
        assert_eq!(" AUTO ".parse(), Ok(OutlierBudget::Auto));
        let e = "-1".parse::<OutlierBudget>().unwrap_err();
        assert!(e.contains("`-1`") && e.contains("auto"), "{e}");
        assert!("1.5".parse::<OutlierBudget>().is_err());
        for b in [OutlierBudget::Fixed(3), OutlierBudget::Auto] {
            assert_eq!(b.to_string().parse(), Ok(b));
        }
    }

    #[test]
    fn a_fixed_budget_must_leave_a_configuration() {
        assert!(OutlierBudget::Fixed(2).check(3).is_ok());
        assert!(OutlierBudget::Fixed(3)
            .check(3)
            .unwrap_err()
            .contains("--max-outliers 3"));
        assert!(OutlierBudget::Auto.check(1).is_ok());
    }

    /// A sub-problem that is empty below `needed` outliers.
    fn search(budget: OutlierBudget, configs: usize, needed: usize) -> (usize, Vec<usize>) {
        let mut tried = Vec::new();
        let (q, r) = smallest_consistent(
            budget,
            configs,
            |q| {
                tried.push(q);
                Ok::<_, ()>(q >= needed)
            },
            |consistent| !consistent,
        )
        .unwrap();
        assert_eq!(r, q >= needed);
        (q, tried)
    }

    #[test]
    fn auto_stops_at_the_first_consistent_q() {
        assert_eq!(search(OutlierBudget::Auto, 10, 0), (0, vec![0]));
        assert_eq!(search(OutlierBudget::Auto, 10, 3), (3, vec![0, 1, 2, 3]));
        // Never every configuration dropped: the last try keeps one.
        assert_eq!(search(OutlierBudget::Auto, 4, 9), (3, vec![0, 1, 2, 3]));
        // A fixed budget is tried once, whatever it gives.
        assert_eq!(search(OutlierBudget::Fixed(1), 10, 3), (1, vec![1]));
    }

    #[test]
    fn errors_stop_the_search() {
        let mut calls = 0;
        let r = smallest_consistent(
            OutlierBudget::Auto,
            10,
            |q| {
                calls += 1;
                if q == 1 {
                    Err("failed")
                } else {
                    Ok(false)
                }
            },
            |consistent| !consistent,
        );
        assert_eq!(r, Err("failed"));
        assert_eq!(calls, 2);
    }
}
