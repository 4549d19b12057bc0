//! Browser tests of the BARN functions (`wasm-pack test --headless
//! --chrome`): a world's scenario built in wasm runs to the trace the
//! native CLI runs (cross-platform determinism), and bad input arrives as a
//! one-line `JsError`.
#![cfg(target_arch = "wasm32")]

use planlab_wasm::{barn_planners, barn_scenario, barn_score, barn_worlds, SimHandle};
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::*;

wasm_bindgen_test_configure!(run_in_browser);

/// The worlds file the site serves.
const WORLDS: &str = include_str!("../../../assets/barn/worlds.txt");

/// The message of a `JsError` thrown across the boundary.
fn message(err: wasm_bindgen::JsError) -> String {
    let v: JsValue = err.into();
    let e: js_sys::Error = v.dyn_into().expect("a JS Error object");
    e.message().into()
}

#[wasm_bindgen_test]
fn barn_world_1_with_dwb_runs_to_the_native_trace_hash() {
    // `planlab run barn:1 --planner dwb --seed 1` (default laser noise
    // 0.01 m) prints: outcome reached, time 10.30 s, 103 steps,
    // trace hash c2bd27030861f5a2.
    const NATIVE: u64 = 0xc2bd_2703_0861_f5a2;
    let json = barn_scenario(WORLDS, 1, "dwb", 1.0, 0.01).expect("world 1 builds");
    let mut sim = SimHandle::from_scenario(&json, None).expect("the episode starts");
    while sim.outcome() == "running" {
        sim.step(50);
    }
    assert_eq!(sim.outcome(), "reached");
    assert_eq!(sim.steps(), 103.0);
    assert_eq!(sim.trace_hash(), NATIVE.to_string());
}

#[wasm_bindgen_test]
fn barn_worlds_lists_every_world_with_its_class_and_optimal_time() {
    let v: serde_json::Value = serde_json::from_str(&barn_worlds(WORLDS).unwrap()).unwrap();
    let list = v.as_array().unwrap();
    // Worlds 0–299 without the held-back N mod 6 = 0.
    assert_eq!(list.len(), 250);
    assert!(list.iter().all(|w| w["id"].as_u64().unwrap() % 6 != 0));
    let w1 = &list[0];
    assert_eq!(w1["id"], 1);
    assert!(["easy", "medium", "hard"].contains(&w1["difficulty"].as_str().unwrap()));
    assert!(w1["optimal_time"].as_f64().unwrap() > 4.0);
    assert!(w1["cylinders"].as_u64().unwrap() > 50);
}

#[wasm_bindgen_test]
fn barn_bad_input_is_a_one_line_error() {
    for (id, planner, seed, noise, needle) in [
        (6, "dwb", 0.0, 0.01, "not in the worlds file"),
        (1, "a-star", 0.0, 0.01, "cannot drive an unknown map"),
        (1, "dwb", -1.0, 0.01, "seed"),
        (1, "dwb", 0.5, 0.01, "seed"),
        (1, "dwb", 0.0, -0.1, "noise_std"),
    ] {
        let m = message(barn_scenario(WORLDS, id, planner, seed, noise).unwrap_err());
        assert!(m.contains(needle), "{m}");
        assert!(!m.contains('\n'), "{m}");
    }
    let m = message(barn_worlds("1 not a world").unwrap_err());
    assert!(m.starts_with("BARN compact form"), "{m}");
}

#[wasm_bindgen_test]
fn barn_planners_and_score_are_the_cores() {
    let p = barn_planners();
    assert_eq!(p[0], "move-base-dwa");
    assert!(p.iter().any(|n| n == "dwb"));
    // OT / clip(T, 2·OT, 8·OT): 4 / clip(10, 8, 32) = 0.4; fast runs cap at 0.5.
    assert_eq!(barn_score(true, 10.0, 4.0), 0.4);
    assert_eq!(barn_score(true, 1.0, 4.0), 0.5);
    assert_eq!(barn_score(false, 10.0, 4.0), 0.0);
}
