//! Evaluations per second of the generated Gough-leg evaluators (point and interval).
//!
//! `cargo bench --bench eval`

use calib_core::{Interval, Model};
use calib_gough::GoughLeg;
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;

fn boxes() -> ([Interval; 7], [Interval; 8]) {
    let x = [-9.7, 9.1, 0.0, -3.0, 7.3, 0.0, 52.2496].map(|v| Interval::mid_rad(v, 0.1));
    // Position, axis, angle (degrees), reading (`docs/data/sample21`'s first configuration).
    let m = [4.69, 3.94, 62.55, 0.0802, -0.9956, -0.0491, 7.1448, 11.08];
    let r = [5e-4, 5e-4, 5e-4, 5e-6, 5e-6, 5e-6, 1e-3, 5e-4];
    let m = core::array::from_fn(|i| Interval::mid_rad(m[i], r[i]));
    (x, m)
}

fn bench(c: &mut Criterion) {
    let (x, m) = boxes();
    let xp = x.map(Interval::mid);
    let mp = m.map(Interval::mid);
    let mut g = c.benchmark_group("gough_leg");
    g.throughput(Throughput::Elements(1));
    g.bench_function("residual (f64)", |b| {
        b.iter(|| GoughLeg.residual(black_box(&xp), black_box(&mp)))
    });
    g.bench_function("evaluate (f64, value + both Jacobians)", |b| {
        b.iter(|| GoughLeg.evaluate(black_box(&xp), black_box(&mp)))
    });
    g.bench_function("residual_interval", |b| {
        b.iter(|| GoughLeg.residual_interval(black_box(&x), black_box(&m)))
    });
    g.bench_function("jacobian_x_interval", |b| {
        b.iter(|| GoughLeg.jacobian_x_interval(black_box(&x), black_box(&m)))
    });
    g.bench_function("jacobian_m_interval", |b| {
        b.iter(|| GoughLeg.jacobian_m_interval(black_box(&x), black_box(&m)))
    });
    g.bench_function("evaluate_interval (value + both Jacobians)", |b| {
        b.iter(|| GoughLeg.evaluate_interval(black_box(&x), black_box(&m)))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
