//! Number types: what a residual is evaluated in. Rigorous intervals ([`crate::Interval`]),
//! affine forms ([`crate::Affine`]), second-order Taylor models ([`crate::Quadratic`]),
//! forward-mode derivatives ([`crate::Jet`], [`crate::Dual`], and [`crate::Jet2`] with a symmetric
//! Hessian), the [`crate::Scalar`] trait they all implement, and the small dense linear algebra
//! the kernel runs on floats.

pub(crate) mod affine;
pub(crate) mod dual;
pub(crate) mod hessian_jet;
pub(crate) mod interval;
pub(crate) mod jet;
pub(crate) mod linalg;
pub(crate) mod quadratic;
pub(crate) mod scalar;
