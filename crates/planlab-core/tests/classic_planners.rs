//! The teaching planners (`global::classic`, `global::dstar_lite`, JPS on
//! 4-connected grids) through the public API: the optimal ones against the
//! Moving AI optimum on the repository's maps, the others against stated
//! bounds, D* Lite's repairs against a fresh A*, and the typed errors.

use planlab_core::global::astar::{AStar, AStarConfig};
use planlab_core::global::classic::{
    Bfs, BidirectionalAStar, Greedy, IdaStar, ThetaStar, IDA_STAR_MAX_EXPANSIONS,
};
use planlab_core::global::dstar_lite::{DStarLite, DStarLitePlanner};
use planlab_core::global::jps::{Jps, JpsConfig};
use planlab_core::global::plan::{
    build_observed_planner, build_planner, plan_on_map, Algorithm, GridPlanError, GridPlanOptions,
};
use planlab_core::global::{
    Diagonal, GridPlanner, GridPos, Path, PlanError, PlanGrid, SearchEvent, SearchLog,
};
use planlab_core::map::io::movingai::{parse_map, parse_scen, ScenRow};
use planlab_core::map::OccupancyGrid;

const MOVINGAI: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/data/movingai");
const NCC: Diagonal = Diagonal::NoCornerCutting;
const SQRT2: f64 = std::f64::consts::SQRT_2;

/// The repository's Moving AI maps: (name, map, rows).
fn benchmarks() -> Vec<(&'static str, OccupancyGrid, Vec<ScenRow>)> {
    let read = |rel: &str| std::fs::read_to_string(format!("{MOVINGAI}/{rel}")).unwrap();
    [
        ("arena", "dao/arena.map"),
        ("arena2", "dao/arena2.map"),
        ("random512", "random/random512-10-0.map"),
        ("maze512", "maze/maze512-1-0.map"),
    ]
    .into_iter()
    .map(|(name, map)| {
        let grid = parse_map(&read(map)).unwrap();
        let rows = parse_scen(&read(&format!("{map}.scen"))).unwrap();
        assert!(rows.len() > 100);
        (name, grid, rows)
    })
    .collect()
}

/// Why `path` is not a legal `start`→`goal` path under `rule` whose `cost`
/// is its polyline length, if it is not. Segments may be longer than one
/// move (Theta*); each must cross free cells only.
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
    if !grid.path_is_free(cells, rule) {
        return Some("path crosses a blocked cell or corner".into());
    }
    if rule == Diagonal::Never
        && cells
            .windows(2)
            .any(|w| w[0].col != w[1].col && w[0].row != w[1].row)
    {
        return Some("diagonal move on a 4-connected grid".into());
    }
    let length = Path::polyline_length(cells);
    if (length - path.cost).abs() > 1e-9 * length.max(1.0) {
        return Some(format!("cost {} but segments sum to {length}", path.cost));
    }
    None
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= slack(b)
}

/// How far a cost may be from a `.scen` optimum that is printed rounded
/// (`1.41421` for √2): the tolerance of [`close`].
fn slack(optimum: f64) -> f64 {
    1e-3 * optimum.max(1.0)
}

/// Every `steps[m]`-th row of map `m` (arena, arena2, random512, maze512;
/// 1 = every row, 0 = none): `check` says what is wrong with a planner's
/// answer. The 8-connected optimal planners take every row of every map,
/// as A* and JPS do; the others every row of the first three and a sample
/// of maze512's 12 121 (their checks are bounds or a second search, and
/// the suite must stay within CI's time).
fn every_row(
    steps: [usize; 4],
    planner: &dyn GridPlanner,
    mut check: impl FnMut(&PlanGrid, &ScenRow, Result<Path, PlanError>) -> Option<String>,
) {
    let mut failures = Vec::new();
    let mut solved = 0;
    for ((name, map, rows), step) in benchmarks().into_iter().zip(steps) {
        if step == 0 {
            continue;
        }
        let grid = PlanGrid::new(&map, false);
        for (k, row) in rows.iter().enumerate().step_by(step) {
            let result = planner.plan(&grid, row.start, row.goal);
            solved += usize::from(result.is_ok());
            if let Some(why) = check(&grid, row, result) {
                failures.push(format!("{name} row {k}: {why}"));
            }
        }
    }
    assert!(solved > 0);
    assert!(
        failures.is_empty(),
        "{} failures, first: {:#?}",
        failures.len(),
        &failures[..failures.len().min(10)]
    );
}

/// A check that the answer is the row's Moving AI optimum, legally.
fn optimum(grid: &PlanGrid, row: &ScenRow, result: Result<Path, PlanError>) -> Option<String> {
    match result {
        Ok(p) if !close(p.cost, row.optimal) => {
            Some(format!("cost {} ≠ optimum {}", p.cost, row.optimal))
        }
        Ok(p) => illegal(grid, &p, row.start, row.goal, NCC),
        Err(e) => Some(e.to_string()),
    }
}

#[test]
fn bidirectional_astar_is_optimal_on_every_row() {
    every_row([1, 1, 1, 1], &BidirectionalAStar::default(), optimum);
}

#[test]
fn dstar_lite_is_optimal_on_every_row() {
    every_row([1, 1, 1, 1], &DStarLitePlanner::default(), optimum);
}

#[test]
fn jps_4_connected_equals_4_connected_astar_on_every_row() {
    let four = AStar::new(AStarConfig {
        diagonal: Diagonal::Never,
        ..AStarConfig::default()
    })
    .unwrap();
    let jps = Jps::new(JpsConfig {
        diagonal: Diagonal::Never,
        ..JpsConfig::default()
    })
    .unwrap();
    let mut fewer = 0usize;
    let mut rows = 0usize;
    every_row([1, 1, 1, 4], &jps, |grid, row, result| {
        let best = four.plan(grid, row.start, row.goal).unwrap();
        rows += 1;
        match result {
            Ok(p) if (p.cost - best.cost).abs() > 1e-9 * best.cost.max(1.0) => {
                Some(format!("cost {} ≠ 4-connected A* {}", p.cost, best.cost))
            }
            Ok(p) => {
                fewer += usize::from(p.expanded < best.expanded);
                illegal(grid, &p, row.start, row.goal, Diagonal::Never)
            }
            Err(e) => Some(e.to_string()),
        }
    });
    // Jumping is the point: most queries expand fewer cells than A*.
    assert!(
        fewer * 2 > rows,
        "JPS expanded fewer on {fewer} of {rows} rows"
    );
}

#[test]
fn ida_star_is_optimal_or_stops_at_its_limit() {
    let (mut solved, mut limited, mut rows) = (0, 0, 0);
    // Every row of arena (49×49): on the 512 maps most queries end at the
    // limit, 2 M expansions each (see the next test).
    every_row([1, 0, 0, 0], &IdaStar::default(), |grid, row, result| {
        rows += 1;
        match result {
            Err(PlanError::SearchLimit { expanded, limit }) => {
                limited += 1;
                (expanded != limit || limit != IDA_STAR_MAX_EXPANSIONS)
                    .then(|| format!("stopped at {expanded} of {limit}"))
            }
            other => {
                solved += 1;
                optimum(grid, row, other)
            }
        }
    });
    // Short queries finish; some long ones hit the limit.
    assert!(
        solved * 2 > rows,
        "IDA* solved {solved} of {rows} ({limited} limited)"
    );
}

#[test]
fn ida_star_gives_a_typed_limit_error_on_a_long_512_query() {
    let (_, map, rows) = benchmarks().swap_remove(2);
    let grid = PlanGrid::new(&map, false);
    let row = rows
        .iter()
        .max_by(|a, b| a.optimal.total_cmp(&b.optimal))
        .unwrap();
    let err = IdaStar::default()
        .plan(&grid, row.start, row.goal)
        .unwrap_err();
    assert_eq!(
        err,
        PlanError::SearchLimit {
            expanded: IDA_STAR_MAX_EXPANSIONS,
            limit: IDA_STAR_MAX_EXPANSIONS
        }
    );
    assert!(err.to_string().contains("search limit"));
}

#[test]
fn bfs_finds_fewest_moves_within_sqrt2_of_the_optimum() {
    let astar = AStar::default();
    every_row([1, 1, 1, 8], &Bfs::default(), |grid, row, result| {
        let best = astar.plan(grid, row.start, row.goal).unwrap();
        match result {
            // Fewest moves: never more moves than A*'s path; each move is
            // at most √2 and the optimum has at least as many cells of
            // length ≥ 1, so cost ≤ √2 · optimum.
            Ok(p) if p.cells.len() > best.cells.len() => Some(format!(
                "{} moves > A*'s {}",
                p.cells.len(),
                best.cells.len()
            )),
            Ok(p) if p.cost > SQRT2 * row.optimal + 1e-6 => {
                Some(format!("cost {} > √2 · {}", p.cost, row.optimal))
            }
            Ok(p) => illegal(grid, &p, row.start, row.goal, NCC),
            Err(e) => Some(e.to_string()),
        }
    });
}

#[test]
fn bfs_is_optimal_on_4_connected_grids() {
    let four = AStar::new(AStarConfig {
        diagonal: Diagonal::Never,
        ..AStarConfig::default()
    })
    .unwrap();
    let bfs = Bfs {
        diagonal: Diagonal::Never,
    };
    every_row([1, 1, 1, 4], &bfs, |grid, row, result| {
        let best = four.plan(grid, row.start, row.goal).unwrap();
        match result {
            Ok(p) if p.cost != best.cost => Some(format!("cost {} ≠ {}", p.cost, best.cost)),
            Ok(p) => illegal(grid, &p, row.start, row.goal, Diagonal::Never),
            Err(e) => Some(e.to_string()),
        }
    });
}

#[test]
fn greedy_finds_a_legal_path_whenever_astar_does() {
    let mut longer = 0;
    every_row(
        [1, 1, 1, 8],
        &Greedy::default(),
        |grid, row, result| match result {
            Ok(p) => {
                longer += usize::from(p.cost > row.optimal + slack(row.optimal));
                if p.cost < row.optimal - slack(row.optimal) {
                    return Some(format!("cost {} below the optimum {}", p.cost, row.optimal));
                }
                illegal(grid, &p, row.start, row.goal, NCC)
            }
            Err(e) => Some(e.to_string()),
        },
    );
    // Not optimal, and the rows show it.
    assert!(longer > 0);
}

#[test]
fn theta_star_is_no_longer_than_the_8_connected_optimum() {
    let mut shorter = 0;
    every_row(
        [1, 1, 1, 8],
        &ThetaStar::default(),
        |grid, row, result| match result {
            Ok(p) => {
                let straight = Path::polyline_length(&[row.start, row.goal]);
                shorter += usize::from(p.cost < row.optimal - slack(row.optimal));
                if p.cost > row.optimal + slack(row.optimal) {
                    Some(format!(
                        "cost {} > 8-connected optimum {}",
                        p.cost, row.optimal
                    ))
                } else if p.cost < straight - 1e-9 {
                    Some(format!("cost {} < straight line {straight}", p.cost))
                } else {
                    illegal(grid, &p, row.start, row.goal, NCC)
                }
            }
            Err(e) => Some(e.to_string()),
        },
    );
    // Any-angle: strictly shorter on most rows.
    assert!(shorter > 1000, "shorter on {shorter} rows");
}

// ---------------------------------------------------------------------------
// D* Lite repairs.

/// xorshift64, seeded.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

#[test]
fn dstar_lite_repairs_a_wall_across_the_path_cheaper_than_a_fresh_astar() {
    let (_, map, rows) = benchmarks().swap_remove(1); // arena2
    let mut grid = PlanGrid::new(&map, false);
    let mut rng = Rng(0x0d57_a511);
    let options = GridPlanOptions::default();
    let mut cases = 0;
    let mut tried = 0;
    let mut saved = Vec::new();
    while cases < 12 && tried < 400 {
        tried += 1;
        let row = &rows[rows.len() / 2 + rng.below(rows.len() / 2)];
        let (s, t) = (row.start, row.goal);
        let base = grid.clone();
        let mut d = DStarLite::new(&grid, s, t, &options).unwrap();
        let first = d.plan(&mut ()).unwrap();
        assert!(close(first.cost, row.optimal));
        if first.cells.len() < 30 {
            continue;
        }
        // The robot drives a few cells, then sees a wall across the path a
        // few cells ahead: perpendicular to the path there, 5–9 cells long.
        let k = 3 + rng.below(5);
        let robot = first.cells[k];
        d.move_start(robot).unwrap();
        let at = first.cells[k + 4 + rng.below(4)];
        let next = first.cells[k + 10];
        let (dx, dy) = (
            next.col as i64 - at.col as i64,
            next.row as i64 - at.row as i64,
        );
        let (px, py) = (-dy.signum(), dx.signum());
        let half = 2 + rng.below(3) as i64;
        for o in -half..=half {
            let (c, r) = (at.col as i64 + o * px, at.row as i64 + o * py);
            let q = GridPos::new(c as u32, r as u32);
            if grid.is_free(c, r) && q != robot && q != t {
                grid.set_free(q.col as usize, q.row as usize, false);
                d.set_blocked(q, true);
            }
        }
        let fresh = AStar::default().plan(&grid, robot, t);
        let repaired = d.plan(&mut ());
        match (fresh, repaired) {
            (Ok(f), Ok(r)) => {
                assert!(
                    (f.cost - r.cost).abs() < 1e-9 * f.cost.max(1.0),
                    "D* Lite {} vs fresh A* {}",
                    r.cost,
                    f.cost
                );
                assert!(grid.path_is_free(&r.cells, NCC));
                assert!(
                    r.expanded < f.expanded,
                    "repair expanded {} ≥ fresh A* {}",
                    r.expanded,
                    f.expanded
                );
                saved.push((r.expanded, f.expanded));
                cases += 1;
            }
            (Err(PlanError::Unreachable { .. }), Err(PlanError::Unreachable { .. })) => {}
            (f, r) => panic!("fresh A* {f:?}, D* Lite {r:?}"),
        }
        grid = base;
    }
    assert_eq!(
        cases, 12,
        "only {cases} walled queries in {tried} tries: {saved:?}"
    );
}

#[test]
fn dstar_lite_unblocking_restores_the_original_cost() {
    let (_, map, rows) = benchmarks().swap_remove(0); // arena
    let grid = PlanGrid::new(&map, false);
    let row = rows
        .iter()
        .max_by(|a, b| a.optimal.total_cmp(&b.optimal))
        .unwrap();
    let mut d = DStarLite::new(&grid, row.start, row.goal, &GridPlanOptions::default()).unwrap();
    let first = d.plan(&mut ()).unwrap();
    let mid = first.cells[first.cells.len() / 2];
    d.set_blocked(mid, true);
    let detour = d.plan(&mut ()).unwrap();
    assert!(!detour.cells.contains(&mid));
    assert!(detour.cost >= first.cost - 1e-9);
    d.set_blocked(mid, false);
    let back = d.plan(&mut ()).unwrap();
    assert!((back.cost - first.cost).abs() < 1e-9);
    // Moving the start off the map or into a wall is a typed error.
    assert!(matches!(
        d.move_start(GridPos::new(10_000, 0)),
        Err(PlanError::OffMap { .. })
    ));
}

// ---------------------------------------------------------------------------
// Through plan_on_map: names, events and errors.

const NEW: [Algorithm; 6] = [
    Algorithm::Bfs,
    Algorithm::Greedy,
    Algorithm::BidirectionalAStar,
    Algorithm::IdaStar,
    Algorithm::ThetaStar,
    Algorithm::DStarLite,
];

#[test]
fn every_algorithm_has_a_name_reference_and_summary() {
    assert_eq!(Algorithm::ALL.len(), 11);
    for (a, name) in Algorithm::ALL {
        assert_eq!(name.parse::<Algorithm>().unwrap(), a);
        assert_eq!(serde_json::to_string(&a).unwrap(), format!("\"{name}\""));
        assert!(a.reference().len() > 20, "{name}");
        assert!(a.summary().len() > 200, "{name}");
        assert!(!a.description().is_empty());
    }
    let err = "nope".parse::<Algorithm>().unwrap_err().to_string();
    assert!(
        err.contains("dstar-lite") && err.contains("theta-star"),
        "{err}"
    );
}

#[test]
fn new_planners_report_events_that_match_their_answer() {
    let (_, map, rows) = benchmarks().swap_remove(0);
    let grid = PlanGrid::new(&map, false);
    for algorithm in NEW {
        let options = GridPlanOptions {
            algorithm,
            ..GridPlanOptions::default()
        };
        let planner = build_observed_planner(&options).unwrap();
        for row in rows.iter().step_by(16) {
            let plain = planner.plan(&grid, row.start, row.goal).unwrap();
            let mut log = SearchLog::with_limit(usize::MAX);
            let seen = planner
                .plan_observed(&grid, row.start, row.goal, &mut log)
                .unwrap();
            assert_eq!(plain, seen, "{algorithm:?}");
            let closes = log
                .events
                .iter()
                .filter(|e| matches!(e, SearchEvent::Close { .. }))
                .count();
            assert_eq!(closes, plain.expanded, "{algorithm:?}");
            // Every closed cell was opened before.
            let mut opened = std::collections::HashSet::new();
            for e in &log.events {
                match e {
                    SearchEvent::Open { cell, .. } => {
                        opened.insert(*cell);
                    }
                    SearchEvent::Close { cell } => assert!(opened.contains(cell), "{algorithm:?}"),
                    SearchEvent::Line { .. } => {}
                }
            }
        }
    }
}

#[test]
fn bad_input_gets_the_typed_errors() {
    let map = OccupancyGrid::from_ascii("...\n.#.\n...\n").unwrap();
    let (free, wall, off) = (GridPos::new(0, 0), GridPos::new(1, 1), GridPos::new(9, 0));
    for algorithm in NEW.into_iter().chain([Algorithm::Jps]) {
        let options = GridPlanOptions {
            algorithm,
            diagonal: if algorithm == Algorithm::Jps {
                Diagonal::Never
            } else {
                NCC
            },
            ..GridPlanOptions::default()
        };
        let plan = |s, t, o: &GridPlanOptions| plan_on_map(&map, s, t, o);
        assert!(matches!(
            plan(wall, free, &options),
            Err(GridPlanError::Plan(PlanError::Blocked { .. }))
        ));
        assert!(matches!(
            plan(free, off, &options),
            Err(GridPlanError::Plan(PlanError::OffMap { .. }))
        ));
        let nan = GridPlanOptions {
            weight: f64::NAN,
            ..options
        };
        assert!(matches!(
            plan(free, GridPos::new(2, 2), &nan),
            Err(GridPlanError::Plan(PlanError::InvalidConfig(_)))
        ));
        let walled = OccupancyGrid::from_ascii(".#.\n##.\n...\n").unwrap();
        assert!(
            matches!(
                plan_on_map(&walled, free, GridPos::new(2, 2), &options),
                Err(GridPlanError::Plan(PlanError::Unreachable { .. }))
            ),
            "{algorithm:?}"
        );
        assert_eq!(plan(free, free, &options).unwrap().path.cells, vec![free]);
    }
    for diagonal in [Diagonal::OneSideFree, Diagonal::Always] {
        let err = build_planner(&GridPlanOptions {
            algorithm: Algorithm::Jps,
            diagonal,
            ..GridPlanOptions::default()
        })
        .err()
        .unwrap();
        assert!(err.to_string().contains("use A*"), "{err}");
    }
}
