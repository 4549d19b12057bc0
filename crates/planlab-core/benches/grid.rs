//! Criterion benchmarks of the grid planners on the Moving AI maps in `tests/data`:
//! our A*, our JPS and the `pathfinding` crate's `astar` (same 8-connected,
//! no-corner-cutting moves) on the same seeded sample of scenario rows, with
//! every cost checked against the optimum inside the benchmark.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use planlab_core::global::astar::{AStar, AStarConfig};
use planlab_core::global::jps::{Jps, JpsConfig};
use planlab_core::global::{GridPlanner, PlanGrid};
use planlab_core::map::io::movingai::{parse_map, parse_scen, ScenRow};
use std::hint::black_box;

const MAPS: [&str; 4] = [
    "dao/arena",
    "dao/arena2",
    "maze/maze512-1-0",
    "random/random512-10-0",
];

fn load(name: &str) -> (PlanGrid, Vec<ScenRow>) {
    let base = format!(
        "{}/../../tests/data/movingai/{name}.map",
        env!("CARGO_MANIFEST_DIR")
    );
    let map = parse_map(&std::fs::read_to_string(&base).expect("map")).expect("parse map");
    let rows =
        parse_scen(&std::fs::read_to_string(format!("{base}.scen")).expect("scen")).expect("scen");
    // A fixed, evenly spread sample (seeded by position, not by a clock) that
    // keeps the hardest buckets: every k-th row up to 40 rows.
    let k = rows.len().div_ceil(40).max(1);
    let sample = rows.into_iter().step_by(k).collect();
    (PlanGrid::new(&map, false), sample)
}

// The same peer `planlab bench grid` times, so both report one thing.
#[path = "../../planlab-cli/src/peer.rs"]
mod peer;

fn peer(grid: &PlanGrid, row: &ScenRow) -> f64 {
    peer::pathfinding_cost(grid, row.start, row.goal).unwrap_or(f64::NAN)
}

fn close(cost: f64, optimal: f64) -> bool {
    (cost - optimal).abs() <= 1e-3 * optimal.max(1.0)
}

fn grid_planners(c: &mut Criterion) {
    let astar = AStar::new(AStarConfig::default()).expect("A*");
    let jps = Jps::new(JpsConfig::default()).expect("JPS");
    let mut group = c.benchmark_group("moving_ai_rows");
    group.sample_size(10);
    for name in MAPS {
        let (grid, rows) = load(name);
        let label = name.rsplit('/').next().unwrap_or(name);
        group.bench_with_input(BenchmarkId::new("astar", label), &rows, |b, rows| {
            b.iter(|| {
                for r in rows {
                    let p = astar.plan(&grid, r.start, r.goal).expect("A* path");
                    assert!(close(p.cost, r.optimal));
                    black_box(p);
                }
            })
        });
        group.bench_with_input(BenchmarkId::new("jps", label), &rows, |b, rows| {
            b.iter(|| {
                for r in rows {
                    let p = jps.plan(&grid, r.start, r.goal).expect("JPS path");
                    assert!(close(p.cost, r.optimal));
                    black_box(p);
                }
            })
        });
        group.bench_with_input(BenchmarkId::new("pathfinding", label), &rows, |b, rows| {
            b.iter(|| {
                for r in rows {
                    assert!(close(peer(&grid, r), r.optimal));
                }
            })
        });
    }
    group.finish();
}

criterion_group!(benches, grid_planners);
criterion_main!(benches);
