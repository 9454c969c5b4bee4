//! Times the kernel on the built-in arm: `cargo run --release -p calib-arm --example arm_kernel
//! [configs] [seed]`. Prints the contraction to x1 and the certification, with the truth check.

use calib_arm::simulate::{measurement_box, Uncertainty};
use calib_arm::{builtin_arm, params, simulate, Arm6Point};
use calib_core::{certify, Interval, Settings};
use std::time::Instant;

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let configs = args.first().copied().unwrap_or(50);
    let seed = args.get(1).copied().unwrap_or(1) as u64;
    let arm = builtin_arm();
    let sim = simulate(&arm, configs, seed, Uncertainty::TRACKER, 1.0, &[]);
    let data: Vec<[Interval; 9]> = sim
        .readings
        .iter()
        .map(|r| measurement_box(r, &sim.uncertainty).expect("6 joints"))
        .collect();
    let x0: [Interval; 39] = arm.initial_box().try_into().expect("39 parameters");
    let start = Instant::now();
    let mut settings = Settings::default();
    if std::env::var("ARM_LP").as_deref() == Ok("clarabel") {
        settings = settings.with_lp(calib_core::lp::LpEngine::Clarabel);
    }
    let c = certify(&Arm6Point, &x0, &data, &settings);
    println!(
        "certify: {:?} in {:.2} s, {} Newton/LP steps, {} LP solves ({} failed)",
        c.status,
        start.elapsed().as_secs_f64(),
        c.iterations,
        c.lp_solves,
        c.lp_failures
    );
    let names = params::names(6);
    for (j, (name, unit)) in names.iter().enumerate() {
        if x0[j].wid() == 0.0 {
            continue;
        }
        let scale = if *unit == params::Unit::Deg {
            180.0 / std::f64::consts::PI
        } else {
            1.0
        };
        let truth = if *unit == params::Unit::Deg {
            sim.truth[j].to_radians()
        } else {
            sim.truth[j]
        };
        let inner = c.inner.map(|i| i[j].wid() * scale).unwrap_or(f64::NAN);
        println!(
            "{name:>8}: x0 width {:.4} {} -> outer {:.5}, inner {:.5}, truth inside: {}",
            x0[j].wid() * scale,
            unit.symbol(),
            c.outer[j].wid() * scale,
            inner,
            c.outer[j].contains(truth)
        );
    }
}
