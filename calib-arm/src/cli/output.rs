//! What `arm certify` and `arm demo` print: the identifiability findings, the verdict, a table of
//! the parameters, and the JSON report.

use calib_arm::certification::{json_report, units_of, ArmRun};
use calib_arm::report_page::ArmReportPage;
use calib_arm::ArmError;
use calib_core::{Interval, Status};
use calib_pipeline::html::outward;
use calib_pipeline::verdict::{self, ConfigurationNames};
use calib_pipeline::{is_fixed, write_atomically};
use std::path::Path;

/// The identifiability findings, before certification.
pub fn print_identifiability(run: &ArmRun) {
    let sv = &run.identifiability.singular_values;
    if let (Some(first), Some(last)) = (sv.first(), sv.last()) {
        println!(
            "identifiability: {} free parameters; singular values of the scaled identification \
             Jacobian {first:.3e} … {last:.3e}",
            sv.len()
        );
    }
    let sentences = run.identifiability.sentences(&run.outcome.names);
    if sentences.is_empty() {
        println!("  every free parameter is determined by these configurations (to first order)");
    }
    for s in sentences {
        println!("  {s}");
    }
}

/// The verdict, the table and the sentences that qualify it.
pub fn print_outcome(run: &ArmRun, names: &ConfigurationNames<'_>, max_outliers: usize) {
    let o = &run.outcome;
    for s in verdict::verdict(o, names, max_outliers) {
        println!("{s}");
    }
    if o.status == calib_core::Status::Empty && !o.spread {
        // (A spread misfit's sentences already say what to do.)
        println!(
            "if a few readings are bad, tolerate them (--max-outliers); if every configuration is \
             a little off — the model does not describe the arm to these bounds (real arms bend \
             and their gears play) — tolerating outliers only hides it: find the bounds the data \
             need with --error-scale auto"
        );
    }
    let units = units_of(&o.names);
    let ratios = o.width_ratios();
    let lsq = run.fit.as_ref().map(|f| &f.x);
    println!(
        "\n{:<9} {:<4} {:>26} {:>26} {:>26} {:>7}{}",
        "parameter",
        "unit",
        "x0",
        "outer",
        "inner",
        "ratio",
        if lsq.is_some() { "  least squares" } else { "" }
    );
    let mut fixed = Vec::new();
    for j in 0..o.x0.len() {
        if is_fixed(o.x0[j]) {
            fixed.push(o.names[j].as_str());
            continue;
        }
        let cell = |b: &Option<Vec<Interval>>| b.as_ref().map_or("—".into(), |b| outward(b[j]));
        let ratio = ratios
            .as_ref()
            .map_or("—".into(), |r| format!("{:.3}", r[j]));
        let fit = lsq.map_or(String::new(), |x| {
            let mark = match o.outer.as_ref() {
                Some(b) if !b[j].contains(x[j]) => "  (outside outer: refuted)",
                None if o.status == Status::Empty => "  (refuted)",
                _ => "",
            };
            format!("  {:.5}{mark}", x[j])
        });
        println!(
            "{:<9} {:<4} {:>26} {:>26} {:>26} {:>7}{fit}",
            o.names[j],
            units[j],
            outward(o.x0[j]),
            cell(&o.outer),
            cell(&o.inner),
            ratio
        );
    }
    if !fixed.is_empty() {
        println!("fixed (radius 0): {}", fixed.join(", "));
    }
    if let Some(line) = verdict::not_determined(o) {
        println!("{line}");
    }
    if let Some(line) = verdict::outliers(o, names, max_outliers) {
        println!("{line}");
    }
    match o.converged {
        None if o.inner.is_some() => println!(
            "ratio: after one contraction (the paper's x1); --hull refines to the tight hull"
        ),
        _ => {
            if let Some(meaning) = verdict::tightness(o) {
                println!("ratio: {meaning}");
            }
        }
    }
    if let Some(f) = &run.fit {
        println!(
            "least squares: rms {:.4} mm, max {:.4} mm over every coordinate ({})",
            f.rms,
            f.max_abs,
            if f.converged {
                "converged"
            } else {
                "did not converge"
            }
        );
    }
    println!(
        "time: {:.2} s, {} Newton/LP steps, {} box{}",
        o.seconds,
        o.iterations,
        o.boxes,
        if o.boxes == 1 { "" } else { "es" }
    );
}

/// Writes the JSON report of a run, with the `extra` top-level entries (`error_scale`,
/// `calibrated`) merged in.
pub fn write_json(
    path: &Path,
    run: &ArmRun,
    names: &ConfigurationNames<'_>,
    max_outliers: usize,
    extra: serde_json::Map<String, serde_json::Value>,
) -> Result<(), ArmError> {
    let mut text = json_report(run, names, max_outliers);
    if !extra.is_empty() {
        let mut v: serde_json::Value =
            serde_json::from_str(&text).map_err(|e| ArmError::JsonReport(e.to_string()))?;
        for (key, value) in extra {
            v[key] = value;
        }
        text = format!("{v:#}\n");
    }
    write_atomically(path, &text).map_err(|e| ArmError::Write {
        path: path.to_path_buf(),
        reason: e.to_string(),
    })
}

/// A spinner on a terminal while the kernel works (indicatif draws nothing when stderr is not a
/// terminal).
pub fn spinner(message: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new_spinner();
    bar.set_style(
        indicatif::ProgressStyle::with_template("{spinner} {msg} [{elapsed}]")
            .expect("static template"),
    );
    bar.set_message(message.to_string());
    bar.enable_steady_tick(std::time::Duration::from_millis(200));
    bar
}

/// The file name as the user should see it in messages.
pub fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |f| f.to_string_lossy().into(),
    )
}

/// Writes the certificate page (atomically) and says where.
pub fn write_certificate(path: &Path, page: &ArmReportPage<'_>) -> Result<(), ArmError> {
    write_atomically(path, &page.to_html()).map_err(|e| ArmError::WriteCertificate {
        path: path.to_path_buf(),
        reason: e.to_string(),
    })?;
    println!("certificate written to {}", path.display());
    Ok(())
}
