//! [`certify`]: contraction to a fixed point plus the evidence for the verdict.

use crate::certificate::{find_witness, inner_box};
use crate::contract::{contract, EmptinessProof, Workspace};
use crate::{Interval, Model, Settings};

/// The verdict on a box of parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Status {
    /// Proved: no parameter vector in the initial box is consistent with the measurements
    /// (the proof is in [`Certification::emptiness`]).
    Empty,
    /// Proved: at least one parameter vector in the box is consistent with the measurements (the
    /// witness is in [`Certification::witness`]).
    Consistent,
    /// Neither proof was found; the outer box is still a valid enclosure of all solutions.
    Undecided,
}

/// The result of [`certify`].
#[derive(Clone, Debug, PartialEq)]
pub struct Certification<const NX: usize> {
    /// The verdict.
    pub status: Status,
    /// A box containing every parameter vector of `x0` consistent with the measurements (all
    /// intervals empty when the status is `Empty`).
    pub outer: [Interval; NX],
    /// Newton/LP steps performed.
    pub iterations: usize,
    /// For `Empty`: which test proved it.
    pub emptiness: Option<EmptinessProof>,
    /// For `Consistent`: a point of `outer` proved consistent with every measurement box.
    pub witness: Option<[f64; NX]>,
    /// Inner bounds: the hull of certified consistent points, contained in the hull of the solution
    /// set (so the true hull lies between `inner` and `outer`).
    pub inner: Option<[Interval; NX]>,
    /// LP solves and failures (failures never shrink the box).
    pub lp_solves: usize,
    /// LP solves that failed or whose infeasibility claim did not check.
    pub lp_failures: usize,
}

impl<const NX: usize> Certification<NX> {
    /// Per parameter, `wid(outer) / wid(inner)`: the worst-case overestimation of the outer bound
    /// over the true hull of the solution set (`None` without inner bounds; `inf` where the inner
    /// interval is a point).
    pub fn overestimation(&self) -> Option<[f64; NX]> {
        let inner = self.inner?;
        Some(core::array::from_fn(|j| {
            self.outer[j].wid() / (inner[j].sup() - inner[j].inf())
        }))
    }
}

/// Certifies a box: contracts `x0` with the Newton/Krawczyk–LP step to a fixed point (paper Section
/// IV), then looks for a certified witness and inner bounds.
///
/// `measurements[k]` is the box `M_k` of measurement `k`. The returned `outer` box contains every
/// `x ∈ x0` with `f(x, M_k) = 0` for some `M_k ∈ measurements[k]`, for all `k`.
pub fn certify<M: Model<NX, NM>, const NX: usize, const NM: usize>(
    model: &M,
    x0: &[Interval; NX],
    measurements: &[[Interval; NM]],
    settings: &Settings,
) -> Certification<NX> {
    let mut ws = Workspace::new(settings);
    certify_with(model, x0, measurements, settings, &mut ws)
}

/// [`certify`] with a caller-provided workspace (no allocation in the contraction after warm-up).
pub fn certify_with<M: Model<NX, NM>, const NX: usize, const NM: usize>(
    model: &M,
    x0: &[Interval; NX],
    measurements: &[[Interval; NM]],
    settings: &Settings,
    ws: &mut Workspace<NX>,
) -> Certification<NX> {
    let (solves, failures) = (ws.lp_solves, ws.lp_failures);
    let c = contract(model, x0, measurements, settings, ws);
    let mut out = Certification {
        status: Status::Undecided,
        outer: [Interval::EMPTY; NX],
        iterations: c.iterations,
        emptiness: None,
        witness: None,
        inner: None,
        lp_solves: 0,
        lp_failures: 0,
    };
    match c.result {
        Err(proof) => {
            out.status = Status::Empty;
            out.emptiness = Some(proof);
        }
        Ok(outer) => {
            out.outer = outer;
            let extremes = if c.iterations > 0 {
                ws.extreme_points.clone()
            } else {
                Vec::new()
            };
            if let Some(w) = find_witness(model, &outer, measurements, &extremes) {
                out.status = Status::Consistent;
                out.witness = Some(w);
                if settings.inner_bounds {
                    out.inner = Some(inner_box(
                        model,
                        &w,
                        &outer,
                        &extremes,
                        measurements,
                        settings.inner_bisections,
                    ));
                }
            }
        }
    }
    out.lp_solves = ws.lp_solves - solves;
    out.lp_failures = ws.lp_failures - failures;
    out
}
