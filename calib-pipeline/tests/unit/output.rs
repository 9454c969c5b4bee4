//! The tests of `calib_pipeline::output`.

use calib_pipeline::*;

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
            .to_string()
            .starts_with("--tolerance"));
    }
    for s in [0.0, -2.0, f64::NAN] {
        assert!(check_hull_options(0.05, Some(s))
            .unwrap_err()
            .to_string()
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

/// A named pipe stands for every path that is not a regular file (`/dev/null` among them, which
/// this test must not risk replacing): it is written to, not renamed over, and stays a pipe.
#[cfg(target_os = "linux")]
#[test]
fn a_path_that_is_not_a_regular_file_is_written_to_not_replaced() {
    use std::os::unix::fs::FileTypeExt;
    let dir = std::env::temp_dir().join(format!("calib-pipeline-fifo-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let fifo = dir.join("pipe");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo is needed here");
    // Opened for reading and writing, a pipe's open does not wait for the other end (Linux).
    let mut end = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .open(&fifo)
        .unwrap();
    write_atomically(&fifo, "through the pipe").unwrap();
    let kind = std::fs::symlink_metadata(&fifo).unwrap().file_type();
    assert!(kind.is_fifo(), "the pipe was replaced by {kind:?}");
    let mut got = [0u8; 16];
    std::io::Read::read_exact(&mut end, &mut got).unwrap();
    assert_eq!(&got, b"through the pipe");
    // A symbolic link: the file it leads to is replaced, the link stays.
    let file = dir.join("file.json");
    std::fs::write(&file, "old").unwrap();
    let link = dir.join("link.json");
    std::os::unix::fs::symlink(&file, &link).unwrap();
    write_atomically(&link, "new").unwrap();
    assert!(std::fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "new");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--json /dev/stdout` with standard output sent to a file: the path leads to one of the
/// process's descriptors (here `/proc/self/fd/N` of a file this test holds open, as a shell's
/// `> out.txt` would). The text is added after what was written through the descriptor, and the
/// file is the same file (not one renamed in its place, which the descriptor would not see).
#[cfg(target_os = "linux")]
#[test]
fn a_descriptor_by_name_is_appended_to_not_replaced() {
    use std::os::unix::fs::MetadataExt;
    use std::os::unix::io::AsRawFd;
    let dir = std::env::temp_dir().join(format!("calib-pipeline-fd-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("out.txt");
    let mut held = std::fs::File::create(&out).unwrap();
    std::io::Write::write_all(&mut held, b"printed first\n").unwrap();
    let by_name = std::path::PathBuf::from(format!("/proc/self/fd/{}", held.as_raw_fd()));
    write_atomically(&by_name, "written by name\n").unwrap();
    assert_eq!(
        std::fs::read_to_string(&out).unwrap(),
        "printed first\nwritten by name\n"
    );
    let same = held.metadata().unwrap().ino() == std::fs::metadata(&out).unwrap().ino();
    assert!(same, "the file was replaced under its descriptor");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn outputs_are_checked_before_any_work_and_the_error_names_the_file() {
    let dir = std::env::temp_dir().join(format!("calib-outputs-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let fine = dir.join("report.json");
    let missing = dir.join("no-such-dir").join("c.html");
    assert!(
        calib_pipeline::check_outputs(&[("the JSON report", Some(&fine)), ("x", None)]).is_ok()
    );
    let e = calib_pipeline::check_outputs(&[
        ("the JSON report", Some(&fine)),
        ("the certificate", Some(&missing)),
    ])
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("c.html: cannot write the certificate: the directory")
            && e.contains("no-such-dir"),
        "{e}"
    );
    let e = calib_pipeline::check_outputs(&[("the JSON report", Some(&dir))])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("cannot write the JSON report: it is a directory"),
        "{e}"
    );
    // Nothing was created.
    assert!(!fine.exists() && !missing.parent().unwrap().exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
