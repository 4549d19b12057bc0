//! `planlab batch`: seeded variants, several planners, per-planner
//! statistics, the per-run CSV, determinism and one-line errors.

mod common;

use common::{assert_error, planlab};
use serde_json::Value;
use std::path::PathBuf;
use std::process::Output;

fn preset(name: &str) -> String {
    common::asset(&format!("scenarios/{name}"))
}

fn lines_of(o: &Output) -> Vec<Value> {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON line"))
        .collect()
}

fn temp_path(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("planlab-batch-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn batch_summarises_every_planner_and_is_deterministic() {
    let csv = temp_path("runs.csv");
    let demo = preset("pursuit-demo.json");
    let args = [
        "batch",
        demo.as_str(),
        "--planners",
        "pursuit,dwa",
        "--variants",
        "6",
        "--seed",
        "11",
        "--jitter",
        "0.4",
        "--json",
        "--csv",
        csv.to_str().unwrap(),
    ];
    let first = lines_of(&planlab(&args));
    assert_eq!(first.len(), 3, "two planner lines and a footer");
    for (line, name) in first.iter().zip(["pursuit", "dwa"]) {
        assert_eq!(line["planner"], name);
        assert_eq!(line["runs"], 6);
        let reached = line["reached"].as_u64().unwrap();
        let outcomes: u64 = line["outcomes"]
            .as_object()
            .unwrap()
            .values()
            .map(|v| v.as_u64().unwrap())
            .sum();
        assert_eq!(outcomes, 6);
        assert!((line["success_rate"].as_f64().unwrap() - reached as f64 / 6.0).abs() < 1e-12);
        assert!(reached > 0, "{name} reached no variant: {line}");
        let time = &line["metrics"]["time_s"];
        assert_eq!(time["n"].as_u64().unwrap(), reached);
        let (mean, lo, hi) = (
            time["mean"].as_f64().unwrap(),
            time["ci95"][0].as_f64().unwrap(),
            time["ci95"][1].as_f64().unwrap(),
        );
        assert!(lo <= mean && mean <= hi, "{time}");
        let med = time["median"].as_f64().unwrap();
        assert!(time["min"].as_f64().unwrap() <= med && med <= time["max"].as_f64().unwrap());
    }
    let footer = &first[2];
    assert_eq!(footer["variants"], 6);
    assert_eq!(footer["episodes"], 12);

    // Same seed: the same statistics (the footer's seconds differ).
    let again = lines_of(&planlab(&args));
    assert_eq!(first[..2], again[..2]);

    // The CSV: one row per episode; jittered variants really differ, and
    // variant 0 is the scenario as written, the same episode as `planlab
    // run` with that seed.
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<&str>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    assert_eq!(rows.len(), 12);
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let col = |n: &str| header.iter().position(|h| *h == n).unwrap();
    let lengths: std::collections::BTreeSet<&str> = rows
        .iter()
        .filter(|r| r[col("planner")] == "pursuit")
        .map(|r| r[col("path_length_m")])
        .collect();
    assert!(lengths.len() >= 4, "variants look alike: {lengths:?}");
    let v0 = rows
        .iter()
        .find(|r| r[col("variant")] == "0" && r[col("planner")] == "dwa")
        .unwrap();
    let run = lines_of(&planlab(&[
        "run",
        demo.as_str(),
        "--planner",
        "dwa",
        "--seed",
        v0[col("seed")],
        "--json",
    ]));
    assert_eq!(run[0]["trace_hash"], v0[col("trace_hash")]);
}

#[test]
fn batch_without_planners_uses_the_scenarios_own_and_prints_a_table() {
    let o = planlab(&[
        "batch",
        &preset("pursuit-demo.json"),
        "--variants",
        "3",
        "--jitter",
        "0",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("pursuit: success 100.0% (3/3"), "{out}");
    assert!(out.contains("95% CI of the mean"), "{out}");
}

#[test]
fn batch_errors_are_one_line() {
    let demo = preset("pursuit-demo.json");
    assert_error(
        &planlab(&["batch", &demo, "--planners", "dwa,nope"]),
        &["unknown planner `nope`", "known:"],
    );
    assert_error(
        &planlab(&["batch", &demo, "--variants", "0"]),
        &["--variants"],
    );
    assert_error(
        &planlab(&["batch", &demo, "--jitter", "-1"]),
        &["jitter", "-1"],
    );
    assert_error(&planlab(&["batch", &demo, "--jitter", "NaN"]), &["jitter"]);
    assert_error(
        &planlab(&["batch", &demo, "--planners", "dwa,dwa"]),
        &["twice"],
    );
    assert_error(&planlab(&["batch", "/nonexistent/x.json"]), &["x.json"]);
}
