//! Hostile and malformed input, core side: one regression test per defect
//! found by fuzzing and hostile use (huge or non-finite numbers, readers
//! with quadratic time or unbounded allocation, errors that echo garbage or
//! span lines). The CLI side is planlab-cli's `tests/hostile_input_cli.rs`.

use planlab_core::map::io::ros;
use planlab_core::metrics::{resample, MAX_RESAMPLE_POINTS};
use planlab_core::num::fmt_num;
use planlab_core::scenario::{set_json_path, Scenario, SET_PATH_MAX_NAMES};
use planlab_core::sim::Episode;
use std::time::Instant;

const DWA_DEMO: &str = include_str!("../../../assets/scenarios/dwa-demo.json");

/// Builds the episode of the DWA demo with `edits` (`path`, `value`)
/// applied; the error of whichever step refused it.
fn edited(edits: &[(&str, &str)]) -> Result<(), String> {
    let mut tree: serde_json::Value = serde_json::from_str(DWA_DEMO).unwrap();
    for (k, v) in edits {
        set_json_path(&mut tree, k, v).map_err(|e| e.to_string())?;
    }
    let s = Scenario::from_value(&tree).map_err(|e| e.to_string())?;
    let mut no_files = |_: &str| Err::<Vec<u8>, String>("no files".into());
    let grid = s.load_grid(&mut no_files).map_err(|e| e.to_string())?;
    Episode::from_scenario(&s, grid)
        .map(|_| ())
        .map_err(|e| e.to_string())
}

#[test]
fn dt_1e9_is_refused() {
    let e = edited(&[("sim.dt", "1e9")]).unwrap_err();
    assert!(e.contains("sim.dt = 1e9 s: must be at most 1 s"), "{e}");
    // The largest allowed period still builds, and the paper's 0.1 s too.
    assert!(edited(&[("sim.dt", "1")]).is_ok());
    assert!(edited(&[("sim.dt", "0.1")]).is_ok());
}

#[test]
fn every_time_speed_and_size_has_an_upper_bound() {
    for (path, needle) in [
        (
            "sim.max_time",
            "sim.max_time = 1e300 s: must be at most 1e6",
        ),
        ("sim.goal_tolerance", "sim.goal_tolerance = 1e300 m"),
        ("sim.sensing_range", "sim.sensing_range = 1e300 m"),
        (
            "robot.limits.v_max",
            "v_max (m/s) = 1e300: must be at most 1e6",
        ),
        ("robot.limits.acc_v", "acc_v (m/s²) = 1e300"),
        ("movers.0.radius", "radius (m) = 1e300"),
        (
            "grid_planner.inflate_m",
            "inflate_m is 1e300 (metres): it must be at most 1e6",
        ),
        ("local_planner.config.predict_time", "predict_time = 1e300"),
    ] {
        let e = edited(&[(path, "1e300")]).expect_err(path);
        assert!(e.contains(needle), "{path}: {e}");
        assert!(e.len() < 200, "{path}: long message {e}");
    }
}

#[test]
fn resample_is_bounded() {
    // One 7.6·10⁸ m step (what sim.dt = 1e9 produced) resampled every
    // 0.1 m asked for 7.6·10⁹ points and aborted.
    let r = resample(&[[0.0, 0.0], [7.6e8, 0.0]], 0.1);
    assert!(r.len() <= MAX_RESAMPLE_POINTS + 2, "{}", r.len());
    // A normal path keeps its spacing exactly.
    assert_eq!(resample(&[[0.0, 0.0], [1.0, 0.0]], 0.1).len(), 11);
}

#[test]
fn ros_yaml_reader_is_linear_in_the_keys() {
    // 160 000 keys took 247 s with the quadratic duplicate check.
    let mut yaml = String::from("image: m.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n");
    for i in 0..160_000 {
        yaml.push_str(&format!("key_{i}: {i}\n"));
    }
    let t = Instant::now();
    let meta = ros::parse_yaml(&yaml).unwrap();
    let secs = t.elapsed().as_secs_f64();
    assert_eq!(meta.image, "m.pgm");
    assert!(secs < 5.0, "160 000 keys took {secs} s");
    // Duplicates are still found, at the end of a long file too.
    yaml.push_str("key_7: again\n");
    let e = ros::parse_yaml(&yaml).unwrap_err().to_string();
    assert!(e.contains("key `key_7` appears twice"), "{e}");
}

#[test]
fn pgm_read_limit_comes_from_the_header() {
    // P5 8-bit: header + 1 + w·h; 16-bit: 2 bytes a pixel; P2: a bound per
    // pixel; a lying header is refused before any pixel is read.
    let p5 = b"P5\n4 3\n255\n";
    assert_eq!(
        ros::pgm_byte_limit(p5).unwrap(),
        (p5.len() - 1 + 1 + 12) as u64
    );
    let p5w = b"P5\n4 3\n1000\n";
    assert_eq!(
        ros::pgm_byte_limit(p5w).unwrap(),
        (p5w.len() - 1 + 1 + 24) as u64
    );
    let p2 = b"P2\n4 3\n255\n";
    assert_eq!(
        ros::pgm_byte_limit(p2).unwrap(),
        (p2.len() - 1 + 1) as u64 + 12 * ros::P2_BYTES_PER_PIXEL
    );
    let e = ros::pgm_byte_limit(b"P5\n100000 100000\n255\n").unwrap_err();
    assert!(e.to_string().contains("map too large"), "{e}");
    // Bytes after the last pixel are ignored, so reading up to the limit
    // gives the same image.
    let mut full = b"P5\n2 2\n255\n\x00\x01\x02\x03".to_vec();
    let limit = ros::pgm_byte_limit(&full).unwrap() as usize;
    assert_eq!(limit, full.len());
    let img = ros::parse_pgm(&full).unwrap();
    full.extend_from_slice(&[9; 1000]);
    assert_eq!(ros::parse_pgm(&full[..limit]).unwrap(), img);
}

#[test]
fn numbers_in_errors_are_compact() {
    assert_eq!(fmt_num(1e308), "1e308");
    assert_eq!(fmt_num(-1e308), "-1e308");
    assert_eq!(fmt_num(0.1), "0.1");
    assert_eq!(fmt_num(1e-300), "1e-300");
    assert_eq!(fmt_num(123456.5), "123456.5");
    let e = planlab_core::map::MapError::BadResolution(-1e308).to_string();
    assert!(e.contains("-1e308") && e.len() < 100, "{e}");
}

#[test]
fn a_newline_in_a_json_key_stays_one_line() {
    // cargo fuzz (scenario_sim) found a scenario whose key holds an escaped
    // newline: serde's "unknown field" message quoted it raw, two lines.
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../tests/data/malformed/fuzz-newline-in-key.scenario.json"),
    )
    .unwrap();
    let e = Scenario::from_json(&text).unwrap_err().to_string();
    assert!(!e.contains('\n'), "{e:?}");
    assert!(
        e.contains("unknown field `width") && e.contains("\\n"),
        "{e}"
    );
    let e = edited(&[("local_planner.name", "dwa\nx")]).unwrap_err();
    assert!(e.contains("unknown planner `dwa\\nx`"), "{e}");
}

#[test]
fn nan_in_scenario_json_is_named() {
    let text = r#"{ "version": 1, "name": "n", "map": { "width": 3, "height": 1, "resolution": 1.0, "cells": ["..."] },
  "start": { "col": 0, "row": 0 }, "goal": { "col": 2, "row": 0 },
  "sim": { "dt": NaN } }"#;
    let e = planlab_core::scenario::Scenario::from_json(text)
        .unwrap_err()
        .to_string();
    assert!(e.contains("NaN is not a number JSON allows"), "{e}");
    assert!(e.contains("line 3"), "{e}");
    let any = planlab_core::scenario::AnyScenario::from_json(&text.replace("NaN", "-Infinity"))
        .unwrap_err()
        .to_string();
    assert!(
        any.contains("-Infinity is not a number JSON allows"),
        "{any}"
    );
}

#[test]
fn a_garbage_map_is_not_echoed() {
    use planlab_core::map::io::movingai::parse_map;
    let e = parse_map("\u{1}PNG\u{1a}\u{0}\u{0}garbage\nmore")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("not a Moving AI map: the first line should be `type octile`"),
        "{e}"
    );
    assert!(!e.contains("\\u{") && !e.contains("PNG"), "{e}");
}

#[test]
fn a_ros_yaml_starting_with_a_byte_order_mark_parses() {
    // Before: "missing `image`" (the BOM became part of the first key).
    // Windows editors write one.
    let yaml = "\u{feff}image: m.pgm\nresolution: 0.05\norigin: [1, 2, 0]\n";
    let meta = ros::parse_yaml(yaml).unwrap();
    assert_eq!(meta.image, "m.pgm");
    assert_eq!(meta.resolution, 0.05);
    // Only a leading one: anywhere else it is still an unknown character.
    assert!(
        ros::parse_yaml("image: m.pgm\n\u{feff}resolution: 0.05\norigin: [1, 2, 0]\n").is_err()
    );
}

#[test]
fn batch_variants_of_an_apf_scenario_are_refused_as_such() {
    // Before: drawn as a robot scenario, then "no valid start/goal/mover
    // placement … (0.000, 0.000) m: a wall".
    let text = include_str!("../../../assets/scenarios/T-fig4-6.json");
    let s = Scenario::from_json(text).unwrap();
    let mut no_files = |_: &str| Err::<Vec<u8>, String>("no files".into());
    let grid = s.load_grid(&mut no_files).unwrap();
    let e = planlab_core::batch::variant(&s, &grid, 1, 0, 0.3).unwrap_err();
    assert!(
        e.to_string()
            .contains("APF scenarios have no batch variants"),
        "{e}"
    );
    let e = planlab_core::batch::planner_choices(&s, &[]).unwrap_err();
    assert!(
        e.to_string()
            .contains("APF scenarios have no batch variants"),
        "{e}"
    );
}

#[test]
fn every_numeric_planner_field_at_its_largest_allowed_value_ends_a_short_run() {
    // Once improved-dwa with inflate_margin at its bound (10⁶ m) never
    // ended: its start-snapping search walked rings of 10⁸ cells.
    let (mut tried, mut ran) = (0, 0);
    for p in planlab_core::planners::list() {
        for f in &p.fields {
            let (Some(bound), Some(_)) = (f.bound, f.default.as_f64()) else {
                continue;
            };
            let mut tree: serde_json::Value = serde_json::from_str(DWA_DEMO).unwrap();
            // Display, not fmt_num: "1000000" is also a valid integer.
            let max = format!("{}", bound.max);
            for (k, v) in [
                ("local_planner.name", p.name.as_str()),
                (&format!("local_planner.config.{}", f.name), max.as_str()),
                ("sim.max_time", "1"),
            ] {
                set_json_path(&mut tree, k, v).unwrap();
            }
            let what = format!("{}.{} = {max}", p.name, f.name);
            tried += 1;
            let s = Scenario::from_value(&tree).unwrap_or_else(|e| panic!("{what}: {e}"));
            let mut no_files = |_: &str| Err::<Vec<u8>, String>("no files".into());
            let grid = s.load_grid(&mut no_files).unwrap();
            // A typed refusal is fine (a value legal alone may clash with
            // another field); building and running must both end.
            if let Ok(mut ep) = Episode::from_scenario(&s, grid) {
                ran += 1;
                let end = ep.run();
                assert!(ep.time() <= 1.0 + 1e-9, "{what}: {end:?} at {}", ep.time());
            }
        }
    }
    // Not vacuous: most fields at their bound make a planner that runs.
    assert!(tried > 200 && ran * 2 > tried, "{ran} of {tried} ran");
}

#[test]
fn a_set_path_deeper_than_the_limit_is_refused_in_one_line() {
    // Before: `a.a.a…` 20 000 names deep built a tree as deep, and reading
    // it printed every level indented (0.8 GB) before failing.
    let deep = vec!["a"; 20_000].join(".");
    let e = edited(&[(&deep, "1")]).unwrap_err();
    assert!(
        e.contains("the path has 20000 names; at most 64 are allowed"),
        "{e}"
    );
    assert!(!e.contains('\n') && e.len() < 200, "{e}");
    // The limit itself is allowed, one more is not, and a refused edit
    // leaves the tree as it was.
    assert_eq!(SET_PATH_MAX_NAMES, 64);
    let path = |n: usize| vec!["a"; n].join(".");
    let mut tree: serde_json::Value = serde_json::from_str(DWA_DEMO).unwrap();
    let before = tree.clone();
    let e = set_json_path(&mut tree, &path(65), "1").unwrap_err();
    assert!(e.to_string().contains("65 names; at most 64"), "{e}");
    assert_eq!(tree, before);
    set_json_path(&mut tree, &path(64), "1").unwrap();
    assert_eq!(
        tree.pointer(&format!("/{}", path(64).replace('.', "/"))),
        Some(&1.into())
    );
}

#[test]
fn a_scripted_mover_sample_time_beyond_1e6_s_is_refused() {
    // Coordinates were bounded, times were not: 10³⁰⁰ s was accepted.
    let script = r#"{"model": "scripted", "samples": [{"t": 0, "x": 8, "y": 8}, {"t": 1e300, "x": 9, "y": 8}]}"#;
    let e = edited(&[("movers.0.motion", script)]).unwrap_err();
    assert!(
        e.contains("sample 1 time 1e300 s: times must be finite, within ±1e6 s"),
        "{e}"
    );
    let script = r#"{"model": "scripted", "samples": [{"t": 0, "x": 8, "y": 8}, {"t": 1e6, "x": 9, "y": 8}]}"#;
    assert!(edited(&[("movers.0.motion", script)]).is_ok());
}
