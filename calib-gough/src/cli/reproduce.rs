//! `gough reproduce`: the paper's Section V experiment on an embedded default.

use calib_core::{certify, hull, sweep, Interval, Settings, Status};
use calib_gough::certification::LegResult;
use calib_gough::lsq::fit_leg;
use calib_gough::plot::{self, Layer, PlotError, Points};
use calib_gough::report::{ratios, write_atomically};
use calib_gough::report_page::{error_bounds, Figure, Input, LegEntry, ReportPage, Section, Table};
use calib_gough::simulate::data_set_files;
use calib_gough::verdict::{self, ConfigurationNames, Standing};
use calib_gough::{
    builtin_hexapod, leg_boxes, simulate, Orientation, Simulation, Uncertainty, PARAMETER_NAMES,
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
    /// Write the certificate and the figures into this folder: report.html (one self-contained
    /// page: verdict, inputs with SHA-256, tables, figures, the comparison with the paper),
    /// fig3.svg (histogram of the least-squares offsets l against the certified intervals),
    /// fig4.svg (the base point's boxes and the least-squares solutions in 3 projections) and
    /// fig5.svg (total box volume per sweep step).
    #[arg(long, value_name = "DIR")]
    out: Option<std::path::PathBuf>,
}

/// The paper's number of measured configurations.
const CONFIGS: usize = 21;

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
    let started = Instant::now();
    let truth = builtin_hexapod();
    let settings = Settings::default();
    println!("Reproducing Daney, Papegay & Neumaier (ICRA 2004), Section V: leg 1 (Table I),");
    println!("{CONFIGS} simulated configurations, initial box x0 = nominal ± 0.1 cm.\n");
    // Findings are printed and kept for the certificate's comparison section.
    let mut notes = Notes::default();
    notes.say(exact_data_check(&truth, a.seed, &settings));
    println!();
    let u = Uncertainty::PAPER;
    let sim = simulate(&truth, CONFIGS, a.seed, u, 1.0, 0.1);
    let e = Experiment::run(&sim, &u, &settings);
    let LeastSquares {
        fits,
        seconds: t_mc,
    } = least_squares_fits(&a, &sim, &u)?;
    let xs = hull_of(&fits);
    let x1 = (e.certified.status != Status::Empty).then_some(e.certified.outer);
    println!(
        "certified (this run): {:?}, {} iterations",
        e.certified.status, e.certified.iterations
    );
    let leg = e.leg(x1);
    let ours = [
        ("x0", Some(e.x0)),
        ("x1", x1),
        ("x2", e.swept.hull),
        ("xs", xs),
        ("outer", leg.outer),
        ("inner", leg.inner),
    ];
    print!("{}", side_by_side(&ours));
    println!(
        "\nx0 initial box, x1 the paper's fixed point, x2 its sweep, xs the hull of the least-squares \
         solutions;\nouter the tight certified hull (every consistent parameter vector lies in it), \
         inner the hull of\nparameter vectors proved consistent: the true range lies between them."
    );
    compare_widths(&mut notes, &e, &leg, x1);
    for (name, certified) in [("x1", x1), ("outer", leg.outer)] {
        notes.say(standing_of_fits(name, &e.x0, certified.as_ref(), &fits));
    }
    println!();
    notes.say(sweep_words(&e.swept));
    notes.say(format!(
        "timing: certify {:.3} s, sweep {:.3} s, hull {:.3} s, {} least-squares fits {t_mc:.3} s ({} threads)",
        e.t_certify,
        e.t_sweep,
        e.t_hull,
        a.samples,
        rayon::current_num_threads()
    ));
    if let Some(dir) = &a.out {
        let run = Run {
            args: &a,
            sim: &sim,
            leg: &leg,
            fits: &fits,
            xs,
            ours: &ours,
            volumes: &e.swept.volumes,
        };
        write_outputs(dir, &run, notes.0, started.elapsed().as_secs_f64())?;
    }
    Ok(0)
}

/// The findings of the run: printed as they come, kept for the certificate.
#[derive(Default)]
struct Notes(Vec<String>);

impl Notes {
    /// Prints `line` and keeps it.
    fn say(&mut self, line: String) {
        println!("{line}");
        self.0.push(line);
    }
}

/// Exact measurements: the certified box shrinks around the truth. The finding in words.
fn exact_data_check(truth: &[calib_gough::Leg], seed: u64, settings: &Settings) -> String {
    let t0 = Instant::now();
    let exact = simulate(truth, CONFIGS, seed, Uncertainty::uniform(1e-9), 0.0, 0.1);
    let boxes = leg_boxes(&exact.measured, &exact.uncertainty, 0);
    let x0 = exact.nominal[0].params().map(|v| Interval::mid_rad(v, 0.1));
    let r = certify(&calib_gough::GoughLeg, &x0, &boxes, settings);
    let worst = r.outer.iter().map(|v| v.rad()).fold(0.0, f64::max);
    let inside = (0..7).all(|j| r.outer[j].contains(truth[0].params()[j]));
    format!(
        "exact data (error bounds 1e-9): {:?} after {} iterations, largest radius {worst:.1e}, truth inside: {inside} ({:.2} s)",
        r.status, r.iterations, t0.elapsed().as_secs_f64()
    )
}

/// The paper's three computations on the noisy data (with the paper's error bounds) and the
/// tight hull, with their times.
struct Experiment {
    x0: [Interval; 7],
    certified: calib_core::Certification<7>,
    swept: calib_core::SweepResult<7>,
    hull: calib_core::Hull<7>,
    t_certify: f64,
    t_sweep: f64,
    t_hull: f64,
}

impl Experiment {
    /// x1 (certify), x2 (sweep) and the tight hull of leg 1 of `sim`.
    fn run(sim: &Simulation, u: &Uncertainty, settings: &Settings) -> Experiment {
        let boxes = leg_boxes(&sim.measured, u, 0);
        let x0 = sim.nominal[0].params().map(|v| Interval::mid_rad(v, 0.1));
        let t1 = Instant::now();
        let certified = certify(&calib_gough::GoughLeg, &x0, &boxes, settings);
        let t_certify = t1.elapsed().as_secs_f64();
        let t2 = Instant::now();
        let swept = sweep(&calib_gough::GoughLeg, &x0, &boxes, settings);
        let t_sweep = t2.elapsed().as_secs_f64();
        let t4 = Instant::now();
        let hull = hull(&calib_gough::GoughLeg, &x0, &boxes, settings);
        let t_hull = t4.elapsed().as_secs_f64();
        Experiment {
            x0,
            certified,
            swept,
            hull,
            t_certify,
            t_sweep,
            t_hull,
        }
    }

    /// Leg 1's result: the tight hull, with x1 and the sweep's x2.
    fn leg(&self, x1: Option<[Interval; 7]>) -> LegResult {
        let mut leg = LegResult::from_hull(0, self.x0, self.hull.clone());
        leg.x1 = x1;
        leg.x2 = Some(self.swept.hull);
        leg.boxes += self.swept.boxes_contracted;
        leg.seconds = self.t_hull + self.t_sweep;
        leg
    }
}

/// xs's samples and the seconds they took.
struct LeastSquares {
    fits: Vec<[f64; 7]>,
    seconds: f64,
}

/// xs's samples: least-squares solutions on measurements drawn inside M ∩ [true - e, true + e].
fn least_squares_fits(
    a: &Args,
    sim: &Simulation,
    u: &Uncertainty,
) -> Result<LeastSquares, Box<dyn std::error::Error>> {
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
            let fit = fit_leg(
                &sim.nominal[0].params(),
                calib_gough::LegModel::AxisAngle,
                &drawn_measurements(&mut rng, sim, u),
            );
            bar.inc(1);
            fit.x
        })
        .collect();
    bar.finish_and_clear();
    Ok(LeastSquares {
        fits,
        seconds: t3.elapsed().as_secs_f64(),
    })
}

/// Leg 1's measurements drawn uniformly inside the measured boxes and around the truth.
fn drawn_measurements(rng: &mut StdRng, sim: &Simulation, u: &Uncertainty) -> Vec<[f64; 8]> {
    sim.measured
        .iter()
        .zip(&sim.poses)
        .zip(&sim.exact_lengths)
        .map(|((c, pose), lengths)| {
            let Orientation::AxisAngle { axis, angle_deg } = c.orientation else {
                unreachable!()
            };
            let p: [f64; 3] = core::array::from_fn(|k| draw(rng, c.p[k], pose.p[k], u.pos));
            let axis: [f64; 3] = core::array::from_fn(|k| draw(rng, axis[k], pose.axis[k], u.axis));
            [
                p[0],
                p[1],
                p[2],
                axis[0],
                axis[1],
                axis[2],
                draw(rng, angle_deg, pose.angle_deg, u.angle_deg),
                draw(rng, c.lengths[0], lengths[0], u.len),
            ]
        })
        .collect()
}

/// xs: the hull of the least-squares solutions (none without samples).
fn hull_of(fits: &[[f64; 7]]) -> Option<[Interval; 7]> {
    fits.first().map(|f0| {
        core::array::from_fn(|j| {
            let (lo, hi) = fits
                .iter()
                .fold((f0[j], f0[j]), |(lo, hi), f| (lo.min(f[j]), hi.max(f[j])));
            Interval::new(lo, hi)
        })
    })
}

/// The width ratios: x1 and the tight hull against their inner bounds, x1 against the hull.
fn compare_widths(notes: &mut Notes, e: &Experiment, leg: &LegResult, x1: Option<[Interval; 7]>) {
    if let Some(ratio) = e.certified.overestimation() {
        notes.say(format!(
            "x1/inner width (x1's own inner bounds):   {}",
            ratios(&ratio)
        ));
    }
    if let Some(ratio) = verdict::width_ratios(leg) {
        notes.say(format!(
            "outer/inner width (tight hull, {} boxes): {}",
            leg.boxes - e.swept.boxes_contracted,
            ratios(&ratio)
        ));
    }
    if let (Some(x1), Some(outer)) = (x1, leg.outer) {
        let shrink: [f64; 7] = core::array::from_fn(|j| x1[j].wid() / outer[j].wid());
        notes.say(format!(
            "x1 width / outer width:                   {}",
            ratios(&shrink)
        ));
    }
}

/// Where the least-squares solutions stand against the certified box `name`, in words.
fn standing_of_fits(
    name: &str,
    x0: &[Interval; 7],
    certified: Option<&[Interval; 7]>,
    fits: &[[f64; 7]],
) -> String {
    // Only fits inside x0 can be refuted: the certificate says nothing beyond x0.
    let (mut refuted, mut beyond) = (0, 0);
    let mut params = [false; 7];
    for f in fits {
        match verdict::standing(x0, certified, f) {
            Standing::Inside => {}
            Standing::Refuted(p) => {
                refuted += 1;
                p.iter().for_each(|&j| params[j] = true);
            }
            Standing::BeyondX0(_) => beyond += 1,
        }
    }
    let sticking: Vec<&str> = (0..7)
        .filter(|&j| params[j])
        .map(|j| PARAMETER_NAMES[j])
        .collect();
    format!(
        "{name}: of {} least-squares solutions, {} lie inside it, {refuted} in x0 but outside \
         it{} (proved not to fit the measurements within their error bounds), {beyond} \
         outside x0 (where nothing is certified)",
        fits.len(),
        fits.len() - refuted - beyond,
        if sticking.is_empty() {
            String::new()
        } else {
            format!(", in {}", sticking.join(", "))
        }
    )
}

/// The sweep's boxes and volumes, in words.
fn sweep_words(s: &calib_core::SweepResult<7>) -> String {
    format!(
        "sweep: {} boxes kept of {} contracted; total volume per step: {}",
        s.boxes.len(),
        s.boxes_contracted,
        s.volumes
            .iter()
            .map(|v| format!("{v:.2e}"))
            .collect::<Vec<_>>()
            .join(" ")
    )
}

/// What `--out` writes from.
struct Run<'a> {
    args: &'a Args,
    sim: &'a Simulation,
    leg: &'a LegResult,
    fits: &'a [[f64; 7]],
    xs: Option<[Interval; 7]>,
    ours: &'a [(&'a str, Option<[Interval; 7]>); 6],
    volumes: &'a [f64],
}

/// --out: the figures as SVG files and the certificate (report.html) with the comparison.
fn write_outputs(
    dir: &std::path::Path,
    run: &Run<'_>,
    notes: Vec<String>,
    seconds: f64,
) -> Result<(), Box<dyn std::error::Error>> {
    let figures = paper_figures(run.fits, run.leg, run.xs, run.volumes)?;
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: cannot create: {e}", dir.display()))?;
    for (name, f) in &figures {
        let path = dir.join(name);
        write_atomically(&path, &f.svg)
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    }
    let comparison = Section {
        heading: "The paper's experiment (Section V, Tables II–IV, Figs. 3–5)".into(),
        paragraphs: notes,
        tables: paper_tables(run.ours),
        figures: figures.into_iter().map(|(_, f)| f).collect(),
    };
    let page = certificate(run.args, run.sim, run.leg, run.fits, comparison, seconds)?;
    let path = dir.join("report.html");
    write_atomically(&path, &page).map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    println!(
        "figures and the certificate (report.html) written to {}",
        dir.display()
    );
    Ok(())
}

/// The certificate of the run: the simulated data identified by the SHA-256 of the files
/// `gough simulate` writes for the same seed, leg 1, and the comparison with the paper.
fn certificate(
    a: &Args,
    sim: &Simulation,
    leg: &LegResult,
    fits: &[[f64; 7]],
    comparison: Section,
    seconds: f64,
) -> Result<String, Box<dyn std::error::Error>> {
    let files = data_set_files(sim, a.seed, 1.0, &[]);
    let generated = format!(
        "simulated (gough simulate --configs {CONFIGS} --seed {} writes the same file)",
        a.seed
    );
    let inputs = files
        .iter()
        .filter(|(name, _)| *name != "truth.json")
        .map(|(name, text)| {
            let role = match *name {
                "robot.toml" => "robot geometry",
                "measurements.csv" => "measurements",
                _ => "error bounds",
            };
            Input::new(role, &format!("{name}: {generated}"), text.as_bytes())
        })
        .collect();
    let lines: Vec<usize> = (2..CONFIGS + 2).collect();
    let settings = Settings::default();
    let page = ReportPage {
        title: format!(
            "the paper's experiment: leg 1 of the built-in hexapod, {CONFIGS} simulated configurations"
        ),
        command: calib_gough::report_page::command_line(),
        date: calib_gough::report_page::now(),
        inputs,
        configurations: CONFIGS,
        error_bounds: error_bounds(&sim.uncertainty, false),
        settings: vec![
            ("seed".into(), a.seed.to_string()),
            ("least-squares samples (xs)".into(), a.samples.to_string()),
            (
                "outer box".into(),
                format!(
                    "tight hull: refine until outer width <= {} x inner width, at most {} boxes",
                    1.0 + settings.hull_tolerance,
                    settings.hull_max_boxes
                ),
            ),
            ("128-box sweep (x2)".into(), "yes".into()),
            ("threads".into(), rayon::current_num_threads().to_string()),
        ],
        seconds,
        legs: vec![LegEntry {
            result: leg,
            nominal: sim.nominal[0].params(),
            least_squares: fits,
            identifiability: &[],
        }],
        names: ConfigurationNames {
            file: "measurements.csv",
            lines: &lines,
            carried: None,
        },
        sections: vec![comparison],
    };
    Ok(page.to_html()?)
}

/// The paper's Tables II–IV next to this run, for the certificate.
fn paper_tables(ours: &[(&str, Option<[Interval; 7]>)]) -> Vec<(String, Table)> {
    table_groups()
        .iter()
        .map(|(title, params)| {
            let mut header = vec!["box".to_string()];
            for &j in *params {
                header.push(format!("{} mid (this run)", PARAMETER_NAMES[j]));
                header.push("rad".into());
                header.push(format!("{} mid (paper)", PARAMETER_NAMES[j]));
                header.push("rad".into());
            }
            let rows = ours
                .iter()
                .map(|(label, b)| {
                    let paper = PAPER.iter().find(|(name, _)| name == label);
                    let mut row = vec![label.to_string()];
                    for &j in *params {
                        match b {
                            Some(b) => {
                                row.push(format!("{:.4}", b[j].mid()));
                                row.push(format!("{:.4}", b[j].rad()));
                            }
                            None => row.extend(["empty".into(), "".into()]),
                        }
                        match paper {
                            Some((_, p)) => {
                                row.push(format!("{:.4}", p[j].0));
                                row.push(format!("{:.4}", p[j].1));
                            }
                            None => row.extend(["—".into(), "—".into()]),
                        }
                    }
                    row
                })
                .collect();
            (
                format!("{title} (mid and radius, cm)"),
                Table { header, rows },
            )
        })
        .collect()
}

/// The paper's three tables: their titles and parameters.
fn table_groups() -> [(&'static str, &'static [usize]); 3] {
    [
        ("Table II: base attachment point a [cm]", &[0, 1, 2]),
        ("Table III: mobile attachment point b [cm]", &[3, 4, 5]),
        ("Table IV: leg length offset l [cm]", &[6]),
    ]
}

/// The paper's Tables II–IV (base point, platform point, offset): for each of x0, x1, x2, xs the
/// mid and rad of this run next to the paper's published values (from its own simulated data).
/// The paper's Tables II–IV next to this run; rows without a published counterpart (the tight hull)
/// show a dash in the paper's column.
fn side_by_side(ours: &[(&str, Option<[Interval; 7]>)]) -> String {
    let mut out = String::new();
    for (title, params) in table_groups() {
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

/// The paper's Figs. 3–5 for this run, with their file names: the least-squares offsets l
/// against the certified intervals, the base point's boxes with the least-squares solutions, and
/// the total box volume per sweep step.
fn paper_figures(
    fits: &[[f64; 7]],
    leg: &LegResult,
    xs: Option<[Interval; 7]>,
    volumes: &[f64],
) -> Result<Vec<(&'static str, Figure)>, PlotError> {
    let offsets: Vec<f64> = fits.iter().map(|f| f[6]).collect();
    let mut bands = vec![("x0", plot::X0, leg.x0[6])];
    bands.extend(leg.x1.map(|b| ("x1 (certified)", plot::X1, b[6])));
    bands.extend(leg.outer.map(|b| ("outer (certified)", plot::OUTER, b[6])));
    let mut layers = plot::leg_layers(leg);
    layers.retain(|l| l.label != "x2");
    layers.extend(xs.map(|b| Layer::outline("xs (hull of least squares)", plot::LEAST_SQUARES, b)));
    Ok(vec![
        (
            "fig3.svg",
            Figure {
                caption: "Fig. 3: histogram of the least-squares offsets l against x0 and the \
                          certified intervals. A solution in x0 but outside a certified interval \
                          does not fit the measurements within their error bounds; outside x0 the \
                          certificate proves nothing."
                    .into(),
                svg: plot::histogram(
                    &offsets,
                    &bands,
                    "Fig. 3: least-squares offsets l vs certified intervals",
                    "l (cm)",
                )?,
            },
        ),
        (
            "fig4.svg",
            Figure {
                caption: "Fig. 4: the base attachment point a in three projections: x0, x1, the \
                          tight outer box, the inner bounds, and the least-squares solutions with \
                          their hull xs."
                    .into(),
                svg: plot::nested_boxes(
                    &layers,
                    Some(Points {
                        label: "least-squares solutions",
                        colour: plot::LEAST_SQUARES,
                        points: fits,
                    }),
                    &[(0, 1), (0, 2), (1, 2)],
                    &PARAMETER_NAMES,
                    "Fig. 4: base attachment point",
                )?,
            },
        ),
        (
            "fig5.svg",
            Figure {
                caption: "Fig. 5: total volume of the boxes kept after each step of the 128-box \
                          bisection sweep (log scale)."
                    .into(),
                svg: plot::log_series(
                    volumes,
                    "Fig. 5: total volume per sweep step",
                    "step",
                    "volume (cm^7)",
                )?,
            },
        ),
    ])
}
