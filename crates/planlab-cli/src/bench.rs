//! `planlab bench grid`: our A* and JPS against the `pathfinding` crate's
//! `astar` on the same Moving AI rows, all three checked against the optimum;
//! `planlab bench sampling`: the sampling planners against Theta* on sampled
//! Moving AI rows; `bench step` and `bench scen`, the browser benchmark's
//! native side.

use crate::peer::pathfinding_cost;
use planlab_core::global::astar::{AStar, AStarConfig};
use planlab_core::global::classic::ThetaStar;
use planlab_core::global::jps::{Jps, JpsConfig};
use planlab_core::global::plan::{build_planner, Algorithm, GridPlanOptions};
use planlab_core::global::{GridPlanner, Path, PlanError, PlanGrid};
use planlab_core::map::io::movingai::ScenRow;
use planlab_core::map::OccupancyGrid;
use planlab_core::sampling::{
    cell_centre, DiscSpace, SamplingAlgorithm, SamplingOptions, SamplingPlanner, MAX_ITERATIONS,
};
use serde::Serialize;
use std::sync::Arc;
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
    /// Every other planner of `planlab plan --algo`, on the same rows.
    pub planners: Vec<PlannerRow>,
}

/// One more planner's figures in [`BenchReport`].
#[derive(Debug, Serialize)]
pub struct PlannerRow {
    /// The `--algo` name.
    pub algo: &'static str,
    /// Rows it ran (IDA* runs only the short ones, see [`IDA_MAX_OPTIMAL`]).
    pub rows: usize,
    /// Rows it solved (IDA* may stop at its search limit).
    pub solved: usize,
    /// ms per query.
    pub ms: f64,
    /// ms / A*'s ms in this run.
    pub ratio_to_astar: f64,
    /// Mean cells expanded per solved query.
    pub expanded: f64,
    /// Mean cost / optimum over solved queries (1 = optimal).
    pub cost_ratio: f64,
    /// Preprocessing a fresh copy of the map before its first query (JPS+'s
    /// jump table; fastest of three), ms; not part of `ms`, which times
    /// queries on a map already prepared.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub setup_ms: Option<f64>,
}

/// IDA* is timed only on rows whose optimum is below this (cells): longer
/// ones mostly end at its search limit, after seconds each.
pub const IDA_MAX_OPTIMAL: f64 = 40.0;

/// Least time each planner is timed for, over all repetitions (s).
const MIN_SECONDS: f64 = 0.2;

fn matches(cost: f64, optimal: f64) -> bool {
    (cost - optimal).abs() <= 1e-3 * optimal.max(1.0)
}

/// Runs the three planners over `rows` `reps` times each, and more until
/// each has run for [`MIN_SECONDS`] (the fastest repetition counts), and
/// checks every cost against the row's optimum; then each planner of
/// `only` (every other `--algo` planner when empty) as a [`PlannerRow`].
pub fn bench_grid(
    grid: &OccupancyGrid,
    rows: &[ScenRow],
    reps: usize,
    only: &[Algorithm],
) -> Result<BenchReport, String> {
    check_count("--reps", reps, MAX_BENCH_REPS)?;
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
    let mut planners = Vec::new();
    for (algo, name) in Algorithm::ALL {
        if matches!(algo, Algorithm::AStar | Algorithm::Jps)
            || !(only.is_empty() || only.contains(&algo))
        {
            continue;
        }
        let options = GridPlanOptions {
            algorithm: algo,
            ..GridPlanOptions::default()
        };
        let planner = build_planner(&options).map_err(|e| e.to_string())?;
        let subset: Vec<&ScenRow> = rows
            .iter()
            .filter(|r| algo != Algorithm::IdaStar || r.optimal < IDA_MAX_OPTIMAL)
            .collect();
        if subset.is_empty() {
            continue;
        }
        // One untimed pass: answers and expansions, each checked.
        let (mut solved, mut expanded, mut ratio) = (0usize, 0usize, 0.0);
        for (i, r) in subset.iter().enumerate() {
            match planner.plan(&plan_grid, r.start, r.goal) {
                Ok(p) => {
                    // Optimal planners give the row's optimum; the others
                    // any legal path, which no shorter than the straight
                    // line (Theta* and safe A*'s smoothed paths cut corners,
                    // so they may beat the 8-connected optimum).
                    let ok = if algo.optimal() {
                        matches(p.cost, r.optimal)
                    } else {
                        p.cost >= Path::polyline_length(&[r.start, r.goal]) - 1e-9
                    };
                    if !ok {
                        return Err(format!(
                            "{name} row {i}: cost {} against the optimum {}",
                            p.cost, r.optimal
                        ));
                    }
                    solved += 1;
                    expanded += p.expanded;
                    ratio += p.cost / r.optimal.max(1e-9);
                }
                Err(PlanError::SearchLimit { .. }) if algo == Algorithm::IdaStar => {}
                Err(e) => return Err(format!("{name} row {i}: {e}")),
            }
        }
        let (mut best, mut total, mut done) = (f64::INFINITY, 0.0, 0);
        while done < reps.max(1) || total < MIN_SECONDS {
            let t = Instant::now();
            for r in &subset {
                std::hint::black_box(planner.plan(&plan_grid, r.start, r.goal).ok());
            }
            let elapsed = t.elapsed().as_secs_f64();
            best = best.min(elapsed);
            total += elapsed;
            done += 1;
        }
        let ms = best * 1e3 / subset.len() as f64;
        let setup_ms = if algo == Algorithm::JpsPlus {
            let mut fastest = f64::INFINITY;
            for _ in 0..3 {
                let fresh = PlanGrid::new(grid, false);
                let t = Instant::now();
                fresh.build_jps_plus_table().map_err(|e| e.to_string())?;
                fastest = fastest.min(t.elapsed().as_secs_f64() * 1e3);
            }
            Some(fastest)
        } else {
            None
        };
        let n = solved.max(1) as f64;
        planners.push(PlannerRow {
            algo: name,
            rows: subset.len(),
            solved,
            ms,
            ratio_to_astar: ms / astar_ms,
            expanded: expanded as f64 / n,
            cost_ratio: ratio / n,
            setup_ms,
        });
    }
    Ok(BenchReport {
        rows: rows.len(),
        astar_ms,
        jps_ms,
        pathfinding_ms,
        astar_speedup: pathfinding_ms / astar_ms,
        jps_speedup: astar_ms / jps_ms,
        planners,
    })
}

/// Timings of `planlab bench step`: the reference DWA step in blocks.
#[derive(Debug, Serialize)]
pub struct StepReport {
    /// Steps per timed block.
    pub steps: usize,
    /// Wall time of each block, ms.
    pub times_ms: Vec<f64>,
    /// Median block time / steps, ms per step.
    pub ms_per_step: f64,
    /// Fastest block time / steps, ms per step.
    pub min_ms_per_step: f64,
    /// Sum of v + ω over one block (the browser must agree).
    pub checksum: f64,
}

/// Timings of `planlab bench scen`: one pass = every query planned once.
#[derive(Debug, Serialize)]
pub struct ScenReport {
    /// Queries per pass.
    pub rows: usize,
    /// Passes per timed block.
    pub inner: usize,
    /// Summed path cost of one pass.
    pub total_cost: f64,
    /// Sum of the scenario's optimal lengths.
    pub optimal_sum: f64,
    /// Wall time of each block, ms.
    pub times_ms: Vec<f64>,
    /// Median block time / (rows × inner), ms per query.
    pub ms_per_query: f64,
}

fn median(xs: &[f64]) -> f64 {
    let mut s = xs.to_vec();
    s.sort_by(f64::total_cmp);
    let m = s.len() / 2;
    if s.len() % 2 == 1 {
        s[m]
    } else {
        (s[m - 1] + s[m]) / 2.0
    }
}

/// Most repetitions, blocks or passes of a benchmark (each is at least one
/// full run; more is a typo, and the timings are kept in memory).
const MAX_BENCH_REPS: usize = 10_000;
/// Most DWA steps per timed block.
const MAX_BENCH_STEPS: usize = 1_000_000;

/// Refuses a count above `max` before anything is sized by it.
fn check_count(flag: &str, n: usize, max: usize) -> Result<(), String> {
    if n > max {
        return Err(format!("{flag} {n}: at most {max}"));
    }
    Ok(())
}

/// Times [`DwaStepBench`](planlab_core::bench::DwaStepBench) in `blocks`
/// blocks of `steps` steps after one untimed warm-up block.
pub fn bench_step(steps: usize, blocks: usize) -> Result<StepReport, String> {
    check_count("--steps", steps, MAX_BENCH_STEPS)?;
    check_count("--blocks", blocks, MAX_BENCH_REPS)?;
    let (steps, blocks) = (steps.max(1), blocks.max(1));
    let mut b = planlab_core::bench::DwaStepBench::reference().map_err(|e| e.to_string())?;
    let checksum = b.run(steps);
    let mut times_ms = Vec::with_capacity(blocks);
    for _ in 0..blocks {
        let t = Instant::now();
        let c = std::hint::black_box(b.run(steps));
        times_ms.push(t.elapsed().as_secs_f64() * 1e3);
        if c != checksum {
            return Err("non-deterministic DWA step".into());
        }
    }
    let n = steps as f64;
    Ok(StepReport {
        steps,
        ms_per_step: median(&times_ms) / n,
        min_ms_per_step: times_ms.iter().copied().fold(f64::INFINITY, f64::min) / n,
        times_ms,
        checksum,
    })
}

/// Times [`ScenBatch::solve_all`](planlab_core::bench::ScenBatch::solve_all)
/// with A* (default options): `reps` blocks of `inner` passes after one
/// untimed pass.
pub fn bench_scen(
    grid: &OccupancyGrid,
    scen_text: &str,
    reps: usize,
    inner: usize,
) -> Result<ScenReport, String> {
    check_count("--reps", reps, MAX_BENCH_REPS)?;
    check_count("--inner", inner, MAX_BENCH_REPS)?;
    let (reps, inner) = (reps.max(1), inner.max(1));
    let options = planlab_core::global::plan::GridPlanOptions::default();
    let batch = planlab_core::bench::ScenBatch::new(grid, scen_text, &options)
        .map_err(|e| e.to_string())?;
    if batch.is_empty() {
        return Err("the scenario has no rows".into());
    }
    let total_cost = batch.solve_all().map_err(|e| e.to_string())?;
    let mut times_ms = Vec::with_capacity(reps);
    for _ in 0..reps {
        let t0 = Instant::now();
        let mut t = 0.0;
        for _ in 0..inner {
            t = batch.solve_all().map_err(|e| e.to_string())?;
        }
        times_ms.push(t0.elapsed().as_secs_f64() * 1e3);
        if (t - total_cost).abs() > 1e-9 {
            return Err("non-deterministic total cost".into());
        }
    }
    Ok(ScenReport {
        rows: batch.len(),
        inner,
        total_cost,
        optimal_sum: batch.optimal_sum(),
        ms_per_query: median(&times_ms) / (batch.len() * inner) as f64,
        times_ms,
    })
}

/// The rows of `planlab bench sampling` and `bench_ompl.py`: `k` rows
/// spread evenly over a scenario of `n`, indices round(i·(n−1)/(k−1)) for
/// i = 0 … k−1 (ties to even, as Python's `round`), without repeats.
/// Moving AI files are sorted by optimal length, so the sample runs from
/// the shortest query to the longest.
pub fn pick_rows(n: usize, k: usize) -> Vec<usize> {
    if k >= n {
        return (0..n).collect();
    }
    if k <= 1 {
        return vec![0];
    }
    let mut out: Vec<usize> = (0..k)
        .map(|i| (i as f64 * (n - 1) as f64 / (k - 1) as f64).round_ties_even() as usize)
        .collect();
    out.dedup();
    out
}

/// One run of `planlab bench sampling`.
#[derive(Debug, Serialize)]
pub struct SamplingRun {
    /// The map's file stem.
    pub map: String,
    /// The row's index in the .scen file.
    pub row: usize,
    /// Start cell (col, row).
    pub start: [u32; 2],
    /// Goal cell (col, row).
    pub goal: [u32; 2],
    /// The planner's `--algo` name.
    pub algo: &'static str,
    /// Its seed.
    pub seed: u64,
    /// The best path's length, cells (`None`: no path).
    pub cost: Option<f64>,
    /// Theta*'s cost on the same row, cells.
    pub theta_star: f64,
    /// Iterations run.
    pub iterations: u64,
    /// The iteration of the first path.
    pub first_solution_iteration: Option<u64>,
    /// Wall time of the run (planner built and stepped), ms.
    pub ms: f64,
}

/// One planner's figures in a [`SamplingReport`], on one map or on all.
#[derive(Debug, Serialize)]
pub struct SamplingRow {
    /// The map's file stem, or "all".
    pub map: String,
    /// The planner's `--algo` name.
    pub algo: &'static str,
    /// Runs (rows × seeds).
    pub runs: usize,
    /// Runs that found a path.
    pub solved: usize,
    /// Median over solved runs of cost / Theta*'s − 1 (negative: shorter
    /// than Theta*, which keeps to cell centres' lines of sight); `None`
    /// when nothing was solved.
    pub median_gap: Option<f64>,
    /// Median iteration of the first path over solved runs.
    pub median_first_iteration: Option<f64>,
    /// Median wall time per run (query), ms.
    pub median_ms: f64,
}

/// `planlab bench sampling`: every run and the per-planner summary.
#[derive(Debug, Serialize)]
pub struct SamplingReport {
    /// Iterations per run.
    pub iterations: u64,
    /// Disc radius, cells.
    pub radius: f64,
    /// Seeds per row (0 … seeds − 1).
    pub seeds: u64,
    /// Per map and planner, then per planner over all maps.
    pub planners: Vec<SamplingRow>,
    /// Every run.
    pub runs: Vec<SamplingRun>,
}

/// One map of `planlab bench sampling`: its name, grid and picked rows.
pub struct SamplingMap {
    /// File stem.
    pub name: String,
    /// The map.
    pub grid: OccupancyGrid,
    /// The picked rows with their .scen indices.
    pub rows: Vec<(usize, ScenRow)>,
}

/// Most seeds per row of `planlab bench sampling`.
const MAX_BENCH_SEEDS: u64 = 1_000;

/// Runs each of `algos` from every picked row's start cell centre to its
/// goal's, `seeds` seeds each, for `iterations` iterations (RRT and
/// RRT-Connect stop at their first path), and compares the costs with
/// Theta*'s on the same row. No time limit: the answers depend only on the
/// seeds, only the times on the machine.
pub fn bench_sampling(
    maps: &[SamplingMap],
    algos: &[SamplingAlgorithm],
    iterations: u64,
    seeds: u64,
    radius: f64,
) -> Result<SamplingReport, String> {
    if !(1..=MAX_ITERATIONS).contains(&iterations) {
        return Err(format!(
            "--iterations {iterations}: must be from 1 to {MAX_ITERATIONS}"
        ));
    }
    if !(1..=MAX_BENCH_SEEDS).contains(&seeds) {
        return Err(format!(
            "--seeds {seeds}: must be from 1 to {MAX_BENCH_SEEDS}"
        ));
    }
    let theta = ThetaStar::default();
    let mut runs = Vec::new();
    for m in maps {
        let space = Arc::new(
            DiscSpace::new(&m.grid, radius, false).map_err(|e| format!("{}: {e}", m.name))?,
        );
        let plan_grid = PlanGrid::new(&m.grid, false);
        for (index, row) in &m.rows {
            // Every Moving AI row has a path; one Theta* cannot find is
            // a scenario that does not fit its map.
            let theta_star = theta
                .plan(&plan_grid, row.start, row.goal)
                .map_err(|e| format!("{} row {index}: Theta*: {e}", m.name))?
                .cost;
            let s = cell_centre(row.start.col, row.start.row);
            let g = cell_centre(row.goal.col, row.goal.row);
            for &algo in algos {
                for seed in 0..seeds {
                    let options = SamplingOptions {
                        algorithm: algo,
                        seed,
                        ..SamplingOptions::default()
                    };
                    let t = Instant::now();
                    let mut p = SamplingPlanner::new(space.clone(), s, g, &options)
                        .map_err(|e| format!("{} row {index}: {e}", m.name))?;
                    p.step(iterations);
                    let ms = t.elapsed().as_secs_f64() * 1e3;
                    runs.push(SamplingRun {
                        map: m.name.clone(),
                        row: *index,
                        start: [row.start.col, row.start.row],
                        goal: [row.goal.col, row.goal.row],
                        algo: algo.name(),
                        seed,
                        cost: p.best_cost(),
                        theta_star,
                        iterations: p.iterations(),
                        first_solution_iteration: p.first_solution_iteration(),
                        ms,
                    });
                }
            }
        }
    }
    let mut planners = Vec::new();
    let names: Vec<String> = maps.iter().map(|m| m.name.clone()).collect();
    for scope in names.iter().map(Some).chain([None]) {
        for &algo in algos {
            let of: Vec<&SamplingRun> = runs
                .iter()
                .filter(|r| r.algo == algo.name() && scope.map_or(true, |n| &r.map == n))
                .collect();
            let gaps: Vec<f64> = of
                .iter()
                .filter_map(|r| r.cost.map(|c| c / r.theta_star - 1.0))
                .collect();
            let firsts: Vec<f64> = of
                .iter()
                .filter_map(|r| r.first_solution_iteration.map(|i| i as f64))
                .collect();
            let ms: Vec<f64> = of.iter().map(|r| r.ms).collect();
            planners.push(SamplingRow {
                map: scope.cloned().unwrap_or_else(|| "all".into()),
                algo: algo.name(),
                runs: of.len(),
                solved: gaps.len(),
                median_gap: (!gaps.is_empty()).then(|| median(&gaps)),
                median_first_iteration: (!firsts.is_empty()).then(|| median(&firsts)),
                median_ms: if ms.is_empty() { 0.0 } else { median(&ms) },
            });
        }
    }
    Ok(SamplingReport {
        iterations,
        radius,
        seeds,
        planners,
        runs,
    })
}

/// The summary of [`bench_sampling`] as a text table.
pub fn sampling_table(r: &SamplingReport) -> String {
    let mut out = format!(
        "{} iterations, disc radius {} cells, seeds 0..{}; gap: median over solved runs of cost / Theta*'s cost − 1\n{:<16} {:<18} {:>7} {:>9} {:>11} {:>10}\n",
        r.iterations, r.radius, r.seeds, "map", "planner", "solved", "gap %", "1st iter", "ms/query"
    );
    for p in &r.planners {
        let opt = |v: Option<f64>, f: &dyn Fn(f64) -> String| v.map_or("–".to_string(), f);
        out.push_str(&format!(
            "{:<16} {:<18} {:>7} {:>9} {:>11} {:>10.2}\n",
            p.map,
            p.algo,
            format!("{}/{}", p.solved, p.runs),
            opt(p.median_gap, &|g| format!("{:+.2}", 100.0 * g)),
            opt(p.median_first_iteration, &|i| format!("{i:.0}")),
            p.median_ms
        ));
    }
    out
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
        let report = bench_grid(&g, &[row((0, 0), (1, 1), 2.0)], 1, &[]).unwrap();
        assert_eq!(report.rows, 1);
        // A wrong optimum is reported, not averaged away.
        let err = bench_grid(&g, &[row((0, 0), (1, 1), 1.5)], 1, &[]).unwrap_err();
        assert!(err.contains("row 0"), "{err}");
    }

    #[test]
    fn rows_are_picked_like_the_ompl_benchmark() {
        // bench_ompl.py's pick_rows on the same sizes (its harness test).
        assert_eq!(
            pick_rows(161, 10),
            [0, 18, 36, 53, 71, 89, 107, 124, 142, 160]
        );
        assert_eq!(pick_rows(5, 10), [0, 1, 2, 3, 4]);
        assert_eq!(pick_rows(7, 1), [0]);
        // 2.5 rounds to 2, as Python's round does.
        assert_eq!(pick_rows(6, 3), [0, 2, 5]);
    }

    #[test]
    fn step_and_scen_reports_agree_with_the_work() {
        let r = bench_step(2, 2).unwrap();
        assert_eq!((r.steps, r.times_ms.len()), (2, 2));
        // Two steps of the same state: twice one step's v + ω.
        let mut b = planlab_core::bench::DwaStepBench::reference().unwrap();
        assert_eq!(r.checksum, b.run(2));
        assert!(r.ms_per_step > 0.0 && r.min_ms_per_step <= r.ms_per_step);

        let g = OccupancyGrid::from_ascii("....\n.##.\n....\n").unwrap();
        let scen = "version 1\n0\tm.map\t4\t3\t0\t0\t3\t2\t5\n";
        let s = bench_scen(&g, scen, 3, 2).unwrap();
        assert_eq!((s.rows, s.inner, s.times_ms.len()), (1, 2, 3));
        assert!((s.total_cost - 5.0).abs() < 1e-9, "{}", s.total_cost);
        assert!(bench_scen(&g, "version 1\n", 1, 1).is_err());
    }
}
