//! The 2D APF local planners (`apf`, `sampling-apf`) in the simulator.

use planlab_core::planners::{self, PlannerChoice};
use planlab_core::reproduce::{run_spec, RunSpec};
use planlab_core::sim::Outcome;
use serde_json::json;

const PURSUIT_DEMO: &str = include_str!("../../../assets/scenarios/pursuit-demo.json");
const FIG3_13A: &str = include_str!("../../../assets/scenarios/T-fig3-13a.json");
const FIG3_2: &str = include_str!("../../../assets/scenarios/T-fig3-2.json");

fn spec(scenario: &'static str, planner: &'static str) -> RunSpec {
    RunSpec {
        name: planner,
        scenario_json: scenario,
        planner: Some(planner),
        set: vec![],
    }
}

#[test]
fn both_apf_planners_reach_open_goals_without_touching_anything() {
    for scene in [PURSUIT_DEMO, FIG3_13A] {
        for p in ["apf", "sampling-apf"] {
            let (ep, m) = run_spec(&spec(scene, p)).unwrap();
            assert_eq!(m.outcome, Outcome::Reached, "{p}: {m:?}");
            assert!(m.min_clearance_m > 0.0, "{p}: {m:?}");
            assert_eq!(ep.planner_choice().name, p);
        }
    }
}

#[test]
fn c_trap_is_a_local_minimum_for_both_but_no_collision() {
    // Potential fields stop in front of a C-shaped trap (the robot page's
    // T-fig3-2): the braking keeps them off the wall.
    for p in ["apf", "sampling-apf"] {
        let (_, m) = run_spec(&spec(FIG3_2, p)).unwrap();
        assert_eq!(m.outcome, Outcome::Stuck, "{p}: {m:?}");
        assert!(m.min_clearance_m > 0.0);
    }
}

#[test]
fn sampled_steps_are_recorded_as_13_rollouts() {
    let (ep, _) = run_spec(&RunSpec {
        set: vec![("sim.max_time", "20"), ("sim.record_rollouts", "true")],
        ..spec(FIG3_2, "sampling-apf")
    })
    .unwrap();
    let d = ep.planner_debug();
    assert_eq!(d.critics, ["attraction", "repulsion"]);
    assert_eq!(d.rollouts.len(), 13, "{}", d.mode);
    let c = d.chosen.unwrap();
    assert!(d
        .rollouts
        .iter()
        .all(|r| r.score <= d.rollouts[c].score + 1e-9));
}

#[test]
fn bad_configs_are_errors_naming_the_field() {
    assert!(planners::is_registered("apf") && planners::is_registered("sampling-apf"));
    let robot = Default::default();
    let grid = planlab_core::map::OccupancyGrid::from_ascii("....\n....\n").unwrap();
    let map = planlab_core::world::StaticMap::new(grid, true).unwrap();
    let state = Default::default();
    let build = |name: &str, config| {
        planners::build(
            &PlannerChoice {
                name: name.into(),
                config,
            },
            &robot,
            &map,
            &state,
            [3.0, 1.0],
        )
        .err()
        .map(|e| e.to_string())
    };
    let e = build("apf", json!({"apf": {"k_r": -1.0}})).unwrap();
    assert!(e.contains("k_r"), "{e}");
    let e = build("sampling-apf", json!({"apf": {"mode": "basic"}})).unwrap();
    assert!(e.contains("basic"), "{e}");
    let e = build("sampling-apf", json!({"k_w": "fast"})).unwrap();
    assert!(e.contains("k_w"), "{e}");
    assert!(build(
        "sampling-apf",
        json!({"apf": {"predictor": "constant-velocity"}})
    )
    .is_none());
}
