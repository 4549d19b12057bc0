//! Helpers shared by the CLI test files that include this module.
#![allow(dead_code)] // each test file uses some

use std::path::PathBuf;
use std::process::{Command, Output};

/// The path of `rel` under the repository's `assets/`.
pub fn asset(rel: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets")
        .join(rel)
        .display()
        .to_string()
}

/// Runs the built `planlab` with `args`.
pub fn planlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_planlab"))
        .args(args)
        .output()
        .expect("run planlab")
}
