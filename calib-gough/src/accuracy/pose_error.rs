//! The platform's position and orientation errors: certified lower bounds by explicit instances.
//!
//! At a commanded pose `X = (p, R)` the controller sends the readings `L_i(X; θ̂_i)`; the actuators
//! realise them within `± ε`; the real robot, with geometry `θ*`, reaches the pose `X'` with
//! `L_i(X'; θ*_i) = L_i(X; θ̂_i) + e_i` — the solution connected to `X`. Writing
//! `X' = (p + d, R(w) R)` (`w` the Rodrigues vector of the rotation error, in the base frame), the
//! position error is `|d|` and the orientation error the angle `2 atan |w|`.
//!
//! [`pose_error_instances`] finds, for each of the two errors, an explicit instance
//! `(X, θ*, e)` with a large error — a search on the first-order error `δ ≈ J⁻¹ s`
//! (`s_i = L_i(X; θ̂_i) + e_i - L_i(X; θ*_i)` taken at the vertices that make each `s_i` extreme),
//! then the exact forward kinematics — and proves the pose reached: a parametric Krawczyk test
//! follows the homotopy `t ↦ L_i(X'; θ*_i) = (1 - t) L_i(X; θ*_i) + t (L_i(X; θ̂_i) + e_i)` from
//! `X' = X` at `t = 0` to `t = 1`, each segment of `t` proving a unique solution in a box that
//! contains the previous segment's end, so the enclosed `X'` is the solution connected to `X`.
//! The instance's error is then a proved lower bound of the worst error over the workspace.
//! Where the path cannot be proved (near a singular pose) the instance is not reported.
//!
//! [`pose_errors`] adds the upper bounds of [`super::pose_bound`], proved over the whole workspace
//! where the reached pose can be enclosed.

use super::enclosure::{AccuracyProblem, PoseVector};
use super::model::LegLengthError;
use super::pose_bound::{pose_error_bounds, PoseBoundSettings, PoseErrorBounds, ReachedChange};
use calib_core::{Interval, Model};
use nalgebra::{Matrix6, Vector6};
use rand::{Rng, SeedableRng};

/// Which error an instance is searched for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PoseErrorKind {
    /// `|p' - p|` (cm).
    Position,
    /// The rotation angle of `R'ᵀ R` (degrees).
    Orientation,
}

/// An explicit instance of the platform's pose error, its reached pose proved.
#[derive(Clone, Debug, PartialEq)]
pub struct PoseErrorInstance {
    /// The commanded pose `X = (p, q)`, proved to lie in the workspace.
    pub commanded: PoseVector,
    /// Per leg, the true geometry `θ*` (a vertex of the leg's box).
    pub theta: Vec<[Interval; 7]>,
    /// Per leg, the actuator error `e_i` (within `± ε`).
    pub actuator: Vec<f64>,
    /// An enclosure of the move `δ = (d, w)` to the reached pose `X' = (p + d, R(w) R(q))`,
    /// the solution connected to `X` (unique in this box).
    pub reached: [Interval; 6],
    /// `|d|`, rounded down (cm): a lower bound of the position error over the workspace.
    pub position: f64,
    /// `2 atan |w|`, rounded down (degrees): a lower bound of the orientation error.
    pub orientation_deg: f64,
    /// Segments of the homotopy proved.
    pub segments: usize,
}

/// The instances of the two errors (`None` where no instance was proved).
#[derive(Clone, Debug, PartialEq)]
pub struct PoseErrors {
    /// The instance with the largest position error found.
    pub position: Option<PoseErrorInstance>,
    /// The instance with the largest orientation error found.
    pub orientation: Option<PoseErrorInstance>,
    /// Without a position instance: the commanded pose of the worst candidate, whose path to
    /// the reached pose could not be proved (a singular pose may lie on it).
    pub position_unproved: Option<PoseVector>,
    /// The same for the orientation error.
    pub orientation_unproved: Option<PoseVector>,
    /// The upper bounds over the workspace, when computed ([`pose_errors`]).
    pub bounds: Option<PoseErrorBounds>,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// Random starting poses of the search.
const STARTS: usize = 400;
/// Starting poses climbed.
const CLIMBED: usize = 4;
/// Vertex patterns followed with the exact forward kinematics.
const EXACT: usize = 4;
/// Steps of `t` when a candidate's move is followed in floating point.
const CONTINUATION: usize = 4;

/// The inputs `m = (X, a, b)` of [`ReachedChange`] (`l` cancels in a leg's change).
fn inputs<T: Copy>(x: &[T; 6], theta: &[T; 7]) -> [T; 12] {
    core::array::from_fn(|k| if k < 6 { x[k] } else { theta[k - 6] })
}

/// The inputs `m = (X, θ̂)` of [`LegLengthError`].
fn error_inputs<T: Copy>(x: &[T; 6], nominal: &[T; 7]) -> [T; 13] {
    core::array::from_fn(|k| if k < 6 { x[k] } else { nominal[k - 6] })
}

/// The first-order candidates at a pose: per sign pattern of the legs, the geometry and actuator
/// error that make each `s_i` extreme, and `δ = J⁻¹ s` with `J` the nominal leg Jacobian.
struct FirstOrder {
    /// Per pattern (bit `i` set: `s_i` at its largest), `δ`.
    moves: Vec<Vector6<f64>>,
}

impl FirstOrder {
    fn at(problem: &AccuracyProblem, x: &PoseVector, eps: f64) -> Option<FirstOrder> {
        let n = problem.legs();
        if n != 6 {
            return None;
        }
        let mut jac = Matrix6::zeros();
        let mut ends = [[0.0; 2]; 6];
        for i in 0..6 {
            let nominal = problem.nominal(i);
            let g = ReachedChange.jacobian_x(&[0.0; 6], &inputs(x, nominal));
            for k in 0..6 {
                jac[(i, k)] = g[k];
            }
            for (end, up) in [(0, true), (1, false)] {
                let theta = problem.vertex(i, x, up).map(|v| v.mid());
                let error = LegLengthError.residual(&theta, &error_inputs(x, nominal));
                // `up`: the largest ΔL, so the smallest s; `e` at the same end.
                let e = if up { -eps } else { eps };
                ends[i][end] = e - error;
            }
        }
        let inverse = jac.try_inverse()?;
        let moves = (0..64u32)
            .map(|pattern| {
                let s = Vector6::from_fn(|i, _| ends[i][usize::from(pattern >> i & 1 == 1)]);
                inverse * s
            })
            .collect();
        Some(FirstOrder { moves })
    }

    fn size(kind: PoseErrorKind, m: &Vector6<f64>) -> f64 {
        match kind {
            PoseErrorKind::Position => m.fixed_rows::<3>(0).norm(),
            PoseErrorKind::Orientation => 2.0 * m.fixed_rows::<3>(3).norm().atan(),
        }
    }

    /// The patterns by decreasing first-order error.
    fn ranked(&self, kind: PoseErrorKind) -> Vec<(u32, f64)> {
        let mut r: Vec<(u32, f64)> = self
            .moves
            .iter()
            .enumerate()
            .map(|(p, m)| (p as u32, Self::size(kind, m)))
            .collect();
        r.sort_by(|a, b| b.1.total_cmp(&a.1));
        r
    }

    fn best(&self, kind: PoseErrorKind) -> f64 {
        self.moves
            .iter()
            .map(|m| Self::size(kind, m))
            .fold(0.0, f64::max)
    }
}

/// The concrete instance of a sign pattern at a pose: per leg the geometry and actuator error.
pub fn pattern_instance(
    problem: &AccuracyProblem,
    x: &PoseVector,
    pattern: u32,
    eps: f64,
) -> (Vec<[Interval; 7]>, Vec<f64>) {
    (0..problem.legs())
        .map(|i| {
            // Bit set: s_i largest, i.e. ΔL_i smallest and e_i = +ε.
            let high = pattern >> i & 1 == 1;
            let e = if high { eps } else { -eps };
            (problem.vertex(i, x, !high), e)
        })
        .unzip()
}

/// The error of `kind` of a sign pattern at `x`, from the floating-point forward kinematics (0
/// where Newton fails): the score of `search`'s second climb.
pub fn exact_size(
    problem: &AccuracyProblem,
    x: &PoseVector,
    pattern: u32,
    eps: f64,
    kind: PoseErrorKind,
) -> f64 {
    let (theta, actuator) = pattern_instance(problem, x, pattern, eps);
    Homotopy::new(problem, x, &theta, &actuator)
        .approximate_move()
        .map_or(0.0, |d| FirstOrder::size(kind, &d))
}

/// The homotopy of an instance: `H_i(δ, t) = G_i(δ) - t s_i` with `G_i(δ) = L_i(X + δ; θ*_i) -
/// L_i(X; θ*_i)` ([`ReachedChange`], without cancellation) and
/// `s_i ∋ L_i(X; θ̂_i) + e_i - L_i(X; θ*_i) = e_i - ΔL_i(X, θ*)`: the same path as
/// `L_i(X + δ; θ*_i) = (1 - t) L_i(X; θ*_i) + t (L_i(X; θ̂_i) + e_i)`.
struct Homotopy<'a> {
    x: [Interval; 6],
    theta: &'a [[Interval; 7]],
    shift: Vec<Interval>,
}

impl<'a> Homotopy<'a> {
    /// The homotopy of the instance `(x, θ*, e)`.
    fn new(
        problem: &AccuracyProblem,
        x: &PoseVector,
        theta: &'a [[Interval; 7]],
        actuator: &[f64],
    ) -> Homotopy<'a> {
        let xi = x.map(Interval::point);
        let shift = (0..problem.legs())
            .map(|i| {
                let nominal = problem.nominal(i).map(Interval::point);
                Interval::point(actuator[i])
                    - LegLengthError.residual_interval(&theta[i], &error_inputs(&xi, &nominal))
            })
            .collect();
        Homotopy {
            x: xi,
            theta,
            shift,
        }
    }

    /// The move at `t = 1` in floating point, followed from `δ = 0` in `CONTINUATION` steps of
    /// `t` (a candidate's error for the search; `None` where Newton fails).
    fn approximate_move(&self) -> Option<Vector6<f64>> {
        (1..=CONTINUATION).try_fold(Vector6::zeros(), |d, k| {
            self.solve(k as f64 / CONTINUATION as f64, &d)
                .map(|(d, _)| d)
        })
    }

    fn residual(&self, d: &[Interval; 6], t: Interval) -> Vec<Interval> {
        (0..6)
            .map(|i| {
                ReachedChange.residual_interval(d, &inputs(&self.x, &self.theta[i]))
                    - t * self.shift[i]
            })
            .collect()
    }

    fn jacobian(&self, d: &[Interval; 6]) -> [[Interval; 6]; 6] {
        core::array::from_fn(|i| {
            ReachedChange.jacobian_x_interval(d, &inputs(&self.x, &self.theta[i]))
        })
    }

    /// A floating-point solution at `t` from `guess` (Newton), with the inverse Jacobian there.
    fn solve(&self, t: f64, guess: &Vector6<f64>) -> Option<(Vector6<f64>, Matrix6<f64>)> {
        let mid = |v: &[Interval; 7]| v.map(|e| e.mid());
        let x = self.x.map(|v| v.mid());
        let mut d = *guess;
        for _ in 0..40 {
            let dd: [f64; 6] = core::array::from_fn(|k| d[k]);
            let mut jac = Matrix6::zeros();
            let mut g = Vector6::zeros();
            for i in 0..6 {
                let m = inputs(&x, &mid(&self.theta[i]));
                g[i] = ReachedChange.residual(&dd, &m) - t * self.shift[i].mid();
                let row = ReachedChange.jacobian_x(&dd, &m);
                for k in 0..6 {
                    jac[(i, k)] = row[k];
                }
            }
            let step = jac.lu().solve(&g)?;
            d -= step;
            if step.norm() <= 1e-14 * (1.0 + d.norm()) {
                break;
            }
        }
        let mut jac = Matrix6::zeros();
        let dd: [f64; 6] = core::array::from_fn(|k| d[k]);
        for i in 0..6 {
            let row = ReachedChange.jacobian_x(&dd, &inputs(&x, &mid(&self.theta[i])));
            for k in 0..6 {
                jac[(i, k)] = row[k];
            }
        }
        let inverse = jac.try_inverse()?;
        // Near a singular pose the solution or the preconditioner may not be finite.
        (d.iter().chain(inverse.iter()).all(|v| v.is_finite())).then_some((d, inverse))
    }

    /// The Krawczyk operator over `bx` for every `t` in `t`, about `c` with the preconditioner
    /// `inv`: every solution in `bx` lies in it; inside `bx`'s interior, exactly one does.
    fn krawczyk(
        &self,
        bx: &[Interval; 6],
        t: Interval,
        c: &Vector6<f64>,
        inv: &Matrix6<f64>,
    ) -> [Interval; 6] {
        let centre: [Interval; 6] = core::array::from_fn(|k| Interval::point(c[k]));
        let g = self.residual(&centre, t);
        let jac = self.jacobian(bx);
        core::array::from_fn(|r| {
            let mut k = centre[r];
            for i in 0..6 {
                k -= Interval::point(inv[(r, i)]) * g[i];
            }
            for col in 0..6 {
                let mut m = Interval::point(if r == col { 1.0 } else { 0.0 });
                for i in 0..6 {
                    m -= Interval::point(inv[(r, i)]) * jac[i][col];
                }
                k += m * (bx[col] - centre[col]);
            }
            k
        })
    }

    /// One segment `[t0, t1]` from the enclosure `prev` of the solution at `t0`: the enclosure
    /// of the solution at `t1`, or `None` when no box could be proved.
    fn segment(
        &self,
        prev: &[Interval; 6],
        t0: f64,
        t1: f64,
        guess: &Vector6<f64>,
    ) -> Option<([Interval; 6], Vector6<f64>)> {
        let t = Interval::new(t0, t1);
        let (c, inv) = self.solve(0.5 * (t0 + t1), guess)?;
        let (end, _) = self.solve(t1, &c)?;
        let mut bx: [Interval; 6] = core::array::from_fn(|k| {
            prev[k]
                .hull(Interval::point(c[k]))
                .hull(Interval::point(end[k]))
        });
        for _ in 0..12 {
            bx = bx.map(|v| {
                let r = 0.1 * v.wid() + 1e-12 + 1e-9 * v.mag();
                Interval::new(v.inf() - r, v.sup() + r)
            });
            let k = self.krawczyk(&bx, t, &c, &inv);
            if k.iter().zip(&bx).all(|(k, b)| k.is_interior_of(*b)) {
                // Unique for every t of the segment; the solution at t1 lies in K(t1) ∩ bx.
                let k1 = self.krawczyk(&bx, Interval::point(t1), &c, &inv);
                let e: [Interval; 6] = core::array::from_fn(|j| k1[j].intersection(bx[j]));
                if e.iter().any(|v| v.is_empty()) {
                    return None;
                }
                return Some((e, end));
            }
            bx = core::array::from_fn(|j| bx[j].hull(k[j]));
            if bx.iter().any(|v| !v.is_bounded()) {
                return None;
            }
        }
        None
    }

    /// Follows the homotopy from `δ = 0` at `t = 0` to `t = 1`: the enclosure of the solution
    /// connected to `X` at `t = 1` and the number of segments, or `None`.
    fn follow(&self) -> Option<([Interval; 6], usize)> {
        let mut enclosure = [Interval::ZERO; 6];
        let mut guess = Vector6::zeros();
        let (mut t, mut step, mut segments) = (0.0f64, 0.125f64, 0);
        while t < 1.0 {
            let t1 = (t + step).min(1.0);
            match self.segment(&enclosure, t, t1, &guess) {
                Some((e, end)) => {
                    enclosure = e;
                    guess = end;
                    t = t1;
                    segments += 1;
                    step = (step * 1.5).min(0.25);
                }
                None if step > 1.0 / 1024.0 => step /= 2.0,
                None => return None,
            }
        }
        // Tighten at t = 1 about the floating-point solution: every iterate still holds it.
        if let Some((c, inv)) = self.solve(1.0, &guess) {
            for _ in 0..4 {
                let k = self.krawczyk(&enclosure, Interval::ONE, &c, &inv);
                let next: [Interval; 6] = core::array::from_fn(|j| k[j].intersection(enclosure[j]));
                if next.iter().any(|v| v.is_empty()) {
                    break;
                }
                enclosure = next;
            }
        }
        Some((enclosure, segments))
    }
}

/// Proves the reached pose of the instance `(x, θ*, e)` (see the module documentation).
pub fn prove_instance(
    problem: &AccuracyProblem,
    x: &PoseVector,
    theta: Vec<[Interval; 7]>,
    actuator: Vec<f64>,
) -> Option<PoseErrorInstance> {
    let homotopy = Homotopy::new(problem, x, &theta, &actuator);
    let (reached, segments) = homotopy.follow()?;
    let norm = |v: &[Interval]| (v[0].sqr() + v[1].sqr() + v[2].sqr()).sqrt().inf();
    let w = norm(&reached[3..]);
    // atan below its libm value by far more than libm's error (a few ulps).
    let angle =
        Interval::point(2.0 * w.atan() * (1.0 - 1e-12)) * Interval::point(180.0) / Interval::PI;
    Some(PoseErrorInstance {
        commanded: *x,
        theta,
        actuator,
        reached,
        position: norm(&reached[..3]),
        orientation_deg: angle.inf().max(0.0),
        segments,
    })
}

/// The worst instance of `kind` found (see the module documentation), with the actuator error
/// `± eps` (0 when unknown), from the random starts of `seed`.
pub fn worst_instance(
    problem: &AccuracyProblem,
    kind: PoseErrorKind,
    eps: f64,
    seed: u64,
) -> Option<PoseErrorInstance> {
    search(problem, kind, eps, seed).0
}

/// [`worst_instance`], and without one the commanded pose of the worst candidate (whose path
/// could not be proved), if any pose of the workspace was found.
fn search(
    problem: &AccuracyProblem,
    kind: PoseErrorKind,
    eps: f64,
    seed: u64,
) -> (Option<PoseErrorInstance>, Option<PoseVector>) {
    let domain = problem.domain();
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let score = |x: &PoseVector| FirstOrder::at(problem, x, eps).map_or(0.0, |f| f.best(kind));
    let mut starts: Vec<(PoseVector, f64)> = (0..STARTS)
        .map(|_| core::array::from_fn(|k| rng.random_range(domain[k].inf()..=domain[k].sup())))
        .filter(|x| problem.proved_feasible(x))
        .map(|x| (x, score(&x)))
        .collect();
    starts.sort_by(|a, b| b.1.total_cmp(&a.1));
    let mut climbed: Vec<(PoseVector, f64)> = starts
        .iter()
        .take(CLIMBED)
        .map(|(x, _)| {
            let y = problem.climb(x, score);
            (y, score(&y))
        })
        .collect();
    climbed.sort_by(|a, b| b.1.total_cmp(&a.1));
    let value = |i: &PoseErrorInstance| match kind {
        PoseErrorKind::Position => i.position,
        PoseErrorKind::Orientation => i.orientation_deg,
    };
    let patterns = |x: &PoseVector| -> Vec<u32> {
        FirstOrder::at(problem, x, eps).map_or(Vec::new(), |f| {
            f.ranked(kind)
                .into_iter()
                .take(EXACT)
                .map(|p| p.0)
                .collect()
        })
    };
    let mut best: Option<PoseErrorInstance> = None;
    for (x, _) in climbed.iter().take(2) {
        // Where the moves are large the first-order error misleads: the pattern whose
        // floating-point error is largest is climbed again on that error.
        let exact = |y: &PoseVector, pattern: u32| exact_size(problem, y, pattern, eps, kind);
        let Some((top, _)) = patterns(x)
            .into_iter()
            .map(|p| (p, exact(x, p)))
            .max_by(|a, b| a.1.total_cmp(&b.1))
        else {
            continue;
        };
        let y = problem.climb(x, |y| exact(y, top));
        for pose in [x, &y] {
            for pattern in patterns(pose) {
                let (theta, actuator) = pattern_instance(problem, pose, pattern, eps);
                if let Some(i) = prove_instance(problem, pose, theta, actuator) {
                    if best.as_ref().is_none_or(|b| value(&i) > value(b)) {
                        best = Some(i);
                    }
                }
            }
        }
    }
    let unproved = match best {
        Some(_) => None,
        None => climbed.first().map(|c| c.0),
    };
    (best, unproved)
}

/// The instances of both errors for `problem` with the actuator error `± eps` as read (the
/// instances take the float below it, inside the decimal bound).
pub fn pose_error_instances(problem: &AccuracyProblem, eps: f64) -> PoseErrors {
    let start = std::time::Instant::now();
    let eps = if eps > 0.0 { eps.next_down() } else { 0.0 };
    let ((position, position_unproved), (orientation, orientation_unproved)) = rayon::join(
        || search(problem, PoseErrorKind::Position, eps, 1),
        || search(problem, PoseErrorKind::Orientation, eps, 2),
    );
    PoseErrors {
        position,
        orientation,
        position_unproved,
        orientation_unproved,
        bounds: None,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// Both errors bracketed: the instances of [`pose_error_instances`] (lower bounds) and the upper
/// bounds of [`pose_error_bounds`] over the workspace, refined towards them.
pub fn pose_errors(
    problem: &AccuracyProblem,
    eps: f64,
    settings: &PoseBoundSettings,
) -> PoseErrors {
    let mut errors = pose_error_instances(problem, eps);
    let lower = [
        errors.position.as_ref().map_or(0.0, |i| i.position),
        errors
            .orientation
            .as_ref()
            .map_or(0.0, |i| i.orientation_deg),
    ];
    let bounds = pose_error_bounds(problem, eps, lower, settings);
    errors.seconds += bounds.seconds;
    errors.bounds = Some(bounds);
    errors
}
