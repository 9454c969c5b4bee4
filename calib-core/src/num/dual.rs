//! A forward-mode dual number: value and gradient with respect to `N` seeds, in floating point.
//!
//! Used to cross-check the Jacobians that `#[interval_model]` generates at compile time against an
//! independent evaluation of the same generic residual.

use crate::Jet;

/// `value + sum_i grad[i] * eps_i` with `eps_i * eps_j = 0`: a [`Jet`] over `f64`
/// (`Dual::<N>::variable(x, i)`, `Dual::<N>::constant(x)`, fields `value` and `grad`).
pub type Dual<const N: usize> = Jet<f64, N>;
