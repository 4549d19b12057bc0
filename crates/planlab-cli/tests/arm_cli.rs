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
