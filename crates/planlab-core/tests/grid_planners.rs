//! A*, Dijkstra and Jump Point Search through the public API: every row of
//! the Moving AI scenarios against its published optimum, seeded property
//! tests against an independent brute-force Dijkstra on random maps, and the
//! typed errors.

use planlab_core::global::astar::{AStar, AStarConfig};
use planlab_core::global::jps::{Jps, JpsConfig};
use planlab_core::global::{
    Diagonal, Endpoint, GridPlanner, GridPos, Heuristic, ObservedGridPlanner, Path, PlanError,
    PlanGrid,
};
use planlab_core::map::io::movingai::{parse_map, parse_scen};
use planlab_core::map::OccupancyGrid;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Root of the Moving AI data in the repository (`tests/data/movingai`).
const MOVINGAI: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/data/movingai");

const NCC: Diagonal = Diagonal::NoCornerCutting;
const SQRT2: f64 = std::f64::consts::SQRT_2;

fn p(col: u32, row: u32) -> GridPos {
    GridPos::new(col, row)
}

fn ascii(text: &str) -> PlanGrid {
    PlanGrid::new(&OccupancyGrid::from_ascii(text).unwrap(), false)
}

/// Why `path` is not a legal `start`→`goal` path under `rule`, if it is not:
/// every cell free, every step one king move, diagonals obeying the rule,
/// and `cost` equal to the sum of the move lengths.
fn illegal(
    grid: &PlanGrid,
    path: &Path,
    start: GridPos,
    goal: GridPos,
    rule: Diagonal,
) -> Option<String> {
    let cells = &path.cells;
    if cells.first() != Some(&start) || cells.last() != Some(&goal) {
        return Some(format!(
            "path runs {:?} → {:?}",
            cells.first(),
            cells.last()
        ));
    }
    let free = |c: u32, r: u32| grid.is_free(c as i64, r as i64);
    if let Some(c) = cells.iter().find(|c| !free(c.col, c.row)) {
        return Some(format!("cell {c:?} is blocked"));
    }
    let mut length = 0.0;
    for w in cells.windows(2) {
        let (a, b) = (w[0], w[1]);
        let (dc, dr) = (a.col.abs_diff(b.col), a.row.abs_diff(b.row));
        match (dc, dr) {
            (1, 0) | (0, 1) => length += 1.0,
            (1, 1) => {
                if !rule.allows(free(b.col, a.row), free(a.col, b.row)) {
                    return Some(format!("diagonal {a:?} → {b:?} breaks {rule:?}"));
                }
                length += SQRT2;
            }
            _ => return Some(format!("step {a:?} → {b:?} is not one move")),
        }
    }
    if (length - path.cost).abs() > 1e-9 * length.max(1.0) {
        return Some(format!("cost {} but moves sum to {length}", path.cost));
    }
    None
}

// ---------------------------------------------------------------------------
// Moving AI benchmarks: every row, both planners.

fn check_benchmark(map: &str, scen: &str) {
    let read = |rel: &str| {
        std::fs::read_to_string(format!("{MOVINGAI}/{rel}"))
            .unwrap_or_else(|e| panic!("reading {rel}: {e}"))
    };
    let grid = PlanGrid::new(&parse_map(&read(map)).unwrap(), false);
    let rows = parse_scen(&read(scen)).unwrap();
    assert!(rows.len() > 100, "{scen} has only {} rows", rows.len());
    let plus = Jps::new(JpsConfig {
        preprocess: true,
        ..JpsConfig::default()
    })
    .unwrap();
    let planners: [(&str, &dyn GridPlanner); 3] = [
        ("A*", &AStar::default()),
        ("JPS", &Jps::default()),
        ("JPS+", &plus),
    ];
    let mut failures = Vec::new();
    let mut jps_expanded = 0usize;
    let mut astar_expanded = 0usize;
    for (k, row) in rows.iter().enumerate() {
        let mut jps_row = None;
        for (name, planner) in planners {
            match planner.plan(&grid, row.start, row.goal) {
                Ok(path) => {
                    let tol = 1e-3 * row.optimal.max(1.0);
                    if (path.cost - row.optimal).abs() > tol {
                        failures.push(format!(
                            "row {k} {name}: cost {} ≠ optimum {}",
                            path.cost, row.optimal
                        ));
                    }
                    if let Some(why) = illegal(&grid, &path, row.start, row.goal, NCC) {
                        failures.push(format!("row {k} {name}: {why}"));
                    }
                    match name {
                        "JPS" => {
                            jps_expanded += path.expanded;
                            jps_row = Some(path);
                        }
                        // JPS+ reads JPS's jumps from a table: the same
                        // jump points, the same path.
                        "JPS+" => {
                            let same = jps_row.as_ref().is_some_and(|j| {
                                j.expanded == path.expanded && j.cells == path.cells
                            });
                            if !same {
                                failures.push(format!("row {k} JPS+: differs from JPS"));
                            }
                        }
                        _ => astar_expanded += path.expanded,
                    }
                }
                Err(e) => failures.push(format!("row {k} {name}: {e}")),
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{scen}: {} failures of {} rows, first: {:#?}",
        failures.len(),
        rows.len(),
        &failures[..failures.len().min(10)]
    );
    // JPS's point is expanding far fewer nodes than A*.
    assert!(
        jps_expanded < astar_expanded,
        "{scen}: JPS expanded {jps_expanded}, A* {astar_expanded}"
    );
}

#[test]
fn movingai_arena_every_row_optimal() {
    check_benchmark("dao/arena.map", "dao/arena.map.scen");
}

#[test]
fn movingai_arena2_every_row_optimal() {
    check_benchmark("dao/arena2.map", "dao/arena2.map.scen");
}

#[test]
fn movingai_maze512_every_row_optimal() {
    check_benchmark("maze/maze512-1-0.map", "maze/maze512-1-0.map.scen");
}

#[test]
fn movingai_random512_every_row_optimal() {
    check_benchmark(
        "random/random512-10-0.map",
        "random/random512-10-0.map.scen",
    );
}

// ---------------------------------------------------------------------------
// Reference: a deliberately plain Dijkstra (f64 costs, hash-free arrays,
// no shared code with the planners) giving the optimum under any rule.

#[derive(PartialEq)]
struct Open(f64, usize);
impl Eq for Open {}
impl Ord for Open {
    fn cmp(&self, o: &Self) -> Ordering {
        o.0.total_cmp(&self.0)
    }
}
impl PartialOrd for Open {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

fn reference_cost(grid: &PlanGrid, start: GridPos, goal: GridPos, rule: Diagonal) -> Option<f64> {
    let (w, h) = (grid.width() as i64, grid.height() as i64);
    let free = |c: i64, r: i64| grid.is_free(c, r);
    let mut dist = vec![f64::INFINITY; (w * h) as usize];
    let id = |c: i64, r: i64| (r * w + c) as usize;
    let mut open = BinaryHeap::new();
    dist[id(start.col as i64, start.row as i64)] = 0.0;
    open.push(Open(0.0, id(start.col as i64, start.row as i64)));
    while let Some(Open(d, i)) = open.pop() {
        if d > dist[i] {
            continue;
        }
        let (c, r) = (i as i64 % w, i as i64 / w);
        if (c, r) == (goal.col as i64, goal.row as i64) {
            return Some(d);
        }
        for dr in -1..=1i64 {
            for dc in -1..=1i64 {
                let (nc, nr) = (c + dc, r + dr);
                if (dc, dr) == (0, 0) || !free(nc, nr) {
                    continue;
                }
                let step = if dc != 0 && dr != 0 {
                    if !rule.allows(free(nc, r), free(c, nr)) {
                        continue;
                    }
                    SQRT2
                } else {
                    1.0
                };
                let j = id(nc, nr);
                if d + step < dist[j] {
                    dist[j] = d + step;
                    open.push(Open(d + step, j));
                }
            }
        }
    }
    None
}

// ---------------------------------------------------------------------------
// Property tests on random maps.

/// A random map (up to 64×64, obstacle density up to ~45%) with a free start
/// and goal picked among its free cells.
fn scenario() -> impl Strategy<Value = (PlanGrid, GridPos, GridPos)> {
    (1usize..=64, 1usize..=64, 0u32..45)
        .prop_flat_map(|(w, h, density)| {
            (
                Just((w, h)),
                proptest::collection::vec(proptest::bool::weighted(density as f64 / 100.0), w * h),
                any::<proptest::sample::Index>(),
                any::<proptest::sample::Index>(),
            )
        })
        .prop_filter_map("no free cell", |((w, h), blocked, a, b)| {
            let grid = PlanGrid::from_fn(w, h, |c, r| !blocked[r * w + c]);
            let free: Vec<GridPos> = (0..h)
                .flat_map(|r| (0..w).map(move |c| p(c as u32, r as u32)))
                .filter(|q| grid.is_free(q.col as i64, q.row as i64))
                .collect();
            if free.is_empty() {
                return None;
            }
            Some((grid, *a.get(&free), *b.get(&free)))
        })
}

fn config(cases: u32, seed: u64) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        ..Config::default()
    }
}

fn astar(heuristic: Heuristic, weight: f64, diagonal: Diagonal) -> AStar {
    AStar::new(AStarConfig {
        heuristic,
        weight,
        diagonal,
    })
    .unwrap()
}

/// Checks `result` against the reference optimum `best` under `rule`.
fn check_optimal(
    name: &str,
    grid: &PlanGrid,
    (start, goal): (GridPos, GridPos),
    rule: Diagonal,
    result: Result<Path, PlanError>,
    best: Option<f64>,
) -> Result<(), TestCaseError> {
    match (result, best) {
        (Ok(path), Some(best)) => {
            prop_assert!(
                (path.cost - best).abs() <= 1e-9 * best.max(1.0),
                "{name}: cost {} ≠ optimum {best}",
                path.cost
            );
            if let Some(why) = illegal(grid, &path, start, goal, rule) {
                return Err(TestCaseError::fail(format!("{name}: {why}")));
            }
        }
        (Err(PlanError::Unreachable { .. }), None) => {}
        (r, best) => {
            return Err(TestCaseError::fail(format!(
                "{name}: got {r:?}, reference optimum {best:?}"
            )))
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(400, 0x5eed_a57a))]

    /// A*, Dijkstra and JPS all find the optimum (or all report unreachable)
    /// with legal, collision-free paths.
    #[test]
    fn astar_dijkstra_jps_are_optimal((grid, start, goal) in scenario()) {
        let best = reference_cost(&grid, start, goal, NCC);
        let q = (start, goal);
        check_optimal("A*", &grid, q, NCC, AStar::default().plan(&grid, start, goal), best)?;
        check_optimal("Dijkstra", &grid, q, NCC, AStar::dijkstra(NCC).plan(&grid, start, goal), best)?;
        check_optimal("JPS", &grid, q, NCC, Jps::default().plan(&grid, start, goal), best)?;
        let plus = Jps::new(JpsConfig { preprocess: true, ..JpsConfig::default() }).unwrap();
        check_optimal("JPS+", &grid, q, NCC, plus.plan(&grid, start, goal), best)?;
        for h in [Heuristic::Euclidean, Heuristic::Chebyshev, Heuristic::Zero] {
            check_optimal("A* admissible", &grid, q, NCC, astar(h, 1.0, NCC).plan(&grid, start, goal), best)?;
            let jps = Jps::new(JpsConfig { heuristic: h, ..JpsConfig::default() }).unwrap();
            check_optimal("JPS admissible", &grid, q, NCC, jps.plan(&grid, start, goal), best)?;
        }
    }

    /// Weighted A* stays within w times the optimum.
    #[test]
    fn weighted_astar_is_bounded((grid, start, goal) in scenario(), w in 1.0f64..6.0) {
        let best = reference_cost(&grid, start, goal, NCC);
        for h in [Heuristic::Octile, Heuristic::Euclidean, Heuristic::Chebyshev] {
            match (astar(h, w, NCC).plan(&grid, start, goal), best) {
                (Ok(path), Some(best)) => {
                    prop_assert!(path.cost <= w * best + 1e-9, "{h:?} w={w}: {} > {w}·{best}", path.cost);
                    prop_assert!(path.cost >= best - 1e-9);
                    if let Some(why) = illegal(&grid, &path, start, goal, NCC) {
                        return Err(TestCaseError::fail(why));
                    }
                }
                (Err(PlanError::Unreachable { .. }), None) => {}
                (r, best) => return Err(TestCaseError::fail(format!("{r:?} vs {best:?}"))),
            }
        }
    }

    /// 4-connected: every heuristic (Manhattan included, admissible there)
    /// gives the 4-connected optimum with no diagonal step.
    #[test]
    fn four_connected_heuristics_are_optimal((grid, start, goal) in scenario()) {
        let best = reference_cost(&grid, start, goal, Diagonal::Never);
        for h in [Heuristic::Manhattan, Heuristic::Euclidean, Heuristic::Octile, Heuristic::Chebyshev, Heuristic::Zero] {
            let name = format!("{h:?} 4-connected");
            check_optimal(&name, &grid, (start, goal), Diagonal::Never,
                astar(h, 1.0, Diagonal::Never).plan(&grid, start, goal), best)?;
        }
    }

    /// The permissive corner rules give legal paths under their own rule,
    /// optimal for it, never longer than with no corner cutting.
    #[test]
    fn corner_rules_are_legal_and_optimal((grid, start, goal) in scenario()) {
        let strict = reference_cost(&grid, start, goal, NCC);
        for rule in [Diagonal::OneSideFree, Diagonal::Always] {
            let best = reference_cost(&grid, start, goal, rule);
            let q = (start, goal);
            check_optimal("A* rule", &grid, q, rule, astar(Heuristic::Octile, 1.0, rule).plan(&grid, start, goal), best)?;
            check_optimal("Dijkstra rule", &grid, q, rule, AStar::dijkstra(rule).plan(&grid, start, goal), best)?;
            if let (Some(s), Some(b)) = (strict, best) {
                prop_assert!(b <= s + 1e-9);
            }
            prop_assert!(strict.is_none() || best.is_some());
        }
    }
}

// ---------------------------------------------------------------------------
// Fixtures and typed errors.

#[test]
fn start_equal_goal_is_a_one_cell_path() {
    let g = ascii("...\n...\n");
    let planners: [&dyn GridPlanner; 3] =
        [&AStar::default(), &AStar::dijkstra(NCC), &Jps::default()];
    for planner in planners {
        let path = planner.plan(&g, p(1, 1), p(1, 1)).unwrap();
        assert_eq!(path.cells, vec![p(1, 1)]);
        assert_eq!(path.cost, 0.0);
    }
}

#[test]
fn endpoints_off_the_map_or_blocked_are_typed_errors() {
    let g = ascii(
        "
..#
...
",
    );
    let planners: [&dyn GridPlanner; 3] =
        [&AStar::default(), &AStar::dijkstra(NCC), &Jps::default()];
    for planner in planners {
        assert!(matches!(
            planner.plan(&g, p(3, 0), p(0, 0)),
            Err(PlanError::OffMap {
                which: Endpoint::Start,
                col: 3,
                row: 0,
                width: 3,
                height: 2
            })
        ));
        assert!(matches!(
            planner.plan(&g, p(0, 0), p(0, 2)),
            Err(PlanError::OffMap {
                which: Endpoint::Goal,
                col: 0,
                row: 2,
                ..
            })
        ));
        assert!(matches!(
            planner.plan(&g, p(0, 0), p(u32::MAX, u32::MAX)),
            Err(PlanError::OffMap {
                which: Endpoint::Goal,
                ..
            })
        ));
        assert_eq!(
            planner.plan(&g, p(2, 0), p(0, 0)),
            Err(PlanError::Blocked {
                which: Endpoint::Start,
                col: 2,
                row: 0
            })
        );
        assert_eq!(
            planner.plan(&g, p(0, 0), p(2, 0)),
            Err(PlanError::Blocked {
                which: Endpoint::Goal,
                col: 2,
                row: 0
            })
        );
    }
}

#[test]
fn walled_off_goal_is_unreachable_for_every_planner() {
    // The goal's pocket touches the outside only diagonally through a
    // corner, which no corner cutting forbids.
    let g = ascii(
        "
....#..
....#..
.....##
......#
",
    );
    let planners: [&dyn GridPlanner; 3] =
        [&AStar::default(), &AStar::dijkstra(NCC), &Jps::default()];
    for planner in planners {
        match planner.plan(&g, p(0, 0), p(6, 0)) {
            Err(PlanError::Unreachable { expanded }) => assert!(expanded > 0),
            other => panic!("expected unreachable, got {other:?}"),
        }
    }
    // Cutting the corner at (4,2)/(5,1) does reach it.
    let cut = astar(Heuristic::Octile, 1.0, Diagonal::Always).plan(&g, p(0, 0), p(6, 0));
    assert!(cut.is_ok());
}

#[test]
fn invalid_weights_and_rules_are_refused() {
    for weight in [f64::NAN, 0.5, 0.0, -1.0, f64::INFINITY] {
        let err = AStar::new(AStarConfig {
            weight,
            ..AStarConfig::default()
        })
        .unwrap_err();
        assert!(
            matches!(err, PlanError::InvalidConfig(_)),
            "weight {weight}"
        );
    }
    assert!(AStar::new(AStarConfig {
        weight: 1.0,
        ..AStarConfig::default()
    })
    .is_ok());
    let err = Jps::new(JpsConfig {
        diagonal: Diagonal::Always,
        ..JpsConfig::default()
    })
    .unwrap_err();
    assert!(matches!(err, PlanError::InvalidConfig(m) if m.contains("no_corner_cutting")));
}

#[test]
fn recording_lists_each_expansion_in_order() {
    let g = ascii(
        "
.........
.#######.
.........
",
    );
    let (a, b) = (p(0, 1), p(8, 1));
    let planners: [&dyn ObservedGridPlanner; 2] = [&AStar::default(), &Jps::default()];
    for planner in planners {
        let mut seen = Vec::new();
        let path = planner.plan_recording(&g, a, b, Some(&mut seen)).unwrap();
        assert_eq!(seen.len(), path.expanded);
        assert_eq!(seen.first(), Some(&a));
        assert_eq!(seen.last(), Some(&b));
        assert!((path.cost - 10.0).abs() < 1e-9);
        assert_eq!(planner.plan(&g, a, b).unwrap(), path);
    }
}

#[test]
fn jps_expands_jump_points_only_in_a_corridor() {
    // A straight corridor: JPS jumps start → goal; A* walks every cell.
    let g = ascii(&format!("{}\n", ".".repeat(200)));
    let jps = Jps::default().plan(&g, p(0, 0), p(199, 0)).unwrap();
    let astar = AStar::default().plan(&g, p(0, 0), p(199, 0)).unwrap();
    assert_eq!(jps.cells, astar.cells);
    assert_eq!(jps.cells.len(), 200);
    assert_eq!(jps.expanded, 2);
    assert_eq!(astar.expanded, 200);
}

#[test]
fn grid_edits_are_seen_by_jps() {
    let map = OccupancyGrid::from_ascii(&format!("{}\n", ".".repeat(100))).unwrap();
    let mut g = PlanGrid::new(&map, false);
    assert!(Jps::default().plan(&g, p(0, 0), p(99, 0)).is_ok());
    g.set_free(70, 0, false);
    assert!(matches!(
        Jps::default().plan(&g, p(0, 0), p(99, 0)),
        Err(PlanError::Unreachable { .. })
    ));
    g.set_free(70, 0, true);
    assert!((Jps::default().plan(&g, p(0, 0), p(99, 0)).unwrap().cost - 99.0).abs() < 1e-9);
}
