//! "Explain this step" (`SearchReplay::explain`, `global::explain`): the
//! open list rebuilt from a recorded search in each planner's order puts
//! first the cell the planner expands next, at every expansion of whole
//! searches on Moving AI maps; the explained f is g + w·h; the neighbours
//! listed are the expansion's open events with the g each had before.

use planlab_core::draw::{SearchReplay, StepKind};
use planlab_core::global::explain::{OpenOrder, Priority};
use planlab_core::global::plan::{plan_on_map_observed, Algorithm, GridPlanOptions};
use planlab_core::global::{Diagonal, GridPos, Heuristic, SearchEvent, SearchLog};
use planlab_core::map::io::movingai::{parse_map, parse_scen};
use planlab_core::map::OccupancyGrid;

const MOVINGAI: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/data/movingai");

fn map(rel: &str, rows: usize) -> (OccupancyGrid, Vec<(GridPos, GridPos)>) {
    let read = |rel: &str| std::fs::read_to_string(format!("{MOVINGAI}/{rel}")).unwrap();
    let map = parse_map(&read(rel)).unwrap();
    let mut all = parse_scen(&read(&format!("{rel}.scen"))).unwrap();
    // The longest queries, every other one: long searches with many ties.
    all.sort_by(|a, b| b.optimal.total_cmp(&a.optimal));
    let q = all
        .iter()
        .step_by(2)
        .take(rows)
        .map(|r| (r.start, r.goal))
        .collect();
    (map, q)
}

fn record(
    grid: &OccupancyGrid,
    (s, g): (GridPos, GridPos),
    o: &GridPlanOptions,
) -> Vec<SearchEvent> {
    let mut log = SearchLog::with_limit(usize::MAX);
    plan_on_map_observed(grid, s, g, o, &mut log).expect("a path");
    log.events
}

/// For every close event after the first: explained one event into the
/// previous expansion, the open list's first entry is that close's cell.
/// Returns the number of expansions checked.
fn first_entry_is_next_expanded(
    grid: &OccupancyGrid,
    events: Vec<SearchEvent>,
    o: &GridPlanOptions,
) -> usize {
    let order = OpenOrder::of(o);
    let weight = match order.priority {
        Priority::F { weight } => weight,
        _ => 1.0,
    };
    let closes: Vec<usize> = (0..events.len())
        .filter(|&i| matches!(events[i], SearchEvent::Close { .. }))
        .collect();
    let mut r = SearchReplay::new(grid, events.clone(), weight);
    for w in closes.windows(2) {
        let (c, next) = (w[0], w[1]);
        r.seek(c + 1);
        let x = r.explain(&order, 5);
        assert_eq!(x.kind, StepKind::Expand);
        assert_eq!(x.expanded_at, Some(c + 1));
        let SearchEvent::Close { cell: want } = events[next] else {
            unreachable!()
        };
        assert_eq!(x.next_expanded, Some(want));
        let first = x.open.first().map(|e| e.cell);
        assert_eq!(
            first,
            Some(want),
            "{:?}: after the expansion at step {}, the open list {:?} should start with {want:?}",
            o.algorithm,
            c + 1,
            x.open
        );
        // The whole expansion's opens, played or not, are listed.
        let opens = events[c + 1..next]
            .iter()
            .filter(|e| matches!(e, SearchEvent::Open { .. }))
            .count();
        assert_eq!(x.relaxed.len(), opens);
        assert!(x.relaxed.iter().all(|n| !n.played));
        // Explained from the middle of the expansion: the same list.
        if next > c + 2 {
            r.seek(next - 1);
            let mid = r.explain(&order, 5);
            let cells = |v: &[planlab_core::draw::OpenEntry]| {
                v.iter().map(|e| (e.cell, e.g)).collect::<Vec<_>>()
            };
            assert_eq!(cells(&mid.open), cells(&x.open));
            let played = events[c + 1..next - 1]
                .iter()
                .filter(|e| matches!(e, SearchEvent::Open { .. }))
                .count();
            assert_eq!(mid.relaxed.iter().filter(|n| n.played).count(), played);
        }
    }
    closes.len()
}

fn check(rel: &str, rows: usize, o: GridPlanOptions, min: usize) {
    let (grid, queries) = map(rel, rows);
    let mut expansions = 0;
    for q in queries {
        let events = record(&grid, q, &o);
        expansions += first_entry_is_next_expanded(&grid, events, &o);
    }
    assert!(
        expansions >= min,
        "{:?}: only {expansions} expansions checked",
        o.algorithm
    );
}

fn with(algorithm: Algorithm) -> GridPlanOptions {
    GridPlanOptions {
        algorithm,
        ..GridPlanOptions::default()
    }
}

#[test]
fn astar_open_list_starts_with_the_cell_it_expands_next() {
    check("dao/arena2.map", 4, with(Algorithm::AStar), 300);
    check("dao/arena.map", 8, with(Algorithm::AStar), 300);
    // 4-connected: many equal f, so the tie rule decides.
    let four = GridPlanOptions {
        diagonal: Diagonal::Never,
        ..with(Algorithm::AStar)
    };
    check("dao/arena2.map", 4, four, 300);
}

#[test]
fn weighted_and_other_heuristic_astar_open_lists_start_with_the_next_expansion() {
    for (heuristic, weight) in [
        (Heuristic::Octile, 1.7),
        (Heuristic::Euclidean, 1.0),
        (Heuristic::Manhattan, 2.0),
    ] {
        let o = GridPlanOptions {
            heuristic,
            weight,
            ..with(Algorithm::AStar)
        };
        check("dao/arena2.map", 3, o, 1000);
    }
}

#[test]
fn dijkstra_jps_theta_greedy_bfs_safe_open_lists_start_with_the_next_expansion() {
    let mut safe = with(Algorithm::SafeAStar);
    safe.safe.admissible = true;
    for o in [
        with(Algorithm::Dijkstra),
        with(Algorithm::Jps),
        GridPlanOptions {
            heuristic: Heuristic::Euclidean,
            ..with(Algorithm::Jps)
        },
        GridPlanOptions {
            diagonal: Diagonal::Never,
            ..with(Algorithm::Jps)
        },
        with(Algorithm::ThetaStar),
        with(Algorithm::Greedy),
        with(Algorithm::Bfs),
        safe,
    ] {
        let min = if o.algorithm == Algorithm::Jps {
            5
        } else {
            150
        };
        check("dao/arena.map", 4, o, min);
    }
}

#[test]
fn explained_f_is_g_plus_weighted_h_and_neighbours_show_their_old_g() {
    let (grid, q) = map("dao/arena2.map", 3);
    let o = GridPlanOptions {
        weight: 1.5,
        ..with(Algorithm::AStar)
    };
    let events = record(&grid, q[2], &o);
    let order = OpenOrder::of(&o);
    let mut r = SearchReplay::new(&grid, events.clone(), 1.5);
    let mut improved = 0;
    for step in 1..=events.len() {
        r.seek(step);
        let x = r.explain(&order, 5);
        let Some(e) = x.expanded else { continue };
        assert!((e.priority - (e.g + 1.5 * e.h)).abs() < 1e-9);
        // The expanded cell's g, h are those of its latest open event.
        let info = r.info(e.cell.col as usize, e.cell.row as usize).unwrap();
        assert_eq!((info.g, info.h), (e.g, e.h));
        for n in &x.relaxed {
            if n.old_g.is_finite() {
                assert!(n.entry.g < n.old_g, "an improvement lowers g");
                improved += 1;
            }
            assert!(
                (n.entry.g - e.g).abs() <= std::f64::consts::SQRT_2 + 1e-9,
                "a neighbour's g is the expanded g plus one move"
            );
            assert_eq!(n.parent, Some(e.cell));
        }
        for pair in x.open.windows(2) {
            assert!(pair[0].priority <= pair[1].priority + 1e-9, "by f");
        }
    }
    assert!(improved > 0, "some step improves a cell's g");
}

#[test]
fn planners_whose_order_is_unrecorded_say_so_and_list_nothing() {
    let (grid, q) = map("dao/arena.map", 2);
    for a in [
        Algorithm::IdaStar,
        Algorithm::DStarLite,
        Algorithm::BidirectionalAStar,
        Algorithm::SafeAStar,
    ] {
        let o = with(a);
        let order = OpenOrder::of(&o);
        assert!(order.ties.is_none() && !order.missing.is_empty(), "{a:?}");
        let events = record(&grid, q[0], &o);
        let mut r = SearchReplay::new(&grid, events.clone(), 1.0);
        r.seek(events.len() / 2);
        let x = r.explain(&order, 5);
        assert!(x.open.is_empty());
        assert!(x.open_len > 0 || a == Algorithm::IdaStar);
    }
}
