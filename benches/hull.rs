//! Legs per second of the tight certified hull (`calib_core::hull`) on simulated hexapods: 21
//! configurations, the paper's error bounds (Section V), all six legs of one data set, from priors
//! of ± 0.1 cm (the paper's) and ± 1 cm; one core and all cores.
//!
//! `cargo bench --bench hull`. Each iteration certifies the six legs in turn, so the reported
//! throughput is legs per second. The widths reached are checked by
//! `cargo run --release --example tightness`, not here.

use calib_core::{hull, Interval, Settings};
use calib_gough::{builtin_hexapod, leg_boxes, simulate, GoughLeg, Uncertainty};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("hull");
    g.sample_size(10);
    g.throughput(Throughput::Elements(6));
    for radius in [0.1, 1.0] {
        let sim = simulate(&builtin_hexapod(), 21, 7, Uncertainty::PAPER, 1.0, radius);
        let legs: Vec<([Interval; 7], Vec<[Interval; 7]>)> = (0..6)
            .map(|leg| {
                let x0 = sim.nominal[leg]
                    .params()
                    .map(|v| Interval::mid_rad(v, radius));
                (x0, leg_boxes(&sim.measured, &sim.uncertainty, leg))
            })
            .collect();
        for (cores, parallel) in [("1 core", false), ("all cores", true)] {
            let settings = Settings::default().with_parallel(parallel);
            g.bench_function(format!("±{radius} cm/{cores}"), |b| {
                b.iter(|| {
                    for (x0, boxes) in &legs {
                        black_box(hull(&GoughLeg, x0, boxes, &settings));
                    }
                })
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
