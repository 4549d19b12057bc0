//! An episode written as MCAP reads back with Foxglove's reader: every
//! step's pose is the trace's, the schemas are Foxglove's, and recording
//! changes nothing in the run.

use std::collections::BTreeMap;

use planlab_core::scenario::{AnyRun, AnyScenario};
use planlab_core::sim::Episode;
use planlab_mcap::{record_episode, TOPICS};
use serde_json::Value;

fn episode(name: &str) -> Episode {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/scenarios");
    let text = std::fs::read_to_string(format!("{dir}/{name}")).unwrap();
    let s = AnyScenario::from_json(&text).unwrap();
    let grid = s
        .load_grid(&mut |p| std::fs::read(format!("{dir}/{p}")).map_err(|e| e.to_string()))
        .unwrap();
    match s.start(grid).unwrap() {
        AnyRun::Robot(ep) => *ep,
        _ => panic!("{name} is not a robot scenario"),
    }
}

/// (topic, schema name, log time, message) of every message, in order.
fn read(bytes: &[u8]) -> Vec<(String, String, u64, Value)> {
    mcap::MessageStream::new(bytes)
        .unwrap()
        .map(|m| {
            let m = m.unwrap();
            let schema = m
                .channel
                .schema
                .as_ref()
                .map(|s| s.name.clone())
                .unwrap_or_default();
            assert_eq!(m.channel.message_encoding, "json");
            (
                m.channel.topic.clone(),
                schema,
                m.log_time,
                serde_json::from_slice(&m.data).unwrap(),
            )
        })
        .collect()
}

fn check(name: &str, want: &[&str]) {
    let mut plain = episode(name);
    plain.run();
    let mut ep = episode(name);
    let (bytes, outcome) = record_episode(&mut ep).unwrap();
    assert_eq!(outcome, plain.outcome(), "{name}");
    assert_eq!(
        ep.trace().hash(),
        plain.trace().hash(),
        "{name}: recording changed the run"
    );
    let msgs = read(&bytes);
    let mut per_topic: BTreeMap<&str, usize> = BTreeMap::new();
    for (topic, schema, _, _) in &msgs {
        let t = TOPICS
            .iter()
            .find(|t| **t == topic)
            .expect("a declared topic");
        *per_topic.entry(t).or_default() += 1;
        assert!(schema.starts_with("foxglove."), "{topic}: {schema}");
    }
    let rows = ep.trace().steps.len();
    assert_eq!(per_topic["/map"], 1, "{name}");
    for t in ["/robot/pose", "/robot/footprint", "/goal"] {
        assert_eq!(per_topic[t], rows, "{name} {t}");
    }
    for t in want {
        assert!(per_topic.get(t).copied().unwrap_or(0) > 0, "{name}: no {t}");
    }
    // Every pose is the trace row of its time.
    let poses: Vec<&(String, String, u64, Value)> =
        msgs.iter().filter(|m| m.0 == "/robot/pose").collect();
    for (row, (_, schema, time, msg)) in ep.trace().steps.iter().zip(poses) {
        assert_eq!(schema, "foxglove.PoseInFrame");
        assert_eq!(*time, (row.t * 1e9).round() as u64);
        assert_eq!(msg["frame_id"], "map");
        let p = &msg["pose"]["position"];
        assert_eq!(
            (p["x"].as_f64().unwrap(), p["y"].as_f64().unwrap()),
            (row.x, row.y)
        );
        let q = &msg["pose"]["orientation"];
        let yaw = 2.0 * q["z"].as_f64().unwrap().atan2(q["w"].as_f64().unwrap());
        assert!(
            (yaw - row.theta).abs() < 1e-9
                || ((yaw - row.theta).abs() - std::f64::consts::TAU).abs() < 1e-9
        );
    }
    // The map: one byte per cell, as many as the grid has.
    let map = &msgs.iter().find(|m| m.0 == "/map").unwrap().3;
    let grid = ep.map().grid();
    assert_eq!(map["column_count"].as_u64().unwrap() as usize, grid.width());
    let data = map["data"].as_str().unwrap();
    assert_eq!(data.len(), (grid.width() * grid.height()).div_ceil(3) * 4);
    // Same run, same messages: nothing in them depends on a clock. (The
    // summary section's record order is the writer's hash order.)
    let mut again = episode(name);
    let again = read(&record_episode(&mut again).unwrap().0);
    assert!(again == msgs, "{name}: a second recording differs");
}

#[test]
fn a_dwa_episode_with_movers_reads_back_with_every_step_and_the_movers() {
    check("dwa-demo.json", &["/movers", "/plan/local"]);
}

#[test]
fn a_lidar_episode_reads_back_with_its_scans_and_global_path() {
    check("L-sim1.json", &["/scan", "/plan/local"]);
}
