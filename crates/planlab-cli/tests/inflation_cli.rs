//! `planlab plan --inflate` below one cell is said, not silently ignored.

use std::process::Command;

const REPO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

#[test]
fn inflation_below_one_cell_is_said() {
    let map = format!("{REPO}/tests/data/movingai/dao/arena.map");
    let run = |inflate: &str| {
        Command::new(env!("CARGO_BIN_EXE_planlab"))
            .args([
                "plan",
                &map,
                "--start",
                "3,3",
                "--goal",
                "40,40",
                "--inflate",
                inflate,
            ])
            .output()
            .expect("run planlab")
    };
    let o = run("0.8");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("planlab: note: 0.8 m inflation < 1 cell (1 m): no effect"),
        "{err}"
    );
    // One cell or more inflates: no note.
    let o = run("1");
    assert!(!String::from_utf8_lossy(&o.stderr).contains("note"));
}
