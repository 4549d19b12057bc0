//! `planlab plan` on a ROS scale-mode map whose grey band is weighted
//! (docs/algorithms.md §weights): A* goes round the band and prints the
//! weighted cost; BFS goes through it and says it ignores weights; JPS is
//! refused with a one-line error.

use std::process::Command;

const REPO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

fn plan(args: &[&str]) -> std::process::Output {
    let map = format!("{REPO}/tests/data/weights/band.yaml");
    Command::new(env!("CARGO_BIN_EXE_planlab"))
        .args([
            "plan",
            &map,
            "--start",
            "1,2",
            "--goal",
            "9,2",
            "--diagonal",
            "never",
        ])
        .args(args)
        .output()
        .expect("run planlab")
}

fn json(o: &std::process::Output) -> serde_json::Value {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).expect("JSON out")
}

#[test]
fn plan_honours_the_weights_of_a_scale_map_and_bfs_says_it_ignores_them() {
    // 4-connected: round the band's end (4 + 8 moves of 1) beats crossing
    // it (7 moves of 1 and one of 9).
    let astar = json(&plan(&["--json"]));
    assert_eq!(astar["cost"], 12.0, "{astar}");
    assert_eq!(astar["weighted"], true);
    assert!(astar.get("note").is_none(), "{astar}");
    // 0.5 m cells: the geometric length, not the weighted cost.
    assert_eq!(astar["length_m"], 6.0);
    let bfs = json(&plan(&["--json", "--algo", "bfs"]));
    assert_eq!(bfs["cost"], 16.0, "{bfs}");
    assert!(
        bfs["note"]
            .as_str()
            .unwrap()
            .contains("ignores cell weights"),
        "{bfs}"
    );
    let text = plan(&["--algo", "bfs"]);
    let out = String::from_utf8_lossy(&text.stdout);
    assert!(
        out.contains("weighted") && out.contains("cost 16.0000"),
        "{out}"
    );
    assert!(
        out.contains("note: breadth-first search ignores cell weights"),
        "{out}"
    );
    let jps = plan(&["--algo", "jps"]);
    assert!(!jps.status.success());
    let err = String::from_utf8_lossy(&jps.stderr);
    assert!(err.contains("needs uniform cell costs"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
}
