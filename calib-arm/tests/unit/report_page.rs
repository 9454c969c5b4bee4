//! The tests of `calib_arm::report_page`.

use calib_arm::certification::ArmRun;
use calib_arm::report_page::*;
use calib_arm::simulate::Uncertainty;
use calib_core::{Interval, Status};
use calib_pipeline::html::Input;
use calib_pipeline::identify::Identifiability;
use calib_pipeline::lsq::Fit;
use calib_pipeline::verdict::ConfigurationNames;
use calib_pipeline::Outcome;

fn run(fit: f64) -> ArmRun {
    let names: Vec<String> = (0..14).map(|j| format!("p{j}")).collect();
    let x0 = vec![Interval::new(-1.0, 1.0); 14];
    ArmRun {
        outcome: Outcome {
            names,
            x0,
            status: Status::Consistent,
            emptiness: None,
            x1: None,
            outer: Some(vec![Interval::new(-0.5, 0.5); 14]),
            inner: Some(vec![Interval::new(-0.25, 0.25); 14]),
            witness: Some(vec![0.0; 14]),
            conflict: None,
            support: None,
            spread: false,
            outliers: vec![],
            iterations: 3,
            converged: Some(true),
            boxes: 7,
            seconds: 1.5,
        },
        identifiability: Identifiability::default(),
        fit: Some(Fit {
            x: vec![fit; 14],
            converged: true,
            rms: 0.01,
            max_abs: 0.02,
            evaluations: 5,
        }),
        set: None,
        pose_set: None,
        two_frame_set: None,
    }
}

fn page(run: &ArmRun) -> String {
    let lines: Vec<usize> = (2..12).collect();
    ArmReportPage {
        title: "3-axis <arm>".into(),
        command: "arm certify".into(),
        date: "2026-11-24T00:00:00Z".into(),
        inputs: vec![Input::new("measurements", "m.csv", b"q1")],
        uncertainty: Uncertainty::TRACKER,
        settings: vec![("mode".into(), "hull".into())],
        run,
        names: ConfigurationNames {
            file: "m.csv",
            lines: &lines,
            carried: None,
        },
        tolerated: 0,
        truth: None,
        error_scale: vec!["certified consistent at × 7.69 <here>".into()],
    }
    .to_html()
}

#[test]
fn the_page_states_the_boxes_and_where_least_squares_stands() {
    let inside = page(&run(0.1));
    assert!(inside.contains("3-axis &lt;arm&gt;"));
    assert!(inside.contains("[-0.50000, 0.50000]") && inside.contains("[-0.25000, 0.25000]"));
    assert!(inside.contains("lies inside the certified outer box"));
    assert!(inside.contains("Largest outer/inner width ratio: <b>2.000</b>"));
    assert!(inside.contains("Error scale: certified consistent at × 7.69 &lt;here&gt;"));
    let refuted = page(&run(0.75));
    assert!(refuted.contains("proved not to fit"), "{refuted}");
    assert!(refuted.contains("0.75000 (outside outer)"));
    let beyond = page(&run(2.0));
    assert!(beyond.contains("outside the prior box x0"));
}
