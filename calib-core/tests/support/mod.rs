//! Checks shared by the model tests (included with `#[path]` by the tests of other crates too):
//! point values inside interval values over random boxes, Jacobians against central finite
//! differences and against forward-mode dual numbers.
#![allow(dead_code)]

use calib_core::{Dual, Interval, Model, VectorModel};
use rand::rngs::StdRng;
use rand::Rng;

/// A random box around `centre` with per-coordinate radii uniform in `[0, rad]` (and sometimes a
/// point interval), shifted by up to `rad` so that the centre is not always the midpoint.
pub fn random_box<const N: usize>(
    rng: &mut StdRng,
    centre: &[f64; N],
    rad: &[f64; N],
) -> [Interval; N] {
    core::array::from_fn(|i| {
        let shift = rng.random_range(-1.0..=1.0) * rad[i];
        let r = if rng.random_range(0..8) == 0 {
            0.0
        } else {
            rng.random_range(0.0..=1.0) * rad[i]
        };
        Interval::mid_rad(centre[i] + shift, r)
    })
}

/// A random member of the box; one in four draws is a corner.
pub fn random_point<const N: usize>(rng: &mut StdRng, b: &[Interval; N]) -> [f64; N] {
    let corner = rng.random_range(0..4) == 0;
    core::array::from_fn(|i| {
        let (lo, hi) = (b[i].inf(), b[i].sup());
        if corner {
            if rng.random::<bool>() {
                lo
            } else {
                hi
            }
        } else {
            (lo + rng.random::<f64>() * (hi - lo)).clamp(lo, hi)
        }
    })
}

/// Over `boxes` random boxes and 20 random points in each: the point residual and both point
/// Jacobians lie inside the interval ones, and the combined evaluators agree with the separate ones.
pub fn assert_encloses<M: Model<NX, NM>, const NX: usize, const NM: usize>(
    model: &M,
    rng: &mut StdRng,
    x_centre: &[f64; NX],
    x_rad: &[f64; NX],
    m_centre: &[f64; NM],
    m_rad: &[f64; NM],
    boxes: usize,
) {
    for _ in 0..boxes {
        let xb = random_box(rng, x_centre, x_rad);
        let mb = random_box(rng, m_centre, m_rad);
        let f = model.residual_interval(&xb, &mb);
        let jx = model.jacobian_x_interval(&xb, &mb);
        let jm = model.jacobian_m_interval(&xb, &mb);
        let all = model.evaluate_interval(&xb, &mb);
        assert_eq!(
            (all.value, all.dx, all.dm),
            (f, jx, jm),
            "combined and separate evaluators differ"
        );
        for _ in 0..20 {
            let x = random_point(rng, &xb);
            let m = random_point(rng, &mb);
            let v = model.residual(&x, &m);
            assert!(
                f.contains(v),
                "f{x:?},{m:?} = {v} outside {f} over {xb:?} {mb:?}"
            );
            let (dx, dm) = (model.jacobian_x(&x, &m), model.jacobian_m(&x, &m));
            for i in 0..NX {
                assert!(
                    jx[i].contains(dx[i]),
                    "df/dx{i} = {} outside {}",
                    dx[i],
                    jx[i]
                );
            }
            for i in 0..NM {
                assert!(
                    jm[i].contains(dm[i]),
                    "df/dm{i} = {} outside {}",
                    dm[i],
                    jm[i]
                );
            }
            let p = model.evaluate(&x, &m);
            assert_eq!((p.value, p.dx, p.dm), (v, dx, dm));
        }
    }
}

/// Central finite differences agree with the generated point Jacobians.
pub fn assert_jacobians_match_finite_differences<
    M: Model<NX, NM>,
    const NX: usize,
    const NM: usize,
>(
    model: &M,
    x: &[f64; NX],
    m: &[f64; NM],
) {
    let f = model.residual(x, m);
    // Central difference of `g` at `v`, compared with the generated derivative `d`.
    let check = |g: &dyn Fn(f64) -> f64, v: f64, d: f64, what: String| {
        let h = 1e-6 * v.abs().max(1.0);
        let fd = (g(v + h) - g(v - h)) / (2.0 * h);
        let tol = 1e-6 * (1.0 + d.abs()) + 8.0 * f64::EPSILON * f.abs().max(1.0) / h;
        assert!(
            (fd - d).abs() <= tol,
            "{what}: generated {d} vs finite difference {fd}"
        );
    };
    let jx = model.jacobian_x(x, m);
    for i in 0..NX {
        let g = |v: f64| {
            let mut y = *x;
            y[i] = v;
            model.residual(&y, m)
        };
        check(&g, x[i], jx[i], format!("df/dx{i}"));
    }
    let jm = model.jacobian_m(x, m);
    for i in 0..NM {
        let g = |v: f64| {
            let mut y = *m;
            y[i] = v;
            model.residual(x, &y)
        };
        check(&g, m[i], jm[i], format!("df/dm{i}"));
    }
}

/// The generated Jacobians agree with forward-mode dual numbers run through the same generic
/// function (`N = NX + NM` seeds: first the parameters, then the measurements).
pub fn assert_jacobians_match_dual<
    M: Model<NX, NM>,
    const NX: usize,
    const NM: usize,
    const N: usize,
>(
    model: &M,
    generic: impl Fn(&[Dual<N>; NX], &[Dual<N>; NM]) -> Dual<N>,
    x: &[f64; NX],
    m: &[f64; NM],
) {
    assert_eq!(N, NX + NM, "N must be NX + NM");
    let xd: [Dual<N>; NX] = core::array::from_fn(|i| Dual::variable(x[i], i));
    let md: [Dual<N>; NM] = core::array::from_fn(|i| Dual::variable(m[i], NX + i));
    let d = generic(&xd, &md);
    let p = model.evaluate(x, m);
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + a.abs().max(b.abs())) * 64.0;
    assert!(
        close(d.value, p.value),
        "value: dual {} vs generated {}",
        d.value,
        p.value
    );
    for i in 0..NX {
        assert!(
            close(d.grad[i], p.dx[i]),
            "df/dx{i}: dual {} vs generated {}",
            d.grad[i],
            p.dx[i]
        );
    }
    for i in 0..NM {
        assert!(
            close(d.grad[NX + i], p.dm[i]),
            "df/dm{i}: dual {} vs generated {}",
            d.grad[NX + i],
            p.dm[i]
        );
    }
}

/// Numerically, independently of the kernel's proof: is there one reading in `m` at which every
/// row vanishes at `x`? Tries every choice of `NR` free quantities, the others on a grid of their
/// intervals, and Newton's method on the square system; accepts a reading inside the box with
/// residuals at rounding level. Quantities known exactly (point intervals: a padded model's unused
/// joints) stay at their value, neither free nor on the grid.
pub fn fits_with_one_reading<
    M: VectorModel<NX, NM, NR>,
    const NX: usize,
    const NM: usize,
    const NR: usize,
>(
    model: &M,
    x: &[f64; NX],
    m: &[Interval; NM],
) -> bool {
    let grid: usize = 17;
    let uncertain: Vec<usize> = (0..NM).filter(|&i| m[i].wid() > 0.0).collect();
    let candidates = if uncertain.len() >= NR {
        uncertain
    } else {
        (0..NM).collect()
    };
    let subsets: Vec<Vec<usize>> = (0..1usize << candidates.len())
        .filter(|mask| mask.count_ones() as usize == NR)
        .map(|mask| {
            (0..candidates.len())
                .filter(|k| mask >> k & 1 == 1)
                .map(|k| candidates[k])
                .collect()
        })
        .collect();
    for free in &subsets {
        let fixed: Vec<usize> = candidates
            .iter()
            .copied()
            .filter(|i| !free.contains(i))
            .collect();
        for cell in 0..grid.pow(fixed.len() as u32) {
            let mut reading = m.map(|v| v.mid());
            let mut c = cell;
            for &i in &fixed {
                let t = (c % grid) as f64 / (grid - 1) as f64;
                c /= grid;
                reading[i] = m[i].inf() + t * (m[i].sup() - m[i].inf());
            }
            if newton_on(model, x, m, free, &mut reading) {
                return true;
            }
        }
    }
    false
}

/// Newton's method in the `free` quantities (Gaussian elimination, no pivoting shortcuts).
#[allow(clippy::needless_range_loop)] // elimination in matrix notation
fn newton_on<M: VectorModel<NX, NM, NR>, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    x: &[f64; NX],
    m: &[Interval; NM],
    free: &[usize],
    reading: &mut [f64; NM],
) -> bool {
    for _ in 0..30 {
        let e = model.evaluate_rows(x, reading);
        let scale = 1.0 + reading.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        if e.iter().all(|r| r.value.abs() <= 1e-11 * scale) {
            return (0..NM).all(|i| m[i].contains(reading[i]));
        }
        // Solve J_free d = -f by elimination with partial pivoting.
        let mut a: Vec<Vec<f64>> = (0..NR)
            .map(|r| {
                let mut row: Vec<f64> = free.iter().map(|&i| e[r].dm[i]).collect();
                row.push(-e[r].value);
                row
            })
            .collect();
        for col in 0..NR {
            let p = (col..NR)
                .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
                .unwrap();
            a.swap(col, p);
            if a[col][col].abs() < 1e-300 {
                return false;
            }
            for r in 0..NR {
                if r != col {
                    let f = a[r][col] / a[col][col];
                    for k in col..=NR {
                        a[r][k] -= f * a[col][k];
                    }
                }
            }
        }
        for (k, &i) in free.iter().enumerate() {
            reading[i] += a[k][NR] / a[k][k];
        }
        if reading.iter().any(|v| !v.is_finite()) {
            return false;
        }
    }
    false
}

/// [`fits_with_one_reading`] for every configuration.
pub fn fits_with_one_reading_all<
    M: VectorModel<NX, NM, NR>,
    const NX: usize,
    const NM: usize,
    const NR: usize,
>(
    model: &M,
    x: &[f64; NX],
    data: &[[Interval; NM]],
) -> bool {
    data.iter().all(|m| fits_with_one_reading(model, x, m))
}
