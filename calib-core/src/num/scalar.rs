//! The [`Scalar`] trait: what a residual written under `#[interval_model]` may use.

use crate::Interval;
use core::fmt::Debug;
use core::ops::{Add, Div, Mul, Neg, Sub};

/// A number type a residual can be written over: `f64` (point evaluation), [`Interval`] (rigorous
/// enclosures), [`crate::Affine`] (affine forms), [`crate::Dual`] (forward-mode derivatives, for
/// tests) and [`crate::Jet`] (derivatives in any of these).
///
/// A residual is written once as `fn f<S: Scalar>(x: &[S; NX], m: &[S; NM]) -> S`; the
/// `#[interval_model]` attribute derives every evaluator from that one body.
pub trait Scalar:
    Copy
    + Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// The constant `v`. Inside an `#[interval_model]` body, `S::cst(0.1)` with a literal argument
    /// is rewritten to [`Scalar::enclose`] of the decimal value, so that the interval evaluators
    /// enclose the real number 0.1 rather than the nearest double.
    fn cst(v: f64) -> Self;

    /// A constant known only to lie in `[lo, hi]`, whose nearest double is `nearest`
    /// (`lo <= nearest <= hi`): `f64` takes `nearest`, [`Interval`] takes `[lo, hi]`.
    /// The `#[interval_model]` code generator emits this for every literal.
    fn enclose(nearest: f64, lo: f64, hi: f64) -> Self;

    /// Whether the large generated evaluators call this type's operations out of line
    /// (`calib-core/src/model/arithmetic.rs`): `true` (the default) for every type whose operations
    /// are more than a few instructions, `false` for `f64`.
    const OUT_OF_LINE: bool = true;

    /// The square `self * self` (tighter than the product for intervals containing zero).
    fn sqr(self) -> Self;

    /// The integer power `self^n`.
    fn powi(self, n: i32) -> Self;

    /// The square root.
    fn sqrt(self) -> Self;

    /// The sine.
    fn sin(self) -> Self;

    /// The cosine.
    fn cos(self) -> Self;

    /// The tangent.
    fn tan(self) -> Self;
}

impl Scalar for f64 {
    const OUT_OF_LINE: bool = false;
    #[inline(always)]
    fn cst(v: f64) -> Self {
        v
    }
    #[inline(always)]
    fn enclose(nearest: f64, _lo: f64, _hi: f64) -> Self {
        nearest
    }
    #[inline(always)]
    fn sqr(self) -> Self {
        self * self
    }
    #[inline(always)]
    fn powi(self, n: i32) -> Self {
        f64::powi(self, n)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn sin(self) -> Self {
        f64::sin(self)
    }
    #[inline(always)]
    fn cos(self) -> Self {
        f64::cos(self)
    }
    #[inline(always)]
    fn tan(self) -> Self {
        f64::tan(self)
    }
}

impl Scalar for Interval {
    /// `[v, v]`; panics if `v` is not finite.
    #[inline(always)]
    fn cst(v: f64) -> Self {
        Interval::point(v)
    }
    /// `[lo, hi]`; panics if the bounds do not describe an interval (checked once per call, off
    /// the hot path when the constants are known at compile time).
    #[inline(always)]
    fn enclose(_nearest: f64, lo: f64, hi: f64) -> Self {
        Interval::new(lo, hi)
    }
    #[inline(always)]
    fn sqr(self) -> Self {
        Interval::sqr(self)
    }
    #[inline(always)]
    fn powi(self, n: i32) -> Self {
        Interval::powi(self, n)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        Interval::sqrt(self)
    }
    #[inline(always)]
    fn sin(self) -> Self {
        Interval::sin(self)
    }
    #[inline(always)]
    fn cos(self) -> Self {
        Interval::cos(self)
    }
    #[inline(always)]
    fn tan(self) -> Self {
        Interval::tan(self)
    }
}
