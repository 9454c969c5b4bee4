//! The tool-point error over the certified set (a calibrated file that carries one).
//!
//! The controller computes `p(q; θ̂)`; the real arm has some `θ*` in the certified set `S` and
//! its joints reach `q + e`, `|e_i| <= joint_deg`. Over a joint box `Q` (widened by the joint
//! error to `Q'`), with `δ = θ* - θ̂`, the mean-value theorem gives
//!
//! `p(q + e; θ*) - p(q; θ̂) = Σ_j g_j δ_j + Σ_i H_i e_i`
//!
//! with `g_j ⊇ ∂p/∂θ_j` over `Q' ×` the set's outer box (with `θ̂`) and `H ⊇ ∂p/∂q` there.
//!
//! **At the set's scale.** On joint boxes up to 1 rad wide, each `g_j` is a
//! second-order model in the joints' noise symbols `ε_i` ([`Quadratic`] carried through the
//! model's derivatives, [`calib_core::Jet`]): `g_j = c_j + Σ_i a_ji ε_i + Σ_{i<=k} b_jik ε_i
//! ε_k ± e_j`, `e_j` of third order. Along a unit direction `u`, the error's component is then
//! at most
//!
//! `h_S(ū) + Σ_i max_S |(u·a_i)·δ| + Σ_{i<=k} max_S |(u·b_ik)·δ| + Σ_j (|u|·e_j) max|δ_j|
//! + |u|·(encoder term)`,
//!
//! `ū_j = u·c_j`: the main term `h_S` — the support function of the set — is one linear program
//! per piece ([`calib_core::SetQuery::max_linear`], safe bounds), or, where that is enough to
//! discard the box, the bound of a parallelotope around the set aligned with what the data
//! determine ([`Parallelotope`]); the joints' terms, of first and second order in the box's
//! width, take the parallelotope; only the remainders `e_j` (the models' third-order remainders
//! and the curvature in `θ` over the outer box, of second order in the set's reach) meet the
//! outer box. Wider joint boxes take the interval slopes `g_j` (midpoints in the program, radii
//! against the box).
//!
//! The error vector's components along an orthonormal frame `u_1, u_2, u_3` — `u_1` the
//! direction of the largest error the catalogue shows at the box's centre — lie in three ranges,
//! so its norm is at most that of the ranges' farthest corner. A branch and bound over the joints
//! ([`calib_core::maximize`]) makes the bound proved over the whole joint box.
//!
//! Lower bounds are attained by certified parameter vectors (a catalogue: the set's points
//! pushed along the error's gradient at joints spread over the box, and at every configuration
//! where the search raises the lower bound), with exact joints.

use super::{norm, SearchPoint, ToolBracket, ToolInstance};
use crate::certification::{padded_index, ArmSet, MAX_JOINTS, NM, NX};
use crate::joint_space::JointSpace;
use crate::model::arm7_point;
use crate::robot::Arm;
use crate::units::{deg_to_rad, rad_to_deg, to_deg};
use crate::Arm7Point;
use calib_core::{
    maximize, Interval, Jet, MaximumSettings, Objective, Parallelotope, Quadratic, SlotQueries,
    VectorModel,
};
use std::cell::{Cell, RefCell};
use std::time::Instant;

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
    /// The set the bounds are proved over.
    set: ArmSet,
    /// A copy of it that collects the certified points of the lower bounds (pushes add points).
    pushes: RefCell<ArmSet>,
    /// `θ̂` (radians, padded).
    nominal: [f64; NX],
    /// The set's outer box, with `θ̂`.
    hull: [Interval; NX],
    /// `max |θ_j - θ̂_j|` over the set's outer box, rounded up.
    reach: [f64; NX],
    /// The parallelotope around the set (`None` if it could not be bounded).
    parallelotope: Option<Parallelotope<NX>>,
    /// The joint box (radians, padded joints at 0).
    domain: [Interval; MAX_JOINTS],
    /// The joint error half-width in radians, enclosed.
    joint_rad: Interval,
    /// Certified parameter vectors (the instances' geometries).
    catalogue: RefCell<Vec<[f64; NX]>>,
}

/// The ranges of the error's components along a frame, over a joint box.
type FrameRanges = [Interval; 3];

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
        let hull: [Interval; NX] =
            core::array::from_fn(|j| outer[j].hull(Interval::point(nominal[j])));
        let reach = core::array::from_fn(|j| (hull[j] - Interval::point(nominal[j])).mag());
        let mut domain = [Interval::ZERO; MAX_JOINTS];
        for (i, &[lo, hi]) in space.ranges_deg.iter().enumerate() {
            let (l, h) = (
                deg_to_rad(Interval::point(lo)),
                deg_to_rad(Interval::point(hi)),
            );
            domain[i] = Interval::new(l.inf(), h.sup());
        }
        let parallelotope = Parallelotope::around_along(&set, &nominal, &hints(&domain, &nominal));
        let out = SetToolAccuracy {
            joints,
            pushes: RefCell::new(set.clone()),
            set,
            nominal,
            hull,
            reach,
            parallelotope,
            domain,
            joint_rad: deg_to_rad(Interval::point(joint_deg)),
            catalogue: RefCell::new(Vec::new()),
        };
        out.fill_catalogue();
        Ok(out)
    }

    /// The catalogue: the set's points, pushed along `±∇_θ p_r` at joints spread over the box.
    fn fill_catalogue(&self) {
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
                    self.pushes
                        .borrow_mut()
                        .extreme_point(&Arm7Point, &e.dx.map(|v| sign * v));
                }
            }
        }
        self.refresh_catalogue();
    }

    /// The catalogue: every certified point the set holds.
    fn refresh_catalogue(&self) {
        *self.catalogue.borrow_mut() = self.pushes.borrow().points().iter().map(|p| p.x).collect();
    }

    /// Pushes the set along the error's gradient at `q` (the direction of the catalogue's largest
    /// error there), adding the certified point it reaches to the catalogue.
    fn push_at(&self, q: &[f64; MAX_JOINTS]) {
        let Some(u) = self.direction_at(q) else {
            return;
        };
        let mut m = [0.0; NM];
        m[..MAX_JOINTS].copy_from_slice(q);
        let rows = Arm7Point.evaluate_rows(&self.nominal, &m);
        let gradient: [f64; NX] =
            core::array::from_fn(|j| (0..3).map(|r| u[r] * rows[r].dx[j]).sum());
        if self
            .pushes
            .borrow_mut()
            .extreme_point(&Arm7Point, &gradient)
            .is_some()
        {
            self.refresh_catalogue();
        }
    }

    /// Per joint, how fast the catalogue's largest error at the box's centre changes with that
    /// joint (its slope plus its curvature times the box's half-width, by central differences):
    /// where to split the box.
    fn error_variation(&self, q: &[Interval; MAX_JOINTS]) -> [f64; MAX_JOINTS] {
        let centre = q.map(|v| v.mid());
        let (theta, _) = self.best(&centre);
        let error = |q: &[f64; MAX_JOINTS]| -> [f64; 3] {
            let mut m = [0.0; NM];
            m[..MAX_JOINTS].copy_from_slice(q);
            let (p, p0) = (
                Arm7Point.residuals(&theta, &m),
                Arm7Point.residuals(&self.nominal, &m),
            );
            core::array::from_fn(|r| p[r] - p0[r])
        };
        let d0 = error(&centre);
        let h = 1e-4;
        core::array::from_fn(|i| {
            if i >= self.joints || q[i].wid() == 0.0 {
                return 0.0;
            }
            let (mut up, mut down) = (centre, centre);
            up[i] += h;
            down[i] -= h;
            let (du, dd) = (error(&up), error(&down));
            let slope = norm(core::array::from_fn(|r| (du[r] - dd[r]) / (2.0 * h)));
            let curvature = norm(core::array::from_fn(|r| {
                (du[r] - 2.0 * d0[r] + dd[r]) / (h * h)
            }));
            slope + 0.5 * curvature * q[i].rad()
        })
    }

    /// The joint box searched (radians, padded).
    pub fn domain(&self) -> [Interval; MAX_JOINTS] {
        self.domain
    }

    /// The unit direction of the catalogue's largest error at `q`.
    fn direction_at(&self, q: &[f64; MAX_JOINTS]) -> Option<[f64; 3]> {
        let (theta, _) = self.best(q);
        let mut m = [0.0; NM];
        m[..MAX_JOINTS].copy_from_slice(q);
        let p = Arm7Point.residuals(&theta, &m);
        let p0 = Arm7Point.residuals(&self.nominal, &m);
        let d: [f64; 3] = core::array::from_fn(|r| p[r] - p0[r]);
        let n = norm(d);
        (n > 0.0 && n.is_finite()).then(|| d.map(|v| v / n))
    }

    /// An upper bound of the error over the joint box `q` (module documentation): the
    /// parallelotope's bound, and where that exceeds `enough`, the linear programs' (the smaller
    /// of the two). `+∞` when an enclosure failed.
    fn upper(&self, q: &[Interval; MAX_JOINTS], enough: f64, lps: &mut LinearPrograms) -> f64 {
        // The real arm's joints lie within the joint error of the box.
        let widened: [Interval; MAX_JOINTS] = core::array::from_fn(|i| {
            q[i] + Interval::new(-self.joint_rad.sup(), self.joint_rad.sup())
        });
        let rows = Arm7Point.evaluate_rows_interval(&self.hull, &joints_box(&widened));
        let encoder: [f64; 3] = core::array::from_fn(|r| {
            (0..self.joints)
                .fold(Interval::ZERO, |s, i| s + rows[r].dm[i] * self.joint_rad)
                .mag()
        });
        let centre = q.map(|v| v.mid());
        let frame = frame(self.direction_at(&centre).unwrap_or([1.0, 0.0, 0.0]));
        let widest = widened.iter().map(|v| v.wid()).fold(0.0, f64::max);
        let models = if widest <= QUADRATIC_WIDTH {
            self.quadratic_columns(&widened)
        } else {
            None
        };
        let slopes = |axis: &[f64; 3]| -> Slopes {
            match &models {
                Some(columns) => Slopes::quadratic(axis, columns, &rows, &self.reach),
                None => Slopes::interval(axis, &rows),
            }
        };
        let per_axis: Vec<(Slopes, f64)> = frame
            .iter()
            .map(|u| {
                let extra = (0..3).fold(Interval::ZERO, |s, r| {
                    s + Interval::point(u[r].abs()) * Interval::point(encoder[r])
                });
                (slopes(u), extra.sup())
            })
            .collect();
        // Σ max_S |a·δ| over the joints' terms: over the parallelotope, or the outer box.
        let terms = |joint: &[[Interval; NX]]| -> f64 {
            joint.iter().fold(0.0, |acc, a| {
                let t = match &self.parallelotope {
                    Some(p) => p.max_abs_linear(a),
                    None => (0..NX)
                        .fold(Interval::ZERO, |s, j| {
                            s + Interval::point(a[j].mag()) * Interval::point(self.reach[j])
                        })
                        .sup(),
                };
                add_up(acc, t)
            })
        };
        let fixed: Vec<f64> = per_axis
            .iter()
            .map(|(s, extra)| add_up(add_up(s.rest, *extra), terms(&s.joint)))
            .collect();
        // The norm's bound from the frame's ranges, the main terms' support from `main` (told
        // the slot of its linear function: programs warm-start per slot).
        let bound = |main: &mut dyn FnMut(usize, &[Interval; NX]) -> f64| -> f64 {
            let ranges: FrameRanges = core::array::from_fn(|k| {
                let slot = Slot::Axis(k);
                let s = &per_axis[k].0;
                let hi = add_up(main(slot.up(), &s.main), fixed[k]);
                let lo = -add_up(main(slot.down(), &s.main.map(|v| -v)), fixed[k]);
                if lo.is_finite() && hi.is_finite() && lo <= hi {
                    Interval::new(lo, hi)
                } else {
                    Interval::ENTIRE
                }
            });
            farthest_corner(&ranges)
        };
        // Stages, each only where the previous ones cannot discard the box: the main terms over
        // the parallelotope; by linear programs; then the norm by the directions of the sphere's
        // cover instead of the frame's corner.
        let mut best = f64::INFINITY;
        if let Some(p) = &self.parallelotope {
            best = bound(&mut |_, w| p.max_linear(w));
            if best <= enough {
                return best;
            }
        }
        let mut lp = |slot: usize, w: &[Interval; NX]| lps.max_linear(slot, w, &self.nominal);
        best = best.min(bound(&mut lp));
        if best <= enough {
            return best;
        }
        cover_bound(best, |d, u| {
            let s = slopes(u);
            let extra = (0..3).fold(Interval::ZERO, |acc, r| {
                acc + Interval::point(u[r].abs()) * Interval::point(encoder[r])
            });
            let rest = add_up(add_up(s.rest, extra.sup()), terms(&s.joint));
            add_up(lp(Slot::Cover(d).up(), &s.main), rest)
        })
    }

    /// The columns `∂p/∂θ_j` over the set's outer box and the joint box `q`, as second-order
    /// models in the joints (one noise symbol per joint), computed on a thread with a stack large
    /// enough for the derivatives' models. `None` if that thread could not run.
    fn quadratic_columns(&self, q: &[Interval; MAX_JOINTS]) -> Option<Box<Columns>> {
        let q = *q;
        let (hull, reach) = (self.hull, self.reach);
        let evaluate = move || -> Box<Columns> {
            let x: [Jet<JointModel, NX>; NX] = core::array::from_fn(|j| {
                let v = JointModel::from_interval(hull[j]);
                if reach[j] > 0.0 {
                    Jet::variable(v, j)
                } else {
                    Jet::constant(v)
                }
            });
            let m: [Jet<JointModel, NX>; NM] = core::array::from_fn(|k| {
                Jet::constant(if k < MAX_JOINTS {
                    JointModel::input(q[k], k)
                } else {
                    JointModel::from_interval(Interval::ZERO)
                })
            });
            let p = arm7_point(&x, &m);
            Box::new(core::array::from_fn(|j| {
                [p[0].grad[j], p[1].grad[j], p[2].grad[j]]
            }))
        };
        std::thread::scope(|s| {
            std::thread::Builder::new()
                .stack_size(MODEL_STACK_BYTES)
                .spawn_scoped(s, evaluate)
                .ok()?
                .join()
                .ok()
        })
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
            .borrow()
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

/// The linear functions the bounds ask of the parallelotope: the tool point's gradients in the
/// parameters, per coordinate, at joints spread over the box, and their derivatives in each
/// joint (finite differences).
fn hints(domain: &[Interval; MAX_JOINTS], nominal: &[f64; NX]) -> Vec<[f64; NX]> {
    let mut out = Vec::new();
    let gradients = |q: &[f64; MAX_JOINTS]| {
        let mut m = [0.0; NM];
        m[..MAX_JOINTS].copy_from_slice(q);
        Arm7Point.evaluate_rows(nominal, &m).map(|e| e.dx)
    };
    for k in 0..HINT_CONFIGURATIONS {
        let q: [f64; MAX_JOINTS] = core::array::from_fn(|i| {
            let t = ((k as f64 + 0.5) * (i as f64 + 1.0) * 0.618_033_988_7).fract();
            domain[i].inf() + t * domain[i].wid()
        });
        let g = gradients(&q);
        out.extend(g);
        for i in 0..MAX_JOINTS {
            if domain[i].wid() == 0.0 {
                continue;
            }
            let mut moved = q;
            moved[i] += 1e-4;
            let h = gradients(&moved);
            for r in 0..3 {
                out.push(core::array::from_fn(|j| (h[r][j] - g[r][j]) / 1e-4));
            }
        }
    }
    out
}

/// Joint configurations whose gradients shape the parallelotope.
const HINT_CONFIGURATIONS: usize = 24;

/// `‖d‖ <= max_k u_k·d / cos α` over the directions `u_k` of [`SphereCover`], each bound
/// `u_k·d <= along(k, u_k)`; `best` where that cannot beat it (then the remaining directions
/// are not bounded) or a bound fails.
fn cover_bound(best: f64, mut along: impl FnMut(usize, &[f64; 3]) -> f64) -> f64 {
    let cover = SphereCover::get();
    let mut largest = 0.0f64;
    for (k, u) in cover.directions.iter().enumerate() {
        let v = along(k, u);
        if v.is_nan() {
            return best;
        }
        largest = largest.max(v);
        if largest / cover.cos_radius > best {
            return best;
        }
    }
    best.min((Interval::point(largest) / Interval::point(cover.cos_radius)).sup())
}

/// `a + b` rounded up.
fn add_up(a: f64, b: f64) -> f64 {
    (Interval::point(a) + Interval::point(b)).sup()
}

/// An orthonormal frame whose first axis is the unit `u`.
fn frame(u: [f64; 3]) -> [[f64; 3]; 3] {
    // The coordinate axis least aligned with u, made orthogonal to it.
    let k = (0..3)
        .min_by(|&a, &b| u[a].abs().total_cmp(&u[b].abs()))
        .unwrap_or(0);
    let mut e = [0.0; 3];
    e[k] = 1.0;
    let d = u[k];
    let v = [e[0] - d * u[0], e[1] - d * u[1], e[2] - d * u[2]];
    let n = norm(v);
    let v = v.map(|c| c / n);
    let w = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    [u, v, w]
}

/// The largest norm of a vector whose components along an orthonormal frame lie in `ranges`:
/// the farthest corner, rounded up (the frame's rounding is covered by the relative slack
/// [`FRAME_SLACK`]); `+∞` for an unbounded range.
fn farthest_corner(ranges: &FrameRanges) -> f64 {
    if ranges.iter().any(|v| !v.is_bounded() || v.is_empty()) {
        return f64::INFINITY;
    }
    let sq = ranges
        .iter()
        .fold(Interval::ZERO, |s, v| s + Interval::point(v.mag()).sqr());
    let n = sq.sqrt().sup();
    (Interval::point(n) * Interval::point(1.0 + FRAME_SLACK)).sup()
}

/// Unit directions covering the sphere: every unit vector is within the angle `α` of one of them,
/// `cos α >= cos_radius` — the vertices of the icosahedron subdivided once (42), whose covering
/// radius is the largest angle from a face's circumcentre to its vertices.
struct SphereCover {
    directions: Vec<[f64; 3]>,
    /// A lower bound of `cos α`.
    cos_radius: f64,
}

impl SphereCover {
    /// The cover (computed once).
    fn get() -> &'static SphereCover {
        static COVER: std::sync::OnceLock<SphereCover> = std::sync::OnceLock::new();
        COVER.get_or_init(SphereCover::icosphere)
    }

    fn icosphere() -> SphereCover {
        let t = (1.0 + 5f64.sqrt()) / 2.0;
        let mut v: Vec<[f64; 3]> = [
            [-1.0, t, 0.0],
            [1.0, t, 0.0],
            [-1.0, -t, 0.0],
            [1.0, -t, 0.0],
            [0.0, -1.0, t],
            [0.0, 1.0, t],
            [0.0, -1.0, -t],
            [0.0, 1.0, -t],
            [t, 0.0, -1.0],
            [t, 0.0, 1.0],
            [-t, 0.0, -1.0],
            [-t, 0.0, 1.0],
        ]
        .iter()
        .map(|p| unit(*p))
        .collect();
        let faces: [[usize; 3]; 20] = [
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ];
        let mut midpoint = std::collections::HashMap::new();
        let mut split = |a: usize, b: usize, v: &mut Vec<[f64; 3]>| -> usize {
            *midpoint.entry((a.min(b), a.max(b))).or_insert_with(|| {
                let (p, q) = (v[a], v[b]);
                v.push(unit([p[0] + q[0], p[1] + q[1], p[2] + q[2]]));
                v.len() - 1
            })
        };
        let mut fine = Vec::with_capacity(80);
        for [a, b, c] in faces {
            let (ab, bc, ca) = (
                split(a, b, &mut v),
                split(b, c, &mut v),
                split(c, a, &mut v),
            );
            fine.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        // Every unit vector lies in the cone of some face; within it, it is no farther from the
        // nearest vertex than the face's circumcentre is from its vertices (the faces are
        // acute). A margin covers the rounding of these floating-point computations.
        let cos_radius = fine
            .iter()
            .map(|&[a, b, c]| {
                let (p, q, r) = (v[a], v[b], v[c]);
                let n = unit(cross(sub(q, p), sub(r, p)));
                dot(n, p).abs().min(dot(n, q).abs()).min(dot(n, r).abs())
            })
            .fold(1.0, f64::min)
            - 1e-9;
        debug_assert_eq!(v.len(), COVER_DIRECTIONS);
        SphereCover {
            directions: v,
            cos_radius,
        }
    }
}

fn unit(p: [f64; 3]) -> [f64; 3] {
    let n = norm(p);
    p.map(|c| c / n)
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// A frame computed in floating point is orthonormal only to rounding: for unit `u_k` with
/// `|u_k·u_l - δ_kl| <= η`, `|v|² <= (1 + 2η) Σ_k (u_k·v)²` (Gershgorin on the Gram matrix), so
/// a relative slack of `η` (~`1e-15`) covers it; `1e-12` is generous.
const FRAME_SLACK: f64 = 1e-12;

/// The slopes of one component `u·(p(q + e; θ) - p(q; θ̂))` over a joint box: `main·δ`, plus
/// `Σ_i |joint_i·δ|`, plus at most `rest` (module documentation).
struct Slopes {
    /// The main term's slopes (a linear program's, or the parallelotope's, objective).
    main: [Interval; NX],
    /// The joints' first-order terms' slopes (one per joint with a spread).
    joint: Vec<[Interval; NX]>,
    /// The remainders, rounded up.
    rest: f64,
}

impl Slopes {
    /// From the interval slopes `rows[r].dx` over the whole box (wide joint boxes).
    fn interval(u: &[f64; 3], rows: &[calib_core::Evaluation<Interval, NX, NM>; 3]) -> Self {
        Slopes {
            main: core::array::from_fn(|j| {
                (0..3).fold(Interval::ZERO, |s, r| {
                    s + Interval::point(u[r]) * rows[r].dx[j]
                })
            }),
            joint: Vec::new(),
            rest: 0.0,
        }
    }

    /// From the second-order columns: the centres in the main term; each joint's linear
    /// coefficients and each pair's quadratic ones as terms bounded apart (their noise symbols'
    /// products lie in `[-1, 1]`); the error radii against the reach.
    fn quadratic(
        u: &[f64; 3],
        columns: &Columns,
        rows: &[calib_core::Evaluation<Interval, NX, NM>; 3],
        reach: &[f64; NX],
    ) -> Self {
        let ui = u.map(Interval::point);
        let mut main = [Interval::ZERO; NX];
        let mut remainder = Interval::ZERO;
        let mut terms = vec![[Interval::ZERO; NX]; TERMS];
        for j in 0..NX {
            if reach[j] == 0.0 {
                continue;
            }
            let c = &columns[j];
            if (0..3).any(|r| !(c[r].error().is_finite() && c[r].centre().is_finite())) {
                // A failed model: the interval slope, all in the main term.
                main[j] = (0..3).fold(Interval::ZERO, |s, r| s + ui[r] * rows[r].dx[j]);
                continue;
            }
            let along = |f: &dyn Fn(&JointModel) -> f64| {
                (0..3).fold(Interval::ZERO, |s, r| s + ui[r] * Interval::point(f(&c[r])))
            };
            main[j] = along(&|m| m.centre());
            let e = (0..3).fold(Interval::ZERO, |s, r| {
                s + Interval::point(u[r].abs()) * Interval::point(c[r].error())
            });
            remainder += e * Interval::point(reach[j]);
            let mut t = 0;
            for i in 0..MAX_JOINTS {
                terms[t][j] = along(&|m| m.linear()[i]);
                t += 1;
                for k in i..MAX_JOINTS {
                    terms[t][j] = along(&|m| m.quadratic(i, k));
                    t += 1;
                }
            }
        }
        let joint = terms
            .into_iter()
            .filter(|a| a.iter().any(|v| v.mag() > 0.0))
            .collect();
        Slopes {
            main,
            joint,
            rest: remainder.sup(),
        }
    }
}

/// Second-order models in the joints' noise symbols.
type JointModel = Quadratic<MAX_JOINTS>;

/// The columns `∂p/∂θ_j` as second-order models, per parameter and coordinate.
type Columns = [[JointModel; 3]; NX];

/// How many terms a column's joints make: one linear per joint, one quadratic per pair.
const TERMS: usize = MAX_JOINTS + MAX_JOINTS * (MAX_JOINTS + 1) / 2;

/// Joint boxes at most this wide (radians, every joint) get the second-order columns (sines and
/// cosines of a joint deviating by at most 1 from its centre, [`Quadratic`]'s reach).
const QUADRATIC_WIDTH: f64 = 1.0;

/// The stack of the thread that evaluates the second-order columns (each derivative's model is
/// ~21 KB; the arm's evaluator holds a few hundred).
const MODEL_STACK_BYTES: usize = 256 << 20;

/// Which linear function a program bounds: programs of the same slot warm-start from each
/// other (their objectives move little from one joint box to the next).
#[derive(Clone, Copy)]
enum Slot {
    /// The main term along frame axis `k`.
    Axis(usize),

    /// The main term along the cover's direction `d`.
    Cover(usize),
}

impl Slot {
    /// The slot's index for the largest value (`down`: for the smallest).
    fn up(self) -> usize {
        2 * match self {
            Slot::Axis(k) => k,
            Slot::Cover(d) => 3 + d,
        }
    }

    fn down(self) -> usize {
        self.up() + 1
    }
}

/// How many directions the sphere's cover has (the icosahedron subdivided once).
const COVER_DIRECTIONS: usize = 42;

/// How many slots there are.
const SLOTS: usize = 2 * (3 + COVER_DIRECTIONS);

/// The programs of the bounds, one slot per linear function ([`Slot`]).
type LinearPrograms<'a> = SlotQueries<'a, NX, NM>;

/// The error as a function of the joints, for [`maximize`].
struct SetToolError<'a> {
    problem: &'a SetToolAccuracy,
    /// The largest error attained so far (a box bounded below it needs no linear program).
    lower: Cell<f64>,
    /// The programs, per slot.
    lps: RefCell<LinearPrograms<'a>>,
}

impl Objective<MAX_JOINTS> for SetToolError<'_> {
    fn enclose(&self, q: &[Interval; MAX_JOINTS]) -> Interval {
        self.enclose_up_to(q, self.lower.get())
    }

    fn enclose_up_to(&self, q: &[Interval; MAX_JOINTS], enough: f64) -> Interval {
        let enough = enough.max(self.lower.get());
        Interval::new(
            0.0,
            self.problem.upper(q, enough, &mut self.lps.borrow_mut()),
        )
    }

    fn at(&self, x: &SearchPoint) -> Interval {
        // The instance's value, and the cheap bound at the point (a lower bound is what counts).
        let i = self.problem.instance(x);
        let upper = self.problem.upper(
            &x.map(Interval::point),
            f64::INFINITY,
            &mut self.lps.borrow_mut(),
        );
        if i.value > self.lower.get() {
            self.lower.set(i.value);
        }
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

    fn split_weights(&self, q: &[Interval; MAX_JOINTS]) -> Option<[f64; MAX_JOINTS]> {
        Some(self.problem.error_variation(q))
    }

    fn improve(&self, x: &SearchPoint) -> Option<(SearchPoint, f64)> {
        let q = self.problem.search(x);
        let before = self.problem.instance(&q).value;
        if before > self.lower.get() {
            // A new largest error: push the set along its gradient there, and search again.
            self.problem.push_at(&q);
            let q = self.problem.search(&q);
            let i = self.problem.instance(&q);
            self.lower.set(self.lower.get().max(i.value));
            return Some((q, i.value));
        }
        Some((q, before))
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
        lower: Cell::new(0.0),
        lps: RefCell::new(LinearPrograms::new(&problem.set, SLOTS)),
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
