//! Input boxes too wide for Taylor models, when the inputs are angles that enter the prediction
//! only through their cosine and sine, one rotation each ([`Prediction::ANGULAR_INPUTS`]: a
//! chain of revolute joints).
//!
//! **Why vertices suffice.** For fixed `θ`, `g(u; θ)` is affine in `(cos u_i, sin u_i)` for each
//! input, the others fixed. So any function convex in `g`'s values and derivatives at a point
//! `v = (v_1, …, v_n)` of planes — each `v_i` a point of the plane where `(cos u_i, sin u_i)`
//! lives, `g` extended by the same affine formula — attains its maximum over a product of
//! convex sets at a product of their extreme points. The arc `[lo, hi]` of an input (half-width
//! `d < π/2` about `m`) lies in the triangle of its ends and `T = ρ (cos m, sin m)`,
//! `ρ >= 1 / cos d` (the point where its end tangents meet, or beyond). An affine function at `T`
//! is `((1 + ρ)/2) f(m) + ((1 - ρ)/2) f(m + π)`: every vertex of the triangles' product is a
//! weighted sum of evaluations at real angles, `4^k` of them for `k` inputs with a width.
//!
//! **What is bounded at each vertex.** With `δ = θ* - θ̂` and the reached inputs `u + e`,
//!
//! `g(u + e; θ*) - g(u; θ̂) = [g(u + e; θ*) - g(u + e; θ̂)] + [g(u + e; θ̂) - g(u; θ̂)]`.
//!
//! Along a unit direction `w` the first part is, by the mean-value theorem in `θ` at a vertex
//! `v` of the widened box's triangles, `w·C(v)·δ` with `C(v) ⊇ ∂g/∂θ` over the set's hull (`θ̂`
//! with the outer box); split as `w·c⁰·δ + w·(C(v) - c⁰)·δ` with `c⁰` the columns at the box's
//! centre and `θ̂`: the first term is the component's main term (a linear program over the set),
//! the second is bounded over the set's parallelotope ([`Parallelotope::split`]), the largest
//! over the vertices. Where a vertex's bound is the largest, that vertex gets its own program
//! (`w·C(v)`'s midpoints), which then also serves every other vertex as a nearer centre
//! ([`Arcs::max_along`]): the bound approaches the largest of the vertices' programs. The
//! second part is at most `Σ_i |w·H_i(v)| ε_i`, `H(v) ⊇ ∂g/∂u`, the
//! largest over the vertices (a convex function of `H`, affine in each input's plane). Both are
//! exact for the triangles, so the excess over the arcs is that of `ρ` (second order in the
//! box's width) and the parallelotope's on the columns' variation (first order).

use super::sphere::add_up;
use super::{slot, Prediction};
use calib_core::{Interval, Parallelotope, VectorModel};
use rayon::prelude::*;

/// Arcs at most this wide (radians) are enclosed by their triangle (`ρ <= 1 / cos 1.2 ≈ 2.8`);
/// wider ones are left to the interval slopes (the branch and bound splits them first).
pub(super) const WIDEST_ARC: f64 = 2.4;

/// What the components over one wide input box are made of (module documentation).
pub(super) struct Arcs<const NX: usize, const NU: usize, const R: usize> {
    /// `c⁰`: per coordinate, the columns `∂g_r/∂θ` at the box's centre and `θ̂`.
    pub(super) centre: [[f64; NX]; R],
    /// Per vertex, per coordinate: `C_r(v) - c⁰_r` split by the parallelotope.
    columns: Vec<[Split; R]>,
    /// The ranges the splits' coefficients multiply.
    ranges: Ranges,
    /// Per vertex, per coordinate: the midpoints of `C_r(v) - c⁰_r`.
    midpoints: Vec<[[f64; NX]; R]>,
    /// Per vertex, per coordinate, per input: `H_ri(v) ⊇ ∂g_r/∂u_i`.
    inputs: Vec<[[Interval; NU]; R]>,
    /// Per input, the half-width of its own error.
    input_error: [Interval; NU],
}

/// One input's choices of vertex: per choice, its evaluations' angles and weights.
pub type Choices = Vec<Vec<(Interval, Interval)>>;

/// The triangle's vertices of the arc `u` (module documentation), or `u` itself for an input
/// without a width: per vertex, the angles (enclosed) whose values, weighted, give a function
/// affine in the angle's cosine and sine there. `None` for an arc wider than 2.4 rad.
pub fn arc_vertices(u: Interval) -> Option<Choices> {
    let one = Interval::ONE;
    if u.wid() == 0.0 {
        return Some(vec![vec![(u, one)]]);
    }
    if u.wid().is_nan() || u.wid() > WIDEST_ARC {
        return None;
    }
    let (lo, hi, m) = (u.inf(), u.sup(), u.mid());
    let d = (Interval::point(m) - Interval::point(lo))
        .hull(Interval::point(hi) - Interval::point(m))
        .sup();
    let rho = Interval::point((one / Interval::point(d).cos()).sup());
    let two = Interval::point(2.0);
    Some(vec![
        vec![(Interval::point(lo), one)],
        vec![(Interval::point(hi), one)],
        vec![
            (Interval::point(m), (one + rho) / two),
            (Interval::point(m) + Interval::PI, (one - rho) / two),
        ],
    ])
}

impl<const NX: usize, const NU: usize, const R: usize> Arcs<NX, NU, R> {
    /// The vertices' columns and input slopes over the input box `u` (the inputs' own errors
    /// included) and the parameter box `hull` (holding `θ̂` and the set), split by
    /// `parallelotope`. `None` for an arc too wide or an enclosure that failed.
    pub(super) fn over<P, const NMS: usize, const NP: usize>(
        prediction: &P,
        u: &[Interval; NU],
        hull: &[Interval; NX],
        nominal: &[f64; NX],
        input_error: &[Interval; NU],
        parallelotope: &Parallelotope<NX>,
    ) -> Option<Self>
    where
        P: Prediction<NX, NMS, NP, NU, R>,
    {
        let per_input: Vec<Choices> = u.iter().map(|v| arc_vertices(*v)).collect::<Option<_>>()?;
        let model = prediction.model();
        let centre_rows = model.evaluate_rows(nominal, &slot(&u.map(|v| v.mid()), 0.0));
        let centre: [[f64; NX]; R] = core::array::from_fn(|r| centre_rows[r].dx);
        if !centre.iter().flatten().all(|v| v.is_finite()) {
            return None;
        }
        let count: usize = per_input.iter().map(Vec::len).product();
        let vertices: Vec<_> = (0..count)
            .into_par_iter()
            .map(|index| {
                // The vertex's choice per input (mixed radix), then its evaluations' sum.
                let mut rest = index;
                let pick: [usize; NU] = core::array::from_fn(|i| {
                    let c = rest % per_input[i].len();
                    rest /= per_input[i].len();
                    c
                });
                vertex(model, hull, &per_input, &pick)
            })
            .collect::<Option<_>>()?;
        let split: Vec<_> = vertices
            .par_iter()
            .map(|(c, _)| {
                let diff: [[Interval; NX]; R] = core::array::from_fn(|r| {
                    core::array::from_fn(|j| c[r][j] - Interval::point(centre[r][j]))
                });
                let columns: [Split; R] =
                    core::array::from_fn(|r| Split::of(parallelotope, &diff[r]));
                (columns, diff.map(|d| d.map(|v| v.mid())))
            })
            .collect();
        let (columns, midpoints) = split.into_iter().unzip();
        let inputs = vertices.into_iter().map(|(_, h)| h).collect();
        Some(Arcs {
            centre,
            columns,
            ranges: Ranges::of(parallelotope),
            midpoints,
            inputs,
            input_error: *input_error,
        })
    }

    /// An upper bound of the error's component along `w` over the box (module documentation):
    /// the largest over the vertices of `max_S w·C(v)·δ`, plus the inputs' term. Each vertex is
    /// first bounded from the program at the centre, `h_S(o) + max_P (w·C(v) - o)·δ` with
    /// `o = w·c⁰`; then, while the largest of these exceeds the largest proved exactly by more
    /// than [`VERTEX_TOLERANCE`], its vertex gets its own program (`main`: the support of the
    /// set, `sup_S o·δ` for slopes `o`), which becomes a further centre for every other
    /// vertex's bound. Without programs (`main` `None`) the parallelotope bounds the centre's
    /// term too. `+∞` where a bound is not finite.
    pub(super) fn max_along(
        &self,
        w: &[f64; R],
        parallelotope: &Parallelotope<NX>,
        mut main: Option<Support<'_, NX>>,
    ) -> f64 {
        let wi = w.map(Interval::point);
        let o: [Interval; NX] = core::array::from_fn(|j| {
            (0..R).fold(Interval::ZERO, |s, r| {
                s + wi[r] * Interval::point(self.centre[r][j])
            })
        });
        // Per vertex, w·(C(v) - c⁰) split by the parallelotope.
        let splits: Vec<Split> = self
            .columns
            .par_iter()
            .map(|split| Split::combination(w, split))
            .collect();
        let none = Split::zero(self.ranges.centre.len());
        let first = match main.as_mut() {
            Some(main) => main(&o),
            None => parallelotope.max_linear(&o),
        };
        let mut bound: Vec<f64> = splits
            .par_iter()
            .map(|v| add_up(first, self.ranges.beyond(v, &none)))
            .collect();
        let mut exact = f64::NEG_INFINITY;
        let mut solved = vec![false; bound.len()];
        if let Some(main) = main {
            for _ in 0..VERTEX_PROGRAMS {
                let Some((v, &top)) = bound
                    .iter()
                    .enumerate()
                    .filter(|(v, _)| !solved[*v])
                    .max_by(|a, b| a.1.total_cmp(b.1))
                else {
                    break;
                };
                if top.is_nan() || top <= exact + VERTEX_TOLERANCE * exact.abs() {
                    break;
                }
                // The vertex's own centre: o + d, d the midpoints of w·(C(v) - c⁰).
                let d: [f64; NX] = core::array::from_fn(|j| {
                    (0..R).map(|r| w[r] * self.midpoints[v][r][j]).sum::<f64>()
                });
                let centre = Split::of(parallelotope, &d.map(Interval::point));
                let h = main(&core::array::from_fn(|j| o[j] + Interval::point(d[j])));
                let own = add_up(h, self.ranges.beyond(&splits[v], &centre));
                bound[v] = own.min(bound[v]);
                solved[v] = true;
                exact = exact.max(bound[v]);
                // Only vertices that could still raise the bound are worth the new centre.
                let matters = exact + VERTEX_TOLERANCE * exact.abs();
                bound
                    .par_iter_mut()
                    .zip(&splits)
                    .zip(&solved)
                    .filter(|((b, _), done)| !**done && **b > matters)
                    .for_each(|((b, split), _)| {
                        *b = b.min(add_up(h, self.ranges.beyond(split, &centre)));
                    });
            }
        }
        let columns = bound.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let mut inputs = 0.0f64;
        for h in &self.inputs {
            let term = (0..NU).fold(Interval::ZERO, |s, i| {
                let along = (0..R).fold(Interval::ZERO, |a, r| a + wi[r] * h[r][i]);
                s + Interval::point(along.mag()) * self.input_error[i]
            });
            inputs = inputs.max(term.sup());
        }
        let out = add_up(columns, inputs);
        if out.is_nan() {
            f64::INFINITY
        } else {
            out
        }
    }
}

/// A linear function `s·δ` split by the parallelotope ([`Parallelotope::split`]), in floating
/// point: per coefficient a midpoint and a radius that holds the interval's own and every
/// rounding since, the rest (the rounding of `T`) as a last coefficient of range `[1, 1]`.
#[derive(Clone, Debug)]
struct Split {
    mid: Vec<f64>,
    rad: Vec<f64>,
}

/// Relative rounding allowance of a short floating-point sum: far above `n · 2⁻⁵³` for the
/// few dozen terms summed here.
const ROUNDING: f64 = 1e-12;

impl Split {
    /// The split of `slopes` (intervals).
    fn of<const NX: usize>(parallelotope: &Parallelotope<NX>, slopes: &[Interval; NX]) -> Self {
        let mid = slopes.map(|v| v.mid());
        let rad = core::array::from_fn(|j| (slopes[j] - Interval::point(mid[j])).mag());
        let (mid, rad) = parallelotope.split_mid_rad(&mid, &rad);
        Split { mid, rad }
    }

    /// The split of `0`, `n` coefficients and the rest.
    fn zero(n: usize) -> Self {
        Split {
            mid: vec![0.0; n],
            rad: vec![0.0; n],
        }
    }

    /// `Σ_r w_r s_r` (the split of the combination: the split is linear).
    fn combination<const R: usize>(w: &[f64; R], splits: &[Split; R]) -> Self {
        let n = splits[0].mid.len();
        let (mid, rad) = (0..n)
            .map(|k| {
                let (mut m, mut size, mut r) = (0.0, 0.0, 0.0);
                for (wr, s) in w.iter().zip(splits) {
                    m += wr * s.mid[k];
                    size += (wr * s.mid[k]).abs();
                    r += wr.abs() * s.rad[k];
                }
                (m, (r + ROUNDING * size) * (1.0 + ROUNDING))
            })
            .unzip();
        Split { mid, rad }
    }
}

/// The ranges `Z_k` of the parallelotope's coefficients (and `[1, 1]` for the rest), as
/// midpoints, radii and magnitudes.
#[derive(Clone, Debug)]
struct Ranges {
    centre: Vec<f64>,
    radius: Vec<f64>,
    magnitude: Vec<f64>,
}

impl Ranges {
    fn of<const NX: usize>(parallelotope: &Parallelotope<NX>) -> Self {
        let all: Vec<Interval> = parallelotope
            .ranges()
            .iter()
            .copied()
            .chain(core::iter::once(Interval::ONE))
            .collect();
        Ranges {
            centre: all.iter().map(|z| z.mid()).collect(),
            radius: all
                .iter()
                .map(|z| (*z - Interval::point(z.mid())).mag())
                .collect(),
            magnitude: all.iter().map(|z| z.mag()).collect(),
        }
    }

    /// An upper bound of `(v - c)·δ` over the parallelotope for splits `v` and `c`: with
    /// `a_k ∈ m_k ± ρ_k` and `z ∈ Z_k`, `a z <= m_k mid Z_k + |m_k| rad Z_k + ρ_k |Z_k|`,
    /// summed in floating point with a rounding allowance. `+∞` if not finite.
    fn beyond(&self, v: &Split, c: &Split) -> f64 {
        let (mut sum, mut size) = (0.0f64, 0.0f64);
        for k in 0..self.centre.len() {
            let m = v.mid[k] - c.mid[k];
            let rho = (v.rad[k] + c.rad[k]) * (1.0 + ROUNDING);
            let t = m.abs() * self.radius[k] + rho * self.magnitude[k];
            let a = m * self.centre[k];
            sum += a + t;
            size += a.abs() + t + m.abs() * ROUNDING * self.magnitude[k];
        }
        let up = (sum + ROUNDING * size) * (1.0 + ROUNDING) + f64::MIN_POSITIVE;
        if up.is_finite() {
            up.max(sum)
        } else {
            f64::INFINITY
        }
    }
}

/// The support of the set, `sup_S o·δ` for slopes `o` (a linear program's safe bound).
pub(super) type Support<'a, const NX: usize> = &'a mut dyn FnMut(&[Interval; NX]) -> f64;

/// At most this many vertices get their own program per component (`benches/README.md`: on wide
/// boxes, more boxes with fewer programs are about as good for the time).
const VERTEX_PROGRAMS: usize = 4;

/// Vertices stop getting their own programs once every other's bound is within this share of
/// the largest proved with one.
const VERTEX_TOLERANCE: f64 = 0.01;

/// A vertex's columns `C_r(v)` and input slopes `H_r(v)`.
type Vertex<const NX: usize, const NU: usize, const R: usize> =
    ([[Interval; NX]; R], [[Interval; NU]; R]);

/// The columns `C_r(v)` and input slopes `H_r(v)` at the vertex `pick` of the inputs' choices:
/// its evaluations over `hull`, weighted and summed. `None` where an enclosure failed.
fn vertex<M, const NX: usize, const NP: usize, const NU: usize, const R: usize>(
    model: &M,
    hull: &[Interval; NX],
    per_input: &[Choices],
    pick: &[usize; NU],
) -> Option<Vertex<NX, NU, R>>
where
    M: VectorModel<NX, NP, R>,
{
    let lists: [&Vec<(Interval, Interval)>; NU] = core::array::from_fn(|i| &per_input[i][pick[i]]);
    let total: usize = lists.iter().map(|l| l.len()).product();
    let mut c = [[Interval::ZERO; NX]; R];
    let mut h = [[Interval::ZERO; NU]; R];
    for index in 0..total {
        let mut rest = index;
        let mut weight = Interval::ONE;
        let angles: [Interval; NU] = core::array::from_fn(|i| {
            let (angle, w) = lists[i][rest % lists[i].len()];
            rest /= lists[i].len();
            weight *= w;
            angle
        });
        let rows = model.evaluate_rows_interval(hull, &slot(&angles, Interval::ZERO));
        for ((c, h), row) in c.iter_mut().zip(h.iter_mut()).zip(&rows) {
            for (c, d) in c.iter_mut().zip(&row.dx) {
                *c += weight * *d;
            }
            for (h, d) in h.iter_mut().zip(&row.dm) {
                *h += weight * *d;
            }
        }
    }
    let bounded = |v: &Interval| v.is_bounded() && !v.is_empty();
    (c.iter().flatten().all(bounded) && h.iter().flatten().all(bounded)).then_some((c, h))
}
