//! Set operations: hull and intersection.

use super::Interval;

impl Interval {
    /// The smallest interval containing both (the convex hull of the union).
    #[inline]
    pub fn hull(self, other: Interval) -> Interval {
        if self.is_empty() {
            return other;
        }
        if other.is_empty() {
            return self;
        }
        Interval::from_bounds_unchecked(self.lo.min(other.lo), self.hi.max(other.hi))
    }

    /// The intersection (empty when the intervals are disjoint).
    #[inline]
    pub fn intersection(self, other: Interval) -> Interval {
        let lo = self.lo.max(other.lo);
        let hi = self.hi.min(other.hi);
        if lo > hi {
            Interval::EMPTY
        } else {
            Interval::from_bounds_unchecked(lo, hi)
        }
    }
}
