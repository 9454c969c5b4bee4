//! The norm of an error vector from bounds of its components: along an orthonormal frame (the
//! farthest corner of the ranges) and along the directions of a cover of the sphere.

use calib_core::Interval;

/// `‖v‖`.
pub(crate) fn norm<const R: usize>(v: &[f64; R]) -> f64 {
    v.iter().map(|c| c * c).sum::<f64>().sqrt()
}

/// `a + b` rounded up; `+∞` when either is `+∞` or not a number (a bound that failed), `-∞`
/// when either is `-∞` and neither is `+∞`.
pub(crate) fn add_up(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() || a == f64::INFINITY || b == f64::INFINITY {
        f64::INFINITY
    } else if a == f64::NEG_INFINITY || b == f64::NEG_INFINITY {
        f64::NEG_INFINITY
    } else {
        (Interval::point(a) + Interval::point(b)).sup()
    }
}

/// An orthonormal frame whose first axis is the unit `u` (Gram–Schmidt on the coordinate axes,
/// least aligned with `u` first).
pub(crate) fn frame<const R: usize>(u: [f64; R]) -> [[f64; R]; R] {
    let mut order: [usize; R] = core::array::from_fn(|k| k);
    order.sort_by(|&a, &b| u[a].abs().total_cmp(&u[b].abs()));
    let mut axes: Vec<[f64; R]> = vec![u];
    for &k in &order {
        if axes.len() == R {
            break;
        }
        let mut v = [0.0; R];
        v[k] = 1.0;
        for a in &axes {
            let d: f64 = (0..R).map(|c| v[c] * a[c]).sum();
            for c in 0..R {
                v[c] -= d * a[c];
            }
        }
        let n = norm(&v);
        if n > 1e-6 {
            axes.push(v.map(|c| c / n));
        }
    }
    core::array::from_fn(|k| axes[k])
}

/// A frame computed in floating point is orthonormal only to rounding: for unit `u_k` with
/// `|u_k·u_l - δ_kl| <= η`, `|v|² <= (1 + 2η) Σ_k (u_k·v)²` (Gershgorin on the Gram matrix), so
/// a relative slack of `η` (~`1e-15`) covers it; `1e-12` is generous.
const FRAME_SLACK: f64 = 1e-12;

/// The largest norm of a vector whose components along an orthonormal frame lie in `ranges`:
/// the farthest corner, rounded up (the frame's rounding is covered by [`FRAME_SLACK`]); `+∞`
/// for an unbounded range.
pub(crate) fn farthest_corner<const R: usize>(ranges: &[Interval; R]) -> f64 {
    if ranges.iter().any(|v| !v.is_bounded() || v.is_empty()) {
        return f64::INFINITY;
    }
    let sq = ranges
        .iter()
        .fold(Interval::ZERO, |s, v| s + Interval::point(v.mag()).sqr());
    let n = sq.sqrt().sup();
    (Interval::point(n) * Interval::point(1.0 + FRAME_SLACK)).sup()
}

/// Unit directions covering the sphere of `R^3`: every unit vector is within the angle `α` of
/// one of them, `cos α >= cos_radius` — the vertices of the icosahedron subdivided once (42),
/// whose covering radius is the largest angle from a face's circumcentre to its vertices.
pub(crate) struct SphereCover {
    pub(crate) directions: Vec<[f64; 3]>,
    /// A lower bound of `cos α`.
    pub(crate) cos_radius: f64,
    /// The subdivided icosahedron's faces (indices into `directions`), which tile the sphere.
    faces: Vec<[usize; 3]>,
}

/// How many directions the sphere's cover has (the icosahedron subdivided once).
pub(crate) const COVER_DIRECTIONS: usize = 42;

impl SphereCover {
    /// The cover (computed once).
    pub(crate) fn get() -> &'static SphereCover {
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
            faces: fine,
        }
    }
}

/// `‖d‖` bounded from bounds `u·d <= along(k, u)` along unit directions `u` (`k` the
/// direction's index, for warm starts), refined where the bound is reached.
///
/// The faces of the subdivided icosahedron tile the sphere; a vector `d` whose direction lies in
/// the cone of a face `F` is within the angle `α_F` of one of its vertices `u`, so
/// `‖d‖ cos α_F <= u·d`: `‖d‖ <= max_{u ∈ F} along(u) / cos α_F` (`face_cos_radius`). The
/// largest of the faces' bounds holds for every `d`. While it exceeds `enough` (and the largest
/// `along` found does not: only then can refining reach `enough`), the face that gives it is
/// split in four at its edges' midpoints (the children tile it, each with a smaller
/// `α`), until the bound is within 1% of the largest `along` found (where the
/// directions' discretisation no longer matters) or 162 directions have been
/// bounded. `best` where the cover cannot beat it (then the remaining directions are not
/// bounded) or a bound fails.
pub fn cover_bound(best: f64, enough: f64, mut along: impl FnMut(usize, &[f64; 3]) -> f64) -> f64 {
    let cover = SphereCover::get();
    let mut directions = cover.directions.clone();
    let mut value = Vec::with_capacity(COVER_BUDGET);
    for (k, u) in cover.directions.iter().enumerate() {
        let v = along(k, u);
        if v.is_nan() || v / cover.cos_radius > best {
            return best;
        }
        value.push(v);
    }
    let bound_of = |f: &[usize; 3], directions: &[[f64; 3]], value: &[f64]| {
        let top = f
            .iter()
            .map(|&i| value[i])
            .fold(f64::NEG_INFINITY, f64::max);
        let cos = face_cos_radius(f.map(|i| directions[i]));
        if top.is_nan() || top == f64::INFINITY {
            f64::INFINITY
        } else if top <= 0.0 {
            // Every direction of the face bounds d·u by 0 or less: no d points into its cone.
            0.0
        } else if cos > 0.0 {
            (Interval::point(top) / Interval::point(cos)).sup()
        } else {
            f64::INFINITY
        }
    };
    let mut faces: Vec<([usize; 3], f64)> = cover
        .faces
        .iter()
        .map(|f| (*f, bound_of(f, &directions, &value)))
        .collect();
    loop {
        let Some((worst, &(face, bound))) = faces
            .iter()
            .enumerate()
            .max_by(|a, b| a.1 .1.total_cmp(&b.1 .1))
        else {
            return best;
        };
        let largest = value.iter().copied().fold(0.0, f64::max);
        // Refined only while that may discard the box: the bound cannot fall below `largest`.
        if bound <= enough
            || largest >= enough
            || bound <= largest * (1.0 + COVER_TOLERANCE)
            || directions.len() + 3 > COVER_BUDGET
        {
            return best.min(bound);
        }
        let [a, b, c] = face;
        let mut mid = |p: usize, q: usize| -> Option<usize> {
            let (x, y) = (directions[p], directions[q]);
            let u = unit([x[0] + y[0], x[1] + y[1], x[2] + y[2]]);
            let k = directions.len();
            let v = along(k, &u);
            if v.is_nan() {
                return None;
            }
            directions.push(u);
            value.push(v);
            Some(k)
        };
        let (Some(ab), Some(bc), Some(ca)) = (mid(a, b), mid(b, c), mid(c, a)) else {
            return best.min(bound);
        };
        faces.swap_remove(worst);
        for f in [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]] {
            // A child's bound is also at most its parent's (its cone lies in the parent's).
            faces.push((f, bound_of(&f, &directions, &value).min(bound)));
        }
    }
}

/// At most this many directions are bounded by one [`cover_bound`].
pub(crate) const COVER_BUDGET: usize = 162;

/// The cover stops refining once its bound is within this share of the largest component.
const COVER_TOLERANCE: f64 = 0.01;

/// A lower bound of `cos α` for a spherical triangle of unit vertices: every unit vector in its
/// cone is within the angle `α` of one of its vertices. For an acute triangle (its circumcentre
/// inside) `α` is the circumradius; in any case the nearest vertex is no farther than the
/// longest edge (the distance to a vertex is convex, largest at another vertex). A margin covers
/// the rounding of these floating-point computations; `0` (no bound) for a degenerate triangle.
fn face_cos_radius(v: [[f64; 3]; 3]) -> f64 {
    let [p, q, r] = v;
    let edges = dot(p, q).min(dot(q, r)).min(dot(r, p));
    let n = cross(sub(q, p), sub(r, p));
    let len = norm(&n);
    let mut cos = edges;
    if len > 1e-12 {
        let n = n.map(|c| c / len);
        let n = if dot(n, p) < 0.0 { n.map(|c| -c) } else { n };
        // The circumcentre n lies in the cone when it is on the inner side of every edge plane.
        let inside = [(p, q, r), (q, r, p), (r, p, q)].iter().all(|&(a, b, c)| {
            let e = cross(a, b);
            dot(e, n) * dot(e, c) >= 0.0
        });
        if inside {
            cos = cos.max(dot(n, p).min(dot(n, q)).min(dot(n, r)));
        }
    }
    (cos - 1e-9).max(0.0)
}

fn unit(p: [f64; 3]) -> [f64; 3] {
    let n = norm(&p);
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
