//! The `planlab` binary as other tools call it: output formats, exit codes
//! and one-line errors.

use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};

fn data(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data")
        .join(rel)
}

fn repo(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(rel)
}

fn planlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_planlab"))
        .args(args)
        .output()
        .expect("run planlab")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Asserts a failure with exactly one `planlab: error:` line containing `needle`.
fn assert_error(o: &Output, needle: &str) {
    assert!(
        !o.status.success(),
        "expected failure, got stdout {}",
        stdout(o)
    );
    let err = stderr(o);
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "one error line expected, got {err:?}");
    assert!(lines[0].starts_with("planlab: error: "), "{err}");
    assert!(
        lines[0].to_lowercase().contains(&needle.to_lowercase()),
        "{needle:?} not in {err:?}"
    );
}

fn temp_file(name: &str, contents: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("planlab-cli-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, contents).unwrap();
    p
}

fn s(p: &std::path::Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn plan_json_matches_moving_ai_optimum() {
    // arena.map.scen row: 1 13 -> 4 12, optimal 3.41421
    let map = data("movingai/dao/arena.map");
    for algo in ["astar", "dijkstra", "jps"] {
        let o = planlab(&[
            "plan",
            s(&map),
            "--start",
            "1,13",
            "--goal",
            "4,12",
            "--algo",
            algo,
            "--json",
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let v: Value = serde_json::from_str(stdout(&o).trim()).unwrap();
        assert!((v["cost"].as_f64().unwrap() - 3.41421).abs() < 1e-3, "{v}");
        assert!((v["length_m"].as_f64().unwrap() - 3.41421).abs() < 1e-3);
        assert!(v["expanded"].as_u64().unwrap() > 0);
        let path = v["path"].as_array().unwrap();
        assert_eq!(path.first().unwrap(), &serde_json::json!([1, 13]));
        assert_eq!(path.last().unwrap(), &serde_json::json!([4, 12]));
        assert!(v["keypoints"].as_array().unwrap().is_empty());
    }
}

#[test]
fn plan_on_ros_map_with_inflation_keypoints_and_bottom_up() {
    let yaml = data("rosmaps/turtlebot3/map.yaml");
    // Two free cells in the TurtleBot3 world, far apart.
    let o = planlab(&[
        "plan",
        s(&yaml),
        "--start",
        "167,218",
        "--goal",
        "230,180",
        "--inflate",
        "0.1",
        "--keypoints",
        "--bottom-up",
        "1.0",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_str(stdout(&o).trim()).unwrap();
    let cost = v["cost"].as_f64().unwrap();
    assert!((v["length_m"].as_f64().unwrap() - cost * 0.05).abs() < 1e-9);
    let path = v["path"].as_array().unwrap().len();
    let kp = v["keypoints"].as_array().unwrap();
    let fnodes = v["feature_nodes"].as_array().unwrap();
    assert_eq!(kp.first().unwrap(), &serde_json::json!([167, 218]));
    assert_eq!(kp.last().unwrap(), &serde_json::json!([230, 180]));
    assert!(
        kp.len() * 4 < path,
        "{} key points for {path} nodes",
        kp.len()
    );
    assert!(fnodes.len() * 4 < path);
}

#[test]
fn scen_json_reports_every_row_and_no_mismatch() {
    let o = planlab(&[
        "scen",
        s(&data("movingai/dao/arena.map")),
        s(&data("movingai/dao/arena.map.scen")),
        "--algo",
        "jps",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    let lines: Vec<Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let rows = lines.len() - 1;
    let summary = lines.last().unwrap();
    assert_eq!(summary["rows"].as_u64().unwrap() as usize, rows);
    assert_eq!(summary["mismatches"], 0);
    assert!(summary["mean_micros"].as_f64().unwrap() >= 0.0);
    for (i, l) in lines[..rows].iter().enumerate() {
        assert_eq!(l["row"].as_u64().unwrap() as usize, i);
        let (opt, cost) = (l["optimal"].as_f64().unwrap(), l["cost"].as_f64().unwrap());
        assert!((opt - cost).abs() <= 1e-3 * opt.max(1.0), "{l}");
        for k in ["start", "goal", "expanded", "micros"] {
            assert!(!l[k].is_null(), "{k} missing in {l}");
        }
    }
}

#[test]
fn bench_grid_prints_ratios() {
    let o = planlab(&[
        "bench",
        "grid",
        s(&data("movingai/dao/arena.map")),
        s(&data("movingai/dao/arena.map.scen")),
        "--reps",
        "1",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_str(stdout(&o).trim()).unwrap();
    for k in [
        "rows",
        "astar_ms",
        "jps_ms",
        "pathfinding_ms",
        "astar_speedup",
        "jps_speedup",
    ] {
        assert!(v[k].as_f64().is_some_and(|x| x > 0.0), "{k} in {v}");
    }
    let ratio = v["pathfinding_ms"].as_f64().unwrap() / v["astar_ms"].as_f64().unwrap();
    assert!((ratio - v["astar_speedup"].as_f64().unwrap()).abs() < 1e-6 * ratio);
}

/// A reader that goes away before the output (`planlab plan … | head -0`)
/// ends `planlab` quietly with success; `println!` panicked there.
#[test]
fn a_closed_stdout_ends_quietly() {
    let map = data("movingai/dao/arena.map");
    let mut child = Command::new(env!("CARGO_BIN_EXE_planlab"))
        .args([
            "plan",
            s(&map),
            "--start",
            "1,11",
            "--goal",
            "42,46",
            "--json",
        ])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let o = child.wait_with_output().unwrap();
    assert!(o.status.success(), "{:?}: {}", o.status, stderr(&o));
    assert!(!stderr(&o).contains("panicked"), "{}", stderr(&o));
}

/// Any-angle planners (Theta*, safe A*'s smoothed path) may beat the
/// 8-connected optimum: the bench takes them (the knight's move of an open
/// map: √5 against 1 + √2) and reports their cost ratio below 1.
#[test]
fn bench_grid_takes_paths_shorter_than_the_8_connected_optimum() {
    let dir = std::env::temp_dir().join(format!("planlab-bench-anyangle-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let map = dir.join("open.map");
    std::fs::write(
        &map,
        "type octile\nheight 5\nwidth 5\nmap\n.....\n.....\n.....\n.....\n.....\n",
    )
    .unwrap();
    let scen = dir.join("open.map.scen");
    std::fs::write(
        &scen,
        "version 1\n0\topen.map\t5\t5\t0\t0\t2\t1\t2.41421356\n",
    )
    .unwrap();
    let o = planlab(&["bench", "grid", s(&map), s(&scen), "--reps", "1"]);
    std::fs::remove_dir_all(&dir).ok();
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_str(stdout(&o).trim()).unwrap();
    let theta = v["planners"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["algo"] == "theta-star")
        .unwrap_or_else(|| panic!("no theta-star row in {v}"));
    let ratio = theta["cost_ratio"].as_f64().unwrap();
    assert!(
        (ratio - 5f64.sqrt() / (1.0 + 2f64.sqrt())).abs() < 1e-6,
        "{theta}"
    );
}

/// JPS+ on arena: every row at the optimum through `scen`, and `bench grid`
/// times its queries apart from building its table (`setup_ms`), with the
/// expansions of JPS (the same jump points).
#[test]
fn jps_plus_solves_every_arena_row_and_bench_grid_reports_its_table_apart() {
    let (map, scen) = (
        data("movingai/dao/arena.map"),
        data("movingai/dao/arena.map.scen"),
    );
    let o = planlab(&["scen", s(&map), s(&scen), "--algo", "jps-plus", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    let v: Value = serde_json::from_str(out.lines().last().unwrap()).unwrap();
    assert_eq!(
        (v["mismatches"].as_u64(), v["rows"].as_u64()),
        (Some(0), Some(160)),
        "{v}"
    );
    let o = planlab(&[
        "bench",
        "grid",
        s(&map),
        s(&scen),
        "--reps",
        "1",
        "--algo",
        "jps-plus",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_str(stdout(&o).trim()).unwrap();
    let rows = v["planners"].as_array().unwrap();
    assert_eq!(rows.len(), 1, "{v}");
    let plus = &rows[0];
    assert_eq!(plus["algo"], "jps-plus");
    assert_eq!(plus["solved"], plus["rows"]);
    assert!(
        (plus["cost_ratio"].as_f64().unwrap() - 1.0).abs() < 1e-3,
        "{plus}"
    );
    assert!(plus["setup_ms"].as_f64().unwrap() > 0.0, "{plus}");
    assert!(plus["ms"].as_f64().unwrap() > 0.0, "{plus}");
}

#[test]
fn plan_uses_a_scenarios_endpoints_and_options_and_flags_override_them() {
    let demo = repo("assets/scenarios/grid-demo.json");
    let run = |extra: &[&str]| {
        let mut args = vec!["plan", s(&demo), "--json"];
        args.extend_from_slice(extra);
        let o = planlab(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        serde_json::from_str::<Value>(stdout(&o).trim()).unwrap()
    };
    let from_file = run(&[]);
    let text = std::fs::read_to_string(&demo).unwrap();
    let scenario: Value = serde_json::from_str(&text).unwrap();
    let (st, gl) = (&scenario["start"], &scenario["goal"]);
    let path = from_file["path"].as_array().unwrap();
    assert_eq!(
        path.first().unwrap(),
        &serde_json::json!([st["col"], st["row"]])
    );
    assert_eq!(
        path.last().unwrap(),
        &serde_json::json!([gl["col"], gl["row"]])
    );
    // The scenario asks for key points and Bottom-Up.
    assert!(from_file["keypoints"].as_array().unwrap().len() >= 2);
    assert!(from_file["feature_nodes"].as_array().unwrap().len() >= 2);
    // JPS is optimal too: same cost on the same (inflated) map.
    let jps = run(&["--algo", "jps"]);
    assert!((jps["cost"].as_f64().unwrap() - from_file["cost"].as_f64().unwrap()).abs() < 1e-9);
    // Without inflation the wall gap is wider, so the path can only get shorter.
    let raw = run(&["--inflate", "0"]);
    assert!(raw["cost"].as_f64().unwrap() <= from_file["cost"].as_f64().unwrap() + 1e-9);
}

#[test]
fn bad_input_gives_one_clear_error_line() {
    let arena = data("movingai/dao/arena.map");
    let a = s(&arena);
    // Unreachable: a free cell walled in on all sides.
    let walled = temp_file(
        "walled.map",
        b"type octile\nheight 5\nwidth 5\nmap\n.....\n.@@@.\n.@.@.\n.@@@.\n.....\n",
    );
    let truncated = temp_file(
        "trunc.map",
        b"type octile\nheight 5\nwidth 5\nmap\n.....\n..\n",
    );
    let huge = temp_file(
        "huge.map",
        b"type octile\nheight 20000\nwidth 20000\nmap\n....\n",
    );
    let no_image = temp_file(
        "noimg.yaml",
        b"image: nothere.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
    );
    let bad_pgm_yaml = temp_file(
        "badpgm.yaml",
        b"image: bad.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
    );
    temp_file("bad.pgm", b"P5\n10 10\n255\nshort");
    let bad_scen = temp_file(
        "bad.scen",
        b"version 1\n0\tarena.map\t49\t49\t1\t11\tx\t12\t1\n",
    );
    let readme = repo("README.md");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec![
                "plan",
                "/nonexistent.map",
                "--start",
                "1,1",
                "--goal",
                "2,2",
            ],
            "cannot read",
        ),
        (
            vec!["plan", a, "--start", "1,13", "--goal", "99,99"],
            "off the",
        ),
        (
            vec!["plan", a, "--start", "0,0", "--goal", "4,12"],
            "obstacle",
        ),
        (
            vec!["plan", s(&walled), "--start", "0,0", "--goal", "2,2"],
            "unreachable",
        ),
        (
            vec!["plan", s(&truncated), "--start", "0,0", "--goal", "1,0"],
            "line",
        ),
        (
            vec!["plan", s(&huge), "--start", "0,0", "--goal", "1,0"],
            "too large",
        ),
        (
            vec!["plan", s(&no_image), "--start", "0,0", "--goal", "1,0"],
            "nothere.pgm",
        ),
        (
            vec!["plan", s(&bad_pgm_yaml), "--start", "0,0", "--goal", "1,0"],
            "bad.pgm",
        ),
        (
            vec!["plan", a, "--start", "1;13", "--goal", "4,12"],
            "invalid cell",
        ),
        (
            vec![
                "plan", a, "--start", "1,13", "--goal", "4,12", "--weight", "NaN",
            ],
            "weight",
        ),
        (
            vec![
                "plan",
                a,
                "--start",
                "1,13",
                "--goal",
                "4,12",
                "--inflate",
                "-1",
            ],
            "inflate",
        ),
        (
            vec![
                "plan",
                a,
                "--start",
                "1,13",
                "--goal",
                "4,12",
                "--bottom-up",
                "inf",
            ],
            "bottom-up",
        ),
        (
            vec![
                "plan",
                a,
                "--start",
                "1,13",
                "--goal",
                "4,12",
                "--algo",
                "jps",
                "--diagonal",
                "always",
            ],
            "jump point search",
        ),
        (
            vec!["plan", s(&readme), "--start", "1,1", "--goal", "2,2"],
            "unknown map format",
        ),
        (vec!["scen", a, s(&bad_scen)], "line 2"),
    ];
    for (args, needle) in cases {
        let o = planlab(&args);
        assert_error(&o, needle);
    }
}

#[test]
fn inflation_blocking_the_start_is_explained() {
    // (1,11) in arena is free but hugs a wall: 2 m of inflation swallows it.
    let o = planlab(&[
        "plan",
        s(&data("movingai/dao/arena.map")),
        "--start",
        "1,11",
        "--goal",
        "24,24",
        "--inflate",
        "2",
    ]);
    assert_error(&o, "after inflation");
}

#[test]
fn plan_writes_a_posthoc_trace_that_replays_to_its_expanded_count() {
    let map = data("movingai/dao/arena.map");
    let out = temp_file("arena-astar.trace.json", b"old");
    for algo in ["astar", "jps", "theta-star"] {
        let o = planlab(&[
            "plan",
            s(&map),
            "--start",
            "3,3",
            "--goal",
            "45,40",
            "--algo",
            algo,
            "--json",
            "--trace-posthoc",
            s(&out),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let plan: Value = serde_json::from_str(stdout(&o).trim()).unwrap();
        let trace: Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
        assert_eq!(trace["version"], "1.4.0");
        let events = trace["events"].as_array().unwrap();
        let count = |k: &str| events.iter().filter(|e| e["type"] == k).count() as u64;
        assert_eq!(
            count("expanding"),
            plan["expanded"].as_u64().unwrap(),
            "{algo}"
        );
        assert_eq!(
            count("source") + count("destination") + count("end"),
            3,
            "{algo}"
        );
        assert_eq!(events[0]["x"], 3);
        assert!(stderr(&o).contains("Posthoc trace"), "{}", stderr(&o));
    }
    // Never over its own input; a failed plan writes nothing.
    let before = std::fs::read(&map).unwrap();
    let o = planlab(&[
        "plan",
        s(&map),
        "--start",
        "3,3",
        "--goal",
        "45,40",
        "--trace-posthoc",
        s(&map),
    ]);
    assert_error(&o, "that is an input of the run");
    assert_eq!(std::fs::read(&map).unwrap(), before);
    let fresh = out.with_file_name("never.trace.json");
    let o = planlab(&[
        "plan",
        s(&map),
        "--start",
        "0,0",
        "--goal",
        "45,40",
        "--trace-posthoc",
        s(&fresh),
    ]);
    assert_error(&o, "inside an obstacle");
    assert!(!fresh.exists());
}
