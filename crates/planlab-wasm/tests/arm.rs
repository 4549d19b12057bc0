//! Browser tests of the arm page's handle (`wasm-pack test --headless
//! --chrome`): the T-tab5-3 preset runs to the goal with the minimum
//! distance it reports, typed arrays have their documented shapes, live
//! edits work, and unreachable targets or bad scenarios arrive as
//! `JsError`s with the core's message.
#![cfg(all(target_arch = "wasm32", feature = "arm"))]

use planlab_wasm::{arm_choices, ArmHandle};
use wasm_bindgen::JsValue;
use wasm_bindgen_test::*;

wasm_bindgen_test_configure!(run_in_browser);

const PRESET: &str = include_str!("../../../assets/scenarios/T-tab5-3.json");

fn message(err: wasm_bindgen::JsError) -> String {
    let v: JsValue = err.into();
    js_sys::Reflect::get(&v, &"message".into())
        .ok()
        .and_then(|m| m.as_string())
        .unwrap_or_default()
}

#[wasm_bindgen_test]
fn preset_runs_to_the_goal_and_reports_its_minimum_distance() {
    let mut h = ArmHandle::new(PRESET).unwrap();
    assert_eq!(h.outcome(), "running");
    assert_eq!(h.links().len(), 8 * 7, "8 links × (a, b, radius)");
    assert_eq!(h.joint_angles().len(), 7);
    assert_eq!(h.joint_limits().len(), 14);
    assert_eq!(h.hand().len(), 4 + 7);
    let mut out = String::new();
    for _ in 0..1000 {
        out = h.step(5).unwrap();
        if out != "running" {
            break;
        }
    }
    assert_eq!(out, "reached");
    let m: serde_json::Value = serde_json::from_str(&h.metrics_json().unwrap()).unwrap();
    assert_eq!(m["outcome"], "reached");
    assert_eq!(
        m["min_obstacle_distance_m"].as_f64().unwrap(),
        h.min_distance()
    );
    assert!(h.min_distance() > 0.0 && h.min_distance() <= h.distance_now());
    let path = h.tool_path();
    assert_eq!(path.len() as u64 % 3, 0);
    assert_eq!(path.len() as u64 / 3, m["path_points"].as_u64().unwrap());
    let goal = h.goal();
    let n = path.len();
    let end = [path[n - 3] as f64, path[n - 2] as f64, path[n - 1] as f64];
    let d = ((end[0] - goal[0]).powi(2) + (end[1] - goal[1]).powi(2) + (end[2] - goal[2]).powi(2))
        .sqrt();
    assert!(d < 0.01, "{d}");
    // Joint angles stay inside the limits.
    let (q, lim) = (h.joint_angles(), h.joint_limits());
    for i in 0..7 {
        assert!(q[i] >= lim[2 * i] && q[i] <= lim[2 * i + 1]);
    }
    assert_eq!(
        h.hand_path().len() as f64 / 3.0,
        (h.time() / h.dt()).round() + 1.0
    );
}

#[wasm_bindgen_test]
fn prediction_shows_virtual_obstacles_and_edits_apply() {
    let mut h = ArmHandle::new(PRESET).unwrap();
    assert_eq!(h.predictor(), "constant-velocity");
    let mut seen = 0;
    for _ in 0..40 {
        h.step(1).unwrap();
        let p = h.predictions();
        assert_eq!(p.len() % 5, 0);
        seen = seen.max(p.len() / 5);
    }
    assert!(seen > 0, "the moving hand gets predicted positions");
    h.set_predictor("none").unwrap();
    h.step(5).unwrap();
    assert!(h.predictions().is_empty());
    assert!(message(h.set_predictor("oracle").unwrap_err()).contains("oracle"));
    // Goal edits: a reachable one is taken, unreachable ones are refused.
    h.set_goal(0.55, 0.3, 0.85).unwrap();
    assert_eq!(h.goal(), vec![0.55, 0.3, 0.85]);
    assert!(message(h.set_goal(3.0, 0.0, 0.9).unwrap_err()).contains("out of reach"));
    assert!(message(h.set_goal(-0.3, -0.3, 0.9).unwrap_err()).contains("cannot be reached"));
    assert_eq!(h.goal(), vec![0.55, 0.3, 0.85]);
    // Hand edits restart the episode.
    h.set_hand("wave", 0.5, 4.0).unwrap();
    assert_eq!(h.time(), 0.0);
    assert_eq!(
        (h.hand_preset().as_str(), h.hand_speed(), h.seed()),
        ("wave", 0.5, 4.0)
    );
    assert!(message(h.set_hand("juggle", 1.0, 0.0).unwrap_err()).contains("juggle"));
    assert!(message(h.set_hand("wave", 0.0, 0.0).unwrap_err()).contains("speed"));
    let choices: serde_json::Value = serde_json::from_str(&arm_choices()).unwrap();
    assert_eq!(choices["hand_presets"].as_array().unwrap().len(), 5);
    assert_eq!(
        choices["planners"],
        serde_json::json!(["apf", "rrt-connect"])
    );
}

#[wasm_bindgen_test]
fn planner_json_names_the_planner_and_counts_its_effort() {
    let mut h = ArmHandle::new(PRESET).unwrap();
    let before: serde_json::Value = serde_json::from_str(&h.planner_json().unwrap()).unwrap();
    assert_eq!(before["planner"], "apf");
    assert_eq!(before["plans"], 0);
    // The APF does not know a table: no distance to it.
    assert!(before["min_table_m"].is_null());
    h.step(20).unwrap();
    let after: serde_json::Value = serde_json::from_str(&h.planner_json().unwrap()).unwrap();
    assert!(after["plans"].as_u64().unwrap() > 0, "{after}");
    assert!(after["joint_path_rad"].as_f64().unwrap() > 0.0, "{after}");
    assert!(after["gripper_path_m"].as_f64().unwrap() > 0.0, "{after}");
}

#[wasm_bindgen_test]
fn bad_scenarios_are_errors() {
    assert!(message(ArmHandle::new("{").err().unwrap()).contains("JSON"));
    let far = PRESET.replace("\"goal\": [0.6, 0.35, 0.82]", "\"goal\": [2.0, 0.0, 0.9]");
    assert!(message(ArmHandle::new(&far).err().unwrap()).contains("out of reach"));
}

#[wasm_bindgen_test]
fn distance_series_records_every_sample_and_restarts() {
    let mut h = ArmHandle::new(PRESET).unwrap();
    assert_eq!(h.distance_series(0).len(), 3);
    h.step(20).unwrap();
    let s = h.distance_series(0);
    assert_eq!(s.len(), 3 * 21);
    for r in s.chunks(3) {
        assert!(r[1] > 0.0 && r[2] >= r[1], "{r:?}");
    }
    assert!((s[60] - h.time()).abs() < 1e-12);
    assert_eq!(s[61], h.distance_now());
    assert_eq!(h.distance_series(20).len(), 3);
    h.reset().unwrap();
    assert_eq!(h.distance_series(0).len(), 3);
}
