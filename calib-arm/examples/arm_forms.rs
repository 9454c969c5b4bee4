//! The affine forms of the arm residual over the prior box (and boxes 10 and 100 times smaller):
//! linear part versus error radius, and the width of the form's range against the natural
//! interval evaluation of the residual (the wrapping effect of a chain of rotations).
//! `cargo run --release -p calib-arm --example arm_forms`.

use calib_arm::certification::padded_box;
use calib_arm::simulate::{measurement_box, Uncertainty};
use calib_arm::{builtin_arm, simulate, Arm7Point};
use calib_core::{Interval, VectorModel};

fn main() {
    let arm = builtin_arm();
    let sim = simulate(&arm, 3, 1, Uncertainty::TRACKER, 1.0, &[]);
    let x0 = padded_box(&arm);
    for r in &sim.readings {
        let m: [Interval; 10] = measurement_box(r, &sim.uncertainty).expect("6 joints");
        for shrink in [1.0, 0.1, 0.01] {
            let xb = x0.map(|v| Interval::mid_rad(v.mid(), v.rad() * shrink));
            let forms = Arm7Point.linear_enclosures(&xb, &m).expect("vector model");
            let natural = Arm7Point.residuals_interval(&xb, &m);
            for (f, n) in forms.iter().zip(natural) {
                let lin: f64 = f.gx.iter().map(|g| g.abs()).sum();
                let meas: f64 = f.gm.iter().map(|g| g.abs()).sum();
                println!(
                    "x{shrink:<5} c {:>10.4}  Σ|gx| {lin:>9.5}  Σ|gm| {meas:.5}  e {:.3e}  \
                     interval/affine width {:.1}",
                    f.c,
                    f.e,
                    n.wid() / f.range().wid()
                );
            }
        }
    }
}
