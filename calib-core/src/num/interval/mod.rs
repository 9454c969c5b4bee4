//! Rigorous interval arithmetic over `f64` with outward rounding.
//!
//! # The decision: an own type with directed widening, not a wrapper of `inari`
//!
//! `inari` implements IEEE 1788 with hardware rounding, but it does not compile without
//! `-C target-cpu=haswell` (or a similar target feature set) in every crate that builds it — a cost
//! we would push onto every crate that embeds certicalib. This type is portable instead: every
//! operation computes the round-to-nearest result and widens it by one unit in the last place with
//! [`f64::next_down`]/[`f64::next_up`]. Because IEEE 754 round-to-nearest is within half an ulp of
//! the exact result, the widened bounds enclose it. The price is at most one ulp of extra width per
//! bound and operation (results that are exact because an operand is zero, and zero sums, are not
//! widened).
//!
//! Measured cost (2026-11, one core of the development machine, the Gough-leg residual of paper
//! eq. 3 over the paper's boxes, the same source expression for both types):
//!
//! | evaluation | time | enclosure width |
//! |---|---|---|
//! | `f64` point evaluation (`cargo bench --bench eval`) | 8 ns | — |
//! | this `Interval` (portable build) | 275 ns | 90.07517 |
//! | `inari` 2.0 (`-C target-cpu=haswell`, no `gmp` feature) | 1537 ns | 90.07517 |
//!
//! (The `inari` figure comes from a scratch crate evaluating the identical expression in a loop;
//! the widths agree to the printed digits, so the extra ulp does not show.)
//!
//! Elementary functions (`sin`, `cos`, `tan`) rely on the platform `libm` having an error below two
//! ulps (glibc and the Rust/LLVM defaults document at most one ulp); their bounds are widened by two
//! ulps. `sqrt` is correctly rounded by IEEE 754 and widened by one ulp.
//!
//! # Representation invariant
//!
//! A non-empty interval `[lo, hi]` has `lo <= hi`, `lo < +inf`, `hi > -inf`, and no NaN; unbounded
//! intervals are represented with infinite bounds (`[-inf, +inf]` is [`Interval::ENTIRE`]). The empty
//! set is stored as `lo = +inf, hi = -inf` ([`Interval::EMPTY`]); every operation with an empty operand
//! returns empty. Intervals are closed sets of reals: the infinities are not members.

mod arith;
mod elementary;
mod set_ops;

use core::fmt;

/// A closed interval of real numbers with `f64` bounds, or the empty set.
///
/// Every operation returns an interval that contains the exact real result of the operation applied to
/// every combination of members (outward rounding). See the module documentation for the invariant.
#[derive(Clone, Copy, PartialEq)]
pub struct Interval {
    lo: f64,
    hi: f64,
}

impl Interval {
    /// The empty set.
    pub const EMPTY: Interval = Interval {
        lo: f64::INFINITY,
        hi: f64::NEG_INFINITY,
    };
    /// The whole real line `[-inf, +inf]`.
    pub const ENTIRE: Interval = Interval {
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
    };
    /// `[0, 0]`.
    pub const ZERO: Interval = Interval { lo: 0.0, hi: 0.0 };
    /// `[1, 1]`.
    pub const ONE: Interval = Interval { lo: 1.0, hi: 1.0 };
    /// An enclosure of pi: `[3.141592653589793, 3.1415926535897936]`.
    pub const PI: Interval = Interval {
        lo: core::f64::consts::PI,
        hi: 3.141_592_653_589_793_6,
    };

    /// The interval `[lo, hi]`.
    ///
    /// # Panics
    /// If `lo > hi`, if either bound is NaN, or if `lo = +inf` or `hi = -inf` (such a pair does not
    /// describe a set of reals). Use [`Interval::try_new`] for data that may be malformed.
    #[track_caller]
    pub fn new(lo: f64, hi: f64) -> Interval {
        match Interval::try_new(lo, hi) {
            Some(x) => x,
            None => {
                panic!("Interval::new({lo}, {hi}): requires lo <= hi, no NaN, lo < +inf, hi > -inf")
            }
        }
    }

    /// The interval `[lo, hi]`, or `None` if the bounds do not describe a non-empty set of reals.
    pub fn try_new(lo: f64, hi: f64) -> Option<Interval> {
        (lo <= hi && lo < f64::INFINITY && hi > f64::NEG_INFINITY).then_some(Interval { lo, hi })
    }

    /// The degenerate interval `[x, x]`.
    ///
    /// # Panics
    /// If `x` is not finite.
    #[track_caller]
    pub fn point(x: f64) -> Interval {
        assert!(
            x.is_finite(),
            "Interval::point({x}): requires a finite number"
        );
        Interval { lo: x, hi: x }
    }

    /// `[mid - rad, mid + rad]`, rounded outward; `rad` must be non-negative and finite.
    ///
    /// # Panics
    /// If `mid` or `rad` is not finite or `rad < 0`.
    #[track_caller]
    pub fn mid_rad(mid: f64, rad: f64) -> Interval {
        assert!(
            mid.is_finite() && rad.is_finite() && rad >= 0.0,
            "Interval::mid_rad({mid}, {rad}): requires finite mid and finite rad >= 0"
        );
        Interval::point(mid) + Interval { lo: -rad, hi: rad }
    }

    /// `[lo, hi]` without checks, for bounds the caller has already validated.
    pub(crate) const fn from_bounds_unchecked(lo: f64, hi: f64) -> Interval {
        Interval { lo, hi }
    }

    /// Lower bound (`+inf` for the empty set).
    #[inline]
    pub fn inf(self) -> f64 {
        self.lo
    }

    /// Upper bound (`-inf` for the empty set).
    #[inline]
    pub fn sup(self) -> f64 {
        self.hi
    }

    /// Whether this is the empty set.
    #[inline]
    pub fn is_empty(self) -> bool {
        self.lo > self.hi
    }

    /// Whether both bounds are finite (the empty set is not bounded here).
    #[inline]
    pub fn is_bounded(self) -> bool {
        !self.is_empty() && self.lo.is_finite() && self.hi.is_finite()
    }

    /// Whether the real number `x` is a member (`false` for NaN and the infinities).
    #[inline]
    pub fn contains(self, x: f64) -> bool {
        self.lo <= x && x <= self.hi && x.is_finite()
    }

    /// Whether every member of `self` is a member of `other`.
    #[inline]
    pub fn is_subset_of(self, other: Interval) -> bool {
        self.is_empty() || (other.lo <= self.lo && self.hi <= other.hi)
    }

    /// Whether `self` lies in the interior of `other` (IEEE 1788 `interior`: an infinite bound of
    /// `other` counts as interior to itself). The empty set is interior to everything.
    #[inline]
    pub fn is_interior_of(self, other: Interval) -> bool {
        self.is_empty()
            || ((other.lo < self.lo || other.lo == f64::NEG_INFINITY)
                && (self.hi < other.hi || other.hi == f64::INFINITY))
    }

    /// A midpoint that is a member of the interval: `(lo + hi) / 2` rounded to nearest for bounded
    /// intervals, `0` for [`Interval::ENTIRE`], `-f64::MAX`/`f64::MAX` for half-bounded ones.
    /// NaN for the empty set.
    #[inline]
    pub fn mid(self) -> f64 {
        if self.is_empty() {
            return f64::NAN;
        }
        match (self.lo == f64::NEG_INFINITY, self.hi == f64::INFINITY) {
            (true, true) => 0.0,
            (true, false) => -f64::MAX,
            (false, true) => f64::MAX,
            (false, false) => {
                let m = 0.5 * self.lo + 0.5 * self.hi;
                m.clamp(self.lo, self.hi)
            }
        }
    }

    /// A radius `r`, rounded up, such that `[mid - r, mid + r]` contains the interval (with
    /// `mid = self.mid()`). `0` for a point, `+inf` if unbounded, NaN for the empty set.
    #[inline]
    pub fn rad(self) -> f64 {
        if self.is_empty() {
            return f64::NAN;
        }
        let m = self.mid();
        let r = (m - self.lo).max(self.hi - m);
        if r == 0.0 {
            0.0
        } else {
            r.next_up()
        }
    }

    /// The width `hi - lo`, rounded up. NaN for the empty set.
    #[inline]
    pub fn wid(self) -> f64 {
        if self.is_empty() {
            return f64::NAN;
        }
        let w = self.hi - self.lo;
        if w == 0.0 {
            0.0
        } else {
            w.next_up()
        }
    }

    /// The magnitude `max |x|` over the members. NaN for the empty set.
    #[inline]
    pub fn mag(self) -> f64 {
        if self.is_empty() {
            return f64::NAN;
        }
        self.lo.abs().max(self.hi.abs())
    }

    /// The mignitude `min |x|` over the members. NaN for the empty set.
    #[inline]
    pub fn mig(self) -> f64 {
        if self.is_empty() {
            f64::NAN
        } else if self.lo > 0.0 {
            self.lo
        } else if self.hi < 0.0 {
            -self.hi
        } else {
            0.0
        }
    }
}

impl fmt::Debug for Interval {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

/// Prints `[lo, hi]` with the bounds in Rust's shortest round-trip form (reading them back gives the
/// same `f64`s, so printing never moves a bound inward), or `[empty]`.
impl fmt::Display for Interval {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_empty() {
            write!(f, "[empty]")
        } else {
            write!(f, "[{:?}, {:?}]", self.lo, self.hi)
        }
    }
}

impl Default for Interval {
    /// `[0, 0]`.
    fn default() -> Self {
        Interval::ZERO
    }
}

impl From<f64> for Interval {
    /// `[x, x]`; panics if `x` is not finite (see [`Interval::point`]).
    fn from(x: f64) -> Self {
        Interval::point(x)
    }
}

/// Rounding primitives: round-to-nearest results widened by one ulp.
pub(crate) mod round {
    /// A lower bound of the exact value whose round-to-nearest result is `x`.
    #[inline(always)]
    pub fn down(x: f64) -> f64 {
        x.next_down()
    }

    /// An upper bound of the exact value whose round-to-nearest result is `x`.
    #[inline(always)]
    pub fn up(x: f64) -> f64 {
        x.next_up()
    }

    /// Lower bound of `a + b`. Exact when an operand is zero, and when the rounded sum is zero (a
    /// floating-point sum is zero only if `a = -b` exactly).
    #[inline(always)]
    pub fn add_down(a: f64, b: f64) -> f64 {
        let s = a + b;
        if a == 0.0 || b == 0.0 || s == 0.0 {
            s
        } else {
            down(s)
        }
    }

    /// Upper bound of `a + b` (exact in the same cases as [`add_down`]).
    #[inline(always)]
    pub fn add_up(a: f64, b: f64) -> f64 {
        let s = a + b;
        if a == 0.0 || b == 0.0 || s == 0.0 {
            s
        } else {
            up(s)
        }
    }

    /// Lower bound of `a * b`, with `0 * inf = 0` (interval convention: the infinities are not
    /// members, so a zero factor makes the product zero).
    #[inline(always)]
    pub fn mul_down(a: f64, b: f64) -> f64 {
        if a == 0.0 || b == 0.0 {
            0.0
        } else {
            down(a * b)
        }
    }

    /// Upper bound of `a * b`, with `0 * inf = 0`.
    #[inline(always)]
    pub fn mul_up(a: f64, b: f64) -> f64 {
        if a == 0.0 || b == 0.0 {
            0.0
        } else {
            up(a * b)
        }
    }

    /// Lower bound of `a / b` for `b != 0`; `0 / b = 0`. `inf / inf` gives NaN, which callers drop
    /// with `f64::min`/`f64::max` (the neighbouring corners bound the quotient).
    #[inline(always)]
    pub fn div_down(a: f64, b: f64) -> f64 {
        if a == 0.0 {
            0.0
        } else {
            down(a / b)
        }
    }

    /// Upper bound of `a / b` for `b != 0`; `0 / b = 0`.
    #[inline(always)]
    pub fn div_up(a: f64, b: f64) -> f64 {
        if a == 0.0 {
            0.0
        } else {
            up(a / b)
        }
    }
}
