//! Out-of-line arithmetic for the large residuals `#[interval_model]` generates.
//!
//! A generated evaluator is one straight-line body. For a kinematic chain differentiated in every
//! input (the arm's point model: ~1,300 operations; its six-row pose model: ~4,100) LLVM's
//! optimisation of that body grows much faster than its length once every interval product — a
//! nine-way sign case with directed roundings — is inlined into it: a clean build of calib-arm's
//! library took minutes with the pose model and seconds once these bodies call out of line
//! (`benches/README.md`, "Compile time of the generated evaluators", has the measurements).
//!
//! Bodies of more than 60 operations (`OUTLINE_ABOVE` in `calib-macros`) therefore call these
//! functions instead of the operators. For number types whose operations are a few instructions
//! (`f64`: [`Scalar::OUT_OF_LINE`] is `false`) they are the operators themselves; for the others
//! the operation is a call to one shared, separately optimised copy. The values are the same
//! either way: only where the code lives changes (tested below). The code runs no slower, often
//! faster: less of it competes for the instruction cache (the same section of
//! `benches/README.md`).

use crate::Scalar;

macro_rules! outlined_binary {
    ($(#[$doc:meta])* $name:ident, $never:ident, $op:tt) => {
        $(#[$doc])*
        #[inline(always)]
        pub fn $name<S: Scalar>(a: S, b: S) -> S {
            if S::OUT_OF_LINE {
                $never(a, b)
            } else {
                a $op b
            }
        }

        #[inline(never)]
        fn $never<S: Scalar>(a: S, b: S) -> S {
            a $op b
        }
    };
}

macro_rules! outlined_unary {
    ($(#[$doc:meta])* $name:ident, $never:ident, |$a:ident| $body:expr) => {
        $(#[$doc])*
        #[inline(always)]
        pub fn $name<S: Scalar>($a: S) -> S {
            if S::OUT_OF_LINE {
                $never($a)
            } else {
                $body
            }
        }

        #[inline(never)]
        fn $never<S: Scalar>($a: S) -> S {
            $body
        }
    };
}

outlined_binary!(
    /// `a + b`.
    add, add_never, +);
outlined_binary!(
    /// `a - b`.
    sub, sub_never, -);
outlined_binary!(
    /// `a * b`.
    mul, mul_never, *);
outlined_binary!(
    /// `a / b`.
    div, div_never, /);
outlined_unary!(
    /// `-a`.
    neg, neg_never, |a| -a);
outlined_unary!(
    /// [`Scalar::sqr`].
    sqr, sqr_never, |a| a.sqr());
outlined_unary!(
    /// [`Scalar::sqrt`].
    sqrt, sqrt_never, |a| a.sqrt());
outlined_unary!(
    /// [`Scalar::sin`].
    sin, sin_never, |a| a.sin());
outlined_unary!(
    /// [`Scalar::cos`].
    cos, cos_never, |a| a.cos());
outlined_unary!(
    /// [`Scalar::tan`].
    tan, tan_never, |a| a.tan());

/// [`Scalar::powi`].
#[inline(always)]
pub fn powi<S: Scalar>(a: S, n: i32) -> S {
    if S::OUT_OF_LINE {
        powi_never(a, n)
    } else {
        a.powi(n)
    }
}

#[inline(never)]
fn powi_never<S: Scalar>(a: S, n: i32) -> S {
    a.powi(n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Affine, Interval};

    fn same<S: Scalar + PartialEq>(a: S, b: S) {
        let checks: [(S, S); 11] = [
            (add(a, b), a + b),
            (sub(a, b), a - b),
            (mul(a, b), a * b),
            (div(a, b), a / b),
            (neg(a), -a),
            (sqr(a), a.sqr()),
            (sqrt(b), b.sqrt()),
            (sin(a), a.sin()),
            (cos(a), a.cos()),
            (tan(a), a.tan()),
            (powi(a, 3), a.powi(3)),
        ];
        for (k, (outlined, inline)) in checks.iter().enumerate() {
            assert_eq!(outlined, inline, "operation {k}");
        }
    }

    #[test]
    fn out_of_line_operations_equal_the_operators() {
        const { assert!(!f64::OUT_OF_LINE && Interval::OUT_OF_LINE && Affine::<2>::OUT_OF_LINE) };
        same(0.3_f64, 1.7);
        same(-2.5_f64, 0.25);
        same(Interval::new(-0.4, 0.3), Interval::new(1.5, 2.0));
        same(Interval::new(0.1, 0.2), Interval::new(0.5, 0.75));
    }
}
