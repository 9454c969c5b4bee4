//! Shared helpers of the top-level tests: random simulated problems and box checks.
#![allow(dead_code)] // each test file uses its own subset

use calib_core::Interval;
use calib_gough::{builtin_hexapod, simulate, Leg, Simulation, Uncertainty};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// The box nominal ± `radius` of one leg.
pub fn x0_of(sim: &Simulation, leg: usize, radius: f64) -> [Interval; 7] {
    sim.nominal[leg]
        .params()
        .map(|v| Interval::mid_rad(v, radius))
}

/// Whether the box holds the point.
pub fn contains(b: &[Interval; 7], x: &[f64; 7]) -> bool {
    (0..7).all(|j| b[j].contains(x[j]))
}

/// A random problem: random truth near the built-in hexapod, random number of configurations,
/// random error bounds (per component, from 1e-3 to 10 times the paper's), random noise level.
pub fn random_problem(seed: u64) -> Simulation {
    let mut rng = StdRng::seed_from_u64(seed);
    let truth: Vec<Leg> = builtin_hexapod()
        .iter()
        .map(|leg| Leg::from_params(&leg.params().map(|v| v + rng.random_range(-1.0..1.0))))
        .collect();
    let mut f = || 10f64.powf(rng.random_range(-3.0..1.0));
    let u = Uncertainty {
        pos: Uncertainty::PAPER.pos * f(),
        len: Uncertainty::PAPER.len * f(),
        axis: Uncertainty::PAPER.axis * f(),
        angle_deg: Uncertainty::PAPER.angle_deg * f(),
        q: 0.0,
    };
    let configs = rng.random_range(9..=25);
    let noise = rng.random_range(0.0..=1.0);
    simulate(&truth, configs, seed, u, noise, 0.1)
}
