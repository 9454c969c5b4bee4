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

use crate::error::{OptionError, ParseError};

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
    type Err = ParseError;

    /// `auto` or a non-negative integer (what `--max-outliers` accepts).
    fn from_str(s: &str) -> Result<Self, ParseError> {
        let s = s.trim();
        if s.eq_ignore_ascii_case("auto") {
            return Ok(OutlierBudget::Auto);
        }
        s.parse()
            .map(OutlierBudget::Fixed)
            .map_err(|_| ParseError::OutlierBudget(s.to_string()))
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
    pub fn check(&self, configs: usize) -> Result<(), OptionError> {
        match *self {
            OutlierBudget::Fixed(q) if q >= configs => Err(OptionError::MaxOutliers {
                outliers: q,
                configurations: configs,
            }),
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
