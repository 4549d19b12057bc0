//! The sampling planners (core [`planlab_core::sampling`]) for the grid and
//! race pages: a [`SamplingRun`] is one seeded planner on a copy of the
//! page's map, stepped from JS. The core has no clock, so a time budget is
//! the page's: it calls [`SamplingRun::step`] in chunks until
//! `performance.now()` passes the budget; the tree does not depend on the
//! chunking (the core's guarantee), only on the seed and the iterations.
//!
//! The event log crosses as three typed arrays ([`SamplingEvents`]: the
//! core's [`Event::flat`] columns), and every improved solution's path is
//! kept so the page can highlight it when the player reaches its event.

use crate::MapHandle;
use planlab_core::sampling::shortcut::shortcut;
use planlab_core::sampling::{
    cell_centre, path_cost, DiscSpace, Event, Point, SamplingAlgorithm, SamplingError,
    SamplingOptions, SamplingPlanner, SpaceError,
};
use std::sync::Arc;
use wasm_bindgen::prelude::*;

/// The disc radius when the page leaves it empty: 0.4 of a cell, the
/// CLI's default (`planlab plan --algo …` without `--radius`).
pub const DEFAULT_RADIUS_CELLS: f64 = 0.4;

/// Shortcut attempts, the CLI's (`planlab plan … --shortcut`), so the page
/// and the CLI shorten a path alike.
const SHORTCUT_ATTEMPTS: usize = 200;

/// The largest seed a JS number holds exactly (2^53 − 1).
const MAX_SEED: f64 = 9_007_199_254_740_991.0;

/// One sampling planner as the page runs it.
#[wasm_bindgen]
pub struct SamplingRun {
    planner: SamplingPlanner,
    seed: u64,
    resolution: f64,
    /// The path of each improvement, in order (flat x, y, cells); the
    /// i-th `Solution` event's path is the i-th entry.
    solution_paths: Vec<Vec<f64>>,
    /// The shortcut best path, made on first request.
    shortcut: Option<(usize, Vec<Point>)>,
}

/// Events taken from a run, as the core's [`Event::flat`] columns: per
/// event a kind byte (0 sample, 1 node, 2 edge, 3 remove edge, 4 connect,
/// 5 rewire, 6 prune, 7 solution), three ids and two numbers.
#[wasm_bindgen]
pub struct SamplingEvents {
    kinds: Vec<u8>,
    ids: Vec<u32>,
    nums: Vec<f64>,
}

#[wasm_bindgen]
impl SamplingEvents {
    /// Number of events.
    #[wasm_bindgen(getter)]
    pub fn length(&self) -> u32 {
        self.kinds.len() as u32
    }

    /// Kind of each event.
    pub fn kinds(&self) -> Vec<u8> {
        self.kinds.clone()
    }

    /// Three ids per event (unused ones 0; a solution's iteration first).
    pub fn ids(&self) -> Vec<u32> {
        self.ids.clone()
    }

    /// Two numbers per event (coordinates in cells; a solution's cost first).
    pub fn nums(&self) -> Vec<f64> {
        self.nums.clone()
    }
}

impl SamplingEvents {
    /// The flat form of `events`.
    pub fn from_events(events: &[Event]) -> Self {
        let mut out = SamplingEvents {
            kinds: Vec::with_capacity(events.len()),
            ids: Vec::with_capacity(events.len() * 3),
            nums: Vec::with_capacity(events.len() * 2),
        };
        for e in events {
            let (k, ids, nums) = e.flat();
            out.kinds.push(k);
            out.ids.extend_from_slice(&ids);
            out.nums.extend_from_slice(&nums);
        }
        out
    }
}

fn flat(path: &[Point]) -> Vec<f64> {
    path.iter().flat_map(|p| [p[0], p[1]]).collect()
}

/// The one-line message of a set-up error, with the radius in the page's
/// metres.
fn message(e: SamplingError, resolution: f64) -> String {
    match e {
        SamplingError::Space(SpaceError::BadRadius(r)) => format!(
            "robot radius {} m: must be a finite number of metres ≥ 0 and less than half the map's smaller side",
            r * resolution
        ),
        SamplingError::InCollision { which, x, y, radius } => format!(
            "the {which} (cell {}, {}) is too close to a wall or the map's edge for a robot of radius {:.3} m: move it or make the robot smaller",
            (x - 0.5).round(),
            (y - 0.5).round(),
            radius * resolution
        ),
        e => e.to_string(),
    }
}

#[wasm_bindgen]
impl SamplingRun {
    /// A planner (`algorithm`: a core name, `rrt` … `bit-star`) from the
    /// centre of cell (`start_col`, `start_row`) to that of the goal cell
    /// on a copy of `map`, for a disc of `radius_m` metres (`undefined`:
    /// 0.4 cell), seeded by `seed` (a whole number), recording its events.
    #[wasm_bindgen(constructor)]
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        map: &MapHandle,
        algorithm: &str,
        start_col: u32,
        start_row: u32,
        goal_col: u32,
        goal_row: u32,
        radius_m: Option<f64>,
        seed: f64,
        allow_unknown: bool,
    ) -> Result<SamplingRun, JsError> {
        let algo = SamplingAlgorithm::from_name(algorithm).ok_or_else(|| {
            let names: Vec<&str> = SamplingAlgorithm::ALL.iter().map(|a| a.1).collect();
            JsError::new(&format!(
                "unknown sampling planner {algorithm:?} (one of {})",
                names.join(", ")
            ))
        })?;
        if !((0.0..=MAX_SEED).contains(&seed) && seed.fract() == 0.0) {
            return Err(JsError::new(&format!(
                "seed {seed}: must be a whole number from 0 to {MAX_SEED}"
            )));
        }
        let grid = map.grid();
        let resolution = grid.resolution();
        // Metres to cells as the CLI converts --radius.
        let radius = radius_m.map_or(DEFAULT_RADIUS_CELLS, |r| r / resolution);
        let options = SamplingOptions {
            algorithm: algo,
            seed: seed as u64,
            record_events: true,
            ..SamplingOptions::default()
        };
        let space = DiscSpace::new(grid, radius, allow_unknown)
            .map_err(|e| JsError::new(&message(e.into(), resolution)))?;
        let planner = SamplingPlanner::new(
            Arc::new(space),
            cell_centre(start_col, start_row),
            cell_centre(goal_col, goal_row),
            &options,
        )
        .map_err(|e| JsError::new(&message(e, resolution)))?;
        Ok(SamplingRun {
            planner,
            seed: seed as u64,
            resolution,
            solution_paths: Vec::new(),
            shortcut: None,
        })
    }

    /// Runs up to `iterations` more iterations (fewer once done); returns
    /// how many ran. One at a time inside, so the path of every
    /// improvement is kept (the result is the same whatever the chunking).
    pub fn step(&mut self, iterations: u32) -> u32 {
        let mut ran = 0;
        while ran < iterations {
            if self.planner.step(1) == 0 {
                break;
            }
            ran += 1;
            let found = self.planner.solutions().len();
            if found > self.solution_paths.len() {
                // Several improvements in one iteration share its final path.
                let path = flat(self.planner.path());
                self.solution_paths.resize(found, path);
            }
        }
        ran
    }

    /// The events logged since the last call.
    #[wasm_bindgen(js_name = takeEvents)]
    pub fn take_events(&mut self) -> SamplingEvents {
        SamplingEvents::from_events(&self.planner.take_events())
    }

    /// Whether stepping can change nothing more (RRT / RRT-Connect with a
    /// path, a straight-line path, the core's iteration limit).
    #[wasm_bindgen(getter)]
    pub fn done(&self) -> bool {
        self.planner.done()
    }

    /// Iterations run so far.
    #[wasm_bindgen(getter)]
    pub fn iterations(&self) -> f64 {
        self.planner.iterations() as f64
    }

    /// The planner's points (tree or roadmap nodes, BIT*'s samples).
    #[wasm_bindgen(getter, js_name = nodeCount)]
    pub fn node_count(&self) -> u32 {
        self.planner.node_count() as u32
    }

    /// The best path's cost, cells (NaN before the first path).
    #[wasm_bindgen(getter, js_name = bestCost)]
    pub fn best_cost(&self) -> f64 {
        self.planner.best_cost().unwrap_or(f64::NAN)
    }

    /// The iteration of the first path (NaN before it).
    #[wasm_bindgen(getter, js_name = firstSolution)]
    pub fn first_solution(&self) -> f64 {
        self.planner
            .first_solution_iteration()
            .map_or(f64::NAN, |i| i as f64)
    }

    /// Every improvement as (iteration, cost) pairs, costs decreasing.
    pub fn solutions(&self) -> Vec<f64> {
        self.planner
            .solutions()
            .iter()
            .flat_map(|&(i, c)| [i as f64, c])
            .collect()
    }

    /// The path of the `i`-th improvement (flat x, y, cells; empty past
    /// the last).
    #[wasm_bindgen(js_name = solutionPath)]
    pub fn solution_path(&self, i: u32) -> Vec<f64> {
        self.solution_paths
            .get(i as usize)
            .cloned()
            .unwrap_or_default()
    }

    /// The best path (flat x, y, cells), shortcut as the CLI's
    /// `--shortcut` does (same seed, same attempts) when `shortened`.
    pub fn path(&mut self, shortened: bool) -> Vec<f64> {
        if shortened {
            flat(self.shortcut_path())
        } else {
            flat(self.planner.path())
        }
    }

    /// The length of [`SamplingRun::path`], cells (NaN before the first
    /// path): the cost the CLI prints.
    #[wasm_bindgen(js_name = pathCost)]
    pub fn path_cost(&mut self, shortened: bool) -> f64 {
        if self.planner.path().is_empty() {
            return f64::NAN;
        }
        if shortened {
            path_cost(self.shortcut_path())
        } else {
            path_cost(self.planner.path())
        }
    }

    /// The disc's radius, cells.
    #[wasm_bindgen(getter, js_name = radiusCells)]
    pub fn radius_cells(&self) -> f64 {
        self.planner.space().radius()
    }

    /// Metres per cell of the planned map.
    #[wasm_bindgen(getter)]
    pub fn resolution(&self) -> f64 {
        self.resolution
    }

    /// The planner's core name.
    #[wasm_bindgen(getter)]
    pub fn algorithm(&self) -> String {
        self.planner.algorithm().name().to_string()
    }
}

impl SamplingRun {
    /// The shortcut best path, remade when a better path came since.
    fn shortcut_path(&mut self) -> &[Point] {
        let n = self.planner.solutions().len();
        if self.shortcut.as_ref().map(|s| s.0) != Some(n) {
            let p = shortcut(
                self.planner.space(),
                self.planner.path(),
                self.seed,
                SHORTCUT_ATTEMPTS,
            );
            self.shortcut = Some((n, p));
        }
        match &self.shortcut {
            Some((_, p)) => p,
            None => &[],
        }
    }
}

/// One sampling planner as the page's menu and help show it.
#[derive(serde::Serialize)]
struct SamplingInfo {
    name: &'static str,
    optimizing: bool,
    reference: &'static str,
    summary: &'static str,
}

/// The core's sampling planners (`SamplingAlgorithm::ALL`): name, whether
/// it keeps improving its path, its reference and a one-line summary.
#[wasm_bindgen(js_name = samplingAlgorithms)]
pub fn sampling_algorithms() -> Result<JsValue, JsError> {
    let all: Vec<SamplingInfo> = SamplingAlgorithm::ALL
        .iter()
        .map(|&(a, name)| SamplingInfo {
            name,
            optimizing: a.optimizing(),
            reference: a.reference(),
            summary: a.description(),
        })
        .collect();
    serde_wasm_bindgen::to_value(&all).map_err(|e| JsError::new(&e.to_string()))
}
