//! The 2D APF as a local planner (`apf`, `sampling-apf`) for the simulator
//! and for navigators that need a motion planner under them (\[L\] sims
//! 8–9).
//!
//! Every control period the planner takes one APF step from the robot's
//! centre toward the observation's goal — movers as discs (with their
//! observed velocities, so prediction has tracks), the nearest static wall
//! as a point obstacle found from the map's clearance field (the point at
//! the clearance distance down its gradient) — and then pursues that APF
//! point within the robot's limits: heading error e to the step direction,
//! ω = k_w·e clamped to ω_max, v = min(v_max, v_b)·cos e, 0 while
//! |e| > `turn_angle` (turn first), where v_b is the speed held for one
//! period and then braked at b·a_v that stops within the room left (to the
//! goal, and to what lies ahead): v_b·Δt + v_b²/(2·b·a_v) ≤ room. The
//! robot's circumscribed radius is added to every distance; a turn in
//! place, whose footprint is not that disc, is swept against the map first
//! and slowed or refused when a corner would meet an obstacle.

use super::planner::{Apf, ObstacleObs, StepKind};
use super::{ApfConfig, ApfMode};
use crate::local::{GoalKind, LocalError, LocalPlanner, Observation, PlannerDebug, Rollout};
use crate::num::{atan2, cos, wrap_angle};
use crate::params::Params;
#[cfg(test)]
use crate::world::Footprint;
use crate::world::{Command, RobotSpec, RobotState, StaticMap};
use glam::DVec2;

/// Id given to the nearest-wall point obstacle.
pub const WALL_ID: u32 = u32::MAX;

crate::params::params! {
    /// Settings of the `apf` / `sampling-apf` local planners.
    #[derive(Debug, Clone, Copy, PartialEq)]
    pub struct ApfLocalConfig {
        /// `mode` is forced to `basic` by `apf`; the robot's radius replaces
        /// `robot_radius`. Defaults scaled for a mobile robot: step 0.25 m,
        /// p₀ 0.5 m, ρ 1 m, k_a 1, k_r 0.02.
        pub apf: ApfConfig = ApfConfig {
            step: 0.25,
            p0: 0.5,
            rho: 1.0,
            k_a: 1.0,
            k_r: 0.02,
            ..ApfConfig::default()
        }, "" [nested] "the potential field";
        pub k_w: f64 = 2.0, "1/s" [> 0.0] label "heading gain k_w" "heading gain: ω = k_w · heading error";
        pub turn_angle: f64 = std::f64::consts::FRAC_PI_3, "rad" [> 0.0]
            label "turn-in-place angle" "turn in place while the heading error exceeds this";
        pub stop_distance: f64 = 0.05, "m" [>= 0.0] label "stopping distance" "stop when the goal is this close";
        pub brake_fraction: f64 = 0.8, "1" [> 0.0, <= 1.0]
            label "braking share" "share of the deceleration limit the braking profile plans with (0–1]";
        pub safety_margin: f64 = 0.05, "m" [>= 0.0]
            label "safety margin" "brake to stop this far from the nearest obstacle surface";
    }
}

/// The 2D APF local planner (see the module doc).
#[derive(Debug)]
pub struct ApfLocal {
    name: &'static str,
    cfg: ApfLocalConfig,
    apf: Apf<DVec2>,
    robot: RobotSpec,
    goal: [f64; 2],
    debug: PlannerDebug,
    record: bool,
}

impl ApfLocal {
    /// `apf` (basic, `basic = true`) or `sampling-apf` (the config's mode,
    /// which must then not be `basic`) for `robot`, heading for `goal`.
    pub fn new(
        basic: bool,
        mut cfg: ApfLocalConfig,
        robot: &RobotSpec,
        goal: [f64; 2],
    ) -> Result<Self, LocalError> {
        let name = if basic { "apf" } else { "sampling-apf" };
        if basic {
            cfg.apf.mode = ApfMode::Basic;
        } else if cfg.apf.mode == ApfMode::Basic {
            return Err(LocalError::InvalidParameter(
                "sampling-apf.apf.mode = basic: use the planner `apf` for the basic field".into(),
            ));
        }
        cfg.check_bounds(name)?;
        if !(goal[0].is_finite() && goal[1].is_finite()) {
            return Err(LocalError::InvalidParameter(format!(
                "goal ({}, {}) must be finite",
                goal[0], goal[1]
            )));
        }
        cfg.apf.robot_radius = robot.footprint.circumscribed_radius();
        let apf =
            Apf::new(cfg.apf).map_err(|e| LocalError::InvalidParameter(format!("{name}: {e}")))?;
        Ok(Self {
            name,
            cfg,
            apf,
            robot: *robot,
            goal,
            debug: PlannerDebug {
                critics: vec!["attraction".into(), "repulsion".into()],
                current_goal: goal,
                goal_kind: GoalKind::Final,
                mode: "start".into(),
                ..Default::default()
            },
            record: true,
        })
    }

    /// The obstacles the field sees: movers, then the nearest wall point.
    fn obstacles(&self, obs: &Observation<'_>) -> Vec<ObstacleObs<DVec2>> {
        let s = obs.state;
        let mut out: Vec<ObstacleObs<DVec2>> = obs
            .movers
            .iter()
            .map(|m| ObstacleObs::moving(m.id, DVec2::from(m.pos), m.radius, DVec2::from(m.vel)))
            .collect();
        if let Some(w) = nearest_wall(obs.map, s.x, s.y) {
            let reach = self.cfg.apf.p0 + self.cfg.apf.robot_radius;
            if (w - DVec2::new(s.x, s.y)).length() <= reach {
                // A measured zero velocity marks it static: no prediction.
                out.push(ObstacleObs::moving(WALL_ID, w, 0.0, DVec2::ZERO));
            }
        }
        out
    }
}

/// The nearest static-obstacle point to (x, y) from the map's clearance
/// field: the clearance distance down its (central-difference) gradient.
/// `None` when the gradient vanishes (far from walls or exactly between).
pub fn nearest_wall(map: &StaticMap, x: f64, y: f64) -> Option<DVec2> {
    let h = 0.5 * map.grid().resolution();
    let c = map.clearance(x, y);
    let gx = (map.clearance(x + h, y) - map.clearance(x - h, y)) / (2.0 * h);
    let gy = (map.clearance(x, y + h) - map.clearance(x, y - h)) / (2.0 * h);
    let g = DVec2::new(gx, gy);
    let n = g.length();
    if n.is_nan() || n <= 1e-9 || !c.is_finite() {
        return None;
    }
    Some(DVec2::new(x, y) - g * (c / n))
}

/// Free distance from `pos` along the unit `heading` before a disc of
/// radius `r` touches a static obstacle (sphere tracing the clearance
/// field), at most `max`, m.
pub fn free_ahead(map: &StaticMap, pos: DVec2, heading: DVec2, r: f64, max: f64) -> f64 {
    let min_step = 0.25 * map.grid().resolution();
    let mut s = 0.0;
    while s < max {
        let p = pos + heading * s;
        let gap = map.clearance(p.x, p.y) - r;
        if gap <= 0.0 {
            return s;
        }
        s += gap.max(min_step);
    }
    max
}

/// The highest speed from which the robot, holding it for one control
/// period `dt` and then braking at `decel`, stops within `room` metres:
/// the largest v with v·dt + v²/(2·decel) ≤ room (0 when room ≤ 0).
pub fn braking_speed(decel: f64, dt: f64, room: f64) -> f64 {
    // NaN counts as no room.
    if room.is_nan() || decel.is_nan() || room <= 0.0 || decel <= 0.0 {
        return 0.0;
    }
    let dt = dt.max(0.0);
    decel * ((dt * dt + 2.0 * room / decel).sqrt() - dt)
}

/// Angle step, rad, at which an in-place turn's sweep is checked: the
/// Jackal's corner (0.33 m out) moves 1.3 cm a step, a quarter of a BARN
/// map cell.
const TURN_CHECK_STEP: f64 = 0.04;

/// ω for an in-place turn that keeps the footprint off every blocked cell
/// of `map`: the turn the robot would make in one period and then while
/// braking ω at the acceleration limit is swept; when it meets an
/// obstacle ω is halved (up to four times), else 0. A robot that already
/// overlaps the map turns as asked (nothing to keep).
fn safe_turn(map: &StaticMap, robot: &RobotSpec, s: &RobotState, w: f64, dt: f64) -> f64 {
    let fp = &robot.footprint;
    if w == 0.0 || map.footprint_collides(fp, s) {
        return w;
    }
    let l = &robot.limits;
    let mut w = w;
    for _ in 0..5 {
        let wf = robot.feasible(s, Command { v: 0.0, vy: 0.0, w }, dt).w;
        let sweep = wf * dt.max(0.0) + wf * wf.abs() / (2.0 * l.acc_w);
        let n = (sweep.abs() / TURN_CHECK_STEP).ceil().max(1.0) as usize;
        let clear = (1..=n).all(|k| {
            let pose = RobotState {
                theta: s.theta + sweep * k as f64 / n as f64,
                ..*s
            };
            !map.footprint_collides(fp, &pose)
        });
        if clear {
            return w;
        }
        w *= 0.5;
    }
    0.0
}

impl LocalPlanner for ApfLocal {
    fn name(&self) -> &'static str {
        self.name
    }

    fn step(&mut self, obs: &Observation<'_>) -> Command {
        self.goal = obs.goal;
        let s = obs.state;
        let pos = DVec2::new(s.x, s.y);
        let goal = DVec2::from(self.goal);
        let d = (goal - pos).length();
        self.debug.current_goal = self.goal;
        self.debug.rollouts.clear();
        self.debug.chosen = None;
        if d <= self.cfg.stop_distance {
            self.debug.mode = "arrived".into();
            return Command::default();
        }
        let obstacles = self.obstacles(obs);
        let step = match self.apf.step(obs.time, pos, goal, &obstacles) {
            Ok(st) => st,
            Err(e) => {
                // Non-finite observations: stop rather than panic.
                self.debug.mode = format!("error: {e}");
                return Command::default();
            }
        };
        self.debug.mode = match step.kind {
            StepKind::Resultant => "resultant",
            StepKind::Sampled => "sampled",
            StepKind::RelativeDistance => "relative-distance",
            StepKind::Stalled => "stalled",
            StepKind::Arrived => "arrived",
        }
        .into();
        if self.record {
            self.debug.rollouts = step
                .candidates
                .iter()
                .map(|c| Rollout {
                    cmd: Command::default(),
                    points: vec![[pos.x, pos.y], [c.point.x, c.point.y]],
                    admissible: true,
                    raw: vec![c.attraction, c.repulsion],
                    normalised: vec![],
                    score: -c.cost,
                })
                .collect();
            self.debug.chosen = step.chosen;
        }
        if step.direction == DVec2::ZERO {
            return Command::default();
        }
        let l = &self.robot.limits;
        let err = wrap_angle(atan2(step.direction.y, step.direction.x) - s.theta);
        let w = (self.cfg.k_w * err).clamp(-l.w_max, l.w_max);
        let v = if err.abs() > self.cfg.turn_angle {
            0.0
        } else {
            // Brake for the goal, and for what lies ahead along the heading:
            // walls by sphere tracing the clearance field, movers as discs
            // (the pursuit lags the field while turning, and a fast robot
            // must see a wall before the field's range does).
            let heading = DVec2::new(cos(s.theta), crate::num::sin(s.theta));
            let r = self.cfg.apf.robot_radius;
            let horizon = l.v_max * l.v_max / (2.0 * self.cfg.brake_fraction * l.acc_v).max(1e-9)
                + self.cfg.safety_margin
                + 0.5;
            let mut ahead = free_ahead(obs.map, pos, heading, r, horizon);
            for o in &obstacles {
                let off = o.centre - pos;
                let along = off.dot(heading);
                let side = (off - heading * along).length();
                let reach = o.radius + r;
                if along > 0.0 && side < reach {
                    ahead = ahead.min(along - (reach * reach - side * side).sqrt());
                }
            }
            let room = (d - self.cfg.stop_distance).min(ahead - self.cfg.safety_margin);
            l.v_max.min(braking_speed(
                self.cfg.brake_fraction * l.acc_v,
                obs.dt,
                room,
            )) * cos(err).max(0.0)
        };
        let w = if v > 0.0 {
            // Driving needs the circumscribed disc clear, and the disc holds
            // the footprint in every orientation: any turn is safe.
            w
        } else {
            safe_turn(obs.map, &self.robot, s, w, obs.dt)
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

    fn set_record_rollouts(&mut self, on: bool) {
        self.record = on;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::{Drive, RobotLimits};

    /// A Jackal-like rectangle (0.42 × 0.33 m, 4 rad/s, 25 rad/s²) — built
    /// here, as `apf` sits below the BARN layer.
    fn jackal() -> RobotSpec {
        RobotSpec {
            drive: Drive::Differential,
            footprint: Footprint::Rectangle {
                length: 0.42,
                width: 0.33,
            },
            limits: RobotLimits {
                v_max: 2.0,
                v_min: -0.1,
                vy_max: 0.0,
                w_max: 4.0,
                acc_v: 20.0,
                acc_vy: 0.0,
                acc_w: 25.0,
            },
            wheel_base: 0.37559,
        }
    }
    use crate::map::{Cell, OccupancyGrid, Pose2};

    #[test]
    fn the_braking_speed_held_one_period_stops_within_the_room() {
        for (decel, dt, room) in [(16.0, 0.1, 0.2), (0.8, 0.05, 1.0), (16.0, 0.0, 0.3)] {
            let v = braking_speed(decel, dt, room);
            let travelled = v * dt + v * v / (2.0 * decel);
            assert!((travelled - room).abs() < 1e-9, "{v} {travelled}");
        }
        // Holding the speed a period costs room: slower than √(2·a·room).
        assert!(braking_speed(16.0, 0.1, 0.2) < (2.0f64 * 16.0 * 0.2).sqrt() - 0.5);
        assert_eq!(braking_speed(16.0, 0.1, -0.1), 0.0);
        assert_eq!(braking_speed(16.0, 0.1, f64::NAN), 0.0);
    }

    /// A 2 m × 2 m map (1 cm cells) with one blocked cell where the
    /// Jackal's front-left corner, the robot at the centre facing +x, is
    /// after turning left by `angle`.
    fn corner_map(angle: f64) -> (StaticMap, RobotState) {
        let robot = jackal();
        let Footprint::Rectangle { length, width } = robot.footprint else {
            unreachable!()
        };
        let mut g = OccupancyGrid::new(200, 200)
            .unwrap()
            .with_frame(0.01, Pose2::default())
            .unwrap();
        let s = RobotState {
            x: 1.0,
            y: 1.0,
            ..Default::default()
        };
        let corner = DVec2::new(0.5 * length, 0.5 * width);
        let p = DVec2::new(s.x, s.y) + DVec2::from_angle(angle).rotate(corner);
        let (c, r) = g.world_to_cell(p.x, p.y).unwrap();
        g.set(c, r, Cell::Occupied).unwrap();
        let map = StaticMap::new(g, false).unwrap();
        assert!(!map.footprint_collides(&robot.footprint, &s));
        (map, s)
    }

    #[test]
    fn an_in_place_turn_that_would_sweep_a_corner_into_an_obstacle_is_slowed_or_refused() {
        let robot = jackal();
        let dt = 0.1;
        // 0.25 rad to the left: a full-speed left turn (and its braking)
        // would reach it; a slower one stops short; turning right is free.
        let (map, s) = corner_map(0.25);
        assert_eq!(safe_turn(&map, &robot, &s, -4.0, dt), -4.0);
        let w = safe_turn(&map, &robot, &s, 4.0, dt);
        assert!(w > 0.0 && w < 4.0, "{w}");
        let reach = w * dt + w * w / (2.0 * robot.limits.acc_w);
        let end = RobotState { theta: reach, ..s };
        assert!(!map.footprint_collides(&robot.footprint, &end));
        // Right at the corner: no left turn at all.
        let (map, s) = corner_map(0.03);
        assert_eq!(safe_turn(&map, &robot, &s, 4.0, dt), 0.0);
        assert_eq!(safe_turn(&map, &robot, &s, -4.0, dt), -4.0);
    }
}
