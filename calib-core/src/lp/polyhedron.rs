//! The LP feasible set `{y : G y <= g, lo <= y <= hi}`, stored densely in reusable buffers.

use std::sync::atomic::{AtomicU64, Ordering};

/// Source of [`Polyhedron::generation`] values (0 is never handed out).
static NEXT_GENERATION: AtomicU64 = AtomicU64::new(1);

/// `{y in R^n : G y <= g, lo <= y <= hi}` with finite `lo <= hi`.
///
/// Rows are scaled by exact powers of two on insertion (the set is unchanged) so that every row's
/// largest coefficient lies in `[0.5, 1)`; rows with non-finite data are dropped (a weaker but valid
/// relaxation). Buffers keep their capacity across [`Polyhedron::reset`], so rebuilding allocates
/// nothing after warm-up.
#[derive(Clone, Debug, Default)]
pub struct Polyhedron {
    n: usize,
    g_rows: Vec<f64>,
    g_rhs: Vec<f64>,
    lo: Vec<f64>,
    hi: Vec<f64>,
    generation: u64,
    /// Per variable: `Some(m)` when it is frozen with `|y_j| <= m` (see [`Polyhedron::freeze`]).
    frozen: Vec<Option<f64>>,
    /// A reusable copy of the row being pushed, when columns are frozen.
    scratch: Vec<f64>,
    /// Per row, its tag ([`Polyhedron::tag`]); and the tag the next pushed row gets.
    tags: Vec<u64>,
    next_tag: u64,
}

impl Polyhedron {
    /// Starts a new polyhedron over the box `[lo, hi]` with no rows.
    ///
    /// # Panics
    /// If the slices differ in length or a bound is not finite or `lo > hi`.
    pub fn reset(&mut self, lo: &[f64], hi: &[f64]) {
        assert_eq!(lo.len(), hi.len());
        assert!(lo
            .iter()
            .zip(hi)
            .all(|(l, h)| l.is_finite() && h.is_finite() && l <= h));
        self.n = lo.len();
        self.lo.clear();
        self.lo.extend_from_slice(lo);
        self.hi.clear();
        self.hi.extend_from_slice(hi);
        self.g_rows.clear();
        self.g_rhs.clear();
        self.tags.clear();
        self.next_tag = 0;
        self.generation = NEXT_GENERATION.fetch_add(1, Ordering::Relaxed);
        self.frozen.clear();
        self.frozen.resize(self.n, None);
    }

    /// Freezes variable `j`, known to satisfy `|y_j| <= magnitude`: rows pushed from now on get a
    /// zero coefficient for it and a right-hand side raised by `|a_j| · magnitude` (rounded up),
    /// which every point of the polyhedron still satisfies. For variables whose interval is a
    /// rounding-level sliver (a parameter fixed at a value converted to other units): as an LP
    /// column they only make the basis singular.
    pub fn freeze(&mut self, j: usize, magnitude: f64) {
        self.frozen[j] = Some(magnitude);
    }

    /// Whether variable `j` is frozen.
    pub fn is_frozen(&self, j: usize) -> bool {
        self.frozen.get(j).is_some_and(|f| f.is_some())
    }

    /// Starts a group of rows (a configuration's rows, say): the rows pushed from now on are
    /// tagged `(group, 0)`, `(group, 1)`, … in the order they are pushed (dropped rows use up
    /// their tag too). Without groups, the tags are `(0, 0)`, `(0, 1)`, …
    ///
    /// Tags let an LP engine recognise "the same" row in the next polyhedron of a sequence
    /// (contraction steps, the boxes of a hull) when a group's row count changes, to warm-start
    /// from an earlier optimal basis. Groups must be started in increasing order.
    pub fn begin_group(&mut self, group: u32) {
        self.next_tag = u64::from(group) << 32;
    }

    /// The tag of row `i` (see [`Polyhedron::begin_group`]).
    pub fn tag(&self, i: usize) -> u64 {
        self.tags[i]
    }

    /// The row with tag `tag`, if there is one (the tags increase with the row index).
    pub fn find_tag(&self, tag: u64) -> Option<usize> {
        self.tags.binary_search(&tag).ok()
    }

    /// Adds the row `a·y <= b` (dropped if any number is not finite or `a = 0` with `b >= 0`).
    /// Returns whether the row was kept.
    pub fn push_row(&mut self, a: &[f64], b: f64) -> bool {
        debug_assert_eq!(a.len(), self.n);
        let tag = self.next_tag;
        self.next_tag += 1;
        let kept = self.push_untagged(a, b);
        if kept {
            self.tags.push(tag);
        }
        kept
    }

    fn push_untagged(&mut self, a: &[f64], b: f64) -> bool {
        if self.frozen.iter().any(Option::is_some) {
            let mut b = b;
            let mut row = core::mem::take(&mut self.scratch);
            row.clear();
            row.extend_from_slice(a);
            for (j, f) in self.frozen.iter().enumerate() {
                if let Some(mag) = f {
                    b = crate::num::interval::round::add_up(
                        b,
                        crate::num::interval::round::mul_up(row[j].abs(), *mag),
                    );
                    row[j] = 0.0;
                }
            }
            let kept = self.push_scaled(&row, b);
            self.scratch = row;
            return kept;
        }
        self.push_scaled(a, b)
    }

    fn push_scaled(&mut self, a: &[f64], b: f64) -> bool {
        if !b.is_finite() || a.iter().any(|v| !v.is_finite()) {
            return false;
        }
        let max = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if max == 0.0 {
            // 0 <= b: always true, carries no information. (0 <= b with b < 0 would be an
            // infeasible row; keep it so that the LP sees it.)
            if b >= 0.0 {
                return false;
            }
        }
        let scale = if max == 0.0 {
            1.0
        } else {
            power_of_two_scale(max)
        };
        self.g_rows.extend(a.iter().map(|v| v * scale));
        self.g_rhs.push(b * scale);
        true
    }

    /// Tightens the box of variable `j` (the caller guarantees `lo <= hi`).
    pub fn set_bounds(&mut self, j: usize, lo: f64, hi: f64) {
        debug_assert!(lo <= hi);
        self.lo[j] = lo;
        self.hi[j] = hi;
    }

    /// Number of variables.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Number of rows of `G`.
    pub fn rows(&self) -> usize {
        self.g_rhs.len()
    }

    /// Row `i` of `G`.
    pub fn row(&self, i: usize) -> &[f64] {
        &self.g_rows[i * self.n..(i + 1) * self.n]
    }

    /// `g[i]`.
    pub fn rhs(&self, i: usize) -> f64 {
        self.g_rhs[i]
    }

    /// Lower bounds of the box.
    pub fn lo(&self) -> &[f64] {
        &self.lo
    }

    /// Upper bounds of the box.
    pub fn hi(&self) -> &[f64] {
        &self.hi
    }

    /// Unique per build of the rows, across all polyhedra of the process (lets engines cache a
    /// factorisation or a basis per polyhedron without confusing two of them).
    pub fn generation(&self) -> u64 {
        self.generation
    }
}

/// `2^-e` such that `max * 2^-e` lies in `[0.5, 1)`: an exact scaling, computed from the exponent
/// bits (no libm call). Subnormal or huge `max` is left unscaled.
pub(super) fn power_of_two_scale(max: f64) -> f64 {
    let biased = ((max.to_bits() >> 52) & 0x7ff) as i64;
    // max = 1.f * 2^(biased - 1023), so e = biased - 1022 puts it in [0.5, 1).
    let e = biased - 1022;
    if biased == 0 || !(-1000..=1000).contains(&e) {
        return 1.0;
    }
    f64::from_bits(((1023 - e) as u64) << 52)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_scaled_exactly_and_bad_rows_dropped() {
        let mut p = Polyhedron::default();
        p.reset(&[0.0, 0.0], &[1.0, 1.0]);
        assert!(p.push_row(&[3.0, -6.0], 12.0));
        assert_eq!(p.row(0), &[0.375, -0.75]);
        assert_eq!(p.rhs(0), 1.5);
        assert_eq!(power_of_two_scale(0.5), 1.0);
        assert_eq!(power_of_two_scale(1.0), 0.5);
        assert_eq!(power_of_two_scale(1000.0), 1.0 / 1024.0);
        assert_eq!(power_of_two_scale(0.001), 512.0);
        assert!(!p.push_row(&[f64::NAN, 1.0], 0.0));
        assert!(!p.push_row(&[0.0, 0.0], 1.0));
        assert!(p.push_row(&[0.0, 0.0], -1.0));
        assert_eq!(p.rows(), 2);
        assert_eq!((p.tag(0), p.tag(1)), (0, 3));
        p.begin_group(2);
        assert!(!p.push_row(&[0.0, 0.0], 1.0));
        assert!(p.push_row(&[1.0, 0.0], 1.0));
        assert_eq!(p.find_tag((2 << 32) | 1), Some(2));
        assert_eq!(p.find_tag(2 << 32), None);
        assert_eq!(p.find_tag(3), Some(1));
    }
}
