//! The tool-point error bound over one box of joints and **every** direction at once.
//!
//! With `‖v‖ = max_{|u| = 1} u·v` and the mean value theorem in `θ`, the error over a joint box
//! `Q` is at most `max_u h(u)`, `h(u) = Σ_j |u·g_j| m_j`, where `g_j ⊇ ∂p/∂θ_j` over `Q × Θ` and
//! `m_j = max |Δθ_j|`. The expensive part, the enclosures `g_j`, depends on the joints only; so
//! they are computed once per joint box ([`Sensitivities`]) and the direction is searched here,
//! best first over boxes of `u(φ, λ) = (cos λ cos φ, cos λ sin φ, sin λ)`, without evaluating the
//! arm again. Every leaf's bound is rigorous and the leaves cover the sphere, so the largest leaf
//! bound is a bound of `max_u h`.
//!
//! Each `g_j` is enclosed twice: by the interval Jacobian (width `O(w)` over a box of width `w`)
//! and, on small boxes, as affine forms in the joints' noise symbols (derivatives carried in
//! affine arithmetic, [`Jet`]), where `u·g_j` keeps its first-order dependence on the joints and
//! the direction: a `g_j` of one sign `s_j` over the box contributes `s_j u·g_j m_j` to one affine
//! sum whose maximum is taken at the end, so the excess over the linearised error's true
//! maximum is `O(w²)`. A leaf's bound is the smaller of the two.

use super::NM;
use crate::certification::{MAX_JOINTS, NX};
use calib_core::{Affine, Interval, Jet, Scalar};
use std::cell::RefCell;
use std::cmp::Ordering;
use std::collections::{BinaryHeap, HashMap};

/// An affine form over a box of joints: one noise symbol per joint.
pub type JointForm = Affine<MAX_JOINTS>;

/// Joint boxes at most this wide (radians, every joint) get the affine enclosures: wider, the
/// affine remainders of sines and cosines exceed the interval widths.
pub const AFFINE_WIDTH: f64 = 0.35;

/// Joint boxes wider than this keep the interval bound too (the smaller of the two is taken).
const INTERVAL_WIDTH: f64 = 0.1;

/// Stop refining directions once the best leaf is within this fraction of the best estimate.
const DIRECTION_TOL: f64 = 0.005;

/// At most this many direction boxes are bounded per joint box (~20 ms; the other rules stop
/// the search well before on the cells measured).
const DIRECTION_BUDGET: usize = 4000;

/// A bound on the relative effect of every floating-point rounding in [`Sensitivities::
/// affine_bound`]: its sums have fewer than 1000 terms, so `γ_1000 = 1000u / (1 - 1000u)
/// < 1.2e-13` bounds each (Higham, Accuracy and Stability of Numerical Algorithms, §3.1); three
/// nested levels of sums stay below `1e-12` of the sum of the terms' magnitudes.
const ROUNDING: f64 = 1e-12;

/// One Jacobian column `∂p/∂θ_j` over a joint box as three affine forms in the joints, unpacked.
#[derive(Clone, Copy, Debug)]
pub struct Column {
    /// Centres.
    pub c: [f64; 3],
    /// Coefficients of the joints' noise symbols.
    pub a: [[f64; MAX_JOINTS]; 3],
    /// Error radii.
    e: [f64; 3],
    /// Radii `Σ|a| + e`, rounded up.
    r: [f64; 3],
}

impl Column {
    const ZERO: Column = Column {
        c: [0.0; 3],
        a: [[0.0; MAX_JOINTS]; 3],
        e: [0.0; 3],
        r: [0.0; 3],
    };

    pub fn new(rows: [JointForm; 3]) -> Self {
        Column {
            c: rows.map(|f| f.centre()),
            a: rows.map(|f| *f.coefficients()),
            e: rows.map(|f| f.error()),
            r: rows.map(|f| f.radius()),
        }
    }
}

/// The enclosures `g_j` of one joint box and the half-widths `m_j` (module documentation).
pub struct Sensitivities {
    /// How many parameters have a spread (the first `count` entries below are used).
    count: usize,
    /// `m_j`, rounded up.
    weight: [f64; NX],
    /// The interval Jacobian's columns, when the box is wide enough for them to matter.
    interval: Option<[[Interval; 3]; NX]>,
    /// The affine forms of the same columns, on small boxes.
    pub affine: Option<[Column; NX]>,
}

impl Sensitivities {
    /// The enclosures over the joint box `q` of the `count` parameters with a spread (their
    /// half-widths `weight`), from the interval Jacobian `interval` and, on small boxes, the
    /// affine one of `model` (parameters `theta`, seeded as `seeds` says).
    pub fn new<F>(
        q: &[Interval; MAX_JOINTS],
        (count, weight): (usize, [f64; NX]),
        interval: [[Interval; 3]; NX],
        (theta, seeds): (&[Interval; NX], &[Option<usize>; NX]),
        model: F,
    ) -> Self
    where
        F: Fn(&[Jet<JointForm, NX>; NX], &[Jet<JointForm, NX>; NM]) -> [Jet<JointForm, NX>; 3],
    {
        let widest = q.iter().map(|v| v.wid()).fold(0.0, f64::max);
        let affine = (widest <= AFFINE_WIDTH).then(|| {
            let x: [Jet<JointForm, NX>; NX] = core::array::from_fn(|j| {
                let v = JointForm::from_interval(theta[j]);
                match seeds[j] {
                    Some(i) => Jet::variable(v, i),
                    None => Jet::constant(v),
                }
            });
            let m: [Jet<JointForm, NX>; NM] = core::array::from_fn(|k| {
                Jet::constant(if k < MAX_JOINTS {
                    JointForm::input(q[k], k)
                } else {
                    JointForm::from_interval(Interval::ZERO)
                })
            });
            let rows = model(&x, &m);
            let mut columns = [Column::ZERO; NX];
            for (i, c) in columns.iter_mut().enumerate().take(count) {
                *c = Column::new([rows[0].grad[i], rows[1].grad[i], rows[2].grad[i]]);
            }
            columns
        });
        Sensitivities {
            count,
            weight,
            interval: (affine.is_none() || widest > INTERVAL_WIDTH).then_some(interval),
            affine,
        }
    }

    /// A rigorous bound of `h(u)` over the box of directions `d`: `+∞` on failure.
    pub fn bound(&self, d: &DirectionBox) -> f64 {
        let mut best = f64::INFINITY;
        if let Some(columns) = &self.interval {
            let u = &d.interval;
            let mut s = Interval::ZERO;
            for (g, m) in columns.iter().zip(&self.weight).take(self.count) {
                let v = u[0] * g[0] + u[1] * g[1] + u[2] * g[2];
                s += Interval::point(v.mag()) * Interval::point(*m);
            }
            best = s.sup();
        }
        if let Some(columns) = &self.affine {
            best = best.min(self.affine_bound(columns, d));
        }
        if best.is_nan() {
            f64::INFINITY
        } else {
            best
        }
    }

    /// The affine variant of [`Self::bound`] (module documentation). `u` is an affine form in
    /// the direction's two noise symbols, each `g_j` in the joints': with disjoint symbols,
    /// `u_r g_jr = ū_r ḡ_jr + ū_r (g_jr - ḡ_jr) + ḡ_jr (u_r - ū_r)` plus the remainder
    /// `|ū_r| e_g + |ḡ_jr| e_u + r_u r_g` (the product of [`Affine`]), summed in floating point
    /// and widened by [`ROUNDING`] of the terms' magnitudes.
    pub fn affine_bound(&self, columns: &[Column; NX], d: &DirectionBox) -> f64 {
        // The signed sum: centre, joint and direction coefficients, error; the rest; magnitudes.
        let (mut sc, mut sa, mut sb, mut se) = (0.0, [0.0; MAX_JOINTS], [0.0; 2], 0.0);
        let (mut rest, mut magnitude) = (0.0, 0.0);
        for (g, m) in columns.iter().zip(&self.weight).take(self.count) {
            let Directional { c, a, b, e, mag } = Directional::new(g, d);
            let spread = a.iter().chain(&b).map(|v| v.abs()).sum::<f64>() + e;
            magnitude += m * (mag + e + spread);
            if c.abs() > spread + ROUNDING * (mag + e) {
                // One sign over the box: |d| = sign(c) d, kept linear.
                let s = m * c.signum();
                sc += s * c;
                for k in 0..MAX_JOINTS {
                    sa[k] += s * a[k];
                }
                for l in 0..2 {
                    sb[l] += s * b[l];
                }
                se += m * e;
            } else {
                rest += m * (c.abs() + spread);
            }
        }
        let raw = sc + sa.iter().chain(&sb).map(|v| v.abs()).sum::<f64>() + se + rest;
        // f64::MIN_POSITIVE: every underflow of the at most 2000 products, with room to spare.
        let bound = raw + ROUNDING * (magnitude + raw.abs()) + f64::MIN_POSITIVE;
        if bound.is_nan() {
            f64::INFINITY
        } else {
            bound
        }
    }

    /// `h(u)` at the centre of the enclosures and of the directions (an estimate, only to decide
    /// when to stop).
    fn estimate(&self, d: &DirectionBox) -> f64 {
        let u = d.centre;
        let centre = |i: usize, r: usize| match (&self.affine, &self.interval) {
            (Some(a), _) => a[i].c[r],
            (None, Some(v)) => v[i][r].mid(),
            (None, None) => 0.0,
        };
        (0..self.count)
            .map(|i| {
                (u[0] * centre(i, 0) + u[1] * centre(i, 1) + u[2] * centre(i, 2)).abs()
                    * self.weight[i]
            })
            .sum()
    }
}

/// `u·g` of a box of directions `u` and a column `g`, as an affine form in the joints' noise
/// symbols and the direction's two, computed in floating point (see [`Sensitivities::
/// affine_bound`] for the rounding): `c + a·ε + b·η ± e`.
pub struct Directional {
    pub c: f64,
    pub a: [f64; MAX_JOINTS],
    pub b: [f64; 2],
    pub e: f64,
    /// The sum of the magnitudes of the products summed into `c`, `a` and `b`.
    pub mag: f64,
}

impl Directional {
    /// `u_r g_r = ū_r ḡ_r + ū_r (g_r - ḡ_r) + ḡ_r (u_r - ū_r)` plus the remainder
    /// `|ū_r| e_g + |ḡ_r| e_u + r_u r_g`, summed over the three rows.
    pub fn new(g: &Column, d: &DirectionBox) -> Self {
        let (uc, ub, ue, ur) = (d.c, d.b, d.e, d.r);
        let (mut c, mut a, mut b, mut e, mut mag) = (0.0, [0.0; MAX_JOINTS], [0.0; 2], 0.0, 0.0);
        for r in 0..3 {
            c += uc[r] * g.c[r];
            mag += (uc[r] * g.c[r]).abs();
            for k in 0..MAX_JOINTS {
                a[k] += uc[r] * g.a[r][k];
                mag += (uc[r] * g.a[r][k]).abs();
            }
            for (bl, ubl) in b.iter_mut().zip(&ub[r]) {
                *bl += g.c[r] * ubl;
                mag += (g.c[r] * ubl).abs();
            }
            e += uc[r].abs() * g.e[r] + g.c[r].abs() * ue[r] + ur[r] * g.r[r];
        }
        Directional { c, a, b, e, mag }
    }
}

/// A box of directions `u(φ, λ) = (cos λ cos φ, cos λ sin φ, sin λ)`, enclosed once: in
/// intervals, and as affine forms in the two noise symbols of `φ` and `λ`, unpacked.
#[derive(Clone, Copy, Debug)]
pub struct DirectionBox {
    interval: [Interval; 3],
    c: [f64; 3],
    b: [[f64; 2]; 3],
    e: [f64; 3],
    r: [f64; 3],
    /// `u` at the box's centre (for estimates).
    centre: [f64; 3],
}

impl DirectionBox {
    pub fn new(phi: Interval, lambda: Interval) -> Self {
        let c = lambda.cos();
        let interval = [c * phi.cos(), c * phi.sin(), lambda.sin()];
        let (p, l) = (Affine::<2>::input(phi, 0), Affine::<2>::input(lambda, 1));
        let cl = l.cos();
        let u = [cl * p.cos(), cl * p.sin(), l.sin()];
        let (pm, lm) = (phi.mid(), lambda.mid());
        DirectionBox {
            interval,
            c: u.map(|v| v.centre()),
            b: u.map(|v| *v.coefficients()),
            e: u.map(|v| v.error()),
            r: u.map(|v| v.radius()),
            centre: [lm.cos() * pm.cos(), lm.cos() * pm.sin(), lm.sin()],
        }
    }
}

/// The boxes of directions met so far: every joint box's search splits the same tiles the same
/// way, so each is enclosed once (up to `CACHE_LIMIT` of them).
#[derive(Debug, Default)]
pub struct DirectionCache {
    boxes: RefCell<HashMap<[u64; 4], DirectionBox>>,
}

/// At most this many boxes of directions are kept (~60 MB).
const CACHE_LIMIT: usize = 1 << 18;

impl DirectionCache {
    fn get(&self, phi: Interval, lambda: Interval) -> DirectionBox {
        let key = [phi.inf(), phi.sup(), lambda.inf(), lambda.sup()].map(f64::to_bits);
        if let Some(d) = self.boxes.borrow().get(&key) {
            return *d;
        }
        let d = DirectionBox::new(phi, lambda);
        let mut boxes = self.boxes.borrow_mut();
        if boxes.len() < CACHE_LIMIT {
            boxes.insert(key, d);
        }
        d
    }
}

/// A box of directions and its bound, ordered by the bound (the heap's largest first).
struct Leaf {
    bound: f64,
    phi: Interval,
    lambda: Interval,
}

impl PartialEq for Leaf {
    fn eq(&self, o: &Self) -> bool {
        self.bound.total_cmp(&o.bound) == Ordering::Equal
    }
}
impl Eq for Leaf {}
impl PartialOrd for Leaf {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Leaf {
    fn cmp(&self, o: &Self) -> Ordering {
        self.bound.total_cmp(&o.bound)
    }
}

/// A rigorous bound of `max_u h(u)` (module documentation): best first over boxes of directions,
/// refined until the best box's bound is within `DIRECTION_TOL` of the best estimate or below
/// `enough` (the caller needs no better), no wider than `finest` (radians: refining the direction
/// beyond the joints' width gains nothing), or the budget is spent.
pub fn max_over_directions(
    s: &Sensitivities,
    cache: &DirectionCache,
    finest: f64,
    enough: f64,
) -> f64 {
    let pi = Interval::PI.sup();
    let half = pi / 2.0;
    let mut heap = BinaryHeap::with_capacity(2 * DIRECTION_BUDGET + 64);
    let mut estimate: f64 = 0.0;
    let push = |heap: &mut BinaryHeap<Leaf>, estimate: &mut f64, phi: Interval, lambda| {
        let d = cache.get(phi, lambda);
        *estimate = estimate.max(s.estimate(&d));
        heap.push(Leaf {
            bound: s.bound(&d),
            phi,
            lambda,
        });
    };
    // Tiles of 45° by 45°, the outer ends at the enclosure of ±π and ±π/2.
    for a in 0..8 {
        for b in 0..4 {
            let cut = |k: i32, n: i32, end: f64| {
                if k == 0 {
                    -end
                } else if k == n {
                    end
                } else {
                    end * f64::from(2 * k - n) / f64::from(n)
                }
            };
            let phi = Interval::new(cut(a, 8, pi), cut(a + 1, 8, pi));
            let lambda = Interval::new(cut(b, 4, half), cut(b + 1, 4, half));
            push(&mut heap, &mut estimate, phi, lambda);
        }
    }
    let mut evaluated = heap.len();
    while let Some(top) = heap.peek() {
        let wide = top.phi.wid().max(top.lambda.wid());
        if !top.bound.is_finite()
            || top.bound <= (1.0 + DIRECTION_TOL) * estimate
            || top.bound <= enough
            || wide <= finest
            || evaluated >= DIRECTION_BUDGET
        {
            return top.bound;
        }
        let Some(leaf) = heap.pop() else { break };
        if leaf.phi.wid() >= leaf.lambda.wid() {
            let m = leaf.phi.mid();
            for phi in [
                Interval::new(leaf.phi.inf(), m),
                Interval::new(m, leaf.phi.sup()),
            ] {
                push(&mut heap, &mut estimate, phi, leaf.lambda);
            }
        } else {
            let m = leaf.lambda.mid();
            for lambda in [
                Interval::new(leaf.lambda.inf(), m),
                Interval::new(m, leaf.lambda.sup()),
            ] {
                push(&mut heap, &mut estimate, leaf.phi, lambda);
            }
        }
        evaluated += 2;
    }
    f64::INFINITY
}
