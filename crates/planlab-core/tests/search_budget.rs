//! Work budgets of the grid planners on hostile maps: a goal that cannot be
//! reached on a large open map must cost each planner about what it costs
//! A* (one expansion per reachable cell), counted in expansions and
//! line-of-sight tests, not seconds; node tables must not take memory for
//! cells a search never reaches.

use planlab_core::global::plan::{build_observed_planner, Algorithm, GridPlanOptions};
use planlab_core::global::{GridPos, PlanError, PlanGrid, SearchEvent, SearchObserver};

/// Counts the line-of-sight tests a search reports.
#[derive(Default)]
struct Lines(usize);

impl SearchObserver for Lines {
    fn event(&mut self, e: SearchEvent) {
        if matches!(e, SearchEvent::Line { .. }) {
            self.0 += 1;
        }
    }
}

/// An open `side`² map whose centre cell is walled in by a ring of blocked
/// cells: the centre is unreachable from anywhere else.
fn walled_centre(side: usize) -> (PlanGrid, GridPos) {
    let c = side / 2;
    let grid = PlanGrid::from_fn(side, side, |col, row| {
        let ring = col.abs_diff(c).max(row.abs_diff(c)) == 1;
        !ring
    });
    (grid, GridPos::new(c as u32, c as u32))
}

/// Expansions (from the planner's error) plus line-of-sight tests of
/// planning `start` → `goal` with `algorithm`, which must fail.
fn work(algorithm: Algorithm, grid: &PlanGrid, start: GridPos, goal: GridPos) -> usize {
    let options = GridPlanOptions {
        algorithm,
        ..Default::default()
    };
    let planner = build_observed_planner(&options).unwrap();
    let mut lines = Lines::default();
    let expanded = match planner.plan_observed(grid, start, goal, &mut lines) {
        Err(PlanError::Unreachable { expanded }) => expanded,
        Err(PlanError::SearchLimit { expanded, .. }) => expanded,
        other => panic!("{}: {other:?}", algorithm.name()),
    };
    expanded + lines.0
}

#[test]
fn every_grid_planner_gives_up_on_an_unreachable_goal_within_a_few_times_astars_work() {
    let (grid, goal) = walled_centre(2000);
    let start = GridPos::new(0, 0);
    let astar = work(Algorithm::AStar, &grid, start, goal);
    // A* closes every reachable cell once.
    assert!(astar > 3_990_000, "{astar}");
    for (algorithm, name) in Algorithm::ALL {
        let w = work(algorithm, &grid, start, goal);
        // Theta* once made 8 line-of-sight tests from a distant
        // grandparent for every cell it closed (minutes here).
        assert!(w <= 4 * astar, "{name}: {w} units of work, A* {astar}");
    }
}

#[test]
fn a_search_walled_in_at_its_start_on_a_huge_map_gives_up_at_once() {
    // 10⁸ cells, the start boxed in: the searches from the start give up
    // after one expansion and (pages allocated on first touch) without
    // allocating tables for the whole map; D* Lite searches back from the
    // open goal, so it is left out here. JPS+ would need a jump table for
    // every cell (1.6 GB): it refuses the map at once with a typed error.
    let side = 10_000;
    let grid = PlanGrid::from_fn(side, side, |col, row| {
        col.max(row) != 1 || (col == 0 && row == 0)
    });
    let start = GridPos::new(0, 0);
    let goal = GridPos::new(9_999, 9_999);
    for (algorithm, name) in Algorithm::ALL {
        if algorithm == Algorithm::DStarLite {
            continue;
        }
        if algorithm == Algorithm::JpsPlus {
            let planner = build_observed_planner(&GridPlanOptions {
                algorithm,
                ..Default::default()
            })
            .unwrap();
            let err = planner.plan_observed(&grid, start, goal, &mut Lines::default());
            assert!(
                matches!(&err, Err(PlanError::InvalidConfig(m)) if m.contains("too large for the JPS+")),
                "{err:?}"
            );
            continue;
        }
        let w = work(algorithm, &grid, start, goal);
        assert!(w <= 8, "{name}: {w}");
    }
}
