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

/// Asserts a failure with exactly one `planlab: error:` line containing
/// every needle, and no panic.
pub fn assert_error(o: &Output, needles: &[&str]) {
    assert!(
        !o.status.success(),
        "expected failure, got {}",
        String::from_utf8_lossy(&o.stdout)
    );
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "one error line expected, got {err:?}");
    assert!(lines[0].starts_with("planlab: error: "), "{err}");
    for n in needles {
        assert!(lines[0].contains(n), "{n:?} not in {err:?}");
    }
}
