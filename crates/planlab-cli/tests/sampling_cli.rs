//! `planlab plan --algo rrt … bit-star`: every sampling planner through the
//! command line on a Moving AI map, its JSON (cost, iterations, nodes,
//! path from the start cell's centre to the goal cell's), seeded
//! repeatability, --shortcut, and one-line errors for bad input.

use std::process::Command;

const REPO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

fn plan(args: &[&str]) -> std::process::Output {
    let map = format!("{REPO}/tests/data/movingai/dao/arena.map");
    Command::new(env!("CARGO_BIN_EXE_planlab"))
        .args(["plan", &map, "--start", "3,3", "--goal", "40,44"])
        .args(args)
        .output()
        .expect("run planlab")
}

fn json(o: &std::process::Output) -> serde_json::Value {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).expect("JSON out")
}

fn error_line(o: &std::process::Output) -> String {
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    let err = String::from_utf8_lossy(&o.stderr).to_string();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("planlab: error: "), "{err}");
    err
}

const ALGOS: [&str; 7] = [
    "rrt",
    "rrt-connect",
    "rrt-star",
    "informed-rrt-star",
    "prm",
    "prm-star",
    "bit-star",
];

#[test]
fn every_sampling_planner_prints_cost_iterations_nodes_and_its_path() {
    for algo in ALGOS {
        let out = json(&plan(&[
            "--algo",
            algo,
            "--iterations",
            "3000",
            "--seed",
            "4",
            "--json",
        ]));
        assert_eq!(out["algorithm"], algo);
        let path = out["path"].as_array().unwrap();
        assert_eq!(
            path.first().unwrap(),
            &serde_json::json!([3.5, 3.5]),
            "{algo}"
        );
        assert_eq!(
            path.last().unwrap(),
            &serde_json::json!([40.5, 44.5]),
            "{algo}"
        );
        let len: f64 = path
            .windows(2)
            .map(|w| {
                let (a, b) = (&w[0], &w[1]);
                (a[0].as_f64().unwrap() - b[0].as_f64().unwrap())
                    .hypot(a[1].as_f64().unwrap() - b[1].as_f64().unwrap())
            })
            .sum();
        let cost = out["cost"].as_f64().unwrap();
        assert!((len - cost).abs() < 1e-6, "{algo}: {len} vs {cost}");
        // No path can beat the straight line.
        assert!(cost >= (37f64).hypot(41.0) - 1e-9, "{algo}: {cost}");
        let iterations = out["iterations"].as_u64().unwrap();
        assert!(iterations <= 3000, "{algo}");
        assert!(out["nodes"].as_u64().unwrap() >= 2, "{algo}");
        assert!(out["first_solution_iteration"].as_u64().unwrap() <= iterations);
    }
    // The text form says the same in one line.
    let text = plan(&["--algo", "rrt-star", "--iterations", "500"]);
    assert!(text.status.success());
    let line = String::from_utf8_lossy(&text.stdout);
    assert!(line.starts_with("rrt-star on "), "{line}");
    assert!(
        line.contains("500 iterations") && line.contains("nodes"),
        "{line}"
    );
}

#[test]
fn the_same_seed_prints_the_same_path_and_shortcut_never_lengthens_it() {
    let a = json(&plan(&[
        "--algo",
        "rrt",
        "--seed",
        "9",
        "--iterations",
        "4000",
        "--json",
    ]));
    let b = json(&plan(&[
        "--algo",
        "rrt",
        "--seed",
        "9",
        "--iterations",
        "4000",
        "--json",
    ]));
    assert_eq!(a["path"], b["path"]);
    let c = json(&plan(&[
        "--algo",
        "rrt",
        "--seed",
        "10",
        "--iterations",
        "4000",
        "--json",
    ]));
    assert_ne!(a["path"], c["path"]);
    let s = json(&plan(&[
        "--algo",
        "rrt",
        "--seed",
        "9",
        "--iterations",
        "4000",
        "--shortcut",
        "--json",
    ]));
    assert_eq!(s["cost_before_shortcut"], a["cost"]);
    assert!(s["cost"].as_f64().unwrap() <= a["cost"].as_f64().unwrap());
}

#[test]
fn bad_sampling_input_is_refused_with_one_line() {
    let e = error_line(&plan(&["--algo", "prm", "--radius", "NaN"]));
    assert!(e.contains("--radius NaN"), "{e}");
    let e = error_line(&plan(&["--algo", "prm", "--iterations", "0"]));
    assert!(e.contains("--iterations 0"), "{e}");
    // Cell (0, 0) of arena.map is a wall.
    let map = format!("{REPO}/tests/data/movingai/dao/arena.map");
    let o = Command::new(env!("CARGO_BIN_EXE_planlab"))
        .args([
            "plan", &map, "--start", "0,0", "--goal", "40,44", "--algo", "rrt",
        ])
        .output()
        .unwrap();
    let e = error_line(&o);
    assert!(e.contains("start") && e.contains("collision"), "{e}");
    let e = error_line(&plan(&["--algo", "rrt", "--keypoints"]));
    assert!(e.contains("--keypoints"), "{e}");
    let e = error_line(&plan(&["--seed", "3"]));
    assert!(e.contains("--seed"), "{e}");
}

fn bench(args: &[&str]) -> std::process::Output {
    let map = format!("{REPO}/tests/data/movingai/dao/arena.map");
    Command::new(env!("CARGO_BIN_EXE_planlab"))
        .args(["bench", "sampling", &map])
        .args(args)
        .output()
        .expect("run planlab")
}

#[test]
fn bench_sampling_counts_what_plan_finds_and_the_optimising_planners_come_near_theta_star() {
    let out = json(&bench(&["--rows", "3", "--iterations", "20000", "--json"]));
    let runs = out["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 3 * ALGOS.len());
    // Each run is `planlab plan` with the same seed: solved exactly when
    // plan finds a path, with the same cost.
    for r in runs {
        let (algo, start, goal) = (
            r["algo"].as_str().unwrap(),
            format!("{},{}", r["start"][0], r["start"][1]),
            format!("{},{}", r["goal"][0], r["goal"][1]),
        );
        let map = format!("{REPO}/tests/data/movingai/dao/arena.map");
        let p = Command::new(env!("CARGO_BIN_EXE_planlab"))
            .args(["plan", &map, "--start", &start, "--goal", &goal])
            .args(["--algo", algo, "--iterations", "20000", "--seed", "0"])
            .args(["--radius", "0.4", "--json"])
            .output()
            .unwrap();
        if r["cost"].is_null() {
            assert!(!p.status.success(), "{algo} {start} → {goal}");
        } else {
            let plan = json(&p);
            assert_eq!(plan["cost"], r["cost"], "{algo} {start} → {goal}");
            assert_eq!(plan["iterations"], r["iterations"], "{algo}");
        }
    }
    let rows = out["planners"].as_array().unwrap();
    assert_eq!(rows.len(), 2 * ALGOS.len(), "per map, then over all");
    for row in rows {
        let algo = row["algo"].as_str().unwrap();
        let mine: Vec<_> = runs.iter().filter(|r| r["algo"] == algo).collect();
        assert_eq!(row["runs"], mine.len(), "{algo}");
        let solved = mine.iter().filter(|r| !r["cost"].is_null()).count();
        assert_eq!(row["solved"], solved, "{algo}");
        assert!(row["median_ms"].as_f64().unwrap() > 0.0, "{algo}");
        if ["rrt-star", "informed-rrt-star", "prm-star", "bit-star"].contains(&algo) {
            assert_eq!(solved, 3, "{algo} solves every arena row");
            let gap = row["median_gap"].as_f64().unwrap();
            assert!(gap.abs() < 0.1, "{algo}: median gap {gap}");
        }
    }
    // The text table names every planner.
    let o = bench(&["--rows", "1", "--iterations", "500"]);
    assert!(o.status.success());
    let text = String::from_utf8(o.stdout).unwrap();
    for algo in ALGOS {
        assert!(text.contains(algo), "{algo} missing from\n{text}");
    }
}

#[test]
fn bench_sampling_refuses_bad_input_with_one_line() {
    for (args, want) in [
        (&["--algo", "astar"][..], "not a sampling planner"),
        (&["--rows", "0"][..], "--rows 0"),
        (&["--iterations", "0"][..], "--iterations 0"),
        (&["--seeds", "0"][..], "--seeds 0"),
        (&["--radius", "NaN"][..], "--radius"),
        (&["--radius", "40"][..], "radius"),
    ] {
        let e = error_line(&bench(args));
        assert!(e.contains(want), "{args:?}: {e}");
    }
}
