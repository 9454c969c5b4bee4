//! Seconds per certification of serial arms through the pipeline (`certify_arm`, the padded
//! 7-joint model): the hull of a small 3-joint arm (12 configurations, tight priors) limited to 20
//! contracted boxes, and one contraction to x1 of the built-in 6-axis arm (10 configurations, the
//! issue's priors and error bounds; 50 configurations take ~7 s, see `arm demo` and
//! `benches/README.md`). And the error-scale search's first step: the Chebyshev fit of the
//! built-in arm to 50 configurations (`calib_core::smallest_scale`, every bound scaled) and the
//! certificate of its point (`calib_core::is_consistent_point`) just above the fit's factor, and
//! the second-order emptiness certificate over the prior just below it.
//! And the kernel's unit of work at real-arm size (issue 36's target: ≤ 30 ms): one Newton/LP
//! step (`calib_core::contract` with one iteration, cold LP bases) of the built-in arm's prior
//! against 50 configurations (27 free parameters, 150 residual rows), and the whole contraction
//! to its fixed point (its number of steps printed once); one step of a hull box (a half of x1
//! whose LPs start from x1's bases, `calib_core::contract_from`, the hull's unit of work); and the
//! built-in arm's whole hull (`arm demo --hull`: 50 configurations, tolerance 0.10; issue 36's
//! target ≤ 20 s on 2 cores, ~20 s per run, so this one alone takes minutes).
//!
//! `cargo bench -p calib-arm --bench arm_hull`.

use calib_arm::certification::{arm_settings, certify_arm, padded_box, RunOptions, NM};
use calib_arm::error_scale::ScaleBounds;
use calib_arm::simulate::{measurement_box, simulate, Uncertainty};
use calib_arm::{builtin_arm, Arm, Arm7Point, Joint};
use calib_core::second_order_emptiness;
use calib_core::split_widest;
use calib_core::{
    contract, contract_from, is_consistent_point, smallest_scale, Interval, Settings, VectorModel,
    Workspace,
};
use calib_pipeline::Depth;
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

/// A 3-joint arm with priors a few times the error bounds' effect.
fn small_arm() -> Arm {
    let joint = |nominal: [f64; 5], radius: [f64; 5]| Joint { nominal, radius };
    Arm {
        joints: vec![
            joint([0.0, 120.0, 0.0, 90.0, 0.0], [0.0, 0.0, 0.02, 0.002, 0.0]),
            joint(
                [2.0, 0.0, -400.0, 0.0, 0.0],
                [0.002, 0.0, 0.02, 0.002, 0.002],
            ),
            joint(
                [-1.0, 15.0, -350.0, 0.0, 0.0],
                [0.002, 0.0, 0.02, 0.002, 0.0],
            ),
        ],
        base: [900.0, -200.0, 100.0, 0.5, -0.4, 30.0],
        base_radius: [0.05, 0.05, 0.05, 0.005, 0.005, 0.005],
        tool: [10.0, 5.0, 60.0],
        tool_radius: [0.02; 3],
        tool_rotation: None,
    }
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("arm");
    g.sample_size(10);
    let cases = [
        (
            "3-joint hull, 12 configurations, 20 boxes",
            small_arm(),
            12,
            Depth::Hull,
        ),
        (
            "built-in x1, 10 configurations",
            builtin_arm(),
            10,
            Depth::Fast,
        ),
    ];
    for (name, arm, configs, depth) in cases {
        let sim = simulate(&arm, configs, 3, Uncertainty::TRACKER, 1.0, &[]);
        let settings = Settings::default()
            .with_hull_tolerance(0.10)
            .with_hull_budget(20, Some(60.0));
        let options = RunOptions { depth, lsq: false };
        g.bench_function(name, |b| {
            b.iter(|| {
                black_box(
                    certify_arm(&arm, &sim.readings, &sim.uncertainty, options, &settings)
                        .expect("3 to 7 joints"),
                )
            })
        });
    }
    let arm = builtin_arm();
    let sim = simulate(&arm, 50, 3, Uncertainty::TRACKER, 1.0, &[]);
    let boxes = |u: &Uncertainty| -> Vec<[Interval; NM]> {
        sim.readings
            .iter()
            .filter_map(|r| measurement_box(r, u))
            .collect()
    };
    let (x0, mask) = (padded_box(&arm), ScaleBounds::All.mask(6));
    let at_one = boxes(&sim.uncertainty);
    g.bench_function("built-in Chebyshev fit, 50 configurations", |b| {
        b.iter(|| black_box(smallest_scale(&Arm7Point, &x0, &at_one, &mask)))
    });
    let e = smallest_scale(&Arm7Point, &x0, &at_one, &mask);
    let widened = boxes(&ScaleBounds::All.scale(&sim.uncertainty, 1.005 * e.scale));
    g.bench_function("built-in witness check at 1.005 x the fit", |b| {
        b.iter(|| black_box(is_consistent_point(&Arm7Point, &e.point, &widened)))
    });
    // The second-order certificate (`calib_core::second_order`) over the prior just below the
    // fit's factor: the fit, the weights' LP and every configuration's derivatives, run whole
    // whether the bound comes out positive or not (which is printed once).
    let below = boxes(&ScaleBounds::All.scale(&sim.uncertainty, 0.98 * e.scale));
    let curvature = Arm7Point
        .curvature()
        .expect("the arm's model has curvature");
    let proved = second_order_emptiness(&Arm7Point, curvature, &x0, &below).is_some();
    eprintln!("the certificate over the prior at 0.98 x the fit proves it empty: {proved}");
    g.bench_function("built-in second-order certificate at 0.98 x the fit", |b| {
        b.iter(|| black_box(second_order_emptiness(&Arm7Point, curvature, &x0, &below)))
    });
    let one_step = Settings {
        max_iterations: 1,
        ..Settings::default()
    };
    g.bench_function("built-in one Newton/LP step, 50 configurations", |b| {
        b.iter(|| {
            let mut ws = Workspace::new(&one_step);
            black_box(contract(&Arm7Point, &x0, &at_one, &one_step, &mut ws))
        })
    });
    let settings = Settings::default();
    let steps = contract(
        &Arm7Point,
        &x0,
        &at_one,
        &settings,
        &mut Workspace::new(&settings),
    )
    .iterations;
    eprintln!("the built-in arm's contraction to its fixed point takes {steps} Newton/LP steps");
    let mut parent = Workspace::new(&settings);
    let x1 = contract(&Arm7Point, &x0, &at_one, &settings, &mut parent)
        .result
        .expect("the simulated data are consistent");
    let bases = parent.lp_memory();
    let (half, _) = split_widest(&x1, &x1).expect("x1 is wider than a point");
    g.bench_function(
        "built-in one Newton/LP step of a half of x1 from x1's bases, 50 configurations",
        |b| {
            b.iter(|| {
                let mut ws = Workspace::new(&one_step);
                black_box(contract_from(
                    &Arm7Point, &half, &at_one, &one_step, &mut ws, &bases,
                ))
            })
        },
    );
    g.bench_function(
        "built-in contraction to the fixed point, 50 configurations",
        |b| {
            b.iter(|| {
                let mut ws = Workspace::new(&settings);
                black_box(contract(&Arm7Point, &x0, &at_one, &settings, &mut ws))
            })
        },
    );
    let hull_settings = arm_settings()
        .with_hull_tolerance(0.10)
        .with_hull_budget(10_000, Some(120.0));
    let hull_options = RunOptions {
        depth: Depth::Hull,
        lsq: false,
    };
    let demo = simulate(&arm, 50, 1, Uncertainty::TRACKER, 1.0, &[]);
    g.bench_function("built-in hull, 50 configurations (arm demo --hull)", |b| {
        b.iter(|| {
            black_box(
                certify_arm(
                    &arm,
                    &demo.readings,
                    &demo.uncertainty,
                    hull_options,
                    &hull_settings,
                )
                .expect("6 joints"),
            )
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
