//! Enclosing decimal literals: the double interval that contains the real number a literal denotes.
//!
//! `0.1` is not a double: round-to-nearest gives `v = 0.1000000000000000055...`. We compare the
//! literal's exact decimal value with the exact decimal expansion of `v` (every double has a finite
//! one) and return `[v, v]` when they are equal, `[pred(v), v]` when the literal is below `v` and
//! `[v, succ(v)]` when it is above.

use std::cmp::Ordering;

/// An enclosure of a non-negative decimal literal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Enclosure {
    /// The double nearest to the literal (what the point evaluators use).
    pub nearest: f64,
    /// Lower bound.
    pub lo: f64,
    /// Upper bound.
    pub hi: f64,
}

/// A non-negative decimal `int(digits) * 10^exp`, normalised: no leading or trailing zeros in
/// `digits` (zero has empty `digits`).
#[derive(Debug, PartialEq, Eq)]
struct Decimal {
    digits: Vec<u8>,
    exp: i64,
}

impl Decimal {
    /// Parses `123`, `1.5`, `1e-300`, `2.5E+3` (ASCII digits, optional fraction and exponent).
    fn parse(text: &str) -> Option<Decimal> {
        let (mantissa, exp) = match text.find(['e', 'E']) {
            Some(i) => (&text[..i], text[i + 1..].parse::<i64>().ok()?),
            None => (text, 0),
        };
        let (int, frac) = mantissa.split_once('.').unwrap_or((mantissa, ""));
        if int.is_empty() && frac.is_empty() {
            return None;
        }
        let mut digits = Vec::with_capacity(int.len() + frac.len());
        for c in int.chars().chain(frac.chars()) {
            digits.push(c.to_digit(10)? as u8);
        }
        Some(Decimal::normalised(digits, exp - frac.len() as i64))
    }

    fn normalised(mut digits: Vec<u8>, mut exp: i64) -> Decimal {
        let lead = digits.iter().take_while(|&&d| d == 0).count();
        digits.drain(..lead);
        while digits.last() == Some(&0) {
            digits.pop();
            exp += 1;
        }
        if digits.is_empty() {
            exp = 0;
        }
        Decimal { digits, exp }
    }

    /// The exact decimal value of a finite non-negative double.
    fn of_f64(v: f64) -> Decimal {
        // Rust formats with an explicit precision exactly (no double rounding); 800 significant
        // digits exceed the longest exact expansion of a double (767).
        let text = format!("{v:.800e}");
        Decimal::parse(&text).expect("Rust's float formatting is a decimal")
    }

    fn cmp(&self, other: &Decimal) -> Ordering {
        match (self.digits.is_empty(), other.digits.is_empty()) {
            (true, true) => return Ordering::Equal,
            (true, false) => return Ordering::Less,
            (false, true) => return Ordering::Greater,
            (false, false) => {}
        }
        // Order of magnitude: the value lies in [10^(len+exp-1), 10^(len+exp)).
        let mag_a = self.digits.len() as i64 + self.exp;
        let mag_b = other.digits.len() as i64 + other.exp;
        mag_a.cmp(&mag_b).then_with(|| {
            let n = self.digits.len().max(other.digits.len());
            let at = |d: &Decimal, i: usize| d.digits.get(i).copied().unwrap_or(0);
            (0..n)
                .map(|i| at(self, i).cmp(&at(other, i)))
                .find(|o| o.is_ne())
                .unwrap_or(Ordering::Equal)
        })
    }
}

/// The enclosure of a non-negative decimal literal given by its base-10 digits (as
/// `syn::LitFloat::base10_digits` returns them), or `None` if the text is not a decimal or the
/// value overflows `f64`.
pub fn enclose(text: &str) -> Option<Enclosure> {
    let exact = Decimal::parse(text)?;
    let nearest: f64 = text.parse().ok()?;
    if !nearest.is_finite() {
        return None;
    }
    let (lo, hi) = match exact.cmp(&Decimal::of_f64(nearest)) {
        Ordering::Equal => (nearest, nearest),
        Ordering::Less => (nearest.next_down(), nearest),
        Ordering::Greater => (nearest, nearest.next_up()),
    };
    Some(Enclosure { nearest, lo, hi })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_literals_are_points() {
        for t in [
            "0",
            "0.0",
            "1",
            "0.5",
            "2.25",
            "1e3",
            "1024",
            "9007199254740992",
            "0.125e1",
        ] {
            let e = enclose(t).unwrap();
            assert_eq!((e.lo, e.hi), (e.nearest, e.nearest), "{t}");
        }
    }

    #[test]
    fn inexact_literals_are_one_ulp_wide_around_the_decimal() {
        // 0.1 rounds up to 0.1000000000000000055511151231257827...
        let e = enclose("0.1").unwrap();
        assert_eq!(e.hi, 0.1);
        assert_eq!(e.lo, 0.1f64.next_down());
        // 0.3 rounds down to 0.299999999999999988897769753748...
        let e = enclose("0.3").unwrap();
        assert_eq!(e.lo, 0.3);
        assert_eq!(e.hi, 0.3f64.next_up());
        // 1e-300 and 9007199254740993 (2^53 + 1, not a double)
        for t in [
            "1e-300",
            "9007199254740993",
            "0.333333333333333333333333",
            "52.2496",
        ] {
            let e = enclose(t).unwrap();
            assert!(e.lo < e.hi && e.lo.next_up() == e.hi, "{t}: {e:?}");
        }
    }

    #[test]
    fn underflow_and_overflow() {
        let e = enclose("1e-400").unwrap();
        assert_eq!((e.lo, e.hi), (0.0, f64::from_bits(1)));
        assert!(enclose("1e400").is_none());
        assert!(enclose("abc").is_none());
    }
}
