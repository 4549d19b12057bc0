//! A grid search as a Posthoc trace (`global::posthoc`): every planner's
//! trace replays to its expanded count, its parent links are the search's,
//! and the document is what Posthoc 1.4.0 reads.

use planlab_core::global::plan::{plan_on_map, Algorithm, GridPlanOptions};
use planlab_core::global::posthoc::{posthoc_trace, PosthocError, DEFAULT_EVENT_LIMIT};
use planlab_core::global::GridPos;
use planlab_core::map::io::movingai::{parse_map, parse_scen};
use planlab_core::map::OccupancyGrid;
use std::collections::{HashMap, HashSet};

const MOVINGAI: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/data/movingai");

fn arena() -> (OccupancyGrid, Vec<(GridPos, GridPos)>) {
    let read = |rel: &str| std::fs::read_to_string(format!("{MOVINGAI}/{rel}")).unwrap();
    let map = parse_map(&read("dao/arena.map")).unwrap();
    let rows = parse_scen(&read("dao/arena.map.scen")).unwrap();
    let q = rows.iter().step_by(25).map(|r| (r.start, r.goal)).collect();
    (map, q)
}

#[test]
fn every_planners_trace_replays_to_its_expanded_count_with_consistent_parents() {
    let (map, queries) = arena();
    let w = map.width() as u64;
    for (algo, name) in Algorithm::ALL {
        let opts = GridPlanOptions {
            algorithm: algo,
            ..Default::default()
        };
        for &(s, t) in &queries {
            let plain = plan_on_map(&map, s, t, &opts).unwrap();
            let (trace, plan) = posthoc_trace(&map, s, t, &opts, DEFAULT_EVENT_LIMIT).unwrap();
            assert_eq!(plan, plain, "{name} {s:?}→{t:?}: tracing changed the plan");
            assert_eq!(
                trace.count("expanding"),
                plan.path.expanded,
                "{name} {s:?}→{t:?}"
            );
            assert_eq!(
                trace.count("closing"),
                plan.path.expanded,
                "{name} {s:?}→{t:?}"
            );
            assert_eq!(trace.events[0].kind, "source");
            assert_eq!(trace.events[0].id, u64::from(s.row) * w + u64::from(s.col));
            assert_eq!(trace.events[1].kind, "destination");
            assert_eq!((trace.events[1].x, trace.events[1].y), (t.col, t.row));
            // Every expansion is of a generated cell, and is closed before
            // the next one starts.
            let mut generated = HashSet::new();
            let mut open_expansion = None;
            for e in &trace.events[2..] {
                assert_eq!(
                    e.id,
                    u64::from(e.y) * w + u64::from(e.x),
                    "{name}: id of {e:?}"
                );
                match e.kind {
                    "generating" | "updating" => {
                        assert!(e.g.is_some_and(f64::is_finite) && e.f.is_some_and(f64::is_finite));
                        assert_eq!(
                            e.kind == "generating",
                            generated.insert(e.id),
                            "{name}: {e:?}"
                        );
                    }
                    "expanding" => {
                        assert!(
                            generated.contains(&e.id),
                            "{name}: expanded before generated: {e:?}"
                        );
                        assert_eq!(open_expansion.replace(e.id), None, "{name}: {e:?}");
                    }
                    "closing" => assert_eq!(open_expansion.take(), Some(e.id), "{name}: {e:?}"),
                    "end" => assert_eq!((e.x, e.y), (t.col, t.row)),
                    k => panic!("{name}: unexpected event type {k}"),
                }
            }
        }
    }
}

#[test]
fn the_end_events_parent_chain_is_the_astar_path() {
    let (map, queries) = arena();
    let w = map.width() as u64;
    for algo in [Algorithm::AStar, Algorithm::Dijkstra, Algorithm::SafeAStar] {
        let opts = GridPlanOptions {
            algorithm: algo,
            ..Default::default()
        };
        for &(s, t) in &queries {
            let (trace, plan) = posthoc_trace(&map, s, t, &opts, DEFAULT_EVENT_LIMIT).unwrap();
            let parent: HashMap<u64, Option<u64>> = trace
                .events
                .iter()
                .filter_map(|e| e.p_id.map(|p| (e.id, p)))
                .collect();
            let end = trace.events.last().unwrap();
            assert_eq!(end.kind, "end");
            // The path's g at the goal is its cost.
            assert!((end.g.unwrap() - plan.path.cost).abs() < 1e-9, "{algo:?}");
            let mut chain = vec![end.id];
            while let Some(Some(p)) = parent.get(chain.last().unwrap()) {
                chain.push(*p);
                assert!(
                    chain.len() <= plan.path.cells.len() + 1,
                    "{algo:?}: a cycle"
                );
            }
            chain.reverse();
            let id = |p: &GridPos| u64::from(p.row) * w + u64::from(p.col);
            assert_eq!(
                chain,
                plan.path.cells.iter().map(id).collect::<Vec<_>>(),
                "{algo:?}"
            );
        }
    }
}

#[test]
fn the_document_is_posthoc_1_4_0_json() {
    let (map, queries) = arena();
    let (s, t) = queries[3];
    let (trace, plan) = posthoc_trace(&map, s, t, &GridPlanOptions::default(), 1 << 20).unwrap();
    let doc: serde_json::Value =
        serde_json::from_str(&serde_json::to_string(&trace).unwrap()).unwrap();
    assert_eq!(doc["version"], "1.4.0");
    assert_eq!(doc["views"]["main"][0]["$"], "rect");
    assert_eq!(doc["pivot"]["x"], "${{ $.x + 0.5 }}");
    let events = doc["events"].as_array().unwrap();
    assert_eq!(
        events[0],
        serde_json::json!({"type": "source", "id": u64::from(s.row) * map.width() as u64 + u64::from(s.col), "x": s.col, "y": s.row})
    );
    // The start is generated with a null parent, g 0 and f its heuristic.
    let first = events.iter().find(|e| e["type"] == "generating").unwrap();
    assert!(first["pId"].is_null() && first.get("pId").is_some());
    assert_eq!(first["g"], 0.0);
    assert!(first["f"].as_f64().unwrap() > 0.0);
    assert_eq!(
        events.iter().filter(|e| e["type"] == "expanding").count(),
        plan.path.expanded
    );
}

#[test]
fn a_trace_over_its_event_limit_is_refused_not_cut() {
    let (map, queries) = arena();
    let (s, t) = *queries.last().unwrap();
    let err = posthoc_trace(&map, s, t, &GridPlanOptions::default(), 100).unwrap_err();
    assert_eq!(err, PosthocError::TooLarge { limit: 100 });
    assert!(err.to_string().contains("more than 100 trace events"));
}
