//! One call from a map and options to a planned path: inflation, the chosen
//! planner, key points and Bottom-Up feature nodes. The CLI, the wasm layer
//! and scenarios all go through [`plan_on_map`], so they agree exactly.

use super::astar::{AStar, AStarConfig};
use super::bottom_up::bottom_up;
use super::jps::{Jps, JpsConfig};
use super::keypoints::key_points;
use super::safe_astar::{safety_index, SafeAStar, SafeAStarConfig};
use super::{Diagonal, Endpoint, GridPlanner, GridPos, Heuristic, Path, PlanError, PlanGrid};
use crate::map::costmap::inflate;
use crate::map::{MapError, OccupancyGrid};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Which grid planner to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Algorithm {
    /// A* (docs/algorithms.md §grid), with the chosen heuristic and weight.
    #[default]
    #[serde(rename = "astar")]
    AStar,
    /// Dijkstra: A* with a zero heuristic.
    #[serde(rename = "dijkstra")]
    Dijkstra,
    /// Jump Point Search (8-connected, no corner cutting).
    #[serde(rename = "jps")]
    Jps,
    /// Safe A* of \[S\] §1 (24-neighbourhood, safety term).
    #[serde(rename = "safe-astar")]
    SafeAStar,
}

impl Algorithm {
    /// Every algorithm with its command-line / JSON name.
    pub const ALL: [(Algorithm, &'static str); 4] = [
        (Algorithm::AStar, "astar"),
        (Algorithm::Dijkstra, "dijkstra"),
        (Algorithm::Jps, "jps"),
        (Algorithm::SafeAStar, "safe-astar"),
    ];

    /// The command-line / JSON name.
    pub fn name(self) -> &'static str {
        Self::ALL
            .iter()
            .find(|(a, _)| *a == self)
            .map_or("astar", |(_, n)| n)
    }
}

impl std::str::FromStr for Algorithm {
    type Err = PlanError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .iter()
            .find(|(_, n)| n.eq_ignore_ascii_case(s))
            .map(|(a, _)| *a)
            .ok_or_else(|| {
                PlanError::InvalidConfig(format!(
                    "unknown algorithm {s:?}; expected one of astar, dijkstra, jps, safe-astar"
                ))
            })
    }
}

/// Everything that shapes a grid plan besides the map and the endpoints.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct GridPlanOptions {
    /// Planner to run.
    pub algorithm: Algorithm,
    /// A* / JPS heuristic (ignored by Dijkstra; safe A* has its own).
    pub heuristic: Heuristic,
    /// A* heuristic weight, ≥ 1 (1 = optimal).
    pub weight: f64,
    /// Diagonal move rule.
    pub diagonal: Diagonal,
    /// Treat unknown cells as free.
    pub allow_unknown: bool,
    /// Grow obstacles by this radius before planning, metres (0 = off).
    pub inflate_m: f64,
    /// Also extract key points (\[T\] §3.2.1) on the inflated map.
    pub keypoints: bool,
    /// Also run Bottom-Up segmentation (\[S\] §4.1) with this maximum error,
    /// in cells; `None` = off.
    pub bottom_up_eps: Option<f64>,
    /// Safe A* parameters (used when `algorithm` is safe A*).
    pub safe: SafeAStarConfig,
}

impl Default for GridPlanOptions {
    fn default() -> Self {
        Self {
            algorithm: Algorithm::AStar,
            heuristic: Heuristic::Octile,
            weight: 1.0,
            diagonal: Diagonal::NoCornerCutting,
            allow_unknown: false,
            inflate_m: 0.0,
            keypoints: false,
            bottom_up_eps: None,
            safe: SafeAStarConfig::default(),
        }
    }
}

/// Changes to a map's or scenario's grid plan options: the `planlab plan`
/// flags, the Python `plan` keywords. `None` / `false` keep the value.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GridPlanOverrides {
    /// Planner to run.
    pub algorithm: Option<Algorithm>,
    /// A* / JPS heuristic.
    pub heuristic: Option<Heuristic>,
    /// A* heuristic weight.
    pub weight: Option<f64>,
    /// Diagonal move rule.
    pub diagonal: Option<Diagonal>,
    /// Inflation radius, metres (checked: finite, ≥ 0).
    pub inflate_m: Option<f64>,
    /// Also treat unknown cells as free.
    pub allow_unknown: bool,
    /// Also extract key points.
    pub keypoints: bool,
    /// Bottom-Up maximum error, cells.
    pub bottom_up_eps: Option<f64>,
    /// Safe A* ε.
    pub epsilon: Option<f64>,
}

impl GridPlanOptions {
    /// These options with `o` applied. The inflation radius is checked
    /// here (`InvalidConfig("inflate …")`, the caller names its flag); the
    /// other values when a planner is built from the options.
    pub fn overridden(mut self, o: &GridPlanOverrides) -> Result<GridPlanOptions, PlanError> {
        if let Some(a) = o.algorithm {
            self.algorithm = a;
        }
        if let Some(h) = o.heuristic {
            self.heuristic = h;
        }
        if let Some(w) = o.weight {
            self.weight = w;
        }
        if let Some(d) = o.diagonal {
            self.diagonal = d;
        }
        if let Some(r) = o.inflate_m {
            if !(r.is_finite() && r >= 0.0) {
                return Err(PlanError::InvalidConfig(format!(
                    "inflate {}: must be a finite number ≥ 0 (metres)",
                    crate::num::fmt_num(r)
                )));
            }
            self.inflate_m = r;
        }
        self.allow_unknown |= o.allow_unknown;
        self.keypoints |= o.keypoints;
        if o.bottom_up_eps.is_some() {
            self.bottom_up_eps = o.bottom_up_eps;
        }
        if let Some(eps) = o.epsilon {
            self.safe.epsilon = eps;
        }
        Ok(self)
    }
}

/// A plan with everything the CLI and the page show.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GridPlan {
    /// The path; `cost` in cells.
    pub path: Path,
    /// Path length in metres (cost × resolution).
    pub length_m: f64,
    /// Key points, when asked for (else empty).
    pub keypoints: Vec<GridPos>,
    /// Bottom-Up feature nodes, when asked for (else empty).
    pub feature_nodes: Vec<GridPos>,
    /// Expanded cells in order, when recording was asked for (else empty).
    pub expanded_cells: Vec<GridPos>,
    /// Safety index per path node, for safe A* (else empty).
    pub safety: Vec<f64>,
}

/// Why [`plan_on_map`] failed.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum GridPlanError {
    /// The planner refused or found no path.
    #[error(transparent)]
    Plan(#[from] PlanError),
    /// Inflation refused its radius.
    #[error(transparent)]
    Map(#[from] MapError),
    /// The endpoint is free on the map but inside the inflated obstacles.
    #[error(
        "{which} ({col}, {row}) is within {} m of an obstacle: blocked after inflation", crate::num::fmt_num(*.inflate_m)
    )]
    BlockedByInflation {
        /// Start or goal.
        which: Endpoint,
        /// Column.
        col: u32,
        /// Row.
        row: u32,
        /// The inflation radius, metres.
        inflate_m: f64,
    },
}

/// Builds the boxed planner `options` ask for.
pub fn build_planner(options: &GridPlanOptions) -> Result<Box<dyn GridPlanner>, PlanError> {
    Ok(match options.algorithm {
        Algorithm::AStar => Box::new(AStar::new(AStarConfig {
            heuristic: options.heuristic,
            weight: options.weight,
            diagonal: options.diagonal,
        })?),
        Algorithm::Dijkstra => Box::new(AStar::dijkstra(options.diagonal)),
        Algorithm::Jps => Box::new(Jps::new(JpsConfig {
            heuristic: options.heuristic,
            diagonal: options.diagonal,
        })?),
        Algorithm::SafeAStar => Box::new(SafeAStar::new(options.safe)?),
    })
}

/// The passability grid `options` imply: unknown cells per
/// `allow_unknown`, obstacles grown by `inflate_m`.
pub fn plan_grid_for(
    grid: &OccupancyGrid,
    options: &GridPlanOptions,
) -> Result<PlanGrid, GridPlanError> {
    if options.inflate_m == 0.0 {
        return Ok(PlanGrid::new(grid, options.allow_unknown));
    }
    let inflated = inflate(grid, options.inflate_m)?;
    Ok(PlanGrid::new(&inflated, options.allow_unknown))
}

/// Plans from `start` to `goal` on `grid` as `options` say; when
/// `record_expanded`, the expanded cells are returned for drawing.
///
/// ```
/// use planlab_core::global::plan::{plan_on_map, Algorithm, GridPlanOptions};
/// use planlab_core::global::GridPos;
/// use planlab_core::map::OccupancyGrid;
/// let map = OccupancyGrid::from_ascii("
/// .....
/// .###.
/// .#...
/// ").unwrap();
/// let opts = GridPlanOptions { algorithm: Algorithm::Jps, keypoints: true, ..Default::default() };
/// let plan = plan_on_map(&map, GridPos::new(0, 1), GridPos::new(4, 1), &opts, false).unwrap();
/// // No corner cutting: round the walls through the top row.
/// assert_eq!(plan.path.cost, 6.0);
/// assert_eq!(plan.keypoints, vec![GridPos::new(0, 1), GridPos::new(0, 0), GridPos::new(4, 0), GridPos::new(4, 1)]);
/// ```
pub fn plan_on_map(
    grid: &OccupancyGrid,
    start: GridPos,
    goal: GridPos,
    options: &GridPlanOptions,
    record_expanded: bool,
) -> Result<GridPlan, GridPlanError> {
    let planner = checked_planner(options)?;
    let plan_grid = plan_grid_for(grid, options)?;
    plan_prepared(
        grid,
        &plan_grid,
        &*planner,
        start,
        goal,
        options,
        record_expanded,
    )
}

/// [`plan_on_map`] on a passability grid built beforehand, so many queries
/// on one map (the Python package's `plan`, a benchmark) build it once.
/// `plan_grid` must be [`plan_grid_for`]`(grid, options)`; the result is
/// then exactly [`plan_on_map`]'s.
pub fn plan_on_plan_grid(
    grid: &OccupancyGrid,
    plan_grid: &PlanGrid,
    start: GridPos,
    goal: GridPos,
    options: &GridPlanOptions,
    record_expanded: bool,
) -> Result<GridPlan, GridPlanError> {
    let planner = checked_planner(options)?;
    plan_prepared(
        grid,
        plan_grid,
        &*planner,
        start,
        goal,
        options,
        record_expanded,
    )
}

/// The planner of `options`, after checking the options the planner does
/// not check itself.
fn checked_planner(options: &GridPlanOptions) -> Result<Box<dyn GridPlanner>, GridPlanError> {
    let planner = build_planner(options)?;
    if let Some(eps) = options.bottom_up_eps {
        if !(eps.is_finite() && eps >= 0.0) {
            return Err(PlanError::InvalidConfig(format!(
                "Bottom-Up maximum error {eps} must be a finite number ≥ 0 (cells)"
            ))
            .into());
        }
    }
    Ok(planner)
}

/// The plan itself: endpoints, search, key points, feature nodes, safety.
fn plan_prepared(
    grid: &OccupancyGrid,
    plan_grid: &PlanGrid,
    planner: &dyn GridPlanner,
    start: GridPos,
    goal: GridPos,
    options: &GridPlanOptions,
    record_expanded: bool,
) -> Result<GridPlan, GridPlanError> {
    if let Err(e) = plan_grid.check_endpoints(start, goal) {
        // Say "blocked after inflation" rather than a bare "inside an
        // obstacle" when the raw map has the endpoint free.
        if let PlanError::Blocked { which, col, row } = e {
            let raw_free = grid
                .get(col as usize, row as usize)
                .is_some_and(|c| c.passable(options.allow_unknown));
            if raw_free && options.inflate_m > 0.0 {
                return Err(GridPlanError::BlockedByInflation {
                    which,
                    col,
                    row,
                    inflate_m: options.inflate_m,
                });
            }
        }
        return Err(e.into());
    }
    let mut expanded = Vec::new();
    let path = planner.plan_recording(
        plan_grid,
        start,
        goal,
        record_expanded.then_some(&mut expanded),
    )?;
    let keypoints = if options.keypoints {
        key_points(plan_grid, &path.cells, options.diagonal)
    } else {
        Vec::new()
    };
    let feature_nodes = match options.bottom_up_eps {
        Some(eps) => bottom_up(plan_grid, &path.cells, eps, options.diagonal)?,
        None => Vec::new(),
    };
    let safety = if options.algorithm == Algorithm::SafeAStar {
        safety_index(plan_grid, &path.cells, options.safe.window_radius)
    } else {
        Vec::new()
    };
    Ok(GridPlan {
        length_m: path.cost * grid.resolution(),
        path,
        keypoints,
        feature_nodes,
        expanded_cells: expanded,
        safety,
    })
}
