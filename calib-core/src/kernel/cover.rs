//! [`Cover`]: what [`crate::certify`], [`crate::hull`] and the sweep end with — boxes whose union
//! contains every solution, each with the measurement subset it was certified against. The
//! certified set ([`crate::CertifiedSet`]) is built from a cover and gives one back.

use crate::Interval;

/// Boxes whose union contains every solution of a certification, with the measurement subset
/// each belongs to (with outliers tolerated, each subset drops some measurements; without, there
/// is one subset, dropping none).
#[derive(Clone, Debug, PartialEq)]
pub struct Cover<const NX: usize> {
    /// The boxes.
    pub boxes: Vec<[Interval; NX]>,
    /// Per box, the index of its subset in `dropped`.
    pub subsets: Vec<usize>,
    /// Per subset, the measurements it drops (0-based, sorted).
    pub dropped: Vec<Vec<usize>>,
}

impl<const NX: usize> Cover<NX> {
    /// The cover of nothing (a certification that proved its box empty).
    pub fn empty() -> Self {
        Cover {
            boxes: Vec::new(),
            subsets: Vec::new(),
            dropped: vec![Vec::new()],
        }
    }

    /// One box, all measurements kept.
    pub fn single(b: [Interval; NX]) -> Self {
        Cover {
            boxes: vec![b],
            subsets: vec![0],
            dropped: vec![Vec::new()],
        }
    }

    /// The hull of the boxes (`None` when there is none).
    pub fn hull(&self) -> Option<[Interval; NX]> {
        hull_of(self.boxes.iter())
    }
}

/// The hull of some boxes.
pub(crate) fn hull_of<'a, const NX: usize>(
    mut boxes: impl Iterator<Item = &'a [Interval; NX]>,
) -> Option<[Interval; NX]> {
    let first = *boxes.next()?;
    Some(boxes.fold(first, |h, b| core::array::from_fn(|j| h[j].hull(b[j]))))
}
