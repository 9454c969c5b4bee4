//! The certified kernel: the contraction of a box to a fixed point ([`crate::contract`]), the
//! verdict with its evidence ([`crate::certify`]), the tight hull ([`crate::hull`]), the paper's
//! sweep and the paver ([`crate::sweep`], [`crate::pave`]), outliers, the covers they produce
//! ([`crate::Cover`]), the local searches for inner bounds, and their [`crate::Settings`].

pub(crate) mod bisection;
pub(crate) mod certify;
pub(crate) mod contract;
pub(crate) mod cover;
pub(crate) mod farthest_point;
pub(crate) mod hull;
pub(crate) mod inner_targets;
pub(crate) mod outliers;
pub(crate) mod settings;
