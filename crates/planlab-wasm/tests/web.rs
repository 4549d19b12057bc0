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

// ------------------------------------------------------------ robot sim

/// A 4 × 2 m room (0.2 m cells) with a wall stub; start left, goal right.
fn room_json(planner: &str, extra: &str) -> String {
    let wall = "#".repeat(20);
    let inside = format!("\"#{}#\"", ".".repeat(18));
    let mut rows = vec![format!("\"{wall}\"")];
    rows.extend(vec![inside; 8]);
    rows.push(format!("\"{wall}\""));
    format!(
        r#"{{"version": 1, "name": "room",
        "map": {{"width": 20, "height": 10, "resolution": 0.2, "cells": [{}]}},
        "start": {{"col": 2, "row": 5}}, "goal": {{"col": 17, "row": 5}},
        "local_planner": {{"name": "{planner}"}}{extra}}}"#,
        rows.join(",")
    )
}

/// Bit set of draw layers.
fn bits(layers: &[planlab_core::draw::Layer]) -> u32 {
    layers.iter().fold(0, |b, l| b | 1 << *l as u8)
}

/// The final goal, from the Goals layer (tag 1).
fn goal_of(sim: &planlab_wasm::SimHandle) -> Vec<f64> {
    use planlab_core::draw::Layer;
    let d = sim.draw_list(bits(&[Layer::Goals]), 0);
    let g = d
        .layer(Layer::Goals)
        .find(|i| i.tag == 1.0)
        .expect("a goal");
    d.numbers(g).to_vec()
}

/// The movers now, stride 6 (`id, radius, x, y, vx, vy`), from the Movers layer.
fn movers_of(sim: &planlab_wasm::SimHandle) -> Vec<f64> {
    use planlab_core::draw::Layer;
    let d = sim.draw_list(bits(&[Layer::Movers]), 0);
    d.layer(Layer::Movers)
        .flat_map(|i| {
            let n = d.numbers(i);
            [i.tag, n[2], n[0], n[1], n[3], n[4]]
        })
        .collect()
}

/// A typed array property of a draw object, as a Vec.
fn array_of(o: &js_sys::Object, key: &str) -> Vec<f64> {
    let v = js_sys::Reflect::get(o, &JsValue::from_str(key)).expect("the key");
    if let Some(a) = v.dyn_ref::<js_sys::Float64Array>() {
        return a.to_vec();
    }
    let b: js_sys::Uint8Array = v.dyn_into().expect("a typed array");
    b.to_vec().into_iter().map(f64::from).collect()
}

#[wasm_bindgen_test]
fn episode_runs_to_reached_with_typed_arrays() {
    use planlab_wasm::SimHandle;
    let mut sim = SimHandle::from_scenario(&room_json("pursuit", ""), None).unwrap();
    assert_eq!(sim.outcome(), "running");
    assert_eq!(sim.trace_len(), 1);
    let goal = goal_of(&sim);
    let mut guard = 0;
    while sim.step(7) == "running" {
        guard += 1;
        assert!(guard < 1000, "episode does not end");
    }
    assert_eq!(sim.outcome(), "reached");
    let s = sim.state();
    assert_eq!(s.len(), 6);
    assert!((s[0] - goal[0]).hypot(s[1] - goal[1]) <= 0.2);
    // Series and trail: one row per step plus the start row, from any row.
    let n = sim.trace_len() as usize;
    assert_eq!(n as f64, sim.steps() + 1.0);
    assert_eq!(sim.series(0).len(), 5 * n);
    use planlab_core::draw::{Layer, ITEM_STRIDE};
    let trail = bits(&[Layer::Trail]);
    assert_eq!(sim.draw_list(trail, 0).data.len(), 2 * n);
    assert_eq!(sim.draw_list(trail, n as u32 - 2).data.len(), 4);
    assert!(sim.draw_list(trail, n as u32 + 5).items.is_empty());
    // The draw object's typed arrays are the core's draw list.
    let all = u32::MAX;
    let list = sim.draw_list(all, 0);
    let o = sim.draw(all, 0).unwrap();
    assert_eq!(array_of(&o, "data"), list.data);
    assert_eq!(array_of(&o, "items"), list.items_flat());
    let cells = array_of(&o, "cells");
    assert_eq!(cells.len(), 2 * 20 * 10, "the map's cells and the fog's");
    let items = array_of(&o, "items");
    assert_eq!(items.len() % ITEM_STRIDE, 0);
    for it in items.chunks(ITEM_STRIDE) {
        assert!(it[2] <= it[3] && it[3] as usize <= list.data.len());
    }
    // A row's frame: the robot where the row says.
    let row = sim.trace_row(3);
    let f = sim.row_draw_list(3, bits(&[Layer::Robot]));
    let body = f.layer(Layer::Robot).next().unwrap();
    assert_eq!(&f.numbers(body)[..2], &row[1..3]);
    // Metrics and hash as the CLI reports them.
    let m: serde_json::Value = serde_json::from_str(&sim.metrics_json().unwrap()).unwrap();
    assert_eq!(m["outcome"], "reached");
    assert!(m["path_length_m"].as_f64().unwrap() > 2.5);
    assert!(sim.trace_hash().parse::<u64>().is_ok());
    assert!(sim.trace_csv().lines().count() == n + 1);
    // The same scenario replays to the same hash.
    let mut again = SimHandle::from_scenario(&room_json("pursuit", ""), None).unwrap();
    while again.step(1000) == "running" {}
    assert_eq!(again.trace_hash(), sim.trace_hash());
}

#[wasm_bindgen_test]
fn bad_scenarios_are_errors_not_panics() {
    use planlab_wasm::SimHandle;
    let err = |r: Result<SimHandle, wasm_bindgen::JsError>| message(r.err().expect("an error"));
    assert!(!err(SimHandle::from_scenario("{\"version\": 1, \"map\": ", None)).is_empty());
    let e = err(SimHandle::from_scenario(
        &room_json("pursuit", r#", "robot": {"limits": {"v_max": -1}}"#),
        None,
    ));
    assert!(e.contains("v_max"), "{e}");
    let e = err(SimHandle::from_scenario(&room_json("teleport", ""), None));
    assert!(e.contains("teleport"), "{e}");
    let e = err(SimHandle::from_scenario(
        &room_json("pursuit", r#", "start_yaw": 0, "sim": {"dt": 0}"#),
        None,
    ));
    assert!(e.contains("sim.dt"), "{e}");
    // A map given by file name that was not passed.
    let e = err(SimHandle::from_scenario(
        r#"{"version": 1, "map": {"file": "maps/room.map"},
            "start": {"col": 1, "row": 1}, "goal": {"col": 2, "row": 2},
            "local_planner": {"name": "pursuit"}}"#,
        None,
    ));
    assert!(e.contains("room.map"), "{e}");
    // Still alive.
    assert!(SimHandle::from_scenario(&room_json("pursuit", ""), None).is_ok());
}

#[wasm_bindgen_test]
fn live_edits_and_their_errors() {
    use planlab_wasm::SimHandle;
    let mut sim = SimHandle::from_scenario(&room_json("pursuit", ""), None).unwrap();
    // An edit before the first step is part of the saved setup, not live.
    sim.set_goal(3.0, 0.7).unwrap();
    assert_eq!(sim.live_edits(), 0);
    sim.step(5);
    // Goal: a free point is taken, a wall refused with the core's message.
    sim.set_goal(3.0, 0.6).unwrap();
    assert_eq!(goal_of(&sim), vec![3.0, 0.6]);
    assert_eq!(sim.live_edits(), 1);
    let e = message(sim.set_goal(0.1, 0.1).unwrap_err());
    assert!(e.contains("wall"), "{e}");
    assert_eq!(goal_of(&sim), vec![3.0, 0.6]);
    // A refused edit is not part of the run.
    assert_eq!(sim.live_edits(), 1);
    // Movers: placed now, at the drop point with the drag's velocity.
    let id = sim
        .place_mover("back-and-forth", 0.2, 2.0, 1.5, 0.3, 0.0, 1.0)
        .unwrap();
    let m = movers_of(&sim);
    assert_eq!(m.len(), 6);
    assert_eq!(m[0], f64::from(id));
    assert!((m[2] - 2.0).abs() < 1e-9 && (m[3] - 1.5).abs() < 1e-9);
    assert!((m[4] - 0.3).abs() < 1e-9 && m[5].abs() < 1e-9);
    let e = message(
        sim.place_mover("teleport", 0.2, 2.0, 1.5, 0.3, 0.0, 1.0)
            .unwrap_err(),
    );
    assert!(e.contains("teleport"), "{e}");
    let e = message(
        sim.place_mover("waypoint-loop", -1.0, 2.0, 1.5, 0.3, 0.0, 1.0)
            .unwrap_err(),
    );
    assert!(e.contains("radius"), "{e}");
    let json = sim.movers_json().unwrap();
    sim.set_movers("[]").unwrap();
    assert!(movers_of(&sim).is_empty());
    sim.set_movers(&json).unwrap();
    assert_eq!(movers_of(&sim).len(), 6);
    assert!(message(sim.set_movers("[{\"radius\": 1}]").unwrap_err()).contains("movers"));
    // Planner: re-tuned live; a bad value names the field and the old one stays.
    sim.set_planner("pursuit", r#"{"k_w": 2.0}"#).unwrap();
    assert!(sim.planner_choice().unwrap().contains("2.0"));
    let e = message(sim.set_planner("pursuit", r#"{"k_w": -1}"#).unwrap_err());
    assert!(e.contains("k_w"), "{e}");
    let e = message(sim.set_planner("pursuit", "{").unwrap_err());
    assert!(e.contains("config JSON"), "{e}");
    assert!(sim.planner_choice().unwrap().contains("2.0"));
    assert_eq!(sim.step(1), "running");
}

#[wasm_bindgen_test]
fn from_map_and_planner_list() {
    use planlab_wasm::{planners, SimHandle};
    let map = MapHandle::from_ascii("..........\n..........\n..........\n").unwrap();
    let mut sim = SimHandle::from_map(
        &map,
        r#"{"start": [1.5, 1.5], "goal": [8.5, 1.5], "local_planner": {"name": "pursuit"}}"#,
    )
    .unwrap();
    while sim.step(50) == "running" {}
    assert_eq!(sim.outcome(), "reached");
    let e = message(
        SimHandle::from_map(
            &map,
            r#"{"start": [1.5, 1.5], "goal": [8.5, 1.5], "wings": 2}"#,
        )
        .err()
        .unwrap(),
    );
    assert!(e.contains("wings"), "{e}");
    let list: serde_json::Value = serde_json::from_str(&planners().unwrap()).unwrap();
    let pursuit = list
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "pursuit")
        .expect("pursuit is registered");
    for f in pursuit["fields"].as_array().unwrap() {
        assert!(f["kind"].is_string() && !f["doc"].as_str().unwrap().is_empty());
    }
}

#[wasm_bindgen_test]
fn apf_handle_runs_a_preset_and_reports_what_the_page_draws() {
    use planlab_wasm::ApfHandle;
    let json = include_str!("../../../assets/scenarios/T-fig4-6.json");
    let mut h = ApfHandle::new(json).unwrap();
    h.set_mode("basic").unwrap();
    assert_eq!(h.step(400).unwrap(), "stuck");
    h.set_mode("sampling").unwrap();
    assert_eq!(h.step(400).unwrap(), "reached");
    assert!(h.path().len() / 2 > 20);
    assert!(h.metrics().contains("\"path_points\""));
    assert_eq!(h.field(8, 6).len(), 2 * 8 * 6);
    h.reset().unwrap();
    h.step(10).unwrap();
    assert_eq!(h.candidates().len(), 13 * 3);
    assert!(h.chosen() >= 0);
    // A goal inside the disc is refused; the run keeps its goal.
    assert!(h.set_goal(0.5, 0.0).is_err());
    assert_eq!(h.endpoints()[2], 1.0);
    assert!(h.set_mode("warp").is_err());
}

#[wasm_bindgen_test]
fn timeline_replays_an_edited_run_exactly_and_reads_rows() {
    use planlab_wasm::SimHandle;
    let mut sim = SimHandle::from_scenario(&room_json("dwa", ""), None).unwrap();
    sim.set_goal(3.2, 1.2).unwrap();
    sim.step(8);
    sim.place_mover("constant-velocity", 0.15, 2.6, 1.5, 0.0, -0.2, 1.0)
        .unwrap();
    // Refused edits are not part of the run.
    assert!(sim.set_goal(0.1, 0.1).is_err());
    while sim.step(50) == "running" {}
    assert_eq!(sim.edit_steps(), vec![0.0, 8.0]);
    let n = sim.steps();
    // The whole run again: the identical trace.
    let again = sim.replay_to(n).unwrap();
    assert_eq!(again.trace_hash(), sim.trace_hash());
    assert_eq!(again.outcome(), sim.outcome());
    // Frame 5, then on to frame 12 without starting over: the rows agree
    // with the run's, and the replay has the mover placed at step 8.
    let mut scratch = sim.replay_to(5.0).unwrap();
    assert_eq!(scratch.steps(), 5.0);
    // (Without a vehicle the loads are NaN, which never compare equal.)
    let head = |r: Vec<f64>| r[..15].to_vec();
    assert_eq!(head(scratch.trace_row(5)), head(sim.trace_row(5)));
    assert!(movers_of(&scratch).is_empty());
    assert!(sim.advance_replay(&mut scratch, 12.0).unwrap());
    assert_eq!(scratch.steps(), 12.0);
    assert_eq!(head(scratch.trace_row(12)), head(sim.trace_row(12)));
    assert_eq!(movers_of(&scratch).len(), 6);
    let fan = bits(&[planlab_core::draw::Layer::Fan]);
    assert!(
        !scratch.draw_list(fan, 0).items.is_empty(),
        "the frame's fan is drawn"
    );
    // Backwards needs a new replay.
    assert!(!sim.advance_replay(&mut scratch, 3.0).unwrap());
    // Rows: pose, goal and movers of the trace.
    let r = sim.trace_row(12);
    assert_eq!(r.len(), 19);
    let csv = sim.trace_csv();
    let line: Vec<f64> = csv
        .lines()
        .nth(13)
        .unwrap()
        .split(',')
        .take(13)
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(&r[..13], &line[..]);
    assert!(r[15].is_nan(), "no vehicle, no loads");
    let movers = bits(&[planlab_core::draw::Layer::Movers]);
    assert_eq!(sim.row_draw_list(12, movers).items.len(), 1);
    assert!(sim.row_draw_list(5, movers).items.is_empty());
    assert!(sim.trace_row(n as u32 + 1).is_empty());
    // A branch from frame 12 continues on its own and replays exactly.
    let mut branch = sim.replay_to(12.0).unwrap();
    branch.set_goal(3.4, 0.6).unwrap();
    while branch.step(50) == "running" {}
    assert_ne!(branch.trace_hash(), sim.trace_hash());
    let b2 = branch.replay_to(branch.steps()).unwrap();
    assert_eq!(b2.trace_hash(), branch.trace_hash());
    assert_eq!(b2.run_id(), sim.run_id());
    // A restart at t = 0 (an editing tool) is a new run with a new
    // recording: its replay is the restarted episode.
    let mut edited = sim.replay_to(20.0).unwrap();
    edited.restart().unwrap();
    assert_ne!(edited.run_id(), sim.run_id());
    assert!(edited.edit_steps().is_empty());
    edited.step(5);
    let r = edited.replay_to(5.0).unwrap();
    assert_eq!(r.trace_hash(), edited.trace_hash());
    // Plot series: no global path for plain DWA (no tracking error), no
    // vehicle (NaN loads).
    assert!(!sim.has_vehicle());
    assert!(sim.tracking_errors(0).is_empty());
    assert_eq!(sim.wheel_loads(0).len() as f64, 5.0 * (n + 1.0));
    // Improved DWA follows a global path: one distance per row whose mean
    // and max are the metrics `planlab run` reports.
    let mut p = SimHandle::from_scenario(&room_json("improved-dwa", ""), None).unwrap();
    while p.step(50) == "running" {}
    let d = p.tracking_errors(0);
    assert_eq!(d.len() as u32, p.trace_len());
    assert_eq!(p.tracking_errors(3).len() + 3, d.len());
    let m: serde_json::Value = serde_json::from_str(&p.metrics_json().unwrap()).unwrap();
    let mean = d.iter().sum::<f64>() / d.len() as f64;
    let max = d.iter().copied().fold(0.0, f64::max);
    assert!((mean - m["mean_tracking_error_m"].as_f64().unwrap()).abs() < 1e-12);
    assert_eq!(max, m["max_tracking_error_m"].as_f64().unwrap());
}

#[wasm_bindgen_test]
fn critics_carry_the_last_steps_weights_and_choose_the_fan_colour() {
    use planlab_core::draw::Layer;
    use planlab_wasm::SimHandle;
    let mut sim = SimHandle::from_scenario(&room_json("dwa", ""), None).unwrap();
    sim.set_planner("dwa", r#"{"beta": 0.3}"#).unwrap();
    let critics = |h: &SimHandle| -> Vec<(String, Option<f64>)> {
        let v: Vec<serde_json::Value> = serde_json::from_str(&h.critics().unwrap()).unwrap();
        v.iter()
            .map(|c| {
                (
                    c["name"].as_str().unwrap().to_string(),
                    c["weight"].as_f64(),
                )
            })
            .collect()
    };
    let names: Vec<String> = sim.episode().planner_debug().critics.clone();
    assert_eq!(names.len(), 3);
    // Before the first step: the names, no weights yet.
    let before = critics(&sim);
    assert!(before.iter().map(|c| &c.0).eq(names.iter()));
    assert!(
        before.iter().all(|c| c.1.is_some()),
        "the built-in weights before the first step"
    );
    sim.step(3);
    let weights: Vec<Option<f64>> = critics(&sim).into_iter().map(|c| c.1).collect();
    assert_eq!(weights, vec![Some(0.05), Some(0.3), Some(0.1)]);
    // The fan's values: the total score by default, then critic 1's
    // normalised values, which a replay of the run keeps.
    let fan = bits(&[Layer::Fan]);
    let values = |h: &SimHandle| -> Vec<u64> {
        let d = h.draw_list(fan, 0);
        d.layer(Layer::Fan).map(|i| i.value.to_bits()).collect()
    };
    let of = |h: &SimHandle, f: &dyn Fn(&planlab_core::local::Rollout) -> f64| -> Vec<u64> {
        let rs = &h.episode().planner_debug().rollouts;
        rs.iter().map(|r| f(r).to_bits()).collect()
    };
    assert!(values(&sim).len() > 10);
    assert_eq!(values(&sim), of(&sim, &|r| r.score));
    sim.set_fan_colour(Some(1)).unwrap();
    assert_eq!(values(&sim), of(&sim, &|r| r.normalised[1]));
    assert_ne!(values(&sim), of(&sim, &|r| r.score));
    let scratch = sim.replay_to(2.0).unwrap();
    assert_eq!(values(&scratch), of(&scratch, &|r| r.normalised[1]));
    // A critic the planner does not have is refused, the choice kept.
    let e = message(sim.set_fan_colour(Some(3)).unwrap_err());
    assert!(
        e.contains("no critic 3") && e.contains(&names.join(", ")),
        "{e}"
    );
    assert_eq!(values(&sim), of(&sim, &|r| r.normalised[1]));
    // A restart (Reset, an editing tool) keeps the choice.
    sim.restart().unwrap();
    sim.step(2);
    assert_eq!(values(&sim), of(&sim, &|r| r.normalised[1]));
    sim.set_fan_colour(None).unwrap();
    assert_eq!(values(&sim), of(&sim, &|r| r.score));
}

#[wasm_bindgen_test]
fn wheel_loads_come_with_a_vehicle_model() {
    use planlab_wasm::SimHandle;
    let mut sim =
        SimHandle::from_scenario(&room_json("dwa", r#", "terrain": {"vehicle": {}}"#), None)
            .unwrap();
    assert!(sim.has_vehicle());
    sim.step(10);
    let l = sim.wheel_loads(1);
    assert_eq!(l.len(), 50);
    // Roughly a quarter of 40 kg·g per wheel.
    assert!(
        l.chunks(5)
            .all(|r| r[1..].iter().all(|f| *f > 20.0 && *f < 200.0)),
        "{l:?}"
    );
}

#[wasm_bindgen_test]
fn apf_handle_runs_the_3d_table_4_1_scene_in_side_view() {
    use planlab_wasm::ApfHandle;
    let json = include_str!("../../../assets/scenarios/T-tab4-1.json");
    let mut h = ApfHandle::new(json).unwrap();
    assert_eq!(h.dims(), 3);
    let mut lengths = vec![];
    for mode in ["basic", "sampling", "sampling-prediction"] {
        h.set_mode(mode).unwrap();
        assert_eq!(h.step(400).unwrap(), "reached", "{mode}");
        let m: serde_json::Value = serde_json::from_str(&h.metrics()).unwrap();
        lengths.push(m["path_length_m"].as_f64().unwrap());
        // Side view (x, z): pairs from the start's height, obstacles as quadruples.
        assert_eq!(h.path()[..2], [0.0, 0.8]);
        assert_eq!(h.obstacles().len(), 4);
    }
    // [T] Table 4-1: basic > sampling > sampling + prediction.
    assert!(
        lengths[0] > lengths[1] && lengths[1] > lengths[2],
        "{lengths:?}"
    );
    assert_eq!(h.field(8, 6).len(), 2 * 8 * 6);
    // The goal moves in the side view and the run restarts.
    h.set_goal(0.6, 0.9).unwrap();
    assert_eq!(h.endpoints()[2..], [0.6, 0.9]);
    assert_eq!(h.outcome(), "running");
}

#[wasm_bindgen_test]
fn map_edits_generate_and_undo_snapshots() {
    use planlab_wasm::{generated_grid_hash, SimHandle};
    let mut sim = SimHandle::from_scenario(&room_json("pursuit", ""), None).unwrap();
    sim.step(3);
    let before = sim.grid_hash();
    let (state, cells) = (sim.edit_state().unwrap(), sim.map().cells());
    // A disc in the middle: cells change, the episode restarts at t = 0.
    let n = sim
        .edit_map(r#"{"op":"disc","centre":[2.0,1.0],"radius":0.3,"cell":"occupied"}"#)
        .unwrap();
    assert_eq!(n, 4, "the four cells around the centre");
    assert_eq!(sim.steps(), 0.0);
    assert_ne!(sim.grid_hash(), before);
    // A wall over the start is refused with the core's message; nothing changes.
    let edited = sim.grid_hash();
    let e = message(
        sim.edit_map(r#"{"op":"rect","a":[0.2,0.6],"b":[0.8,1.4],"cell":"occupied"}"#)
            .unwrap_err(),
    );
    assert!(
        e.contains("starts in collision") && e.contains("wall"),
        "{e}"
    );
    assert_eq!(sim.grid_hash(), edited);
    // Undo: the snapshot restores the map exactly.
    sim.restore_edit(&state, &cells).unwrap();
    assert_eq!(sim.grid_hash(), before);
    // Start with a heading.
    sim.set_start(1.0, 1.0, 0.5).unwrap();
    assert_eq!(sim.start(), vec![1.0, 1.0, 0.5]);
    // Generated maps: same settings, same hash (the CLI's too, see e2e).
    let settings = r#"{"kind":"maze","seed":7,"width_m":8,"height_m":6}"#;
    let h = sim.generate_map(settings).unwrap();
    assert_eq!(h, sim.grid_hash());
    assert_eq!(h, generated_grid_hash(settings).unwrap());
    assert_ne!(
        h,
        generated_grid_hash(r#"{"kind":"maze","seed":8,"width_m":8,"height_m":6}"#).unwrap()
    );
    let e = message(
        sim.generate_map(r#"{"kind":"random","density":2}"#)
            .unwrap_err(),
    );
    assert!(e.contains("density"), "{e}");
    assert_eq!(sim.grid_hash(), h);
}

/// A variant link's scenario is the core's tree of that run on that
/// variant (so the page replays what `planlab reproduce` ran), and bad
/// input arrives as an error with the core's message.
#[wasm_bindgen_test]
fn reproduce_variant_is_the_core_tree() {
    use planlab_core::reproduce;
    let text = planlab_wasm::reproduce_variant("T-fig3-2", "improved", 3, 0).unwrap();
    let got: serde_json::Value = serde_json::from_str(&text).unwrap();
    // It is a scenario the page can load.
    planlab_core::scenario::Scenario::from_json(&text).expect("a scenario");
    let scene = reproduce::find("T-fig3-2")
        .unwrap()
        .variant(0, 3, &[])
        .unwrap();
    let want = &scene
        .trees
        .iter()
        .find(|(n, _)| *n == "improved")
        .unwrap()
        .1;
    assert_eq!(&got, want);
    // Another variant is another scene.
    let other = planlab_wasm::reproduce_variant("T-fig3-2", "improved", 4, 0).unwrap();
    assert_ne!(text, other);
    // A path experiment (APF page) too.
    assert!(planlab_wasm::reproduce_variant("T-fig4-6", "sampling", 2, 0).is_ok());
}

#[wasm_bindgen_test]
fn reproduce_variant_bad_input_is_an_error() {
    use planlab_core::reproduce::MAX_VARIANTS;
    let err = |r: Result<String, wasm_bindgen::JsError>| message(r.unwrap_err());
    assert!(
        err(planlab_wasm::reproduce_variant("T-nope", "improved", 3, 0))
            .contains("unknown experiment `T-nope`")
    );
    assert!(
        err(planlab_wasm::reproduce_variant("T-fig3-2", "nope", 3, 0)).contains("no run `nope`")
    );
    assert!(err(planlab_wasm::reproduce_variant(
        "T-fig3-2",
        "improved",
        MAX_VARIANTS,
        0
    ))
    .contains("variant"));
    assert!(planlab_wasm::reproduce_variant("T-fig3-2", "improved", MAX_VARIANTS - 1, 0).is_ok());
}

/// A wall painted and a cell set through a session give the same plan as a
/// fresh `plan` on a map edited the same way, without rebuilding the grid.
#[wasm_bindgen_test]
fn session_edits_plan_as_a_fresh_plan_on_the_edited_map() {
    use planlab_wasm::PlanSession;
    let arena = include_str!("../../../assets/maps/arena.map");
    let mut map = MapHandle::from_movingai(arena).unwrap();
    for algo in ["astar", "dijkstra", "jps"] {
        let opts = || options(&format!(r#"{{"algorithm":"{algo}"}}"#));
        let mut session = PlanSession::new(&map, opts()).unwrap();
        let before = session.plan(1, 11, 42, 46, false).unwrap();
        let fresh = plan(&map, 1, 11, 42, 46, opts(), false).unwrap();
        assert_eq!(before.path(), fresh.path(), "{algo}: before any edit");
        // A wall across the middle of the path, and one cell freed again.
        let mid = before.path();
        let (c, r) = (mid[(mid.len() / 2) & !1], mid[((mid.len() / 2) & !1) + 1]);
        let mut edited = map.duplicate();
        let top = r.saturating_sub(8).max(1);
        edited.paint_segment(c, top, c, r + 8, 1).unwrap();
        edited.set_cell(c, top, 0).unwrap();
        session.paint_segment(c, top, c, r + 8, 1).unwrap();
        session.set_cell(c, top, 0).unwrap();
        let after = session.plan(1, 11, 42, 46, true).unwrap();
        let fresh = plan(&edited, 1, 11, 42, 46, opts(), true).unwrap();
        assert_eq!(after.path(), fresh.path(), "{algo}: after the edit");
        assert_eq!(after.cost(), fresh.cost());
        assert_eq!(after.expanded_count(), fresh.expanded_count());
        assert_eq!(after.expanded(), fresh.expanded());
        assert!(
            after.cost() > before.cost(),
            "{algo}: the wall lengthens the path"
        );
        assert_eq!(session.rebuilds(), 1, "{algo}: edits update the kept grid");
    }
    // Inflation: an edit rebuilds (cells up to the radius away change) and
    // still agrees with a fresh plan.
    let inflated = || options(r#"{"algorithm":"astar","inflate_m":1.0}"#);
    let mut session = PlanSession::new(&map, inflated()).unwrap();
    session.plan(5, 15, 40, 40, false).unwrap();
    session.paint_segment(20, 20, 28, 20, 1).unwrap();
    map.paint_segment(20, 20, 28, 20, 1).unwrap();
    let a = session.plan(5, 15, 40, 40, false).unwrap();
    let b = plan(&map, 5, 15, 40, 40, inflated(), false).unwrap();
    assert_eq!(a.path(), b.path());
    assert_eq!(session.rebuilds(), 2);
}

/// The recorded plan's events are columns of equal length whose close
/// events are the expanded cells in order.
#[wasm_bindgen_test]
fn recorded_plan_events_are_typed_columns() {
    use planlab_wasm::PlanSession;
    let map = MapHandle::from_ascii(MAP).unwrap();
    let mut session = PlanSession::new(&map, options(r#"{"algorithm":"astar"}"#)).unwrap();
    let rec = session.plan_recorded(0, 0, 0, 4).unwrap();
    let n = rec.length() as usize;
    let kinds = rec.kinds();
    assert_eq!(kinds.len(), n);
    assert_eq!(rec.cells().len(), 2 * n);
    assert_eq!(rec.others().len(), 2 * n);
    assert_eq!((rec.g().len(), rec.h().len()), (n, n));
    let plan = rec.plan();
    let closes: Vec<u32> = kinds
        .iter()
        .zip(rec.cells().chunks(2))
        .filter(|(k, _)| **k == 1)
        .flat_map(|(_, c)| c.to_vec())
        .collect();
    let fresh = plan_fn(&map);
    assert_eq!(closes, fresh.expanded());
    // Every expanded cell was opened first, with its g and h.
    let (g, h, cells) = (rec.g(), rec.h(), rec.cells());
    for close in closes.chunks(2) {
        let opened = (0..n).find(|&i| kinds[i] == 0 && cells[2 * i..2 * i + 2] == *close);
        let i = opened.expect("a closed cell was opened before");
        assert!(g[i].is_finite() && h[i].is_finite() && g[i] >= 0.0);
    }
    assert_eq!(
        (cells[0], cells[1], kinds[0]),
        (0, 0, 0),
        "the start is opened first"
    );
    assert_eq!(plan.expanded_count() as usize, closes.len() / 2);
    assert!(!rec.truncated());
}

/// The replay of a recorded plan counts what the columns hold, and a cell
/// it expanded reads closed at the end and unseen at step 0.
#[wasm_bindgen_test]
fn a_recorded_plan_replays_to_its_expanded_count() {
    use planlab_wasm::PlanSession;
    let map = MapHandle::from_ascii(MAP).unwrap();
    let mut session = PlanSession::new(&map, options(r#"{"algorithm":"astar"}"#)).unwrap();
    let rec = session.plan_recorded(0, 0, 0, 4).unwrap();
    let mut replay = rec.replay(&map, 1.0);
    assert_eq!(replay.length(), rec.length());
    replay.seek(f64::from(rec.length()));
    assert!(replay.done());
    let end = replay.counters_at(replay.step());
    assert_eq!(
        end[2],
        f64::from(rec.plan().expanded_count()),
        "expanded at the end"
    );
    assert_eq!(replay.info(0, 0).unwrap()[0], 2.0, "the start is closed");
    replay.seek(0.0);
    assert_eq!(replay.info(0, 0).unwrap()[0], 0.0, "unseen at step 0");
    assert!(replay.info(99, 0).is_none(), "off the map");
}

fn plan_fn(map: &MapHandle) -> planlab_wasm::PlanResult {
    plan(map, 0, 0, 0, 4, options(r#"{"algorithm":"astar"}"#), true).unwrap()
}

/// D* Lite through its session: a painted wall is repaired to the cost of
/// a fresh plan on the edited map with fewer expansions than a fresh A*;
/// a moved start replans from there; each call's events are its own.
#[wasm_bindgen_test]
fn dstar_session_repairs_edits_and_moved_starts() {
    use planlab_wasm::{DStarSession, PlanSession};
    // arena2's longest query: a fresh A* expands thousands of cells. (On the
    // open 49 × 49 arena a fresh A* needs ~130 and no repair beats it.)
    let text = include_str!("../../../tests/data/movingai/dao/arena2.map");
    let mut map = MapHandle::from_movingai(text).unwrap();
    let (s, g) = ((5, 112), (275, 181));
    let opts = || options(r#"{"algorithm":"dstar-lite"}"#);
    let astar = || options(r#"{"algorithm":"astar"}"#);
    let mut dstar = DStarSession::new(&map, opts(), s.0, s.1, g.0, g.1).unwrap();
    let first = dstar.plan().unwrap();
    let fresh = plan(&map, s.0, s.1, g.0, g.1, astar(), false).unwrap();
    assert!((first.plan().cost() - fresh.cost()).abs() < 1e-9);
    assert!(first.length() > 0);
    // A 3-cell wall across the path where the map is open round it, a tenth
    // of the way from the start.
    let path = first.plan().path();
    let (w, cells) = (map.width() as i64, map.cells());
    let free =
        |c: i64, r: i64| c >= 0 && r >= 0 && c < w && cells.get((r * w + c) as usize) == Some(&0);
    let at = |k: usize| (path[2 * k] as i64, path[2 * k + 1] as i64);
    let k = (path.len() / 20..path.len() / 2 - 1)
        .find(|&k| {
            let (c, r) = at(k);
            (-3..=3).all(|dr| (-3..=3).all(|dc| free(c + dc, r + dr)))
        })
        .unwrap();
    let ((c, r), (nc, nr)) = (at(k), at(k + 1));
    let (pc, pr) = if nr == r {
        (0, 1)
    } else if nc == c {
        (1, 0)
    } else {
        (nc - c, r - nr)
    };
    let ends = [
        (c - pc) as u32,
        (r - pr) as u32,
        (c + pc) as u32,
        (r + pr) as u32,
    ];
    dstar
        .paint_segment(ends[0], ends[1], ends[2], ends[3], 1)
        .unwrap();
    map.paint_segment(ends[0], ends[1], ends[2], ends[3], 1)
        .unwrap();
    let repaired = dstar.plan().unwrap();
    let fresh = plan(&map, s.0, s.1, g.0, g.1, astar(), false).unwrap();
    assert!(
        (repaired.plan().cost() - fresh.cost()).abs() < 1e-9,
        "repaired to the optimum"
    );
    assert!(repaired.plan().cost() > first.plan().cost());
    let closes = repaired.kinds().iter().filter(|&&k| k == 1).count() as u32;
    assert_eq!(
        closes,
        repaired.plan().expanded_count(),
        "the events are this call's"
    );
    assert!(
        repaired.plan().expanded_count() < fresh.expanded_count(),
        "repair {} vs fresh A* {}",
        repaired.plan().expanded_count(),
        fresh.expanded_count()
    );
    // The robot moved along the path: plan from there.
    let (sc, sr) = (path[2], path[3]);
    dstar.move_start(sc, sr).unwrap();
    let moved = dstar.plan().unwrap();
    let fresh = plan(&map, sc, sr, g.0, g.1, astar(), false).unwrap();
    assert!((moved.plan().cost() - fresh.cost()).abs() < 1e-9);
    assert_eq!(&moved.plan().path()[..2], &[sc, sr]);
    // Errors are typed, not panics.
    assert!(dstar.set_cell(10_000, 10_000, 1).is_err());
    assert!(DStarSession::new(&map, opts(), 0, 0, g.0, g.1).is_err());
    // The plain session plans D* Lite too, to the same cost.
    let mut session = PlanSession::new(&map, opts()).unwrap();
    let once = session.plan(s.0, s.1, g.0, g.1, false).unwrap();
    assert!((once.cost() - repaired.plan().cost()).abs() < 1e-9);
}
