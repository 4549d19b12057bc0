//! planlab-core: the pure-Rust heart of planlab.
//!
//! No clock, no global randomness, no wasm bindings: the same inputs give the
//! same outputs natively and in WebAssembly.
//!
//! # Algorithms (see `docs/algorithms.md` for the equations)
//! - [`map`]: occupancy grids with resolution and origin; readers for ROS
//!   map_server YAML + PGM, Moving AI `.map` / `.scen`, planlab's scenario
//!   JSON and ASCII art; inflation and a ROS-style decaying costmap
//!   (docs/algorithms.md §maps, §inflation).
//! - [`global`]: A* with four heuristics and a weight, Dijkstra, Jump Point
//!   Search, safe A* of Ge & Li (2022) §1, key-point extraction of Wu (2022)
//!   §3.2.1 and Bottom-Up segmentation of Ge & Li §4.1 (docs/algorithms.md §grid–§bottom-up).
//! - [`lidar`]: LiDAR heuristic navigation in unknown maps of Chang et al.
//!   (2024): scan simulation, edges, gap and obstacle patterns, temporary
//!   goals over a pluggable motion planner (docs/algorithms.md §lidar).
#![warn(missing_docs)]

pub mod apf;
pub mod arm;
pub mod batch;
pub mod bench;
pub mod draw;
pub mod global;
pub mod lidar;
pub mod local;
pub mod map;
pub mod metrics;
pub mod num;
pub mod reproduce;
pub mod sim;
pub mod text;
pub mod world;
