//! Regression tests of DWA-family planners that misbehaved by their own
//! papers' method: each replays the scene that showed the bug.

use planlab_core::batch;
use planlab_core::map::OccupancyGrid;
use planlab_core::planners::PlannerChoice;
use planlab_core::scenario::Scenario;
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

/// Runs every DWA-family run of variant `k` (seed 0) of the reproduce
/// experiment `id` with the `--sweep`-style edits `set`: (run, outcome,
/// smallest clearance).
fn family_runs(id: &str, k: u32, set: &[(&str, &str)]) -> Vec<(String, Outcome, f64)> {
    let exp = planlab_core::reproduce::find(id).unwrap();
    let set: Vec<(String, String)> = set
        .iter()
        .map(|(p, v)| (p.to_string(), v.to_string()))
        .collect();
    let scene = exp.variant(0, k, &set).unwrap();
    scene
        .trees
        .iter()
        .map(|(name, tree)| {
            let s = Scenario::from_value(tree).unwrap();
            let g = s
                .load_grid(&mut |p| Err(format!("inline map expected, not {p}")))
                .unwrap();
            let mut ep = Episode::from_scenario(&s, g).unwrap();
            let outcome = ep.run();
            let min_c = ep
                .trace()
                .steps
                .iter()
                .map(|r| r.clearance)
                .fold(f64::INFINITY, f64::min);
            (name.to_string(), outcome, min_c)
        })
        .collect()
}

/// T-fig3-11 with a 1 s rollout horizon (`--sweep
/// local_planner.config.dwa.predict_time=1`): improved-dwa drove into the
/// side wall past the goal in 8 of 30 variants. Two causes: a braking
/// rollout was checked over the horizon only, so one still doing 0.5 m/s
/// at its end counted as stopped (variant 2); and with no admissible
/// sample the braking fallback turned toward the goal while still moving,
/// sweeping into a wall that straight braking stops short of (variant 16).
/// Braking rollouts and the braking check are now followed until the robot
/// stands, and the fallback turns only when that turn hits nothing.
#[test]
fn t_fig3_11_short_horizon_improved_dwa_does_not_drive_into_the_wall() {
    for k in [2, 16] {
        let runs = family_runs(
            "T-fig3-11",
            k,
            &[("local_planner.config.dwa.predict_time", "1")],
        );
        let (_, outcome, min_c) = runs.iter().find(|(n, ..)| n == "improved").unwrap();
        assert_eq!(*outcome, Outcome::Reached, "variant {k}");
        assert!(*min_c > 0.0, "variant {k}: touched something");
    }
}

/// S-fig12 variant 11: `preliminary-fusion` stood at rest 5 cm beside the
/// lane of a back-and-forth mover and started off toward its temporary
/// goal as the mover, predicted (constant velocity) to keep moving away,
/// reached its turnaround; the mover came back and hit the robot, which
/// was moving at 0.08 m/s and braking. A robot at rest now starts off only
/// when no perceived mover, free to turn at once at its observed speed,
/// could reach it before it would be at rest again (passive safety).
#[test]
fn s_fig12_preliminary_does_not_start_off_beside_a_turning_mover() {
    let runs = family_runs("S-fig12", 11, &[]);
    for name in ["preliminary", "dual"] {
        let (_, outcome, min_c) = runs.iter().find(|(n, ..)| n == name).unwrap();
        assert_ne!(*outcome, Outcome::Collision, "{name}");
        assert!(*min_c > 0.0, "{name}: touched something ({min_c} m)");
    }
}

/// T-fig3-11 at a 1 s horizon, variant 16: `fusion-53` (\[53\]) collided
/// — the one collision left in the horizon sweep after the braking fixes
/// above: it reached a state with no admissible sample (`no-admissible-evade`)
/// from which no collision-free way out remained. With the start-from-rest
/// check of passive safety (previous test) it does not get there.
#[test]
fn t_fig3_11_short_horizon_fusion53_is_not_hit() {
    let runs = family_runs(
        "T-fig3-11",
        16,
        &[("local_planner.config.dwa.predict_time", "1")],
    );
    for (name, outcome, min_c) in &runs {
        assert_ne!(*outcome, Outcome::Collision, "{name}");
        assert!(*min_c > 0.0, "{name}: touched something ({min_c} m)");
    }
}

/// T-fig3-11 at the default 3 s horizon: improved-dwa reached the goal in
/// 2 of 30 variants. Past the mover it orbited the still disc at full
/// speed and turn rate, a new virtual goal set each lap. The virtual goal
/// was kept until its obstacle was behind the robot *as seen toward the
/// current goal*; the detour itself moves the robot off the line, which
/// turns that direction, so a disc passed by 0.5–1.4 m still counted as
/// ahead and the robot kept turning back toward a virtual goal behind it
/// (variant 0: crossed the disc's perpendicular at 17.3 s, dropped at
/// 18.05 s, ω at its maximum throughout). "Behind" is now measured along
/// the robot→goal direction the virtual goal was placed from (\[T\]
/// §3.2.2: on the perpendicular to it through the obstacle).
#[test]
fn t_fig3_11_improved_dwa_does_not_orbit_the_still_disc() {
    for k in [0, 1] {
        let runs = family_runs("T-fig3-11", k, &[]);
        let (_, outcome, min_c) = runs.iter().find(|(n, ..)| n == "improved").unwrap();
        assert_eq!(*outcome, Outcome::Reached, "variant {k}");
        assert!(*min_c > 0.0, "variant {k}: touched something ({min_c} m)");
    }
}
