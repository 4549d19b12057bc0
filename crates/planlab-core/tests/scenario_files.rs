//! What the robot page's Files menu relies on: an episode (after goal,
//! mover and planner edits) saved as a self-contained scenario rebuilds the
//! identical trace; bare ROS and Moving AI maps get usable default start and
//! goal; inline maps of real size round-trip; bad files give typed errors;
//! the metrics CSV holds the `planlab run` metrics.

use planlab_core::map::io::{movingai, ros};
use planlab_core::map::{MapError, OccupancyGrid};
use planlab_core::metrics::{EpisodeMetrics, DEFAULT_LOAD_THRESHOLD_N};
use planlab_core::scenario::{
    default_endpoints, set_json_path, MapSpec, Scenario, ScenarioError, ENDPOINT_MARGIN_M,
};
use planlab_core::sim::{Episode, Outcome};
use planlab_core::world::{MoverSpec, Placement, RobotSpec, StaticMap};

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/data");
const ASSETS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/scenarios");

fn read(path: &str) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("cannot read {path}: {e}"))
}

fn preset(name: &str) -> (Scenario, OccupancyGrid) {
    let text = String::from_utf8(read(&format!("{ASSETS}/{name}"))).unwrap();
    let s = Scenario::from_json(&text).unwrap();
    let g = s
        .load_grid(&mut |p| std::fs::read(format!("{ASSETS}/{p}")).map_err(|e| e.to_string()))
        .unwrap();
    (s, g)
}

/// Saves `ep` as JSON, reads it back and rebuilds the episode.
fn through_json(ep: &Episode) -> (String, Episode) {
    let json = ep
        .to_scenario("saved", "round trip")
        .unwrap()
        .to_json_pretty()
        .unwrap();
    let s = Scenario::from_json(&json).unwrap();
    let g = s.load_grid(&mut |p| Err(format!("no file {p}"))).unwrap();
    (json, Episode::from_scenario(&s, g).unwrap())
}

#[test]
fn edited_episode_saved_and_reloaded_gives_the_identical_trace() {
    let (s, g) = preset("dwa-demo.json");
    let mut edited = Episode::from_scenario(&s, g).unwrap();
    let old_goal = edited.goal();
    // The page's edits before playing: goal moved, a mover added, a
    // planner parameter changed.
    edited.set_goal([9.0, 6.5]).unwrap();
    let mut movers = edited.movers().to_vec();
    let added = MoverSpec::placed(
        99,
        0.3,
        Placement::ConstantVelocity,
        [6.0, 4.0],
        [-0.2, 0.1],
        3.0,
        0.0,
    )
    .unwrap();
    movers.push(added.clone());
    edited.set_movers(movers).unwrap();
    let (json, mut rebuilt) = through_json(&edited);
    // The file is self-contained: the map inline, the edits in.
    let saved = Scenario::from_json(&json).unwrap();
    assert!(matches!(saved.map, MapSpec::Inline(_)));
    assert_eq!(saved.goal.world.map(|w| [w.x, w.y]), Some([9.0, 6.5]));
    assert_ne!(rebuilt.goal(), old_goal);
    assert!(saved.movers.as_ref().unwrap().contains(&added));
    // Saving the rebuilt episode gives the same file (nothing lost).
    assert_eq!(through_json(&rebuilt).0, json);

    let a = edited.run();
    let b = rebuilt.run();
    assert_eq!(a, b);
    assert!(edited.steps() > 10, "the episode ran");
    assert_eq!(edited.trace().hash(), rebuilt.trace().hash());
    assert_eq!(edited.trace().to_csv(), rebuilt.trace().to_csv());
}

#[test]
fn saved_planner_config_and_seed_survive() {
    let (s, g) = preset("pursuit-demo.json");
    let mut ep = Episode::from_scenario(&s, g).unwrap();
    let choice = ep.planner_choice().clone();
    let (json, mut back) = through_json(&ep);
    assert_eq!(back.planner_choice(), &choice);
    let saved = Scenario::from_json(&json).unwrap();
    assert_eq!(saved.seed, Some(s.seed.unwrap_or(0)));
    assert_eq!(saved.sim.map(|c| c.record_rollouts), Some(false));
    ep.run();
    back.run();
    assert_eq!(ep.trace().hash(), back.trace().hash());
}

fn turtlebot3() -> OccupancyGrid {
    let dir = format!("{DATA}/rosmaps/turtlebot3");
    let meta =
        ros::parse_yaml(&String::from_utf8(read(&format!("{dir}/map.yaml"))).unwrap()).unwrap();
    ros::grid_from_pgm(
        &meta,
        &ros::parse_pgm(&read(&format!("{dir}/{}", meta.image))).unwrap(),
    )
    .unwrap()
}

/// Checks that start and goal of a bare-map scenario have room for the
/// robot and are joined: the episode builds (it refuses walled-off goals).
fn check_endpoints(s: &Scenario, grid: &OccupancyGrid, min_apart_m: f64) -> Episode {
    let a = s.start_world(grid);
    let b = s.goal_world(grid);
    let apart = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
    assert!(
        apart >= min_apart_m,
        "start {a:?} and goal {b:?} only {apart:.2} m apart"
    );
    let map = StaticMap::new(grid.clone(), true).unwrap();
    let need = RobotSpec::default().footprint.circumscribed_radius() + ENDPOINT_MARGIN_M;
    for p in [a, b] {
        assert!(
            map.clearance(p[0], p[1]) >= need - 0.35 * grid.resolution(),
            "{p:?}"
        );
    }
    Episode::from_scenario(s, grid.clone()).unwrap()
}

#[test]
fn ros_map_gets_default_endpoints_and_dwa_reaches_the_goal() {
    let grid = turtlebot3();
    let s = Scenario::for_map("turtlebot3", grid.clone()).unwrap();
    // The free part of the TurtleBot3 world is about 4 m across.
    let mut ep = check_endpoints(&s, &grid, 2.5);
    assert_eq!(ep.planner_choice().name, "dwa");
    assert_eq!(ep.run(), Outcome::Reached, "DWA on the TurtleBot3 world");
    // 384×384 is written run-length encoded and reads back equal.
    let json = s.to_json_pretty().unwrap();
    assert!(json.contains("\"rle\""));
    assert_eq!(Scenario::from_json(&json).unwrap(), s);
}

#[test]
fn moving_ai_map_gets_default_endpoints() {
    let text = String::from_utf8(read(&format!("{DATA}/movingai/dao/arena.map"))).unwrap();
    let grid = movingai::parse_map(&text).unwrap();
    let s = Scenario::for_map("arena", grid.clone()).unwrap();
    // The arena is 49 m across at 1 m per cell.
    check_endpoints(&s, &grid, 20.0);
    // Deterministic.
    assert_eq!(Scenario::for_map("arena", grid).unwrap(), s);
}

#[test]
fn endpoints_are_the_ends_of_a_corridor_and_pick_the_largest_area() {
    // A small room on the left, a long corridor area on the right.
    let g = OccupancyGrid::from_ascii(
        "#################\n\
         #...#...........#\n\
         #...#...........#\n\
         #...#...........#\n\
         #################\n",
    )
    .unwrap();
    let map = StaticMap::new(g.clone(), true).unwrap();
    let (a, b) = default_endpoints(&map, &RobotSpec::default()).unwrap();
    let (ca, cb) = (
        g.world_to_cell(a[0], a[1]).unwrap(),
        g.world_to_cell(b[0], b[1]).unwrap(),
    );
    let mut cols = [ca.0, cb.0];
    cols.sort();
    // 1 m cells, the robot needs 0.35 m: every free cell has room; the
    // right area (33 cells, not the left 9) and its opposite corners.
    assert_eq!(cols, [5, 15], "{ca:?} {cb:?}");
    let mut rows = [ca.1, cb.1];
    rows.sort();
    assert_eq!(rows, [1, 3], "{ca:?} {cb:?}");
}

#[test]
fn no_room_is_a_typed_error() {
    let g = OccupancyGrid::from_ascii("###\n#.#\n###\n")
        .unwrap()
        .with_frame(0.1, Default::default())
        .unwrap();
    match Scenario::for_map("tiny", g) {
        Err(ScenarioError::Invalid(m)) => assert!(m.contains("room for the robot"), "{m}"),
        other => panic!("expected Invalid, got {other:?}"),
    }
}

#[test]
fn malformed_files_give_typed_errors() {
    // Not JSON: the position is reported.
    match Scenario::from_json("{\"version\": 1,\n  \"map\": ") {
        Err(ScenarioError::Json { line, .. }) => assert_eq!(line, 2),
        other => panic!("{other:?}"),
    }
    // A bad inline map row names the row.
    let bad_rle = r#"{"version": 1, "map": {"width": 3, "height": 1, "rle": ["2.x"]},
        "start": {"col": 0, "row": 0}, "goal": {"col": 1, "row": 0}}"#;
    let e = Scenario::from_json(bad_rle).unwrap_err();
    assert!(matches!(e, ScenarioError::Json { .. }));
    assert!(e.to_string().contains("map.rle row 1"), "{e}");
    let short = r#"{"version": 1, "map": {"width": 3, "height": 2, "cells": ["..."]},
        "start": {"col": 0, "row": 0}, "goal": {"col": 1, "row": 0}}"#;
    assert!(Scenario::from_json(short)
        .unwrap_err()
        .to_string()
        .contains("expected height 2"));
    // A newer file.
    assert!(matches!(
        Scenario::from_json(r#"{"version": 2}"#),
        Err(ScenarioError::UnsupportedVersion { found: 2, .. })
    ));
    // Garbage map files.
    assert!(matches!(
        movingai::parse_map("type octile\nheight x\n"),
        Err(MapError::Parse { .. })
    ));
    assert!(ros::parse_yaml("image: [unclosed").is_err());
    assert!(ros::parse_pgm(b"P5\n3 3\n255\n\x00").is_err());
}

#[test]
fn metrics_csv_holds_the_run_metrics() {
    let (s, g) = preset("dwa-demo.json");
    let mut ep = Episode::from_scenario(&s, g).unwrap();
    for _ in 0..50 {
        ep.step();
    }
    let m = EpisodeMetrics::from_trace(
        ep.trace(),
        &ep.planner_debug().global_path,
        ep.outcome(),
        DEFAULT_LOAD_THRESHOLD_N,
    );
    let csv = m.to_csv();
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(rows[0], ["name", "value", "unit"]);
    // Header + 15 metrics, among them [L] Table 2's per-step turning and
    // [C] Table 5's per-wheel load share.
    assert_eq!(rows.len(), 16);
    assert!(rows.iter().all(|r| r.len() == 3));
    let get = |k: &str| rows.iter().find(|r| r[0] == k).map(|r| r[1]).unwrap();
    assert_eq!(get("outcome"), "running");
    assert_eq!(get("time_s").parse::<f64>().unwrap(), m.time_s);
    assert_eq!(
        get("path_length_m").parse::<f64>().unwrap(),
        m.path_length_m
    );
    assert!(m.path_length_m > 0.5);
    assert_eq!(get("load_ok_share"), "");
    assert_eq!(get("wheel_load_share"), "");
    assert_eq!(
        get("max_turn_step_rad").parse::<f64>().unwrap(),
        m.max_turn_step_rad
    );
}

#[test]
fn a_tree_reads_as_its_text_does() {
    // `from_value` reads an edited tree directly, not its pretty print: the
    // same scenario for every robot and APF preset, and for a tree that
    // does not read, the message its print gives (line numbers included).
    let mut presets = 0;
    for entry in std::fs::read_dir(ASSETS).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("json") {
            continue;
        }
        let text = String::from_utf8(read(path.to_str().unwrap())).unwrap();
        let tree: serde_json::Value = serde_json::from_str(&text).unwrap();
        if tree.get("arm").is_some() {
            continue;
        }
        let from_text = Scenario::from_json(&text).unwrap();
        assert_eq!(
            Scenario::from_value(&tree).unwrap(),
            from_text,
            "{}",
            path.display()
        );
        presets += 1;
    }
    assert!(presets > 10, "{presets} presets");
    let demo = String::from_utf8(read(&format!("{ASSETS}/dwa-demo.json"))).unwrap();
    for (path, value) in [
        ("sim.dt", "-1"),
        ("sim.dt", "\"fast\""),
        ("sim.dtt", "0.1"),
        ("start.col", "1.5"),
        ("movers.0.radius", "[1]"),
        ("version", "2"),
        ("goal.col", "100000"),
    ] {
        let mut tree: serde_json::Value = serde_json::from_str(&demo).unwrap();
        set_json_path(&mut tree, path, value).unwrap();
        let printed = Scenario::from_json(&serde_json::to_string_pretty(&tree).unwrap());
        let e = Scenario::from_value(&tree).expect_err(path).to_string();
        assert_eq!(e, printed.expect_err(path).to_string(), "{path}={value}");
    }
}
