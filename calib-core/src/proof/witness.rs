//! Witnesses: a parameter vector of a box proved consistent with every measurement, searched
//! among candidates — the least-squares point, its Chebyshev (minimax) refinement, the centre —
//! each checked by [`crate::is_consistent_point`].

use crate::proof::chebyshev::minimax_point;
use crate::proof::consistency::{is_consistent_point, least_squares_point};
use crate::{Interval, VectorModel};

/// A certified consistent point of the box, if one of the candidates passes: the least-squares
/// point, its Chebyshev refinement, the centre, and the given extra candidates.
pub(crate) fn find_witness<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[Interval; NX],
    measurements: &[[Interval; NM]],
    extra: &[[f64; NX]],
) -> Option<[f64; NX]>
where
    M: VectorModel<NX, NM, NR>,
{
    let lsq = least_squares_point(model, x, measurements);
    let centre = x.map(|v| v.mid());
    let chebyshev = minimax_point(model, x, measurements, &[true; NM], lsq, true);
    [lsq, chebyshev, centre]
        .iter()
        .chain(extra)
        .filter(|p| (0..NX).all(|j| x[j].contains(p[j])))
        .find(|p| is_consistent_point(model, p, measurements))
        .copied()
}
