//! One certified sub-problem of a robot (a Gough leg, an arm's whole chain), whatever its model:
//! [`Outcome`] holds what the kernel proved in plain vectors, with the parameters' names, and
//! [`certify_model`] produces it from any [`VectorModel`].

pub use calib_core::is_fixed;
use calib_core::{certify, hull, Cover, EmptinessProof, Interval, Settings, Status, VectorModel};
use std::time::Instant;

/// What is certified about one sub-problem (parameters in the model's units).
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// The parameters' names, in model order.
    pub names: Vec<String>,
    /// The initial box.
    pub x0: Vec<Interval>,
    /// The verdict.
    pub status: Status,
    /// For `Empty`: what proved it.
    pub emptiness: Option<EmptinessProof>,
    /// The paper's fixed point (`None` when x0 was proved empty at once).
    pub x1: Option<Vec<Interval>>,
    /// The tightest certified outer box (`None` when empty).
    pub outer: Option<Vec<Interval>>,
    /// Certified inner bounds.
    pub inner: Option<Vec<Interval>>,
    /// A certified consistent parameter vector.
    pub witness: Option<Vec<f64>>,
    /// For an empty sub-problem: a minimal set of configurations (0-based) that cannot be fitted
    /// together (not searched when the misfit is [`spread`](Outcome::spread)).
    pub conflict: Option<Vec<usize>>,
    /// For an empty sub-problem: the configurations (0-based) the final certificate of emptiness
    /// weighs, when it names them ([`calib_core::Certification::support`]).
    pub support: Option<Vec<usize>>,
    /// For an empty sub-problem: the support weighs most of what a certificate can weigh — a
    /// misfit spread over the data, the error bounds too tight for the model, rather than a few
    /// bad readings ([`calib_core::is_spread`]); no conflict set was searched.
    pub spread: bool,
    /// With outliers tolerated: the configurations (0-based) proved to be outliers.
    pub outliers: Vec<usize>,
    /// Newton/LP steps to x1.
    pub iterations: usize,
    /// Whether the hull met its tolerance (`None` when only x1 was computed).
    pub converged: Option<bool>,
    /// Boxes contracted in total.
    pub boxes: usize,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// How far to go: the paper's x1 alone, or the tight hull with its tolerance and budget.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Depth {
    /// One contraction to the fixed point x1, with a witness and inner bounds.
    Fast,
    /// The tight hull ([`calib_core::hull`]) under the settings' tolerance and budget.
    Hull,
}

/// What [`certify_model`] proves: the [`Outcome`], and the cover and certified points the
/// certified set is built from ([`calib_core::CertifiedSet::new`]), in the model's dimensions.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelCertification<const NX: usize> {
    /// The outcome.
    pub outcome: Outcome,
    /// Boxes whose union holds every consistent parameter vector (empty when proved empty).
    pub cover: Cover<NX>,
    /// Certified consistent parameter vectors: the witness, then the inner bounds' points.
    pub points: Vec<[f64; NX]>,
}

/// Certifies `x0` against the measurement boxes (one per configuration).
pub fn certify_model<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    names: &[String],
    x0: &[Interval; NX],
    boxes: &[[Interval; NM]],
    depth: Depth,
    settings: &Settings,
) -> ModelCertification<NX>
where
    M: VectorModel<NX, NM, NR> + Sync,
{
    let t = Instant::now();
    let vec = |b: [Interval; NX]| b.to_vec();
    let (mut out, cover, points) = match depth {
        Depth::Fast => {
            let c = certify(model, x0, boxes, settings);
            let x1 = (c.status != Status::Empty).then(|| vec(c.outer));
            let points = c.witness.into_iter().collect();
            let outcome = Outcome {
                names: names.to_vec(),
                x0: x0.to_vec(),
                status: c.status,
                emptiness: c.emptiness,
                outer: x1.clone(),
                x1,
                inner: c.inner.map(vec),
                witness: c.witness.map(|w| w.to_vec()),
                conflict: c.conflict,
                support: c.support,
                spread: c.spread,
                outliers: c.outliers,
                iterations: c.iterations,
                converged: None,
                boxes: 1,
                seconds: 0.0,
            };
            (outcome, c.cover, points)
        }
        Depth::Hull => {
            let h = hull(model, x0, boxes, settings);
            let points = h
                .witness
                .into_iter()
                .chain(h.inner_points.clone())
                .collect();
            let outcome = Outcome {
                names: names.to_vec(),
                x0: x0.to_vec(),
                status: h.status,
                emptiness: h.emptiness,
                x1: h.x1.map(vec),
                outer: (h.status != Status::Empty).then(|| vec(h.outer)),
                inner: h.inner.map(vec),
                witness: h.witness.map(|w| w.to_vec()),
                conflict: h.conflict,
                support: h.support,
                spread: h.spread,
                outliers: h.outliers,
                iterations: h.iterations,
                converged: Some(h.converged),
                boxes: h.boxes_contracted,
                seconds: 0.0,
            };
            (outcome, h.cover, points)
        }
    };
    out.seconds = t.elapsed().as_secs_f64();
    ModelCertification {
        outcome: out,
        cover,
        points,
    }
}

impl Outcome {
    /// The outer width over the inner width, per parameter, when both exist (`NaN` for a
    /// parameter fixed in x0, whose widths are both zero).
    pub fn width_ratios(&self) -> Option<Vec<f64>> {
        let (outer, inner) = (self.outer.as_ref()?, self.inner.as_ref()?);
        Some(
            outer
                .iter()
                .zip(inner)
                .map(|(o, i)| o.wid() / i.wid())
                .collect(),
        )
    }

    /// The parameters (index, which end) where the outer box reaches a face of x0. Parameters
    /// fixed in x0 (zero width up to rounding) are left out.
    pub fn x0_faces(&self) -> Vec<(usize, &'static str)> {
        let Some(outer) = &self.outer else {
            return Vec::new();
        };
        (0..self.x0.len())
            .filter(|&j| !is_fixed(self.x0[j]))
            .filter_map(|j| {
                let lo = outer[j].inf() <= self.x0[j].inf();
                let hi = outer[j].sup() >= self.x0[j].sup();
                match (lo, hi) {
                    (true, true) => Some((j, "both ends")),
                    (true, false) => Some((j, "lower end")),
                    (false, true) => Some((j, "upper end")),
                    (false, false) => None,
                }
            })
            .collect()
    }

    /// The outcome restricted to the parameters `index` (in that order), renamed `names`: for a
    /// robot certified through a larger model (an arm padded with identity joints).
    pub fn select(&self, index: &[usize], names: Vec<String>) -> Outcome {
        let pick = |b: &Vec<Interval>| index.iter().map(|&j| b[j]).collect();
        Outcome {
            names,
            x0: pick(&self.x0),
            x1: self.x1.as_ref().map(pick),
            outer: self.outer.as_ref().map(pick),
            inner: self.inner.as_ref().map(pick),
            witness: self
                .witness
                .as_ref()
                .map(|w| index.iter().map(|&j| w[j]).collect()),
            emptiness: match self.emptiness {
                Some(EmptinessProof::EmptyIntersection { parameter }) => {
                    Some(EmptinessProof::EmptyIntersection {
                        parameter: index.iter().position(|&j| j == parameter).unwrap_or(0),
                    })
                }
                other => other,
            },
            ..self.clone()
        }
    }

    /// The same outcome with every interval mapped by `f(index, interval)` (to display units;
    /// `f` must enclose, e.g. radians to degrees rounded outward) and the witness by `g`.
    pub fn map_units(
        &self,
        f: impl Fn(usize, Interval) -> Interval,
        g: impl Fn(usize, f64) -> f64,
    ) -> Outcome {
        let boxes = |b: &Vec<Interval>| b.iter().enumerate().map(|(j, v)| f(j, *v)).collect();
        Outcome {
            x0: boxes(&self.x0),
            x1: self.x1.as_ref().map(boxes),
            outer: self.outer.as_ref().map(boxes),
            inner: self.inner.as_ref().map(boxes),
            witness: self
                .witness
                .as_ref()
                .map(|w| w.iter().enumerate().map(|(j, v)| g(j, *v)).collect()),
            ..self.clone()
        }
    }
}
