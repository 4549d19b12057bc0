//! `planlab run`, `planlab planners` and `planlab reproduce` as other tools
//! call them: outputs, determinism, edits and one-line errors.

mod common;

use common::assert_error;
use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};

fn demo() -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenarios/pursuit-demo.json")
        .display()
        .to_string()
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

fn json_of(o: &Output) -> Value {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_str(stdout(o).trim()).expect("one JSON object")
}

fn temp_file(name: &str, contents: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("planlab-sim-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, contents).unwrap();
    p
}

const METRICS: [&str; 14] = [
    "outcome",
    "time_s",
    "path_length_m",
    "min_clearance_m",
    "mean_clearance_m",
    "total_turn_rad",
    "max_turn_rad",
    "max_turn_step_rad",
    "speed_drops",
    "mean_tracking_error_m",
    "max_tracking_error_m",
    "tracking_error_var_m2",
    "load_ok_share",
    "temp_goal_switches",
];

#[test]
fn run_prints_metrics_as_table_and_json() {
    let d = demo();
    let o = planlab(&["run", &d]);
    assert!(o.status.success());
    let text = stdout(&o);
    assert!(text.contains("planner pursuit"), "{text}");
    assert!(
        text.lines()
            .any(|l| l.starts_with("outcome") && l.ends_with("reached")),
        "{text}"
    );
    assert!(text.contains("path length"), "{text}");

    let j = json_of(&planlab(&["run", &d, "--json"]));
    for k in METRICS {
        assert!(j.get(k).is_some(), "{k} missing: {j}");
    }
    assert_eq!(j["outcome"], "reached");
    assert_eq!(j["planner"], "pursuit");
    // Straight from (0.7, 1.1) to (9.1, 2.9): 8.59 m as the crow flies.
    let len = j["path_length_m"].as_f64().unwrap();
    assert!(len > 8.3 && len < 9.2, "{len}");
    assert!(j["mean_tracking_error_m"].is_null());
    // Same scenario, same trace.
    let again = json_of(&planlab(&["run", &d, "--json"]));
    assert_eq!(j["trace_hash"], again["trace_hash"]);
}

#[test]
fn rrt_shortcut_on_l_sim7_is_deterministic_and_seeded() {
    // The RRT samples from the episode seed: the same scenario and seed
    // give the same trace, run after run.
    let sim7 = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenarios/L-sim7.json")
        .display()
        .to_string();
    let args = ["run", &sim7, "--json", "--planner", "rrt-shortcut"];
    let a = json_of(&planlab(&args));
    let b = json_of(&planlab(&args));
    assert_eq!(a["planner"], "rrt-shortcut");
    assert_eq!(a["outcome"], "reached", "{a}");
    assert!(a["min_clearance_m"].as_f64().unwrap() > 0.0, "{a}");
    assert_eq!(a["trace_hash"], b["trace_hash"]);
    let mut seeded = args.to_vec();
    seeded.extend(["--seed", "5"]);
    let c = json_of(&planlab(&seeded));
    let d = json_of(&planlab(&seeded));
    assert_eq!(c["trace_hash"], d["trace_hash"]);
    assert_ne!(
        a["trace_hash"], c["trace_hash"],
        "the seed reaches the sampler"
    );
}

#[test]
fn set_seed_planner_and_trace_file() {
    let d = demo();
    let j = json_of(&planlab(&[
        "run",
        &d,
        "--json",
        "--seed",
        "42",
        "--planner",
        "pursuit",
        "--set",
        "sim.max_time=2",
        "--set",
        "local_planner.config.k_w=2.5",
    ]));
    assert_eq!(j["seed"], 42);
    assert_eq!(j["outcome"], "timeout");
    assert!((j["time_s"].as_f64().unwrap() - 2.0).abs() < 1e-9);
    assert_eq!(j["steps"], 20);

    // A slower robot takes longer over the same ground.
    let slow = json_of(&planlab(&[
        "run",
        &d,
        "--json",
        "--set",
        "robot.limits.v_max=0.5",
    ]));
    let fast = json_of(&planlab(&["run", &d, "--json"]));
    assert!(slow["time_s"].as_f64().unwrap() > fast["time_s"].as_f64().unwrap() + 3.0);

    let csv = temp_file("trace.csv", "");
    let o = planlab(&["run", &d, "--json", "--trace", csv.to_str().unwrap()]);
    let j = json_of(&o);
    let text = std::fs::read_to_string(&csv).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert!(
        lines[0].starts_with("t,x,y,theta,v,vy,w,cmd_v"),
        "{}",
        lines[0]
    );
    assert_eq!(lines.len() as u64, j["steps"].as_u64().unwrap() + 2);
    assert!(lines[1].starts_with("0.0,0.7,1.1,"), "{}", lines[1]);
}

#[test]
fn bad_input_gives_one_clear_error_line() {
    let d = demo();
    let cases: Vec<(Vec<&str>, Vec<&str>)> = vec![
        (
            vec!["--set", "robot.limits.v_max=NaN"],
            vec!["robot.limits.v_max", "finite"],
        ),
        (
            vec!["--set", "robot.limits.v_max=-1"],
            vec!["robot.limits.v_max"],
        ),
        (
            vec!["--set", "robot.footprint.radius=-0.2"],
            vec!["robot.footprint.radius"],
        ),
        (
            vec!["--set", "movers.0.radius=-1"],
            vec!["movers[0]", "radius"],
        ),
        (
            vec!["--set", "movers.5.radius=1"],
            vec!["movers", "no index 5"],
        ),
        (vec!["--set", "sim.dt=-0.1"], vec!["sim.dt"]),
        (
            vec!["--set", "robot.limits.vmax=1"],
            vec!["`robot.limits.vmax`", "unknown field"],
        ),
        (vec!["--set", "sim.dt"], vec!["PATH=VALUE"]),
        (
            vec!["--set", "local_planner.config.k_w=-1"],
            vec!["pursuit.k_w"],
        ),
        (
            vec!["--set", "local_planner.config.kw=1"],
            vec!["unknown field `kw`"],
        ),
        (
            vec!["--planner", "warp"],
            vec!["unknown planner `warp`", "pursuit"],
        ),
        // Start against the left wall (column 1 is free, the wall is x < 0.2).
        (
            vec!["--set", "start.col=1", "--set", "start.world.x=0.3"],
            vec!["starts in collision"],
        ),
        // Start on the pacing mover.
        (
            vec!["--set", "movers.0.motion.a=[0.9, 1.1]"],
            vec!["starts in collision", "mover 1"],
        ),
        // Goal in the border wall.
        (
            vec!["--set", "goal.col=0", "--set", "goal.row=20"],
            vec!["goal", "inside a wall"],
        ),
        // Goal inside the box (rows 10–14, columns 20–29).
        (
            vec!["--set", "goal.col=25", "--set", "goal.row=12"],
            vec!["inside a wall"],
        ),
    ];
    for (extra, needles) in cases {
        let mut args = vec!["run", d.as_str()];
        args.extend(extra.iter().copied());
        assert_error(&planlab(&args), &needles);
    }
    assert_error(&planlab(&["run", "/no/such/file.json"]), &["cannot read"]);
}

#[test]
fn an_unreachable_goal_is_refused() {
    // A closed 3×3 box of walls with a free centre in a free room.
    let rows = [
        "##########",
        "#........#",
        "#..###...#",
        "#..#.#...#",
        "#..###...#",
        "#........#",
        "##########",
    ];
    let cells: Vec<String> = rows.iter().map(|r| format!("\"{r}\"")).collect();
    let text = format!(
        r#"{{"version": 1, "map": {{"width": 10, "height": 7, "resolution": 0.5, "cells": [{}]}},
           "start": {{"col": 1, "row": 1}}, "goal": {{"col": 4, "row": 3}},
           "local_planner": {{"name": "pursuit"}}}}"#,
        cells.join(", ")
    );
    let p = temp_file("boxed.json", &text);
    assert_error(
        &planlab(&["run", p.to_str().unwrap()]),
        &["cannot be reached", "boxed.json"],
    );
}

#[test]
fn planners_lists_fields_with_units_and_defaults() {
    let o = planlab(&["planners", "--json"]);
    let j = json_of(&o);
    let list = j.as_array().unwrap();
    let p = list
        .iter()
        .find(|p| p["name"] == "pursuit")
        .expect("pursuit listed");
    assert!(p["summary"]
        .as_str()
        .unwrap()
        .contains("no obstacle avoidance"));
    let k_w = p["fields"]
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["name"] == "k_w")
        .unwrap();
    assert_eq!(k_w["unit"], "1/s");
    assert_eq!(k_w["default"], 1.5);
    // The plain-words name beside the config name.
    assert_eq!(k_w["label"], "heading gain k_w");
    let text = stdout(&planlab(&["planners"]));
    assert!(
        text.contains("pursuit — ") && text.contains("k_w") && text.contains("1/s"),
        "{text}"
    );
    assert!(
        text.lines().any(|l| l.trim_start().starts_with("alpha ")
            && l.contains("heading weight α — α, heading weight")),
        "{text}"
    );
}

#[test]
fn reproduce_refuses_unknown_ids() {
    assert_error(
        &planlab(&["reproduce", "T-fig9-99"]),
        &["unknown experiment `T-fig9-99`"],
    );
}

#[test]
fn a_closed_pipe_ends_quietly() {
    // `planlab reproduce --json | head -1`: the reader goes away; planlab
    // must neither panic nor report an error.
    use std::process::Stdio;
    for args in [&["reproduce", "S-tab1", "--json"][..], &["planners"][..]] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_planlab"))
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("run planlab");
        drop(child.stdout.take());
        let out = child.wait_with_output().expect("wait");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{args:?}: {:?} {err}", out.status);
        assert!(err.is_empty(), "{args:?}: {err}");
    }
}
