//! Arithmetic: `+ - * /`, negation, `sqr`, `powi`, `recip`, and mixed operations with `f64`.

use super::round::{add_down, add_up, div_down, div_up, mul_down, mul_up};
use super::Interval;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

impl Neg for Interval {
    type Output = Interval;
    /// `[-hi, -lo]` (exact).
    #[inline(always)]
    fn neg(self) -> Interval {
        Interval::from_bounds_unchecked(-self.hi, -self.lo)
    }
}

impl Add for Interval {
    type Output = Interval;
    /// `[lo1 + lo2, hi1 + hi2]` rounded outward.
    #[inline(always)]
    fn add(self, rhs: Interval) -> Interval {
        if self.is_empty() || rhs.is_empty() {
            return Interval::EMPTY;
        }
        Interval::from_bounds_unchecked(add_down(self.lo, rhs.lo), add_up(self.hi, rhs.hi))
    }
}

impl Sub for Interval {
    type Output = Interval;
    /// `[lo1 - hi2, hi1 - lo2]` rounded outward.
    #[inline(always)]
    fn sub(self, rhs: Interval) -> Interval {
        self + (-rhs)
    }
}

impl Mul for Interval {
    type Output = Interval;
    /// Hull of the four corner products, rounded outward; a zero factor gives zero even against an
    /// infinite bound.
    #[inline(always)]
    fn mul(self, rhs: Interval) -> Interval {
        if self.is_empty() || rhs.is_empty() {
            return Interval::EMPTY;
        }
        let (a, b, c, d) = (self.lo, self.hi, rhs.lo, rhs.hi);
        // Sign cases: two corner products (four only when both straddle zero).
        let (lo, hi) = if a >= 0.0 {
            if c >= 0.0 {
                (mul_down(a, c), mul_up(b, d))
            } else if d <= 0.0 {
                (mul_down(b, c), mul_up(a, d))
            } else {
                (mul_down(b, c), mul_up(b, d))
            }
        } else if b <= 0.0 {
            if c >= 0.0 {
                (mul_down(a, d), mul_up(b, c))
            } else if d <= 0.0 {
                (mul_down(b, d), mul_up(a, c))
            } else {
                (mul_down(a, d), mul_up(a, c))
            }
        } else if c >= 0.0 {
            (mul_down(a, d), mul_up(b, d))
        } else if d <= 0.0 {
            (mul_down(b, c), mul_up(a, c))
        } else {
            (
                mul_down(a, d).min(mul_down(b, c)),
                mul_up(a, c).max(mul_up(b, d)),
            )
        };
        Interval::from_bounds_unchecked(lo, hi)
    }
}

impl Div for Interval {
    type Output = Interval;
    /// The hull of `{x / y : x in self, y in rhs, y != 0}`, rounded outward.
    ///
    /// Division by an interval that contains zero stays sound: `[1, 2] / [0, 1] = [1, +inf]`,
    /// `[1, 2] / [-1, 1] = ENTIRE` (the hull of two half-lines), `[0, 0] / y = [0, 0]` for any `y`
    /// other than `[0, 0]`, and `x / [0, 0] = EMPTY` (no real quotient exists).
    #[inline]
    fn div(self, rhs: Interval) -> Interval {
        if self.is_empty() || rhs.is_empty() {
            return Interval::EMPTY;
        }
        let (a, b, c, d) = (self.lo, self.hi, rhs.lo, rhs.hi);
        if c > 0.0 || d < 0.0 {
            // The quotient is monotone in each operand on a divisor of one sign, so each end is
            // one corner: the numerator's end over the divisor's end that the signs pick. Two
            // divisions instead of four corners and the same bounds, except where the numerator's
            // chosen end is ±0 and another corner was zero only by underflow or `x / ∞`: that end
            // is now the exact 0, where the four corners rounded it out to the next subnormal. A
            // NaN corner (∞/∞) cannot arise from intervals with finite or half-line ends; the four
            // corners remain the fallback should one.
            let (lo, hi) = if c > 0.0 {
                (
                    div_down(a, if a >= 0.0 { d } else { c }),
                    div_up(b, if b >= 0.0 { c } else { d }),
                )
            } else {
                (
                    div_down(b, if b >= 0.0 { d } else { c }),
                    div_up(a, if a >= 0.0 { c } else { d }),
                )
            };
            if !(lo.is_nan() || hi.is_nan()) {
                return Interval::from_bounds_unchecked(lo, hi);
            }
            let lo = div_down(a, c)
                .min(div_down(a, d))
                .min(div_down(b, c))
                .min(div_down(b, d));
            let hi = div_up(a, c)
                .max(div_up(a, d))
                .max(div_up(b, c))
                .max(div_up(b, d));
            return Interval::from_bounds_unchecked(lo, hi);
        }
        // From here on, 0 is in the divisor.
        if c == 0.0 && d == 0.0 {
            return Interval::EMPTY;
        }
        if a == 0.0 && b == 0.0 {
            return Interval::ZERO;
        }
        if a <= 0.0 && b >= 0.0 {
            return Interval::ENTIRE;
        }
        let inf = f64::INFINITY;
        if c == 0.0 {
            // Divisor (0, d] with d > 0.
            if a > 0.0 {
                Interval::from_bounds_unchecked(div_down(a, d), inf)
            } else {
                Interval::from_bounds_unchecked(-inf, div_up(b, d))
            }
        } else if d == 0.0 {
            // Divisor [c, 0) with c < 0.
            if a > 0.0 {
                Interval::from_bounds_unchecked(-inf, div_up(a, c))
            } else {
                Interval::from_bounds_unchecked(div_down(b, c), inf)
            }
        } else {
            // Zero strictly inside the divisor: the quotient set is two half-lines; their hull is
            // the whole line.
            Interval::ENTIRE
        }
    }
}

macro_rules! mixed_ops {
    ($($tr:ident $method:ident),*) => {$(
        impl $tr<f64> for Interval {
            type Output = Interval;
            /// The operation with the point interval `[rhs, rhs]` (panics if `rhs` is not finite).
            #[inline]
            fn $method(self, rhs: f64) -> Interval {
                $tr::$method(self, Interval::point(rhs))
            }
        }
        impl $tr<Interval> for f64 {
            type Output = Interval;
            /// The operation with the point interval `[self, self]` (panics if `self` is not finite).
            #[inline]
            fn $method(self, rhs: Interval) -> Interval {
                $tr::$method(Interval::point(self), rhs)
            }
        }
    )*};
}
mixed_ops!(Add add, Sub sub, Mul mul, Div div);

impl AddAssign for Interval {
    #[inline]
    fn add_assign(&mut self, rhs: Interval) {
        *self = *self + rhs;
    }
}

impl SubAssign for Interval {
    #[inline]
    fn sub_assign(&mut self, rhs: Interval) {
        *self = *self - rhs;
    }
}

impl MulAssign for Interval {
    #[inline]
    fn mul_assign(&mut self, rhs: Interval) {
        *self = *self * rhs;
    }
}

/// Lower bound of `x^n` for `x >= 0` by binary exponentiation with every product rounded down
/// (monotone in the factors, so the result stays below the exact power).
fn pow_nonneg_down(x: f64, n: u32) -> f64 {
    pow_nonneg(x, n, mul_down)
}

/// Upper bound of `x^n` for `x >= 0`.
fn pow_nonneg_up(x: f64, n: u32) -> f64 {
    pow_nonneg(x, n, mul_up)
}

#[inline]
fn pow_nonneg(x: f64, mut n: u32, mul: fn(f64, f64) -> f64) -> f64 {
    let mut base = x;
    let mut acc = 1.0;
    while n > 0 {
        if n & 1 == 1 {
            acc = mul(acc, base);
        }
        n >>= 1;
        if n > 0 {
            base = mul(base, base);
        }
    }
    acc.max(0.0)
}

impl Interval {
    /// The square `{x^2}`: tighter than `x * x` when the interval contains zero
    /// (`[-1, 2].sqr() = [0, 4]`, while `[-1, 2] * [-1, 2] = [-2, 4]`).
    #[inline]
    pub fn sqr(self) -> Interval {
        if self.is_empty() {
            return Interval::EMPTY;
        }
        let (a, b) = (self.lo, self.hi);
        if a >= 0.0 {
            Interval::from_bounds_unchecked(mul_down(a, a).max(0.0), mul_up(b, b))
        } else if b <= 0.0 {
            Interval::from_bounds_unchecked(mul_down(b, b).max(0.0), mul_up(a, a))
        } else {
            Interval::from_bounds_unchecked(0.0, mul_up(a, a).max(mul_up(b, b)))
        }
    }

    /// The integer power `{x^n}` (`x^0 = 1`); for negative `n` the reciprocal of `x^|n|`, so that
    /// an interval containing zero gives an unbounded result.
    pub fn powi(self, n: i32) -> Interval {
        if self.is_empty() {
            return Interval::EMPTY;
        }
        if n < 0 {
            return self.powi_unsigned(n.unsigned_abs()).recip();
        }
        self.powi_unsigned(n as u32)
    }

    fn powi_unsigned(self, n: u32) -> Interval {
        if n == 0 {
            return Interval::ONE;
        }
        let (a, b) = (self.lo, self.hi);
        if n % 2 == 0 {
            let (lo, hi) = (self.mig(), self.mag());
            Interval::from_bounds_unchecked(pow_nonneg_down(lo, n), pow_nonneg_up(hi, n))
        } else {
            // Odd powers are increasing: x^n = -((-x)^n) for x < 0.
            let lo = if a >= 0.0 {
                pow_nonneg_down(a, n)
            } else {
                -pow_nonneg_up(-a, n)
            };
            let hi = if b >= 0.0 {
                pow_nonneg_up(b, n)
            } else {
                -pow_nonneg_down(-b, n)
            };
            Interval::from_bounds_unchecked(lo, hi)
        }
    }

    /// The reciprocal `{1/x : x != 0}` (see division for the zero cases).
    #[inline]
    pub fn recip(self) -> Interval {
        Interval::ONE / self
    }
}
