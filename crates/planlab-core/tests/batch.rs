//! Batch variants: seeded, within the jitter, always startable, identical
//! for every planner; statistics per planner.

use planlab_core::batch::{self, BatchError};
use planlab_core::map::OccupancyGrid;
use planlab_core::metrics::{EpisodeMetrics, DEFAULT_LOAD_THRESHOLD_N};
use planlab_core::scenario::Scenario;
use planlab_core::sim::{Episode, Outcome};
use planlab_core::world::MotionModel;

fn preset(file: &str) -> (Scenario, OccupancyGrid) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenarios")
        .join(file);
    let s = Scenario::from_json(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let g = s
        .load_grid(&mut |p| Err(format!("{file} should have an inline map, not {p}")))
        .unwrap();
    (s, g)
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

#[test]
fn variants_stay_within_the_jitter_and_can_start() {
    let (base, grid) = preset("dwa-demo.json");
    let j = 0.5;
    let mut starts = Vec::new();
    for i in 0..12 {
        let v = batch::variant(&base, &grid, i, 7, j).unwrap();
        assert_eq!(v, batch::variant(&base, &grid, i, 7, j).unwrap(), "seeded");
        let (s0, s1) = (base.start_world(&grid), v.start_world(&grid));
        let (g0, g1) = (base.goal_world(&grid), v.goal_world(&grid));
        // Each axis within j: the distance within j·√2.
        assert!(dist(s0, s1) <= j * 2f64.sqrt() + 1e-9);
        assert!(dist(g0, g1) <= j * 2f64.sqrt() + 1e-9);
        if i == 0 {
            assert_eq!((s0, g0), (s1, g1), "variant 0 is the scenario as written");
        }
        for (m0, m1) in base.movers.iter().flatten().zip(v.movers.iter().flatten()) {
            if let (
                MotionModel::BackAndForth { a: a0, b: b0, .. },
                MotionModel::BackAndForth { a: a1, b: b1, .. },
            ) = (&m0.motion, &m1.motion)
            {
                // One offset per mover: the segment is translated, not bent.
                let d = [a1[0] - a0[0], a1[1] - a0[1]];
                assert!((b1[0] - b0[0] - d[0]).abs() < 1e-12);
                assert!((b1[1] - b0[1] - d[1]).abs() < 1e-12);
            }
        }
        // It starts, and the episode seed is the variant's.
        assert!(Episode::from_scenario(&v, grid.clone()).is_ok());
        assert_eq!(v.seed, Some(batch::variant_seed(7, i)));
        starts.push(s1);
    }
    starts.dedup();
    assert!(starts.len() > 8, "jitter moved the start: {starts:?}");
}

#[test]
fn bad_jitter_and_impossible_placements_are_errors() {
    let (base, grid) = preset("dwa-demo.json");
    assert!(matches!(
        batch::variant(&base, &grid, 1, 0, f64::NAN),
        Err(BatchError::BadJitter(_))
    ));
    assert!(matches!(
        batch::variant(&base, &grid, 1, 0, -0.1),
        Err(BatchError::BadJitter(_))
    ));
    // A start inside a wall cannot be fixed by a zero jitter.
    let mut walled = base.clone();
    let (c, r) = (0..grid.height())
        .flat_map(|r| (0..grid.width()).map(move |c| (c, r)))
        .find(|&(c, r)| !grid.get(c, r).unwrap().passable(false))
        .unwrap();
    walled.start = planlab_core::scenario::ScenarioPoint::cell(c as u32, r as u32);
    assert!(matches!(
        batch::variant(&walled, &grid, 3, 0, 0.0),
        Err(BatchError::NoPlacement { tries: 1, .. })
    ));
}

#[test]
fn summary_counts_outcomes_and_uses_reached_runs_only() {
    let (base, grid) = preset("pursuit-demo.json");
    let mut runs = Vec::new();
    for i in 0..4 {
        let v = batch::variant(&base, &grid, i, 3, 0.3).unwrap();
        let mut ep = Episode::from_scenario(&v, grid.clone()).unwrap();
        let out = ep.run();
        runs.push(EpisodeMetrics::from_trace(
            ep.trace(),
            &ep.planner_debug().global_path,
            out,
            DEFAULT_LOAD_THRESHOLD_N,
        ));
    }
    // One failed run: its (huge) time must not enter the statistics.
    let mut failed = runs[0].clone();
    failed.outcome = Outcome::Timeout;
    failed.time_s = 1e6;
    runs.push(failed);
    let s = batch::summarise("pursuit", &runs);
    assert_eq!(s.runs, 5);
    assert_eq!(s.reached, 4, "{s:?}");
    assert_eq!(s.outcomes["timeout"], 1);
    assert!((s.success_rate - 0.8).abs() < 1e-12);
    let t = s.metrics["time_s"];
    assert_eq!(t.n, 4);
    assert!(t.max < 1e5);
    assert!(t.ci95[0] <= t.mean && t.mean <= t.ci95[1]);
}
