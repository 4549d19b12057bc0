//! One entry point per parser and file-driven path of planlab-core, shared
//! by the `cargo fuzz` targets (`fuzz/fuzz_targets/*.rs` include this file)
//! and the stable seeded mutation test (`tests/mutation.rs`), so both
//! exercise the same code with the same checks.
//!
//! Each target takes arbitrary bytes and must return without panicking;
//! whatever it parses must fail with a one-line error or satisfy the
//! format's round-trip property.
#![allow(dead_code)] // each fuzz target uses one function

use planlab_core::apf::rnn::SimpleRnn;
use planlab_core::arm::{ArmEpisode, ArmModel};
use planlab_core::map::io::{movingai, ros};
use planlab_core::metrics::{EpisodeMetrics, DEFAULT_LOAD_THRESHOLD_N};
use planlab_core::scenario::{set_json_path, ArmScenario, Scenario};
use planlab_core::sim::Episode;
use std::fmt::Display;
use std::path::PathBuf;

/// Simulation steps the scenario targets take (enough to plan, move,
/// collide and compute metrics; few enough to keep executions fast).
const SIM_STEPS: usize = 5;

/// A target: its name, its function and the seed files of its corpus
/// (relative to the repository root).
pub struct Target {
    pub name: &'static str,
    pub run: fn(&[u8]),
    pub seeds: &'static [&'static str],
}

/// Every target, with its seeds: valid files of the repository and the
/// malformed corpus's files of that kind.
pub const TARGETS: &[Target] = &[
    Target {
        name: "movingai_map",
        run: movingai_map,
        seeds: &["assets/maps/arena.map", "tests/data/malformed/*.map"],
    },
    Target {
        name: "movingai_scen",
        run: movingai_scen,
        seeds: &[
            "tests/data/movingai/maze/maze512-1-0.map.scen",
            "tests/data/malformed/*.scen",
        ],
    },
    Target {
        name: "ros_yaml",
        run: ros_yaml,
        seeds: &["assets/maps/turtlebot3.yaml", "tests/data/malformed/*.yaml"],
    },
    Target {
        name: "pgm",
        run: pgm,
        seeds: &["assets/maps/turtlebot3.pgm", "tests/data/malformed/*.pgm"],
    },
    Target {
        name: "scenario_json",
        run: scenario_json,
        seeds: &[
            "assets/scenarios/grid-demo.json",
            "assets/scenarios/pursuit-demo.json",
            "tests/data/malformed/*.scenario.json",
        ],
    },
    Target {
        name: "scenario_set",
        run: scenario_set,
        seeds: &["tests/data/fuzz-seeds/*.set"],
    },
    Target {
        name: "scenario_sim",
        run: scenario_sim,
        seeds: &[
            "assets/scenarios/pursuit-demo.json",
            "assets/scenarios/grid-demo.json",
            "tests/data/malformed/*.scenario.json",
        ],
    },
    Target {
        name: "arm_model",
        run: arm_model,
        seeds: &["assets/arm/tiago.json", "tests/data/malformed/*.arm.json"],
    },
    Target {
        name: "arm_scenario",
        run: arm_scenario,
        seeds: &[
            "assets/scenarios/T-tab5-3.json",
            "tests/data/malformed/*.armscen.json",
        ],
    },
    Target {
        name: "predictor",
        run: predictor,
        seeds: &[
            "assets/predictor/rnn.json",
            "tests/data/malformed/*.rnn.json",
        ],
    },
];

/// The repository root: the nearest folder above the including crate's
/// manifest (planlab-core or fuzz/) that holds `assets/`.
pub fn repo_root() -> PathBuf {
    let here = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    here.ancestors()
        .find(|d| d.join("assets/scenarios").is_dir())
        .unwrap_or(&here)
        .to_path_buf()
}

/// The seed files of `t`, read (a `*` in the last component matches any
/// file name prefix ending in the rest).
pub fn seed_files(t: &Target) -> Vec<(String, Vec<u8>)> {
    let root = repo_root();
    let mut out = Vec::new();
    for pattern in t.seeds {
        let path = root.join(pattern);
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if let Some(suffix) = name.strip_prefix('*') {
            let dir = path.parent().unwrap();
            let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
                .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
                .map(|e| e.unwrap().path())
                .filter(|p| p.to_string_lossy().ends_with(suffix))
                .collect();
            files.sort();
            for f in files {
                out.push((f.display().to_string(), std::fs::read(&f).unwrap()));
            }
        } else {
            let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            out.push((pattern.to_string(), bytes));
        }
    }
    out
}

/// An error must be one line (the CLI prints it after `planlab: error:`,
/// the page in one status line).
fn one_line(e: &dyn Display) {
    let s = e.to_string();
    assert!(!s.contains('\n'), "multi-line error: {s:?}");
    assert!(!s.is_empty(), "empty error message");
}

fn text(data: &[u8]) -> Option<&str> {
    std::str::from_utf8(data).ok()
}

/// Moving AI `.map`: parse, and a parsed map writes and reads back equal.
pub fn movingai_map(data: &[u8]) {
    let Some(t) = text(data) else { return };
    match movingai::parse_map(t) {
        Ok(g) => {
            let again = movingai::parse_map(&movingai::write_map(&g)).expect("written map reads");
            assert_eq!(again.cells(), g.cells());
        }
        Err(e) => one_line(&e),
    }
}

/// Moving AI `.scen`.
pub fn movingai_scen(data: &[u8]) {
    let Some(t) = text(data) else { return };
    if let Err(e) = movingai::parse_scen(t) {
        one_line(&e);
    }
}

/// ROS map_server YAML: parse, and parsed metadata writes and reads back
/// equal.
pub fn ros_yaml(data: &[u8]) {
    let Some(t) = text(data) else { return };
    match ros::parse_yaml(t) {
        Ok(m) => {
            let again = ros::parse_yaml(&ros::write_yaml(&m)).expect("written YAML reads");
            assert_eq!(again, m);
        }
        Err(e) => one_line(&e),
    }
}

/// PGM (P2, P5, 8- and 16-bit): parse; a P5 cut at its header's byte
/// limit parses the same; the grid builds.
pub fn pgm(data: &[u8]) {
    match ros::parse_pgm(data) {
        Ok(p) => {
            let limit = ros::pgm_byte_limit(data).expect("a parsed PGM has a limit");
            // P5: reading up to the limit is exact. P2: a file within the
            // limit is read whole, a longer one refused (never cut).
            if data.starts_with(b"P5") || data.len() as u64 <= limit {
                let cut = &data[..data.len().min(limit as usize)];
                assert_eq!(ros::parse_pgm(cut).expect("the limit keeps every pixel"), p);
            }
            let grid = planlab_core::map::OccupancyGrid::new(1, 1).unwrap();
            let meta = ros::RosMapMeta::for_grid(&grid, "m.pgm");
            let g = ros::grid_from_pgm(&meta, &p).expect("a parsed PGM makes a grid");
            assert_eq!((g.width(), g.height()), (p.width, p.height));
        }
        Err(e) => one_line(&e),
    }
}

/// The grid of a scenario (inline maps; a file reference fails to read).
fn grid_of(s: &Scenario) -> Option<planlab_core::map::OccupancyGrid> {
    let mut no_files = |_: &str| Err::<Vec<u8>, String>("no files in fuzzing".into());
    match s.load_grid(&mut no_files) {
        Ok(g) => Some(g),
        Err(e) => {
            one_line(&e);
            None
        }
    }
}

/// Scenario JSON: parse, load the map, write and read back.
pub fn scenario_json(data: &[u8]) {
    let Some(t) = text(data) else { return };
    match Scenario::from_json(t) {
        Ok(s) => {
            let json = s.to_json_pretty().expect("a parsed scenario writes");
            let again = Scenario::from_json(&json).expect("a written scenario reads");
            assert_eq!(again.to_json_pretty().unwrap(), json);
            grid_of(&s);
        }
        Err(e) => one_line(&e),
    }
}

/// A few steps of the episode of a valid scenario, and its metrics.
fn simulate(s: &Scenario) {
    let Some(grid) = grid_of(s) else { return };
    match Episode::from_scenario(s, grid) {
        Ok(mut ep) => {
            let mut outcome = ep.step();
            for _ in 1..SIM_STEPS {
                outcome = ep.step();
            }
            let m = EpisodeMetrics::from_trace(
                ep.trace(),
                &ep.planner_debug().global_path,
                outcome,
                DEFAULT_LOAD_THRESHOLD_N,
            );
            assert!(m.path_length_m.is_finite() || m.path_length_m.is_nan());
        }
        Err(e) => one_line(&e),
    }
}

/// Scenario JSON → a few simulation steps.
pub fn scenario_sim(data: &[u8]) {
    let Some(t) = text(data) else { return };
    match Scenario::from_json(t) {
        Ok(s) => simulate(&s),
        Err(e) => one_line(&e),
    }
}

/// `--set PATH=VALUE` edits (one per line) of the pursuit demo, then a few
/// simulation steps.
pub fn scenario_set(data: &[u8]) {
    let Some(t) = text(data) else { return };
    static BASE: &str = include_str!("../../../../assets/scenarios/pursuit-demo.json");
    let mut tree: serde_json::Value = serde_json::from_str(BASE).unwrap();
    for edit in t.lines().take(8) {
        let Some((k, v)) = edit.split_once('=') else {
            continue;
        };
        if let Err(e) = set_json_path(&mut tree, k.trim(), v) {
            one_line(&e);
            return;
        }
    }
    match Scenario::from_value(&tree) {
        Ok(s) => simulate(&s),
        Err(e) => one_line(&e),
    }
}

/// Arm model JSON.
pub fn arm_model(data: &[u8]) {
    let Some(t) = text(data) else { return };
    if let Err(e) = ArmModel::from_json(t) {
        one_line(&e);
    }
}

/// Arm scenario JSON → a few steps of its episode.
pub fn arm_scenario(data: &[u8]) {
    let Some(t) = text(data) else { return };
    match ArmScenario::from_json(t) {
        Ok(s) => match ArmEpisode::new(s.arm, s.seed.unwrap_or(0)) {
            Ok(mut ep) => {
                for _ in 0..SIM_STEPS {
                    if let Err(e) = ep.step() {
                        one_line(&e);
                        return;
                    }
                }
            }
            Err(e) => one_line(&e),
        },
        Err(e) => one_line(&e),
    }
}

/// Predictor weights JSON.
pub fn predictor(data: &[u8]) {
    let Some(t) = text(data) else { return };
    if let Err(e) = SimpleRnn::from_json(t) {
        one_line(&e);
    }
}
