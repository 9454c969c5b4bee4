//! `gough reproduce`: the paper's Section V experiment on an embedded default.

use calib_core::{certify, hull, sweep, Interval, Settings, Status};
use calib_gough::geometry::Pose;
use calib_gough::lsq::fit_leg;
use calib_gough::plot;
use calib_gough::report::{ratios, write_atomically};
use calib_gough::{
    builtin_hexapod, leg_boxes, simulate, Orientation, Uncertainty, PARAMETER_NAMES,
};
use indicatif::{ProgressBar, ProgressStyle};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Monte-Carlo least-squares solutions for xs (the paper uses 1000).
    #[arg(long, default_value_t = 1000)]
    samples: usize,
    /// Seed of the simulated data set.
    #[arg(long, default_value_t = 2004)]
    seed: u64,
    /// Write the figures as SVG into this folder: fig3.svg (histogram of the least-squares
    /// offsets l against the certified interval), fig4.svg (x0, x1 and xs of the base point in 3
    /// projections), fig5.svg (total box volume per sweep step).
    #[arg(long, value_name = "DIR")]
    out: Option<std::path::PathBuf>,
}

/// The paper's published mid/rad of x0, x1, x2, xs (Tables II–IV), per parameter.
const PAPER: [(&str, [(f64, f64); 7]); 4] = [
    (
        "x0",
        [
            (-9.6609, 0.1),
            (9.0442, 0.1),
            (0.0251, 0.1),
            (-3.0468, 0.1),
            (7.2122, 0.1),
            (-0.0334, 0.1),
            (52.3376, 0.1),
        ],
    ),
    (
        "x1",
        [
            (-9.6825, 0.0784),
            (9.0988, 0.0455),
            (0.0041, 0.0791),
            (-3.0055, 0.0587),
            (7.2937, 0.0187),
            (-0.0127, 0.0793),
            (52.3164, 0.0789),
        ],
    ),
    (
        "x2",
        [
            (-9.6842, 0.0767),
            (9.1011, 0.0433),
            (0.0038, 0.0788),
            (-3.0026, 0.0558),
            (7.2946, 0.0177),
            (-0.0119, 0.0786),
            (52.3161, 0.0787),
        ],
    ),
    (
        "xs",
        [
            (-9.6904, 0.0735),
            (9.0978, 0.0205),
            (0.0210, 0.1895),
            (-2.9943, 0.0562),
            (7.3002, 0.0071),
            (-0.0080, 0.0726),
            (52.2366, 0.1597),
        ],
    ),
];

/// A value drawn uniformly in `[v - e, v + e] ∩ [t - e, t + e]` (measured `v`, true `t`).
fn draw(rng: &mut StdRng, v: f64, t: f64, e: f64) -> f64 {
    let (lo, hi) = ((v - e).max(t - e), (v + e).min(t + e));
    if lo >= hi {
        lo
    } else {
        rng.random_range(lo..=hi)
    }
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    let truth = builtin_hexapod();
    let settings = Settings::default();
    println!("Reproducing Daney, Papegay & Neumaier (ICRA 2004), Section V: leg 1 (Table I),");
    println!("21 simulated configurations, initial box x0 = nominal ± 0.1 cm.\n");

    // Exact measurements: the certified box shrinks around the truth.
    let t0 = Instant::now();
    let exact = simulate(&truth, 21, a.seed, Uncertainty::uniform(1e-9), 0.0, 0.1);
    let boxes = leg_boxes(&exact.measured, &exact.uncertainty, 0);
    let x0 = exact.nominal[0].params().map(|v| Interval::mid_rad(v, 0.1));
    let r = certify(&calib_gough::GoughLeg, &x0, &boxes, &settings);
    let worst = r.outer.iter().map(|v| v.rad()).fold(0.0, f64::max);
    let inside = (0..7).all(|j| r.outer[j].contains(truth[0].params()[j]));
    println!(
        "exact data (error bounds 1e-9): {:?} after {} iterations, largest radius {worst:.1e}, truth inside: {inside} ({:.2} s)\n",
        r.status, r.iterations, t0.elapsed().as_secs_f64()
    );

    // Noisy measurements with the paper's error bounds.
    let u = Uncertainty::PAPER;
    let sim = simulate(&truth, 21, a.seed, u, 1.0, 0.1);
    let boxes = leg_boxes(&sim.measured, &u, 0);
    let x0 = sim.nominal[0].params().map(|v| Interval::mid_rad(v, 0.1));
    let t1 = Instant::now();
    let c = certify(&calib_gough::GoughLeg, &x0, &boxes, &settings);
    let t_certify = t1.elapsed().as_secs_f64();
    let t2 = Instant::now();
    let s = sweep(&calib_gough::GoughLeg, &x0, &boxes, &settings);
    let t_sweep = t2.elapsed().as_secs_f64();
    let t4 = Instant::now();
    let h = hull(&calib_gough::GoughLeg, &x0, &boxes, &settings);
    let t_hull = t4.elapsed().as_secs_f64();

    // xs: hull of least-squares solutions on measurements drawn inside M ∩ [true - e, true + e].
    let t3 = Instant::now();
    let bar = ProgressBar::new(a.samples as u64);
    bar.set_style(ProgressStyle::with_template(
        "least squares {bar:40} {pos}/{len} [{elapsed_precise}]",
    )?);
    let fits: Vec<[f64; 7]> = (0..a.samples)
        .into_par_iter()
        .map(|i| {
            let mut rng =
                StdRng::seed_from_u64(a.seed ^ (i as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
            let m: Vec<[f64; 7]> = sim
                .measured
                .iter()
                .zip(&sim.poses)
                .zip(&sim.exact_lengths)
                .map(|((c, pose), lengths)| {
                    let Orientation::AxisAngle { axis, angle_deg } = c.orientation else {
                        unreachable!()
                    };
                    let drawn = Pose {
                        p: core::array::from_fn(|k| draw(&mut rng, c.p[k], pose.p[k], u.pos)),
                        axis: core::array::from_fn(|k| {
                            draw(&mut rng, axis[k], pose.axis[k], u.axis)
                        }),
                        angle_deg: draw(&mut rng, angle_deg, pose.angle_deg, u.angle_deg),
                    };
                    let q = drawn.rodrigues();
                    [
                        drawn.p[0],
                        drawn.p[1],
                        drawn.p[2],
                        q[0],
                        q[1],
                        q[2],
                        draw(&mut rng, c.lengths[0], lengths[0], u.len),
                    ]
                })
                .collect();
            let fit = fit_leg(&sim.nominal[0].params(), &m);
            bar.inc(1);
            fit.x
        })
        .collect();
    bar.finish_and_clear();
    let t_mc = t3.elapsed().as_secs_f64();
    let xs: Option<[Interval; 7]> = fits.first().map(|f0| {
        core::array::from_fn(|j| {
            let (lo, hi) = fits
                .iter()
                .fold((f0[j], f0[j]), |(lo, hi), f| (lo.min(f[j]), hi.max(f[j])));
            Interval::new(lo, hi)
        })
    });

    let x1 = (c.status != Status::Empty).then_some(c.outer);
    println!(
        "certified (this run): {:?}, {} iterations",
        c.status, c.iterations
    );
    let outer = (h.status != Status::Empty).then_some(h.outer);
    let ours = [
        ("x0", Some(x0)),
        ("x1", x1),
        ("x2", s.hull),
        ("xs", xs),
        ("outer", outer),
        ("inner", h.inner),
    ];
    print!("{}", side_by_side(&ours));
    println!(
        "\nx0 initial box, x1 the paper's fixed point, x2 its sweep, xs the hull of the least-squares \
         solutions;\nouter the tight certified hull (every consistent parameter vector lies in it), \
         inner the hull of\nparameter vectors proved consistent: the true range lies between them."
    );
    if let Some(ratio) = c.overestimation() {
        println!(
            "x1/inner width (x1's own inner bounds):   {}",
            ratios(&ratio)
        );
    }
    if h.inner.is_some() {
        println!(
            "outer/inner width (tight hull, {} boxes): {}",
            h.boxes_contracted,
            ratios(&h.ratio)
        );
    }
    if let (Some(x1), Some(outer)) = (x1, outer) {
        let shrink: [f64; 7] = core::array::from_fn(|j| x1[j].wid() / outer[j].wid());
        println!(
            "x1 width / outer width:                   {}",
            ratios(&shrink)
        );
    }
    for (name, certified) in [("x1", x1), ("outer", outer)] {
        let (Some(b), Some(xs)) = (certified, xs) else {
            continue;
        };
        let sticking: Vec<&str> = (0..7)
            .filter(|&j| !xs[j].is_subset_of(b[j]))
            .map(|j| PARAMETER_NAMES[j])
            .collect();
        let count = fits
            .iter()
            .filter(|f| (0..7).any(|j| !b[j].contains(f[j])))
            .count();
        if sticking.is_empty() {
            println!(
                "all {} least-squares solutions lie inside {name}",
                fits.len()
            );
        } else {
            println!(
                "{count} of {} least-squares solutions stick out of the certified {name} (in {}): \
                 they are not consistent with the measurements and their error bounds",
                fits.len(),
                sticking.join(", ")
            );
        }
    }
    println!(
        "\nsweep: {} boxes kept of {} contracted; total volume per step: {}",
        s.boxes.len(),
        s.boxes_contracted,
        s.volumes
            .iter()
            .map(|v| format!("{v:.2e}"))
            .collect::<Vec<_>>()
            .join(" ")
    );
    println!(
        "timing: certify {t_certify:.3} s, sweep {t_sweep:.3} s, hull {t_hull:.3} s, {} least-squares fits {t_mc:.3} s ({} threads)",
        a.samples,
        rayon::current_num_threads()
    );
    if let Some(dir) = &a.out {
        write_figures(dir, &fits, x0, x1, xs, &s.volumes)?;
        println!("figures written to {}", dir.display());
    }
    Ok(0)
}

/// The paper's Tables II–IV (base point, platform point, offset): for each of x0, x1, x2, xs the
/// mid and rad of this run next to the paper's published values (from its own simulated data).
/// The paper's Tables II–IV next to this run; rows without a published counterpart (the tight hull)
/// show a dash in the paper's column.
fn side_by_side(ours: &[(&str, Option<[Interval; 7]>)]) -> String {
    let groups: [(&str, &[usize]); 3] = [
        ("Table II: base attachment point a [cm]", &[0, 1, 2]),
        ("Table III: mobile attachment point b [cm]", &[3, 4, 5]),
        ("Table IV: leg length offset l [cm]", &[6]),
    ];
    let mut out = String::new();
    for (title, params) in groups {
        out.push_str(&format!("\n{title}   (this run | paper)\n{:<5}", ""));
        for &j in params {
            out.push_str(&format!(" | {:^39}", PARAMETER_NAMES[j]));
        }
        out.push('\n');
        for (label, b) in ours {
            out.push_str(&format!("{label:<5}"));
            let paper = PAPER.iter().find(|(name, _)| name == label);
            for &j in params {
                let theirs = match paper {
                    Some((_, p)) => format!("{:>9.4} {:>8.4}", p[j].0, p[j].1),
                    None => format!("{:>18}", "—"),
                };
                match b {
                    Some(b) => out.push_str(&format!(
                        " | {:>9.4} {:>8.4} | {theirs}",
                        b[j].mid(),
                        b[j].rad(),
                    )),
                    None => out.push_str(&format!(" | {:>18} | {theirs}", "empty")),
                }
            }
            out.push('\n');
        }
    }
    out
}

fn write_figures(
    dir: &std::path::Path,
    fits: &[[f64; 7]],
    x0: [Interval; 7],
    x1: Option<[Interval; 7]>,
    xs: Option<[Interval; 7]>,
    volumes: &[f64],
) -> Result<(), Box<dyn std::error::Error>> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: cannot create: {e}", dir.display()))?;
    let offsets: Vec<f64> = fits.iter().map(|f| f[6]).collect();
    let mut boxes = vec![("x0", "black", x0)];
    boxes.extend(x1.map(|b| ("x1 (certified)", "#369", b)));
    boxes.extend(xs.map(|b| ("xs (least squares)", "#c33", b)));
    let figures = [
        (
            "fig3.svg",
            plot::histogram(
                &offsets,
                x1.map_or(x0[6], |b| b[6]),
                "Fig. 3: least-squares offsets l vs certified x1",
                "l (cm)",
            ),
        ),
        (
            "fig4.svg",
            plot::nested_boxes(
                &boxes,
                &[(0, 1), (0, 2), (1, 2)],
                &PARAMETER_NAMES,
                "Fig. 4: base attachment point",
            ),
        ),
        (
            "fig5.svg",
            plot::log_series(
                volumes,
                "Fig. 5: total volume per sweep step",
                "step",
                "volume (cm^7)",
            ),
        ),
    ];
    for (name, svg) in figures {
        let path = dir.join(name);
        write_atomically(&path, &svg)
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    }
    Ok(())
}
