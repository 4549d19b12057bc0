//! `planlab bench grid`: our A* and JPS against the `pathfinding` crate's
//! `astar` on the same Moving AI rows, all three checked against the optimum.

use crate::peer::pathfinding_cost;
use planlab_core::global::astar::{AStar, AStarConfig};
use planlab_core::global::jps::{Jps, JpsConfig};
use planlab_core::global::{GridPlanner, PlanGrid};
use planlab_core::map::io::movingai::ScenRow;
use planlab_core::map::OccupancyGrid;
use serde::Serialize;
use std::time::Instant;

/// Milliseconds per query of each planner and the ratios.
#[derive(Debug, Serialize)]
pub struct BenchReport {
    /// Rows solved per repetition.
    pub rows: usize,
    /// Our A*, ms per query.
    pub astar_ms: f64,
    /// Our JPS, ms per query.
    pub jps_ms: f64,
    /// `pathfinding::directed::astar::astar`, ms per query.
    pub pathfinding_ms: f64,
    /// pathfinding_ms / astar_ms.
    pub astar_speedup: f64,
    /// astar_ms / jps_ms.
    pub jps_speedup: f64,
}

/// Least time each planner is timed for, over all repetitions (s).
const MIN_SECONDS: f64 = 0.2;

fn matches(cost: f64, optimal: f64) -> bool {
    (cost - optimal).abs() <= 1e-3 * optimal.max(1.0)
}

/// Runs the three planners over `rows` `reps` times each, and more until
/// each has run for [`MIN_SECONDS`] (the fastest repetition counts), and
/// checks every cost against the row's optimum.
pub fn bench_grid(
    grid: &OccupancyGrid,
    rows: &[ScenRow],
    reps: usize,
) -> Result<BenchReport, String> {
    if rows.is_empty() {
        return Err("the scenario has no rows".into());
    }
    let plan_grid = PlanGrid::new(grid, false);
    let astar = AStar::new(AStarConfig::default()).map_err(|e| e.to_string())?;
    let jps = Jps::new(JpsConfig::default()).map_err(|e| e.to_string())?;
    let check = |name: &str, i: usize, cost: Option<f64>| -> Result<(), String> {
        match cost {
            Some(c) if matches(c, rows[i].optimal) => Ok(()),
            other => Err(format!(
                "{name} row {i}: cost {other:?} differs from the optimum {}",
                rows[i].optimal
            )),
        }
    };
    let time = |name: &str, solve: &dyn Fn(&ScenRow) -> Option<f64>| -> Result<f64, String> {
        let (mut best, mut total, mut done) = (f64::INFINITY, 0.0, 0);
        // A small row set takes well under a millisecond, a window in which
        // a shared machine's noise dominates: repeat it until the planner has
        // run for MIN_SECONDS too, the same for every planner.
        while done < reps.max(1) || total < MIN_SECONDS {
            let t = Instant::now();
            for (i, row) in rows.iter().enumerate() {
                check(name, i, solve(row))?;
            }
            let elapsed = t.elapsed().as_secs_f64();
            best = best.min(elapsed);
            total += elapsed;
            done += 1;
        }
        Ok(best * 1e3 / rows.len() as f64)
    };
    let astar_ms = time("A*", &|r| {
        astar.plan(&plan_grid, r.start, r.goal).ok().map(|p| p.cost)
    })?;
    let jps_ms = time("JPS", &|r| {
        jps.plan(&plan_grid, r.start, r.goal).ok().map(|p| p.cost)
    })?;
    let pathfinding_ms = time("pathfinding astar", &|r| {
        pathfinding_cost(&plan_grid, r.start, r.goal)
    })?;
    Ok(BenchReport {
        rows: rows.len(),
        astar_ms,
        jps_ms,
        pathfinding_ms,
        astar_speedup: pathfinding_ms / astar_ms,
        jps_speedup: astar_ms / jps_ms,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use planlab_core::global::GridPos;

    #[test]
    fn peer_is_optimal_and_refuses_corner_cutting() {
        let g = OccupancyGrid::from_ascii("..\n#.\n").unwrap();
        let pg = PlanGrid::new(&g, false);
        let row = |s: (u32, u32), t: (u32, u32), optimal: f64| ScenRow {
            bucket: 0,
            map: String::new(),
            width: 2,
            height: 2,
            start: GridPos::new(s.0, s.1),
            goal: GridPos::new(t.0, t.1),
            optimal,
        };
        // (0,0) -> (1,1) may cut no corner: two straight moves.
        assert_eq!(
            pathfinding_cost(&pg, GridPos::new(0, 0), GridPos::new(1, 1)),
            Some(2.0)
        );
        let report = bench_grid(&g, &[row((0, 0), (1, 1), 2.0)], 1).unwrap();
        assert_eq!(report.rows, 1);
        // A wrong optimum is reported, not averaged away.
        let err = bench_grid(&g, &[row((0, 0), (1, 1), 1.5)], 1).unwrap_err();
        assert!(err.contains("row 0"), "{err}");
    }
}
