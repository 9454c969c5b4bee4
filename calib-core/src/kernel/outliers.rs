//! Outliers: conflict sets of inconsistent data, and certification with up to `q` outliers
//! tolerated.
//!
//! **q-relaxed solution set.** With `p` measurements and `q` tolerated outliers, a parameter vector
//! is a solution when it fits at least `p - q` measurements. That set is exactly the union, over
//! the *drop-sets* `D ⊆ {0..p}` with `|D| = q`, of the solution sets of the measurements not in `D`:
//! so `certify`, `hull` and `sweep` certify each of those subsets with the ordinary (q = 0) method
//! — whose LPs only ever use measurements that every solution of that subset fits — and take the
//! hull of the results. A subset proved empty is a proof for its part of the union; the union is
//! empty only when every subset is.
//!
//! **Certified outliers.** Measurement `k` is a certified outlier (under the assumption of at most
//! `q` bad measurements) when every subset that keeps `k` was proved empty: every solution then
//! misfits `k`.
//!
//! **Conflict sets.** When a box is proved empty, a *deletion filter* finds a minimal set of
//! measurements that still cannot be fitted together: drop each measurement in turn and keep the
//! drop when the rest is still proved empty; repeat until no single removal keeps the proof.
//! Measurements that the proof used are tried last, so they tend to stay in the set.
//!
//! **Spread misfits.** The deletion filter costs one certification per measurement, and where the
//! misfit is spread over the data its answer names many of them (22 of the real UR10's 60
//! configurations at 0.98 times their smallest consistent error bound, in many times the verdict's
//! time; `benches/README.md`): no list of readings to re-measure, but a model that does not
//! describe the data to these bounds. What tells the two apart at no cost is the *support* of the
//! final certificate of emptiness, the measurements it weighs ([`crate::Certification::support`]).
//! A certificate in `n` free parameters combines at most `n + 1` rows (a vertex of the LP's dual;
//! the second-order certificate's weights, once the solver's noise is dropped, stay below that), so
//! it weighs at most `min(p, n + 1)` of `p` measurements. When it weighs more than half of that
//! ([`is_spread`]), the misfit is called spread and the conflict set is not searched.
//!
//! Measured supports. Kept (a few bad readings): a gross error, 1 of 10 configurations (simulated
//! arms) or 2 of 21 (Gough leg, 7 free parameters: spread above 4); a subtle one on a leg, 4 of 21;
//! one configuration of the real UR10 (27 free parameters: spread above 14) moved 1.2 or 1.5 mm at
//! bounds 0.39–0.42 mm, 6 and 10 of 60. Spread: the real UR10's series at 0.52–0.98 times its
//! smallest consistent bound, 17–18 of 60; Gough legs with every reading off by up to three times
//! its bound, 5–7 of 21. The rule is a heuristic with a known miss: a bad reading just beyond
//! consistency is weighed like a spread misfit (one UR10 configuration moved 0.9 mm at 1.01 times
//! the smallest consistent bound: 19 of 60, where the search named it and one other), and a misfit
//! far beyond it can be weighed like a few readings (the series at 0.13 times the bound: 12 of 60,
//! 10 configurations named by the search). `--max-outliers` is the certified way to find bad
//! readings either way. A first-order (Farkas) certificate can also weigh many measurements around
//! one gross error (a simulated arm with one configuration moved 50 times its bound: 19 of 50), so
//! a spread first-order proof is checked once more: leaving out each weighed measurement in turn;
//! if the rest is then proved consistent (a witness in the box one contraction leaves) for one or
//! two of them only, the conflict set is searched after all ([`crate::certify`]); where a dozen
//! would each do, no reading stands out.

/// Whether a proof of emptiness whose final certificate weighs `support` of `p` measurements, with
/// `free` parameters not fixed in the box, points at a misfit spread over the data rather than at
/// a few bad measurements: when the certificate weighs more than half of the measurements it
/// could weigh at most, `min(p, free + 1)` (see the module documentation).
pub fn is_spread(support: usize, p: usize, free: usize) -> bool {
    2 * support > p.min(free + 1)
}

/// Subsets of `0..p` with `q` elements in lexicographic order, if there are at most `limit`.
pub(crate) fn drop_sets(p: usize, q: usize, limit: usize) -> Option<Vec<Vec<usize>>> {
    if q > p || binomial(p, q) > limit as f64 {
        return None;
    }
    let mut out = Vec::new();
    let mut current: Vec<usize> = (0..q).collect();
    loop {
        out.push(current.clone());
        // The next combination: bump the rightmost index that can still move.
        let Some(i) = (0..q).rev().find(|&i| current[i] < p - q + i) else {
            return Some(out);
        };
        current[i] += 1;
        for k in i + 1..q {
            current[k] = current[k - 1] + 1;
        }
    }
}

/// `C(p, q)` as a float (no overflow for large arguments).
pub(crate) fn binomial(p: usize, q: usize) -> f64 {
    (0..q.min(p)).fold(1.0, |acc, i| acc * (p - i) as f64 / (i + 1) as f64)
}

/// The measurements of `all` whose indices are not in the sorted `drop`.
pub(crate) fn keep_all_but<T: Copy>(all: &[T], drop: &[usize]) -> Vec<T> {
    all.iter()
        .enumerate()
        .filter(|(k, _)| drop.binary_search(k).is_err())
        .map(|(_, m)| *m)
        .collect()
}

/// The measurements (sorted indices) that every possibly non-empty subset drops: `alive[s]` says
/// whether the subset without `drops[s]` may hold a solution. Empty when no subset is alive.
pub(crate) fn certified_outliers(p: usize, drops: &[Vec<usize>], alive: &[bool]) -> Vec<usize> {
    if !alive.iter().any(|a| *a) {
        return Vec::new();
    }
    (0..p)
        .filter(|k| {
            drops
                .iter()
                .zip(alive)
                .all(|(d, a)| !a || d.binary_search(k).is_ok())
        })
        .collect()
}

/// A minimal conflict set by the deletion filter (see the module documentation): `proves_empty`
/// decides whether a set of measurement indices (sorted) is proved empty; `used` are the
/// measurements the original proof used (tried last). Assumes `proves_empty(0..p)` holds.
pub(crate) fn conflict_set(
    p: usize,
    used: &[usize],
    proves_empty: impl FnMut(&[usize]) -> bool,
) -> Vec<usize> {
    conflict_subset((0..p).collect(), used, proves_empty)
}

/// [`conflict_set`] from the proved set `start` (sorted) instead of every measurement.
pub(crate) fn conflict_subset(
    start: Vec<usize>,
    used: &[usize],
    mut proves_empty: impl FnMut(&[usize]) -> bool,
) -> Vec<usize> {
    let mut set = start;
    let order: Vec<usize> = set
        .iter()
        .copied()
        .filter(|k| !used.contains(k))
        .chain(used.iter().copied().filter(|k| set.contains(k)))
        .collect();
    // Passes until no single removal keeps the proof (a prover need not be monotone).
    loop {
        let mut changed = false;
        for &k in &order {
            let Ok(pos) = set.binary_search(&k) else {
                continue;
            };
            let mut rest = set.clone();
            rest.remove(pos);
            if !rest.is_empty() && proves_empty(&rest) {
                set = rest;
                changed = true;
            }
        }
        if !changed {
            return set;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn drop_sets_enumerate_every_combination_once() {
        let d = drop_sets(5, 2, 100).unwrap();
        assert_eq!(d.len(), 10);
        assert_eq!(d[0], vec![0, 1]);
        assert_eq!(d[9], vec![3, 4]);
        let mut sorted = d.clone();
        sorted.dedup();
        assert_eq!(sorted.len(), 10);
        assert_eq!(drop_sets(4, 0, 10).unwrap(), vec![Vec::<usize>::new()]);
        assert!(
            drop_sets(40, 3, 1000).is_none(),
            "9880 subsets exceed the limit"
        );
        assert!(drop_sets(3, 4, 1000).is_none());
    }

    #[test]
    fn outliers_are_the_measurements_every_live_subset_drops() {
        let drops = drop_sets(4, 1, 10).unwrap();
        // Only the subset without measurement 2 survives: 2 is an outlier.
        assert_eq!(
            certified_outliers(4, &drops, &[false, false, true, false]),
            vec![2]
        );
        // Two survivors: no single measurement is dropped by both.
        assert!(certified_outliers(4, &drops, &[true, false, true, false]).is_empty());
        assert!(certified_outliers(4, &drops, &[false; 4]).is_empty());
    }

    #[test]
    fn a_support_over_half_of_what_a_certificate_can_weigh_is_spread() {
        // The real UR10: 60 configurations, 27 free parameters, at most 28 weighed.
        assert!(is_spread(17, 60, 27));
        assert!(!is_spread(14, 60, 27) && !is_spread(1, 60, 27));
        // A Gough leg: 21 configurations, 7 free parameters, at most 8 weighed.
        assert!(is_spread(5, 21, 7) && !is_spread(4, 21, 7));
        // Fewer configurations than parameters: half of the configurations.
        assert!(is_spread(7, 12, 18) && !is_spread(6, 12, 18));
    }

    #[test]
    fn the_deletion_filter_finds_a_minimal_conflict() {
        // "Empty" exactly when the set holds both 3 and 5, or all of 0, 1, 2.
        let empty = |s: &[usize]| (s.contains(&3) && s.contains(&5)) || s.starts_with(&[0, 1, 2]);
        let c = conflict_set(8, &[5], empty);
        assert!(empty(&c));
        for k in 0..c.len() {
            let mut rest = c.clone();
            rest.remove(k);
            assert!(!empty(&rest), "{c:?} is not minimal");
        }
        assert_eq!(c, vec![3, 5]);
    }
}
