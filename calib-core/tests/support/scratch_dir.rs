//! Scratch directories for tests that run a command on files: removed when the test passes (a
//! test suite run should leave nothing in the system's temporary directory), kept when it fails,
//! for inspection. Included by path into every test binary that writes files.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// A fresh directory under the system's temporary directory, unique to this process and `name`,
/// removed on drop unless the thread is panicking (a failed assertion keeps the evidence and
/// prints where it is). Dereferences to its [`Path`].
pub struct ScratchDir(PathBuf);

impl ScratchDir {
    /// Creates (after removing any leftover of the same name) `<tmp>/<name>-<pid>`.
    pub fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("a scratch directory");
        ScratchDir(dir)
    }
}

impl std::ops::Deref for ScratchDir {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for ScratchDir {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for ScratchDir {
    fn drop(&mut self) {
        if std::thread::panicking() {
            eprintln!("test files kept in {}", self.0.display());
        } else {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

#[test]
fn a_scratch_directory_goes_when_its_test_passes_and_stays_when_it_fails() {
    let passed = ScratchDir::new("scratch-dir-passed");
    std::fs::write(passed.join("file"), "x").unwrap();
    let path = passed.to_path_buf();
    drop(passed);
    assert!(!path.exists(), "{} left behind", path.display());
    let failed = std::panic::catch_unwind(|| {
        let dir = ScratchDir::new("scratch-dir-failed");
        std::fs::write(dir.join("evidence"), "x").unwrap();
        panic!("{}", dir.display());
    });
    let message = failed.unwrap_err();
    let kept = std::path::PathBuf::from(message.downcast_ref::<String>().unwrap());
    assert!(kept.join("evidence").exists());
    std::fs::remove_dir_all(kept).unwrap();
}
