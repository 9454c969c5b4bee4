//! `gough design`.

use calib_gough::design::{
    builtin_robot, certified_widths, criterion_name, extension, geometric_mean, plan, poses_csv,
    Design, DesignRequest, Plan,
};
use calib_gough::files::{
    check_uncertainty, read_measurements, read_robot, read_uncertainty, LegSpec,
};
use calib_gough::geometry::{Leg, Pose};
use calib_gough::measurement::Uncertainty;
use calib_gough::report::write_atomically;
use calib_gough::workspace::{read_workspace, Workspace};
use calib_gough::PARAMETER_NAMES;
use calib_pipeline::design::Criterion;
use std::path::PathBuf;
use std::time::Instant;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Nominal geometry and prior radii (robot.toml). Default: the built-in hexapod, ± 0.1 cm.
    #[arg(long, value_name = "FILE")]
    robot: Option<PathBuf>,
    /// Half-widths of the measurement errors. Default: the paper's (5 µm, 1e-3°).
    #[arg(long, value_name = "FILE")]
    uncertainty: Option<PathBuf>,
    /// The poses allowed (workspace.toml: x, y, z = [lo, hi] cm, tilt_deg, optional stroke).
    /// Default: the simulator's workspace (± 5 cm, 55–65 cm high, 15°, stroke [0, 15] cm).
    #[arg(long, value_name = "FILE")]
    workspace: Option<PathBuf>,
    /// How many configurations to choose.
    #[arg(long, value_name = "K", default_value_t = 21)]
    configs: usize,
    /// How many candidate poses to draw from the workspace.
    #[arg(long, value_name = "N", default_value_t = 2000)]
    candidates: usize,
    /// certified: the smallest predicted certified box (geometric mean of the widths);
    /// d-optimal: the classical index (product of the singular values).
    #[arg(long, value_name = "NAME", default_value = "certified")]
    criterion: Criterion,
    /// Seeds the candidates, the random design compared with, and the simulated noise.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Configurations already measured (measurements.csv of the robot): choose the next ones,
    /// those that shrink the certified box of these data most.
    #[arg(long, value_name = "FILE")]
    extend: Option<PathBuf>,
    /// Also write the design and its predictions as JSON (poses, certified widths per design,
    /// first-order widths).
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
    /// Where to write the poses (header px,py,pz,ax,ay,az,angle_deg), for
    /// `gough simulate --poses` or the measurement campaign.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    let robot = match &a.robot {
        Some(p) => read_robot(p)?,
        None => builtin_robot(),
    };
    let u = match &a.uncertainty {
        Some(p) => {
            let u = read_uncertainty(p)?;
            // The designed poses are given as axis and angle.
            check_uncertainty(p, &u, false)?;
            u
        }
        None => Uncertainty::PAPER,
    };
    let workspace = match &a.workspace {
        Some(p) => read_workspace(p)?,
        None => Workspace::SIMULATOR,
    };
    let already = match &a.extend {
        Some(p) => extension(
            read_measurements(p, robot.len())?,
            &u,
            a.uncertainty.as_deref(),
        )?,
        None => Vec::new(),
    };
    let request = DesignRequest {
        configs: a.configs,
        candidates: a.candidates,
        criterion: a.criterion,
        seed: a.seed,
    };
    let start = Instant::now();
    let bar = indicatif::ProgressBar::new(a.configs as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template("choosing poses {bar:30} {pos}/{len} [{elapsed}]")
            .expect("static template"),
    );
    let plan = plan(&robot, &u, &workspace, &request, &already, &|| bar.inc(1))?;
    bar.finish_and_clear();
    let d = &plan.design;
    if let Some(path) = &a.json {
        write_atomically(path, &format!("{:#}\n", plan.json()))
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    }
    write_atomically(&a.out, &poses_csv(&d.poses))
        .map_err(|e| format!("{}: cannot write: {e}", a.out.display()))?;
    let what = if already.is_empty() {
        String::new()
    } else {
        format!(" after the {} measured", already.len())
    };
    println!(
        "designed {} poses{what} from {} candidates ({} criterion) in {:.1} s: {}",
        d.poses.len(),
        a.candidates,
        criterion_name(a.criterion),
        plan.design_seconds,
        a.out.display()
    );
    print_predictions(&robot, &plan);
    print_separation(&robot, d);
    println!("total: {:.1} s", start.elapsed().as_secs_f64());
    Ok(0)
}

fn print_predictions(robot: &[LegSpec], plan: &Plan) {
    let d = &plan.design;
    let names = ["designed", "random", criterion_name(plan.other)];
    println!(
        "\npredicted certified widths (cm): the tight hull of simulated data measured at each \
         design\n(noise within the error bounds), prior = the robot file's box; first-order best \
         = every candidate measured"
    );
    println!(
        "{:<9}{:>9}{:>11}{:>11}{:>11}{:>13}",
        "", "prior", names[0], names[1], names[2], "first-order"
    );
    for (leg, spec) in robot.iter().enumerate() {
        println!("leg {}", leg + 1);
        let w: Vec<[f64; 7]> = plan
            .predicted
            .iter()
            .map(|r| certified_widths(&r[leg]))
            .collect();
        for (j, name) in PARAMETER_NAMES.iter().enumerate() {
            println!(
                "  {name:<7}{:>9.4}{:>11.4}{:>11.4}{:>11.4}{:>13.4}",
                2.0 * spec.radius[j],
                w[0][j],
                w[1][j],
                w[2][j],
                d.first_order[leg][2][j]
            );
        }
    }
    let gm = plan.geometric_means();
    let params = 7 * robot.len();
    println!(
        "\ngeometric mean of the {params} certified widths: designed {:.4} cm, random {:.4} cm \
         ({:.2}× narrower), {} {:.4} cm ({:.2}×)",
        gm[0],
        gm[1],
        gm[1] / gm[0],
        names[2],
        gm[2],
        gm[2] / gm[0]
    );
    let first: Vec<f64> = (0..3)
        .map(|i| geometric_mean(d.first_order.iter().flat_map(|w| w[i])))
        .collect();
    println!(
        "first order (linearised at the nominal geometry): designed {:.4} cm, random {:.4} cm, \
         every candidate measured {:.4} cm — no design from these candidates does better than \
         {:.2}× random",
        first[0],
        first[1],
        first[2],
        first[1] / first[2]
    );
    match d.matching_prefix {
        Some(m) => println!(
            "the first {m} designed poses already match {} random ones (first order)",
            d.random.len()
        ),
        None => println!(
            "the designed poses do not match {} random ones to first order",
            d.random.len()
        ),
    }
}

/// How well the workspace can tell `a_z` from `l`: their effects on a reading differ by the
/// cosine of the leg's angle to the vertical, so the spread of that cosine over the workspace is
/// what separates them.
fn print_separation(robot: &[LegSpec], d: &Design) {
    let legs: Vec<Leg> = robot.iter().map(|s| s.nominal).collect();
    println!(
        "\na_z and l: their effects on a reading differ by the cosine of the leg's angle to the \
         vertical;\nthe workspace's poses spread it only so far (first-order widths, cm):"
    );
    let [az, l] = [2, 6];
    for (leg, nominal) in legs.iter().enumerate() {
        let cosines: Vec<f64> = d
            .poses
            .iter()
            .chain(&d.random)
            .map(|p| cos_to_vertical(nominal, p))
            .collect();
        let lo = cosines.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = cosines.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let [designed, random, best] = d.first_order[leg];
        let prior = |j: usize| 2.0 * robot[leg].radius[j];
        let verdict = if best[az] >= 0.99 * prior(az) && best[l] >= 0.99 * prior(l) {
            "this workspace cannot separate them: with every candidate measured both keep \
             their prior width"
                .to_string()
        } else {
            format!(
                "a_z {:.4} (best {:.4}, random {:.4}), l {:.4} (best {:.4}, random {:.4})",
                designed[az], best[az], random[az], designed[l], best[l], random[l]
            )
        };
        println!(
            "  leg {}: cos in [{lo:.3}, {hi:.3}] (spread {:.1}%): {verdict}",
            leg + 1,
            100.0 * (hi - lo),
        );
    }
}

/// The cosine of the leg's angle to the vertical at `pose`.
fn cos_to_vertical(leg: &Leg, pose: &Pose) -> f64 {
    let rb = calib_gough::geometry::rotate(&pose.rodrigues(), &leg.b);
    let v: [f64; 3] = core::array::from_fn(|i| pose.p[i] + rb[i] - leg.a[i]);
    v[2].abs() / (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}
