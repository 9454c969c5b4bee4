//! Simulated calibration data for a built-in hexapod (paper Section V).

use crate::geometry::{leg_reading, Leg, Pose};
use crate::measurement::{Configuration, Orientation, Uncertainty};
use crate::report::write_atomically;
use crate::GoughError;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use std::fmt::Write as _;
use std::path::Path;

/// The built-in hexapod: leg 1 is the paper's Table I, the other legs those of `sample21`.
pub fn builtin_hexapod() -> Vec<Leg> {
    vec![
        Leg {
            a: [-9.7, 9.1, 0.0],
            b: [-3.0, 7.3, 0.0],
            l: 52.2496,
        },
        Leg {
            a: [-9.669, -9.122, 0.0],
            b: [-3.014, -7.279, 0.0],
            l: 52.3871,
        },
        Leg {
            a: [-3.0478, -12.9064, 0.0],
            b: [-4.795, -6.2591, 0.0],
            l: 52.1183,
        },
        Leg {
            a: [12.7568, -3.8374, 0.0],
            b: [7.814, 1.0279, 0.0],
            l: 52.2959,
        },
        Leg {
            a: [12.6928, 3.8414, 0.0],
            b: [7.841, -1.0359, 0.0],
            l: 52.1837,
        },
        Leg {
            a: [-3.0188, 12.9154, 0.0],
            b: [-4.845, 6.2551, 0.0],
            l: 52.3312,
        },
    ]
}

/// A simulated data set: truth, nominal geometry, exact poses and readings, measurements.
#[derive(Clone, Debug, PartialEq)]
pub struct Simulation {
    /// The true legs.
    pub truth: Vec<Leg>,
    /// The nominal legs: truth perturbed uniformly within ± `perturbation`.
    pub nominal: Vec<Leg>,
    /// The exact poses.
    pub poses: Vec<Pose>,
    /// The exact leg readings, per configuration and leg.
    pub exact_lengths: Vec<Vec<f64>>,
    /// The measurements: exact values plus uniform noise within `noise_scale` × the half-widths.
    pub measured: Vec<Configuration>,
    /// The half-widths the measurements are declared with.
    pub uncertainty: Uncertainty,
}

/// A random pose in a realistic workspace: position within ± 5 cm horizontally and 55–65 cm high,
/// rotation up to 15° about a random axis.
pub fn random_pose(rng: &mut StdRng) -> Pose {
    let axis = loop {
        let v: [f64; 3] = core::array::from_fn(|_| rng.random_range(-1.0..1.0));
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        if n > 0.2 && n <= 1.0 {
            break v.map(|c| c / n);
        }
    };
    Pose {
        p: [
            rng.random_range(-5.0..5.0),
            rng.random_range(-5.0..5.0),
            rng.random_range(55.0..65.0),
        ],
        axis,
        angle_deg: rng.random_range(0.5..15.0),
    }
}

/// Simulates `configs` configurations of `truth` (paper Section V): exact readings from the inverse
/// kinematics, then measurements with uniform noise within `noise_scale × uncertainty`, and a
/// nominal geometry within ± `perturbation` of the truth (strictly inside, so that nominal ±
/// `perturbation` contains the truth).
pub fn simulate(
    truth: &[Leg],
    configs: usize,
    seed: u64,
    uncertainty: Uncertainty,
    noise_scale: f64,
    perturbation: f64,
) -> Simulation {
    let mut pose_rng = StdRng::seed_from_u64(seed.wrapping_add(0x5eed));
    let poses: Vec<Pose> = (0..configs).map(|_| random_pose(&mut pose_rng)).collect();
    simulate_at(truth, &poses, seed, uncertainty, noise_scale, perturbation)
}

/// [`simulate`] at the given poses instead of random ones (the same noise model and nominal
/// geometry for the same seed).
pub fn simulate_at(
    truth: &[Leg],
    poses: &[Pose],
    seed: u64,
    uncertainty: Uncertainty,
    noise_scale: f64,
    perturbation: f64,
) -> Simulation {
    let configs = poses.len();
    let mut rng = StdRng::seed_from_u64(seed);
    let inside = perturbation * (1.0 - 1e-9);
    let nominal = truth
        .iter()
        .map(|leg| {
            let x = leg.params().map(|v| v + rng.random_range(-inside..=inside));
            Leg::from_params(&x)
        })
        .collect();
    let mut exact_lengths = Vec::with_capacity(configs);
    let mut measured = Vec::with_capacity(configs);
    let mut noise = |h: f64| rng.random_range(-1.0..=1.0) * h * noise_scale;
    for pose in poses {
        let lengths: Vec<f64> = truth.iter().map(|leg| leg_reading(leg, pose)).collect();
        let noisy = Configuration {
            p: pose.p.map(|v| v + noise(uncertainty.pos)),
            orientation: Orientation::AxisAngle {
                axis: pose.axis.map(|v| v + noise(uncertainty.axis)),
                angle_deg: pose.angle_deg + noise(uncertainty.angle_deg),
            },
            lengths: lengths.iter().map(|v| v + noise(uncertainty.len)).collect(),
        };
        exact_lengths.push(lengths);
        measured.push(noisy);
    }
    Simulation {
        truth: truth.to_vec(),
        nominal,
        poses: poses.to_vec(),
        exact_lengths,
        measured,
        uncertainty,
    }
}

/// Simulates the built-in hexapod (the paper's error bounds, nominal geometry within ± 0.1 cm) with
/// leg readings moved by `outliers` (`(configuration, leg, delta)`, 0-based, delta in cm), and
/// writes the data set `gough simulate` writes into `dir`: `measurements.csv`, `robot.toml`,
/// `uncertainty.toml` and `truth.json` (each written atomically). Returns the simulation.
pub fn write_data_set(
    dir: &Path,
    configs: usize,
    seed: u64,
    noise_scale: f64,
    outliers: &[(usize, usize, f64)],
) -> Result<Simulation, GoughError> {
    if configs < 7 {
        return Err(GoughError::TooFewConfigurations(configs));
    }
    let mut pose_rng = StdRng::seed_from_u64(seed.wrapping_add(0x5eed));
    let poses: Vec<Pose> = (0..configs).map(|_| random_pose(&mut pose_rng)).collect();
    write_data_set_at(dir, &poses, seed, noise_scale, outliers)
}

/// [`write_data_set`] at the given poses (`gough simulate --poses`): one configuration per pose.
pub fn write_data_set_at(
    dir: &Path,
    poses: &[Pose],
    seed: u64,
    noise_scale: f64,
    outliers: &[(usize, usize, f64)],
) -> Result<Simulation, GoughError> {
    let configs = poses.len();
    if configs < 7 {
        return Err(GoughError::TooFewPoses(configs));
    }
    if !(noise_scale.is_finite() && noise_scale >= 0.0) {
        return Err(GoughError::NoiseScale);
    }
    if let Some((c, l, d)) = outliers
        .iter()
        .find(|(c, l, d)| *c >= configs || *l >= 6 || !d.is_finite())
    {
        return Err(GoughError::Outlier {
            configuration: *c,
            leg: *l,
            delta: *d,
            configs,
        });
    }
    let u = Uncertainty::PAPER;
    let mut sim = simulate_at(&builtin_hexapod(), poses, seed, u, noise_scale, 0.1);
    for &(c, l, d) in outliers {
        sim.measured[c].lengths[l] += d;
    }
    std::fs::create_dir_all(dir).map_err(|source| GoughError::CreateDir {
        path: dir.to_path_buf(),
        source,
    })?;
    for (name, text) in data_set_files(&sim, seed, noise_scale, outliers) {
        let path = dir.join(name);
        write_atomically(&path, &text).map_err(|source| GoughError::Write { path, source })?;
    }
    Ok(sim)
}

/// The files of a simulated data set, as `(name, text)`: `measurements.csv`, `robot.toml`,
/// `uncertainty.toml` and `truth.json` — what [`write_data_set`] writes, byte for byte (so their
/// SHA-256 identify the data of `gough reproduce` too).
pub fn data_set_files(
    sim: &Simulation,
    seed: u64,
    noise_scale: f64,
    outliers: &[(usize, usize, f64)],
) -> [(&'static str, String); 4] {
    let (u, configs) = (sim.uncertainty, sim.measured.len());
    let mut csv = String::from("px,py,pz,ax,ay,az,angle_deg,L1,L2,L3,L4,L5,L6\n");
    for c in &sim.measured {
        let Orientation::AxisAngle { axis, angle_deg } = c.orientation else {
            unreachable!("simulated axis-angle")
        };
        let mut row: Vec<String> =
            c.p.iter()
                .chain(&axis)
                .chain([&angle_deg])
                .map(|v| format!("{v:?}"))
                .collect();
        row.extend(c.lengths.iter().map(|v| format!("{v:?}")));
        let _ = writeln!(csv, "{}", row.join(","));
    }
    let mut robot =
        String::from("# nominal geometry (cm); initial box per parameter = value +- radius\n");
    for leg in &sim.nominal {
        let _ = writeln!(
            robot,
            "[[leg]]\na = {:?}\nb = {:?}\nl = {:?}\nradius = 0.1\n",
            leg.a, leg.b, leg.l
        );
    }
    let unc = format!(
        "# half-widths of the measurement boxes (cm, unitless axis components, degrees)\npos = {:?}\nlen = {:?}\naxis = {:?}\nangle_deg = {:?}\n",
        u.pos, u.len, u.axis, u.angle_deg
    );
    let legs = |v: &[Leg]| -> Vec<serde_json::Value> {
        v.iter()
            .map(|l| serde_json::json!({ "a": l.a, "b": l.b, "l": l.l }))
            .collect()
    };
    let truth = serde_json::json!({
        "generator": "gough simulate",
        "seed": seed,
        "p": configs,
        "noise_scale": noise_scale,
        "param_order": ["a_x", "a_y", "a_z", "b_x", "b_y", "b_z", "l"],
        "legs": legs(&sim.truth),
        "nominal": legs(&sim.nominal),
        "outliers": outliers
            .iter()
            .map(|(c, l, d)| serde_json::json!({ "config": c + 1, "leg": l + 1, "delta": d }))
            .collect::<Vec<_>>(),
    });
    [
        ("measurements.csv", csv),
        ("robot.toml", robot),
        ("uncertainty.toml", unc),
        ("truth.json", format!("{truth:#}")),
    ]
}
