//! `planlab run` on APF scenarios, `planlab reproduce T-tab4-1 --json` and
//! `planlab train-predictor`.

use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};

fn preset(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join(format!("../../assets/scenarios/{name}.json"))
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

const METRICS: [&str; 6] = [
    "outcome",
    "path_length_m",
    "path_points",
    "spikes",
    "min_obstacle_distance_m",
    "time_s",
];

#[test]
fn run_prints_the_apf_metrics_and_modes_change_the_outcome() {
    let p = preset("T-fig4-6");
    let v = json_of(&planlab(&["run", &p, "--json"]));
    for k in METRICS {
        assert!(v.get(k).is_some(), "{k} missing in {v}");
    }
    assert_eq!(v["outcome"], "reached");
    assert_eq!(v["dims"], 2);
    let b = json_of(&planlab(&[
        "run",
        &p,
        "--json",
        "--set",
        "apf.config.mode=basic",
    ]));
    assert_eq!(b["outcome"], "stuck");
    let t = json_of(&planlab(&["run", &preset("T-tab4-1"), "--json"]));
    assert_eq!(t["dims"], 3);
    // A goal inside an obstacle is one clear error line.
    let o = planlab(&["run", &p, "--set", "apf.goal=[0.5,0.0]"]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("inside obstacle") && !err.contains("panicked"),
        "{err}"
    );
}

#[test]
fn reproduce_tab4_1_json_has_the_table_metrics() {
    let v = json_of(&planlab(&["reproduce", "T-tab4-1", "--json"]));
    assert_eq!(v["holds"], true);
    for run in ["apf", "sampling", "sampling+prediction"] {
        for k in METRICS {
            assert!(v["runs"][run].get(k).is_some(), "{run}.{k} missing in {v}");
        }
    }
    assert_eq!(v["runs"]["sampling+prediction"]["spikes"], 0);
}

#[test]
fn train_predictor_writes_weights_that_beat_constant_velocity() {
    let out = std::env::temp_dir().join(format!("planlab-rnn-{}.json", std::process::id()));
    let o = planlab(&[
        "train-predictor",
        "--epochs",
        "15",
        "--trajectories",
        "20",
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]);
    let r = json_of(&o);
    let (rnn, cv) = (
        r["heldout_mse"].as_f64().unwrap(),
        r["heldout_mse_constant_velocity"].as_f64().unwrap(),
    );
    assert!(rnn < cv, "{r}");
    let w = std::fs::read_to_string(&out).unwrap();
    assert!(planlab_core::apf::SimpleRnn::from_json(&w).is_ok());
    let _ = std::fs::remove_file(&out);
}
