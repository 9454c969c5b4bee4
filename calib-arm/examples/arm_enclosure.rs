//! How wide are the interval enclosures of the arm residual over the prior box, compared with
//! the range of point values, in interval and in affine arithmetic (`evaluate_rows_tight`)?
//! `cargo run --release -p calib-arm --example arm_enclosure`.

use calib_arm::simulate::{measurement_box, Uncertainty};
use calib_arm::{builtin_arm, simulate, Arm6Point};
use calib_core::{Interval, VectorModel};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn main() {
    let arm = builtin_arm();
    let sim = simulate(&arm, 5, 1, Uncertainty::TRACKER, 1.0, &[]);
    let x0: [Interval; 39] = arm.initial_box().try_into().expect("39");
    let mut rng = StdRng::seed_from_u64(9);
    for r in &sim.readings {
        let m: [Interval; 9] = measurement_box(r, &sim.uncertainty).expect("6 joints");
        for shrink in [1.0, 0.1, 0.01] {
            let xb = x0.map(|v| Interval::mid_rad(v.mid(), v.rad() * shrink));
            let e = Arm6Point.evaluate_rows_interval(&xb, &m);
            let t = Arm6Point.evaluate_rows_tight(&xb, &m);
            let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
            let mut dlo = [[f64::INFINITY; 39]; 3];
            let mut dhi = [[f64::NEG_INFINITY; 39]; 3];
            for _ in 0..2000 {
                let x: [f64; 39] = xb.map(|v| v.inf() + rng.random::<f64>() * v.wid());
                let mm: [f64; 9] = m.map(|v| v.inf() + rng.random::<f64>() * v.wid());
                let p = Arm6Point.evaluate_rows(&x, &mm);
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k].value);
                    hi[k] = hi[k].max(p[k].value);
                    for j in 0..39 {
                        dlo[k][j] = dlo[k][j].min(p[k].dx[j]);
                        dhi[k][j] = dhi[k][j].max(p[k].dx[j]);
                    }
                }
            }
            let ratios = |e: &[calib_core::Evaluation<Interval, 39, 9>; 3]| {
                let over: Vec<String> = (0..3)
                    .map(|k| format!("{:.2}", e[k].value.wid() / (hi[k] - lo[k])))
                    .collect();
                let jac: f64 = (0..3)
                    .flat_map(|k| (0..39).map(move |j| (k, j)))
                    .filter(|&(k, j)| dhi[k][j] > dlo[k][j])
                    .map(|(k, j)| e[k].dx[j].wid() / (dhi[k][j] - dlo[k][j]))
                    .fold(0.0, f64::max);
                format!("value/sampled {over:?}, worst Jacobian entry {jac:.2}")
            };
            println!(
                "box x{shrink:<5} interval: {}; affine: {}",
                ratios(&e),
                ratios(&t)
            );
        }
    }
}
