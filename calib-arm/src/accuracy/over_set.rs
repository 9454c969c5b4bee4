//! The tool-point error over the certified set (a calibrated file that carries one).
//!
//! The controller computes `p(q; θ̂)`; the real arm has some `θ*` in the certified set `S` and
//! its joints reach `q + e`, `|e_i| <= joint_deg`. Over a joint box `Q`, by the mean-value
//! theorem, the error's coordinate `r` is
//!
//! `d_r = Σ_j G_rj (θ*_j - θ̂_j) + Σ_i H_ri e_i`
//!
//! with `G ⊇ ∂p_r/∂θ` and `H ⊇ ∂p_r/∂q` over `Q` widened by the joint error and the hull of the
//! set and `θ̂`. Its largest and smallest values over the set are one linear program per piece
//! each ([`calib_core::SetQuery::max_linear`], safe bounds: the slopes' midpoints in the program,
//! their radii against the set's box), the joint error's term by its magnitude; so is the error's
//! component along the direction `u` of the worst instance found.
//! The error vector then lies in the box of the coordinates' ranges cut by the two planes of
//! `u·d`; its largest norm there (at a vertex: box corners and the planes' crossings of the
//! box's edges) bounds the error over `Q` — a branch and bound over the joints
//! ([`calib_core::maximize`]) makes it proved over the whole joint box. Lower bounds are
//! attained by certified parameter vectors (a catalogue: the set's points pushed along the
//! error's gradient at joints spread over the box), with exact joints.

use super::{norm, SearchPoint, ToolBracket, ToolInstance};
use crate::certification::{padded_index, ArmSet, MAX_JOINTS, NM, NX};
use crate::joint_space::JointSpace;
use crate::robot::Arm;
use crate::units::{deg_to_rad, rad_to_deg, to_deg};
use crate::Arm7Point;
use calib_core::{maximize, Interval, MaximumSettings, Objective, VectorModel};
use std::cell::Cell;
use std::time::Instant;

/// `a + b` rounded up.
fn add_up(a: f64, b: f64) -> f64 {
    (Interval::point(a) + Interval::point(b)).sup()
}

/// The box of the joints `q` (the tracked point's part exactly 0, so that the residual is the
/// point itself).
fn joints_box(q: &[Interval; MAX_JOINTS]) -> [Interval; NM] {
    core::array::from_fn(|k| if k < MAX_JOINTS { q[k] } else { Interval::ZERO })
}

/// Joint configurations whose error directions the catalogue's points are pushed along.
const CATALOGUE_CONFIGURATIONS: usize = 6;

/// The tool-point accuracy problem over a certified set.
pub struct SetToolAccuracy {
    joints: usize,
    set: ArmSet,
    /// `θ̂` (radians, padded).
    nominal: [f64; NX],
    /// The set's outer box, with `θ̂`.
    hull: [Interval; NX],
    /// The joint box (radians, padded joints at 0).
    domain: [Interval; MAX_JOINTS],
    /// The joint error half-width in radians, enclosed.
    joint_rad: Interval,
    /// Certified parameter vectors (the instances' geometries).
    catalogue: Vec<[f64; NX]>,
}

impl SetToolAccuracy {
    /// The problem for the calibrated `arm` (its values: what the controller computes with) over
    /// its certified `set`, on `space`, every joint within `joint_deg` of its command.
    pub fn new(arm: &Arm, set: ArmSet, space: &JointSpace, joint_deg: f64) -> Result<Self, String> {
        let joints = arm.joints.len();
        if space.ranges_deg.len() != joints {
            return Err(format!(
                "the joint space has {} ranges; the arm has {joints} joints",
                space.ranges_deg.len()
            ));
        }
        if !(joint_deg.is_finite() && joint_deg >= 0.0) {
            return Err(format!(
                "joint error {joint_deg}: expected a finite value >= 0"
            ));
        }
        let mut nominal = [0.0; NX];
        let units = crate::params::names(joints);
        for ((&p, v), (_, unit)) in padded_index(joints).iter().zip(arm.nominal()).zip(&units) {
            nominal[p] = match unit {
                crate::params::Unit::Deg => crate::units::to_rad(v),
                crate::params::Unit::Mm => v,
            };
        }
        let outer = set.outer().ok_or("the certified set is empty")?;
        let hull = core::array::from_fn(|j| outer[j].hull(Interval::point(nominal[j])));
        let mut domain = [Interval::ZERO; MAX_JOINTS];
        for (i, &[lo, hi]) in space.ranges_deg.iter().enumerate() {
            let (l, h) = (
                deg_to_rad(Interval::point(lo)),
                deg_to_rad(Interval::point(hi)),
            );
            domain[i] = Interval::new(l.inf(), h.sup());
        }
        let mut out = SetToolAccuracy {
            joints,
            set,
            nominal,
            hull,
            domain,
            joint_rad: deg_to_rad(Interval::point(joint_deg)),
            catalogue: Vec::new(),
        };
        out.fill_catalogue();
        Ok(out)
    }

    /// The catalogue: the set's points, pushed along `±∇_θ p_r` at joints spread over the box.
    fn fill_catalogue(&mut self) {
        for k in 0..CATALOGUE_CONFIGURATIONS {
            let q: [f64; MAX_JOINTS] = core::array::from_fn(|i| {
                let d = self.domain[i];
                let t = (k as f64 + 0.5) / CATALOGUE_CONFIGURATIONS as f64;
                // A different fraction per joint, so the configurations spread.
                let f = (t * (i as f64 + 1.0) * 0.618_033_988_7).fract();
                d.inf() + f * d.wid()
            });
            let mut m = [0.0; NM];
            m[..MAX_JOINTS].copy_from_slice(&q);
            for e in Arm7Point.evaluate_rows(&self.nominal, &m) {
                for sign in [1.0, -1.0] {
                    self.set.extreme_point(&Arm7Point, &e.dx.map(|v| sign * v));
                }
            }
        }
        self.catalogue = self.set.points().iter().map(|p| p.x).collect();
    }

    /// The joint box searched (radians, padded).
    pub fn domain(&self) -> [Interval; MAX_JOINTS] {
        self.domain
    }

    /// An upper bound of the error over the joint box `q` (module documentation), with the cut
    /// along `u` when given. `+∞` when an enclosure failed.
    fn upper(&self, q: &[Interval; MAX_JOINTS], u: Option<[f64; 3]>) -> f64 {
        // The real arm's joints lie within the joint error of the box.
        let widened: [Interval; MAX_JOINTS] = core::array::from_fn(|i| {
            q[i] + Interval::new(-self.joint_rad.sup(), self.joint_rad.sup())
        });
        let rows = Arm7Point.evaluate_rows_interval(&self.hull, &joints_box(&widened));
        // p(q + e; θ) - p(q; θ̂) = ∇_θ p (θ - θ̂) + ∇_q p e, each gradient over the boxes.
        let encoder: [f64; 3] = core::array::from_fn(|r| {
            (0..self.joints)
                .fold(Interval::ZERO, |s, i| s + rows[r].dm[i] * self.joint_rad)
                .mag()
        });
        let mut query = self.set.query();
        let mut range = |slopes: &[Interval; NX], extra: f64| -> Interval {
            let up = query.max_linear(slopes, &self.nominal).upper;
            let down = query.max_linear(&slopes.map(|s| -s), &self.nominal).upper;
            let hi = add_up(up, extra);
            let lo = -add_up(down, extra);
            if lo.is_finite() && hi.is_finite() && lo <= hi {
                Interval::new(lo, hi)
            } else {
                Interval::ENTIRE
            }
        };
        let boxes: [Interval; 3] = core::array::from_fn(|r| range(&rows[r].dx, encoder[r]));
        let cut = u.map(|u| {
            let slopes = core::array::from_fn(|j| {
                (0..3).fold(Interval::ZERO, |s, r| {
                    s + Interval::point(u[r]) * rows[r].dx[j]
                })
            });
            let extra = (0..3).fold(Interval::ZERO, |s, r| {
                s + Interval::point(u[r].abs()) * Interval::point(encoder[r])
            });
            (u, range(&slopes, extra.sup()))
        });
        largest_norm(&boxes, cut)
    }

    /// The error `p(q; θ) - p(q; θ̂)` at exact joints `q`, enclosed.
    fn error_at(&self, q: &[f64; MAX_JOINTS], theta: &[f64; NX]) -> [Interval; 3] {
        let m = joints_box(&q.map(Interval::point));
        let real = Arm7Point.residuals_interval(&theta.map(Interval::point), &m);
        let nominal = Arm7Point.residuals_interval(&self.nominal.map(Interval::point), &m);
        core::array::from_fn(|r| real[r] - nominal[r])
    }

    /// The catalogue's geometry with the largest error at `q` (floating point), and its error.
    fn best(&self, q: &[f64; MAX_JOINTS]) -> ([f64; NX], f64) {
        let mut m = [0.0; NM];
        m[..MAX_JOINTS].copy_from_slice(q);
        let nominal = Arm7Point.residuals(&self.nominal, &m);
        self.catalogue
            .iter()
            .map(|t| {
                let p = Arm7Point.residuals(t, &m);
                (*t, norm(core::array::from_fn(|r| p[r] - nominal[r])))
            })
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((self.nominal, 0.0))
    }

    /// The instance at `q` with the catalogue's best geometry: its error, enclosed, rounded down.
    fn instance(&self, q: &[f64; MAX_JOINTS]) -> ToolInstance {
        let (theta, _) = self.best(q);
        let e = self.error_at(q, &theta);
        let value = (e[0].sqr() + e[1].sqr() + e[2].sqr()).sqrt().inf();
        let index = padded_index(self.joints);
        ToolInstance {
            joints_deg: q[..self.joints].iter().map(|v| to_deg(*v)).collect(),
            joints_rad: q[..self.joints].to_vec(),
            theta: index.iter().map(|&p| Interval::point(theta[p])).collect(),
            error: e.map(|v| v.mid()),
            value: if value.is_nan() { 0.0 } else { value.max(0.0) },
        }
    }

    /// A local search over the joints from `x` for the largest error of the catalogue.
    fn search(&self, x: &SearchPoint) -> [f64; MAX_JOINTS] {
        let clamp = |q: [f64; MAX_JOINTS]| -> [f64; MAX_JOINTS] {
            core::array::from_fn(|k| q[k].clamp(self.domain[k].inf(), self.domain[k].sup()))
        };
        let mut best = (clamp(*x), self.best(&clamp(*x)).1);
        let mut step = 0.25;
        while step >= 1e-4 {
            let mut moved = false;
            for k in 0..self.joints {
                for sign in [-1.0, 1.0] {
                    let mut q = best.0;
                    q[k] += sign * step * self.domain[k].wid();
                    let q = clamp(q);
                    let v = self.best(&q).1;
                    if v > best.1 {
                        best = (q, v);
                        moved = true;
                    }
                }
            }
            if !moved {
                step /= 2.0;
            }
        }
        best.0
    }
}

/// The largest norm of a vector in the box `b` whose component along the unit `u` lies in
/// `cut`: at a vertex of that polytope — a corner of the box, or a crossing of a box edge with
/// a cut plane. Rounded up (sums of squares in interval arithmetic); `+∞` for an unbounded box.
fn largest_norm(b: &[Interval; 3], cut: Option<([f64; 3], Interval)>) -> f64 {
    if b.iter().any(|v| !v.is_bounded() || v.is_empty()) {
        return f64::INFINITY;
    }
    let norm_up = |p: [Interval; 3]| (p[0].sqr() + p[1].sqr() + p[2].sqr()).sqrt().sup();
    let corners = (0..8).map(|c| {
        core::array::from_fn(|r| {
            if c >> r & 1 == 1 {
                b[r].sup()
            } else {
                b[r].inf()
            }
        })
    });
    let Some((u, h)) = cut.filter(|(_, h)| h.is_bounded()) else {
        return corners
            .map(|p: [f64; 3]| norm_up(p.map(Interval::point)))
            .fold(0.0, f64::max);
    };
    // The cut in floating point decides which vertices to take; each is then enclosed with the
    // rounding of its construction, and any box corner outside the cut by rounding is kept, so
    // the maximum over the candidates is at least the polytope's.
    let dot = |p: &[f64; 3]| u[0] * p[0] + u[1] * p[1] + u[2] * p[2];
    let slack = 1e-12 * (b.iter().map(|v| v.mag()).sum::<f64>() + 1.0);
    let mut best = 0.0f64;
    for p in corners {
        let d = dot(&p);
        if d <= h.sup() + slack && d >= h.inf() - slack {
            best = best.max(norm_up(p.map(Interval::point)));
        }
    }
    for axis in 0..3 {
        if u[axis] == 0.0 {
            continue;
        }
        for c in 0..4 {
            let others: Vec<usize> = (0..3).filter(|&r| r != axis).collect();
            let mut p = [Interval::ZERO; 3];
            for (bit, &r) in others.iter().enumerate() {
                p[r] = Interval::point(if c >> bit & 1 == 1 {
                    b[r].sup()
                } else {
                    b[r].inf()
                });
            }
            for level in [h.inf(), h.sup()] {
                // u·p = level along the edge: p_axis = (level - Σ u_r p_r) / u_axis.
                let rest = others.iter().fold(Interval::point(level), |s, &r| {
                    s - Interval::point(u[r]) * p[r]
                });
                let along = rest / Interval::point(u[axis]);
                let on_edge = along.intersection(b[axis]);
                if on_edge.is_empty() {
                    continue;
                }
                p[axis] = on_edge;
                best = best.max(norm_up(p));
            }
        }
    }
    if best == 0.0 {
        // Rounding left no candidate: the box's corners bound it.
        return largest_norm(b, None);
    }
    best
}

/// The error as a function of the joints, for [`maximize`].
struct SetToolError<'a> {
    problem: &'a SetToolAccuracy,
    /// The direction of the worst error found so far (the cut of the bound).
    direction: Cell<Option<[f64; 3]>>,
}

impl Objective<MAX_JOINTS> for SetToolError<'_> {
    fn enclose(&self, q: &[Interval; MAX_JOINTS]) -> Interval {
        Interval::new(0.0, self.problem.upper(q, self.direction.get()))
    }

    fn at(&self, x: &SearchPoint) -> Interval {
        let upper = self
            .problem
            .upper(&x.map(Interval::point), self.direction.get());
        let i = self.problem.instance(x);
        if i.value > 0.0 && i.value <= upper {
            Interval::new(i.value, upper)
        } else {
            Interval::new(0.0, upper)
        }
    }

    fn split_reference(&self, domain: &[Interval; MAX_JOINTS]) -> [Interval; MAX_JOINTS] {
        let widest = domain
            .iter()
            .map(|v| v.wid())
            .fold(f64::MIN_POSITIVE, f64::max);
        [Interval::new(0.0, widest); MAX_JOINTS]
    }

    fn improve(&self, x: &SearchPoint) -> Option<(SearchPoint, f64)> {
        let q = self.problem.search(x);
        let i = self.problem.instance(&q);
        let n = norm(i.error);
        if n > 0.0 {
            self.direction.set(Some(i.error.map(|v| v / n)));
        }
        Some((q, i.value))
    }
}

/// Brackets the tool-point error over the certified set (module documentation).
pub fn certify_set_accuracy(
    problem: &SetToolAccuracy,
    settings: &super::ToolAccuracySettings,
) -> ToolBracket {
    let start = Instant::now();
    let objective = SetToolError {
        problem,
        direction: Cell::new(None),
    };
    let m = maximize(
        &objective,
        &problem.domain,
        &MaximumSettings {
            rel_tol: settings.rel_tol,
            abs_tol: 0.0,
            max_boxes: settings.max_set_boxes,
        },
    );
    let worst = problem.instance(&m.argmax);
    let lower = worst.value.max(m.lower);
    ToolBracket {
        upper: m.upper.max(lower),
        lower,
        worst: Some(worst).filter(|w| w.value > 0.0),
        frontier_deg: m.frontier[..problem.joints]
            .iter()
            .map(|v| {
                let d = rad_to_deg(*v);
                [d.inf(), d.sup()]
            })
            .collect(),
        converged: m.converged,
        boxes: m.boxes,
        seconds: start.elapsed().as_secs_f64(),
    }
}
