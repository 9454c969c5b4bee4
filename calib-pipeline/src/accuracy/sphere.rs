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
        }
    }
}

/// `‖d‖ <= max_k u_k·d / cos α` over the directions `u_k` of [`SphereCover`], each bound
/// `u_k·d <= along(k, u_k)`; `best` where that cannot beat it (then the remaining directions
/// are not bounded) or a bound fails.
pub(crate) fn cover_bound(best: f64, mut along: impl FnMut(usize, &[f64; 3]) -> f64) -> f64 {
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
