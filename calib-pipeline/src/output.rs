//! Writing outputs: files so that nothing is half-written, standard output so that a closed pipe
//! ends the program quietly.

use std::path::Path;

use crate::{DataError, OptionError};

/// Writes `text` to `path` atomically: to a temporary file beside it, then renamed (a reader sees
/// the old file or the whole new one, never a part).
///
/// Only a regular file is replaced. A path that names anything else (`/dev/null`, a named pipe),
/// or that leads to the process's own descriptors (`/dev/stdout`, `/dev/fd/N`, `/proc/…`), is
/// written to as it is, at its end: renaming over it would put a regular file in place of the
/// device or of the link, for every program on the machine when run as root. A symbolic link
/// elsewhere is followed, and the file it leads to is replaced (the link stays a link).
pub fn write_atomically(path: &Path, text: &str) -> std::io::Result<()> {
    let descriptor = ["/proc", "/dev/fd", "/dev/stdout", "/dev/stderr"]
        .iter()
        .any(|p| path.starts_with(p));
    let target = match std::fs::metadata(path) {
        Ok(m) if descriptor || !m.is_file() => {
            return std::fs::OpenOptions::new()
                .append(true)
                .open(path)
                .and_then(|mut f| std::io::Write::write_all(&mut f, text.as_bytes()));
        }
        Ok(_) => std::fs::canonicalize(path)?,
        Err(_) => path.to_path_buf(),
    };
    let dir = target
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = dir.join(format!(".{name}.tmp{}", std::process::id()));
    std::fs::write(&tmp, text)?;
    std::fs::rename(&tmp, &target).inspect_err(|_| {
        let _ = std::fs::remove_file(&tmp);
    })
}

/// Checks, before any work, that every output file asked for can be written where it is asked
/// for: its directory exists and it is not itself a directory. A run of minutes should not end in
/// "cannot write". Each output is `(what it is, its path if asked for)`; the error names both
/// (`c.html: cannot write the certificate: the directory out does not exist`).
pub fn check_outputs(outputs: &[(&str, Option<&Path>)]) -> Result<(), DataError> {
    for (what, path) in outputs {
        let Some(path) = path else { continue };
        let dir = path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let why = if !dir.is_dir() {
            format!("the directory {} does not exist", dir.display())
        } else if path.is_dir() {
            "it is a directory".to_string()
        } else {
            continue;
        };
        return Err(DataError::new(
            path,
            None,
            None,
            format!("cannot write {what}: {why}"),
        ));
    }
    Ok(())
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
pub fn check_hull_options(tolerance: f64, max_seconds: Option<f64>) -> Result<(), OptionError> {
    if !(tolerance > 0.0 && tolerance.is_finite()) {
        return Err(OptionError::Tolerance(tolerance));
    }
    if let Some(s) = max_seconds {
        if s.is_nan() || s <= 0.0 {
            return Err(OptionError::MaxSeconds(s));
        }
    }
    Ok(())
}

/// Whether a panic message is the standard library's for writing to a closed stdout or stderr.
#[doc(hidden)]
pub fn is_closed_output(message: &str) -> bool {
    message.starts_with("failed printing to std") && message.contains("Broken pipe")
}
