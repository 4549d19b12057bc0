//! `dwb`: Nav2's DWB controller (docs/algorithms.md §dwb) as an engine
//! composition: DWB's [`StandardGenerator`] and the critics named in
//! `critics` (Nav2's `critics:` parameter), each looked up in the
//! [`CriticCatalogue`] with its settings from `critic_config.<Name>`
//! (`scale` and the critic's own parameters), summed as Σ scale·cost,
//! lowest wins; a critic declaring a rollout illegal rules it out.
//!
//! The default list and scales are nav2_params.yaml's (BaseObstacle 0.02,
//! PathAlign 32, GoalAlign 24, PathDist 32, GoalDist 24, RotateToGoal 32,
//! Oscillation); `forward_point_distance` is the critics' source default
//! 0.325 m. The plan the critics see runs from the plan point nearest the
//! robot to `forward_prune_distance` ahead. Nav2's default behaviour tree
//! replans every second (`replan_period`). Declared deviations are in
//! [`super`] and [`super::critics`].

use super::generators::{StandardGenerator, StandardSettings};
use super::move_base::{samples_in_range, steps_in_range};
use super::{CostmapParams, Following, Layers, RosPlanner};
use crate::local::engine::catalogue::{CriticCatalogue, CriticEnv};
use crate::local::engine::{Engine, Scoring};
use crate::local::LocalError;
use crate::params::Params;
use crate::world::{RobotSpec, StaticMap};

/// Nav2's default critic list (nav2_params.yaml).
pub fn default_critics() -> Vec<String> {
    [
        "RotateToGoal",
        "Oscillation",
        "BaseObstacle",
        "GoalAlign",
        "PathAlign",
        "PathDist",
        "GoalDist",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect()
}

crate::params::params! {
    /// Settings of `dwb`; defaults are Nav2's (nav2_params.yaml for the
    /// sample counts, granularities and critic list). Speed and
    /// acceleration limits are the scenario robot's (min/max_vel_x = v_min /
    /// v_max, max_vel_theta = ω_max, acc_lim_x = −decel_lim_x = a_v,
    /// acc_lim_theta = a_ω).
    #[derive(Debug, Clone, PartialEq)]
    pub struct DwbConfig {
        pub vx_samples: u32 = 20, "1" [] label "speed samples" "vx_samples: forward speeds sampled (at least 1)";
        pub vtheta_samples: u32 = 20, "1" [] label "turn-rate samples" "vtheta_samples: turn rates sampled (at least 1)";
        pub sim_time: f64 = 1.7, "s" [> 0.0, <= 60.0] label "look-ahead time" "sim_time: rollout horizon";
        pub linear_granularity: f64 = 0.05, "m" [> 0.0, <= 10.0]
            label "rollout step" "linear_granularity: linear step between rollout poses";
        pub angular_granularity: f64 = 0.025, "rad" [> 0.0, <= 10.0]
            label "rollout angular step" "angular_granularity: angular step between rollout poses";
        pub include_last_point: bool = true, "bool" []
            label "repeat last pose" "include_last_point: the final pose is appended once more (as the source does)";
        pub forward_prune_distance: f64 = 2.0, "m" [> 0.0, <= 1000.0]
            label "plan window" "forward_prune_distance: the plan the critics see ends this far from the robot";
        pub replan_period: f64 = 1.0, "s" [>= 0.0, <= 1000.0]
            label "replanning period" "global replanning period of Nav2's default behaviour tree (0: only after a failure)";
        pub critics: Vec<String> = default_critics(), "" []
            label "critic list" "critics: critic names in order, looked up in the critic catalogue";
        pub critic_config: serde_json::Value = serde_json::json!({}), "" []
            label "critic settings" "per-critic settings by name, e.g. {\"PathAlign\": {\"scale\": 32, \"forward_point_distance\": 0.325}}";
        pub costmap: CostmapParams = CostmapParams::default(), "" [nested] "costmap inflation layer";
    }
}

impl DwbConfig {
    /// Checks every number; errors name `prefix.field`.
    pub fn validate(&self, prefix: &str) -> Result<(), LocalError> {
        self.check_bounds(prefix)?;
        self.costmap.check_bounds(&format!("{prefix}.costmap"))?;
        samples_in_range(
            prefix,
            [
                ("vx_samples", self.vx_samples),
                ("vtheta_samples", self.vtheta_samples),
            ],
        )?;
        if !(self.critic_config.is_object() || self.critic_config.is_null()) {
            return Err(LocalError::InvalidParameter(format!(
                "{prefix}.critic_config must be an object of critic settings by name"
            )));
        }
        Ok(())
    }
}

/// The `dwb` planner.
pub type Dwb = RosPlanner<StandardGenerator>;

/// Builds `dwb` for `robot` on `map`, from `start` to `goal`, with the
/// critics of `catalogue`.
pub fn build(
    cfg: &DwbConfig,
    catalogue: &CriticCatalogue,
    robot: &RobotSpec,
    map: &StaticMap,
    start: [f64; 2],
    goal: [f64; 2],
) -> Result<Dwb, LocalError> {
    let prefix = "dwb";
    cfg.validate(prefix)?;
    robot
        .validate()
        .map_err(|e| LocalError::InvalidParameter(e.to_string()))?;
    steps_in_range(
        prefix,
        robot,
        cfg.sim_time,
        (cfg.linear_granularity, cfg.angular_granularity),
        true,
    )?;
    let env = CriticEnv {
        robot,
        map,
        costmap: cfg.costmap,
    };
    let at = format!("{prefix}.critic_config");
    let mut critics = Vec::with_capacity(cfg.critics.len());
    for name in &cfg.critics {
        let own = cfg
            .critic_config
            .get(name)
            .unwrap_or(&serde_json::Value::Null);
        critics.push(catalogue.build(name, &env, &at, own)?);
    }
    if let Some(obj) = cfg.critic_config.as_object() {
        if let Some(k) = obj.keys().find(|k| !cfg.critics.contains(k)) {
            return Err(LocalError::InvalidParameter(format!(
                "{at}.{}: not in {prefix}.critics",
                crate::text::one_line(k)
            )));
        }
    }
    let generator = StandardGenerator::new(
        robot.limits,
        StandardSettings {
            vx_samples: cfg.vx_samples,
            vtheta_samples: cfg.vtheta_samples,
            sim_time: cfg.sim_time,
            linear_granularity: cfg.linear_granularity,
            angular_granularity: cfg.angular_granularity,
            include_last_point: cfg.include_last_point,
        },
    );
    let engine = Engine::new(
        robot,
        Box::new(generator),
        critics,
        Scoring::WeightedCost,
        None,
    )
    .keep_chosen(true);
    let follow = Following {
        reach: cfg.forward_prune_distance,
        replan_period: cfg.replan_period,
        escape: None,
    };
    let layers = Layers::new(map, robot, &cfg.costmap)?;
    RosPlanner::new(prefix, engine, layers, follow, start, goal)
}
