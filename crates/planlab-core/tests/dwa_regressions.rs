//! Regression tests of DWA-family planners that misbehaved by their own
//! papers' method: each replays the scene that showed the bug.

use planlab_core::batch;
use planlab_core::local::registry::PlannerChoice;
use planlab_core::map::io::scenario::Scenario;
use planlab_core::map::OccupancyGrid;
use planlab_core::sim::{Episode, Outcome, Trace};

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

/// Runs `scenario` with `planner` (its default config): outcome and trace.
fn run(scenario: &Scenario, grid: &OccupancyGrid, planner: &str) -> (Outcome, Trace) {
    let mut s = scenario.clone();
    s.local_planner = Some(PlannerChoice::named(planner));
    let mut ep = Episode::from_scenario(&s, grid.clone()).unwrap();
    let outcome = ep.run();
    (outcome, ep.trace().clone())
}

/// \[53\] decelerates for moving obstacles only: in front of a still disc
/// on the start–goal line (T-fig3-11's, its mover taken out) it used to
/// hold the deceleration weights and braking and wait for the disc to
/// leave, stuck, where plain DWA drives round it. Now it is plain DWA there.
#[test]
fn fusion53_passes_a_still_disc_where_plain_dwa_does() {
    let (mut base, grid) = preset("T-fig3-11.json");
    let movers = base.movers.as_mut().unwrap();
    movers.retain(|m| m.id == 2);
    assert_eq!(movers.len(), 1, "T-fig3-11 keeps its still disc, id 2");
    for k in 0..4 {
        let scene = batch::variant(&base, &grid, k, 1, 0.2).unwrap();
        let (dwa, _) = run(&scene, &grid, "dwa");
        let (f53, trace) = run(&scene, &grid, "fusion-53");
        assert_eq!(dwa, Outcome::Reached, "variant {k}: plain DWA reaches");
        assert_eq!(f53, Outcome::Reached, "variant {k}: fusion-53 too");
        assert!(
            trace.steps.iter().all(|s| s.mode != "decelerate"),
            "variant {k}: no deceleration strategy for a still disc"
        );
        assert!(trace.steps.iter().all(|s| s.clearance > 0.0));
    }
}
