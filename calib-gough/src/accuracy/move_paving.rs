//! Bounding the reached move by a paving of the moves themselves, with second-order Taylor
//! models: for errors too large for a chart.
//!
//! The charts of [`super::pose_chart`] and [`super::pose_bound`] close a region in the leg
//! changes `y ≈ J δ`, leg by leg: each leg's nonlinear remainder `|G_i - y_i|` must stay below
//! the region's margin. Where the legs are nearly vertical (the hexapod of `sample21`), a
//! sideways move `d` lengthens every leg by about `|d|² / 2L`: for the centimetre moves that a
//! few millimetres of leg error cause there, that is 40% of `U_i` per leg, and no region in the
//! leg changes closes. The same term is harmless in the moves: the inverse Jacobian maps the
//! same lengthening of all six legs to a vertical move, which the legs fix tightly.
//!
//! **The test.** Every move `δ` the platform can reach from a pose of the box satisfies
//! `G(X, δ, θ*) = s*` with `s* ∈ S = [-U, U]` ([`super::pose_bound`]); with the geometry's share
//! `γ = G(X, δ, θ*) - G(X, δ, θ̂) ∈ Γ` (a mean-value form over the boxes), it is a fixed point of
//! `T(δ, s) = δ - M (G(X, δ, θ̂) - s)`, `s = s* - γ ∈ S - Γ`, for any matrix `M`. Over
//! a box `Y` of moves, the values of `T` — evaluated as [`calib_core::Quadratic`] models, noise
//! symbols `0..6` for the move and `6..12` for the pose, so that the quadratic terms common to
//! all legs cancel in `M G` exactly — enclose every such move in `Y`, for every pose of the box,
//! geometry and actuator error: `Y ∩ T(Y, S')` with `S' = (S - Γ) ∩ G(Y; θ̂)` (empty: no reached
//! move in `Y`; `M` the inverse of the nominal Jacobian at `Y`'s centre, so that `T`'s
//! dependence on `δ` is of second order).
//!
//! **The region argument.** A best-first branch and bound paves a box `B` around `δ = 0`: a box
//! is dropped when it holds no move of `F`, kept (and bounded) when its enclosure stays inside
//! `B`, and split first when the enclosure still reaches `B`'s boundary. Once no kept box
//! reaches it, no move on `∂B` lies in `F` for any pose, geometry or actuator error, so the path
//! from the commanded pose never leaves `B` (see [`super::pose_bound`]), and the reached move lies
//! in one of the kept boxes' enclosures. Boxes are dropped only when no pose of the box of poses
//! reaches a move in them, so the pieces (closed or not) hold for every sub-box of poses, which
//! starts from them ([`Paved`]) instead of paving `B` again.
//!
//! **The bound of a box.** The smaller of the enclosure's farthest corner and, since a fixed
//! point is `δ = A + M s` with `A = δ - M G` (its range over `Y`) and `s ∈ S'`, the largest
//! `|d|` and `|w|` over the 64 × 64 vertices of `S'` and of the pose's noise symbols (`A`'s
//! linear terms in them), the rest of `A`'s range added outward: the vertices
//! follow the skew of `M`, which the box's corner cannot, and what is left is second order.
//! (Each is a bound on its own; mixing them component by component would not be.) Boxes are
//! split by their bound relative to the target until the largest is within it.

use super::enclosure::{AccuracyProblem, PoseBox};
use super::pose_bound::{errors_from_squares, leg_change_bounds, leg_inputs, reached_change};
use super::pose_bound::{key, ReachedChange};
use super::pose_chart::{add_up, mul_up};
use calib_core::split_widest;
use calib_core::Ranked;
use calib_core::{Interval, Model, Quadratic};
use nalgebra::Matrix6;
use rayon::prelude::*;
use std::collections::BinaryHeap;

/// Second-order models over the box of moves (noise symbols `0..6`) and of poses (`6..12`).
type Form = Quadratic<12>;

/// The smallest reach of the moves, relative to the platform's distance from the base, for
/// which a box of poses is paved (see [`MovePaving::new`]).
const LARGE_MOVE: f64 = 0.01;
/// Contraction rounds per box of moves.
const ROUNDS: usize = 4;
/// A round that narrows the box by less than this (summed relative widths) is the last.
const STALL: f64 = 0.3;
/// `∂B` must be excluded within `1 / CLOSING_SHARE` of the budget of boxes of moves.
const CLOSING_SHARE: usize = 2;
/// `B`'s half-widths in units of the linear estimate `Σ_c |M_rc| U_c` of each coordinate's
/// reach (the farthest first: a wider `B` is easier to close on and costs only the boxes that
/// hold no move).
const OUTER: f64 = 2.0;
/// The smallest half-width of `B` in position (cm) and in the Rodrigues vector: coordinates the
/// linear estimate says barely move still get room for their second-order moves.
const OUTER_MIN: [f64; 2] = [0.5, 0.01];
/// Boxes of moves pieced in parallel per round of [`MovePaving::bound`].
const BATCH: usize = 16;
/// A box still reaching `∂B` and narrower than this fraction of `B` (in every coordinate) ends
/// the search unproved.
const FINEST: f64 = 1.0 / 4096.0;

/// One box of poses: the models of its inputs and what the contraction needs.
pub struct MovePaving {
    /// `U_i`.
    bound: [f64; 6],
    /// Per leg, the inputs of [`reached_change`]: the pose as models, the nominal geometry.
    inputs: Vec<[Form; 12]>,
    /// Per leg, the pose's box and the geometry's box, and the nominal geometry.
    pub boxes: Vec<[Interval; 12]>,
    pub nominal: Vec<[f64; 6]>,
    /// Per leg, the pose's centre and the nominal geometry (for the chart matrices `M`).
    centre: Vec<[f64; 12]>,
    /// The box `B`.
    pub outer: [Interval; 6],
    /// The box of poses.
    poses: PoseBox,
}

/// A box of moves with what its enclosure proves.
#[derive(Clone, Copy, Debug)]
pub struct Piece {
    /// The enclosure of the reached moves in the box.
    pub moves: [Interval; 6],
    /// Upper bounds of the position (cm) and orientation (degrees) errors over them.
    value: [f64; 2],
    /// Whether the enclosure reaches `∂B`.
    touches: bool,
    /// Whether `moves` and `value` were computed for a larger box of poses (the box's parent:
    /// valid, but not yet narrowed to this box).
    inherited: bool,
}

/// What the paving of a box of poses proved, which holds for each of its sub-boxes: every move of
/// `B` that a pose of the box can reach lies in one of the pieces' enclosures. Once no piece
/// reaches the boundary of `B` (the paving is closed), every reached move does.
#[derive(Clone, Debug)]
pub struct Paved {
    /// The box of poses paved.
    poses: PoseBox,
    /// The box `B`.
    outer: [Interval; 6],
    /// The pieces, `inherited` for the sub-boxes.
    pub pieces: Vec<Piece>,
}

impl MovePaving {
    /// The paving of the box of poses `x` with actuator errors `± eps`; `None` when the legs'
    /// bounds or the nominal Jacobian fail. `parent`: what the paving of `x` or of a box of poses
    /// containing it proved (its `B` is kept, and its pieces are the start).
    pub fn new(
        problem: &AccuracyProblem,
        x: &PoseBox,
        eps: f64,
        parent: Option<&Paved>,
    ) -> Option<MovePaving> {
        if problem.legs() != 6 {
            return None;
        }
        let bound = leg_change_bounds(problem, x, eps)?;
        let pose: [Form; 6] = core::array::from_fn(|k| Form::input(x[k], 6 + k));
        let nominal: Vec<[f64; 6]> = (0..6)
            .map(|i| core::array::from_fn(|k| problem.nominal(i)[k]))
            .collect();
        let inputs = (0..6)
            .map(|i| {
                core::array::from_fn(|k| {
                    if k < 6 {
                        pose[k]
                    } else {
                        Form::from_interval(Interval::point(nominal[i][k - 6]))
                    }
                })
            })
            .collect();
        let boxes = leg_inputs(problem, x, |v| v);
        let xc = x.map(|v| v.mid());
        let centre: Vec<[f64; 12]> = (0..6)
            .map(|i| {
                let n = problem.nominal(i);
                core::array::from_fn(|k| if k < 6 { xc[k] } else { n[k - 6] })
            })
            .collect();
        let m = chart(&centre, &[0.0; 6])?;
        let reach: [f64; 6] =
            core::array::from_fn(|r| (0..6).map(|c| m[(r, c)].abs() * bound[c]).sum());
        // Only moves that turn the legs (a reach beyond LARGE_MOVE of the platform's distance
        // from the base attachments) are paved: smaller ones are the charts' (splitting the box
        // of poses is far cheaper there); moves beyond a quarter of that distance (near a
        // singular pose) cannot be enclosed by second-order models.
        let scale = (0..6)
            .map(|i| {
                let a = &problem.nominal(i)[..3];
                ((xc[0] - a[0]).powi(2) + (xc[1] - a[1]).powi(2) + (xc[2] - a[2]).powi(2)).sqrt()
            })
            .fold(f64::INFINITY, f64::min);
        let position_reach = reach[..3].iter().fold(0.0f64, |a, v| a.max(*v));
        if !(position_reach >= LARGE_MOVE * scale && position_reach <= 0.25 * scale) {
            return None;
        }
        let outer = parent.map_or_else(
            || {
                core::array::from_fn(|r| {
                    let h = (OUTER * reach[r]).max(OUTER_MIN[r / 3]);
                    Interval::new(-h, h)
                })
            },
            |p| p.outer,
        );
        Some(MovePaving {
            bound,
            inputs,
            boxes,
            nominal,
            centre,
            outer,
            poses: *x,
        })
    }

    /// `Γ_i ∋ G_i(X, δ, θ*) - G_i(X, δ, θ̂)` over the box of poses, the moves `y` and the
    /// geometry's box: `∇_θ G_i · (Θ_i - θ̂_i)`, the gradient enclosed over all three (mean
    /// value; `l` does not enter `G`).
    pub fn geometry_spread(&self, i: usize, y: &[Interval; 6]) -> Interval {
        let m = &self.boxes[i];
        let grad = ReachedChange.jacobian_m_interval(y, m);
        (0..6).fold(Interval::ZERO, |acc, j| {
            acc + grad[6 + j] * (m[6 + j] - Interval::point(self.nominal[i][j]))
        })
    }

    /// Whether `y` reaches `∂B`.
    fn touches(&self, y: &[Interval; 6]) -> bool {
        (0..6).any(|k| y[k].inf() <= self.outer[k].inf() || y[k].sup() >= self.outer[k].sup())
    }

    /// The enclosure of the reached moves in `y` and its bounds, or `None` when `y` holds none.
    fn piece(&self, y: &[Interval; 6]) -> Option<Piece> {
        let mut y = *y;
        let mut value = [f64::INFINITY; 2];
        for _ in 0..ROUNDS {
            let Some(m) = chart(&self.centre, &y.map(|v| v.mid())) else {
                break;
            };
            let delta: [Form; 6] = core::array::from_fn(|k| Form::input(y[k], k));
            let g: [Form; 6] = core::array::from_fn(|i| reached_change(&delta, &self.inputs[i]));
            // S' = (S - Γ) ∩ G(Y; θ̂): a leg that cannot reach its bound leaves no move in the
            // box.
            let mut s = [Interval::ZERO; 6];
            for i in 0..6 {
                let spread = self.geometry_spread(i, &y);
                s[i] = g[i]
                    .range()
                    .intersection(Interval::new(-self.bound[i], self.bound[i]) - spread);
                if s[i].is_empty() {
                    return None;
                }
            }
            let cst = |v: f64| Form::from_interval(Interval::point(v));
            let forms: [Form; 6] = core::array::from_fn(|r| {
                (0..6).fold(delta[r], |acc, c| acc - cst(m[(r, c)]) * g[c])
            });
            let a = forms.map(|f| f.range());
            let mut narrowed = 0.0;
            for r in 0..6 {
                let t = (0..6).fold(a[r], |acc, c| acc + Interval::point(m[(r, c)]) * s[c]);
                let cut = y[r].intersection(t);
                if cut.is_empty() {
                    return None;
                }
                narrowed += 1.0 - cut.wid() / y[r].wid().max(f64::MIN_POSITIVE);
                y[r] = cut;
            }
            let at_vertices = vertex_value(&m, &forms, &s);
            value = [value[0].min(at_vertices[0]), value[1].min(at_vertices[1])];
            if narrowed < STALL {
                break;
            }
        }
        let corner = errors_from_squares(squares(&y.map(Interval::mag)));
        Some(Piece {
            moves: y,
            value: [value[0].min(corner[0]), value[1].min(corner[1])],
            touches: self.touches(&y),
            inherited: false,
        })
    }

    /// Upper bounds of the position (cm) and orientation (degrees) errors over the box of
    /// poses, refined until within `target` or `max_boxes` boxes of moves are examined; `None`
    /// when `∂B` could not be excluded. Also returns the boxes examined, and what the paving
    /// proved for the box and its sub-boxes (also when it did not close).
    ///
    /// With `parent` (a paving of this box of poses or of one containing it, whose `B` this
    /// paving shares), the parent's pieces hold every move of `B` reached from this box: they
    /// start the search, this box's own pieces as they are (the paving continues), a larger
    /// box's with their values there (bounds for this box too), each narrowed to this box's
    /// poses only when it comes first. A closed parent needs no closing; an open one's pieces
    /// still reaching `∂B` come first, as in a paving from scratch.
    pub fn bound(
        &self,
        target: [f64; 2],
        max_boxes: usize,
        parent: Option<&Paved>,
    ) -> (Option<[f64; 2]>, usize, Option<Paved>) {
        let rank = |p: Piece| Ranked {
            key: if p.touches {
                f64::INFINITY
            } else {
                key(p.value, target)
            },
            item: p,
        };
        let mut heap = BinaryHeap::new();
        let mut examined = 0;
        match parent {
            Some(p) => {
                let inherited = p.poses != self.poses;
                heap.extend(p.pieces.iter().map(|q| rank(Piece { inherited, ..*q })));
            }
            None => {
                heap.extend(self.piece(&self.outer).map(rank));
                examined += 1;
            }
        }
        // Rounds of up to BATCH boxes, the first ones of the queue, pieced in parallel (the
        // pieces join the queue in a fixed order: the same result on every run).
        let mut done = false;
        while examined < max_boxes && !done {
            // `∂B` not yet excluded after half the budget: the box of poses is too wide for its
            // second-order models (the caller splits it; its halves start from these pieces).
            if heap.peek().is_some_and(|t| t.item.touches) && examined * CLOSING_SHARE >= max_boxes
            {
                break;
            }
            let mut work: Vec<[Interval; 6]> = Vec::with_capacity(BATCH);
            while work.len() + 2 <= BATCH && examined + work.len() < max_boxes {
                let Some(top) = heap.pop() else { break };
                if top.key <= 1.0 {
                    heap.push(top);
                    done = true;
                    break;
                }
                let y = top.item.moves;
                if top.item.inherited {
                    work.push(y);
                    continue;
                }
                let fine = (0..6).all(|c| y[c].wid() <= FINEST * self.outer[c].wid());
                let Some((l, r)) = split_widest(&y, &self.outer).filter(|_| !fine) else {
                    heap.push(top);
                    done = true;
                    break;
                };
                work.extend([l, r]);
            }
            if work.is_empty() {
                break;
            }
            examined += work.len();
            let pieces: Vec<Option<Piece>> = work.par_iter().map(|b| self.piece(b)).collect();
            heap.extend(pieces.into_iter().flatten().map(rank));
        }
        let bound = heap.iter().fold([0.0f64; 2], |acc, q| {
            [acc[0].max(q.item.value[0]), acc[1].max(q.item.value[1])]
        });
        let paved = Paved {
            poses: self.poses,
            outer: self.outer,
            pieces: heap.into_iter().map(|q| q.item).collect(),
        };
        let closed = !paved.pieces.iter().any(|q| q.touches);
        (closed.then_some(bound), examined, Some(paved))
    }
}

/// The inverse of the nominal legs' Jacobian at the move `delta` (floating point: any matrix
/// serves in `T`).
fn chart(centre: &[[f64; 12]], delta: &[f64; 6]) -> Option<Matrix6<f64>> {
    Matrix6::from_fn(|i, k| ReachedChange.jacobian_x(delta, &centre[i])[k]).try_inverse()
}

/// `|d|²` and `|w|²` rounded up, from bounds of the components' magnitudes (`+∞` when one is
/// not finite).
fn squares(comp: &[f64; 6]) -> [f64; 2] {
    if !comp.iter().all(|v| v.is_finite()) {
        return [f64::INFINITY; 2];
    }
    let sq = |k: usize| {
        (k..k + 3)
            .fold(Interval::ZERO, |s, j| s + Interval::point(comp[j]).sqr())
            .sup()
    };
    [sq(0), sq(3)]
}

/// The largest errors of `δ = A + M s` over the box of moves, the box of poses and `s ∈ s`
/// (module documentation). `A = P ε_pose + R`, with `P` its linear terms in the pose's noise
/// symbols and `R` the rest (its range): `|d|²` and `|w|²` are convex in `(ε_pose, R, s)`, so
/// their largest values are at one of the 64 × 64 vertices of `ε_pose` and `s`, each component's
/// largest magnitude over `R` being `|mid R + P ε + M s| + rad R`. The sums are in floating point
/// with a margin far above their rounding errors (thirteen terms, each within the bound `S_r`).
fn vertex_value(m: &Matrix6<f64>, a: &[Form; 6], s: &[Interval; 6]) -> [f64; 2] {
    let rest: [Interval; 6] = core::array::from_fn(|r| a[r].linear_removed(6..12).range());
    if !rest.iter().chain(s).all(|v| v.is_bounded()) {
        return [f64::INFINITY; 2];
    }
    let pose: [[f64; 6]; 6] =
        core::array::from_fn(|r| core::array::from_fn(|k| a[r].linear()[6 + k]));
    let margin: [f64; 6] = core::array::from_fn(|r| {
        let size = (0..6).fold(rest[r].mid().abs(), |acc, k| {
            acc + pose[r][k].abs() + m[(r, k)].abs() * s[k].mag()
        });
        mul_up(size, 1e-13)
    });
    let moves: Vec<[f64; 6]> = (0..64u32)
        .map(|vertex| {
            core::array::from_fn(|r| {
                (0..6)
                    .map(|c| {
                        m[(r, c)]
                            * if vertex >> c & 1 == 1 {
                                s[c].sup()
                            } else {
                                s[c].inf()
                            }
                    })
                    .sum()
            })
        })
        .collect();
    // Each component's largest magnitude is `|mid R + P ε + M s| + pad`, the pad rounded up
    // once here rather than in the 4,096 vertex pairs.
    let pad: [f64; 6] = core::array::from_fn(|r| add_up(rest[r].rad(), margin[r]));
    let mut best = [0.0f64; 2];
    for signs in 0..64u32 {
        let shift: [f64; 6] = core::array::from_fn(|r| {
            (0..6).fold(rest[r].mid(), |acc, k| {
                acc + if signs >> k & 1 == 1 {
                    pose[r][k]
                } else {
                    -pose[r][k]
                }
            })
        });
        for ms in &moves {
            let mut sq = [0.0f64; 2];
            for r in 0..6 {
                let c = (shift[r] + ms[r]).abs() + pad[r];
                sq[r / 3] += c * c;
            }
            best = [best[0].max(sq[0]), best[1].max(sq[1])];
        }
    }
    // Three squares summed: within 5 units in the last place.
    errors_from_squares(best.map(|v| mul_up(v, 1.0 + 1e-14)))
}
