//! `gough lsq`.

use super::DataFiles;
use calib_gough::files::{read_measurements, read_robot};
use calib_gough::lsq::fit_leg;
use calib_gough::{Orientation, PARAMETER_NAMES};
use rayon::prelude::*;

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    files: DataFiles,
}

pub fn run(a: Args) -> Result<i32, Box<dyn std::error::Error>> {
    let robot = read_robot(&a.files.robot)?;
    let data = read_measurements(&a.files.measurements, robot.len())?;
    let fits: Vec<_> = (0..robot.len())
        .into_par_iter()
        .map(|leg| {
            let m: Vec<[f64; 7]> = data
                .configs
                .iter()
                .map(|c| {
                    let q = match c.orientation {
                        Orientation::Rodrigues(q) => q,
                        Orientation::AxisAngle { axis, angle_deg } => {
                            let t = (angle_deg.to_radians() / 2.0).tan();
                            axis.map(|v| v * t)
                        }
                    };
                    [c.p[0], c.p[1], c.p[2], q[0], q[1], q[2], c.lengths[leg]]
                })
                .collect();
            fit_leg(&robot[leg].nominal.params(), &m)
        })
        .collect();
    print!("{:<4} {:<9}", "leg", "converged");
    for n in PARAMETER_NAMES {
        print!(" {n:>10}");
    }
    println!(" {:>10} {:>12}", "rms f", "max |dL| cm");
    for (leg, f) in fits.iter().enumerate() {
        print!("{:<4} {:<9}", leg + 1, f.converged);
        for v in f.x {
            print!(" {v:>10.4}");
        }
        println!(" {:>10.2e} {:>12.2e}", f.rms, f.max_length_error);
    }
    Ok(0)
}
