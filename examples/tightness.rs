//! How tight is the certified hull? For simulated hexapods (21 configurations, the paper's error
//! bounds) and a prior box of ± `RADIUS` around the nominal geometry, runs `calib_core::hull` per leg
//! and compares its outer box with feasible points found independently: from the truth, successive
//! linear programs push each parameter towards its extremes, and each point is kept only if every
//! measurement box has corners with residuals of both signs (all 128 corners evaluated). The hull of
//! those points, together with the certified inner box, is a lower bound on the true hull of the
//! solution set.
//!
//! ```sh
//! cargo run --release --example tightness -- [RADIUS] [SEEDS] [THREADS]
//! ```
//! prints per leg the worst `wid(outer)/wid(feasible)`, `wid(outer)/wid(inner)` and
//! `wid(inner)/wid(feasible)` over the seven parameters, the paper's `x1` for comparison, boxes and
//! seconds.
use calib_core::{hull, Interval, Settings};
use calib_gough::{builtin_hexapod, leg_boxes, simulate, GoughLeg, Uncertainty};

// The independent feasible-point finder shared with the tests.
#[path = "../tests/support/mod.rs"]
mod support;
use support::extreme;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let radius: f64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(0.1);
    let seeds: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(3);
    let threads: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool");
    let max_boxes = std::env::var("TIGHTNESS_MAX_BOXES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(Settings::default().hull_max_boxes);
    let settings = Settings::default()
        .with_parallel(threads > 1)
        .with_hull_budget(max_boxes, None);
    println!("prior ± {radius} cm, {seeds} seeds × 6 legs, {threads} thread(s)");
    println!(
        "{:>4} {:>3} {:>10} {:>12} {:>12} {:>12} {:>12} {:>8} {:>8}",
        "seed", "leg", "status", "outer/feas", "outer/inner", "inner/feas", "x1/feas", "boxes", "s"
    );
    let (mut worst, mut worst_time) = (0.0f64, 0.0f64);
    for seed in 0..seeds {
        let sim = simulate(
            &builtin_hexapod(),
            21,
            seed,
            Uncertainty::PAPER,
            1.0,
            radius,
        );
        for leg in 0..6 {
            let boxes = leg_boxes(&sim.measured, &sim.uncertainty, leg);
            let x0 = sim.nominal[leg]
                .params()
                .map(|v| Interval::mid_rad(v, radius));
            let h = pool.install(|| hull(&GoughLeg, &x0, &boxes, &settings));
            let truth = sim.truth[leg].params();
            let mut lo = truth;
            let mut hi = truth;
            for j in 0..7 {
                for sign in [1.0, -1.0] {
                    let p = extreme(truth, j, sign, &x0, &boxes);
                    for i in 0..7 {
                        lo[i] = lo[i].min(p[i]);
                        hi[i] = hi[i].max(p[i]);
                    }
                }
            }
            // Certified inner points are solutions too: the reference is the hull of both.
            if let Some(b) = h.inner {
                for i in 0..7 {
                    lo[i] = lo[i].min(b[i].inf());
                    hi[i] = hi[i].max(b[i].sup());
                }
            }
            let max_ratio = |a: &[Interval; 7], w: &dyn Fn(usize) -> f64| {
                (0..7).map(|j| a[j].wid() / w(j)).fold(0.0f64, f64::max)
            };
            let feas = |j: usize| hi[j] - lo[j];
            let of = max_ratio(&h.outer, &feas);
            let oi = h.ratio.iter().copied().fold(0.0f64, f64::max);
            let inf = h
                .inner
                .map(|b| {
                    (0..7)
                        .map(|j| b[j].wid() / feas(j))
                        .fold(f64::INFINITY, f64::min)
                })
                .unwrap_or(0.0);
            let x1 = h.x1.map(|b| max_ratio(&b, &feas)).unwrap_or(f64::NAN);
            let inside = (0..7).all(|j| h.outer[j].contains(truth[j]));
            assert!(inside, "seed {seed} leg {leg}: truth outside the outer box");
            if std::env::var_os("TIGHTNESS_DETAIL").is_some() {
                for j in 0..7 {
                    let i = h.inner.map(|b| b[j]).unwrap_or(Interval::EMPTY);
                    println!(
                        "     {j} outer [{:.6}, {:.6}] inner [{:.6}, {:.6}] feasible [{:.6}, {:.6}] x0 [{:.4}, {:.4}]",
                        h.outer[j].inf(), h.outer[j].sup(), i.inf(), i.sup(), lo[j], hi[j],
                        x0[j].inf(), x0[j].sup()
                    );
                }
            }
            worst = worst.max(oi);
            worst_time = worst_time.max(h.seconds);
            println!(
                "{seed:>4} {:>3} {:>10} {of:>12.3} {oi:>12.3} {inf:>12.3} {x1:>12.3} {:>8} {:>8.3}",
                leg + 1,
                format!("{:?}", h.status),
                h.boxes_contracted,
                h.seconds
            );
        }
    }
    println!("worst outer/inner {worst:.3}, slowest leg {worst_time:.3} s");
}
