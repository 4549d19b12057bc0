//! `move-base-dwa`: ROS 1 move_base with base_local_planner's
//! `TrajectoryPlannerROS` and `dwa: true` (docs/algorithms.md
//! §move-base-dwa), as an engine composition:
//!
//! - generator: [`TrajectoryPlannerWindow`] (the window over one control
//!   period, `vx_samples` × `vtheta_samples` forward samples, in-place
//!   rotations of at least `min_in_place_vel_theta`; rollouts of
//!   `sim_time` stepped by `sim_granularity` / `angular_sim_granularity`);
//! - critics, summed as `pdist_scale·path_dist + gdist_scale·goal_dist +
//!   occdist_scale·occ_cost` (lowest wins; with `meter_scoring` every scale
//!   is multiplied by the costmap resolution): the MapGrid distances (cells)
//!   of the rollout's last point to the pruned plan and to its last point,
//!   and the highest cost along the rollout under the footprint
//!   ([`super::critics`]); a point on an obstacle or unreachable cell, or
//!   the footprint on a lethal cell, makes the rollout illegal;
//! - the source's in-place rotation rule (the rotation looking at the
//!   lowest goal distance `heading_lookahead` ahead, taken when its cost is
//!   no worse) as a tie-break critic, its oscillation flags
//!   (`oscillation_reset_dist`) as a critic, and its escape (back up at
//!   `escape_vel` until `escape_reset_dist` / `escape_reset_theta`) as the
//!   fallback.
//!
//! Declared deviations: the differential robot's samples only
//! (`holonomic_robot: false`; the source's default `true` adds strafing
//! samples a differential base cannot drive); `heading_scoring` and
//! `simple_attractor` off (their defaults); the plan the critics see is cut
//! at `plan_window` m from the robot, half the width of costmap_2d's
//! default 10 m local costmap, while the grids span the whole static map
//! ([`super`] lists the common simplifications).

use super::generators::{TrajectoryPlannerSettings, TrajectoryPlannerWindow};
use super::{CostmapParams, Escape, Following, Layers, RosPlanner};
use crate::local::engine::catalogue::{CriticCatalogue, CriticEnv};
use crate::local::engine::generator::{MAX_ROLLOUT_STEPS, MAX_SAMPLES_PER_AXIS};
use crate::local::engine::{CriticSlot, Engine, Scoring};
use crate::local::LocalError;
use crate::params::Params;
use crate::world::{RobotSpec, StaticMap};

crate::params::params! {
    /// Settings of `move-base-dwa`; defaults are base_local_planner's
    /// (TrajectoryPlannerROS) and costmap_2d's. Speed and acceleration
    /// limits are the scenario robot's (max_vel_x = v_max, max_vel_theta =
    /// ω_max, acc_lim_x = a_v, acc_lim_theta = a_ω).
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct MoveBaseConfig {
        pub vx_samples: u32 = 3, "1" [] label "speed samples" "vx_samples: forward speeds sampled (at least 1)";
        pub vtheta_samples: u32 = 20, "1" [] label "turn-rate samples" "vtheta_samples: turn rates sampled (at least 1)";
        pub sim_time: f64 = 1.0, "s" [> 0.0, <= 60.0] label "look-ahead time" "sim_time: rollout horizon";
        pub sim_granularity: f64 = 0.025, "m" [> 0.0, <= 10.0]
            label "rollout step" "sim_granularity: linear step between rollout points";
        pub angular_sim_granularity: f64 = 0.025, "rad" [> 0.0, <= 10.0]
            label "rollout angular step" "angular_sim_granularity: angular step term of the rollout's step count";
        pub min_vel_x: f64 = 0.1, "m/s" [>= 0.0, <= 100.0]
            label "slowest speed" "min_vel_x: slowest forward sample (at most the robot's v_max)";
        pub min_in_place_vel_theta: f64 = 0.4, "rad/s" [>= 0.0, <= 100.0]
            label "slowest in-place turn" "min_in_place_vel_theta: slowest in-place rotation";
        pub pdist_scale: f64 = 0.6, "1" [>= 0.0] label "path distance weight" "pdist_scale: weight of the distance to the plan";
        pub gdist_scale: f64 = 0.8, "1" [>= 0.0] label "goal distance weight" "gdist_scale: weight of the distance to the local goal";
        pub occdist_scale: f64 = 0.01, "1" [>= 0.0] label "obstacle cost weight" "occdist_scale: weight of the costmap cost";
        pub meter_scoring: bool = false, "bool" []
            label "distances in metres" "meter_scoring: distances in metres (every scale times the resolution) instead of cells";
        pub heading_lookahead: f64 = 0.325, "m" [>= 0.0, <= 100.0]
            label "heading look-ahead" "heading_lookahead: how far ahead of an in-place rotation the goal distance is read";
        pub oscillation_reset_dist: f64 = 0.05, "m" [>= 0.0, <= 100.0]
            label "oscillation reset distance" "oscillation_reset_dist: moving this far clears the in-place oscillation flags";
        pub escape_vel: f64 = -0.1, "m/s" [>= -100.0, <= 0.0]
            label "escape speed" "escape_vel: backing-up speed with no legal trajectory (the robot's v_min bounds it)";
        pub escape_reset_dist: f64 = 0.1, "m" [>= 0.0, <= 100.0]
            label "escape distance" "escape_reset_dist: backing up ends this far from where it began";
        pub escape_reset_theta: f64 = std::f64::consts::FRAC_PI_4, "rad" [>= 0.0, <= 10.0]
            label "escape turn" "escape_reset_theta: backing up ends after turning this far";
        pub max_vel_x: f64 = 0.0, "m/s" [>= 0.0, <= 100.0]
            label "top speed" "max_vel_x: fastest forward sample (0: the robot's v_max; at most the robot's v_max)";
        pub max_vel_theta: f64 = 0.0, "rad/s" [>= 0.0, <= 100.0]
            label "top turn rate" "max_vel_theta: fastest turn sample (0: the robot's ω_max; at most the robot's)";
        pub acc_lim_x: f64 = 0.0, "m/s²" [>= 0.0, <= 1000.0]
            label "acceleration" "acc_lim_x: the window's linear acceleration (0: the robot's a_v; at most the robot's)";
        pub acc_lim_theta: f64 = 0.0, "rad/s²" [>= 0.0, <= 1000.0]
            label "turn acceleration" "acc_lim_theta: the window's angular acceleration (0: the robot's a_ω; at most the robot's)";
        pub planner_frequency: f64 = 0.0, "Hz" [>= 0.0, <= 100.0]
            label "replanning rate" "planner_frequency: global replanning rate (0: once, and after a failure)";
        pub plan_window: f64 = 5.0, "m" [> 0.0, <= 1000.0]
            label "plan window" "the plan the critics see ends this far from the robot (half of costmap_2d's default 10 m local costmap)";
        pub costmap: CostmapParams = CostmapParams::default(), "" [nested] "costmap inflation layer";
    }
}

impl MoveBaseConfig {
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
        )
    }
}

impl MoveBaseConfig {
    /// The robot's limits with the planner's own caps (a cap of 0 keeps
    /// the robot's value; a cap never raises it).
    pub fn limits(&self, robot: &RobotSpec) -> crate::world::RobotLimits {
        crate::local::dwa::capped_limits(
            robot.limits,
            [
                self.max_vel_x,
                self.max_vel_theta,
                self.acc_lim_x,
                self.acc_lim_theta,
            ],
        )
    }
}

/// Checks sample counts are 1 ..= [`MAX_SAMPLES_PER_AXIS`].
pub(super) fn samples_in_range(prefix: &str, counts: [(&str, u32); 2]) -> Result<(), LocalError> {
    for (name, n) in counts {
        if n == 0 || n as usize > MAX_SAMPLES_PER_AXIS {
            return Err(LocalError::InvalidParameter(format!(
                "{prefix}.{name} = {n}: must be 1 ..= {MAX_SAMPLES_PER_AXIS}"
            )));
        }
    }
    Ok(())
}

/// Checks a rollout of `sim_time` at the robot's top speeds stays within
/// [`MAX_ROLLOUT_STEPS`] steps.
pub(super) fn steps_in_range(
    prefix: &str,
    robot: &RobotSpec,
    sim_time: f64,
    (lin, ang): (f64, f64),
    angular_has_time: bool,
) -> Result<(), LocalError> {
    let l = &robot.limits;
    let ang_t = if angular_has_time { sim_time } else { 1.0 };
    let n = (l.v_max.abs().max(l.v_min.abs()) * sim_time / lin).max(l.w_max.abs() * ang_t / ang);
    if n > MAX_ROLLOUT_STEPS as f64 {
        return Err(LocalError::InvalidParameter(format!(
            "{prefix}: a rollout at top speed takes {n:.0} steps (at most {MAX_ROLLOUT_STEPS}): raise the granularities or shorten sim_time"
        )));
    }
    Ok(())
}

/// The `move-base-dwa` planner.
pub type MoveBaseDwa = RosPlanner<TrajectoryPlannerWindow>;

/// Builds `move-base-dwa` for `robot` on `map`, from `start` to `goal`.
pub fn build(
    cfg: &MoveBaseConfig,
    robot: &RobotSpec,
    map: &StaticMap,
    start: [f64; 2],
    goal: [f64; 2],
) -> Result<MoveBaseDwa, LocalError> {
    let prefix = "move-base-dwa";
    cfg.validate(prefix)?;
    robot
        .validate()
        .map_err(|e| LocalError::InvalidParameter(e.to_string()))?;
    steps_in_range(
        prefix,
        robot,
        cfg.sim_time,
        (cfg.sim_granularity, cfg.angular_sim_granularity),
        false,
    )?;
    let env = CriticEnv {
        robot,
        map,
        costmap: cfg.costmap,
    };
    let unit = if cfg.meter_scoring {
        map.grid().resolution()
    } else {
        1.0
    };
    let cat = CriticCatalogue::standard();
    let scaled = |name: &str, scale: f64| -> Result<CriticSlot, LocalError> {
        let mut slot = cat.build(name, &env, prefix, &serde_json::Value::Null)?;
        slot.weight = scale;
        Ok(slot)
    };
    let heading = serde_json::json!({ "heading_lookahead": cfg.heading_lookahead });
    let osc = serde_json::json!({ "oscillation_reset_dist": cfg.oscillation_reset_dist });
    let critics = vec![
        scaled("move_base.path_dist", cfg.pdist_scale * unit)?,
        scaled("move_base.goal_dist", cfg.gdist_scale * unit)?,
        scaled("move_base.occ_cost", cfg.occdist_scale * unit)?,
        cat.build("move_base.heading_lookahead", &env, prefix, &heading)?,
        cat.build("move_base.oscillation", &env, prefix, &osc)?,
    ];
    let generator = TrajectoryPlannerWindow::new(
        cfg.limits(robot),
        TrajectoryPlannerSettings {
            vx_samples: cfg.vx_samples,
            vtheta_samples: cfg.vtheta_samples,
            sim_time: cfg.sim_time,
            sim_granularity: cfg.sim_granularity,
            angular_sim_granularity: cfg.angular_sim_granularity,
            min_vel_x: cfg.min_vel_x,
            min_in_place_vel_theta: cfg.min_in_place_vel_theta,
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
        reach: cfg.plan_window,
        replan_period: if cfg.planner_frequency > 0.0 {
            1.0 / cfg.planner_frequency
        } else {
            0.0
        },
        escape: Some(Escape {
            vel: cfg.escape_vel,
            reset_dist: cfg.escape_reset_dist,
            reset_theta: cfg.escape_reset_theta,
        }),
    };
    let layers = Layers::new(map, robot, &cfg.costmap)?;
    RosPlanner::new(prefix, engine, layers, follow, start, goal)
}
