//! A Moving AI scenario solved in one call: the unit both the browser (timed
//! with `performance.now()` around [`Batch::solve_all`]) and the native
//! `examples/bench_native.rs` (timed with `Instant`) measure, so the
//! wasm-vs-native ratio compares the same Rust code.

use planlab_core::global::plan::{build_planner, plan_grid_for, GridPlanError, GridPlanOptions};
use planlab_core::global::{GridPlanner, GridPos, PlanError, PlanGrid};
use planlab_core::map::io::movingai;
use planlab_core::map::{MapError, OccupancyGrid};
use thiserror::Error;

/// Why a batch could not be built or solved.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum BatchError {
    /// The `.scen` is malformed or does not fit the map.
    #[error(transparent)]
    Map(#[from] MapError),
    /// The options are invalid or a query failed.
    #[error(transparent)]
    Plan(#[from] PlanError),
    /// The plan grid could not be built (e.g. a bad inflation radius).
    #[error(transparent)]
    Grid(#[from] GridPlanError),
    /// A query failed; `row` is 1-based.
    #[error("scenario query {row}: {source}")]
    Query {
        /// 1-based query number.
        row: usize,
        /// The planner's error.
        source: PlanError,
    },
}

/// Queries of one `.scen` with the planner and passability grid built once.
pub struct Batch {
    grid: PlanGrid,
    planner: Box<dyn GridPlanner>,
    queries: Vec<(GridPos, GridPos)>,
    optimal_sum: f64,
}

impl Batch {
    /// Parses `scen_text`, checks it against `map` and builds the planner.
    pub fn new(
        map: &OccupancyGrid,
        scen_text: &str,
        options: &GridPlanOptions,
    ) -> Result<Self, BatchError> {
        let rows = movingai::parse_scen(scen_text)?;
        movingai::check_scen_against_map(&rows, map)?;
        Ok(Self {
            grid: plan_grid_for(map, options)?,
            planner: build_planner(options)?,
            optimal_sum: rows.iter().map(|r| r.optimal).sum(),
            queries: rows.iter().map(|r| (r.start, r.goal)).collect(),
        })
    }

    /// Number of queries.
    pub fn len(&self) -> usize {
        self.queries.len()
    }

    /// Whether there are no queries.
    pub fn is_empty(&self) -> bool {
        self.queries.is_empty()
    }

    /// Sum of the scenario's optimal lengths, to check [`Batch::solve_all`].
    pub fn optimal_sum(&self) -> f64 {
        self.optimal_sum
    }

    /// Plans every query once; the summed path cost.
    pub fn solve_all(&self) -> Result<f64, BatchError> {
        let mut total = 0.0;
        for (i, &(s, g)) in self.queries.iter().enumerate() {
            let path = self
                .planner
                .plan(&self.grid, s, g)
                .map_err(|source| BatchError::Query { row: i + 1, source })?;
            total += path.cost;
        }
        Ok(total)
    }
}
