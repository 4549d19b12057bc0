//! The search as events (`global::events`): an A* search replays to a
//! consistent state, and recording changes no planner's answer.

use planlab_core::global::astar::AStar;
use planlab_core::global::jps::Jps;
use planlab_core::global::plan::{
    plan_on_map, plan_on_map_observed, plan_on_map_recording, Algorithm, GridPlanOptions,
};
use planlab_core::global::safe_astar::{SafeAStar, SafeAStarConfig};
use planlab_core::global::{
    Diagonal, GridPos, ObservedGridPlanner, PlanGrid, SearchEvent, SearchLog, SearchObserver,
};
use planlab_core::map::io::movingai::{parse_map, parse_scen};
use planlab_core::map::OccupancyGrid;
use std::collections::HashMap;

const MOVINGAI: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/data/movingai");

fn arena() -> (OccupancyGrid, Vec<(GridPos, GridPos)>) {
    let read = |rel: &str| std::fs::read_to_string(format!("{MOVINGAI}/{rel}")).unwrap();
    let map = parse_map(&read("dao/arena.map")).unwrap();
    let rows = parse_scen(&read("dao/arena.map.scen")).unwrap();
    // Every 10th row: short and long queries alike.
    let q = rows.iter().step_by(10).map(|r| (r.start, r.goal)).collect();
    (map, q)
}

fn step_cost(a: GridPos, b: GridPos) -> f64 {
    let (dc, dr) = (a.col.abs_diff(b.col), a.row.abs_diff(b.row));
    ((dc * dc + dr * dr) as f64).sqrt()
}

/// Replays `events` of a cell-by-cell search (A*, Dijkstra) and says what
/// is inconsistent: a Close of a cell never opened or closed twice, an Open
/// of a closed cell, an Open whose g is not its parent's g plus the move,
/// a parent that is not closed. Returns the number of Close events.
fn replay(events: &[SearchEvent], start: GridPos) -> Result<usize, String> {
    let mut g: HashMap<GridPos, f64> = HashMap::new();
    let mut closed: HashMap<GridPos, usize> = HashMap::new();
    for (k, e) in events.iter().enumerate() {
        match *e {
            SearchEvent::Open {
                cell,
                parent,
                g: gc,
                h,
            } => {
                if closed.contains_key(&cell) {
                    return Err(format!("event {k}: {cell:?} opened after it was closed"));
                }
                if !(h.is_finite() && h >= 0.0) {
                    return Err(format!("event {k}: h = {h}"));
                }
                match parent {
                    None if cell == start && gc == 0.0 => {}
                    None => return Err(format!("event {k}: {cell:?} has no parent")),
                    Some(p) => {
                        if !closed.contains_key(&p) {
                            return Err(format!("event {k}: parent {p:?} is not closed"));
                        }
                        let want = g[&p] + step_cost(p, cell);
                        if (gc - want).abs() > 1e-9 {
                            return Err(format!("event {k}: g {gc} ≠ parent's g + move {want}"));
                        }
                        if let Some(&old) = g.get(&cell) {
                            if gc >= old {
                                return Err(format!("event {k}: reopened at {gc} ≥ {old}"));
                            }
                        }
                    }
                }
                g.insert(cell, gc);
            }
            SearchEvent::Close { cell } => {
                if !g.contains_key(&cell) {
                    return Err(format!("event {k}: {cell:?} closed but never opened"));
                }
                if closed.insert(cell, k).is_some() {
                    return Err(format!("event {k}: {cell:?} closed twice"));
                }
            }
            SearchEvent::Line { .. } => return Err(format!("event {k}: A* has no line tests")),
        }
    }
    Ok(closed.len())
}

#[test]
fn astar_events_replay_to_a_consistent_search() {
    let (map, queries) = arena();
    let grid = PlanGrid::new(&map, false);
    for planner in [AStar::default(), AStar::dijkstra(Diagonal::NoCornerCutting)] {
        for &(s, t) in &queries {
            let mut log = SearchLog::with_limit(usize::MAX);
            let path = planner.plan_observed(&grid, s, t, &mut log).unwrap();
            assert!(!log.truncated);
            let closes = replay(&log.events, s).unwrap_or_else(|e| panic!("{s:?}→{t:?}: {e}"));
            assert_eq!(closes, path.expanded, "{s:?}→{t:?}");
            // The last event closes the goal, reached at the path's cost.
            assert_eq!(log.events.last(), Some(&SearchEvent::Close { cell: t }));
            let g_goal = log.events.iter().rev().find_map(|e| match e {
                SearchEvent::Open { cell, g, .. } if *cell == t => Some(*g),
                _ => None,
            });
            assert!((g_goal.unwrap() - path.cost).abs() < 1e-9);
        }
    }
}

#[test]
fn recording_changes_no_planner_answer() {
    let (map, queries) = arena();
    let grid = PlanGrid::new(&map, false);
    let planners: [(&str, &dyn ObservedGridPlanner); 4] = [
        ("astar", &AStar::default()),
        ("dijkstra", &AStar::dijkstra(Diagonal::NoCornerCutting)),
        ("jps", &Jps::default()),
        (
            "safe-astar",
            &SafeAStar::new(SafeAStarConfig::default()).unwrap(),
        ),
    ];
    for (name, planner) in planners {
        let mut lines = 0;
        for &(s, t) in &queries {
            let plain = planner.plan(&grid, s, t).unwrap();
            let mut log = SearchLog::with_limit(usize::MAX);
            let seen = planner.plan_observed(&grid, s, t, &mut log).unwrap();
            assert_eq!(plain, seen, "{name} {s:?}→{t:?}");
            let closes = log
                .events
                .iter()
                .filter(|e| matches!(e, SearchEvent::Close { .. }))
                .count();
            assert_eq!(closes, plain.expanded, "{name} {s:?}→{t:?}");
            lines += log
                .events
                .iter()
                .filter(|e| matches!(e, SearchEvent::Line { .. }))
                .count();
        }
        // Only JPS scans lines; its scans are what the page draws.
        assert_eq!(lines > 0, name == "jps", "{name}: {lines} line events");
    }
}

#[test]
fn jps_scans_run_along_straight_or_diagonal_lines_over_free_cells() {
    let (map, queries) = arena();
    let grid = PlanGrid::new(&map, false);
    for &(s, t) in &queries {
        let mut log = SearchLog::with_limit(usize::MAX);
        Jps::default().plan_observed(&grid, s, t, &mut log).unwrap();
        for e in &log.events {
            if let SearchEvent::Line { from, to, .. } = *e {
                let (dc, dr) = (from.col.abs_diff(to.col), from.row.abs_diff(to.row));
                assert!(dc == 0 || dr == 0 || dc == dr, "{from:?}→{to:?}");
                assert!(grid.is_free(to.col as i64, to.row as i64), "{to:?}");
                assert!(grid.segment_is_free(from, to, Diagonal::NoCornerCutting));
            }
        }
    }
}

#[test]
fn plan_on_map_reports_keypoint_and_bottom_up_checks() {
    let (map, queries) = arena();
    let (s, t) = queries[queries.len() - 1];
    let options = GridPlanOptions {
        keypoints: true,
        bottom_up_eps: Some(1.5),
        ..GridPlanOptions::default()
    };
    let plain = plan_on_map_recording(&map, s, t, &options).unwrap();
    let mut log = SearchLog::with_limit(usize::MAX);
    let seen = plan_on_map_observed(&map, s, t, &options, &mut log).unwrap();
    assert_eq!(plain.path, seen.path);
    assert_eq!(plain.keypoints, seen.keypoints);
    assert_eq!(plain.feature_nodes, seen.feature_nodes);
    // The search's closes are the cells plan_on_map records.
    let closes: Vec<GridPos> = log
        .events
        .iter()
        .filter_map(|e| match e {
            SearchEvent::Close { cell } => Some(*cell),
            _ => None,
        })
        .collect();
    assert_eq!(closes, plain.expanded_cells);
    // A* has no line tests, so every Line is a segment check between path
    // cells, after the search.
    let last_close = log
        .events
        .iter()
        .rposition(|e| matches!(e, SearchEvent::Close { .. }))
        .unwrap();
    let lines: Vec<_> = log.events[last_close + 1..].to_vec();
    assert!(lines.len() >= 2, "{} segment checks", lines.len());
    for e in &lines {
        let SearchEvent::Line { from, to, clear } = *e else {
            panic!("{e:?} after the search");
        };
        assert!(plain.path.cells.contains(&from) && plain.path.cells.contains(&to));
        assert_eq!(
            clear,
            PlanGrid::new(&map, false).segment_is_free(from, to, options.diagonal)
        );
    }
}

#[test]
fn a_full_log_stops_recording_but_not_the_search() {
    let (map, queries) = arena();
    let (s, t) = queries[queries.len() - 1];
    let options = GridPlanOptions {
        algorithm: Algorithm::AStar,
        ..GridPlanOptions::default()
    };
    let full = plan_on_map(&map, s, t, &options).unwrap();
    let mut log = SearchLog::with_limit(10);
    let cut = plan_on_map_observed(&map, s, t, &options, &mut log).unwrap();
    assert_eq!(full.path, cut.path);
    assert_eq!(log.events.len(), 10);
    assert!(log.truncated);
    assert!(!log.enabled());
}
