//! The scenario JSON's simulation sections: round trip, old files, field
//! errors, and episodes built from a scenario.

use planlab_core::metrics::EpisodeMetrics;
use planlab_core::scenario::{Scenario, ScenarioError};
use planlab_core::sim::{Episode, Outcome, SimError};
use planlab_core::world::{Drive, Footprint, MotionModel};

const FULL: &str = r##"{
  "version": 1,
  "name": "sim sections",
  "map": { "width": 20, "height": 10, "resolution": 0.5, "rle": [
    "20#",
    "#18.#",
    "#18.#",
    "#18.#",
    "#18.#",
    "#18.#",
    "#18.#",
    "#18.#",
    "#18.#",
    "20#"
  ] },
  "start": { "col": 2, "row": 5, "world": { "x": 1.25, "y": 2.3 } },
  "goal": { "col": 17, "row": 5 },
  "robot": {
    "drive": "omnidirectional",
    "footprint": { "shape": "rectangle", "length": 0.6, "width": 0.4 },
    "limits": { "v_max": 0.8, "vy_max": 0.3, "acc_vy": 0.5 },
    "wheel_base": 0.35
  },
  "start_yaw": 0.1,
  "movers": [
    { "id": 1, "radius": 0.3, "motion": { "model": "back-and-forth", "a": [5.0, 1.0], "b": [5.0, 4.0], "speed": 0.4 } },
    { "id": 2, "radius": 0.25, "motion": { "model": "waypoint-loop", "points": [[7.0, 1.0], [8.0, 1.0], [8.0, 2.0]], "speed": 0.2 } },
    { "id": 3, "radius": 0.2, "motion": { "model": "scripted", "samples": [{ "t": 0.0, "x": 3.0, "y": 4.0 }, { "t": 5.0, "x": 4.0, "y": 4.0 }] } },
    { "id": 4, "radius": 0.2, "motion": { "model": "constant-velocity", "start": [6.0, 4.0], "velocity": [0.1, 0.0] } }
  ],
  "local_planner": { "name": "pursuit", "config": { "k_w": 2.0 } },
  "sim": { "dt": 0.05, "max_time": 60.0, "goal_tolerance": 0.3, "record_rollouts": true },
  "terrain": {},
  "seed": 18446744073709551615
}"##;

#[test]
fn all_sections_round_trip() {
    let s = Scenario::from_json(FULL).unwrap();
    let r = s.robot.unwrap();
    assert_eq!(r.drive, Drive::Omnidirectional);
    assert_eq!(
        r.footprint,
        Footprint::Rectangle {
            length: 0.6,
            width: 0.4
        }
    );
    assert_eq!(r.limits.v_max, 0.8);
    // Left-out limits keep their defaults.
    assert_eq!(r.limits.acc_v, 0.2);
    assert_eq!(s.start_yaw, Some(0.1));
    let movers = s.movers.as_ref().unwrap();
    assert_eq!(movers.len(), 4);
    assert!(matches!(movers[1].motion, MotionModel::WaypointLoop { .. }));
    assert_eq!(s.local_planner.as_ref().unwrap().name, "pursuit");
    let sim = s.sim.unwrap();
    assert_eq!((sim.dt, sim.max_time, sim.stuck_time), (0.05, 60.0, 15.0));
    assert_eq!(s.seed, Some(u64::MAX));
    let text = s.to_json_pretty().unwrap();
    let back = Scenario::from_json(&text).unwrap();
    assert_eq!(back, s);
    assert_eq!(back.to_json_pretty().unwrap(), text);
}

#[test]
fn old_files_load_and_write_without_new_sections() {
    let old = r#"{"version": 1, "map": {"width": 3, "height": 2, "cells": ["...", "..."]},
        "start": {"col": 0, "row": 0}, "goal": {"col": 2, "row": 1}}"#;
    let s = Scenario::from_json(old).unwrap();
    assert!(s.robot.is_none() && s.movers.is_none() && s.local_planner.is_none());
    let text = s.to_json_pretty().unwrap();
    for key in [
        "robot",
        "movers",
        "local_planner",
        "\"sim\"",
        "terrain",
        "seed",
        "start_yaw",
    ] {
        assert!(!text.contains(key), "{key} written: {text}");
    }
    let demo = include_str!("../../../assets/scenarios/grid-demo.json");
    let s = Scenario::from_json(demo).unwrap();
    assert_eq!(s.to_json_pretty().unwrap(), demo);
}

fn err(text: &str) -> String {
    Scenario::from_json(text).unwrap_err().to_string()
}

#[test]
fn bad_values_name_their_field() {
    let cases = [
        (r#""v_max": 0.8"#, r#""v_max": -0.8"#, "robot.limits.v_max"),
        (r#""v_max": 0.8"#, r#""v_max": "NaN""#, "robot.limits.v_max"),
        (r#""v_max": 0.8"#, r#""v_mx": 0.8"#, "robot.limits.v_mx"),
        (
            r#""length": 0.6"#,
            r#""length": 0"#,
            "robot.footprint.length",
        ),
        (r#""radius": 0.25"#, r#""radius": -0.25"#, "mover 2 radius"),
        (r#""radius": 0.25"#, r#""radius": -0.25"#, "movers[1]"),
        (
            r#""speed": 0.4"#,
            r#""speed": "fast""#,
            "movers[0].motion`: invalid type: string \"fast\"",
        ),
        (
            r#""model": "scripted""#,
            r#""model": "teleport""#,
            "teleport",
        ),
        (r#""dt": 0.05"#, r#""dt": -0.05"#, "sim.dt"),
        (r#""dt": 0.05"#, r#""dtt": 0.05"#, "sim.dtt"),
        (
            r#""start_yaw": 0.1"#,
            r#""start_yaw": "north""#,
            "start_yaw",
        ),
        (
            r#""name": "pursuit""#,
            r#""name": "warp""#,
            "local_planner.name",
        ),
        (
            r#""config": { "k_w": 2.0 }"#,
            r#""config": [2.0]"#,
            "local_planner.config",
        ),
        (
            r#""terrain": {}"#,
            r#""terrain": {"mud": 1}"#,
            "terrain.mud",
        ),
        (r#""seed": 18446744073709551615"#, r#""seed": -1"#, "seed"),
    ];
    for (from, to, want) in cases {
        assert!(FULL.contains(from), "{from}");
        let e = err(&FULL.replacen(from, to, 1));
        assert!(e.contains(want), "{to}\n  gave: {e}\n  want: {want}");
        assert!(!e.contains('\n'), "{e}");
    }
}

#[test]
fn a_scenario_becomes_an_episode() {
    let s = Scenario::from_json(FULL).unwrap();
    let grid = s.inline_grid().unwrap().unwrap();
    let ep = Episode::from_scenario(&s, grid.clone()).unwrap();
    assert_eq!(
        (ep.state().x, ep.state().y, ep.state().theta),
        (1.25, 2.3, 0.1)
    );
    // Goal: the centre of cell (17, 5) at 0.5 m per cell: x = 8.75, y = 2.25.
    assert_eq!(ep.goal(), [8.75, 2.25]);
    assert_eq!(ep.config().dt, 0.05);
    assert_eq!(ep.movers_now().len(), 4);

    // Without movers pursuit drives straight over.
    let mut quiet = s.clone();
    quiet.movers = None;
    let mut ep = Episode::from_scenario(&quiet, grid.clone()).unwrap();
    assert_eq!(ep.run(), Outcome::Reached);
    let m = EpisodeMetrics::from_trace(ep.trace(), &[], ep.outcome(), 40.0);
    assert!(m.path_length_m > 7.0 && m.path_length_m < 8.0, "{m:?}");

    // Start on a mover.
    let mut bad = s.clone();
    bad.start_yaw = None;
    if let Some(ms) = bad.movers.as_mut() {
        ms[0].motion = MotionModel::ConstantVelocity {
            start: [1.25, 2.3],
            velocity: [0.0, 0.0],
            since: 0.0,
        };
    }
    let e = Episode::from_scenario(&bad, grid.clone()).unwrap_err();
    assert!(e.to_string().contains("mover 1"), "{e}");

    // A goal cell that is a wall.
    let mut bad = s.clone();
    bad.goal.col = 19;
    let e = Episode::from_scenario(&bad, grid).unwrap_err();
    assert!(matches!(e, SimError::BadGoal { .. }), "{e}");
    let _ = ScenarioError::Invalid(String::new());
}

#[test]
fn set_json_path_edits_the_tree() {
    use planlab_core::scenario::{set_json_path, set_planner_name};
    let mut v: serde_json::Value = serde_json::from_str(FULL).unwrap();
    set_json_path(&mut v, "sim.dt", "0.2").unwrap();
    set_json_path(&mut v, "movers.1.radius", "0.5").unwrap();
    set_json_path(
        &mut v,
        "robot.footprint",
        r#"{"shape": "circle", "radius": 0.3}"#,
    )
    .unwrap();
    set_json_path(&mut v, "name", "plain text").unwrap();
    set_json_path(&mut v, "terrain.new_section.x", "1").unwrap();
    assert_eq!(v["sim"]["dt"], 0.2);
    assert_eq!(v["movers"][1]["radius"], 0.5);
    assert_eq!(v["robot"]["footprint"]["radius"], 0.3);
    assert_eq!(v["name"], "plain text");
    assert_eq!(v["terrain"]["new_section"]["x"], 1);
    for (path, want) in [
        ("movers.9.radius", "no index 9"),
        ("movers.x.radius", "must be an index"),
        ("seed.x", "`seed` is a number"),
        ("sim..dt", "single dots"),
        ("", "single dots"),
    ] {
        let e = set_json_path(&mut v, path, "1").unwrap_err().to_string();
        assert!(e.contains(want) && e.contains("--set"), "{path}: {e}");
    }
    // The unknown section is then refused by the parser, naming it.
    let e = Scenario::from_value(&v).unwrap_err().to_string();
    assert!(e.contains("terrain.new_section"), "{e}");

    let mut v: serde_json::Value = serde_json::from_str(FULL).unwrap();
    set_planner_name(&mut v, "pursuit").unwrap();
    assert_eq!(v["local_planner"]["config"]["k_w"], 2.0);
    set_planner_name(&mut v, "dwa").unwrap();
    assert_eq!(
        v["local_planner"],
        serde_json::json!({"name": "dwa", "config": {}})
    );
}
