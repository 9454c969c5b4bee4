//! Boxes per second of the paper's 128-box sweep step on the paper's setting: one Gough leg, 21
//! measurements, the paper's error bounds (Section V). Also one full `certify` per LP engine and
//! relaxation.
//!
//! `cargo bench --bench sweep` (all cores) and `RAYON_NUM_THREADS=1 cargo bench --bench sweep`.

use calib_core::LpEngine;
use calib_core::{certify, contract, Interval, Relaxation, Settings, Workspace};
use calib_gough::{builtin_hexapod, leg_boxes, simulate, GoughLeg, Uncertainty};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;

/// The 128 sub-boxes of one sweep step of `x1` (split at 5% from the lower bounds).
fn sweep_step_boxes(x1: &[Interval; 7]) -> Vec<[Interval; 7]> {
    (0..128u32)
        .map(|mask| {
            core::array::from_fn(|j| {
                let (lo, hi) = (x1[j].inf(), x1[j].sup());
                let cut = lo + 0.05 * (hi - lo);
                if mask >> j & 1 == 0 {
                    Interval::new(lo, cut)
                } else {
                    Interval::new(cut, hi)
                }
            })
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let sim = simulate(&builtin_hexapod(), 21, 2004, Uncertainty::PAPER, 1.0, 0.1);
    let boxes = leg_boxes(&sim.measured, &sim.uncertainty, 0);
    let x0 = sim.nominal[0].params().map(|v| Interval::mid_rad(v, 0.1));
    let mut g = c.benchmark_group("sweep_step");
    g.sample_size(10);
    for (engine, relaxation) in [
        (LpEngine::DenseSimplex, Relaxation::Corners),
        (LpEngine::DenseSimplex, Relaxation::Krawczyk),
        (LpEngine::DenseSimplex, Relaxation::Both),
        (LpEngine::Clarabel, Relaxation::Corners),
    ] {
        let settings = Settings::default()
            .with_lp(engine)
            .with_relaxation(relaxation);
        let x1 = certify(&GoughLeg, &x0, &boxes, &settings).outer;
        let pieces = sweep_step_boxes(&x1);
        g.throughput(Throughput::Elements(pieces.len() as u64));
        let name = format!("{engine:?}/{relaxation:?}/1 core");
        g.bench_function(name, |b| {
            let mut ws = Workspace::new(&settings);
            b.iter(|| {
                for p in &pieces {
                    black_box(contract(&GoughLeg, p, &boxes, &settings, &mut ws));
                }
            })
        });
        if engine == LpEngine::DenseSimplex && relaxation == Relaxation::Corners {
            use rayon::prelude::*;
            g.bench_function(format!("{engine:?}/{relaxation:?}/all cores"), |b| {
                b.iter(|| {
                    pieces
                        .par_iter()
                        .map_init(
                            || Workspace::new(&settings),
                            |ws, p| contract(&GoughLeg, p, &boxes, &settings, ws).iterations,
                        )
                        .sum::<usize>()
                })
            });
        }
    }
    g.finish();
    let mut g = c.benchmark_group("certify_leg");
    g.sample_size(10);
    g.throughput(Throughput::Elements(1));
    g.bench_function("certify (default settings)", |b| {
        b.iter(|| certify(&GoughLeg, &x0, &boxes, &Settings::default()))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
