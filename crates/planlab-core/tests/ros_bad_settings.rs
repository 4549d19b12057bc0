//! The ROS baselines refuse bad settings with one-line errors naming the
//! field (they are built through the planner catalogue, a layer above
//! `local`, hence an integration test).

use planlab_core::map::{Cell, OccupancyGrid, Pose2};
use planlab_core::planners::{build, PlannerChoice};
use planlab_core::world::{RobotSpec, RobotState, StaticMap};
use serde_json::json;

fn open_map() -> StaticMap {
    let g = OccupancyGrid::from_cells(40, 20, vec![Cell::Free; 800])
        .and_then(|g| g.with_frame(0.1, Pose2::default()))
        .unwrap();
    StaticMap::new(g, true).unwrap()
}

#[test]
fn bad_settings_are_one_line_errors_naming_the_field() {
    let map = open_map();
    let s = RobotState {
        x: 0.5,
        y: 1.0,
        ..Default::default()
    };
    let err = |name: &str, config: serde_json::Value| {
        let choice = PlannerChoice {
            name: name.into(),
            config,
        };
        let e = build(&choice, &RobotSpec::default(), &map, &s, [3.5, 1.0])
            .err()
            .expect("refused");
        let text = e.to_string();
        assert!(!text.contains('\n'), "{text}");
        text
    };
    assert!(err("move-base-dwa", json!({"sim_time": 1e9})).contains("move-base-dwa.sim_time"));
    assert!(err("move-base-dwa", json!({"vx_samples": 0})).contains("move-base-dwa.vx_samples"));
    assert!(err(
        "move-base-dwa",
        json!({"costmap": {"inflation_radius": -1.0}})
    )
    .contains("costmap.inflation_radius"));
    assert!(err("dwb", json!({"linear_granularity": 0.0})).contains("dwb.linear_granularity"));
    assert!(err("dwb", json!({"vtheta_samples": 100000})).contains("dwb.vtheta_samples"));
    assert!(err(
        "dwb",
        json!({"critic_config": {"PathAlign": {"scale": 1e300}}})
    )
    .contains("dwb.critic_config.PathAlign.scale"));
    assert!(err(
        "dwb",
        json!({"critic_config": {"PathAlign": {"forward_point_distance": "x"}}})
    )
    .contains("forward_point_distance"));
    assert!(err("dwb", json!({"critics": ["PathDist", "Nope"]})).contains("unknown critic `Nope`"));
    assert!(err(
        "dwb",
        json!({"critic_config": {"Twirling": {"scale": 1.0}}})
    )
    .contains("not in dwb.critics"));
    // NaN cannot be written in JSON; through the API it is refused too.
    let cfg = planlab_core::local::ros::move_base::MoveBaseConfig {
        pdist_scale: f64::NAN,
        ..Default::default()
    };
    let e = planlab_core::local::ros::move_base::build(
        &cfg,
        &RobotSpec::default(),
        &map,
        [0.5, 1.0],
        [3.5, 1.0],
    )
    .err()
    .unwrap();
    assert!(e.to_string().contains("move-base-dwa.pdist_scale"), "{e}");
}
