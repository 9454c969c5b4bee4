//! The planning and acceptance work around a calibration, on the default hexapod (the built-in
//! geometry, the paper's error bounds, the simulator's workspace): `gough design` (21 poses from
//! 2,000 candidates, certified criterion; issue target ≤ 60 s on 2 cores) and the accuracy
//! certificate's leg-length brackets (all six legs to 1.04, ± 0.01 cm and ± 0.1 cm boxes; issue
//! target ≤ 30 s on 2 cores), its platform pose-error instances (search and proof of the reached
//! pose, position and orientation) and both errors bracketed (instances and upper bounds) for a
//! tightly calibrated robot (± 0.001 cm) on a small workspace (± 0.3 cm, 0.5°); and the serial
//! arm's tool-point accuracy on a ± 3° cell of all six joints (the built-in arm, 1/20 of its
//! prior box, ± 0.001° joints), bracketed within 1.05.
//!
//! `cargo bench --bench planning`. One iteration is one whole design or one whole certificate.

use calib_arm::accuracy::{certify_tool_accuracy, ToolAccuracyProblem, ToolAccuracySettings};
use calib_arm::joint_space::JointSpace;
use calib_gough::accuracy::{
    certify_accuracy, pose_error_instances, pose_errors, AccuracyProblem, AccuracySettings,
    PoseBoundSettings,
};
use calib_gough::design::{builtin_robot, design, DesignRequest};
use calib_gough::files::LegSpec;
use calib_gough::measurement::Uncertainty;
use calib_gough::workspace::Workspace;
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("planning");
    g.sample_size(10);
    let robot = builtin_robot();
    g.bench_function("design/21 of 2000 candidates, certified", |b| {
        b.iter(|| {
            black_box(design(
                &robot,
                &Uncertainty::PAPER,
                &Workspace::SIMULATOR,
                &DesignRequest::default(),
                &[],
                &|| {},
            ))
        })
    });
    for radius in [0.01, 0.1] {
        let boxes: Vec<LegSpec> = robot
            .iter()
            .map(|s| LegSpec {
                nominal: s.nominal,
                radius: [radius; 7],
            })
            .collect();
        g.bench_function(format!("accuracy/leg lengths, ±{radius} cm"), |b| {
            b.iter(|| {
                black_box(certify_accuracy(
                    &AccuracyProblem::new(&boxes, &Workspace::SIMULATOR),
                    &AccuracySettings::default(),
                ))
            })
        });
        let problem = AccuracyProblem::new(&boxes, &Workspace::SIMULATOR);
        g.bench_function(
            format!("accuracy/pose-error instances, ±{radius} cm"),
            |b| b.iter(|| black_box(pose_error_instances(&problem, Uncertainty::PAPER.len))),
        );
    }
    let tight: Vec<LegSpec> = robot
        .iter()
        .map(|s| LegSpec {
            nominal: s.nominal,
            radius: [0.001; 7],
        })
        .collect();
    let small = Workspace {
        x: [-0.3, 0.3],
        y: [-0.3, 0.3],
        z: [59.7, 60.3],
        tilt_deg: 0.5,
        stroke: None,
    };
    let problem = AccuracyProblem::new(&tight, &small);
    g.bench_function(
        "accuracy/pose errors bracketed, ±0.001 cm, small workspace",
        |b| {
            b.iter(|| {
                black_box(pose_errors(
                    &problem,
                    Uncertainty::PAPER.len,
                    &PoseBoundSettings::default(),
                ))
            })
        },
    );
    let arm = calib_arm::builtin_arm().with_radii_scaled(0.05);
    let cell = JointSpace {
        ranges_deg: [10.0, -80.0, 95.0, -100.0, 85.0, 30.0]
            .iter()
            .map(|q| [*q - 3.0, *q + 3.0])
            .collect(),
    };
    if let Ok(problem) = ToolAccuracyProblem::new(&arm, &cell, 0.001) {
        g.bench_function(
            "accuracy/arm tool point bracketed, ± 3° cell of six joints",
            |b| {
                b.iter(|| {
                    black_box(certify_tool_accuracy(
                        &problem,
                        &ToolAccuracySettings::default(),
                    ))
                })
            },
        );
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
