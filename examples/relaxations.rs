//! Compares the linear relaxations (the paper's Krawczyk rows, corner rows, both) on simulated Gough
//! data: certified radii, iterations and time, for exact and for noisy measurements.
//!
//! `cargo run --release --example relaxations`

use calib_core::{certify, Interval, Relaxation, Settings};
use calib_gough::{builtin_hexapod, leg_boxes, simulate, GoughLeg, Uncertainty};
use std::time::Instant;

fn main() {
    let truth = builtin_hexapod();
    let cases = [
        ("exact (half-widths 1e-9)", Uncertainty::uniform(1e-9), 0.0),
        ("noisy (paper bounds)", Uncertainty::PAPER, 1.0),
    ];
    for (label, u, noise) in cases {
        println!("== {label}");
        for seed in [1u64, 2] {
            let sim = simulate(&truth, 21, seed, u, noise, 0.1);
            for leg in 0..6 {
                let boxes = leg_boxes(&sim.measured, &u, leg);
                let x0 = sim.nominal[leg].params().map(|v| Interval::mid_rad(v, 0.1));
                let t = sim.truth[leg].params();
                for rel in [Relaxation::Krawczyk, Relaxation::Corners, Relaxation::Both] {
                    let s = Settings::default().with_relaxation(rel);
                    let start = Instant::now();
                    let r = certify(&GoughLeg, &x0, &boxes, &s);
                    let dt = start.elapsed();
                    let inside = (0..7).all(|j| r.outer[j].contains(t[j]));
                    let rads: Vec<String> =
                        r.outer.iter().map(|v| format!("{:.1e}", v.rad())).collect();
                    println!(
                        "seed {seed} leg {} {rel:>9?} it {:>3} {:>8.1?} truth-in {inside} status {:?} rad {}",
                        leg + 1,
                        r.iterations,
                        dt,
                        r.status,
                        rads.join(" ")
                    );
                }
            }
        }
    }
}
