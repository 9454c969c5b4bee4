//! The enclosures behind the accuracy certificate: per box of poses, the legs' length errors
//! over every geometry of the certified box; per pose, an explicit worst instance.
//!
//! Leg `i` has the nominal geometry `θ̂_i` the controller loads and a true geometry `θ*_i`
//! somewhere in the box `Θ_i` of the robot file. At a pose `X = (p, q)` (`q` the Rodrigues vector)
//! the controller commands `L_i(X; θ̂_i)`; the real leg would need `L_i(X; θ*_i)`. The leg-length
//! error `ΔL_i(X, θ*) = L_i(X; θ*) - L_i(X; θ̂)` is enclosed over a box of poses and all of `Θ_i` by
//! the natural enclosure of [`super::leg_length_error`] (written without cancellation)
//! intersected with its mean-value form about the box's centre. Since `L_i` is convex in `(a, b)`
//! and affine in `l`, its largest value over `Θ_i` is at a vertex: instances take the vertex the
//! gradient's signs point to.

use super::model::{LegLengthError, LegReading};
use crate::files::LegSpec;
use crate::measurement::measured;
use crate::workspace::Workspace;
use calib_core::{Interval, Model};

/// The most rounds of [`AccuracyProblem::climb`].
const MAX_CLIMB_ROUNDS: usize = 500;

/// A pose as `(p_x, p_y, p_z, q_1, q_2, q_3)`: centre (cm) and Rodrigues vector.
pub type PoseVector = [f64; 6];

/// A box of poses.
pub type PoseBox = [Interval; 6];

/// One leg's geometry: what the controller loads and the box the real leg lies in.
#[derive(Clone, Debug, PartialEq)]
struct LegBounds {
    /// `θ̂`: the robot file's values, as the controller loads them.
    nominal: [f64; 7],
    /// `Θ`: an enclosure of nominal ± radius (decimal values enclosed).
    theta: [Interval; 7],
    /// Per parameter, the box's lower and upper ends moved inward past rounding (the vertices
    /// of instances), or, for a fixed parameter, the enclosure of its value.
    vertex: [[Interval; 7]; 2],
}

impl LegBounds {
    fn new(spec: &LegSpec) -> LegBounds {
        let nominal = spec.nominal.params();
        let theta: [Interval; 7] = core::array::from_fn(|j| measured(nominal[j], spec.radius[j]));
        let inward = |j: usize, up: bool| {
            let (v, r) = (Interval::point(nominal[j]), Interval::point(spec.radius[j]));
            if spec.radius[j] == 0.0 {
                return theta[j];
            }
            // The value and the radius are within half an ulp of their decimals: two ulps of the
            // sum inward stay inside the decimal box (and never pass the nominal value).
            let end = if up {
                (v + r).inf().next_down().next_down().max(nominal[j])
            } else {
                (v - r).sup().next_up().next_up().min(nominal[j])
            };
            Interval::point(end)
        };
        LegBounds {
            nominal,
            theta,
            vertex: [false, true].map(|up| core::array::from_fn(|j| inward(j, up))),
        }
    }
}

/// The accuracy problem of a robot file on a workspace (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct AccuracyProblem {
    legs: Vec<LegBounds>,
    /// The pose box searched: the workspace's position ranges and the cube `|q_j| <= tan(tilt/2)`.
    domain: PoseBox,
    /// `tan(tilt/2)²`, enclosed.
    tilt_sq: Interval,
    /// The stroke, when given.
    stroke: Option<[f64; 2]>,
    /// The position ranges as read (for the feasibility of instance poses).
    ranges: [[f64; 2]; 3],
}

fn thin<const N: usize>(x: &[f64; N]) -> [Interval; N] {
    x.map(Interval::point)
}

impl AccuracyProblem {
    /// The problem for `robot` on `workspace`.
    pub fn new(robot: &[LegSpec], workspace: &Workspace) -> AccuracyProblem {
        let half_tilt = measured(workspace.tilt_deg, 0.0) * Interval::PI / Interval::point(360.0);
        let t = half_tilt.tan();
        let widen = |[lo, hi]: [f64; 2]| Interval::new(lo.next_down(), hi.next_up());
        let cube = Interval::new(-t.sup(), t.sup());
        AccuracyProblem {
            legs: robot.iter().map(LegBounds::new).collect(),
            domain: [
                widen(workspace.x),
                widen(workspace.y),
                widen(workspace.z),
                cube,
                cube,
                cube,
            ],
            tilt_sq: t.sqr(),
            stroke: workspace.stroke,
            ranges: [workspace.x, workspace.y, workspace.z],
        }
    }

    /// The values `θ̂_i` the controller loads for leg `i`.
    pub(crate) fn nominal(&self, i: usize) -> &[f64; 7] {
        &self.legs[i].nominal
    }

    /// The box `Θ_i` the real leg `i` lies in (decimal bounds enclosed).
    pub(crate) fn theta(&self, i: usize) -> &[Interval; 7] {
        &self.legs[i].theta
    }

    /// The number of legs.
    pub fn legs(&self) -> usize {
        self.legs.len()
    }

    /// The box of poses searched.
    pub fn domain(&self) -> PoseBox {
        self.domain
    }

    /// The commanded reading of leg `i` over the box (nominal geometry).
    fn commanded(&self, i: usize, x: &PoseBox) -> Interval {
        LegReading.residual_interval(&thin(&self.legs[i].nominal), x)
    }

    /// Whether the box may hold a pose of the workspace (`false` is a proof that it holds none).
    pub fn may_be_feasible(&self, x: &PoseBox) -> bool {
        let q_sq = x[3].sqr() + x[4].sqr() + x[5].sqr();
        if q_sq.inf() > self.tilt_sq.sup() {
            return false;
        }
        match self.stroke {
            None => true,
            Some([lo, hi]) => (0..self.legs.len()).all(|i| {
                let r = self.commanded(i, x);
                !(r.sup() < lo.next_down() || r.inf() > hi.next_up())
            }),
        }
    }

    /// Whether the pose is proved to lie in the workspace.
    pub fn proved_feasible(&self, x: &PoseVector) -> bool {
        let inside = |v: f64, [lo, hi]: [f64; 2]| lo.next_up() <= v && v <= hi.next_down();
        if !(0..3).all(|k| inside(x[k], self.ranges[k])) {
            return false;
        }
        let q = thin(&[x[3], x[4], x[5]]);
        if (q[0].sqr() + q[1].sqr() + q[2].sqr()).sup() > self.tilt_sq.inf() {
            return false;
        }
        match self.stroke {
            None => true,
            Some(s) => (0..self.legs.len()).all(|i| {
                let r = self.commanded(i, &thin(x));
                inside(r.inf(), s) && inside(r.sup(), s)
            }),
        }
    }

    /// The pose-and-nominal inputs `m = (X, θ̂_i)` of [`LegLengthError`] over the box `x`.
    fn inputs(&self, i: usize, x: &PoseBox) -> [Interval; 13] {
        let nominal = &self.legs[i].nominal;
        core::array::from_fn(|k| {
            if k < 6 {
                x[k]
            } else {
                Interval::point(nominal[k - 6])
            }
        })
    }

    /// An enclosure of `ΔL_i(X, θ)` over the poses of `x` and the geometries `theta`: the
    /// natural enclosure intersected with the mean-value form about the centre of both.
    fn mean_value(&self, i: usize, x: &PoseBox, theta: &[Interval; 7]) -> Interval {
        let e = LegLengthError.evaluate_interval(theta, &self.inputs(i, x));
        let xc = x.map(|v| v.mid());
        let tc = theta.map(|v| v.mid());
        let mut mv = LegLengthError.residual_interval(&thin(&tc), &self.inputs(i, &thin(&xc)));
        for j in 0..7 {
            mv += e.dx[j] * (theta[j] - Interval::point(tc[j]));
        }
        for k in 0..6 {
            mv += e.dm[k] * (x[k] - Interval::point(xc[k]));
        }
        let both = e.value.intersection(mv);
        if both.is_empty() || both.inf().is_nan() || both.sup().is_nan() {
            e.value
        } else {
            both
        }
    }

    /// An enclosure of leg `i`'s length error `ΔL_i(X, θ*)` over the poses of `x` and every
    /// `θ*` in its box (see the module documentation).
    pub fn leg_error(&self, i: usize, x: &PoseBox) -> Interval {
        self.mean_value(i, x, &self.legs[i].theta)
    }

    /// An enclosure of `f_i(X) = max_{θ* ∈ Θ_i} |ΔL_i(X, θ*)|` over the poses of `x`.
    ///
    /// Where `∂ΔL_i/∂θ_j` keeps its sign over the box (and all of `Θ_i`), `ΔL_i` is monotone in
    /// `θ_j`, so its largest and smallest values over `Θ_i` have `θ_j` at an end. With `θ↑`
    /// (`θ↓`) those ends — as boxes only as wide as rounding, from the inward vertex to the
    /// outward enclosure's end — and the whole range of the other parameters,
    /// `f_i ∈ [max(ΔL_i(X, θ↑), -ΔL_i(X, θ↓))]`, each enclosed by its mean-value form: without
    /// the overestimation of an interval over every parameter.
    pub fn leg_bounds(&self, i: usize, x: &PoseBox) -> Interval {
        let leg = &self.legs[i];
        let e = LegLengthError.evaluate_interval(&leg.theta, &self.inputs(i, x));
        let end = |up: bool| -> [Interval; 7] {
            core::array::from_fn(|j| {
                let g = e.dx[j];
                if !(g.inf() > 0.0 || g.sup() < 0.0) {
                    // The sign is not known on this box: the whole range of the parameter.
                    return leg.theta[j];
                }
                let rising = (g.inf() > 0.0) == up;
                let outer = Interval::point(if rising {
                    leg.theta[j].sup()
                } else {
                    leg.theta[j].inf()
                });
                outer.hull(leg.vertex[usize::from(rising)][j])
            })
        };
        let u = self.mean_value(i, x, &end(true));
        let d = -self.mean_value(i, x, &end(false));
        Interval::new(u.inf().max(d.inf()).max(0.0), u.sup().max(d.sup()).max(0.0))
    }

    /// The vertex of leg `i`'s box where `ΔL_i` at `x` is largest (`up`) or smallest, by the
    /// signs of its gradient at the nominal geometry.
    pub(crate) fn vertex(&self, i: usize, x: &PoseVector, up: bool) -> [Interval; 7] {
        let leg = &self.legs[i];
        let m: [f64; 13] = core::array::from_fn(|k| if k < 6 { x[k] } else { leg.nominal[k - 6] });
        let g = LegLengthError.jacobian_x(&leg.nominal, &m);
        core::array::from_fn(|j| leg.vertex[usize::from((g[j] > 0.0) == up)][j])
    }

    /// `|ΔL_i|` at the pose `x` with the geometry `theta`, rounded down.
    fn error_at(&self, i: usize, x: &PoseVector, theta: &[Interval; 7]) -> f64 {
        LegLengthError
            .residual_interval(theta, &self.inputs(i, &thin(x)))
            .mig()
    }

    /// The largest `|ΔL_i|` of the two extreme vertices at `x` (a floating-point estimate, for
    /// the search).
    fn estimate(&self, i: usize, x: &PoseVector) -> f64 {
        [true, false]
            .map(|up| {
                let t = self.vertex(i, x, up).map(|v| v.mid());
                let leg = &self.legs[i];
                let m: [f64; 13] =
                    core::array::from_fn(|k| if k < 6 { x[k] } else { leg.nominal[k - 6] });
                LegLengthError.residual(&t, &m).abs()
            })
            .into_iter()
            .fold(0.0, f64::max)
    }

    /// A local search for the largest `score` from the pose `x` (proved inside the workspace)
    /// over poses proved inside it: steps along each coordinate, rotations projected back onto
    /// the largest tilt, halving down to 1e-7 of the workspace; jumps to the position bounds and
    /// out to the largest tilt; at most 500 rounds.
    pub(crate) fn climb(&self, x: &PoseVector, score: impl Fn(&PoseVector) -> f64) -> PoseVector {
        let mut best = (*x, score(x));
        let widths = self.domain.map(|v| v.wid());
        let t_max = self.tilt_sq.inf().sqrt() * (1.0 - 1e-9);
        // Onto the ball |q| <= t_max: rotations larger than the tilt are not poses.
        let project = |mut y: PoseVector| {
            let n = (y[3].powi(2) + y[4].powi(2) + y[5].powi(2)).sqrt();
            if n > t_max {
                for k in 3..6 {
                    y[k] *= t_max / n;
                }
            }
            y
        };
        let mut step = 0.25;
        // A ridge may be climbed in ever smaller gains: the rounds are capped.
        let mut rounds = 0;
        while step >= 1e-7 && rounds < MAX_CLIMB_ROUNDS {
            rounds += 1;
            let mut tries: Vec<PoseVector> = Vec::with_capacity(20);
            for k in 0..6 {
                for sign in [-1.0, 1.0] {
                    let mut y = best.0;
                    y[k] += sign * step * widths[k];
                    tries.push(project(y));
                }
            }
            // Straight to the position bounds, and out to the largest tilt along the axis.
            for k in 0..3 {
                for end in [self.ranges[k][0].next_up(), self.ranges[k][1].next_down()] {
                    let mut y = best.0;
                    y[k] = end;
                    tries.push(y);
                }
            }
            let n = (best.0[3].powi(2) + best.0[4].powi(2) + best.0[5].powi(2)).sqrt();
            if n > 0.0 {
                let mut y = best.0;
                for k in 3..6 {
                    y[k] *= t_max / n;
                }
                tries.push(y);
            }
            let mut moved = false;
            for y in tries {
                let v = score(&y);
                if v > best.1 && self.proved_feasible(&y) {
                    best = (y, v);
                    moved = true;
                }
            }
            if !moved {
                step /= 2.0;
            }
        }
        best.0
    }

    /// The worst instance of leg `i` found from the pose `x`: a local search (steps along each
    /// coordinate, jumps to the workspace's bounds) on the larger `|ΔL_i|` of the two extreme
    /// vertices, then the vertex with the larger `|ΔL_i|`. `None` when `x` is not proved to lie
    /// in the workspace.
    pub fn instance(&self, i: usize, x: &PoseVector) -> Option<Instance> {
        if !self.proved_feasible(x) {
            return None;
        }
        let x = self.climb(x, |y| self.estimate(i, y));
        let (value, theta) = [true, false]
            .map(|up| {
                let theta = self.vertex(i, &x, up);
                (self.error_at(i, &x, &theta), theta)
            })
            .into_iter()
            .max_by(|a, b| a.0.total_cmp(&b.0))?;
        Some(Instance {
            pose: x,
            theta,
            value,
        })
    }
}

/// An explicit worst-case instance of a leg: a pose of the workspace and a true geometry in the
/// leg's box whose length error is at least `value`.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// The commanded pose `(p, q)`, proved to lie in the workspace.
    pub pose: PoseVector,
    /// The true geometry `θ*` (points inside the box; a fixed parameter as the enclosure of its
    /// decimal value).
    pub theta: [Interval; 7],
    /// `|L(X; θ*) - L(X; θ̂)|`, rounded down (cm).
    pub value: f64,
}
