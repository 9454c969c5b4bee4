//! Evaluates the Gough leg model on an embedded box: the paper's Table I leg with the initial box
//! `x0 = x ± 0.1` and one measured configuration (position, axis, angle in degrees, reading) with
//! the paper's error bounds, then prints the
//! interval residual and Jacobians next to the point values at the box centre.
//!
//! `cargo run --release --example gough_leg`

use calib_core::{Interval, Model};
use calib_gough::{GoughLeg, MEASUREMENT_NAMES, PARAMETER_NAMES};

fn main() {
    let truth = [-9.7, 9.1, 0.0, -3.0, 7.3, 0.0, 52.2496];
    let x = truth.map(|v| Interval::mid_rad(v, 0.1));
    let m_mid = [
        4.688, 3.9394, 62.548, 0.0802, -0.9956, -0.0491, 7.1448, 11.0836,
    ];
    let m_rad = [5e-4, 5e-4, 5e-4, 5e-6, 5e-6, 5e-6, 1e-3, 5e-4];
    let m: [Interval; 8] = core::array::from_fn(|i| Interval::mid_rad(m_mid[i], m_rad[i]));

    let e = GoughLeg.evaluate_interval(&x, &m);
    let p = GoughLeg.evaluate(&x.map(Interval::mid), &m.map(Interval::mid));
    println!(
        "Gough leg residual f(x, M) = ||P + R(axis, angle) b - a||^2 - (L + l)^2 (paper eq. 3)"
    );
    println!("over x = Table I ± 0.1 and one configuration M ± the paper's error bounds\n");
    println!(
        "{:>10} {:>42} {:>14}",
        "", "interval enclosure", "at the centre"
    );
    println!("{:>10} {:>42} {:>14.6}", "f", e.value.to_string(), p.value);
    for (i, name) in PARAMETER_NAMES.iter().enumerate() {
        let label = format!("df/d{name}");
        println!("{label:>10} {:>42} {:>14.6}", e.dx[i].to_string(), p.dx[i]);
    }
    for (i, name) in MEASUREMENT_NAMES.iter().enumerate() {
        let label = format!("df/d{name}");
        println!("{label:>10} {:>42} {:>14.6}", e.dm[i].to_string(), p.dm[i]);
    }
    let inside = e.value.contains(p.value)
        && (0..7).all(|i| e.dx[i].contains(p.dx[i]))
        && (0..8).all(|i| e.dm[i].contains(p.dm[i]));
    println!("\npoint values inside the enclosures: {inside}");
}
