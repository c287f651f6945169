//! Shared by the root package's tests: running the built `patina` binary, and scratch directories.
//! A module of the `cli` test binary, included by `library` too; each module uses part of it.
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Command, Output};

/// Runs the `patina` binary with `args` (Mesa's device-select warnings silenced).
pub fn patina(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_patina"))
        .args(args)
        .env("NODEVICE_SELECT", "1")
        .output()
        .expect("the patina binary runs")
}

/// A directory of one test's own, created if need be (`suite` names the test file; the process id
/// keeps runs apart, the test's name the tests of one run, which run in parallel).
pub fn scratch_dir(suite: &str, test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("patina-{suite}-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}
