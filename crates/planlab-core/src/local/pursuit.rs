//! `pursuit`: a naive baseline that steers straight at the goal.
//!
//! Not from any paper and **no obstacle avoidance**: it exists so the
//! simulator, metrics and CLI can be exercised with a real (honest) planner,
//! and as the "what happens without a local planner" reference. Heading
//! error e = bearing to goal − θ; ω = k_w·e clamped to ω_max; the forward
//! speed follows a braking profile v = min(v_max, √(2·a_v·(d − tol)))·cos e,
//! and is 0 while |e| > `turn_angle` (turn in place first).

use super::{GoalKind, LocalError, LocalPlanner, Observation, PlannerDebug};
use crate::num::{atan2, cos, hypot, wrap_angle};
use crate::params::Params;
use crate::world::{Command, RobotSpec, RobotState, StaticMap};

crate::params::params! {
    /// Settings of the `pursuit` baseline.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct PursuitConfig {
        pub k_w: f64 = 1.5, "1/s" [> 0.0] label "heading gain k_w" "heading gain: ω = k_w · heading error";
        pub turn_angle: f64 = std::f64::consts::FRAC_PI_3, "rad" [> 0.0]
            label "turn-in-place angle" "turn in place while the heading error exceeds this";
        pub stop_distance: f64 = 0.05, "m" [>= 0.0] label "stopping distance" "stop when the goal is this close";
        pub brake_fraction: f64 = 0.8, "1" [> 0.0, <= 1.0]
            label "braking share" "share of the deceleration limit the braking profile plans with (0–1]";
    }
}

/// The `pursuit` planner (see the module doc).
#[derive(Debug, Clone)]
pub struct Pursuit {
    cfg: PursuitConfig,
    robot: RobotSpec,
    goal: [f64; 2],
    debug: PlannerDebug,
}

impl Pursuit {
    /// Builds it for `robot`, heading for `goal`.
    pub fn new(cfg: PursuitConfig, robot: &RobotSpec, goal: [f64; 2]) -> Result<Self, LocalError> {
        cfg.check_bounds("pursuit")?;
        Ok(Self {
            cfg,
            robot: *robot,
            goal,
            debug: PlannerDebug {
                current_goal: goal,
                goal_kind: GoalKind::Final,
                mode: "pursuit".into(),
                ..Default::default()
            },
        })
    }
}

impl LocalPlanner for Pursuit {
    fn name(&self) -> &'static str {
        "pursuit"
    }

    fn step(&mut self, obs: &Observation<'_>) -> Command {
        let s = obs.state;
        let (dx, dy) = (self.goal[0] - s.x, self.goal[1] - s.y);
        let d = hypot(dx, dy);
        let l = &self.robot.limits;
        self.debug.current_goal = self.goal;
        if d <= self.cfg.stop_distance {
            self.debug.mode = "arrived".into();
            return Command::default();
        }
        let err = wrap_angle(atan2(dy, dx) - s.theta);
        let w = (self.cfg.k_w * err).clamp(-l.w_max, l.w_max);
        let v = if err.abs() > self.cfg.turn_angle {
            self.debug.mode = "turn".into();
            0.0
        } else {
            self.debug.mode = "pursuit".into();
            let brake = 2.0 * self.cfg.brake_fraction * l.acc_v * (d - self.cfg.stop_distance);
            l.v_max.min(brake.max(0.0).sqrt()) * cos(err).max(0.0)
        };
        Command { v, vy: 0.0, w }
    }

    fn set_goal(
        &mut self,
        _map: &StaticMap,
        _state: &RobotState,
        goal: [f64; 2],
    ) -> Result<(), LocalError> {
        if !(goal[0].is_finite() && goal[1].is_finite()) {
            return Err(LocalError::InvalidParameter(format!(
                "goal ({}, {}) must be finite",
                goal[0], goal[1]
            )));
        }
        self.goal = goal;
        self.debug.current_goal = goal;
        Ok(())
    }

    fn debug(&self) -> &PlannerDebug {
        &self.debug
    }

    fn set_record_rollouts(&mut self, _on: bool) {}
}
