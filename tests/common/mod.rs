//! Helpers shared by the integration tests that run the command-line tool.
// Each test binary uses its own subset of these.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// The tool built by Cargo for the tests.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_layertrace"))
}

/// A path in the repository.
pub fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// Runs the CLI in `dir` with standard input closed; returns (exit code, stderr). Fails the
/// test if the tool panicked.
pub fn cli_in(dir: &Path, args: &[&str]) -> (i32, String) {
    let out = bin()
        .current_dir(dir)
        .args(args)
        .stdin(Stdio::null())
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    (out.status.code().unwrap_or(-1), err)
}

/// The names in `dir` (temporaries included), sorted.
pub fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}
