//! The prediction error over a certified set, bounded at the set's scale.
//!
//! Over an input box `U` (widened by the inputs' own errors to `U'`), with `δ = θ* - θ̂`, the
//! mean-value theorem gives
//!
//! `g(u + e; θ*) - g(u; θ̂) = Σ_j c_j δ_j + Σ_i H_i e_i`
//!
//! with `c_j ⊇ ∂g/∂θ_j` over `U' ×` the set's outer box (with `θ̂`) and `H ⊇ ∂g/∂u` there.
//!
//! **At the set's scale.** On input boxes up to [`Prediction::SECOND_ORDER_WIDTH`] wide, each `c_j` is a
//! second-order model in the inputs' noise symbols `ε_i` ([`Quadratic`] carried through the
//! prediction's derivatives, [`Jet`]): `c_j = c⁰_j + Σ_i a_ji ε_i + Σ_{i<=k} b_jik ε_i ε_k ±
//! r_j`, `r_j` of third order. Along a unit direction `w`, the error's component is then at most
//!
//! `h_S(w̄) + Σ_i max_S |(w·a_i)·δ| + Σ_{i<=k} max_S |(w·b_ik)·δ| + Σ_j (|w|·r_j) max|δ_j|
//! + |w|·(input term)`,
//!
//! `w̄_j = w·c⁰_j`: the main term `h_S` — the support function of the set — is one linear
//! program over the set's own rows ([`SlotQueries`], safe bounds, warm-started per slot) or,
//! where that is enough to discard the box, the bound of a parallelotope around the set aligned
//! with what the data determine ([`Parallelotope`]); the inputs' terms, of first and second order
//! in the box's width, take the parallelotope; only the remainders `r_j` meet the outer box.
//! Wider input boxes take the interval slopes `c_j` (midpoints in the program, radii against the
//! box).
//!
//! The error's components along an orthonormal frame — its first axis the direction of the
//! largest error the catalogue shows at the box's centre — lie in `R` ranges, so its norm is at
//! most that of the ranges' farthest corner; in three dimensions, where that cannot discard the
//! box, a cover of the sphere by 42 directions with a proved covering radius bounds it instead.
//! A branch and bound over the inputs ([`maximize`]) makes the bound proved over the whole box.
//!
//! Lower bounds are attained by certified parameter vectors (a catalogue: the set's points
//! pushed along the error's gradient at inputs spread over the box, and at every input where the
//! search raises the lower bound), with exact inputs.

use super::arcs::{Arcs, WIDEST_ARC};
use super::sphere::{add_up, cover_bound, farthest_corner, frame, norm, COVER_DIRECTIONS};
use super::taylor::taylor_remainder;
use super::{slot, Attained, Bracket, BracketSettings, Instance, Predicted, Prediction};
use calib_core::{
    maximize, maximize_over_list, CertifiedSet, Evaluation, Interval, Jet, MaximumSettings,
    Objective, Parallelotope, Quadratic, SlotQueries, VectorModel,
};
use std::cell::{Cell, RefCell};
use std::sync::{Mutex, MutexGuard};
use std::time::Instant;

/// The prediction-error problem over a certified set (module documentation).
pub struct SetAccuracy<
    'p,
    P,
    const NX: usize,
    const NMS: usize,
    const NP: usize,
    const NU: usize,
    const R: usize,
> {
    prediction: &'p P,
    /// The set the bounds are proved over.
    set: CertifiedSet<NX, NMS>,
    /// A copy of it that collects the certified points of the lower bounds (pushes add points).
    pushes: Mutex<CertifiedSet<NX, NMS>>,
    /// `θ̂`.
    nominal: [f64; NX],
    /// The set's outer box.
    outer: [Interval; NX],
    /// The set's outer box, with `θ̂`.
    hull: [Interval; NX],
    /// `max |θ_j - θ̂_j|` over the set's outer box, rounded up.
    reach: [f64; NX],
    /// The parallelotope around the set (`None` if it could not be bounded).
    parallelotope: Option<Parallelotope<NX>>,
    /// The input box.
    domain: [Interval; NU],
    /// Per input, the half-width of its own error, enclosed.
    input_error: [Interval; NU],
    /// Certified parameter vectors (the instances' geometries).
    catalogue: Mutex<Vec<[f64; NX]>>,
}

/// Input points spread over the box whose error directions the catalogue is pushed along, per
/// coordinate of the prediction (a scalar prediction gets three times as many as a point).
const CATALOGUE_PUSHES: usize = 18;

/// Input boxes at most this wide (in the inputs' own units, their errors included: a joint
/// reading within ±0.05° is 1.7·10⁻³ rad wide) are thin: bounded by the interval slopes alone
/// when the prediction has no curvature enclosure (see [`SetAccuracy::terms`]).
const THIN_INPUTS: f64 = 2e-3;

/// Input points whose gradients shape the parallelotope.
const HINT_INPUTS: usize = 24;

/// The stack of the thread that evaluates the second-order columns (a 44-parameter arm's
/// derivative models are ~21 KB each, and its evaluator holds a few hundred).
const MODEL_STACK_BYTES: usize = 256 << 20;

/// The value behind `m`, locked. A worker that panicked holding it may have left it part-way
/// through a change (a push, a refinement), but every piece and point it holds is still
/// certified, and the panic reaches the caller before anything is written.
fn locked<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// The point `k` of `count` spread over `domain` (a different golden-ratio fraction per input).
fn spread<const NU: usize>(domain: &[Interval; NU], k: usize, count: usize) -> [f64; NU] {
    core::array::from_fn(|i| {
        let t = (k as f64 + 0.5) / count as f64;
        let f = (t * (i as f64 + 1.0) * 0.618_033_988_7).fract();
        domain[i].inf() + f * domain[i].wid()
    })
}

impl<
        'p,
        P,
        const NX: usize,
        const NMS: usize,
        const NP: usize,
        const NU: usize,
        const R: usize,
    > SetAccuracy<'p, P, NX, NMS, NP, NU, R>
where
    P: Prediction<NX, NMS, NP, NU, R>,
{
    /// The problem of `prediction` computed with `nominal` over the certified `set`, on the
    /// input box `domain`, each input within `input_error` of its command. `None` if the set
    /// is empty or an input error is not a finite value `>= 0`.
    pub fn new(
        prediction: &'p P,
        set: CertifiedSet<NX, NMS>,
        nominal: [f64; NX],
        domain: [Interval; NU],
        input_error: [f64; NU],
    ) -> Option<Self> {
        if !input_error.iter().all(|e| e.is_finite() && *e >= 0.0) {
            return None;
        }
        let outer = set.outer()?;
        let hull: [Interval; NX] =
            core::array::from_fn(|j| outer[j].hull(Interval::point(nominal[j])));
        let reach = core::array::from_fn(|j| (hull[j] - Interval::point(nominal[j])).mag());
        let hints = hints(prediction.model(), &domain, &nominal);
        let parallelotope = Parallelotope::around_along(&set, &nominal, &hints);
        let out = SetAccuracy {
            prediction,
            pushes: Mutex::new(set.clone()),
            set,
            nominal,
            outer,
            hull,
            reach,
            parallelotope,
            domain,
            input_error: input_error.map(Interval::point),
            catalogue: Mutex::new(Vec::new()),
        };
        out.fill_catalogue();
        Some(out)
    }

    /// The input box searched.
    pub fn domain(&self) -> [Interval; NU] {
        self.domain
    }

    /// The certified parameter vectors the lower bounds take (the set's points and their pushes).
    pub fn catalogue(&self) -> Vec<[f64; NX]> {
        locked(&self.catalogue).clone()
    }

    /// The catalogue: the set's points, pushed along `±∇_θ g_r` at inputs spread over the box.
    fn fill_catalogue(&self) {
        let count = CATALOGUE_PUSHES / R.max(1);
        for k in 0..count {
            let u = spread(&self.domain, k, count);
            let rows = self
                .prediction
                .model()
                .evaluate_rows(&self.nominal, &slot(&u, 0.0));
            for e in rows {
                for sign in [1.0, -1.0] {
                    self.prediction
                        .push(&mut locked(&self.pushes), &e.dx.map(|v| sign * v));
                }
            }
        }
        self.refresh_catalogue();
    }

    /// The catalogue: every certified point the set holds.
    fn refresh_catalogue(&self) {
        let points = locked(&self.pushes).points().iter().map(|p| p.x).collect();
        *locked(&self.catalogue) = points;
    }

    /// Pushes the set along the error's gradient at `u` (the direction of the catalogue's
    /// largest error there), adding the certified point it reaches to the catalogue.
    fn push_at(&self, u: &[f64; NU]) {
        let Some(w) = self.direction_at(u) else {
            return;
        };
        let rows = self
            .prediction
            .model()
            .evaluate_rows(&self.nominal, &slot(u, 0.0));
        let gradient: [f64; NX] =
            core::array::from_fn(|j| (0..R).map(|r| w[r] * rows[r].dx[j]).sum());
        if self.prediction.push(&mut locked(&self.pushes), &gradient) {
            self.refresh_catalogue();
        }
    }

    /// `g(u; θ) - g(u; θ̂)` in floating point.
    fn error_estimate(&self, u: &[f64; NU], theta: &[f64; NX]) -> [f64; R] {
        let m = slot(u, 0.0);
        let model = self.prediction.model();
        let (p, p0) = (
            model.residuals(theta, &m),
            model.residuals(&self.nominal, &m),
        );
        core::array::from_fn(|r| p[r] - p0[r])
    }

    /// Per input, how fast the catalogue's largest error at the box's centre changes with that
    /// input (its slope plus its curvature times the box's half-width, by central differences):
    /// where to split the box.
    fn error_variation(&self, u: &[Interval; NU]) -> [f64; NU] {
        let centre = u.map(|v| v.mid());
        let (theta, _) = self.best(&centre);
        let d0 = self.error_estimate(&centre, &theta);
        let h = 1e-4;
        core::array::from_fn(|i| {
            if u[i].wid() == 0.0 {
                return 0.0;
            }
            let (mut up, mut down) = (centre, centre);
            up[i] += h;
            down[i] -= h;
            let (du, dd) = (
                self.error_estimate(&up, &theta),
                self.error_estimate(&down, &theta),
            );
            let slope = norm(&core::array::from_fn::<f64, R, _>(|r| {
                (du[r] - dd[r]) / (2.0 * h)
            }));
            let curvature = norm(&core::array::from_fn::<f64, R, _>(|r| {
                (du[r] - 2.0 * d0[r] + dd[r]) / (h * h)
            }));
            slope + 0.5 * curvature * u[i].rad()
        })
    }

    /// The unit direction of the catalogue's largest error at `u`.
    fn direction_at(&self, u: &[f64; NU]) -> Option<[f64; R]> {
        let (theta, _) = self.best(u);
        let d = self.error_estimate(u, &theta);
        let n = norm(&d);
        (n > 0.0 && n.is_finite()).then(|| d.map(|v| v / n))
    }

    /// The inputs the real robot reaches from the box `u`: within their own errors of it when
    /// `errors`, else `u`.
    fn widened(&self, u: &[Interval; NU], errors: bool) -> [Interval; NU] {
        core::array::from_fn(|i| {
            let e = if errors {
                self.input_error[i].sup()
            } else {
                0.0
            };
            u[i] + Interval::new(-e, e)
        })
    }

    /// What every direction's bound over the input box `u` is made of (module documentation):
    /// `None` where the derivatives have no enclosure.
    fn terms(&self, u: &[Interval; NU]) -> Option<Terms<NX, NP, NU, R>> {
        let widened = self.widened(u, true);
        let rows = self
            .prediction
            .model()
            .evaluate_rows_interval(&self.hull, &slot(&widened, Interval::ZERO));
        let bounded = |v: &Interval| v.is_bounded() && !v.is_empty();
        if !rows
            .iter()
            .all(|e| e.dx.iter().all(bounded) && e.dm[..NU].iter().all(bounded))
        {
            return None;
        }
        // Σ_i |H_ri| ε_i: each input's error takes its own worst sign (they do not cancel).
        let input_term: [f64; R] = core::array::from_fn(|r| {
            (0..NU)
                .fold(Interval::ZERO, |s, i| {
                    s + Interval::point(rows[r].dm[i].mag()) * self.input_error[i]
                })
                .sup()
        });
        let widest = widened.iter().map(|v| v.wid()).fold(0.0, f64::max);
        let spread: [Interval; NX] =
            core::array::from_fn(|j| self.hull[j] - Interval::point(self.nominal[j]));
        let curvature = self
            .curvature(&spread, &widened)
            .filter(|c| c.iter().all(|v| v.is_bounded() && !v.is_empty()));
        let arcs = match &self.parallelotope {
            Some(p) if P::ANGULAR_INPUTS && widest > P::SECOND_ORDER_WIDTH => Arcs::over(
                self.prediction,
                &widened,
                &self.hull,
                &self.nominal,
                &self.input_error,
                p,
            )
            .map(Box::new),
            _ => None,
        };
        // On thin inputs the columns' variation with the inputs is negligible: the interval
        // slopes serve, without the costly second-order models — over the set's box, or with a
        // curvature enclosure at `θ̂`.
        let thin = widest <= THIN_INPUTS;
        let at_nominal = (thin && curvature.is_some()).then(|| {
            self.prediction.model().evaluate_rows_interval(
                &self.nominal.map(Interval::point),
                &slot(&widened, Interval::ZERO),
            )
        });
        let columns = if widest <= P::SECOND_ORDER_WIDTH && !thin {
            let at = match curvature {
                Some(_) => self.nominal.map(Interval::point),
                None => self.hull,
            };
            self.second_order_columns(&widened, &at)
        } else {
            None
        };
        Some(Terms {
            rows,
            at_nominal,
            input_term,
            columns,
            curvature,
            arcs,
        })
    }

    /// The prediction's curvature enclosure over `spread` and the inputs `widened`: the robot's
    /// own ([`Prediction::curvature`]), else, on inputs wider than [`THIN_INPUTS`], the Taylor
    /// remainder from its model's second and third derivatives where it has them
    /// ([`taylor_remainder`]: tens of milliseconds for an arm, which a box of the branch and
    /// bound affords and a list of thousands of configurations does not).
    fn curvature(
        &self,
        spread: &[Interval; NX],
        widened: &[Interval; NU],
    ) -> Option<[Interval; R]> {
        self.prediction.curvature(spread, widened).or_else(|| {
            let widest = widened.iter().map(|v| v.wid()).fold(0.0, f64::max);
            if widest <= THIN_INPUTS {
                return None;
            }
            let model = self.prediction.model().curvature()?;
            taylor_remainder(model, &self.nominal, spread, &slot(widened, Interval::ZERO))
        })
    }

    /// The component of the error along `w` over the box `terms` were made for.
    fn along(&self, terms: &Terms<NX, NP, NU, R>, w: &[f64; R]) -> Component<NX> {
        let along_curvature =
            |k: [Interval; R]| (0..R).fold(Interval::ZERO, |s, r| s + Interval::point(w[r]) * k[r]);
        let (slopes, shift) = match (&terms.columns, terms.curvature, &terms.at_nominal) {
            (Some(c), k, _) => (
                Slopes::second_order(w, c, &terms.rows, &self.reach),
                k.map_or(Interval::ZERO, along_curvature),
            ),
            (None, Some(k), Some(at)) => (Slopes::interval(w, at), along_curvature(k)),
            (None, _, _) => (Slopes::interval(w, &terms.rows), Interval::ZERO),
        };
        let inputs = (0..R).fold(Interval::ZERO, |s, r| {
            s + Interval::point(w[r].abs()) * Interval::point(terms.input_term[r])
        });
        self.component(slopes, inputs.sup(), shift)
    }

    /// An upper bound of the error over the input box `u` (module documentation): the
    /// parallelotope's bound, and where that exceeds `enough`, the linear programs' (the smaller
    /// of the two). `+∞` when an enclosure failed.
    fn upper(&self, u: &[Interval; NU], enough: f64, lps: &mut SlotQueries<'_, NX, NMS>) -> f64 {
        let Some(terms) = self.terms(u) else {
            // No enclosure of the derivatives here: no bound (the branch and bound splits).
            return f64::INFINITY;
        };
        let centre = u.map(|v| v.mid());
        let mut first = [0.0; R];
        first[0] = 1.0;
        let axes = frame(self.direction_at(&centre).unwrap_or(first));
        if let (Some(arcs), Some(p)) = (&terms.arcs, &self.parallelotope) {
            return self.upper_by_arcs(arcs, p, &axes, enough, lps);
        }
        let mut per_axis: Vec<Component<NX>> = axes.iter().map(|w| self.along(&terms, w)).collect();
        // The norm's bound from the frame's ranges, the main terms' support from `main` (told
        // the slot of its linear function: programs warm-start per slot).
        let bound = |per_axis: &[Component<NX>],
                     main: &mut dyn FnMut(usize, &[Interval; NX]) -> f64|
         -> f64 { farthest_corner(&ranges_of::<NX, R>(per_axis, main)) };
        // Stages, each only where the previous ones cannot discard the box: the main terms over
        // the parallelotope; by linear programs; then (in three dimensions) the norm by the
        // directions of the sphere's cover instead of the frame's corner.
        let mut best = f64::INFINITY;
        if let Some(p) = &self.parallelotope {
            best = bound(&per_axis, &mut |_, w| p.max_linear(w));
            if best <= enough {
                return best;
            }
        }
        let mut lp = |slot: usize, w: &[Interval; NX]| lps.max_linear(slot, w, &self.nominal);
        if P::TERMS_BY_PROGRAMS {
            terms_by_programs(&mut per_axis, &mut lp);
        }
        best = best.min(bound(&per_axis, &mut lp));
        if best <= enough || R != 3 {
            return best;
        }
        cover_bound(best, enough, |d, w3| {
            let w: [f64; R] = core::array::from_fn(|r| w3[r]);
            self.along(&terms, &w)
                .max(2 * R + d % COVER_DIRECTIONS, 1.0, &mut lp)
        })
    }

    /// [`SetAccuracy::upper`] over a wide box of angular inputs, from its arcs' vertices
    /// ([`Arcs`]): the frame's ranges first over the parallelotope alone, then with programs,
    /// then (in three dimensions) the sphere's cover.
    fn upper_by_arcs(
        &self,
        arcs: &Arcs<NX, NU, R>,
        p: &Parallelotope<NX>,
        axes: &[[f64; R]; R],
        enough: f64,
        lps: &mut SlotQueries<'_, NX, NMS>,
    ) -> f64 {
        let ranges = |main: &mut dyn FnMut(usize, &[Interval; NX]) -> f64, programs: bool| {
            let ranges: [Interval; R] = core::array::from_fn(|k| {
                let down = axes[k].map(|v| -v);
                let (hi, lo) = if programs {
                    (
                        arcs.max_along(&axes[k], p, Some(&mut |o| main(2 * k, o))),
                        -arcs.max_along(&down, p, Some(&mut |o| main(2 * k + 1, o))),
                    )
                } else {
                    (
                        arcs.max_along(&axes[k], p, None),
                        -arcs.max_along(&down, p, None),
                    )
                };
                if lo.is_finite() && hi.is_finite() && lo <= hi {
                    Interval::new(lo, hi)
                } else {
                    Interval::ENTIRE
                }
            });
            farthest_corner(&ranges)
        };
        let mut lp = |slot: usize, w: &[Interval; NX]| {
            lps.max_linear(slot << VERTEX_INPUTS, w, &self.nominal)
        };
        let mut best = ranges(&mut lp, false);
        if best <= enough {
            return best;
        }
        best = best.min(ranges(&mut lp, true));
        if best <= enough || R != 3 {
            return best;
        }
        cover_bound(best, enough, |d, w3| {
            let w: [f64; R] = core::array::from_fn(|r| w3[r]);
            arcs.max_along(&w, p, Some(&mut |o| lp(2 * R + d % COVER_DIRECTIONS, o)))
        })
    }

    /// The linear programs [`SetAccuracy::predict`] asks, one set per worker (they warm-start
    /// from the previous prediction's).
    pub fn programs(&self) -> SlotQueries<'_, NX, NMS> {
        let slots = program_slots(R);
        if P::OWN_ROWS {
            SlotQueries::new(&self.set, slots)
        } else {
            SlotQueries::with_all_rows(&self.set, slots)
        }
    }

    /// What the robot predicts over the set at the inputs `u` (a point; a thin box around one,
    /// for an input with no exact binary value; or the box a measured input's error bounds
    /// allow): per coordinate, an enclosure of `g_r(u + e; θ*)` over every `u` in the box,
    /// `θ*` in the set and, when `errors`, every `|e| <=` the inputs' own errors (`e = 0`
    /// otherwise), and what certified geometries reach there ([`Predicted`]). `None` where no
    /// enclosure could be made.
    ///
    /// Two enclosures, each where the prediction allows it, intersected:
    ///
    /// - the affine form of `g` over the set's outer box `X` and the inputs,
    ///   `g ∈ c + Σ_j (g_j / rad X_j)(θ_j - mid X_j) + Σ_i h_i η_i ± e`
    ///   ([`VectorModel::linear_enclosures`]), its parameters' part bounded over the set;
    /// - `g(u; θ̂) + ∇_θ g(u; θ̂)·(θ - θ̂) +` the prediction's curvature enclosure
    ///   ([`Prediction::curvature`]), the gradient's part likewise.
    ///
    /// Each part over the set takes one linear program per side (safe bounds,
    /// [`SlotQueries::max_linear`], warm-started from the previous prediction's in the same
    /// slots) and, where the prediction refines ([`Prediction::max_over_set`]), a refined
    /// maximum, whose certified maximisers join what is attained.
    pub fn predict(
        &self,
        u: &[Interval; NU],
        errors: bool,
        lps: &mut SlotQueries<'_, NX, NMS>,
    ) -> Option<Predicted<NX, R>> {
        let widened = self.widened(u, errors);
        let m = slot(&widened, Interval::ZERO);
        let mut outer = [Interval::ENTIRE; R];
        let mut found = Vec::new();
        self.narrow_by_affine_forms(&m, lps, &mut outer, &mut found);
        self.narrow_by_curvature(&widened, &m, lps, &mut outer, &mut found);
        if !outer.iter().all(|v| v.is_bounded() && !v.is_empty()) {
            return None;
        }
        Some(Predicted {
            outer,
            attained: self.attained(u, &found),
        })
    }

    /// The first enclosure of [`SetAccuracy::predict`]: per coordinate, the affine form of `g`
    /// over the set's outer box and the inputs `m` (its measurement slot), its parameters' part
    /// bounded over the set by linear programs and, where the prediction refines, by a refined
    /// maximum (whose certified maximisers go to `found`); `outer` is narrowed to each.
    fn narrow_by_affine_forms(
        &self,
        m: &[Interval; NP],
        lps: &mut SlotQueries<'_, NX, NMS>,
        outer: &mut [Interval; R],
        found: &mut Vec<[f64; NX]>,
    ) {
        let Some(forms) = self.prediction.model().linear_enclosures(&self.outer, m) else {
            return;
        };
        let mid = self.outer.map(|v| v.mid());
        for (r, f) in forms.iter().enumerate() {
            // A failed affine form (e.g. a reciprocal over a range holding 0): no bound.
            let finite = |v: &f64| v.is_finite();
            if !(finite(&f.c) && finite(&f.e) && f.gx.iter().chain(&f.gm).all(finite)) {
                continue;
            }
            // θ_j - mid_j = rad_j ε_j: the coefficient of (θ_j - mid_j) is g_j / rad_j.
            let slopes: [Interval; NX] = core::array::from_fn(|j| {
                let rad = self.outer[j].rad();
                if f.gx[j] == 0.0 || rad == 0.0 {
                    Interval::ZERO
                } else {
                    Interval::point(f.gx[j]) / Interval::point(rad)
                }
            });
            let rest =
                f.gm.iter()
                    .fold(Interval::point(f.e), |s, g| s + Interval::point(g.abs()));
            let rest = Interval::new(-rest.sup(), rest.sup());
            if let Some(main) = main_term_over_set(lps, 2 * r, &slopes, &mid) {
                narrow(&mut outer[r], Interval::point(f.c) + main + rest);
            }
            if let Some(main) = self.refined(&slopes, &mid, found) {
                narrow(&mut outer[r], Interval::point(f.c) + main + rest);
            }
        }
    }

    /// The second enclosure of [`SetAccuracy::predict`]: per coordinate, `g(u; θ̂)` plus the
    /// gradient's part over the set (by linear programs and, where the prediction refines, a
    /// refined maximum whose certified maximisers go to `found`) plus the prediction's
    /// curvature enclosure over the inputs `widened` (`m`: their measurement slot); `outer` is
    /// narrowed to each.
    fn narrow_by_curvature(
        &self,
        widened: &[Interval; NU],
        m: &[Interval; NP],
        lps: &mut SlotQueries<'_, NX, NMS>,
        outer: &mut [Interval; R],
        found: &mut Vec<[f64; NX]>,
    ) {
        let spread: [Interval; NX] =
            core::array::from_fn(|j| self.hull[j] - Interval::point(self.nominal[j]));
        let Some(k) = self.curvature(&spread, widened) else {
            return;
        };
        let at = self
            .prediction
            .model()
            .evaluate_rows_interval(&self.nominal.map(Interval::point), m);
        for r in 0..R {
            if let Some(main) = main_term_over_set(lps, 2 * (R + r), &at[r].dx, &self.nominal) {
                narrow(&mut outer[r], at[r].value + main + k[r]);
            }
            if let Some(main) = self.refined(&at[r].dx, &self.nominal, found) {
                narrow(&mut outer[r], at[r].value + main + k[r]);
            }
        }
    }

    /// Inward, per coordinate: the range certified geometries (the catalogue's and those in
    /// `found`) reach at the inputs `u`: some gives at most its lower end, another at least its
    /// upper end. `None` where they do not reach a range.
    fn attained(&self, u: &[Interval; NU], found: &[[f64; NX]]) -> [Option<Attained<NX>>; R] {
        let model = self.prediction.model();
        let at = slot(u, Interval::ZERO);
        let mut lowest: [Option<(f64, [f64; NX])>; R] = [None; R];
        let mut highest: [Option<(f64, [f64; NX])>; R] = [None; R];
        for theta in locked(&self.catalogue).iter().chain(found) {
            let g = model.residuals_interval(&theta.map(Interval::point), &at);
            for r in 0..R {
                if !g[r].is_bounded() || g[r].is_empty() {
                    continue;
                }
                if lowest[r].is_none_or(|(v, _)| g[r].sup() < v) {
                    lowest[r] = Some((g[r].sup(), *theta));
                }
                if highest[r].is_none_or(|(v, _)| g[r].inf() > v) {
                    highest[r] = Some((g[r].inf(), *theta));
                }
            }
        }
        core::array::from_fn(|r| match (lowest[r], highest[r]) {
            (Some((lo, a)), Some((hi, b))) if lo <= hi => Some(Attained {
                range: Interval::new(lo, hi),
                lowest: a,
                highest: b,
            }),
            _ => None,
        })
    }

    /// `s·(θ - about)` over the set, both sides, by [`Prediction::max_over_set`] (the pieces
    /// refined where the bound is attained) at the slopes' midpoints, their radii against the
    /// set's hull; the certified geometries the maxima found go to `found`. `None` where the
    /// prediction does not refine or a bound failed.
    fn refined(
        &self,
        s: &[Interval; NX],
        about: &[f64; NX],
        found: &mut Vec<[f64; NX]>,
    ) -> Option<Interval> {
        if !s.iter().all(|v| v.is_bounded() && !v.is_empty()) {
            return None;
        }
        let mid = s.map(|v| v.mid());
        // s·(θ - about) <= mid·(θ - about) + Σ_j |s_j - mid_j| max|θ_j - about_j|.
        let slack = (0..NX)
            .fold(Interval::ZERO, |acc, j| {
                let reach = (self.hull[j] - Interval::point(about[j])).mag();
                acc + Interval::point((s[j] - Interval::point(mid[j])).mag())
                    * Interval::point(reach)
            })
            .sup();
        let centre = (0..NX).fold(Interval::ZERO, |acc, j| {
            acc + Interval::point(mid[j]) * Interval::point(about[j])
        });
        let mut set = locked(&self.pushes);
        let up = self.prediction.max_over_set(&mut set, &mid)?;
        let down = self.prediction.max_over_set(&mut set, &mid.map(|v| -v))?;
        found.extend(up.argmax.into_iter().chain(down.argmax));
        if !(up.upper.is_finite() && down.upper.is_finite() && slack.is_finite()) {
            return None;
        }
        let hi = (Interval::point(up.upper) - centre + Interval::point(slack)).sup();
        let lo = (-Interval::point(down.upper) - centre - Interval::point(slack)).inf();
        (lo.is_finite() && hi.is_finite() && lo <= hi).then(|| Interval::new(lo, hi))
    }

    /// One component's bound from its slopes (module documentation): the inputs' linear terms
    /// that weigh most go to the vertices of their noise symbols' cube, with the main term;
    /// every other term, bounded apart, to the rest.
    fn component(&self, slopes: Slopes<NX>, input_term: f64, shift: Interval) -> Component<NX> {
        let mut linear: Vec<(f64, [Interval; NX])> = slopes
            .linear
            .into_iter()
            .map(|a| (self.term_bound(&a), a))
            .collect();
        linear.sort_by(|a, b| b.0.total_cmp(&a.0));
        let total: f64 = linear.iter().map(|t| t.0).sum();
        let kept = linear
            .iter()
            .take(VERTEX_INPUTS)
            .take_while(|t| t.0 > total / 64.0)
            .count();
        let fixed = add_up(slopes.rest, input_term);
        let rest = linear[kept..]
            .iter()
            .map(|t| t.0)
            .chain(slopes.quadratic.iter().map(|a| self.term_bound(a)))
            .fold(fixed, add_up);
        let mut linear = linear.into_iter().map(|t| t.1);
        let vertex = linear.by_ref().take(kept).collect();
        Component {
            main: slopes.main,
            vertex,
            terms: linear.chain(slopes.quadratic).collect(),
            fixed,
            rest,
            shift,
        }
    }

    /// `max_S |a·δ|`: over the parallelotope, or the outer box.
    fn term_bound(&self, a: &[Interval; NX]) -> f64 {
        match &self.parallelotope {
            Some(p) => p.max_abs_linear(a),
            None => (0..NX)
                .fold(Interval::ZERO, |s, j| {
                    s + Interval::point(a[j].mag()) * Interval::point(self.reach[j])
                })
                .sup(),
        }
    }

    /// The columns `∂g/∂θ_j` over the parameter box `at` (the set's outer box, or `θ̂`) and the
    /// input box `u`, as second-order models in the inputs (one noise symbol per input), computed
    /// on a thread with a stack large enough for the derivatives' models. `None` if that thread
    /// could not run.
    fn second_order_columns(
        &self,
        u: &[Interval; NU],
        at: &[Interval; NX],
    ) -> Option<Box<Columns<NX, NU, R>>> {
        let (at, reach, prediction, u) = (*at, self.reach, self.prediction, *u);
        let evaluate = move || -> Box<Columns<NX, NU, R>> {
            let x: [Jet<Quadratic<NU>, NX>; NX] = core::array::from_fn(|j| {
                let v = Quadratic::from_interval(at[j]);
                if reach[j] > 0.0 {
                    Jet::variable(v, j)
                } else {
                    Jet::constant(v)
                }
            });
            let inputs: [Jet<Quadratic<NU>, NX>; NU] =
                core::array::from_fn(|k| Jet::constant(Quadratic::input(u[k], k)));
            let zero = Jet::constant(Quadratic::from_interval(Interval::ZERO));
            let g = prediction.second_order(&x, &slot(&inputs, zero));
            Box::new(core::array::from_fn(|j| {
                core::array::from_fn(|r| g[r].grad[j])
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

    /// The error `g(u; θ) - g(u; θ̂)` at exact inputs `u`, enclosed.
    fn error_at(&self, u: &[f64; NU], reached: &[f64; NU], theta: &[f64; NX]) -> [Interval; R] {
        let at = |u: &[f64; NU]| slot(&u.map(Interval::point), Interval::ZERO);
        let model = self.prediction.model();
        let real = model.residuals_interval(&theta.map(Interval::point), &at(reached));
        let nominal = model.residuals_interval(&self.nominal.map(Interval::point), &at(u));
        core::array::from_fn(|r| real[r] - nominal[r])
    }

    /// Where the robot commanded to `u` may reach with the geometry `theta`: each input moved by
    /// its own error, to the side that lengthens the error there (first order); `u` itself where
    /// the move would leave the errors' bounds by rounding.
    fn reached(&self, u: &[f64; NU], theta: &[f64; NX]) -> [f64; NU] {
        let d = self.error_estimate(u, theta);
        let rows = self.prediction.model().evaluate_rows(theta, &slot(u, 0.0));
        core::array::from_fn(|i| {
            let eps = self.input_error[i].inf();
            let along: f64 = (0..R).map(|r| d[r] * rows[r].dm[i]).sum();
            let moved = u[i] + eps * (1.0 - 1e-12) * along.signum();
            if eps > 0.0 && along != 0.0 && (moved - u[i]).abs() <= eps {
                moved
            } else {
                u[i]
            }
        })
    }

    /// The catalogue's geometry with the largest error at `u` (floating point), and its error.
    fn best(&self, u: &[f64; NU]) -> ([f64; NX], f64) {
        locked(&self.catalogue)
            .iter()
            .map(|t| (*t, norm(&self.error_estimate(u, t))))
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((self.nominal, 0.0))
    }

    /// The instance at `u` with the catalogue's best geometry: its error, enclosed, rounded
    /// down (`0` where `u` is not proved to be one of the task's inputs).
    pub fn instance(&self, u: &[f64; NU]) -> Instance<NX, NU, R> {
        let (theta, _) = self.best(u);
        let norm_down = |e: &[Interval; R]| {
            let v = e
                .iter()
                .fold(Interval::ZERO, |s, v| s + v.sqr())
                .sqrt()
                .inf();
            if v.is_nan() {
                0.0
            } else {
                v.max(0.0)
            }
        };
        // The inputs' own errors moved to where they lengthen the error, or none.
        let (reached, e, value) = [self.reached(u, &theta), *u]
            .into_iter()
            .map(|r| {
                let e = self.error_at(u, &r, &theta);
                (r, e, norm_down(&e))
            })
            .max_by(|a, b| a.2.total_cmp(&b.2))
            .unwrap_or((*u, [Interval::ZERO; R], 0.0));
        Instance {
            inputs: *u,
            reached,
            theta,
            error: e.map(|v| v.mid()),
            value: if self.prediction.admits(u) {
                value
            } else {
                0.0
            },
        }
    }

    /// A local search over the inputs from `x` for the largest error of the catalogue.
    fn search(&self, x: &[f64; NU]) -> [f64; NU] {
        let clamp = |u: [f64; NU]| -> [f64; NU] {
            core::array::from_fn(|k| u[k].clamp(self.domain[k].inf(), self.domain[k].sup()))
        };
        let value = |u: &[f64; NU]| {
            if self.prediction.admits(u) {
                self.best(u).1
            } else {
                f64::NEG_INFINITY
            }
        };
        let mut best = (clamp(*x), value(&clamp(*x)));
        let mut step = 0.25;
        while step >= 1e-4 {
            let mut moved = false;
            for k in (0..NU).filter(|&k| self.domain[k].wid() > 0.0) {
                for sign in [-1.0, 1.0] {
                    let mut u = best.0;
                    u[k] += sign * step * self.domain[k].wid();
                    let u = clamp(u);
                    let v = value(&u);
                    if v > best.1 {
                        best = (u, v);
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

/// The linear functions the bounds ask of the parallelotope: the prediction's gradients in the
/// parameters, per coordinate, at inputs spread over the box, and their derivatives in each input
/// (finite differences).
fn hints<M, const NX: usize, const NP: usize, const NU: usize, const R: usize>(
    model: &M,
    domain: &[Interval; NU],
    nominal: &[f64; NX],
) -> Vec<[f64; NX]>
where
    M: VectorModel<NX, NP, R>,
{
    let mut out = Vec::new();
    let gradients = |u: &[f64; NU]| model.evaluate_rows(nominal, &slot(u, 0.0)).map(|e| e.dx);
    for k in 0..HINT_INPUTS {
        let u: [f64; NU] = core::array::from_fn(|i| {
            let t = ((k as f64 + 0.5) * (i as f64 + 1.0) * 0.618_033_988_7).fract();
            domain[i].inf() + t * domain[i].wid()
        });
        let g = gradients(&u);
        out.extend(g);
        for i in (0..NU).filter(|&i| domain[i].wid() > 0.0) {
            let mut moved = u;
            moved[i] += 1e-4;
            let h = gradients(&moved);
            for r in 0..R {
                out.push(core::array::from_fn(|j| (h[r][j] - g[r][j]) / 1e-4));
            }
        }
    }
    out
}

/// The columns `∂g/∂θ_j` as second-order models, per parameter and coordinate.
type Columns<const NX: usize, const NU: usize, const R: usize> = [[Quadratic<NU>; R]; NX];

/// The slopes of one component `w·(g(u + e; θ) - g(u; θ̂))` over an input box: `main·δ`, plus
/// `Σ_i |input_i·δ|`, plus at most `rest` (module documentation).
struct Slopes<const NX: usize> {
    /// The main term's slopes (a linear program's, or the parallelotope's, objective).
    main: [Interval; NX],
    /// The inputs' first-order terms' slopes (those that are not zero).
    linear: Vec<[Interval; NX]>,
    /// The inputs' second-order terms' slopes (those that are not zero).
    quadratic: Vec<[Interval; NX]>,
    /// The remainders, rounded up.
    rest: f64,
}

impl<const NX: usize> Slopes<NX> {
    /// From the interval slopes `rows[r].dx` over the whole box (wide input boxes).
    fn interval<const NP: usize, const R: usize>(
        w: &[f64; R],
        rows: &[Evaluation<Interval, NX, NP>; R],
    ) -> Self {
        Slopes {
            main: core::array::from_fn(|j| {
                (0..R).fold(Interval::ZERO, |s, r| {
                    s + Interval::point(w[r]) * rows[r].dx[j]
                })
            }),
            linear: Vec::new(),
            quadratic: Vec::new(),
            rest: 0.0,
        }
    }

    /// From the second-order columns: the centres in the main term; each input's linear
    /// coefficients and each pair's quadratic ones as terms bounded apart (their noise symbols'
    /// products lie in `[-1, 1]`); the error radii against the reach.
    fn second_order<const NP: usize, const NU: usize, const R: usize>(
        w: &[f64; R],
        columns: &Columns<NX, NU, R>,
        rows: &[Evaluation<Interval, NX, NP>; R],
        reach: &[f64; NX],
    ) -> Self {
        let wi = w.map(Interval::point);
        let mut main = [Interval::ZERO; NX];
        let mut remainder = Interval::ZERO;
        let mut linear = vec![[Interval::ZERO; NX]; NU];
        let mut quadratic = vec![[Interval::ZERO; NX]; NU * (NU + 1) / 2];
        for j in 0..NX {
            if reach[j] == 0.0 {
                continue;
            }
            let c = &columns[j];
            let usable = |m: &Quadratic<NU>| {
                m.error().is_finite()
                    && m.centre().is_finite()
                    && m.linear().iter().all(|v| v.is_finite())
                    && (0..NU).all(|i| (i..NU).all(|k| m.quadratic(i, k).is_finite()))
            };
            if !(0..R).all(|r| usable(&c[r])) {
                // A failed model: the interval slope, all in the main term.
                main[j] = (0..R).fold(Interval::ZERO, |s, r| s + wi[r] * rows[r].dx[j]);
                continue;
            }
            let along = |f: &dyn Fn(&Quadratic<NU>) -> f64| {
                (0..R).fold(Interval::ZERO, |s, r| s + wi[r] * Interval::point(f(&c[r])))
            };
            main[j] = along(&|m| m.centre());
            let e = (0..R).fold(Interval::ZERO, |s, r| {
                s + Interval::point(w[r].abs()) * Interval::point(c[r].error())
            });
            remainder += e * Interval::point(reach[j]);
            let mut t = 0;
            for (i, term) in linear.iter_mut().enumerate() {
                term[j] = along(&|m| m.linear()[i]);
                for k in i..NU {
                    quadratic[t][j] = along(&|m| m.quadratic(i, k));
                    t += 1;
                }
            }
        }
        let nonzero = |a: &[Interval; NX]| a.iter().any(|v| v.mag() > 0.0);
        linear.retain(nonzero);
        quadratic.retain(nonzero);
        Slopes {
            main,
            linear,
            quadratic,
            rest: remainder.sup(),
        }
    }
}

/// At most this many inputs' linear terms go to the vertices of their cube (`2^n` linear
/// programs per component and sign).
const VERTEX_INPUTS: usize = 3;

/// Narrows `outer` to the enclosure `v` where that is bounded: both hold every prediction, so
/// they are disjoint only by a fault, and then the wider (their hull) is kept.
fn narrow(outer: &mut Interval, v: Interval) {
    if v.is_bounded() && !v.is_empty() {
        let both = outer.intersection(v);
        *outer = if both.is_empty() { outer.hull(v) } else { both };
    }
}

/// The main term `s·(θ - about)` over the set, both sides, `[-down, up]`, by the linear
/// programs of `slot` (up) and `slot + 1` (down). `None` when a side failed or they cross.
fn main_term_over_set<const NX: usize, const NMS: usize>(
    lps: &mut SlotQueries<'_, NX, NMS>,
    slot: usize,
    s: &[Interval; NX],
    about: &[f64; NX],
) -> Option<Interval> {
    let up = lps.max_linear(slot, s, about);
    let down = lps.max_linear(slot + 1, &s.map(|v| -v), about);
    (up.is_finite() && down.is_finite() && -down <= up).then(|| Interval::new(-down, up))
}

/// Each component's terms bounded apart, by two programs each over the set
/// ([`Prediction::TERMS_BY_PROGRAMS`]): where that is below the parallelotope's bound, it
/// replaces it (both are valid).
fn terms_by_programs<const NX: usize>(
    per_axis: &mut [Component<NX>],
    lp: &mut dyn FnMut(usize, &[Interval; NX]) -> f64,
) {
    let base = first_term_slot(per_axis.len());
    for (k, c) in per_axis.iter_mut().enumerate() {
        let by_programs = c.terms.iter().enumerate().fold(c.fixed, |acc, (t, a)| {
            let slot = base + 2 * (k * TERM_SLOTS + t.min(TERM_SLOTS - 1));
            let (up, down) = (lp(slot, a), lp(slot + 1, &a.map(|v| -v)));
            if up.is_nan() || down.is_nan() {
                return f64::INFINITY;
            }
            add_up(acc, up.max(down).max(0.0))
        });
        if by_programs < c.rest {
            c.rest = by_programs;
        }
    }
}

/// The first slot of the terms bounded by programs, after the frame's and the cover's (each with
/// its vertices), for a prediction of `r` coordinates.
fn first_term_slot(r: usize) -> usize {
    let cover = if r == 3 { COVER_DIRECTIONS } else { 0 };
    (2 * r + cover) << VERTEX_INPUTS
}

/// The slots of the programs of one box: the frame's and the cover's components (each with its
/// vertices), then the terms bounded by programs.
fn program_slots(r: usize) -> usize {
    first_term_slot(r) + 2 * r * TERM_SLOTS
}

/// The ranges of components (the component `k` along its axis up and down, slots `2k` and
/// `2k + 1`), the main terms' support from `main`; `ENTIRE` where a bound failed.
fn ranges_of<const NX: usize, const R: usize>(
    components: &[Component<NX>],
    main: &mut dyn FnMut(usize, &[Interval; NX]) -> f64,
) -> [Interval; R] {
    core::array::from_fn(|k| {
        let c = &components[k];
        let hi = c.max(2 * k, 1.0, main);
        let lo = -c.max(2 * k + 1, -1.0, main);
        if lo.is_finite() && hi.is_finite() && lo <= hi {
            Interval::new(lo, hi)
        } else {
            Interval::ENTIRE
        }
    })
}

/// What the components of the error over one input box are made of ([`SetAccuracy::terms`]).
struct Terms<const NX: usize, const NP: usize, const NU: usize, const R: usize> {
    /// The prediction's rows with their derivatives over the box and the set's outer box.
    rows: [Evaluation<Interval, NX, NP>; R],
    /// On thin inputs with a curvature enclosure, the rows over the box at `θ̂`.
    at_nominal: Option<[Evaluation<Interval, NX, NP>; R]>,
    /// Per coordinate, the inputs' own errors' term (`Σ_i |H_ri| ε_i`, rounded up).
    input_term: [f64; R],
    /// The columns `∂g/∂θ_j` as second-order models in the inputs (narrow boxes).
    columns: Option<Box<Columns<NX, NU, R>>>,
    /// The robot's curvature enclosure, when it has one.
    curvature: Option<[Interval; R]>,
    /// The arcs' vertices (wide boxes of angular inputs, [`Prediction::ANGULAR_INPUTS`]).
    arcs: Option<Box<Arcs<NX, NU, R>>>,
}

/// Slots per component for the terms bounded by programs ([`Prediction::TERMS_BY_PROGRAMS`]):
/// the inputs' linear and second-order terms of up to seven inputs (any beyond share the last).
const TERM_SLOTS: usize = 7 + 7 * 8 / 2;

/// One component's bound: `max_{s ∈ {±1}^V} max_S (main + Σ_i s_i a_i)·δ + rest + shift`
/// along its direction, the `a_i` the `vertex` terms.
struct Component<const NX: usize> {
    main: [Interval; NX],
    vertex: Vec<[Interval; NX]>,
    /// The other inputs' terms, each bounded apart (`max_S |a·δ|`).
    terms: Vec<[Interval; NX]>,
    /// The remainders and the inputs' own errors' term.
    fixed: f64,
    /// Bounds `fixed` and the terms (over the parallelotope) on both sides.
    rest: f64,
    /// Encloses the curvature's term (one side may be 0).
    shift: Interval,
}

impl<const NX: usize> Component<NX> {
    /// The component's largest value times `sign` (`1` or `-1`), the main terms' support from
    /// `main`, told each linear function's slot: `slot · 2^VERTEX_INPUTS + pattern`.
    fn max(
        &self,
        slot: usize,
        sign: f64,
        main: &mut dyn FnMut(usize, &[Interval; NX]) -> f64,
    ) -> f64 {
        let s = Interval::point(sign);
        let mut best = f64::NEG_INFINITY;
        for pattern in 0..1usize << self.vertex.len() {
            let w: [Interval; NX] = core::array::from_fn(|j| {
                let sum = self
                    .vertex
                    .iter()
                    .enumerate()
                    .fold(self.main[j], |acc, (b, a)| {
                        if pattern >> b & 1 == 1 {
                            acc + a[j]
                        } else {
                            acc - a[j]
                        }
                    });
                s * sum
            });
            let v = main((slot << VERTEX_INPUTS) + pattern, &w);
            if v.is_nan() {
                return f64::INFINITY;
            }
            best = best.max(v);
        }
        let shift = if sign > 0.0 {
            self.shift.sup()
        } else {
            (-self.shift).sup()
        };
        add_up(add_up(best, self.rest), shift)
    }
}

/// The error as a function of the inputs, for [`maximize`].
struct SetError<
    'a,
    'p,
    P,
    const NX: usize,
    const NMS: usize,
    const NP: usize,
    const NU: usize,
    const R: usize,
> {
    problem: &'a SetAccuracy<'p, P, NX, NMS, NP, NU, R>,
    /// The largest error attained so far (a box bounded below it needs no linear program).
    lower: Cell<f64>,
    /// The programs, per slot ([`Component::max`]): `2k`, `2k + 1` the frame's axis `k` up and
    /// down, `2R + d` the cover's direction `d`, each with its vertices.
    lps: RefCell<SlotQueries<'a, NX, NMS>>,
}

impl<P, const NX: usize, const NMS: usize, const NP: usize, const NU: usize, const R: usize>
    Objective<NU> for SetError<'_, '_, P, NX, NMS, NP, NU, R>
where
    P: Prediction<NX, NMS, NP, NU, R>,
{
    fn enclose(&self, u: &[Interval; NU]) -> Interval {
        self.enclose_up_to(u, self.lower.get())
    }

    fn enclose_up_to(&self, u: &[Interval; NU], enough: f64) -> Interval {
        // Inputs outside the task do not raise the error over it.
        let Some(u) = self.problem.prediction.narrow(u) else {
            return Interval::ZERO;
        };
        let enough = enough.max(self.lower.get());
        Interval::new(
            0.0,
            self.problem.upper(&u, enough, &mut self.lps.borrow_mut()),
        )
    }

    fn at(&self, x: &[f64; NU]) -> Interval {
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

    fn attained(&self, x: &[f64; NU]) -> f64 {
        let v = self.problem.instance(x).value;
        if v > self.lower.get() {
            self.lower.set(v);
        }
        v
    }

    fn split_reference(&self, domain: &[Interval; NU]) -> [Interval; NU] {
        let widest = domain
            .iter()
            .map(|v| v.wid())
            .fold(f64::MIN_POSITIVE, f64::max);
        [Interval::new(0.0, widest); NU]
    }

    fn split_weights(&self, u: &[Interval; NU]) -> Option<[f64; NU]> {
        // Arcs too wide for their triangles (with the inputs' own errors) are split first.
        let widened = self.problem.widened(u, true);
        if P::ANGULAR_INPUTS && widened.iter().any(|v| v.wid() > WIDEST_ARC) {
            return Some(widened.map(|v| if v.wid() > WIDEST_ARC { 1.0 } else { 0.0 }));
        }
        Some(self.problem.error_variation(u))
    }

    fn improve(&self, x: &[f64; NU]) -> Option<([f64; NU], f64)> {
        let u = self.problem.search(x);
        let before = self.problem.instance(&u).value;
        if before > self.lower.get() {
            // A new largest error: push the set along its gradient there, and search again.
            self.problem.push_at(&u);
            let u = self.problem.search(&u);
            let i = self.problem.instance(&u);
            self.lower.set(self.lower.get().max(i.value));
            return Some((u, i.value));
        }
        Some((u, before))
    }
}

/// Brackets the prediction error of `problem` over its input box and set (module
/// documentation).
pub fn bracket_over_set<
    P,
    const NX: usize,
    const NMS: usize,
    const NP: usize,
    const NU: usize,
    const R: usize,
>(
    problem: &SetAccuracy<'_, P, NX, NMS, NP, NU, R>,
    settings: &BracketSettings,
) -> Bracket<NX, NU, R>
where
    P: Prediction<NX, NMS, NP, NU, R>,
{
    let start = Instant::now();
    let objective = SetError {
        problem,
        lower: Cell::new(0.0),
        lps: RefCell::new(problem.programs()),
    };
    let m = maximize(
        &objective,
        &problem.domain,
        &MaximumSettings {
            rel_tol: settings.rel_tol,
            abs_tol: 0.0,
            max_boxes: settings.max_boxes,
        },
    );
    // The lower bound is what the reported instance attains (its enclosure, rounded down).
    let worst = problem.instance(&m.argmax);
    let lower = worst.value;
    Bracket {
        upper: m.upper.max(lower),
        lower,
        worst: Some(worst).filter(|w| w.value > 0.0),
        frontier: m.frontier,
        converged: m.converged,
        boxes: m.boxes,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// Brackets the prediction error of `problem` over a finite list of inputs (a task's
/// configurations, held-out rows) instead of its input box, each input given as its enclosure
/// (a thin box: a reading converted to the model's units): per input the bound the branch and
/// bound takes on that box (the inputs' own errors included) and an instance of the catalogue's
/// geometries ([`calib_core::maximize_over_list`]); then the set is pushed along the error's
/// gradient at the input attaining the lower bound and at the one with the largest upper bound,
/// which may raise the lower bound there. `problem`'s input box should hold the list (the
/// catalogue and the parallelotope are spread over it; an input outside it is still bounded
/// soundly, but one the prediction's [`Prediction::narrow`] excludes counts as error 0, as in
/// the branch and bound). `boxes` is the number of inputs; `frontier` the input with the largest
/// upper bound. An empty list gives the trivial bracket (`upper` `+∞`, no instance).
pub fn bracket_over_inputs<
    P,
    const NX: usize,
    const NMS: usize,
    const NP: usize,
    const NU: usize,
    const R: usize,
>(
    problem: &SetAccuracy<'_, P, NX, NMS, NP, NU, R>,
    inputs: &[[Interval; NU]],
    settings: &BracketSettings,
) -> Bracket<NX, NU, R>
where
    P: Prediction<NX, NMS, NP, NU, R>,
{
    let start = Instant::now();
    if inputs.is_empty() {
        return Bracket {
            upper: f64::INFINITY,
            lower: 0.0,
            worst: None,
            frontier: [Interval::ZERO; NU],
            converged: false,
            boxes: 0,
            seconds: start.elapsed().as_secs_f64(),
        };
    }
    let m = maximize_over_list(
        || SetError {
            problem,
            lower: Cell::new(0.0),
            lps: RefCell::new(problem.programs()),
        },
        inputs,
        &MaximumSettings {
            rel_tol: settings.rel_tol,
            abs_tol: 0.0,
            max_boxes: inputs.len(),
        },
    );
    // The lower bound: the best instance at the worst inputs after pushes there.
    let mut candidates: Vec<[f64; NU]> = vec![m.argmax, m.frontier.map(|v| v.mid())];
    candidates.dedup();
    for u in &candidates {
        problem.push_at(u);
    }
    let worst = candidates
        .iter()
        .map(|u| problem.instance(u))
        .max_by(|a, b| a.value.total_cmp(&b.value))
        .filter(|w| w.value > 0.0);
    let lower = worst.as_ref().map_or(0.0, |w| w.value).max(0.0);
    let upper = m.upper.max(lower);
    Bracket {
        upper,
        lower,
        worst,
        frontier: m.frontier,
        converged: upper <= (1.0 + settings.rel_tol) * lower,
        boxes: m.boxes,
        seconds: start.elapsed().as_secs_f64(),
    }
}
