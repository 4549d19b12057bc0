//! planlab-core: the pure-Rust heart of planlab.
//!
//! No clock, no global randomness, no wasm bindings: the same inputs give the
//! same outputs natively and in WebAssembly.
//!
//! # Modules, bottom layer first
//! Each module uses only modules listed in a layer before its own
//! (`ARCHITECTURE.md`; `tests/layering.rs` checks it). Algorithms follow
//! the papers; `docs/algorithms.md` gives the equations.
//! - [`text`]: one-line error text.
//! - [`num`]: deterministic numerics: `libm` trigonometry, the seeded RNG,
//!   number formatting.
//! - [`params`]: the one bound check of every config number, config
//!   parsing, and `params!`, which declares a config one line per field.
//! - [`geom`]: plane geometry: closest point of a segment, distance to a
//!   polyline.
//! - [`map`]: occupancy grids with resolution and origin, cells and the
//!   supercover line, editing and generated maps, inflation and a ROS-style
//!   decaying costmap; readers for ROS map_server YAML + PGM, Moving AI
//!   `.map` / `.scen` and a scenario's `map` section (docs/algorithms.md
//!   §maps, §inflation).
//! - [`global`]: A* with four heuristics and a weight, Dijkstra, Jump Point
//!   Search, safe A* of Ge & Li (2022) §1, key-point extraction of Wu (2022)
//!   §3.2.1 and Bottom-Up segmentation of Ge & Li §4.1 (docs/algorithms.md
//!   §grid–§bottom-up).
//! - [`car`]: car-like robots: Dubins and Reeds-Shepp curves and Hybrid
//!   A* over continuous poses (§car-curves, §hybrid-astar).
//! - [`world`]: the robot's body and kinematics, moving obstacles, terrain
//!   and vehicle dynamics, the static map's geometry, sensor samples and
//!   run outcomes (§robot, §terrain, §movers).
//! - [`local`]: the local-planner interface and the DWA family of Wu
//!   (2022), Ge & Li (2022) and Zhang et al. (2020) (§dwa–§cleaning-dwa).
//! - [`apf`]: artificial potential fields in 2D and 3D with obstacle
//!   prediction and the SimpleRNN predictor, Wu (2022) ch. 4 (§apf).
//! - [`lidar`]: LiDAR heuristic navigation in unknown maps of Chang et al.
//!   (2024): scan simulation, edges, gap and obstacle patterns, temporary
//!   goals over a pluggable motion planner, and its peers (§lidar).
//! - [`arm`]: the 7-DOF arm beside a moving hand, Wu (2022) §5.3.3 (§arm).
//! - [`planners`]: the catalogue of local planners by name (`planlab
//!   planners`), their config fields and their construction.
//! - [`sim`]: fixed-step, seeded episodes, their traces, recordings and
//!   edits (§episode).
//! - [`metrics`]: what an episode measured, from its trace (§metrics).
//! - [`draw`]: the draw list: what a frame of an episode shows, as layers
//!   of typed primitives in world metres, for the page and screenshots.
//! - [`scenario`]: the scenario files of every kind and the one way from a
//!   file to a finished run.
//! - [`batch`]: seeded variants of a scenario and per-planner statistics.
//! - [`recipe`]: the one edit recipe (planner, seed, `--set` edits, batch
//!   variant, arm predictor) every front end applies to a scenario.
//! - [`reproduce`]: the papers' experiments: presets, clauses, families,
//!   verdicts (§reproduce).
//! - [`bench`](mod@bench): the benchmark scenes shared by the CLI and the page.
//! - [`barn`]: the BARN benchmark's worlds (SDF, reference paths, a compact
//!   text form), their occupancy grids and the BARN score.
#![warn(missing_docs)]

pub mod apf;
pub mod arm;
pub mod barn;
pub mod batch;
pub mod bench;
pub mod car;
pub mod draw;
pub mod geom;
pub mod global;
pub mod lidar;
pub mod local;
pub mod map;
pub mod metrics;
pub mod num;
pub mod params;
pub mod planners;
pub mod recipe;
pub mod reproduce;
pub mod sampling;
pub mod scenario;
pub mod sim;
pub mod text;
pub mod world;
