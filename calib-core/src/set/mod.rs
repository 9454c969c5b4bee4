//! The certified set and the questions asked of it: its pieces and points
//! ([`crate::CertifiedSet`]), maxima over it and over boxes ([`crate::maximize_over_set`],
//! [`crate::maximize`]), a parallelotope around it, and the calibrated point chosen in it (towards
//! the Chebyshev centre, or the least-squares fit within the set).

pub(crate) mod calibrated_point;
pub(crate) mod certified_set;
pub(crate) mod curvature_rows;
pub(crate) mod least_squares;
pub(crate) mod maximum;
pub(crate) mod parallelotope;
