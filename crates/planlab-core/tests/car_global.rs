//! A scenario's `global_planner` section: a Hybrid A* car path the local
//! planner follows (crate::local::car_guide).

use planlab_core::car::max_curvature;
use planlab_core::local::car_guide::{plan_car_route, GlobalPlannerSpec};
use planlab_core::metrics::EpisodeMetrics;
use planlab_core::scenario::{set_json_path, Scenario, ScenarioError};
use planlab_core::sim::{Episode, Outcome, SimError};
use std::path::Path;

fn scenarios_dir() -> &'static Path {
    Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/scenarios"
    ))
}

/// Preset `file` with the `--set` edits `sets` applied.
fn preset(file: &str, sets: &[(&str, &str)]) -> Result<Scenario, ScenarioError> {
    let text = std::fs::read_to_string(scenarios_dir().join(file)).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    for (path, value) in sets {
        set_json_path(&mut v, path, value)?;
    }
    Scenario::from_value(&v)
}

fn episode(s: &Scenario) -> Result<Episode, SimError> {
    let dir = scenarios_dir();
    let grid = s.load_grid(&mut |name| std::fs::read(dir.join(name)).map_err(|e| e.to_string()))?;
    Episode::from_scenario(s, grid)
}

const HYBRID: [(&str, &str); 3] = [
    ("local_planner", r#"{"name": "dwa"}"#),
    ("global_planner.algorithm", "hybrid-astar"),
    ("global_planner.turning_radius_m", "1.0"),
];

/// Runs `file` with the car path, checks the path (curvature, ends) and
/// returns the finished episode.
fn drive(file: &str, extra: &[(&str, &str)]) -> Episode {
    let sets: Vec<(&str, &str)> = HYBRID.iter().chain(extra).copied().collect();
    let s = preset(file, &sets).unwrap();
    let spec = s.global_planner.unwrap();
    let mut ep = episode(&s).unwrap();
    let guide = ep.car_guide().expect("a car path");
    let route = guide.route().clone();
    // The path the episode draws is the car path, from the start to the
    // goal, never turning tighter than the radius.
    assert_eq!(ep.planner_debug().global_path, route.points());
    let k = max_curvature(&route.poses);
    assert!(
        k <= 1.0 / spec.turning_radius_m * (1.0 + 1e-6),
        "{file}: κ {k}"
    );
    assert!(k > 0.5 / spec.turning_radius_m, "{file}: the path turns");
    let (s0, g) = (ep.state(), ep.goal());
    assert_eq!([route.poses[0].x, route.poses[0].y], [s0.x, s0.y]);
    let last = route.poses.last().unwrap();
    assert_eq!([last.x, last.y], g);
    assert!(route.length > planlab_core::num::hypot(g[0] - s0.x, g[1] - s0.y));
    assert_eq!(ep.run(), Outcome::Reached, "{file}: {:?}", ep.collision());
    ep
}

#[test]
fn a_dwa_following_a_hybrid_astar_path_reaches_the_goal_on_two_presets() {
    for file in ["T-fig3-2.json", "S-fig6.json"] {
        let ep = drive(file, &[]);
        let m = EpisodeMetrics::of_episode(&ep);
        assert!(m.min_clearance_m > 0.0, "{file}: {m:?}");
    }
}

#[test]
fn the_car_path_is_the_one_plan_car_route_gives_and_is_deterministic() {
    let s = preset("T-fig3-2.json", &HYBRID).unwrap();
    let a = episode(&s).unwrap();
    let b = episode(&s).unwrap();
    assert_eq!(
        a.car_guide().unwrap().route(),
        b.car_guide().unwrap().route()
    );
    let st = a.state();
    let spec = s.global_planner.unwrap();
    let g = a.goal();
    let direct = plan_car_route(
        a.map(),
        &spec,
        &a.robot().footprint,
        planlab_core::car::Pose::new(st.x, st.y, st.theta),
        g,
        planlab_core::num::atan2(g[1] - st.y, g[0] - st.x),
    )
    .unwrap();
    assert_eq!(&direct, a.car_guide().unwrap().route());
    let (mut a, mut b) = (a, b);
    a.run();
    b.run();
    assert_eq!(a.trace(), b.trace());
}

#[test]
fn a_missing_or_nan_turning_radius_is_a_typed_error_naming_the_field() {
    let e = preset(
        "T-fig3-2.json",
        &[
            ("local_planner", r#"{"name": "dwa"}"#),
            ("global_planner.algorithm", "hybrid-astar"),
        ],
    )
    .unwrap_err();
    assert!(
        matches!(&e, ScenarioError::Json { message, .. } if message.contains("turning_radius_m")),
        "{e}"
    );
    let mut s = preset("T-fig3-2.json", &HYBRID).unwrap();
    for r in [f64::NAN, 0.0, -1.0, f64::INFINITY] {
        s.global_planner = Some(GlobalPlannerSpec::hybrid_astar(r, false));
        let e = s.validate().unwrap_err();
        assert!(
            matches!(&e, ScenarioError::Invalid(m) if m.contains("global_planner.turning_radius_m")),
            "{r}: {e}"
        );
        assert!(!e.to_string().contains('\n'));
    }
    let e = preset(
        "T-fig3-2.json",
        &[
            ("global_planner.algorithm", "rrt"),
            ("global_planner.turning_radius_m", "1.0"),
        ],
    )
    .unwrap_err();
    assert!(e.to_string().contains("hybrid-astar"), "{e}");
}

#[test]
fn a_local_planner_with_its_own_route_is_refused_with_the_car_path() {
    // T-fig3-2's improved-dwa plans its own A* route.
    let e = preset(
        "T-fig3-2.json",
        &[
            ("global_planner.algorithm", "hybrid-astar"),
            ("global_planner.turning_radius_m", "1.0"),
        ],
    )
    .unwrap_err();
    assert!(e.to_string().contains("improved-dwa"), "{e}");
    let s = preset("T-fig3-2.json", &HYBRID).unwrap();
    let mut ep = episode(&s).unwrap();
    let e = ep
        .set_planner(planlab_core::planners::PlannerChoice::named("improved-dwa"))
        .unwrap_err();
    assert!(e.to_string().contains("own global route"), "{e}");
    assert_eq!(ep.planner_choice().name, "dwa");
}

#[test]
fn moving_the_goal_replans_the_car_path_and_a_saved_episode_keeps_the_section() {
    let s = preset("T-fig3-2.json", &HYBRID).unwrap();
    let mut ep = episode(&s).unwrap();
    for _ in 0..20 {
        ep.step();
    }
    let before = ep.car_guide().unwrap().route().clone();
    ep.set_goal([10.5, 6.0]).unwrap();
    let after = ep.car_guide().unwrap().route().clone();
    assert_ne!(before, after);
    let last = after.poses.last().unwrap();
    assert_eq!([last.x, last.y], [10.5, 6.0]);
    let st = ep.state();
    assert_eq!([after.poses[0].x, after.poses[0].y], [st.x, st.y]);
    let saved = ep.to_scenario("saved", "").unwrap();
    assert_eq!(saved.global_planner, s.global_planner);
    // Without the section nothing changes: the preset as it was.
    let plain = preset("T-fig3-2.json", &[("local_planner", r#"{"name": "dwa"}"#)]).unwrap();
    let ep = episode(&plain).unwrap();
    assert!(ep.car_guide().is_none());
}

#[test]
fn a_rectangular_robot_follows_a_car_path_planned_for_its_rectangle() {
    let rect = r#"{"shape": "rectangle", "length": 0.5, "width": 0.3}"#;
    let ep = drive("T-fig3-2.json", &[("robot.footprint", rect)]);
    assert_eq!(ep.car_guide().unwrap().route().margin_m, 0.1);
    // Its path is not the preset's 0.25 m disc's.
    let s = preset("T-fig3-2.json", &HYBRID).unwrap();
    let disc = episode(&s).unwrap();
    assert_ne!(
        disc.car_guide().unwrap().route().length,
        ep.car_guide().unwrap().route().length
    );
}
