//! `planlab run` of an arm scenario: the arm metrics by name, the
//! predictor switch, `--set` edits and one-line errors for unreachable
//! targets.

use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};

fn preset() -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenarios/T-tab5-3.json")
        .display()
        .to_string()
}

fn planlab(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_planlab"))
        .args(args)
        .output()
        .expect("run planlab")
}

fn json_of(o: &Output) -> Value {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_str(String::from_utf8_lossy(&o.stdout).trim()).expect("one JSON object")
}

#[test]
fn arm_run_reports_the_arm_metrics_and_prediction_keeps_more_distance() {
    let p = preset();
    let with = json_of(&planlab(&["run", &p, "--json"]));
    for k in [
        "outcome",
        "path_length_m",
        "path_points",
        "spikes",
        "min_obstacle_distance_m",
        "time_s",
    ] {
        assert!(with.get(k).is_some(), "{k} missing in {with}");
    }
    assert_eq!(with["outcome"], "reached");
    assert_eq!(with["planner"], "arm-apf:constant-velocity");
    let without = json_of(&planlab(&["run", &p, "--json", "--planner", "none"]));
    assert_eq!(without["planner"], "arm-apf:none");
    assert!(
        without["min_obstacle_distance_m"].as_f64().unwrap()
            < with["min_obstacle_distance_m"].as_f64().unwrap()
    );
    // A table without --json.
    let o = planlab(&["run", &p]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("min obstacle dist") && text.contains("spikes"),
        "{text}"
    );
}

#[test]
fn arm_run_edits_and_errors() {
    let p = preset();
    let slow = json_of(&planlab(&[
        "run",
        &p,
        "--json",
        "--set",
        "arm.sim.plan_period_s=1.0",
    ]));
    let fast = json_of(&planlab(&["run", &p, "--json"]));
    assert!(slow["time_s"].as_f64().unwrap() > fast["time_s"].as_f64().unwrap());
    let o = planlab(&["run", &p, "--set", "arm.goal=[2.0, 0.0, 0.9]"]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("out of reach"), "{err}");
    let o = planlab(&["run", &p, "--planner", "oracle"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("unknown predictor"));
}

/// `planlab batch` of the arm preset with both arm planners: one summary
/// per planner over the variants (success, joint and gripper path, hand
/// distance, compute time), and a CSV row replays with `planlab run
/// --variant` to the same trace hash.
#[test]
fn arm_batch_compares_the_planners_and_its_rows_replay() {
    let p = preset();
    let csv = std::env::temp_dir().join(format!("planlab-arm-batch-{}.csv", std::process::id()));
    let csv_s = csv.display().to_string();
    let o = planlab(&[
        "batch",
        &p,
        "--planners",
        "apf,rrt-connect",
        "--variants",
        "2",
        "--set",
        "arm.table_z_m=0.72",
        "--json",
        "--csv",
        &csv_s,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let lines: Vec<Value> = String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 3, "two summaries and a footer");
    for (s, name) in lines.iter().zip(["apf", "rrt-connect"]) {
        assert_eq!(s["planner"], name);
        assert_eq!(s["runs"], 2);
        for k in [
            "joint_path_length_rad",
            "gripper_path_length_m",
            "min_hand_distance_m",
            "compute_ms",
        ] {
            assert!(s["metrics"][k]["median"].as_f64().is_some(), "{k} in {s}");
        }
    }
    assert_eq!(lines[2]["jitter_m"], 0.02, "the arm's default jitter");
    let text = std::fs::read_to_string(&csv).unwrap();
    let _ = std::fs::remove_file(&csv);
    let rows: Vec<Vec<&str>> = text.lines().map(|l| l.split(',').collect()).collect();
    let col = |name: &str| rows[0].iter().position(|c| *c == name).unwrap();
    assert_eq!(rows.len(), 5, "{text}");
    let row = rows
        .iter()
        .find(|r| r[col("variant")] == "1" && r[col("planner")] == "rrt-connect")
        .unwrap();
    let run = json_of(&planlab(&[
        "run",
        &p,
        "--planner",
        "rrt-connect",
        "--variant",
        "1",
        "--seed",
        row[col("batch_seed")],
        "--set",
        "arm.table_z_m=0.72",
        "--json",
    ]));
    assert_eq!(run["trace_hash"], row[col("trace_hash")]);
    assert_eq!(run["outcome"], row[col("outcome")]);
}

/// Unknown arm planners in a batch are refused in one line naming the
/// known ones.
#[test]
fn arm_batch_refuses_a_robot_planner() {
    let o = planlab(&["batch", &preset(), "--planners", "dwa", "--variants", "2"]);
    assert!(!o.status.success());
    let e = String::from_utf8_lossy(&o.stderr);
    assert_eq!(e.trim().lines().count(), 1, "{e}");
    assert!(
        e.contains("unknown arm planner `dwa`") && e.contains("rrt-connect"),
        "{e}"
    );
}
