//! Shared helpers of the top-level tests (and of the `tightness` example): random simulated
//! problems, box checks, and feasible points found independently of the kernel.
#![allow(dead_code)] // each test file uses its own subset

use calib_core::{is_consistent_by_corners, Interval, Model};
use calib_core::{DenseSimplex, LpBackend, LpStatus, Polyhedron};
use calib_gough::GoughLeg;
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

/// The most extreme feasible point of `x0` along `±x_j` (`sign` 1 minimises, -1 maximises)
/// reached from `start` by successive LPs on the first-order consistency conditions
/// `|f + g·d| <= θ w`, with backtracking; every accepted step passes the exhaustive corner test.
/// Independent of the kernel's inner-point search, so it can check the outer box.
pub fn extreme(
    start: [f64; 7],
    j: usize,
    sign: f64,
    x0: &[Interval; 7],
    boxes: &[[Interval; 8]],
) -> [f64; 7] {
    let mut p = start;
    let mut lp = DenseSimplex::default();
    let mut poly = Polyhedron::default();
    let mut c = [0.0; 7];
    c[j] = sign;
    let (mut dual, mut primal) = (vec![0.0; 2 * boxes.len()], [0.0; 7]);
    let mut theta = 0.999;
    for _ in 0..30 {
        let lo: [f64; 7] = core::array::from_fn(|i| x0[i].inf() - p[i]);
        let hi: [f64; 7] = core::array::from_fn(|i| x0[i].sup() - p[i]);
        poly.reset(&lo, &hi);
        for m in boxes {
            let e = GoughLeg.evaluate(&p, &m.map(|v| v.mid()));
            let w: f64 = (0..8).map(|i| e.dm[i].abs() * m[i].rad()).sum();
            poly.push_row(&e.dx, theta * w - e.value);
            poly.push_row(&e.dx.map(|v| -v), theta * w + e.value);
        }
        dual.resize(poly.rows(), 0.0);
        if lp.minimize(&poly, &c, &mut dual, &mut primal) != LpStatus::Optimal {
            break;
        }
        let q: [f64; 7] =
            core::array::from_fn(|i| (p[i] + primal[i]).clamp(x0[i].inf(), x0[i].sup()));
        if is_consistent_by_corners(&GoughLeg, &q, boxes) {
            if (q[j] - p[j]).abs() < 1e-13 {
                break;
            }
            p = q;
        } else {
            theta = 1.0 - 2.0 * (1.0 - theta);
        }
    }
    p
}
