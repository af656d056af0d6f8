//! Running the real `agesim` binary, shared by the command-line test files.
#![allow(dead_code, clippy::expect_used)]

use std::process::{Command, Output};

/// `agesim ARGS…` and its output (with a runtime directory, which the commands that open
/// a GPU adapter want).
pub fn agesim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_agesim"))
        .args(args)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("the agesim binary runs")
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}
