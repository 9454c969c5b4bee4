//! Vector residuals: several equations per configuration that share one measurement box.
//!
//! The generated evaluators enclose every row and agree with finite differences; the kernel's entry
//! points (`certify`, `hull`, `sweep`, `pave`, outliers) keep the truth of random multi-residual
//! problems; witnesses and inner points are certified for the *coupled* set (one reading fits
//! every row of a configuration) and rechecked by an independent search for that reading; points
//! that only fit the rows with different readings are rejected.
#![allow(clippy::needless_range_loop)]

use crate::support;

use calib_core::{
    certify, hull, interval_model, is_consistent_point, pave, sweep, Interval, Scalar, Settings,
    Status, VectorModel,
};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use support::{fits_with_one_reading_all, random_box, random_point};

/// Two equations sharing the reading `m0`: `a = m0` and `a = 1 + m1 - m0`. Row by row, every
/// `a ∈ [0, 1]` fits (each row with its own `m0`); with one reading, `a = (1 + m1) / 2`.
#[interval_model]
pub fn coupled_pair<S: Scalar>(x: &[S; 1], m: &[S; 2]) -> [S; 2] {
    [x[0] - m[0], x[0] + m[0] - 1.0 - m[1]]
}

/// The tip of a planar two-link arm tracked in the plane: parameters `(l1, l2, bx, by)`,
/// measurements `(q1, q2, px, py)`.
#[interval_model]
pub fn planar_arm<S: Scalar>(x: &[S; 4], m: &[S; 4]) -> [S; 2] {
    let [l1, l2, bx, by] = *x;
    let [q1, q2, px, py] = *m;
    let q12 = q1 + q2;
    [
        bx + l1 * q1.cos() + l2 * q12.cos() - px,
        by + l1 * q1.sin() + l2 * q12.sin() - py,
    ]
}

/// A pan-tilt pointer seen by a tracker: centre `o`, reach `r`, encoder offsets `t1, t2`;
/// measurements: the two encoder readings and the tracked point.
#[interval_model]
pub fn pointer<S: Scalar>(x: &[S; 6], m: &[S; 5]) -> [S; 3] {
    let [ox, oy, oz, r, t1, t2] = *x;
    let [q1, q2, px, py, pz] = *m;
    let (pan, tilt) = (q1 + t1, q2 + t2);
    let reach = r * tilt.cos();
    [
        ox + reach * pan.cos() - px,
        oy + reach * pan.sin() - py,
        oz + r * tilt.sin() - pz,
    ]
}

fn contains<const N: usize>(b: &[Interval; N], p: &[f64; N]) -> bool {
    (0..N).all(|j| b[j].contains(p[j]))
}

fn subset<const N: usize>(a: &[Interval; N], b: &[Interval; N]) -> bool {
    (0..N).all(|j| a[j].is_subset_of(b[j]))
}

#[test]
fn vector_evaluators_enclose_every_row_and_match_finite_differences() {
    let mut rng = StdRng::seed_from_u64(5);
    check_rows(
        &Pointer,
        &mut rng,
        &[1.0, -2.0, 0.5, 500.0, 0.1, -0.2],
        &[0.3, 0.3, 0.3, 5.0, 0.1, 0.1],
        &[1.0, 0.5, 300.0, 200.0, 100.0],
        &[0.2, 0.2, 1.0, 1.0, 1.0],
    );
    check_rows(
        &PlanarArm,
        &mut rng,
        &[300.0, 250.0, 1.0, -1.0],
        &[5.0, 5.0, 1.0, 1.0],
        &[0.7, -1.2, 400.0, 100.0],
        &[0.3, 0.3, 1.0, 1.0],
    );
}

fn check_rows<M: VectorModel<NX, NM, NR>, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    rng: &mut StdRng,
    xc: &[f64; NX],
    xr: &[f64; NX],
    mc: &[f64; NM],
    mr: &[f64; NM],
) {
    for _ in 0..200 {
        let xb = random_box(rng, xc, xr);
        let mb = random_box(rng, mc, mr);
        let rows = model.evaluate_rows_interval(&xb, &mb);
        assert_eq!(rows.map(|r| r.value), model.residuals_interval(&xb, &mb));
        // The ∂f/∂M-only evaluator (the existence test's) encloses what the full one does.
        let jm_box = model.jacobians_m_interval(&xb, &mb);
        for _ in 0..10 {
            let x = random_point(rng, &xb);
            let m = random_point(rng, &mb);
            let p = model.evaluate_rows(&x, &m);
            assert_eq!(p.map(|r| r.value), model.residuals(&x, &m));
            assert_eq!(p.map(|r| r.dm), model.jacobians_m(&x, &m));
            assert_eq!(
                (p.map(|r| r.value), p.map(|r| r.dm)),
                model.residuals_and_jacobians_m(&x, &m)
            );
            for r in 0..NR {
                assert!(rows[r].value.contains(p[r].value), "row {r}: value outside");
                for j in 0..NX {
                    assert!(
                        rows[r].dx[j].contains(p[r].dx[j]),
                        "row {r}: d/dx{j} outside"
                    );
                }
                for i in 0..NM {
                    assert!(
                        rows[r].dm[i].contains(p[r].dm[i]) && jm_box[r][i].contains(p[r].dm[i]),
                        "row {r}: d/dm{i} outside"
                    );
                }
            }
            // Central differences, every row and every input.
            let h = 1e-6;
            for j in 0..NX + NM {
                let shifted = |d: f64| {
                    let (mut xs, mut ms) = (x, m);
                    let v = if j < NX { &mut xs[j] } else { &mut ms[j - NX] };
                    let step = h * v.abs().max(1.0);
                    *v += d * step;
                    (model.residuals(&xs, &ms), step)
                };
                let ((plus, step), (minus, _)) = (shifted(1.0), shifted(-1.0));
                for r in 0..NR {
                    let fd = (plus[r] - minus[r]) / (2.0 * step);
                    let d = if j < NX { p[r].dx[j] } else { p[r].dm[j - NX] };
                    let tol = 1e-5 * (1.0 + d.abs()) + 1e-9 * (1.0 + p[r].value.abs()) / step;
                    assert!((fd - d).abs() <= tol, "row {r} input {j}: {d} vs {fd}");
                }
            }
        }
    }
}

#[test]
fn one_reading_per_configuration_decides_the_certified_box() {
    let data = [[Interval::new(0.0, 1.0), Interval::new(-0.01, 0.01)]];
    let x0 = [Interval::new(-1.0, 2.0)];
    let r = certify(&CoupledPair, &x0, &data, &Settings::default());
    assert_eq!(r.status, Status::Consistent);
    // Row by row the box would stay [0, 1]; coupled it is [0.495, 0.505].
    assert!(
        r.outer[0].inf() >= 0.495 - 1e-9 && r.outer[0].sup() <= 0.505 + 1e-9,
        "{}",
        r.outer[0]
    );
    assert!(r.outer[0].inf() <= 0.495 && r.outer[0].sup() >= 0.505);
    let h = hull(&CoupledPair, &x0, &data, &Settings::default());
    assert!(h.converged && h.outer[0].is_subset_of(r.outer[0]));
    let inner = h.inner.expect("inner bounds");
    assert!(
        inner[0].inf() < 0.4951 && inner[0].sup() > 0.5049,
        "{}",
        inner[0]
    );
    // Points that fit each row with another reading of m0 are not certified.
    for k in 0..=1000 {
        let a = k as f64 / 1000.0;
        let certified = is_consistent_point(&CoupledPair, &[a], &data);
        if !(0.495..=0.505).contains(&a) {
            assert!(
                !certified,
                "a = {a} certified, but no single reading fits both rows"
            );
        } else if (0.4955..=0.5045).contains(&a) {
            assert!(certified, "a = {a} fits with m0 = a, m1 = 2a - 1");
        }
    }
}

/// A random problem: the truth, configurations within the model's range, readings within the
/// error bounds of the true values, and a prior box around the truth (not centred on it).
struct Problem<const NX: usize, const NM: usize> {
    truth: [f64; NX],
    data: Vec<[Interval; NM]>,
    x0: [Interval; NX],
}

fn pointer_problem(seed: u64, configs: usize) -> Problem<6, 5> {
    let mut rng = StdRng::seed_from_u64(seed);
    let truth = [
        rng.random_range(-10.0..10.0),
        rng.random_range(-10.0..10.0),
        rng.random_range(-10.0..10.0),
        rng.random_range(300.0..800.0),
        rng.random_range(-0.05..0.05),
        rng.random_range(-0.05..0.05),
    ];
    let prior = [0.5, 0.5, 0.5, 0.5, 0.002, 0.002];
    let err = [2e-5, 2e-5, 0.01, 0.01, 0.01];
    let data = (0..configs)
        .map(|_| {
            let q = [rng.random_range(-3.0..3.0), rng.random_range(-1.0..1.0)];
            let p = Pointer.residuals(&truth, &[q[0], q[1], 0.0, 0.0, 0.0]);
            let exact = [q[0], q[1], p[0], p[1], p[2]];
            core::array::from_fn(|i| {
                Interval::mid_rad(exact[i] + rng.random_range(-0.9..0.9) * err[i], err[i])
            })
        })
        .collect();
    let x0 = core::array::from_fn(|j| {
        Interval::mid_rad(truth[j] + rng.random_range(-0.5..0.5) * prior[j], prior[j])
    });
    Problem { truth, data, x0 }
}

fn planar_problem(seed: u64, configs: usize) -> Problem<4, 4> {
    let mut rng = StdRng::seed_from_u64(seed);
    let truth = [
        rng.random_range(200.0..400.0),
        rng.random_range(150.0..300.0),
        rng.random_range(-5.0..5.0),
        rng.random_range(-5.0..5.0),
    ];
    let prior = [1.0, 1.0, 1.0, 1.0];
    let err = [1e-4, 1e-4, 0.02, 0.02];
    let data = (0..configs)
        .map(|_| {
            let q = [rng.random_range(-3.0..3.0), rng.random_range(-2.5..2.5)];
            let p = PlanarArm.residuals(&truth, &[q[0], q[1], 0.0, 0.0]);
            let exact = [q[0], q[1], p[0], p[1]];
            core::array::from_fn(|i| {
                Interval::mid_rad(exact[i] + rng.random_range(-0.9..0.9) * err[i], err[i])
            })
        })
        .collect();
    let x0 = core::array::from_fn(|j| {
        Interval::mid_rad(truth[j] + rng.random_range(-0.5..0.5) * prior[j], prior[j])
    });
    Problem { truth, data, x0 }
}

/// Every entry point keeps the truth; every certified point is rechecked independently.
fn assert_sound<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    p: &Problem<NX, NM>,
    what: &str,
) where
    M: VectorModel<NX, NM, NR> + Sync,
{
    let s = Settings::default();
    let c = certify(model, &p.x0, &p.data, &s);
    assert_ne!(
        c.status,
        Status::Empty,
        "{what}: consistent data proved empty"
    );
    assert!(
        contains(&c.outer, &p.truth),
        "{what}: truth outside certify's box"
    );
    if let Some(w) = c.witness {
        assert!(
            fits_with_one_reading_all(model, &w, &p.data),
            "{what}: witness fails the recheck"
        );
        assert!(subset(&c.inner.expect("inner with a witness"), &c.outer));
    }
    let h = hull(model, &p.x0, &p.data, &s);
    assert_ne!(
        h.status,
        Status::Empty,
        "{what}: hull proved consistent data empty"
    );
    assert!(
        contains(&h.outer, &p.truth),
        "{what}: truth outside the hull's outer box"
    );
    assert!(subset(&h.outer, &h.x1.expect("x1")));
    if let Some(inner) = h.inner {
        assert!(subset(&inner, &h.outer), "{what}: inner not inside outer");
        for q in &h.inner_points {
            assert!(contains(&h.outer, q));
            assert!(is_consistent_point(model, q, &p.data));
            assert!(
                fits_with_one_reading_all(model, q, &p.data),
                "{what}: inner point {q:?} fails the recheck"
            );
        }
    }
    if NX <= 4 {
        let sw = sweep(model, &p.x0, &p.data, &s);
        let kept = sw.boxes.iter().any(|b| contains(b, &p.truth));
        assert!(kept, "{what}: truth in no sweep box");
        let pv = pave(model, &p.x0, &p.data, &s, 0.2, 400);
        assert!(
            pv.boxes.iter().any(|b| contains(b, &p.truth)),
            "{what}: truth in no paving box"
        );
    }
}

#[test]
fn random_multi_residual_problems_keep_the_truth_in_every_entry_point() {
    let mut consistent = 0;
    for seed in 0..6 {
        let p = pointer_problem(seed, 10);
        assert_sound(&Pointer, &p, &format!("pointer seed {seed}"));
        let q = planar_problem(100 + seed, 8);
        assert_sound(&PlanarArm, &q, &format!("planar seed {seed}"));
        consistent += usize::from(
            certify(&Pointer, &p.x0, &p.data, &Settings::default()).status == Status::Consistent,
        );
    }
    assert!(
        consistent >= 4,
        "only {consistent} of 6 pointer problems certified consistent"
    );
}

#[test]
fn a_shifted_configuration_is_named_and_tolerated_as_an_outlier() {
    let mut p = pointer_problem(42, 10);
    // Move the tracked x of configuration 3 by 2 (the error bound is 0.01).
    p.data[3][2] += Interval::point(2.0);
    let c = certify(&Pointer, &p.x0, &p.data, &Settings::default());
    assert_eq!(c.status, Status::Empty);
    let conflict = c.conflict.expect("a conflict set");
    assert!(
        conflict.contains(&3),
        "conflict {conflict:?} misses configuration 3"
    );
    let relaxed = Settings::default().with_max_outliers(1);
    let h = hull(&Pointer, &p.x0, &p.data, &relaxed);
    assert_ne!(h.status, Status::Empty);
    assert!(contains(&h.outer, &p.truth));
    assert_eq!(h.outliers, vec![3]);
}

/// Over random boxes, every point value of every row lies in its linear enclosure evaluated (in
/// interval arithmetic) at the point's noise symbols, and the range of the form contains it too
/// (what the Newton step's cheap rejection uses).
fn check_linear_enclosures<M, const NX: usize, const NM: usize, const NR: usize>(
    model: &M,
    rng: &mut StdRng,
    xc: &[f64; NX],
    xr: &[f64; NX],
    mc: &[f64; NM],
    mr: &[f64; NM],
) where
    M: VectorModel<NX, NM, NR>,
{
    for _ in 0..200 {
        let xb = random_box(rng, xc, xr);
        let mb = random_box(rng, mc, mr);
        let forms = model
            .linear_enclosures(&xb, &mb)
            .expect("a generated vector model");
        for _ in 0..20 {
            let x = random_point(rng, &xb);
            let m = random_point(rng, &mb);
            let p = model.evaluate_rows(&x, &m);
            // ε_j = (x_j - mid) / rad, enclosed.
            let eps = |v: f64, b: Interval| {
                if b.rad() == 0.0 {
                    Interval::ZERO
                } else {
                    (Interval::point(v) - Interval::point(b.mid())) / Interval::point(b.rad())
                }
            };
            for r in 0..NR {
                let f = &forms[r];
                let mut v = Interval::point(f.c) + Interval::new(-f.e, f.e);
                for j in 0..NX {
                    v += Interval::point(f.gx[j]) * eps(x[j], xb[j]);
                }
                for i in 0..NM {
                    v += Interval::point(f.gm[i]) * eps(m[i], mb[i]);
                }
                assert!(
                    v.contains(p[r].value),
                    "row {r}: {} outside {v}",
                    p[r].value
                );
                assert!(f.range().contains(p[r].value), "row {r}: range");
            }
        }
    }
}

#[test]
fn affine_enclosures_contain_every_point_value() {
    let mut rng = StdRng::seed_from_u64(17);
    check_linear_enclosures(
        &Pointer,
        &mut rng,
        &[1.0, -2.0, 0.5, 500.0, 0.1, -0.2],
        &[0.3, 0.3, 0.3, 5.0, 0.1, 0.1],
        &[1.0, 0.5, 300.0, 200.0, 100.0],
        &[0.2, 0.2, 1.0, 1.0, 1.0],
    );
    check_linear_enclosures(
        &PlanarArm,
        &mut rng,
        &[300.0, 250.0, 1.0, -1.0],
        &[5.0, 5.0, 1.0, 1.0],
        &[0.7, -1.2, 400.0, 100.0],
        &[0.3, 0.3, 1.0, 1.0],
    );
}
