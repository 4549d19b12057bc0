//! Browser tests of the wasm boundary (`wasm-pack test --headless --chrome`):
//! plans cross as typed arrays with the core's costs, and core errors arrive
//! as `JsError`s with the core's message instead of panics.
#![cfg(target_arch = "wasm32")]

use planlab_wasm::{default_plan_options, plan, MapHandle, ScenBatch};
use wasm_bindgen::{JsCast, JsValue};
use wasm_bindgen_test::*;

wasm_bindgen_test_configure!(run_in_browser);

const SQRT2: f64 = std::f64::consts::SQRT_2;

/// A wall with one gap forces a detour of known length.
const MAP: &str = "
.......
.......
####.##
.......
.......
";

/// Options object as the page builds it.
fn options(json: &str) -> JsValue {
    js_sys::JSON::parse(json).expect("test JSON is valid")
}

/// The message of a `JsError` thrown across the boundary.
fn message(err: wasm_bindgen::JsError) -> String {
    let v: JsValue = err.into();
    let e: js_sys::Error = v.dyn_into().expect("a JS Error object");
    e.message().into()
}

#[wasm_bindgen_test]
fn astar_cost_and_path_arrays() {
    let map = MapHandle::from_ascii(MAP).unwrap();
    assert_eq!((map.width(), map.height()), (7, 5));
    // (0,0) → (0,4) must pass the gap at (4,2), which without corner
    // cutting is entered and left straight: (0,0)→(4,1) is 3 + √2,
    // (4,1)→(4,3) is 2, (4,3)→(0,4) is 3 + √2.
    let expected = 8.0 + 2.0 * SQRT2;
    let result = plan(&map, 0, 0, 0, 4, options(r#"{"algorithm":"astar"}"#), true).unwrap();
    let path = result.path();
    assert_eq!(path.len() % 2, 0);
    assert_eq!(path.len() as u32, result.path_len() * 2);
    assert_eq!((path[0], path[1]), (0, 0));
    assert_eq!((path[path.len() - 2], path[path.len() - 1]), (0, 4));
    // The path goes through the gap at (4, 2).
    assert!(path.chunks(2).any(|p| p == [4, 2]));
    // Every step is a king move and the reported cost is the sum of steps.
    let mut len = 0.0;
    for w in path.chunks(2).collect::<Vec<_>>().windows(2) {
        let (dc, dr) = (
            w[1][0] as i64 - w[0][0] as i64,
            w[1][1] as i64 - w[0][1] as i64,
        );
        assert!(dc.abs() <= 1 && dr.abs() <= 1 && (dc, dr) != (0, 0));
        len += if dc != 0 && dr != 0 { SQRT2 } else { 1.0 };
    }
    assert!((result.cost() - len).abs() < 1e-9);
    assert!(
        (result.cost() - expected).abs() < 1e-9,
        "cost {} != {expected}",
        result.cost()
    );
    assert!(result.expanded_count() > 0);
    assert_eq!(result.expanded().len() as u32, result.expanded_count() * 2);
    assert!((result.length_m() - result.cost() * map.resolution()).abs() < 1e-12);
}

#[wasm_bindgen_test]
fn jps_and_dijkstra_agree_with_astar() {
    let map = MapHandle::from_ascii(MAP).unwrap();
    let a = plan(&map, 6, 0, 0, 4, options(r#"{"algorithm":"astar"}"#), false).unwrap();
    let j = plan(&map, 6, 0, 0, 4, options(r#"{"algorithm":"jps"}"#), false).unwrap();
    let d = plan(
        &map,
        6,
        0,
        0,
        4,
        options(r#"{"algorithm":"dijkstra"}"#),
        false,
    )
    .unwrap();
    assert!((a.cost() - j.cost()).abs() < 1e-9);
    assert!((a.cost() - d.cost()).abs() < 1e-9);
    // Not recording leaves the expanded list empty but still counts.
    assert!(a.expanded().is_empty() && a.expanded_count() > 0);
}

#[wasm_bindgen_test]
fn start_in_wall_is_a_js_error_with_the_core_message() {
    let map = MapHandle::from_ascii(MAP).unwrap();
    let err = plan(&map, 0, 2, 6, 4, JsValue::UNDEFINED, false).unwrap_err();
    assert_eq!(message(err), "start (0, 2) is inside an obstacle");
    // The module is still alive after the error.
    assert!(plan(&map, 0, 0, 6, 4, JsValue::UNDEFINED, false).is_ok());
}

#[wasm_bindgen_test]
fn bad_options_and_files_are_errors_not_panics() {
    let map = MapHandle::from_ascii(MAP).unwrap();
    let err = plan(
        &map,
        0,
        0,
        6,
        4,
        options(r#"{"algorithm":"teleport"}"#),
        false,
    )
    .unwrap_err();
    assert!(message(err).starts_with("invalid plan options"));
    let err = plan(&map, 0, 0, 6, 4, options(r#"{"weight":0.5}"#), false).unwrap_err();
    assert!(message(err).contains("weight"));
    let err = MapHandle::from_movingai("type octile\nheight 2\nwidth 3\nmap\n...\n").unwrap_err();
    assert!(message(err).contains("Moving AI map"));
    let err = MapHandle::from_ros(
        "image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n",
        b"P5 2 2 255\n\x00",
    )
    .unwrap_err();
    assert!(!message(err).is_empty());
}

#[wasm_bindgen_test]
fn editing_cells_replans_and_refuses_off_map() {
    let mut map = MapHandle::from_ascii(MAP).unwrap();
    // Closing the gap makes the goal unreachable.
    map.set_cell(4, 2, 1).unwrap();
    assert_eq!(map.cells()[2 * 7 + 4], 1);
    let err = plan(&map, 0, 0, 0, 4, JsValue::UNDEFINED, false).unwrap_err();
    assert!(message(err).starts_with("goal is unreachable"));
    let err = map.set_cell(7, 0, 1).unwrap_err();
    assert!(message(err).contains("outside"));
    // A stroke re-opens the whole (now all-wall) row: all 7 cells change,
    // and repeating it changes none.
    assert_eq!(map.paint_segment(0, 2, 6, 2, 0).unwrap(), 7);
    assert_eq!(map.paint_segment(6, 2, 0, 2, 0).unwrap(), 0);
    assert!(plan(&map, 0, 0, 0, 4, JsValue::UNDEFINED, false).is_ok());
}

#[wasm_bindgen_test]
fn defaults_and_scen_batch() {
    let d = default_plan_options().unwrap();
    let algo = js_sys::Reflect::get(&d, &"algorithm".into()).unwrap();
    assert_eq!(algo.as_string().as_deref(), Some("astar"));
    let map = MapHandle::from_ascii(MAP).unwrap();
    let scen = format!(
        "version 1\n0\tm.map\t7\t5\t0\t0\t0\t4\t{}\n",
        8.0 + 2.0 * SQRT2
    );
    let batch = ScenBatch::new(&map, &scen, JsValue::UNDEFINED).unwrap();
    assert_eq!(batch.rows(), 1);
    assert!((batch.solve_all().unwrap() - batch.optimal_sum()).abs() < 1e-9);
}

#[wasm_bindgen_test]
fn scenario_inline_and_file_reference() {
    let inline = r#####"{"version": 1, "name": "gap",
        "map": {"width": 7, "height": 5, "cells": [".......", ".......", "####.##", ".......", "......."]},
        "start": {"col": 0, "row": 0}, "goal": {"col": 0, "row": 4},
        "grid_planner": {"algorithm": "jps"}}"#####;
    let sc = planlab_wasm::ScenarioHandle::from_json(inline).unwrap();
    assert_eq!(sc.name(), "gap");
    assert_eq!((sc.start(), sc.goal()), (vec![0, 0], vec![0, 4]));
    assert_eq!(sc.map_file(), None);
    let opts = sc.planner_options().unwrap();
    let algo = js_sys::Reflect::get(&opts, &"algorithm".into()).unwrap();
    assert_eq!(algo.as_string().as_deref(), Some("jps"));
    let map = sc.load_map(&js_sys::Object::new()).unwrap();
    let r = plan(&map, 0, 0, 0, 4, opts, false).unwrap();
    assert!((r.cost() - (8.0 + 2.0 * SQRT2)).abs() < 1e-9);

    let by_ref = r#"{"version": 1, "map": {"file": "maps/gap.map"},
        "start": {"col": 0, "row": 0}, "goal": {"col": 0, "row": 4}}"#;
    let sc = planlab_wasm::ScenarioHandle::from_json(by_ref).unwrap();
    assert_eq!(sc.map_file().as_deref(), Some("maps/gap.map"));
    let err = sc.load_map(&js_sys::Object::new()).unwrap_err();
    assert!(message(err).contains("gap.map"));
    let files = js_sys::Object::new();
    let text = "type octile\nheight 5\nwidth 7\nmap\n.......\n.......\n@@@@.@@\n.......\n.......\n";
    js_sys::Reflect::set(
        &files,
        &"gap.map".into(),
        &js_sys::Uint8Array::from(text.as_bytes()),
    )
    .unwrap();
    let map = sc.load_map(&files).unwrap();
    assert_eq!((map.width(), map.height()), (7, 5));
    assert_eq!(map.cells()[2 * 7 + 4], 0);
}
