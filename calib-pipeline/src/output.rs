//! Writing outputs: files so that nothing is half-written, standard output so that a closed pipe
//! ends the program quietly.

use std::path::Path;

/// Writes `text` to `path` atomically: to a temporary file beside it, then renamed (a reader sees
/// the old file or the whole new one, never a part).
pub fn write_atomically(path: &Path, text: &str) -> std::io::Result<()> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = dir.join(format!(".{name}.tmp{}", std::process::id()));
    std::fs::write(&tmp, text)?;
    std::fs::rename(&tmp, path).inspect_err(|_| {
        let _ = std::fs::remove_file(&tmp);
    })
}

/// The exit status after standard output was closed under the program (128 + SIGPIPE: what a
/// shell reports for a tool that the closed pipe stopped, so `set -o pipefail` still sees it).
pub const CLOSED_OUTPUT_STATUS: i32 = 141;

/// Makes a closed standard output (`gough certify … | head`) end the program quietly, as
/// command-line tools do: `println!` panics when its pipe is closed, and this panic hook turns
/// exactly that panic into a silent exit with [`CLOSED_OUTPUT_STATUS`]. Every other panic goes to
/// the hook that was installed before. Call it first thing in `main`.
pub fn exit_quietly_when_output_closes() {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let payload = info.payload();
        let message = payload
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| payload.downcast_ref::<&str>().copied())
            .unwrap_or("");
        if is_closed_output(message) {
            std::process::exit(CLOSED_OUTPUT_STATUS);
        }
        previous(info)
    }));
}

/// The `main` of a robot's command-line tool: installs [`exit_quietly_when_output_closes`], runs
/// `run` (which parses the arguments and does the work), prints an error as `error: …` on
/// standard error, and exits with `run`'s code, or 1 after an error.
pub fn main_with(run: impl FnOnce() -> Result<i32, Box<dyn std::error::Error>>) -> ! {
    exit_quietly_when_output_closes();
    let code = run().unwrap_or_else(|e| {
        eprintln!("error: {e}");
        1
    });
    std::process::exit(code)
}

/// The checks every robot's `certify` makes of its hull options; errors name the option as the
/// command line spells it.
pub fn check_hull_options(tolerance: f64, max_seconds: Option<f64>) -> Result<(), String> {
    if !(tolerance > 0.0 && tolerance.is_finite()) {
        return Err(format!(
            "--tolerance: expected a positive number, found {tolerance}"
        ));
    }
    if let Some(s) = max_seconds {
        if s.is_nan() || s <= 0.0 {
            return Err(format!(
                "--max-seconds: expected a positive number, found {s}"
            ));
        }
    }
    Ok(())
}

/// Whether a panic message is the standard library's for writing to a closed stdout or stderr.
fn is_closed_output(message: &str) -> bool {
    message.starts_with("failed printing to std") && message.contains("Broken pipe")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_closed_output_panics_are_recognised() {
        assert!(is_closed_output(
            "failed printing to stdout: Broken pipe (os error 32)"
        ));
        assert!(!is_closed_output(
            "failed printing to stdout: No space left on device"
        ));
        assert!(!is_closed_output("index out of bounds: Broken pipe"));
    }

    #[test]
    fn hull_options_are_checked_by_name() {
        assert!(check_hull_options(0.05, None).is_ok());
        assert!(check_hull_options(0.05, Some(10.0)).is_ok());
        for tol in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(check_hull_options(tol, None)
                .unwrap_err()
                .starts_with("--tolerance"));
        }
        for s in [0.0, -2.0, f64::NAN] {
            assert!(check_hull_options(0.05, Some(s))
                .unwrap_err()
                .starts_with("--max-seconds"));
        }
    }

    #[test]
    fn writes_whole_files_and_leaves_no_temporary_behind() {
        let dir = std::env::temp_dir().join(format!("calib-pipeline-out-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("report.json");
        write_atomically(&path, "one").unwrap();
        write_atomically(&path, "two").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "two");
        let names: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert_eq!(names.len(), 1, "a temporary file was left behind");
        // A directory that does not exist: an error, and nothing written.
        assert!(write_atomically(&dir.join("missing/report.json"), "x").is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
