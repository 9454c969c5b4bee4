//! The affine forms of the arm residual over the prior box: linear part versus error radius.
//! `cargo run --release -p calib-arm --example arm_forms`.

use calib_arm::simulate::{measurement_box, Uncertainty};
use calib_arm::{builtin_arm, simulate, Arm6Point};
use calib_core::{Interval, VectorModel};

fn main() {
    let arm = builtin_arm();
    let sim = simulate(&arm, 3, 1, Uncertainty::TRACKER, 1.0, &[]);
    let x0: [Interval; 39] = arm.initial_box().try_into().expect("39");
    for r in &sim.readings {
        let m: [Interval; 9] = measurement_box(r, &sim.uncertainty).expect("6 joints");
        for shrink in [1.0, 0.1, 0.01] {
            let xb = x0.map(|v| Interval::mid_rad(v.mid(), v.rad() * shrink));
            let forms = Arm6Point.linear_enclosures(&xb, &m).expect("vector model");
            for f in &forms {
                let lin: f64 = f.gx.iter().map(|g| g.abs()).sum();
                let meas: f64 = f.gm.iter().map(|g| g.abs()).sum();
                println!(
                    "x{shrink:<5} c {:>10.4}  Σ|gx| {lin:>9.5}  Σ|gm| {meas:.5}  e {:.3e}",
                    f.c, f.e
                );
            }
        }
    }
}
