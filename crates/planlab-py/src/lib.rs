//! `planlab._planlab`: the Python bindings of planlab-core (built by maturin
//! into the `planlab` package; the Python half is in `python/planlab/`).
//!
//! Everything goes through the core's own entry points, as the CLI does:
//! `map::io` through [`planlab_files`] for files, `plan_on_map` and the
//! core's algorithm / heuristic / diagonal names for grid plans,
//! `AnyScenario` for runs, `batch::variant` / `batch::run_variant` for
//! batch episodes, `reproduce` for the papers' experiments. So the numbers
//! are the CLI's, and a planner or algorithm added to the core appears here
//! with no change. Every core error becomes a `PlanlabError` subclass with
//! the core's one-line message; nothing panics across the boundary.

use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::{Arc, Mutex, MutexGuard, OnceLock};

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray2};
use planlab_core::batch;
use planlab_core::global::plan::{
    plan_on_map, plan_on_plan_grid, Algorithm, GridPlanError, GridPlanOptions, GridPlanOverrides,
};
use planlab_core::global::{Diagonal, GridPos, Heuristic, PlanError as CorePlanError, PlanGrid};
use planlab_core::lidar::{Lidar, LidarConfig};
use planlab_core::map::{Cell, OccupancyGrid, Pose2, MAX_CELLS};
use planlab_core::metrics::EpisodeMetrics;
use planlab_core::planners;
use planlab_core::recipe::Recipe;
use planlab_core::reproduce::{self, Experiment, RunMetrics};
use planlab_core::sampling::shortcut::shortcut;
use planlab_core::sampling::{
    cell_centre, path_cost, DiscSpace, SamplingAlgorithm, SamplingError, SamplingOptions,
    SamplingPlanner, SpaceError, MAX_ITERATIONS,
};
use planlab_core::scenario::{AnyRun, AnyScenario, FinishedRun, Scenario as CoreScenario};
use planlab_core::sim::{Column, Episode as CoreEpisode, Outcome, Trace};
use planlab_core::text::one_line;
use planlab_core::world::Command;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde_json::Value;

/// The exception hierarchy: `PlanlabError` and one subclass per kind of
/// input that can be wrong.
mod errors {
    use pyo3::create_exception;
    create_exception!(
        planlab,
        PlanlabError,
        pyo3::exceptions::PyException,
        "Base of every planlab error; the message is the core's one line."
    );
    create_exception!(
        planlab,
        MapError,
        PlanlabError,
        "A map file or array could not be read or is invalid."
    );
    create_exception!(
        planlab,
        ScenarioError,
        PlanlabError,
        "A scenario could not be read, built or run."
    );
    create_exception!(
        planlab,
        PlanError,
        PlanlabError,
        "A grid plan failed: an endpoint off the map or in a wall, no path."
    );
    create_exception!(
        planlab,
        ParamError,
        PlanlabError,
        "A parameter is out of range, not finite or unknown."
    );
}
use errors::{MapError, ParamError, PlanError, PlanlabError, ScenarioError};

fn err<E: pyo3::PyTypeInfo>(msg: impl std::fmt::Display) -> PyErr {
    PyErr::new::<E, _>(one_line(&msg.to_string()))
}

/// A JSON document (serde) as a Python object, through Python's `json`.
fn to_py<'py>(py: Python<'py>, v: &impl serde::Serialize) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(v).map_err(err::<PlanlabError>)?;
    py.import("json")?.call_method1("loads", (text,))
}

/// A Python object (dict, list, number …) as a JSON tree, through `json`.
fn from_py(obj: &Bound<'_, PyAny>) -> PyResult<Value> {
    let kwargs = PyDict::new(obj.py());
    kwargs.set_item("allow_nan", false)?;
    let text: String = obj
        .py()
        .import("json")?
        .call_method("dumps", (obj,), Some(&kwargs))
        .map_err(|e| err::<ParamError>(format!("not a JSON document: {e}")))?
        .extract()?;
    serde_json::from_str(&text).map_err(err::<ParamError>)
}

/// A (rows, cols) array from row-major values.
fn table<T: numpy::Element>(
    py: Python<'_>,
    rows: usize,
    cols: usize,
    flat: Vec<T>,
) -> PyResult<Bound<'_, PyArray2<T>>> {
    let a = Array2::from_shape_vec((rows, cols), flat).map_err(err::<PlanlabError>)?;
    Ok(a.into_pyarray(py))
}

// ---------------------------------------------------------------- maps

/// An occupancy grid: `occupancy[row, col]` (uint8: 0 free, 1 occupied,
/// 2 unknown), `resolution` (m per cell) and `origin` (x, y, yaw). A grid
/// read from a scenario also carries its start and goal cells and its grid
/// planner options, which `plan` uses as defaults (as `planlab plan` does).
#[pyclass(module = "planlab", frozen)]
struct Grid {
    grid: OccupancyGrid,
    start: Option<GridPos>,
    goal: Option<GridPos>,
    options: GridPlanOptions,
    /// The passability grid without inflation, by `allow_unknown`, built on
    /// the first query that needs it: later queries skip that pass over the
    /// map (the CLI's bench builds it once too).
    prepared: [OnceLock<PlanGrid>; 2],
    /// The sampling planners' free space of the last (radius in cells,
    /// allow_unknown) asked for: its exact distance transform is a pass over
    /// the map (about 12 ms on 512 × 512), which a series of queries with
    /// one disc should pay once, as a benchmark's peer builds its checker
    /// once per map.
    disc_space: Mutex<Option<(f64, bool, Arc<DiscSpace>)>>,
}

impl Grid {
    /// The free space for a disc of `radius` cells, built once per radius
    /// in a row (see `disc_space`).
    fn disc_space(&self, radius: f64, allow_unknown: bool) -> Result<Arc<DiscSpace>, SpaceError> {
        let mut cached = self.disc_space.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((r, u, space)) = cached.as_ref() {
            if *r == radius && *u == allow_unknown {
                return Ok(space.clone());
            }
        }
        let space = Arc::new(DiscSpace::new(&self.grid, radius, allow_unknown)?);
        *cached = Some((radius, allow_unknown, space.clone()));
        Ok(space)
    }

    fn of(grid: OccupancyGrid, scenario: Option<&CoreScenario>) -> Grid {
        Grid {
            grid,
            start: scenario.map(|s| s.start.pos()),
            goal: scenario.map(|s| s.goal.pos()),
            options: scenario.map_or_else(GridPlanOptions::default, |s| s.grid_planner),
            prepared: Default::default(),
            disc_space: Mutex::new(None),
        }
    }
}

#[pymethods]
impl Grid {
    /// A grid from a 2-D array (`[row, col]`; bool or integers: 0 free,
    /// 1 occupied, 2 unknown).
    #[new]
    #[pyo3(signature = (occupancy, resolution = 1.0, origin = (0.0, 0.0, 0.0)))]
    fn new(
        occupancy: &Bound<'_, PyAny>,
        resolution: f64,
        origin: (f64, f64, f64),
    ) -> PyResult<Grid> {
        let py = occupancy.py();
        let a = py.import("numpy")?.call_method1("asarray", (occupancy,))?;
        let dtype = a.getattr("dtype")?;
        let kind: String = dtype.getattr("kind")?.extract()?;
        if !matches!(kind.as_str(), "b" | "i" | "u") {
            return Err(err::<MapError>(format!(
                "occupancy: expected a bool or integer array (0 free, 1 occupied, 2 unknown), got {}",
                dtype.str()?
            )));
        }
        // Out-of-range integers would wrap in the cast to uint8: refused
        // first (min and max are one pass each, in C).
        if a.getattr("size")?.extract::<usize>()? > 0 {
            for end in ["min", "max"] {
                let v: i64 = a
                    .call_method0(end)?
                    .call_method0("__int__")?
                    .extract()
                    .unwrap_or(i64::MAX);
                if !(0..=2).contains(&v) {
                    return Err(err::<MapError>(format!(
                        "occupancy value {v}: expected 0 (free), 1 (occupied) or 2 (unknown)"
                    )));
                }
            }
        }
        let arr = a.call_method1("astype", ("uint8",))?;
        let arr: PyReadonlyArray2<u8> = arr
            .extract()
            .map_err(|_| err::<MapError>("occupancy must be a 2-D array of 0/1/2 values"))?;
        let view = arr.as_array();
        let (h, w) = view.dim();
        if (w as u64).saturating_mul(h as u64) > MAX_CELLS {
            // The core's own refusal, before anything is allocated.
            OccupancyGrid::new(w, h).map_err(err::<MapError>)?;
        }
        let mut cells = Vec::with_capacity(w * h);
        for v in view.iter() {
            cells.push(match v {
                0 => Cell::Free,
                1 => Cell::Occupied,
                2 => Cell::Unknown,
                other => {
                    return Err(err::<MapError>(format!(
                        "occupancy value {other}: expected 0 (free), 1 (occupied) or 2 (unknown)"
                    )))
                }
            });
        }
        let grid = OccupancyGrid::from_cells(w, h, cells)
            .and_then(|g| {
                g.with_frame(
                    resolution,
                    Pose2 {
                        x: origin.0,
                        y: origin.1,
                        yaw: origin.2,
                    },
                )
            })
            .map_err(err::<MapError>)?;
        Ok(Grid::of(grid, None))
    }

    /// `occupancy[row, col]` as a uint8 array (a copy).
    #[getter]
    fn occupancy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<u8>>> {
        let g = &self.grid;
        let cells: Vec<u8> = g.cells().iter().map(|c| *c as u8).collect();
        table(py, g.height(), g.width(), cells)
    }

    /// `weights[row, col]`: each cell's traversal weight as a uint8 array
    /// (1 ordinary … 9; all ones on a unit-cost map; docs/algorithms.md
    /// §weights). A move costs its length times the weight it enters.
    #[getter]
    fn weights<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<u8>>> {
        let g = &self.grid;
        let w = g
            .weights()
            .map_or_else(|| vec![1; g.cells().len()], <[u8]>::to_vec);
        table(py, g.height(), g.width(), w)
    }

    #[getter]
    fn width(&self) -> usize {
        self.grid.width()
    }

    #[getter]
    fn height(&self) -> usize {
        self.grid.height()
    }

    #[getter]
    fn resolution(&self) -> f64 {
        self.grid.resolution()
    }

    /// (x, y, yaw) of the map's origin, metres and radians.
    #[getter]
    fn origin(&self) -> (f64, f64, f64) {
        let o = self.grid.origin();
        (o.x, o.y, o.yaw)
    }

    /// The scenario's start cell (col, row), or None.
    #[getter]
    fn start(&self) -> Option<(u32, u32)> {
        self.start.map(|p| (p.col, p.row))
    }

    /// The scenario's goal cell (col, row), or None.
    #[getter]
    fn goal(&self) -> Option<(u32, u32)> {
        self.goal.map(|p| (p.col, p.row))
    }

    /// World coordinates (m) of a cell's centre.
    fn cell_to_world(&self, col: usize, row: usize) -> (f64, f64) {
        self.grid.cell_to_world(col, row)
    }

    fn __repr__(&self) -> String {
        format!(
            "Grid({}×{} cells, {} m/cell)",
            self.grid.width(),
            self.grid.height(),
            self.grid.resolution()
        )
    }
}

/// Reads a map: a ROS map_server `.yaml` (+ its image), a Moving AI `.map`
/// or a scenario `.json` (its map, start, goal and grid planner options).
#[pyfunction]
fn load_map(py: Python<'_>, path: PathBuf) -> PyResult<Grid> {
    let (grid, scenario) = py
        .detach(|| planlab_files::load_any(&path))
        .map_err(err::<MapError>)?;
    Ok(Grid::of(grid, scenario.as_ref()))
}

/// The rows of a Moving AI `.scen` as an (n, 5) float array: start col,
/// start row, goal col, goal row, optimal length.
#[pyfunction]
fn load_scen<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let rows = planlab_files::load_scen(&path).map_err(err::<MapError>)?;
    let flat: Vec<f64> = rows
        .iter()
        .flat_map(|r| {
            [
                f64::from(r.start.col),
                f64::from(r.start.row),
                f64::from(r.goal.col),
                f64::from(r.goal.row),
                r.optimal,
            ]
        })
        .collect();
    table(py, rows.len(), 5, flat)
}

/// A name in the core's serde spelling (`no_corner_cutting`); the CLI's
/// `no-corner-cutting` is accepted too.
fn by_serde_name<T: serde::de::DeserializeOwned>(what: &str, name: &str) -> PyResult<T> {
    serde_json::from_value(Value::String(name.trim().replace('-', "_")))
        .map_err(|e| err::<ParamError>(format!("{what} {name:?}: {e}")))
}

fn cell(which: &str, p: (i64, i64)) -> PyResult<GridPos> {
    let ok = |v: i64| u32::try_from(v).ok();
    match (ok(p.0), ok(p.1)) {
        (Some(c), Some(r)) => Ok(GridPos::new(c, r)),
        _ => Err(err::<ParamError>(format!(
            "{which} ({}, {}): expected (COLUMN, ROW) with non-negative integers",
            p.0, p.1
        ))),
    }
}

fn cells_array<'py>(py: Python<'py>, cells: &[GridPos]) -> PyResult<Bound<'py, PyArray2<i64>>> {
    let flat: Vec<i64> = cells
        .iter()
        .flat_map(|p| [i64::from(p.col), i64::from(p.row)])
        .collect();
    table(py, cells.len(), 2, flat)
}

/// A map for [`plan`]: a [`Grid`] or the path of a map file.
#[derive(FromPyObject)]
enum GridOrPath<'py> {
    Grid(PyRef<'py, Grid>),
    Path(PathBuf),
}

/// Plans on `grid` (a `Grid` or a map file's path) from `start` to `goal`
/// (cells (col, row); default: the scenario's), as `planlab plan` does.
///
/// A grid algorithm (`algorithms()`; default astar or the scenario's) runs
/// the core's `plan_on_map` and returns a dict: `path` ((n, 2) int array of
/// (col, row)), `cost` (cells), `length_m`, `expanded`, `keypoints`,
/// `feature_nodes`, `safety`, `note`.
///
/// A sampling algorithm (`sampling_algorithms()`: rrt, rrt-connect,
/// rrt-star, informed-rrt-star, prm, prm-star, bit-star) plans a disc of
/// `radius` metres (default 0.4 cell) between the cells' centres for
/// `iterations` (default 10 000), seeded by `seed` (default 0), as `planlab
/// plan --algo NAME --json` does; `shortcut` shortens the path afterwards
/// (seeded by `seed` too), `range` (cells) sets the longest extension
/// (default a tenth of the map's diagonal), `time_limit` (seconds) stops
/// earlier when the wall clock runs out — the one input that makes a run
/// depend on the machine. Returns a dict: `algorithm`, `cost` (the path's
/// length, cells), `length_m`, `iterations`, `first_solution_iteration`,
/// `nodes`, `path` ((n, 2) float array of (x, y) cells: x along the
/// columns, y down the rows, a cell's centre at +0.5), `solutions` (list of
/// (iteration, cost), costs strictly falling), `seed`, `radius` (cells),
/// `seconds` (wall time of the planning) and, with `shortcut`,
/// `cost_before_shortcut`. No path within the budget is a `PlanError`, as
/// in the CLI.
#[pyfunction]
#[pyo3(signature = (grid, start = None, goal = None, algo = None, heuristic = None,
    diagonal = None, weight = None, inflate = None, allow_unknown = false,
    keypoints = false, bottom_up = None, epsilon = None, iterations = None, seed = None,
    radius = None, shortcut = false, range = None, time_limit = None))]
#[allow(clippy::too_many_arguments)]
fn plan<'py>(
    py: Python<'py>,
    grid: GridOrPath<'py>,
    start: Option<(i64, i64)>,
    goal: Option<(i64, i64)>,
    algo: Option<&str>,
    heuristic: Option<&str>,
    diagonal: Option<&str>,
    weight: Option<f64>,
    inflate: Option<f64>,
    allow_unknown: bool,
    keypoints: bool,
    bottom_up: Option<f64>,
    epsilon: Option<f64>,
    iterations: Option<i128>,
    seed: Option<i128>,
    radius: Option<f64>,
    shortcut: bool,
    range: Option<f64>,
    time_limit: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let loaded;
    let grid: &Grid = match &grid {
        GridOrPath::Grid(g) => g,
        GridOrPath::Path(p) => {
            loaded = load_map(py, p.clone())?;
            &loaded
        }
    };
    let sampling_algo = algo.and_then(|a| SamplingAlgorithm::from_name(a.trim()));
    if let Some(algorithm) = sampling_algo {
        let grid_only = [
            ("heuristic", heuristic.is_some()),
            ("diagonal", diagonal.is_some()),
            ("weight", weight.is_some()),
            ("inflate", inflate.is_some()),
            ("keypoints", keypoints),
            ("bottom_up", bottom_up.is_some()),
            ("epsilon", epsilon.is_some()),
        ];
        if let Some((name, _)) = grid_only.iter().find(|f| f.1) {
            return Err(err::<ParamError>(format!(
                "{name} applies to the grid planners, not to {}",
                algorithm.name()
            )));
        }
        let args = SamplingCall {
            algorithm,
            iterations,
            seed,
            radius,
            shortcut,
            range,
            time_limit,
            allow_unknown,
        };
        return plan_sampling(py, grid, start, goal, &args);
    }
    let sampling_only = [
        ("iterations", iterations.is_some()),
        ("seed", seed.is_some()),
        ("radius", radius.is_some()),
        ("shortcut", shortcut),
        ("range", range.is_some()),
        ("time_limit", time_limit.is_some()),
    ];
    if let Some((name, _)) = sampling_only.iter().find(|f| f.1) {
        return Err(err::<ParamError>(format!(
            "{name} applies to the sampling planners (algo={})",
            SamplingAlgorithm::ALL
                .iter()
                .map(|(_, n)| format!("{n:?}"))
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    let overrides = GridPlanOverrides {
        algorithm: algo
            .map(|a| Algorithm::from_str(a.trim()))
            .transpose()
            .map_err(err::<ParamError>)?,
        heuristic: heuristic
            .map(|h| by_serde_name::<Heuristic>("heuristic", h))
            .transpose()?,
        weight,
        diagonal: diagonal
            .map(|d| by_serde_name::<Diagonal>("diagonal", d))
            .transpose()?,
        inflate_m: inflate,
        allow_unknown,
        keypoints,
        bottom_up_eps: bottom_up,
        epsilon,
    };
    let options = grid.options.overridden(&overrides).map_err(|e| match e {
        CorePlanError::InvalidConfig(m) => err::<ParamError>(m),
        e => err::<ParamError>(e),
    })?;
    let endpoint = |name: &str, given: Option<(i64, i64)>, own: Option<GridPos>| match (given, own)
    {
        (Some(p), _) => cell(name, p),
        (None, Some(p)) => Ok(p),
        (None, None) => Err(err::<ParamError>(format!(
            "{name} (COLUMN, ROW) is required for this map"
        ))),
    };
    let start = endpoint("start", start, grid.start)?;
    let goal = endpoint("goal", goal, grid.goal)?;
    let g = &grid.grid;
    let result = py
        .detach(|| {
            if options.inflate_m == 0.0 {
                let prepared = grid.prepared[usize::from(options.allow_unknown)]
                    .get_or_init(|| PlanGrid::new(g, options.allow_unknown));
                plan_on_plan_grid(g, prepared, start, goal, &options)
            } else {
                plan_on_map(g, start, goal, &options)
            }
        })
        .map_err(|e| match e {
            GridPlanError::Plan(CorePlanError::InvalidConfig(_)) | GridPlanError::Map(_) => {
                err::<ParamError>(e)
            }
            _ => err::<PlanError>(e),
        })?;
    let d = PyDict::new(py);
    d.set_item("path", cells_array(py, &result.path.cells)?)?;
    d.set_item("cost", result.path.cost)?;
    d.set_item("length_m", result.length_m)?;
    d.set_item("expanded", result.path.expanded)?;
    d.set_item("keypoints", cells_array(py, &result.keypoints)?)?;
    d.set_item("feature_nodes", cells_array(py, &result.feature_nodes)?)?;
    d.set_item("safety", PyArray1::from_vec(py, result.safety))?;
    d.set_item("algorithm", options.algorithm.name())?;
    // E.g. that BFS ignored the map's cell weights; None when nothing to say.
    d.set_item("note", result.note)?;
    Ok(d)
}

/// The sampling arguments of [`plan`].
struct SamplingCall {
    algorithm: SamplingAlgorithm,
    iterations: Option<i128>,
    seed: Option<i128>,
    radius: Option<f64>,
    shortcut: bool,
    range: Option<f64>,
    time_limit: Option<f64>,
    allow_unknown: bool,
}

/// Iterations between two looks at the clock under a `time_limit`: an
/// iteration costs microseconds, so the limit is overrun by well under a
/// millisecond, and the clock is read rarely enough not to show.
const CLOCK_EVERY: u64 = 64;

/// Shortcut attempts after a sampling plan, as `planlab plan --shortcut`.
const SHORTCUT_ATTEMPTS: usize = 200;

/// `plan` with a sampling algorithm: `plan_on_grid`'s work, stepped so that
/// a time limit can stop it, then the CLI's answer.
fn plan_sampling<'py>(
    py: Python<'py>,
    grid: &Grid,
    start: Option<(i64, i64)>,
    goal: Option<(i64, i64)>,
    a: &SamplingCall,
) -> PyResult<Bound<'py, PyDict>> {
    let name = a.algorithm.name();
    let iterations = match a.iterations {
        None => 10_000,
        Some(n) if (1..=i128::from(MAX_ITERATIONS)).contains(&n) => n as u64,
        Some(n) => {
            return Err(err::<ParamError>(format!(
                "iterations {n}: must be from 1 to {MAX_ITERATIONS}"
            )))
        }
    };
    let seed = match a.seed {
        None => 0,
        Some(s) => u64::try_from(s)
            .map_err(|_| err::<ParamError>(format!("seed {s}: must be from 0 to {}", u64::MAX)))?,
    };
    let res = grid.grid.resolution();
    let radius = match a.radius {
        None => 0.4,
        Some(r) if r.is_finite() && r >= 0.0 => r / res,
        Some(r) => {
            return Err(err::<ParamError>(format!(
                "radius {r}: must be a finite number of metres ≥ 0"
            )))
        }
    };
    let deadline = match a.time_limit {
        None => None,
        Some(t) if t.is_finite() && t > 0.0 => Some(std::time::Duration::from_secs_f64(t)),
        Some(t) => {
            return Err(err::<ParamError>(format!(
                "time_limit {t}: must be a positive number of seconds"
            )))
        }
    };
    let endpoint = |which: &str, given: Option<(i64, i64)>, own: Option<GridPos>| {
        let p = match (given, own) {
            (Some(p), _) => cell(which, p)?,
            (None, Some(p)) => p,
            (None, None) => {
                return Err(err::<ParamError>(format!(
                    "{which} (COLUMN, ROW) is required for this map"
                )))
            }
        };
        Ok(cell_centre(p.col, p.row))
    };
    let start = endpoint("start", start, grid.start)?;
    let goal = endpoint("goal", goal, grid.goal)?;
    let options = SamplingOptions {
        algorithm: a.algorithm,
        seed,
        range: a.range,
        ..SamplingOptions::default()
    };
    let allow_unknown = a.allow_unknown;
    let shortcut_path = a.shortcut;
    let outcome = py.detach(|| {
        let t = std::time::Instant::now();
        let space = grid.disc_space(radius, allow_unknown)?;
        let mut planner = SamplingPlanner::new(space, start, goal, &options)?;
        match deadline {
            None => {
                planner.step(iterations);
            }
            Some(limit) => {
                // Chunks give the same run as one call (the core's promise),
                // so only where it stops depends on the clock.
                while planner.iterations() < iterations && !planner.done() && t.elapsed() < limit {
                    planner.step(CLOCK_EVERY.min(iterations - planner.iterations()));
                }
            }
        }
        let path = match (planner.best_cost(), shortcut_path) {
            (Some(_), true) => shortcut(planner.space(), planner.path(), seed, SHORTCUT_ATTEMPTS),
            _ => planner.path().to_vec(),
        };
        Ok::<_, SamplingError>((planner, path, t.elapsed().as_secs_f64()))
    });
    let (planner, path, seconds) = outcome.map_err(|e| match e {
        SamplingError::Space(SpaceError::BadRadius(r)) => err::<ParamError>(format!(
            "radius {}: must be a finite number of metres ≥ 0 and less than half the map's smaller side",
            r * res
        )),
        SamplingError::InCollision { .. } => err::<PlanError>(e),
        e => err::<ParamError>(e),
    })?;
    let Some(raw_cost) = planner.best_cost() else {
        return Err(err::<PlanError>(format!(
            "{name}: no path after {} iterations ({} nodes); try more iterations or another seed",
            planner.iterations(),
            planner.node_count()
        )));
    };
    let cost = path_cost(&path);
    let d = PyDict::new(py);
    d.set_item("algorithm", name)?;
    d.set_item("cost", cost)?;
    d.set_item("length_m", cost * res)?;
    d.set_item("iterations", planner.iterations())?;
    d.set_item(
        "first_solution_iteration",
        planner.first_solution_iteration(),
    )?;
    d.set_item("nodes", planner.node_count())?;
    let flat: Vec<f64> = path.iter().flat_map(|p| [p[0], p[1]]).collect();
    d.set_item("path", table(py, path.len(), 2, flat)?)?;
    d.set_item("solutions", planner.solutions().to_vec())?;
    d.set_item("seed", seed)?;
    d.set_item("radius", radius)?;
    d.set_item("seconds", seconds)?;
    if a.shortcut {
        d.set_item("cost_before_shortcut", raw_cost)?;
    }
    Ok(d)
}

/// A car's typed error as a Python exception: bad numbers are `ParamError`,
/// the rest (endpoint off the map or in collision, no path) `PlanError`.
fn car_err(e: planlab_core::car::CarError) -> PyErr {
    use planlab_core::car::CarError;
    match e {
        CarError::InvalidParameter(_) | CarError::BadPose { .. } => err::<ParamError>(e),
        e => err::<PlanError>(e),
    }
}

fn pose(p: (f64, f64, f64)) -> planlab_core::car::Pose {
    planlab_core::car::Pose::new(p.0, p.1, p.2)
}

/// Hybrid A* for a car (docs/algorithms.md §hybrid-astar), as `planlab
/// plan --algo hybrid-astar`: `start`, `goal` are (x, y, θ) in world metres
/// and **radians**; `footprint` = (length, width) m plans a rectangle
/// instead of the `radius` disc (`--footprint LxW`). Returns a dict:
/// `poses` ((n, 3) array x, y, θ), `forward` (bool per pose), `length_m`,
/// `expanded`, `analytic`, `cusps`.
#[pyfunction]
#[pyo3(signature = (grid, start, goal, turning_radius, reverse = false, radius = None, footprint = None))]
#[allow(clippy::too_many_arguments)]
fn plan_car<'py>(
    py: Python<'py>,
    grid: &Grid,
    start: (f64, f64, f64),
    goal: (f64, f64, f64),
    turning_radius: f64,
    reverse: bool,
    radius: Option<f64>,
    footprint: Option<(f64, f64)>,
) -> PyResult<Bound<'py, PyDict>> {
    use planlab_core::car::hybrid_astar::{plan_hybrid_astar, HybridAStarConfig};
    if radius.is_some() && footprint.is_some() {
        return Err(err::<ParamError>(
            "plan_car: radius and footprint are two footprints: give one",
        ));
    }
    let mut cfg = HybridAStarConfig {
        turning_radius,
        reverse,
        allow_unknown: grid.options.allow_unknown,
        ..Default::default()
    };
    if let Some(r) = radius {
        cfg.footprint_radius = r;
    }
    cfg.footprint_rect = footprint;
    let g = &grid.grid;
    let p = py
        .detach(|| plan_hybrid_astar(g, pose(start), pose(goal), &cfg))
        .map_err(car_err)?;
    let flat: Vec<f64> = p.poses.iter().flat_map(|q| [q.x, q.y, q.yaw]).collect();
    let d = PyDict::new(py);
    d.set_item(
        "poses",
        Array2::from_shape_vec((p.poses.len(), 3), flat)
            .map_err(err::<PlanError>)?
            .into_pyarray(py),
    )?;
    d.set_item("forward", p.forward)?;
    d.set_item("length_m", p.length)?;
    d.set_item("expanded", p.expanded)?;
    d.set_item("analytic", p.analytic)?;
    d.set_item("cusps", p.cusps)?;
    Ok(d)
}

fn curve_dict<'py>(
    py: Python<'py>,
    p: planlab_core::car::CurvePath,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("length", p.length())?;
    d.set_item("word", p.word())?;
    let segs: Vec<(String, f64)> = p
        .segments
        .iter()
        .map(|s| (s.steer.letter().to_string(), s.length))
        .collect();
    d.set_item("segments", segs)?;
    Ok(d)
}

/// The shortest forward-only car path (Dubins) from `start` to `goal`
/// ((x, y, θ), metres and radians) at `radius`: `length`, `word`,
/// `segments` ((letter, signed length) pairs).
#[pyfunction]
fn dubins<'py>(
    py: Python<'py>,
    start: (f64, f64, f64),
    goal: (f64, f64, f64),
    radius: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let p = planlab_core::car::dubins(pose(start), pose(goal), radius).map_err(car_err)?;
    curve_dict(py, p)
}

/// As [`dubins`] when the car may reverse (Reeds-Shepp).
#[pyfunction]
fn reeds_shepp<'py>(
    py: Python<'py>,
    start: (f64, f64, f64),
    goal: (f64, f64, f64),
    radius: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let p = planlab_core::car::reeds_shepp(pose(start), pose(goal), radius).map_err(car_err)?;
    curve_dict(py, p)
}

/// The grid algorithms' names (what `plan(algo=…)` accepts besides
/// `sampling_algorithms()`).
#[pyfunction]
fn algorithms() -> Vec<&'static str> {
    Algorithm::ALL.iter().map(|(_, n)| *n).collect()
}

/// The sampling planners' names (`plan(algo=…)` with a disc robot,
/// iterations and a seed).
#[pyfunction]
fn sampling_algorithms() -> Vec<&'static str> {
    SamplingAlgorithm::ALL.iter().map(|(_, n)| *n).collect()
}

/// The local planner catalogue (`planlab planners --json`).
#[pyfunction]
fn planner_catalogue(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    to_py(py, &planners::list())
}

// ----------------------------------------------------------- scenarios

/// A scenario document of any kind (robot, APF, arm) and the folder its
/// map files are relative to.
#[pyclass(module = "planlab", frozen)]
struct Scenario {
    tree: Value,
    dir: PathBuf,
    parsed: AnyScenario,
}

/// Options of a run or an episode: `planlab run`'s `--planner`, `--seed`,
/// `--set`.
fn set_edits(set: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(String, String)>> {
    let mut out = Vec::new();
    if let Some(d) = set {
        for (k, v) in d.iter() {
            let key: String = k
                .extract()
                .map_err(|_| err::<ParamError>("set: keys are dotted paths like sim.dt"))?;
            // Strings as written (a planner name, `true`); anything else as
            // its JSON text.
            let value = if let Ok(s) = v.extract::<String>() {
                s
            } else if v.is_instance_of::<pyo3::types::PyFloat>() {
                // NaN and infinities as the CLI's text, which the core
                // refuses with its own message; JSON has no form for them.
                let x: f64 = v.extract()?;
                match x {
                    x if x.is_nan() => "NaN".into(),
                    x if x.is_infinite() => (if x > 0.0 { "inf" } else { "-inf" }).into(),
                    x => format!("{x:?}"),
                }
            } else {
                from_py(&v)?.to_string()
            };
            out.push((key, value));
        }
    }
    Ok(out)
}

impl Scenario {
    fn of_tree(tree: Value, dir: PathBuf) -> PyResult<Scenario> {
        let parsed = AnyScenario::from_value(&tree).map_err(err::<ScenarioError>)?;
        Ok(Scenario { tree, dir, parsed })
    }

    /// The scenario with `recipe` applied (the core's, as `planlab run`
    /// applies it) and its loaded map.
    fn edited(&self, recipe: &Recipe) -> PyResult<(AnyScenario, Option<OccupancyGrid>)> {
        let dir = &self.dir;
        let done = recipe
            .apply_tree(&self.tree, &mut |rel: &str| {
                planlab_files::read_map_file(&dir.join(rel))
            })
            .map_err(err::<ScenarioError>)?;
        Ok((done.scenario, done.grid))
    }

    fn load_grid(&self, s: &AnyScenario) -> PyResult<Option<OccupancyGrid>> {
        let dir = &self.dir;
        s.load_grid(&mut |rel: &str| planlab_files::read_map_file(&dir.join(rel)))
            .map_err(err::<ScenarioError>)
    }

    fn robot(&self) -> PyResult<(&CoreScenario, OccupancyGrid)> {
        let AnyScenario::Robot(s) = &self.parsed else {
            return Err(err::<ScenarioError>(format!(
                "{} scenarios have no batch variants or episodes to step",
                self.parsed.kind().name()
            )));
        };
        let grid = self
            .load_grid(&self.parsed)?
            .ok_or_else(|| err::<ScenarioError>("the scenario's map could not be loaded"))?;
        Ok((s, grid))
    }
}

#[pymethods]
impl Scenario {
    /// Reads a scenario `.json` (any kind); a map file it names is found
    /// relative to it.
    #[staticmethod]
    fn from_file(path: PathBuf) -> PyResult<Scenario> {
        let text = planlab_files::read_text(&path).map_err(err::<ScenarioError>)?;
        let at =
            |e: &dyn std::fmt::Display| err::<ScenarioError>(format!("{}: {e}", path.display()));
        // Parsed from the text so errors point at the file's lines.
        let parsed = AnyScenario::from_json(&text).map_err(|e| at(&e))?;
        let tree: Value = serde_json::from_str(&text).map_err(|e| at(&e))?;
        let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
        Ok(Scenario { tree, dir, parsed })
    }

    /// The scenario of a BARN world (`planlab run barn:N`): `source` is
    /// `barn:N` (one of the 250 worlds the package holds) or `barn:PATH`
    /// (a `world_N.world` file of a BARN checkout), driven by `planner`
    /// (default `move-base-dwa`) with `seed`.
    #[staticmethod]
    #[pyo3(signature = (source, planner = None, seed = None))]
    fn barn(source: &str, planner: Option<&str>, seed: Option<u64>) -> PyResult<Scenario> {
        let text = planlab_files::barn::scenario_json(source, planner, seed)
            .map_err(err::<ScenarioError>)?
            .ok_or_else(|| err::<ParamError>(format!("{source}: expected barn:N or barn:PATH")))?;
        let tree: Value = serde_json::from_str(&text).map_err(err::<ScenarioError>)?;
        Scenario::of_tree(tree, PathBuf::from("."))
    }

    /// A scenario from a dict (the JSON document); relative map files are
    /// found in `base_dir` (default: the working folder).
    #[staticmethod]
    #[pyo3(signature = (doc, base_dir = None))]
    fn from_dict(doc: &Bound<'_, PyAny>, base_dir: Option<PathBuf>) -> PyResult<Scenario> {
        Scenario::of_tree(
            from_py(doc)?,
            base_dir.unwrap_or_else(|| PathBuf::from(".")),
        )
    }

    /// The JSON document as a dict.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &self.tree)
    }

    /// The folder relative map files are read from.
    #[getter]
    fn base_dir(&self) -> PathBuf {
        self.dir.clone()
    }

    /// The same robot scenario with its map inline (no file references), so
    /// it can travel to another process or machine as a dict.
    fn inlined(&self) -> PyResult<Scenario> {
        let (s, grid) = self.robot()?;
        let s = s.clone().with_inline_grid(grid);
        let tree = serde_json::to_value(&s).map_err(err::<ScenarioError>)?;
        Scenario::of_tree(tree, self.dir.clone())
    }

    /// Variant `index` of `planlab batch --seed SEED --jitter JITTER`
    /// (start, goal and movers jittered, the episode seed the variant's;
    /// variant 0 is this scenario with that seed).
    #[pyo3(signature = (index, seed = 0, jitter = 0.3))]
    fn variant(&self, index: u32, seed: u64, jitter: f64) -> PyResult<Scenario> {
        let (base, grid) = self.robot()?;
        let v = batch::variant(base, &grid, index, seed, jitter).map_err(|e| match e {
            batch::BatchError::BadJitter(_) => err::<ParamError>(e),
            _ => err::<ScenarioError>(e),
        })?;
        let tree = serde_json::to_value(&v).map_err(err::<ScenarioError>)?;
        Scenario::of_tree(tree, self.dir.clone())
    }

    /// `robot`, `APF` or `arm`.
    #[getter]
    fn kind(&self) -> &'static str {
        self.parsed.kind().name()
    }

    #[getter]
    fn name(&self) -> String {
        self.parsed.name().to_string()
    }

    #[getter]
    fn seed(&self) -> u64 {
        self.parsed.seed()
    }

    /// Runs to the end, as `planlab run` does (same planner, seed and
    /// `set` edits: `{"sim.dt": 0.05}`). Returns a dict: `scenario`,
    /// `planner`, `seed`, `steps`, `trace_hash` (hex, `planlab run`'s),
    /// `metrics` (dict), with a `global_planner` section `global_path`
    /// (dict: `algorithm`, `length_m`, `cusps`, `expanded`, `replans`), and
    /// `trace` (dict of 1-D arrays; APF and arm runs:
    /// `path`, an (n, 3) array of points). `mcap`: also write a robot
    /// episode as an MCAP file there (`planlab run --mcap`: Foxglove
    /// schemas, JSON; pose, scan, paths, movers and map per step).
    #[pyo3(signature = (planner = None, seed = None, set = None, mcap = None))]
    fn run<'py>(
        &self,
        py: Python<'py>,
        planner: Option<&str>,
        seed: Option<u64>,
        set: Option<&Bound<'py, PyDict>>,
        mcap: Option<PathBuf>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let recipe = Recipe {
            planner: planner.map(str::to_string),
            seed,
            set: set_edits(set)?,
            variant: None,
        };
        let (scenario, grid) = self.edited(&recipe)?;
        // Other Python threads run meanwhile.
        let done = match &mcap {
            None => py
                .detach(|| scenario.start(grid).and_then(AnyRun::run))
                .map_err(err::<ScenarioError>)?,
            Some(out) => {
                let run = scenario.start(grid).map_err(err::<ScenarioError>)?;
                let AnyRun::Robot(mut ep) = run else {
                    return Err(err::<ScenarioError>(format!(
                        "mcap: {} runs have no MCAP export; only robot episodes",
                        scenario.kind().name()
                    )));
                };
                let bytes = py
                    .detach(|| planlab_mcap::record_episode(&mut ep))
                    .map_err(err::<ScenarioError>)?
                    .0;
                planlab_files::output::write_atomically(out, &bytes)
                    .map_err(pyo3::exceptions::PyOSError::new_err)?;
                let m = EpisodeMetrics::of_episode(&ep);
                FinishedRun::Robot(ep, m)
            }
        };
        let d = PyDict::new(py);
        d.set_item("scenario", scenario.name())?;
        d.set_item("trace_hash", format!("{:016x}", done.trace_hash()))?;
        match &done {
            FinishedRun::Robot(ep, m) => {
                d.set_item("planner", &ep.planner_choice().name)?;
                d.set_item("seed", scenario.seed())?;
                d.set_item("steps", ep.steps())?;
                d.set_item("metrics", to_py(py, m)?)?;
                d.set_item("trace", trace_columns(py, ep.trace())?)?;
                if let Some(c) = ep.car_guide() {
                    // As `planlab run --json`'s `global_path`.
                    let g = PyDict::new(py);
                    g.set_item("algorithm", "hybrid-astar")?;
                    g.set_item("length_m", c.route().length)?;
                    g.set_item("cusps", c.route().cusps)?;
                    g.set_item("expanded", c.route().expanded)?;
                    g.set_item("replans", c.replans())?;
                    d.set_item("global_path", g)?;
                }
            }
            FinishedRun::Apf(r, m) => {
                d.set_item("planner", format!("apf:{}", r.mode_label()))?;
                d.set_item("steps", r.steps())?;
                d.set_item("metrics", to_py(py, m)?)?;
                let pts: Vec<[f64; 3]> = r.path_xyz().iter().map(|p| [p.x, p.y, p.z]).collect();
                d.set_item("trace", points(py, &pts)?)?;
            }
            FinishedRun::Arm(ep, m) => {
                d.set_item("seed", scenario.seed())?;
                d.set_item("metrics", to_py(py, m)?)?;
                let pts: Vec<[f64; 3]> = ep.tool_path().iter().map(|p| [p.x, p.y, p.z]).collect();
                d.set_item("trace", points(py, &pts)?)?;
            }
        }
        Ok(d)
    }

    /// A robot episode to step: `ep.observe()`, `ep.step()` (the
    /// scenario's planner) or `ep.step(command=(v, omega))`. `lidar`
    /// configures the scan `observe` returns (`{"beams": 360, "range":
    /// 10.0, "noise_std": 0.0, "noise_seed": 0}`).
    #[pyo3(signature = (seed = None, planner = None, set = None, lidar = None))]
    fn episode(
        &self,
        seed: Option<u64>,
        planner: Option<&str>,
        set: Option<&Bound<'_, PyDict>>,
        lidar: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Episode> {
        let recipe = Recipe {
            planner: planner.map(str::to_string),
            seed,
            set: set_edits(set)?,
            variant: None,
        };
        let (scenario, grid) = self.edited(&recipe)?;
        let AnyScenario::Robot(s) = &scenario else {
            return Err(err::<ScenarioError>(format!(
                "{} scenarios run whole (Scenario.run); only robot episodes step",
                scenario.kind().name()
            )));
        };
        let grid =
            grid.ok_or_else(|| err::<ScenarioError>("the scenario's map could not be loaded"))?;
        let ep = CoreEpisode::from_scenario(s, grid).map_err(err::<ScenarioError>)?;
        let cfg = match lidar {
            None => LidarConfig::default(),
            Some(d) => {
                let mut v =
                    serde_json::to_value(LidarConfig::default()).map_err(err::<ParamError>)?;
                for (k, x) in from_py(d.as_any())?.as_object().into_iter().flatten() {
                    v[k] = x.clone();
                }
                planlab_core::params::parse_config::<LidarConfig>("lidar", &v)
                    .map_err(err::<ParamError>)?
            }
        };
        let lidar = Lidar::new(cfg, "lidar").map_err(err::<ParamError>)?;
        Ok(Episode {
            inner: Mutex::new(Stepped { ep, lidar }),
        })
    }

    fn __repr__(&self) -> String {
        format!("Scenario({:?}, kind={})", self.parsed.name(), self.kind())
    }
}

/// An (n, 3) array of points.
fn points<'py>(py: Python<'py>, pts: &[[f64; 3]]) -> PyResult<Bound<'py, PyDict>> {
    let flat: Vec<f64> = pts.iter().flatten().copied().collect();
    let d = PyDict::new(py);
    d.set_item("path", table(py, pts.len(), 3, flat)?)?;
    Ok(d)
}

/// The trace as columns, in the core's column order
/// ([`planlab_core::sim::TraceStep::columns`]): every number as a 1-D
/// float array (wheel loads NaN without a vehicle model), `goal_kind` and
/// `mode` as lists of str. The per-row mover and class lists are left out.
fn trace_columns<'py>(py: Python<'py>, trace: &Trace) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let Some(first) = trace.steps.first() else {
        return Ok(d);
    };
    let n = trace.steps.len();
    for (i, col) in first.columns().iter().enumerate() {
        let pick = |f: &dyn Fn(&Column<'_>) -> Option<f64>| -> Vec<f64> {
            trace
                .steps
                .iter()
                .map(|r| f(&r.columns()[i]).unwrap_or(f64::NAN))
                .collect()
        };
        match col {
            Column::Num(name, _) => {
                let v = pick(&|c| match c {
                    Column::Num(_, x) => Some(*x),
                    _ => None,
                });
                d.set_item(*name, PyArray1::from_vec(py, v))?;
            }
            Column::WheelLoads(_) => {
                for (w, name) in col.csv_names().iter().enumerate() {
                    let v = pick(&|c| match c {
                        Column::WheelLoads(l) => l.map(|l| l[w]),
                        _ => None,
                    });
                    d.set_item(*name, PyArray1::from_vec(py, v))?;
                }
            }
            Column::GoalKind(_) | Column::Mode(_) => {
                let mut v: Vec<String> = Vec::with_capacity(n);
                for r in &trace.steps {
                    v.push(match &r.columns()[i] {
                        Column::Mode(m) => m.to_string(),
                        Column::GoalKind(k) => serde_json::to_value(k)
                            .ok()
                            .and_then(|x| x.as_str().map(String::from))
                            .unwrap_or_default(),
                        _ => String::new(),
                    });
                }
                d.set_item(col.csv_names()[0], PyList::new(py, v)?)?;
            }
            Column::Classes(_) | Column::Movers(_) => {}
        }
    }
    Ok(d)
}

// ------------------------------------------------------------ episodes

/// A robot episode stepped from Python. Behind a mutex so any Python
/// thread may use it (a pyclass must be `Sync`; a planner is only `Send`).
#[pyclass(module = "planlab", frozen)]
struct Episode {
    inner: Mutex<Stepped>,
}

/// The episode and the sensor `observe` scans with.
struct Stepped {
    ep: CoreEpisode,
    lidar: Lidar,
}

impl Episode {
    fn lock(&self) -> MutexGuard<'_, Stepped> {
        // Nothing panics while the lock is held; a poisoned lock still
        // holds a consistent episode.
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }
}

#[pymethods]
impl Episode {
    /// What the robot knows now, as a dict of arrays: `t`, `pose` (x, y,
    /// θ), `velocity` (v, vy, ω), `goal` (x, y), `scan` (ranges, m; inf =
    /// no return), `scan_angles` (rad, robot frame), `movers` ((k, 6):
    /// id, x, y, vx, vy, radius of the movers within sensing range).
    fn observe<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let mut g = self.lock();
        let Stepped { ep, lidar } = &mut *g;
        let s = *ep.state();
        let scan = ep.scan(lidar);
        let n = scan.len();
        let d = PyDict::new(py);
        d.set_item("t", ep.time())?;
        d.set_item("pose", PyArray1::from_vec(py, vec![s.x, s.y, s.theta]))?;
        d.set_item("velocity", PyArray1::from_vec(py, vec![s.v, s.vy, s.w]))?;
        d.set_item("goal", PyArray1::from_vec(py, ep.goal().to_vec()))?;
        d.set_item("scan", PyArray1::from_vec(py, scan.ranges().to_vec()))?;
        let angles: Vec<f64> = (0..n).map(|i| scan.angle(i)).collect();
        d.set_item("scan_angles", PyArray1::from_vec(py, angles))?;
        let movers = ep.observed_movers();
        let flat: Vec<f64> = movers
            .iter()
            .flat_map(|m| {
                [
                    f64::from(m.id),
                    m.pos[0],
                    m.pos[1],
                    m.vel[0],
                    m.vel[1],
                    m.radius,
                ]
            })
            .collect();
        d.set_item("movers", table(py, movers.len(), 6, flat)?)?;
        Ok(d)
    }

    /// One control period: the scenario's planner, or `command` = (v, ω)
    /// or (v, vy, ω) (clamped to the robot's limits like a planner's).
    /// Returns the outcome: `running`, `reached`, `collision`, `timeout`,
    /// `stuck`.
    #[pyo3(signature = (command = None))]
    fn step(&self, command: Option<Vec<f64>>) -> PyResult<&'static str> {
        let mut g = self.lock();
        let ep = &mut g.ep;
        let o = match command.as_deref() {
            None => ep.step(),
            Some(&[v, w]) => ep
                .step_with(Command { v, vy: 0.0, w })
                .map_err(err::<ParamError>)?,
            Some(&[v, vy, w]) => ep
                .step_with(Command { v, vy, w })
                .map_err(err::<ParamError>)?,
            Some(other) => {
                return Err(err::<ParamError>(format!(
                    "command: expected (v, omega) or (v, vy, omega), got {} numbers",
                    other.len()
                )))
            }
        };
        Ok(o.as_str())
    }

    /// Steps with the scenario's planner until the episode ends.
    fn run(&self, py: Python<'_>) -> &'static str {
        py.detach(|| self.lock().ep.run().as_str())
    }

    #[getter]
    fn outcome(&self) -> &'static str {
        self.lock().ep.outcome().as_str()
    }

    #[getter]
    fn done(&self) -> bool {
        self.lock().ep.outcome() != Outcome::Running
    }

    #[getter]
    fn time(&self) -> f64 {
        self.lock().ep.time()
    }

    #[getter]
    fn steps(&self) -> u64 {
        self.lock().ep.steps()
    }

    #[getter]
    fn planner(&self) -> String {
        self.lock().ep.planner_choice().name.clone()
    }

    /// The map's extent in metres: (x_min, y_min, x_max, y_max).
    #[getter]
    fn bounds(&self) -> (f64, f64, f64, f64) {
        let b = self.lock().ep.map().bounds();
        (b[0], b[1], b[2], b[3])
    }

    /// The robot's limits and the control period: `v_min`, `v_max`,
    /// `vy_max`, `w_max`, `acc_v`, `acc_vy`, `acc_w`, `dt`, `goal_tolerance`,
    /// `max_time`, `radius` (circumscribed), `lidar_range`, `lidar_beams`.
    #[getter]
    fn limits<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let g = self.lock();
        let l = g.ep.robot().limits;
        let c = g.ep.config();
        let d = PyDict::new(py);
        for (k, v) in [
            ("v_min", l.v_min),
            ("v_max", l.v_max),
            ("vy_max", l.vy_max),
            ("w_max", l.w_max),
            ("acc_v", l.acc_v),
            ("acc_vy", l.acc_vy),
            ("acc_w", l.acc_w),
            ("dt", c.dt),
            ("goal_tolerance", c.goal_tolerance),
            ("max_time", c.max_time),
            ("radius", g.ep.robot().footprint.circumscribed_radius()),
            ("lidar_range", g.lidar.config().range),
            ("lidar_beams", f64::from(g.lidar.config().beams)),
        ] {
            d.set_item(k, v)?;
        }
        Ok(d)
    }

    /// The metrics the core computes from the trace so far (what `planlab
    /// run` prints once the episode has ended).
    fn metrics<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_py(py, &EpisodeMetrics::of_episode(&self.lock().ep))
    }

    /// The trace so far as columns (see `Scenario.run`).
    fn trace<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        trace_columns(py, self.lock().ep.trace())
    }

    /// FNV-1a of the trace so far, hex (`planlab run`'s once ended).
    fn trace_hash(&self) -> String {
        format!("{:016x}", self.lock().ep.trace().hash())
    }
}

// ---------------------------------------------------- batches, sweeps

/// Episodes of `planlab batch` on `scenario` (a robot or arm scenario):
/// for each variant index in `variants` and each planner in `planners`
/// (names; empty = the scenario's own), the episode `planlab batch --seed
/// SEED --jitter JITTER` runs for that row (jitter `None`: the kind's
/// default, 0.3 m for a robot, 0.02 m for an arm). Returns a list of dicts:
/// `variant`, `planner`, `seed`, `trace_hash` (hex), `metrics`, and a
/// robot's `steps`; an arm row's `metrics` is the whole run (outcome, path
/// lengths, hand distance, effort; [`summarise`] reads it). The GIL is
/// released while the episodes run, so threads run them in parallel.
#[pyfunction]
#[pyo3(signature = (scenario, variants, planners = Vec::new(), seed = 0, jitter = None))]
fn batch_episodes<'py>(
    py: Python<'py>,
    scenario: &Scenario,
    variants: Vec<i64>,
    planners: Vec<String>,
    seed: u64,
    jitter: Option<f64>,
) -> PyResult<Bound<'py, PyList>> {
    let jitter = jitter.unwrap_or_else(|| batch::default_jitter(scenario.parsed.kind()));
    if let AnyScenario::Arm(base) = &scenario.parsed {
        return arm_batch_episodes(py, base, variants, planners, seed, jitter);
    }
    let (base, grid) = scenario.robot()?;
    let choices = batch::planner_choices(base, &planners)
        .map_err(|e| err::<ParamError>(format!("planners: {e}")))?;
    let idx = variant_indices(variants)?;
    let runs = py.detach(|| -> Result<Vec<batch::BatchRun>, batch::BatchError> {
        let mut out = Vec::with_capacity(idx.len() * choices.len());
        for &k in &idx {
            let v = batch::variant(base, &grid, k, seed, jitter)?;
            for c in &choices {
                out.push(batch::run_variant(&v, &grid, k, c)?);
            }
        }
        Ok(out)
    });
    let runs = runs.map_err(batch_error)?;
    let list = PyList::empty(py);
    for r in &runs {
        let d = batch_row(py, r.variant, &r.planner, r.seed)?;
        d.set_item("steps", r.steps)?;
        d.set_item("trace_hash", format!("{:016x}", r.trace_hash))?;
        d.set_item("metrics", to_py(py, &r.metrics)?)?;
        list.append(d)?;
    }
    Ok(list)
}

/// A batch's error: a bad jitter is the caller's parameter, the rest the
/// scenario's.
fn batch_error(e: batch::BatchError) -> PyErr {
    match e {
        batch::BatchError::BadJitter(_) => err::<ParamError>(e),
        _ => err::<ScenarioError>(e),
    }
}

/// A batch row's dict with the keys every kind has.
fn batch_row<'py>(
    py: Python<'py>,
    variant: u32,
    planner: &str,
    seed: u64,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("variant", variant)?;
    d.set_item("planner", planner)?;
    d.set_item("seed", seed)?;
    Ok(d)
}

/// The variant indices of a batch, checked.
fn variant_indices(variants: Vec<i64>) -> PyResult<Vec<u32>> {
    variants
        .into_iter()
        .map(|v| match u32::try_from(v) {
            Ok(k) if k < batch::MAX_VARIANTS => Ok(k),
            _ => Err(err::<ParamError>(format!(
                "variant {v}: must be from 0 to {}",
                batch::MAX_VARIANTS - 1
            ))),
        })
        .collect()
}

/// [`batch_episodes`] of an arm scenario: the rows of `planlab batch` of an
/// arm file (the core's `batch::arm_variant` and `run_arm_variant`).
fn arm_batch_episodes<'py>(
    py: Python<'py>,
    base: &planlab_core::scenario::ArmScenario,
    variants: Vec<i64>,
    planners: Vec<String>,
    seed: u64,
    jitter: f64,
) -> PyResult<Bound<'py, PyList>> {
    let planners = batch::arm_planners(base, &planners)
        .map_err(|e| err::<ParamError>(format!("planners: {e}")))?;
    let idx = variant_indices(variants)?;
    let runs = py.detach(|| -> Result<Vec<batch::ArmBatchRun>, batch::BatchError> {
        let mut out = Vec::with_capacity(idx.len() * planners.len());
        for &k in &idx {
            let v = batch::arm_variant(base, k, seed, jitter)?;
            for &p in &planners {
                out.push(batch::run_arm_variant(&v, k, p)?);
            }
        }
        Ok(out)
    });
    let runs = runs.map_err(batch_error)?;
    let list = PyList::empty(py);
    for r in &runs {
        let d = batch_row(py, r.variant, &r.planner, r.seed)?;
        d.set_item("trace_hash", format!("{:016x}", r.trace_hash))?;
        d.set_item("metrics", to_py(py, r)?)?;
        list.append(d)?;
    }
    Ok(list)
}

// --------------------------------------------------------------- BARN

/// The BARN worlds: the package's 250 (`paths` empty) or those at `paths`
/// (BARN folders or `world_N.world` files).
fn barn_worlds(paths: &[PathBuf]) -> PyResult<Vec<planlab_core::barn::BarnWorld>> {
    if paths.is_empty() {
        return planlab_files::barn::builtin_worlds().map_err(err::<ScenarioError>);
    }
    let mut out = Vec::new();
    for p in paths {
        out.extend(planlab_files::barn::load_worlds(p).map_err(err::<ScenarioError>)?);
    }
    Ok(out)
}

/// The planners that can drive an unknown map on BARN (`planlab barn`'s
/// default list).
#[pyfunction]
fn barn_planners() -> Vec<&'static str> {
    planlab_core::barn::run::PLANNERS.to_vec()
}

/// The numbers of the BARN worlds at `paths` (default: the package's 250)
/// with their difficulty class and optimal time OT: a list of dicts
/// `world`, `difficulty`, `optimal_time`.
#[pyfunction]
#[pyo3(signature = (paths = Vec::new()))]
fn barn_worlds_info<'py>(py: Python<'py>, paths: Vec<PathBuf>) -> PyResult<Bound<'py, PyList>> {
    let list = PyList::empty(py);
    for w in barn_worlds(&paths)? {
        let d = PyDict::new(py);
        d.set_item("world", w.id)?;
        d.set_item("difficulty", w.difficulty().name())?;
        d.set_item("optimal_time", w.optimal_time())?;
        list.append(d)?;
    }
    Ok(list)
}

/// BARN runs (`planlab barn`'s episodes): each `(world, planner, run)` of
/// `jobs`, seeded as `planlab barn --seed SEED` seeds it, with laser noise
/// `noise` m. Returns one dict per run: `world`, `planner`, `run`, `seed`,
/// `outcome`, `time`, `optimal_time`, `score`, `path_length`,
/// `trace_hash` (hex), `difficulty`. The GIL is released while they run.
#[pyfunction]
#[pyo3(signature = (jobs, seed = 0, noise = planlab_core::barn::run::DEFAULT_NOISE, paths = Vec::new()))]
fn barn_runs<'py>(
    py: Python<'py>,
    jobs: Vec<(u32, String, u32)>,
    seed: u64,
    noise: f64,
    paths: Vec<PathBuf>,
) -> PyResult<Bound<'py, PyList>> {
    use planlab_core::barn::run as br;
    if !(noise.is_finite() && (0.0..=1.0).contains(&noise)) {
        return Err(err::<ParamError>(format!(
            "noise {noise}: must be from 0 to 1 m"
        )));
    }
    let worlds = barn_worlds(&paths)?;
    for (w, p, _) in &jobs {
        if !worlds.iter().any(|x| x.id == *w) {
            return Err(err::<ParamError>(format!(
                "world {w}: not among the BARN worlds loaded"
            )));
        }
        if !br::PLANNERS.contains(&p.as_str()) {
            return Err(err::<ParamError>(format!(
                "planner {p}: cannot drive an unknown map on BARN; choose from {}",
                br::PLANNERS.join(", ")
            )));
        }
    }
    let opts = br::BarnOptions { noise_std: noise };
    let runs = py.detach(
        || -> Result<Vec<(br::BarnRun, &'static str)>, br::RunError> {
            jobs.iter()
                .map(|(w, p, r)| {
                    let world = worlds.iter().find(|x| x.id == *w).expect("checked above");
                    let run = br::run_one(world, p, *r, br::run_seed(seed, *w, *r), &opts)?;
                    Ok((run, world.difficulty().name()))
                })
                .collect()
        },
    );
    let runs = runs.map_err(err::<ScenarioError>)?;
    let list = PyList::empty(py);
    for (r, class) in &runs {
        let d = PyDict::new(py);
        d.set_item("world", r.world)?;
        d.set_item("difficulty", *class)?;
        d.set_item("planner", &r.planner)?;
        d.set_item("run", r.run)?;
        d.set_item("seed", r.seed)?;
        d.set_item("outcome", r.outcome.as_str())?;
        d.set_item("time", r.time)?;
        d.set_item("optimal_time", r.optimal_time)?;
        d.set_item("score", r.score)?;
        d.set_item("path_length", r.path_length)?;
        d.set_item("trace_hash", format!("{:016x}", r.trace_hash))?;
        d.set_item("collision_seen", r.collision_seen)?;
        list.append(d)?;
    }
    Ok(list)
}

/// The figures of BARN runs of one planner (`planlab barn --json`'s
/// lines): `runs` is a list of the dicts [`barn_runs`] returns.
#[pyfunction]
fn barn_stats<'py>(py: Python<'py>, runs: &Bound<'py, PyList>) -> PyResult<Bound<'py, PyAny>> {
    use planlab_core::barn::run as br;
    let mut rows = Vec::with_capacity(runs.len());
    for item in runs.iter() {
        let get = |k: &str| -> PyResult<Bound<'py, PyAny>> {
            item.get_item(k)
                .map_err(|_| err::<ParamError>(format!("runs: each run needs `{k}`")))
        };
        let outcome: String = get("outcome")?.extract()?;
        let outcome = match outcome.as_str() {
            "reached" => planlab_core::world::Outcome::Reached,
            "collision" => planlab_core::world::Outcome::Collision,
            "timeout" | "stuck" => planlab_core::world::Outcome::Timeout,
            o => return Err(err::<ParamError>(format!("runs: unknown outcome {o}"))),
        };
        rows.push(br::BarnRun {
            world: get("world")?.extract()?,
            planner: get("planner")?.extract()?,
            run: get("run")?.extract()?,
            seed: get("seed")?.extract()?,
            outcome,
            time: get("time")?.extract()?,
            optimal_time: get("optimal_time")?.extract()?,
            score: get("score")?.extract()?,
            path_length: get("path_length")?.extract()?,
            trace_hash: 0,
            collision_seen: match item.get_item("collision_seen") {
                Ok(v) => v.extract()?,
                Err(_) => None,
            },
        });
    }
    to_py(py, &br::BarnStats::of(rows.iter()))
}

/// Per-planner statistics of batch runs (`planlab batch --json`'s summary
/// lines): `runs` is a list of metrics dicts of one planner — a robot's,
/// or an arm row's whole run (told apart by its `joint_path_length_rad`;
/// without the CLI's compute time).
#[pyfunction]
fn summarise<'py>(
    py: Python<'py>,
    planner: &str,
    runs: &Bound<'py, PyList>,
) -> PyResult<Bound<'py, PyAny>> {
    let tree = from_py(runs.as_any())?;
    let arm = tree
        .get(0)
        .is_some_and(|r| r.get("joint_path_length_rad").is_some());
    if arm {
        let runs: Vec<batch::ArmBatchRun> =
            serde_json::from_value(tree).map_err(err::<ParamError>)?;
        return to_py(py, &batch::summarise_arm(planner, &runs, &[]));
    }
    let runs: Vec<EpisodeMetrics> = serde_json::from_value(tree).map_err(err::<ParamError>)?;
    to_py(py, &batch::summarise(planner, &runs))
}

/// The largest batch (`planlab batch --variants`).
#[pyfunction]
fn max_variants() -> u32 {
    batch::MAX_VARIANTS
}

// ----------------------------------------------------------- reproduce

fn reproduce_one<M: RunMetrics + serde::Serialize>(
    exp: &Experiment<M>,
    variants: Option<u32>,
    seed: u64,
) -> Result<Value, String> {
    let at = |e: &dyn std::fmt::Display| format!("{}: {e}", exp.id);
    match variants {
        None => {
            let r = reproduce::run(exp).map_err(|e| at(&e))?;
            serde_json::to_value(&r).map_err(|e| e.to_string())
        }
        Some(n) => {
            let results = (0..n)
                .map(|k| reproduce::run_variant(exp, seed, k, &[]))
                .collect::<Result<Vec<_>, _>>()
                .map_err(|e| at(&e))?;
            let f = reproduce::summarise(exp, seed, None, &results);
            serde_json::to_value(&f).map_err(|e| e.to_string())
        }
    }
}

/// One of the papers' experiments, as `planlab reproduce ID --json`
/// prints it: the presets, or with `variants=N` the family of N seeded
/// variants (success rates, clauses, verdict).
#[pyfunction(name = "reproduce")]
#[pyo3(signature = (id, variants = None, seed = 0))]
fn reproduce_experiment<'py>(
    py: Python<'py>,
    id: &str,
    variants: Option<u32>,
    seed: u64,
) -> PyResult<Bound<'py, PyAny>> {
    if let Some(n) = variants {
        if n == 0 || n > reproduce::MAX_VARIANTS {
            return Err(err::<ParamError>(format!(
                "variants {n}: give 1 to {} (the preset is variant 0)",
                reproduce::MAX_VARIANTS
            )));
        }
    }
    let out = py.detach(|| {
        if let Some(e) = reproduce::find(id) {
            reproduce_one(&e, variants, seed)
        } else if let Some(e) = reproduce::find_path(id) {
            reproduce_one(&e, variants, seed)
        } else {
            Err(format!(
                "unknown experiment `{id}`; known ids: {}",
                reproduce::ids().join(", ")
            ))
        }
    });
    let v = out.map_err(|e| {
        if e.starts_with("unknown experiment") {
            err::<ParamError>(e)
        } else {
            err::<ScenarioError>(e)
        }
    })?;
    to_py(py, &v)
}

/// The experiments' ids, in `planlab reproduce` order.
#[pyfunction]
fn reproduce_ids() -> Vec<&'static str> {
    reproduce::ids()
}

#[pymodule]
fn _planlab(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("PlanlabError", py.get_type::<PlanlabError>())?;
    m.add("MapError", py.get_type::<MapError>())?;
    m.add("ScenarioError", py.get_type::<ScenarioError>())?;
    m.add("PlanError", py.get_type::<PlanError>())?;
    m.add("ParamError", py.get_type::<ParamError>())?;
    m.add_class::<Grid>()?;
    m.add_class::<Scenario>()?;
    m.add_class::<Episode>()?;
    m.add_function(wrap_pyfunction!(load_map, m)?)?;
    m.add_function(wrap_pyfunction!(load_scen, m)?)?;
    m.add_function(wrap_pyfunction!(plan, m)?)?;
    m.add_function(wrap_pyfunction!(plan_car, m)?)?;
    m.add_function(wrap_pyfunction!(dubins, m)?)?;
    m.add_function(wrap_pyfunction!(reeds_shepp, m)?)?;
    m.add_function(wrap_pyfunction!(algorithms, m)?)?;
    m.add_function(wrap_pyfunction!(sampling_algorithms, m)?)?;
    m.add_function(wrap_pyfunction!(planner_catalogue, m)?)?;
    m.add_function(wrap_pyfunction!(batch_episodes, m)?)?;
    m.add_function(wrap_pyfunction!(summarise, m)?)?;
    m.add_function(wrap_pyfunction!(max_variants, m)?)?;
    m.add_function(wrap_pyfunction!(barn_runs, m)?)?;
    m.add_function(wrap_pyfunction!(barn_planners, m)?)?;
    m.add_function(wrap_pyfunction!(barn_stats, m)?)?;
    m.add_function(wrap_pyfunction!(barn_worlds_info, m)?)?;
    m.add_function(wrap_pyfunction!(reproduce_experiment, m)?)?;
    m.add_function(wrap_pyfunction!(reproduce_ids, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
