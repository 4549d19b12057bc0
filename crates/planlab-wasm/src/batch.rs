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

#[cfg(test)]
mod tests {
    use super::*;
    use planlab_core::global::plan::Algorithm;

    const ARENA: &str = include_str!("../../../assets/maps/arena.map");
    /// Three rows of the Moving AI `arena.map.scen` (buckets 3, 9, 15).
    const SCEN: &str = "version 1\n3\tmaps/dao/arena.map\t49\t49\t1\t10\t11\t19\t13.7279\n9\tmaps/dao/arena.map\t49\t49\t1\t10\t15\t43\t38.799\n15\tmaps/dao/arena.map\t49\t49\t1\t3\t41\t47\t60.5685\n";

    #[test]
    fn solves_every_row_to_the_scenario_optimum() {
        let map = movingai::parse_map(ARENA).unwrap();
        for algorithm in [Algorithm::AStar, Algorithm::Dijkstra, Algorithm::Jps] {
            let options = GridPlanOptions {
                algorithm,
                ..Default::default()
            };
            let batch = Batch::new(&map, SCEN, &options).unwrap();
            assert_eq!(batch.len(), 3);
            let total = batch.solve_all().unwrap();
            // .scen optima are printed to 4 decimals.
            assert!(
                (total - batch.optimal_sum()).abs() < 3e-4,
                "{algorithm:?}: {total} vs {}",
                batch.optimal_sum()
            );
        }
    }

    #[test]
    fn a_blocked_query_names_its_row() {
        let map = movingai::parse_map(ARENA).unwrap();
        // Row 2 starts on the border wall (0, 0).
        let scen = "version 1\n0\tarena.map\t49\t49\t1\t11\t1\t12\t1\n0\tarena.map\t49\t49\t0\t0\t1\t12\t1\n";
        let err = match Batch::new(&map, scen, &GridPlanOptions::default()) {
            Ok(batch) => batch.solve_all().unwrap_err().to_string(),
            Err(e) => e.to_string(),
        };
        assert!(err.contains('2') && err.contains("(0, 0)"), "{err}");
    }
}
