//! `gough simulate`.

use calib_gough::report::write_atomically;
use calib_gough::{builtin_hexapod, simulate, Orientation, Uncertainty};
use std::fmt::Write as _;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Number of measured configurations.
    #[arg(long, default_value_t = 21)]
    configs: usize,
    /// Random seed (the same seed gives the same files).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Noise amplitude as a multiple of the error bounds (<= 1 keeps the truth inside the boxes).
    #[arg(long, default_value_t = 1.0)]
    noise_scale: f64,
    /// Move one leg reading: CONFIG:LEG:DELTA (1-based configuration and leg, DELTA in cm).
    /// Repeat for several outliers: --outlier 5:2:0.3 --outlier 9:2:0.05.
    #[arg(long, value_name = "CONFIG:LEG:DELTA")]
    outlier: Vec<String>,
    /// Output folder (created if missing).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

fn parse_outlier(s: &str, configs: usize) -> Result<(usize, usize, f64), String> {
    let parts: Vec<&str> = s.split(':').collect();
    let bad = || format!("--outlier `{s}`: expected CONFIG:LEG:DELTA, e.g. 5:2:0.1");
    let [c, l, d] = parts[..] else {
        return Err(bad());
    };
    let c: usize = c.parse().map_err(|_| bad())?;
    let l: usize = l.parse().map_err(|_| bad())?;
    let d: f64 = d.parse().map_err(|_| bad())?;
    if c == 0 || c > configs || l == 0 || l > 6 || !d.is_finite() {
        return Err(format!(
            "--outlier `{s}`: configuration must be 1..={configs}, leg 1..=6, delta finite"
        ));
    }
    Ok((c - 1, l - 1, d))
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    if a.configs < 7 {
        return Err(format!(
            "--configs {}: at least 7 configurations are needed",
            a.configs
        )
        .into());
    }
    if !(a.noise_scale.is_finite() && a.noise_scale >= 0.0) {
        return Err("--noise-scale: expected a finite number >= 0".into());
    }
    let outliers = a
        .outlier
        .iter()
        .map(|s| parse_outlier(s, a.configs))
        .collect::<Result<Vec<_>, _>>()?;
    let u = Uncertainty::PAPER;
    let mut sim = simulate(&builtin_hexapod(), a.configs, a.seed, u, a.noise_scale, 0.1);
    for &(c, l, d) in &outliers {
        sim.measured[c].lengths[l] += d;
    }
    std::fs::create_dir_all(&a.out)
        .map_err(|e| format!("{}: cannot create: {e}", a.out.display()))?;
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
        writeln!(csv, "{}", row.join(","))?;
    }
    let mut robot =
        String::from("# nominal geometry (cm); initial box per parameter = value +- radius\n");
    for leg in &sim.nominal {
        writeln!(
            robot,
            "[[leg]]\na = {:?}\nb = {:?}\nl = {:?}\nradius = 0.1\n",
            leg.a, leg.b, leg.l
        )?;
    }
    let unc = format!(
        "# half-widths of the measurement boxes (cm, unitless axis components, degrees)\npos = {:?}\nlen = {:?}\naxis = {:?}\nangle_deg = {:?}\n",
        u.pos, u.len, u.axis, u.angle_deg
    );
    let legs = |v: &[calib_gough::Leg]| -> Vec<serde_json::Value> {
        v.iter()
            .map(|l| serde_json::json!({ "a": l.a, "b": l.b, "l": l.l }))
            .collect()
    };
    let truth = serde_json::json!({
        "generator": "gough simulate",
        "seed": a.seed,
        "p": a.configs,
        "noise_scale": a.noise_scale,
        "param_order": ["a_x", "a_y", "a_z", "b_x", "b_y", "b_z", "l"],
        "legs": legs(&sim.truth),
        "nominal": legs(&sim.nominal),
        "outliers": outliers
            .iter()
            .map(|(c, l, d)| serde_json::json!({ "config": c + 1, "leg": l + 1, "delta": d }))
            .collect::<Vec<_>>(),
    });
    for (name, text) in [
        ("measurements.csv", csv),
        ("robot.toml", robot),
        ("uncertainty.toml", unc),
        ("truth.json", serde_json::to_string_pretty(&truth)?),
    ] {
        let path = a.out.join(name);
        write_atomically(&path, &text)
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    }
    println!("wrote {} configurations to {}", a.configs, a.out.display());
    Ok(0)
}
