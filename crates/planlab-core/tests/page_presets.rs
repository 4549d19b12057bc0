//! The robot page's own presets (`assets/scenarios/dwa-demo.json`, the page
//! opens with it; `dwa-crowd.json`, its frame-rate scene) keep doing what
//! the page and its browser tests rely on, checked natively so a change in
//! a planner that breaks them shows up in `cargo test`; the [S] presets the
//! page lists run to the goal with `safe-dual-dwa` and show its feature nodes.

use planlab_core::local::GoalKind;
use planlab_core::planners::PlannerChoice;
use planlab_core::scenario::Scenario;
use planlab_core::sim::{Episode, Outcome};

fn episode(file: &str) -> Episode {
    let path = format!(
        "{}/../../assets/scenarios/{file}",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).unwrap();
    let sc = Scenario::from_json(&text).unwrap();
    let grid = sc
        .load_grid(&mut |p| Err(format!("{file} should have an inline map, not {p}")))
        .unwrap();
    Episode::from_scenario(&sc, grid).unwrap()
}

#[test]
fn demo_reaches_the_goal_with_every_dwa_of_t() {
    // The page's demo preset: planner swaps in the page should work there.
    for name in ["dwa", "improved-dwa", "fusion-53"] {
        let mut ep = episode("dwa-demo.json");
        if name != "dwa" {
            ep.set_planner(PlannerChoice::named(name)).unwrap();
        }
        assert_eq!(ep.run(), Outcome::Reached, "{name} on dwa-demo.json");
        let min = ep
            .trace()
            .steps
            .iter()
            .map(|r| r.clearance)
            .fold(f64::INFINITY, f64::min);
        assert!(min > 0.0, "{name}: touched something (min clearance {min})");
    }
}

#[test]
fn crowd_has_20_movers_and_a_20_by_40_fan() {
    let mut ep = episode("dwa-crowd.json");
    assert_eq!(ep.movers().len(), 20);
    ep.set_record_rollouts(true);
    ep.step();
    let d = ep.planner_debug();
    // 20 × 40 samples, plus v = 0 / ω = 0 where the even spread misses them.
    let n = d.rollouts.len();
    assert!((800..=21 * 41).contains(&n), "{n} rollouts");
    assert!(d.rollouts.iter().all(|r| !r.points.is_empty()));
    // Every mover is within sensing range, so the planner sees all 20.
    assert!(ep.config().sensing_range >= 30.0);
}

#[test]
fn s_presets_reach_with_safe_dual_dwa_and_draw_the_feature_nodes() {
    // The page lists the [S] presets (they name safe-dual-dwa); it draws the
    // planner's global path, feature nodes and current temporary goal.
    for file in ["S-tab1.json", "S-fig12.json"] {
        let mut ep = episode(file);
        assert_eq!(ep.planner_choice().name, "safe-dual-dwa", "{file}");
        ep.step();
        let d = ep.planner_debug();
        assert!(d.global_path.len() > d.keypoints.len(), "{file}");
        assert!(d.keypoints.len() >= 3, "{file}: {:?}", d.keypoints);
        assert_eq!(d.goal_kind, GoalKind::Intermediate, "{file}");
        assert!(d.keypoints.contains(&d.current_goal), "{file}");
        assert_eq!(ep.run(), Outcome::Reached, "{file}");
    }
}
