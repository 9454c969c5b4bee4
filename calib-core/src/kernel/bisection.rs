//! The paper's bisection sweep (Section V) and a general branch-and-prune paver.
//!
//! **Sweep.** Split the current box in every dimension at `fraction` of its width from the lower
//! bound (`2^n` sub-boxes, 128 for the 7 Gough-leg parameters), contract each, drop those proved
//! empty, keep the survivors, and continue from the largest survivor; `steps` steps from the lower
//! bounds, then `steps` from the upper bounds. The union of all kept boxes contains every solution of
//! the initial box; its hull is the paper's `x2`, and the total volume after each step is the
//! paper's Fig. 5.
//!
//! **Paver.** Contract; drop empty boxes; keep boxes whose widths (relative to the initial box) are
//! all below the tolerance; otherwise bisect the widest relative dimension — until the queue is
//! empty or the box budget is spent (then the remaining boxes are kept unsplit). Each kept box is
//! also tested for lying entirely inside the solution set ([`crate::is_certified_consistent`]),
//! which gives an inner volume next to the outer one.

use crate::kernel::certify::MAX_SUBSETS;
use crate::kernel::contract::{contract, Workspace};
use crate::kernel::outliers::{drop_sets, keep_all_but};
use crate::proof::consistency::is_certified_consistent;
use crate::{Interval, Settings, VectorModel};
use rayon::prelude::*;

/// The volume `Π wid(x_j)` (0 for an empty box).
pub(crate) fn volume<const NX: usize>(x: &[Interval; NX]) -> f64 {
    if x.iter().any(|v| v.is_empty()) {
        return 0.0;
    }
    x.iter().map(|v| v.sup() - v.inf()).product()
}

/// The hull of a list of boxes (`None` for an empty list).
pub(crate) fn hull_of<const NX: usize>(boxes: &[[Interval; NX]]) -> Option<[Interval; NX]> {
    let (first, rest) = boxes.split_first()?;
    Some(
        rest.iter()
            .fold(*first, |h, b| core::array::from_fn(|j| h[j].hull(b[j]))),
    )
}

/// The result of [`sweep`].
#[derive(Clone, Debug, PartialEq)]
pub struct SweepResult<const NX: usize> {
    /// The surviving boxes: their union contains every solution of the initial box.
    pub boxes: Vec<[Interval; NX]>,
    /// The hull of the surviving boxes (the paper's `x2`); `None` when every box was proved empty.
    pub hull: Option<[Interval; NX]>,
    /// The total volume of the kept boxes: first of the contracted initial box, then after each
    /// step (the paper's Fig. 5).
    pub volumes: Vec<f64>,
    /// How many boxes were contracted in total.
    pub boxes_contracted: usize,
}

/// Splits `b` at the midpoint of its widest side relative to `reference` (`None` when no side
/// can be split: the midpoint equals a bound). Used by [`crate::hull`] (relative to the outer
/// box), [`crate::maximize`] (relative to the domain), and by robot crates' own searches.
pub fn split_widest<const NX: usize>(
    b: &[Interval; NX],
    reference: &[Interval; NX],
) -> Option<([Interval; NX], [Interval; NX])> {
    let rel = |j: usize| b[j].wid() / reference[j].wid().max(f64::MIN_POSITIVE);
    let j = (0..NX).max_by(|&a, &c| rel(a).total_cmp(&rel(c)))?;
    let (lo, hi, m) = (b[j].inf(), b[j].sup(), b[j].mid());
    if !(lo < m && m < hi) {
        return None;
    }
    let (mut l, mut r) = (*b, *b);
    l[j] = Interval::new(lo, m);
    r[j] = Interval::new(m, hi);
    Some((l, r))
}

/// The `2^n` sub-boxes of `x` split at `fraction` of each width from the lower (or upper) bound.
fn split_all<const NX: usize>(
    x: &[Interval; NX],
    fraction: f64,
    from_upper: bool,
) -> Vec<[Interval; NX]> {
    let cut: [f64; NX] = core::array::from_fn(|j| {
        let (lo, hi) = (x[j].inf(), x[j].sup());
        let c = if from_upper {
            hi - fraction * (hi - lo)
        } else {
            lo + fraction * (hi - lo)
        };
        c.clamp(lo, hi)
    });
    (0..1usize << NX)
        .map(|mask| {
            core::array::from_fn(|j| {
                if mask >> j & 1 == 0 {
                    Interval::new(x[j].inf(), cut[j])
                } else {
                    Interval::new(cut[j], x[j].sup())
                }
            })
        })
        .collect()
}

/// Contracts every box (in parallel when asked) and keeps the non-empty results.
fn contract_all<
    M: VectorModel<NX, NM, NR> + Sync,
    const NX: usize,
    const NM: usize,
    const NR: usize,
>(
    model: &M,
    boxes: &[[Interval; NX]],
    measurements: &[[Interval; NM]],
    settings: &Settings,
) -> Vec<[Interval; NX]> {
    let one = |ws: &mut Workspace<NX>, b: &[Interval; NX]| {
        contract(model, b, measurements, settings, ws).result.ok()
    };
    if settings.parallel {
        boxes
            .par_iter()
            .map_init(|| Workspace::new(settings), one)
            .flatten()
            .collect()
    } else {
        let mut ws = Workspace::new(settings);
        boxes.iter().filter_map(|b| one(&mut ws, b)).collect()
    }
}

/// The paper's sweep (see the module documentation), starting by contracting `x0`.
///
/// # Panics
/// If `NX > 16` (the sweep contracts `2^NX` boxes per step).
pub fn sweep<
    M: VectorModel<NX, NM, NR> + Sync,
    const NX: usize,
    const NM: usize,
    const NR: usize,
>(
    model: &M,
    x0: &[Interval; NX],
    measurements: &[[Interval; NM]],
    settings: &Settings,
) -> SweepResult<NX> {
    assert!(
        NX <= 16,
        "the sweep splits every dimension: 2^{NX} boxes per step is too many"
    );
    if settings.max_outliers > 0 {
        return sweep_relaxed(model, x0, measurements, settings);
    }
    let mut ws = Workspace::new(settings);
    let mut contracted = 1;
    let Ok(x1) = contract(model, x0, measurements, settings, &mut ws).result else {
        return SweepResult {
            boxes: vec![],
            hull: None,
            volumes: vec![0.0],
            boxes_contracted: 1,
        };
    };
    let mut volumes = vec![volume(&x1)];
    if !x1.iter().all(|v| v.is_bounded()) {
        // An unbounded box cannot be split at a fraction of its width: keep it whole.
        return SweepResult {
            boxes: vec![x1],
            hull: Some(x1),
            volumes,
            boxes_contracted: contracted,
        };
    }
    let mut kept: Vec<[Interval; NX]> = Vec::new();
    let mut current = x1;
    for step in 0..2 * settings.sweep_steps {
        let pieces = split_all(
            &current,
            settings.sweep_fraction,
            step >= settings.sweep_steps,
        );
        contracted += pieces.len();
        let mut survivors = contract_all(model, &pieces, measurements, settings);
        if survivors.is_empty() {
            // The current box held no solution after all.
            volumes.push(kept.iter().map(volume).sum());
            let hull = hull_of(&kept);
            return SweepResult {
                boxes: kept,
                hull,
                volumes,
                boxes_contracted: contracted,
            };
        }
        let largest = (0..survivors.len())
            .max_by(|&a, &b| volume(&survivors[a]).total_cmp(&volume(&survivors[b])))
            .expect("non-empty");
        current = survivors.swap_remove(largest);
        kept.extend(survivors);
        volumes.push(kept.iter().map(volume).sum::<f64>() + volume(&current));
    }
    kept.push(current);
    let hull = hull_of(&kept);
    SweepResult {
        boxes: kept,
        hull,
        volumes,
        boxes_contracted: contracted,
    }
}

/// The sweep with `q` outliers tolerated: the union of the sweeps of every subset of `p - q`
/// measurements (see [`crate::outliers`]); volumes are added step by step (an outer volume of the
/// union). Beyond the subset limit, `x0` is kept whole.
fn sweep_relaxed<
    M: VectorModel<NX, NM, NR> + Sync,
    const NX: usize,
    const NM: usize,
    const NR: usize,
>(
    model: &M,
    x0: &[Interval; NX],
    measurements: &[[Interval; NM]],
    settings: &Settings,
) -> SweepResult<NX> {
    let Some(drops) = drop_sets(measurements.len(), settings.max_outliers, MAX_SUBSETS) else {
        return SweepResult {
            boxes: vec![*x0],
            hull: Some(*x0),
            volumes: vec![volume(x0)],
            boxes_contracted: 0,
        };
    };
    let plain = settings.clone().with_max_outliers(0);
    let mut out = SweepResult {
        boxes: Vec::new(),
        hull: None,
        volumes: Vec::new(),
        boxes_contracted: 0,
    };
    let sweeps: Vec<SweepResult<NX>> = drops
        .iter()
        .map(|d| sweep(model, x0, &keep_all_but(measurements, d), &plain))
        .collect();
    // A sweep that ended early keeps its last volume for the remaining steps.
    let steps = sweeps.iter().map(|s| s.volumes.len()).max().unwrap_or(0);
    out.volumes = (0..steps)
        .map(|i| {
            sweeps
                .iter()
                .map(|s| {
                    s.volumes
                        .get(i)
                        .or(s.volumes.last())
                        .copied()
                        .unwrap_or(0.0)
                })
                .sum()
        })
        .collect();
    for s in sweeps {
        out.boxes.extend(s.boxes);
        out.boxes_contracted += s.boxes_contracted;
    }
    out.hull = hull_of(&out.boxes);
    out
}

/// The result of [`pave`].
#[derive(Clone, Debug, PartialEq)]
pub struct Paving<const NX: usize> {
    /// Boxes whose union contains every solution of the initial box.
    pub boxes: Vec<[Interval; NX]>,
    /// Which of `boxes` are proved to lie entirely inside the solution set.
    pub inside: Vec<bool>,
    /// The hull of `boxes` (`None` when every box was proved empty).
    pub hull: Option<[Interval; NX]>,
    /// Total volume of `boxes` (an outer volume of the solution set).
    pub outer_volume: f64,
    /// Total volume of the boxes proved inside (an inner volume of the solution set).
    pub inner_volume: f64,
    /// How many boxes were contracted.
    pub boxes_contracted: usize,
    /// Whether the box budget ran out before every box reached the tolerance.
    pub budget_exhausted: bool,
}

/// Branch-and-prune paving of the solution set (see the module documentation): stops splitting a
/// box when every width is below `tolerance` times the corresponding width of `x0`, and contracts at
/// most `max_boxes` boxes.
pub fn pave<
    M: VectorModel<NX, NM, NR> + Sync,
    const NX: usize,
    const NM: usize,
    const NR: usize,
>(
    model: &M,
    x0: &[Interval; NX],
    measurements: &[[Interval; NM]],
    settings: &Settings,
    tolerance: f64,
    max_boxes: usize,
) -> Paving<NX> {
    let scale = x0.map(|v| v.wid().max(f64::MIN_POSITIVE));
    let relative = |b: &[Interval; NX], j: usize| b[j].wid() / scale[j];
    let mut queue = vec![*x0];
    let mut done: Vec<[Interval; NX]> = Vec::new();
    let mut contracted = 0;
    let mut budget_exhausted = false;
    while !queue.is_empty() {
        if contracted + queue.len() > max_boxes.max(1) {
            budget_exhausted = true;
            done.append(&mut queue);
            break;
        }
        contracted += queue.len();
        let survivors = contract_all(model, &queue, measurements, settings);
        queue.clear();
        for b in survivors {
            let widest = (0..NX)
                .max_by(|&a, &c| relative(&b, a).total_cmp(&relative(&b, c)))
                .expect("NX > 0");
            if relative(&b, widest) <= tolerance {
                done.push(b);
            } else {
                let m = b[widest].mid();
                let (mut left, mut right) = (b, b);
                left[widest] = Interval::new(b[widest].inf(), m);
                right[widest] = Interval::new(m, b[widest].sup());
                queue.push(left);
                queue.push(right);
            }
        }
    }
    let inside: Vec<bool> = done
        .iter()
        .map(|b| is_certified_consistent(model, b, measurements))
        .collect();
    // Folded from +0.0: `sum` of no terms is -0.0, printed as "-0".
    let outer_volume = done.iter().map(volume).fold(0.0, |s, v| s + v);
    let inner_volume = done
        .iter()
        .zip(&inside)
        .filter(|(_, i)| **i)
        .map(|(b, _)| volume(b))
        .fold(0.0, |s, v| s + v);
    let hull = hull_of(&done);
    Paving {
        boxes: done,
        inside,
        hull,
        outer_volume,
        inner_volume,
        boxes_contracted: contracted,
        budget_exhausted,
    }
}
